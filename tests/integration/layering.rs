//! Crate layers: scenario format → force laws, record → multibody bookkeeping → engines (never
//! depending on each other) →
//! comparison → CLI. Every workspace crate must be listed here; a new crate or a new internal
//! dependency that breaks the layers fails this test.

use std::collections::BTreeMap;

/// Internal crates each crate may depend on (normal, dev or build dependencies).
const ALLOWED: &[(&str, &[&str])] = &[
    ("touchdown-scenario", &[]),
    ("touchdown-laws", &["touchdown-scenario"]),
    // What every engine reports (summary, history sample, stability criteria).
    ("touchdown-record", &["touchdown-scenario"]),
    // What the multibody engines share around their own stepping (strut laws at a multibody
    // gear state, bookkeeping).
    (
        "touchdown-multibody",
        &["touchdown-scenario", "touchdown-laws", "touchdown-record"],
    ),
    // Engines: scenario, laws, record (and multibody for the multibody engines) only; never
    // another engine.
    (
        "touchdown-core",
        &["touchdown-scenario", "touchdown-laws", "touchdown-record"],
    ),
    (
        "touchdown-rapier",
        &[
            "touchdown-scenario",
            "touchdown-laws",
            "touchdown-record",
            "touchdown-multibody",
        ],
    ),
    (
        "touchdown-mujoco",
        &[
            "touchdown-scenario",
            "touchdown-laws",
            "touchdown-record",
            "touchdown-multibody",
        ],
    ),
    // Comparison level: runs engines, never reached by them.
    (
        "touchdown-compare",
        &[
            "touchdown-scenario",
            "touchdown-record",
            "touchdown-core",
            "touchdown-rapier",
            "touchdown-mujoco",
        ],
    ),
    (
        "touchdown-validation",
        &["touchdown-scenario", "touchdown-core"],
    ),
    (
        "touchdown-cli",
        &[
            "touchdown-scenario",
            "touchdown-laws",
            "touchdown-record",
            "touchdown-core",
            "touchdown-rapier",
            "touchdown-mujoco",
            "touchdown-compare",
            "touchdown-validation",
            // As a dev-dependency only: the test helpers (the fuzz harnesses' seeded runner)
            // that the command-line tests share with the workspace tests.
            "touchdown-tests",
        ],
    ),
    (
        "touchdown-tests",
        &[
            "touchdown-scenario",
            "touchdown-laws",
            "touchdown-record",
            "touchdown-core",
            "touchdown-rapier",
            "touchdown-mujoco",
        ],
    ),
];

fn internal_dependencies() -> BTreeMap<String, Vec<String>> {
    let root = touchdown_tests::root();
    let workspace: toml::Table =
        toml::from_str(&std::fs::read_to_string(root.join("Cargo.toml")).unwrap()).unwrap();
    let members = workspace["workspace"]["members"].as_array().unwrap();
    let mut out = BTreeMap::new();
    for m in members {
        let dir = root.join(m.as_str().unwrap());
        let manifest: toml::Table =
            toml::from_str(&std::fs::read_to_string(dir.join("Cargo.toml")).unwrap()).unwrap();
        let name = manifest["package"]["name"].as_str().unwrap().to_string();
        let mut deps = Vec::new();
        for section in ["dependencies", "dev-dependencies", "build-dependencies"] {
            if let Some(t) = manifest.get(section).and_then(|t| t.as_table()) {
                deps.extend(t.keys().filter(|k| k.starts_with("touchdown")).cloned());
            }
        }
        out.insert(name, deps);
    }
    out
}

#[test]
fn crates_respect_the_layers() {
    let deps = internal_dependencies();
    let allowed: BTreeMap<&str, &[&str]> = ALLOWED.iter().copied().collect();
    let mut problems = Vec::new();
    for (name, ds) in &deps {
        match allowed.get(name.as_str()) {
            None => problems.push(format!(
                "{name} is not in the layering table of tests/integration/layering.rs"
            )),
            Some(ok) => {
                for d in ds {
                    if !ok.contains(&d.as_str()) {
                        problems.push(format!("{name} must not depend on {d}"));
                    }
                }
            }
        }
    }
    assert!(
        problems.is_empty(),
        "layering violations:\n{}",
        problems.join("\n")
    );
    assert!(deps.len() >= 5, "the workspace lost crates: {deps:?}");
}

/// The test helpers are only ever a dev-dependency: no crate's own code depends on them.
#[test]
fn only_tests_depend_on_the_test_helpers() {
    let root = touchdown_tests::root();
    let workspace: toml::Table =
        toml::from_str(&std::fs::read_to_string(root.join("Cargo.toml")).unwrap()).unwrap();
    for m in workspace["workspace"]["members"].as_array().unwrap() {
        let dir = root.join(m.as_str().unwrap());
        let manifest: toml::Table =
            toml::from_str(&std::fs::read_to_string(dir.join("Cargo.toml")).unwrap()).unwrap();
        for section in ["dependencies", "build-dependencies"] {
            let uses = manifest
                .get(section)
                .and_then(|t| t.as_table())
                .is_some_and(|t| t.contains_key("touchdown-tests"));
            assert!(!uses, "{}: touchdown-tests in [{section}]", dir.display());
        }
    }
}

#[test]
fn engines_never_depend_on_each_other() {
    let deps = internal_dependencies();
    let engines: Vec<&String> = deps
        .keys()
        .filter(|n| {
            ["touchdown-core", "touchdown-rapier", "touchdown-mujoco"].contains(&n.as_str())
        })
        .collect();
    assert!(!engines.is_empty());
    for e in &engines {
        for other in &engines {
            assert!(
                e == other || !deps[*e].contains(other),
                "{e} depends on the engine {other}"
            );
        }
    }
}
