//! Reading a file: tables only as tables, numbers in their file's units, special and huge files.

use super::{
    bundled, display, extending, field_error, load_value, nodes, replaced, resolved, scenario,
    scratch,
};
use crate::error::ScenarioError;
use crate::Scenario;
use std::path::Path;
use toml::Value;

// 1. A table is only ever a table.

#[test]
fn every_table_of_every_bundled_scenario_refuses_an_array_in_its_place() {
    let mut tried = 0;
    for path in bundled() {
        let value = resolved(&path);
        for (at, node) in nodes(&value) {
            if !node.is_table() {
                continue;
            }
            let field = display(&at);
            for stand_in in [
                Value::Array(vec![Value::Float(1.0)]),
                Value::Array(vec![]),
                Value::Float(1.0),
                Value::String("x".into()),
            ] {
                let (_, got, message) = field_error(load_value(&replaced(&value, &at, stand_in)));
                assert_eq!(got, field, "{}: {message}", path.display());
                assert!(
                    message.starts_with("expected a table, found "),
                    "{field}: {message}"
                );
                tried += 1;
            }
        }
    }
    assert!(tried > 500, "{tried}");
}

#[test]
fn the_array_readings_serde_would_accept_are_refused() {
    let folder = scratch("arrays");
    let dir = folder.path();
    let flat = scenario("flat-drop.toml");
    for (extra, field) in [
        ("stability = [1.0]\n", "stability"),
        ("[engines]\nrapier = [1.0]\n", "engines.rapier"),
        ("[vehicle]\ninertia = [1.0, 1.0, 1.0]\n", "vehicle.inertia"),
        ("footpad = [0.013, 0.257]\n", "footpad"),
        (
            "units = [\"ft\", \"slug\", \"lbf\", \"deg\", \"s\"]\n",
            "units",
        ),
        ("[gear]\nparametric = [1.0]\n", "gear.parametric"),
    ] {
        let file = extending(dir, "a.toml", &flat, extra);
        let (owner, got, message) = field_error(Scenario::load(&file));
        assert_eq!(got, field, "{message}");
        assert!(owner.ends_with("a.toml"), "{owner}");
        assert_eq!(message, "expected a table, found an array");
    }
}

// 2. Numbers are read in the units of the file that wrote them.

#[test]
fn an_extending_file_may_not_change_the_units_it_inherits() {
    let folder = scratch("units");
    let dir = folder.path();
    let vehicle = scenario("vehicles/lm-1-6.toml");
    let flat = scenario("flat-drop.toml");
    let file = extending(dir, "metres.toml", &flat, "[units]\nlength = \"m\"\n");
    let (owner, field, message) = field_error(Scenario::load(&file));
    assert!(owner.ends_with("metres.toml"), "{owner}");
    assert_eq!(field, "units.length");
    assert!(
        message.contains("\"m\" here but \"ft\" in") && message.contains("lm-1-6.toml"),
        "{message}"
    );
    // Two levels down: the file that set the inherited unit is named.
    let middle = extending(dir, "middle.toml", &flat, "");
    let file = extending(dir, "kilograms.toml", &middle, "[units]\nmass = \"kg\"\n");
    let (_, field, message) = field_error(Scenario::load(&file));
    assert_eq!(field, "units.mass");
    assert!(
        message.contains(&vehicle.display().to_string()),
        "{message}"
    );
    // Restating the same units is not a change.
    let same = "[units]\nlength = \"ft\"\nmass = \"slug\"\nforce = \"lbf\"\nangle = \"deg\"\ntime = \"s\"\n";
    let file = extending(dir, "same.toml", &flat, same);
    Scenario::load(&file).unwrap();
}

// 3. Special files are refused before they are read.

fn not_a_file(result: Result<Scenario, ScenarioError>, path: &Path, kind: &str) {
    match result {
        Err(ScenarioError::NotAFile { file, kind: k }) => {
            assert_eq!(file, path.display().to_string());
            assert!(k.contains(kind), "{k}");
        }
        Err(e) => panic!("expected NotAFile, got {e}"),
        Ok(_) => panic!("{} loaded", path.display()),
    }
}

#[test]
fn a_directory_or_a_device_is_refused_naming_it() {
    let folder = scratch("special");
    let dir = folder.path();
    not_a_file(Scenario::load(dir), dir, "directory");
    #[cfg(unix)]
    not_a_file(
        Scenario::load("/dev/null"),
        Path::new("/dev/null"),
        "character device",
    );
    let file = extending(dir, "dir.toml", dir, "");
    let (_, field, message) = field_error(Scenario::load(&file));
    assert_eq!(field, "extends");
    assert!(
        message.contains(&dir.display().to_string()) && message.contains("a directory"),
        "{message}"
    );
}

/// Runs `f` on a thread and fails if it has not returned within a minute (a FIFO read blocks).
fn within_a_minute<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(f());
    });
    rx.recv_timeout(std::time::Duration::from_secs(60))
        .expect("the loader blocked on a FIFO")
}

#[cfg(unix)]
#[test]
fn a_fifo_is_refused_without_blocking() {
    let folder = scratch("fifo");
    let dir = folder.path();
    let fifo = dir.join("pipe.toml");
    match std::process::Command::new("mkfifo").arg(&fifo).status() {
        Ok(s) if s.success() => {}
        other => {
            eprintln!("skipped: mkfifo is not available ({other:?})");
            return;
        }
    }
    let f = fifo.clone();
    not_a_file(within_a_minute(move || Scenario::load(f)), &fifo, "FIFO");
    let file = extending(dir, "pipe-base.toml", &fifo, "");
    let (owner, field, message) = field_error(within_a_minute(move || Scenario::load(file)));
    assert!(owner.ends_with("pipe-base.toml"), "{owner}");
    assert_eq!(field, "extends");
    assert!(
        message.contains(&fifo.display().to_string()) && message.contains("FIFO"),
        "{message}"
    );
    let f = fifo.clone();
    assert!(within_a_minute(move || Scenario::value_at(f, "vehicle.mass")).is_err());
}

/// A file past the size limit is refused with both sizes in whole bytes, never in floating
/// notation.
#[test]
fn a_file_past_the_size_limit_is_refused_in_whole_bytes() {
    let folder = scratch("huge");
    let path = folder.path().join("huge.toml");
    let file = std::fs::File::create(&path).unwrap();
    file.set_len(17_000_000).unwrap();
    let message = Scenario::load(&path).unwrap_err().to_string();
    assert!(
        message.contains("the file is 17000000 bytes")
            && message.contains("at most 16777216 bytes (16 MiB)")
            && !message.contains("e+"),
        "{message}"
    );
}
