//! The loader against hostile but fair input: tables only as tables, the units of the file that
//! wrote a number, special files, clear messages, plausibility ranges and warnings. Each test
//! names what it guards; the catalogue in tests/data/malformed/ holds one file per case too.

mod lander;
mod messages;
mod overrides;
mod plausibility;
mod range_table;
mod reading;

use crate::error::ScenarioError;
use crate::Scenario;
use std::path::{Path, PathBuf};
use toml::Value;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn scenario(name: &str) -> PathBuf {
    root().join("scenarios").join(name)
}

/// The bundled landings (`scenarios/*.toml`, `scenarios/robustness/*.toml`).
fn bundled() -> Vec<PathBuf> {
    let mut files = Vec::new();
    for dir in ["scenarios", "scenarios/robustness"] {
        for entry in std::fs::read_dir(root().join(dir)).unwrap() {
            let path = entry.unwrap().path();
            if path.is_file() && path.extension().is_some_and(|x| x == "toml") {
                files.push(path);
            }
        }
    }
    files.sort();
    assert!(files.len() > 10, "{files:?}");
    files
}

/// A scratch folder of its own, removed with everything in it when the value is dropped.
fn scratch(name: &str) -> tempfile::TempDir {
    tempfile::Builder::new()
        .prefix(&format!("touchdown-scenario-tests-{name}-"))
        .tempdir()
        .unwrap()
}

/// Writes `dir/file` extending `base` with the TOML `extra`; returns its path.
fn extending(dir: &Path, file: &str, base: &Path, extra: &str) -> PathBuf {
    let path = dir.join(file);
    std::fs::write(
        &path,
        format!(
            "schema_version = 1\nextends = {:?}\nname = \"test\"\n{extra}",
            base.display().to_string()
        ),
    )
    .unwrap();
    path
}

/// The field and message of a field error (panics on any other result).
fn field_error(result: Result<Scenario, ScenarioError>) -> (String, String, String) {
    match result {
        Err(ScenarioError::Field {
            file,
            field,
            message,
        }) => (file, field, message),
        Err(e) => panic!("expected a field error, got {e}"),
        Ok(_) => panic!("expected a field error, the scenario loaded"),
    }
}

/// One step of a path into a TOML value.
#[derive(Debug, Clone)]
enum Seg {
    Key(String),
    Index(usize),
}

/// The path as the loader writes it: `gear.legs[0].b2[1]`.
fn display(path: &[Seg]) -> String {
    let mut out = String::new();
    for seg in path {
        match seg {
            Seg::Key(k) if out.is_empty() => out.push_str(k),
            Seg::Key(k) => {
                out.push('.');
                out.push_str(k);
            }
            Seg::Index(i) => out.push_str(&format!("[{i}]")),
        }
    }
    out
}

/// Every node below the root (tables, arrays and leaves) with its path.
fn nodes(value: &Value) -> Vec<(Vec<Seg>, Value)> {
    fn walk(v: &Value, path: &mut Vec<Seg>, out: &mut Vec<(Vec<Seg>, Value)>) {
        if !path.is_empty() {
            out.push((path.clone(), v.clone()));
        }
        match v {
            Value::Table(t) => {
                for (k, child) in t {
                    path.push(Seg::Key(k.clone()));
                    walk(child, path, out);
                    path.pop();
                }
            }
            Value::Array(a) => {
                for (i, child) in a.iter().enumerate() {
                    path.push(Seg::Index(i));
                    walk(child, path, out);
                    path.pop();
                }
            }
            _ => {}
        }
    }
    let mut out = Vec::new();
    walk(value, &mut Vec::new(), &mut out);
    out
}

/// `value` with the node at `path` replaced by `new`.
fn replaced(value: &Value, path: &[Seg], new: Value) -> Value {
    let mut out = value.clone();
    let mut node = &mut out;
    for seg in path {
        node = match seg {
            Seg::Key(k) => node.get_mut(k.as_str()).unwrap(),
            Seg::Index(i) => node.get_mut(*i).unwrap(),
        };
    }
    *node = new;
    out
}

/// The resolved scenario (every default written out) as a TOML value.
fn resolved(path: &Path) -> Value {
    let sc = Scenario::load(path).unwrap_or_else(|e| panic!("{e}"));
    toml::from_str(&sc.to_toml()).unwrap()
}

fn load_value(value: &Value) -> Result<Scenario, ScenarioError> {
    Scenario::from_toml("mutant", &toml::to_string(value).unwrap())
}

/// Longest run of digits in `text`: a number printed in short notation has at most 6.
fn longest_digit_run(text: &str) -> usize {
    text.split(|c: char| !c.is_ascii_digit())
        .map(str::len)
        .max()
        .unwrap_or(0)
}
