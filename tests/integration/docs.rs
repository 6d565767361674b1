//! docs/scenario-format.md documents every field a resolved scenario has (a check that keeps
//! the page true when the schema grows).

fn leaves(prefix: &str, value: &toml::Value, out: &mut Vec<String>) {
    match value {
        toml::Value::Table(t) => {
            for (k, v) in t {
                let path = if prefix.is_empty() {
                    k.clone()
                } else {
                    format!("{prefix}.{k}")
                };
                leaves(&path, v, out);
            }
        }
        toml::Value::Array(a) if a.first().is_some_and(|v| v.is_table()) => {
            leaves(prefix, &a[0], out)
        }
        _ => out.push(prefix.to_string()),
    }
}

#[test]
fn scenario_format_page_documents_every_field() {
    let doc =
        std::fs::read_to_string(touchdown_tests::root().join("docs/scenario-format.md")).unwrap();
    let mut missing = Vec::new();
    for file in ["flat-drop.toml", "table-i-2-2-vv4.toml"] {
        let sc = touchdown_scenario::Scenario::load(touchdown_tests::scenario(file)).unwrap();
        let resolved: toml::Value = toml::from_str(&sc.to_toml()).unwrap();
        let mut paths = Vec::new();
        leaves("", &resolved, &mut paths);
        assert!(paths.len() > 40, "{paths:?}");
        for p in paths {
            let last = p.rsplit('.').next().unwrap();
            let documented = doc.contains(&format!("`{p}`"))
                || doc.contains(&format!(".{last}`"))
                || doc.contains(&format!("`{last}`"));
            if !documented {
                missing.push(p);
            }
        }
    }
    missing.sort();
    missing.dedup();
    assert!(
        missing.is_empty(),
        "fields missing from docs/scenario-format.md: {missing:?}"
    );
}

/// The table "Mechanisms each engine models" of docs/engines.md says what each engine's own
/// declaration says (`touchdown_registry::unsupported`): a row per mechanism, in the order of
/// `Mechanism::ALL`, "yes" where the engine models it and "no: …" where it does not.
#[test]
fn engines_page_lists_what_each_engine_declares() {
    use touchdown_registry::{unsupported, Engine};
    use touchdown_scenario::model::Mechanism;
    let text = std::fs::read_to_string(touchdown_tests::root().join("docs/engines.md")).unwrap();
    let section = text
        .split("## Mechanisms each engine models")
        .nth(1)
        .expect("docs/engines.md has the section");
    let rows: Vec<Vec<&str>> = section
        .lines()
        .skip_while(|l| !l.starts_with("| mechanism |"))
        .skip(2)
        .take_while(|l| l.starts_with('|'))
        .map(|l| l.split('|').map(str::trim).collect())
        .collect();
    assert_eq!(rows.len(), Mechanism::ALL.len(), "{rows:?}");
    for (m, row) in Mechanism::ALL.into_iter().zip(&rows) {
        assert!(
            row[1].to_lowercase().starts_with(m.name()),
            "{m:?}: row {row:?}"
        );
        for (engine, cell) in Engine::ALL.into_iter().zip(&row[3..6]) {
            let models = unsupported(engine, m).is_none();
            assert_eq!(
                *cell == "yes",
                models,
                "{} on {engine}: docs say {cell:?}",
                m.name()
            );
            assert!(
                models || cell.starts_with("no"),
                "{m:?} on {engine}: {cell:?}"
            );
        }
    }
}
