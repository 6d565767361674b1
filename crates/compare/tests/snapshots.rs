//! The comparison of every scenario in `scenarios/` (one snapshot per file, via a glob), all
//! engines, every pair: the divergence under review. A change to any model, law, engine or
//! scenario that moves a compared value shows up here as a snapshot diff to review (`cargo
//! insta review`); CI never accepts one (INSTA_UPDATE=no in .ci/run). Values are rounded to
//! three significant figures (`touchdown_compare::report`); time series are never
//! snapshotted, only their summaries.

use rayon::prelude::*;
use std::collections::BTreeMap;
use std::path::PathBuf;
use touchdown_compare::{compare_scenario, report, Engine};

#[test]
fn every_scenario_compared_across_engines() {
    // Every scenario is landed first, side by side on every core (a comparison alone keeps two
    // cores busy only part of the time), then each is held against its snapshot in the glob's
    // order.
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenarios");
    let files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    let texts: BTreeMap<PathBuf, (String, String)> = files
        .par_iter()
        .map(|path| {
            let c = compare_scenario(path, &Engine::ALL).unwrap_or_else(|e| panic!("{e}"));
            let file = path.file_name().unwrap().to_string_lossy();
            let text = report::text(&c).replace(&c.file, &format!("scenarios/{file}"));
            let versions: Vec<String> = c
                .engines
                .iter()
                .map(|(e, v)| format!("{}: {v}", e.name()))
                .collect();
            let description = format!(
                "scenario sha256 {}; {}",
                c.scenario_sha256,
                versions.join(", ")
            );
            (path.canonicalize().unwrap(), (text, description))
        })
        .collect();
    insta::glob!("../../../scenarios", "*.toml", |path| {
        let (text, description) = &texts[&path.canonicalize().unwrap()];
        let mut settings = insta::Settings::clone_current();
        settings.set_description(description.as_str());
        settings.set_omit_expression(true);
        settings.bind(|| insta::assert_snapshot!("comparison", text));
    });
}

#[test]
fn every_tolerance_is_documented_with_its_value() {
    let doc = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/engines.md"),
    )
    .unwrap();
    for t in touchdown_compare::metrics::TOLERANCES {
        let row = doc
            .lines()
            .find(|l| l.starts_with(&format!("| {}", t.channel)))
            .unwrap_or_else(|| panic!("docs/engines.md has no row for {}", t.channel));
        assert!(
            row.contains(&format!("| {} |", t.limit)),
            "docs/engines.md: {} should say {}",
            t.channel,
            t.limit
        );
    }
}

/// Each shared scenario says, in its own file, which engines apply to it.
#[test]
fn every_shared_scenario_states_its_engines() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios");
    let mut n = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|x| x != "toml") {
            continue;
        }
        let table: toml::Table = std::fs::read_to_string(&path).unwrap().parse().unwrap();
        let listed = table
            .get("engines")
            .and_then(|e| e.get("applicable"))
            .and_then(|a| a.as_array())
            .map(|a| a.len())
            .unwrap_or(0);
        assert!(
            listed > 0,
            "{}: state the engines that apply, [engines] applicable = [...]",
            path.display()
        );
        n += 1;
    }
    assert!(n >= 10, "{n} shared scenarios");
}
