//! The catalogue of malformed scenarios (`tests/data/malformed/*.toml`): each file has one
//! problem and must fail to load with its own specific error.
//!
//! Every file starts with header comments stating what the error must say:
//!
//! * `# expect: <substring>`: one or more; each must appear in the error's Display text (the
//!   field path where there is one, and a word of the specific message);
//! * `# expect-file: <file name>`: the file the error must name (the malformed file itself, or,
//!   for a missing `extends` target, the missing file).
//!
//! The pipeline is the one every engine runs: [`Scenario::load`], then
//! [`GearLaws::from_scenario`] (which checks the stage tables and the bearing geometry against
//! the stroke capacity); the first error is the one checked.
//!
//! The positive control: every landing scenario in `scenarios/` goes through the same pipeline
//! without error.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use touchdown_laws::GearLaws;
use touchdown_scenario::Scenario;

/// Fewest malformed files the catalogue may hold.
const MIN_CASES: usize = 15;

/// Runs the full pipeline on one scenario file: load and resolve, then build the gear laws.
fn pipeline(path: &Path) -> Result<(), String> {
    let scenario = Scenario::load(path).map_err(|e| e.to_string())?;
    GearLaws::from_scenario(&scenario).map_err(|e| e.to_string())?;
    Ok(())
}

/// `*.toml` files directly in `dir`, sorted by name.
fn toml_files(dir: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("cannot list {}: {e}", dir.display()))
        .map(|entry| entry.expect("directory entry").path())
        .filter(|p| p.is_file() && p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    files
}

/// The `# expect:` substrings and the `# expect-file:` name of a malformed file's header.
struct Expectation {
    substrings: Vec<String>,
    file: Option<String>,
}

fn expectation(text: &str) -> Expectation {
    let mut substrings = Vec::new();
    let mut file = None;
    for line in text.lines() {
        let line = line.trim();
        if let Some(s) = line.strip_prefix("# expect-file:") {
            file = Some(s.trim().to_string());
        } else if let Some(s) = line.strip_prefix("# expect:") {
            substrings.push(s.trim().to_string());
        }
    }
    Expectation { substrings, file }
}

#[test]
fn every_malformed_scenario_fails_with_its_own_error() {
    let dir = touchdown_tests::root().join("tests/data/malformed");
    let files = toml_files(&dir);
    let mut failures: Vec<String> = Vec::new();
    if files.len() < MIN_CASES {
        failures.push(format!(
            "{}: expected at least {MIN_CASES} malformed scenarios, found {}",
            dir.display(),
            files.len()
        ));
    }
    // Error text with the malformed file's own path blanked out (the path alone would make every
    // message unique), mapped to the files that produced it.
    let mut by_message: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for path in &files {
        let name = path
            .file_name()
            .expect("a file name")
            .to_string_lossy()
            .into_owned();
        let text = match std::fs::read_to_string(path) {
            Ok(t) => t,
            Err(e) => {
                failures.push(format!("{name}: cannot read the test file: {e}"));
                continue;
            }
        };
        let expect = expectation(&text);
        let mut problems = Vec::new();
        if expect.substrings.is_empty() {
            problems.push("has no `# expect: <substring>` header line".to_string());
        }
        let Some(expect_file) = &expect.file else {
            failures.push(format!(
                "{name}: has no `# expect-file: <file name>` header line"
            ));
            continue;
        };
        let message = match pipeline(path) {
            Ok(()) => {
                failures.push(format!(
                    "{name}: loaded and built its laws without error, but should fail with {:?}",
                    expect.substrings
                ));
                continue;
            }
            Err(message) => message,
        };
        for s in &expect.substrings {
            if !message.contains(s.as_str()) {
                problems.push(format!("does not contain {s:?}"));
            }
        }
        if !message.contains(expect_file.as_str()) {
            problems.push(format!("does not name the file {expect_file:?}"));
        }
        if !problems.is_empty() {
            failures.push(format!(
                "{name}: the error\n      {message}\n    {}",
                problems.join("; ")
            ));
        }
        let key = message.replace(&path.display().to_string(), "<file>");
        by_message.entry(key).or_default().push(name);
    }
    for (message, names) in &by_message {
        if names.len() > 1 {
            failures.push(format!(
                "{} produce the identical error (each case should hit its own check):\n      {message}",
                names.join(", ")
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} malformed scenarios in {} failed:\n  {}",
        failures.len(),
        files.len(),
        dir.display(),
        failures.join("\n  ")
    );
}

#[test]
fn every_scenario_loads_and_builds_its_laws() {
    let dir = touchdown_tests::root().join("scenarios");
    let files = toml_files(&dir);
    assert!(!files.is_empty(), "no scenarios in {}", dir.display());
    let failures: Vec<String> = files
        .iter()
        .filter_map(|path| pipeline(path).err())
        .collect();
    assert!(
        failures.is_empty(),
        "{} of {} scenarios in {} failed to load:\n  {}",
        failures.len(),
        files.len(),
        dir.display(),
        failures.join("\n  ")
    );
}
