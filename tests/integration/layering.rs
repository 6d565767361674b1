//! Crate layers, as docs/architecture.md tabulates them: every workspace crate has a layer there,
//! and depends only on crates of lower layers (so the engines, all of one layer, never on each
//! other). A new crate, or a new internal dependency that breaks the layers, fails this test
//! until the table says where it stands.

use std::collections::BTreeMap;

/// The layer of each crate, from the table of docs/architecture.md (rows `| N | `crate` | … |`).
fn layers() -> BTreeMap<String, u32> {
    let text =
        std::fs::read_to_string(touchdown_tests::root().join("docs/architecture.md")).unwrap();
    text.lines()
        .filter_map(|line| {
            let cells: Vec<&str> = line.split('|').map(str::trim).collect();
            let layer = cells.get(1)?.parse().ok()?;
            let name = cells.get(2)?.strip_prefix('`')?.strip_suffix('`')?;
            Some((name.to_string(), layer))
        })
        .collect()
}

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
fn crates_respect_the_layers_of_the_architecture_page() {
    let deps = internal_dependencies();
    let layers = layers();
    assert!(
        layers.len() >= 10,
        "docs/architecture.md lost its table: {layers:?}"
    );
    let mut problems = Vec::new();
    for name in layers.keys().filter(|n| !deps.contains_key(*n)) {
        problems.push(format!(
            "docs/architecture.md lists {name}, not a workspace crate"
        ));
    }
    for (name, ds) in &deps {
        let Some(own) = layers.get(name) else {
            problems.push(format!("{name} has no layer in docs/architecture.md"));
            continue;
        };
        for d in ds {
            match layers.get(d) {
                Some(l) if l < own => {}
                Some(l) => problems.push(format!(
                    "{name} (layer {own}) must not depend on {d} (layer {l})"
                )),
                None => problems.push(format!("{d} has no layer in docs/architecture.md")),
            }
        }
    }
    assert!(
        problems.is_empty(),
        "layering violations:\n{}",
        problems.join("\n")
    );
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
    // Every engine's crate, named after the engine (a new engine is checked without a change
    // here).
    let names: Vec<String> = (touchdown_scenario::schema::Engine::ALL.iter())
        .map(|e| format!("touchdown-{}", e.name()))
        .collect();
    let engines: Vec<&String> = names.iter().collect();
    for e in &engines {
        assert!(
            deps.contains_key(*e),
            "the engine's crate {e} is not in the workspace"
        );
    }
    for e in &engines {
        for other in &engines {
            assert!(
                e == other || !deps[*e].contains(other),
                "{e} depends on the engine {other}"
            );
        }
    }
}
