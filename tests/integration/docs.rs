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
