//! The project fuzzes itself: a property-based harness (proptest) that mutates one field of a
//! bundled scenario at a time — zero, negated, scaled by 1e±3, ±1e300, 1e-300, 5e-324, NaN,
//! ±inf, the wrong type, an empty or shortened array — and asserts, for every mutant:
//!
//! * nothing panics;
//! * a refusal names a field (the loader's and the laws' errors carry `field `…``);
//! * a landing that runs ends within the harness's step allowance, or stops with a diagnostic
//!   (time, law, state);
//! * a completed landing's summary has no null and no non-finite number, and its energy balance
//!   is within its tolerance.
//!
//! The suite runs a fixed, seeded sample of [`SUITE_CASES`] mutants on the core. The long run
//! (docs/robustness.md, "Fuzzing") sets `TOUCHDOWN_FUZZ_CASES` and `TOUCHDOWN_FUZZ_SEED`:
//!
//! ```text
//! TOUCHDOWN_FUZZ_CASES=5000 cargo test --release -p touchdown-tests --test integration \
//!     fuzz -- --nocapture
//! ```
//!
//! and prints how many mutants were refused, completed, stopped and long. A mutant that breaks
//! a property is kept as a regression case in [`REGRESSIONS`].

use proptest::prelude::*;
use proptest::test_runner::{TestCaseError, TestRunner};
use std::cell::RefCell;
use std::path::{Path, PathBuf};
use touchdown_core::{Landing, Simulation};
use touchdown_scenario::Scenario;
use touchdown_tests::root;

/// Mutants the test suite tries (seeded: the same ones every run).
const SUITE_CASES: u32 = 48;

/// Steps the harness lets one landing take before it counts it as long (the engines' own budget,
/// `integrator.max_steps`, is far larger by default and has its own tests).
const STEP_ALLOWANCE: u64 = 200_000;

/// Mutants that once broke a property: (scenario, field path, TOML value).
const REGRESSIONS: &[(&str, &str, &str)] = &[
    // A stable landing wrote `"overturn_velocity_m_s": null` (and `decision_time_s`, and the
    // first contact of a footpad that never touched): optional figures are now left out.
    (
        "bending-2-2-vv8.toml",
        "engines.links.link_radius_ratio",
        "3e1",
    ),
];

/// The values a mutation writes in place of a number `x`, as TOML.
fn number_mutants(x: f64) -> Vec<String> {
    let mut v: Vec<String> = [0.0, -x, x * 1e3, x * 1e-3, 1e300, -1e300, 1e-300, 5e-324]
        .iter()
        .map(|y| format!("{y:e}"))
        .collect();
    v.extend(["nan", "inf", "-inf", "\"text\"", "[]", "{}"].map(String::from));
    v
}

/// Every leaf of a resolved scenario: (dotted path, value).
fn leaves(prefix: &str, v: &toml::Value, out: &mut Vec<(String, toml::Value)>) {
    match v {
        toml::Value::Table(t) => {
            for (k, x) in t {
                let p = if prefix.is_empty() {
                    k.clone()
                } else {
                    format!("{prefix}.{k}")
                };
                leaves(&p, x, out);
            }
        }
        _ => out.push((prefix.to_string(), v.clone())),
    }
}

/// The values a mutation may write at a leaf holding `v`.
fn mutants_of(v: &toml::Value) -> Vec<String> {
    match v {
        toml::Value::Float(x) => number_mutants(*x),
        toml::Value::Integer(i) => number_mutants(*i as f64),
        toml::Value::Boolean(_) => vec!["\"text\"".into(), "1.0".into()],
        toml::Value::String(_) => vec!["\"nonsense\"".into(), "1.0".into(), "[]".into()],
        toml::Value::Array(a) => {
            let mut m = vec!["[]".to_string(), "[nan]".into(), "1.0".into()];
            if a.len() > 1 {
                let shorter = toml::Value::Array(a[..a.len() - 1].to_vec());
                m.push(shorter.to_string());
            }
            m
        }
        _ => vec!["1.0".into()],
    }
}

/// The bundled landings (not the vehicle files).
fn landings() -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(root().join("scenarios"))
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    v.sort();
    v
}

/// A field of a scenario that a mutation may change: its dotted path and the values it may get.
type Field = (String, Vec<String>);

/// What became of one mutant.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Fate {
    Refused,
    Completed,
    Stopped,
    Long,
}

/// Writes a scenario extending `base` with `path = value` on top, in `dir`.
fn mutant_file(dir: &Path, n: usize, base: &Path, path: &str, value: &str) -> PathBuf {
    let file = dir.join(format!("mutant-{n}.toml"));
    let text = format!(
        "schema_version = 1\nextends = {:?}\nname = \"mutant\"\n{path} = {value}\n",
        base.display().to_string()
    );
    std::fs::write(&file, text).unwrap();
    file
}

/// Every number in a JSON value is finite and none is null.
fn no_null_or_nan(v: &serde_json::Value, at: &str) -> Result<(), String> {
    match v {
        serde_json::Value::Null => Err(format!("null at {at}")),
        serde_json::Value::Number(n) => match n.as_f64() {
            Some(x) if x.is_finite() => Ok(()),
            _ => Err(format!("non-finite number at {at}")),
        },
        serde_json::Value::Array(a) => a
            .iter()
            .enumerate()
            .try_for_each(|(i, x)| no_null_or_nan(x, &format!("{at}[{i}]"))),
        serde_json::Value::Object(o) => o
            .iter()
            .try_for_each(|(k, x)| no_null_or_nan(x, &format!("{at}.{k}"))),
        _ => Ok(()),
    }
}

/// Checks one mutant: its fate, or the property it breaks.
fn check(file: &Path, path: &str) -> Result<Fate, String> {
    let sc = match Scenario::load(file) {
        Ok(sc) => sc,
        Err(e) => {
            let m = e.to_string();
            return if m.contains("field `") || m.contains(path) {
                Ok(Fate::Refused)
            } else {
                Err(format!("refusal names no field: {m}"))
            };
        }
    };
    let mut sim = match Simulation::new(&sc) {
        Ok(s) => s,
        Err(e) => {
            let m = e.to_string();
            return if m.contains("field `") {
                Ok(Fate::Refused)
            } else {
                Err(format!("the core refuses without naming a field: {m}"))
            };
        }
    };
    let mut steps = 0;
    while !sim.finished() {
        if let Err(e) = sim.step() {
            let m = e.to_string();
            return if m.contains("simulation stopped at t =") && m.contains("state:") {
                Ok(Fate::Stopped)
            } else {
                Err(format!("a stop without its diagnostic: {m}"))
            };
        }
        steps += 1;
        if steps >= STEP_ALLOWANCE {
            return Ok(Fate::Long);
        }
    }
    let summary = sim.summary();
    let json = serde_json::to_value(&summary).map_err(|e| e.to_string())?;
    no_null_or_nan(&json, "summary")?;
    let e = &summary.energy;
    let bound = sc.integrator.energy_tolerance * e.scale() * (1.0 + 1e-9);
    if e.residual_j.abs() > bound {
        return Err(format!(
            "completed with an energy residual {} J beyond {bound} J",
            e.residual_j
        ));
    }
    Ok(Fate::Completed)
}

/// Tries the mutants `runner` draws; the tally of fates, or the first broken property with its
/// mutant.
fn fuzz(mut runner: TestRunner) -> Result<[usize; 4], String> {
    let dir = std::env::temp_dir().join(format!("touchdown-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bases: Vec<(PathBuf, Vec<Field>)> = landings()
        .into_iter()
        .map(|p| {
            let sc = Scenario::load(&p).unwrap();
            let resolved: toml::Value = toml::from_str(&sc.to_toml()).unwrap();
            let mut l = vec![];
            leaves("", &resolved, &mut l);
            let fields = l
                .into_iter()
                .filter(|(k, _)| !matches!(k.as_str(), "schema_version" | "extends" | "name"))
                .map(|(k, v)| {
                    let m = mutants_of(&v);
                    (k, m)
                })
                .collect();
            (p, fields)
        })
        .collect();
    let tally = RefCell::new([0usize; 4]);
    let counter = RefCell::new(0usize);
    let strategy = (
        0..bases.len(),
        any::<prop::sample::Index>(),
        any::<prop::sample::Index>(),
    );
    let result = runner.run(&strategy, |(b, field, value)| {
        let (base, fields) = &bases[b];
        let (path, values) = &fields[field.index(fields.len())];
        let value = &values[value.index(values.len())];
        let n = {
            let mut c = counter.borrow_mut();
            *c += 1;
            *c
        };
        let file = mutant_file(&dir, n, base, path, value);
        let fate = check(&file, path).map_err(|why| {
            TestCaseError::fail(format!(
                "{} with {path} = {value}: {why}",
                base.file_name().unwrap().to_string_lossy()
            ))
        })?;
        tally.borrow_mut()[fate as usize] += 1;
        Ok(())
    });
    let _ = std::fs::remove_dir_all(&dir);
    result.map_err(|e| e.to_string())?;
    Ok(tally.into_inner())
}

#[test]
fn mutated_scenarios_are_refused_naming_a_field_or_run_to_a_clean_end() {
    let (runner, cases, seed) = touchdown_tests::fuzz_runner(SUITE_CASES);
    let tally = fuzz(runner).unwrap_or_else(|e| panic!("{e}"));
    eprintln!(
        "fuzz: {cases} mutants (seed {seed}): {} refused, {} completed, {} stopped, {} long (past {STEP_ALLOWANCE} steps)",
        tally[Fate::Refused as usize],
        tally[Fate::Completed as usize],
        tally[Fate::Stopped as usize],
        tally[Fate::Long as usize]
    );
    assert_eq!(tally.iter().sum::<usize>(), cases as usize);
}

#[test]
fn every_mutant_that_once_broke_a_property_now_keeps_them() {
    let dir = std::env::temp_dir().join(format!("touchdown-fuzz-reg-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (n, (base, path, value)) in REGRESSIONS.iter().enumerate() {
        let file = mutant_file(&dir, n, &touchdown_tests::scenario(base), path, value);
        if let Err(why) = check(&file, path) {
            panic!("{base} with {path} = {value}: {why}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
