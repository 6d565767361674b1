//! No import circles between a crate's modules: each top-level module of each crate (a file
//! `src/m.rs` or a folder `src/m/`) may use another, but no chain of `crate::` paths leads back
//! to where it started, so that a module can be read, tested and moved with what it uses below
//! it; and likewise between the files of a folder module (`super::` and `crate::m::` paths). A
//! new circle fails with the modules that close it.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// The top-level modules of the crate at `src`, each with the top-level modules its files name
/// through `crate::` paths (its own left out).
fn module_graph(src: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    let mut files = Vec::new();
    for entry in std::fs::read_dir(src).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_stem().unwrap().to_string_lossy().to_string();
        if path.is_dir() {
            let mut stack = vec![path.clone()];
            while let Some(dir) = stack.pop() {
                for e in std::fs::read_dir(&dir).unwrap() {
                    let p = e.unwrap().path();
                    if p.is_dir() {
                        stack.push(p);
                    } else if p.extension().is_some_and(|x| x == "rs") {
                        files.push((name.clone(), p));
                    }
                }
            }
        } else if path.extension().is_some_and(|x| x == "rs") && name != "lib" && name != "main" {
            files.push((name, path));
        }
    }
    let modules: BTreeSet<String> = files.iter().map(|(m, _)| m.clone()).collect();
    for (module, path) in &files {
        let text = code_of(path);
        let uses = graph.entry(module.clone()).or_default();
        for head in heads(&text, "crate::") {
            if head != module && modules.contains(head) {
                uses.insert(head.to_string());
            }
        }
    }
    graph
}

/// The code of the Rust file at `path`: its tests (its `#[cfg(test)]` module, last) and its
/// comments (a doc link is a reference, not an import) left out.
fn code_of(path: &Path) -> String {
    let whole = std::fs::read_to_string(path).unwrap();
    let code = whole.split("#[cfg(test)]").next().unwrap_or("");
    code.lines()
        .filter(|l| !l.trim_start().starts_with("//"))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The first segment of each path after `prefix` in `text` (`prefix::name`, and each of
/// `prefix::{a, b::c}`).
fn heads<'a>(text: &'a str, prefix: &str) -> Vec<&'a str> {
    let mut out = Vec::new();
    for (at, _) in text.match_indices(prefix) {
        let rest = &text[at + prefix.len()..];
        if let Some(group) = rest.strip_prefix('{') {
            let end = group.find('}').unwrap_or(group.len());
            out.extend(
                group[..end]
                    .split(',')
                    .map(|p| p.trim().split("::").next().unwrap_or("")),
            );
        } else {
            out.push(
                rest.split(|c: char| !(c.is_alphanumeric() || c == '_'))
                    .next()
                    .unwrap_or(""),
            );
        }
    }
    out
}

/// For each folder module `src/m/` of the crate at `src`, the graph of its files (their stems;
/// `mod.rs`, which declares them, and unit-test files left out), each with its siblings it names
/// through `super::` or `crate::m::` paths.
fn folder_graphs(src: &Path) -> Vec<(String, BTreeMap<String, BTreeSet<String>>)> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(src).unwrap() {
        let dir = entry.unwrap().path();
        let folder = dir.file_name().unwrap().to_string_lossy().to_string();
        if !dir.is_dir() || folder == "tests" {
            continue;
        }
        let files: Vec<(String, std::path::PathBuf)> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|x| x == "rs"))
            .map(|p| (p.file_stem().unwrap().to_string_lossy().to_string(), p))
            .filter(|(m, _)| m != "mod" && m != "tests")
            .collect();
        let siblings: BTreeSet<&str> = files.iter().map(|(m, _)| m.as_str()).collect();
        let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
        for (module, path) in &files {
            let text = code_of(path);
            let uses = graph.entry(module.clone()).or_default();
            let own = format!("crate::{folder}::");
            for head in heads(&text, "super::")
                .into_iter()
                .chain(heads(&text, &own))
            {
                if head != module && siblings.contains(head) {
                    uses.insert(head.to_string());
                }
            }
        }
        out.push((folder, graph));
    }
    out
}

/// The groups of modules of `graph` that reach each other through their imports (its
/// strongly connected components of more than one module), each sorted, in order.
fn circles(graph: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    let reach = |from: &str| {
        let mut seen = BTreeSet::new();
        let mut stack = vec![from.to_string()];
        while let Some(m) = stack.pop() {
            for next in graph.get(&m).into_iter().flatten() {
                if seen.insert(next.clone()) {
                    stack.push(next.clone());
                }
            }
        }
        seen
    };
    let reached: BTreeMap<&String, BTreeSet<String>> =
        graph.keys().map(|m| (m, reach(m))).collect();
    let mut out: BTreeSet<Vec<String>> = BTreeSet::new();
    for (m, r) in &reached {
        let group: Vec<String> = reached
            .iter()
            .filter(|(n, rn)| r.contains(n.as_str()) && rn.contains(m.as_str()))
            .map(|(n, _)| (*n).clone())
            .collect();
        if group.len() > 1 {
            out.insert(group);
        }
    }
    out.into_iter().collect()
}

/// The circles the tree holds today, each a group of one crate's modules (`crate: a, b`, or
/// `crate::folder: a, b` inside a folder module): to be broken, never added to. A circle found
/// and not listed, or listed and no longer found, fails the test. None today.
const KNOWN: [&str; 0] = [];

#[test]
fn the_circle_finder_finds_every_circle_and_nothing_else() {
    let g = |edges: &[(&str, &str)]| {
        let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
        for (a, b) in edges {
            g.entry(a.to_string()).or_default().insert(b.to_string());
            g.entry(b.to_string()).or_default();
        }
        g
    };
    assert!(circles(&g(&[("a", "b"), ("b", "c"), ("a", "c")])).is_empty());
    assert_eq!(
        circles(&g(&[
            ("a", "b"),
            ("b", "c"),
            ("c", "a"),
            ("c", "d"),
            ("d", "e"),
            ("e", "d")
        ])),
        vec![
            vec!["a".to_string(), "b".into(), "c".into()],
            vec!["d".to_string(), "e".into()]
        ]
    );
}

#[test]
fn no_crate_has_an_import_circle_between_its_modules_but_the_known() {
    let crates = touchdown_tests::root().join("crates");
    let mut found = BTreeSet::new();
    let mut checked = 0;
    for entry in std::fs::read_dir(&crates).unwrap() {
        let dir = entry.unwrap().path();
        let src = dir.join("src");
        if !src.is_dir() {
            continue;
        }
        let graph = module_graph(&src);
        checked += graph.len();
        let name = dir.file_name().unwrap().to_string_lossy().to_string();
        for c in circles(&graph) {
            found.insert(format!("{name}: {}", c.join(", ")));
        }
        for (folder, graph) in folder_graphs(&src) {
            checked += graph.len();
            for c in circles(&graph) {
                found.insert(format!("{name}::{folder}: {}", c.join(", ")));
            }
        }
    }
    assert!(checked > 50, "only {checked} modules read");
    let known: BTreeSet<String> = KNOWN.iter().map(|s| s.to_string()).collect();
    let new: Vec<_> = found.difference(&known).collect();
    let gone: Vec<_> = known.difference(&found).collect();
    assert!(
        new.is_empty() && gone.is_empty(),
        "import circles: new {new:?}; broken, to be taken off the list: {gone:?}"
    );
}
