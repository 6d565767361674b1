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
        // One cell per engine, in the order of `Engine::ALL` (a new engine needs its column).
        let cells = &row[3..row.len() - 1];
        assert_eq!(
            cells.len(),
            Engine::ALL.len(),
            "{m:?}: one cell per engine: {row:?}"
        );
        for (engine, cell) in Engine::ALL.into_iter().zip(cells) {
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

/// Every file under `dir`, at any depth, whose name ends in `.ext`.
fn files_under(dir: &std::path::Path, ext: &str) -> Vec<std::path::PathBuf> {
    let mut found = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == ext) {
                found.push(p);
            }
        }
    }
    found
}

/// Every markdown file of the project (README.md, docs/, reference/, python/): the inline links
/// `[text](target)` that are not web addresses.
fn markdown_links() -> Vec<(std::path::PathBuf, String)> {
    let root = touchdown_tests::root();
    let mut files = vec![root.join("README.md")];
    for dir in ["docs", "reference", "python", "scenarios"] {
        files.extend(files_under(&root.join(dir), "md"));
    }
    files.sort();
    let mut links = Vec::new();
    for f in files {
        let text = std::fs::read_to_string(&f).unwrap();
        let mut in_code = false;
        for line in text.lines() {
            if line.trim_start().starts_with("```") {
                in_code = !in_code;
            }
            if in_code {
                continue;
            }
            let mut rest = line;
            while let Some(i) = rest.find("](") {
                let after = &rest[i + 2..];
                let Some(end) = after.find(')') else { break };
                let target = &after[..end];
                if !target.contains("://") && !target.starts_with("mailto:") {
                    links.push((f.clone(), target.to_string()));
                }
                rest = &after[end..];
            }
        }
    }
    links
}

/// A heading's anchor as GitHub makes it: lower case, spaces to hyphens, punctuation dropped.
fn anchor(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
            _ => None,
        })
        .collect()
}

/// Every relative link of the project's pages reaches a file inside the repository, and every
/// `#section` a heading of that file: no page points outside the project or at a section that
/// does not exist.
#[test]
fn every_link_of_the_docs_reaches_a_file_and_section_of_the_repository() {
    let root = touchdown_tests::root();
    let mut broken = Vec::new();
    let links = markdown_links();
    assert!(links.len() > 20, "{links:?}");
    for (file, target) in links {
        let (path, section) = match target.split_once('#') {
            Some((p, s)) => (p, Some(s)),
            None => (target.as_str(), None),
        };
        let dest = if path.is_empty() {
            file.clone()
        } else {
            file.parent().unwrap().join(path)
        };
        let Ok(dest) = dest.canonicalize() else {
            broken.push(format!("{}: {target}: no such file", file.display()));
            continue;
        };
        if !dest.starts_with(&root) {
            broken.push(format!(
                "{}: {target}: outside the repository",
                file.display()
            ));
            continue;
        }
        if let Some(section) = section {
            let text = std::fs::read_to_string(&dest).unwrap_or_default();
            let found = text
                .lines()
                .filter(|l| l.starts_with('#'))
                .any(|l| anchor(l.trim_start_matches('#')) == section);
            if !found {
                broken.push(format!("{}: {target}: no such section", file.display()));
            }
        }
    }
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

/// scenarios/README.md names every bundled scenario (each file under scenarios/, by its path
/// there), so a new scenario cannot go unlisted.
#[test]
fn the_scenario_list_names_every_bundled_scenario() {
    let root = touchdown_tests::root();
    let readme = std::fs::read_to_string(root.join("scenarios/README.md")).unwrap();
    let scenarios = root.join("scenarios");
    let mut missing: Vec<String> = files_under(&scenarios, "toml")
        .iter()
        .map(|p| {
            p.strip_prefix(&scenarios)
                .unwrap()
                .to_string_lossy()
                .replace('\\', "/")
        })
        .filter(|rel| !readme.contains(rel.as_str()))
        .collect();
    missing.sort();
    assert!(
        missing.is_empty(),
        "scenarios scenarios/README.md does not list: {missing:?}"
    );
}
