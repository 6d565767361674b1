//! The engines and the project found: MuJoCo's setup, MJCF export, a copied binary, the root.

use super::{root, temp, touchdown};
use std::path::Path;
use std::process::Command;

/// `touchdown run --engine mujoco` with `python` as the interpreter.
fn run_mujoco_with(python: &Path) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_touchdown"))
        .args(["run", "scenarios/flat-drop.toml", "--engine", "mujoco"])
        .env("TOUCHDOWN_PYTHON", python)
        .current_dir(root())
        .output()
        .expect("the touchdown binary runs")
}

#[test]
fn mujoco_without_the_python_environment_fails_with_the_setup_command() {
    let out = run_mujoco_with(Path::new("/nonexistent/.venv/bin/python"));
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("not set up") && err.contains("scripts/setup-python"),
        "{err}"
    );
}

#[test]
fn mujoco_without_the_mujoco_package_fails_with_the_setup_command() {
    // An interpreter that cannot see any installed package (python3 -S: no site-packages).
    let d = temp("no-mujoco");
    std::fs::create_dir_all(&d).unwrap();
    let python = d.join("python");
    std::fs::write(&python, "#!/bin/sh\nexec python3 -S \"$@\"\n").unwrap();
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(&python, std::fs::Permissions::from_mode(0o755)).unwrap();
    let out = run_mujoco_with(&python);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("cannot be imported") && err.contains("scripts/setup-python"),
        "{err}"
    );
}

#[test]
fn export_mjcf_writes_a_standalone_model() {
    let dir = temp("mjcf");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("flat-drop.xml");
    let out = touchdown(&[
        "export-mjcf",
        "scenarios/flat-drop.toml",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let xml = std::fs::read_to_string(&file).unwrap();
    assert!(
        xml.starts_with("<!-- Touchdown MJCF export"),
        "{}",
        &xml[..80]
    );
    assert!(xml.trim_end().ends_with("</mujoco>"));
    for name in [
        "vehicle",
        "leg4_footpad",
        "leg4_stroke",
        "leg4_s41",
        "touchdown",
    ] {
        assert!(xml.contains(&format!("name=\"{name}\"")), "{name} missing");
    }
}

/// The project's data is found wherever the command runs from: above the executable when the
/// current directory is elsewhere, at `$TOUCHDOWN_HOME` when set; a wrong `$TOUCHDOWN_HOME` or
/// `--root` is an error saying what was expected.
#[test]
fn the_project_is_found_from_any_directory() {
    let elsewhere = std::env::temp_dir();
    let run = |envs: &[(&str, &str)], args: &[&str]| {
        let mut c = Command::new(env!("CARGO_BIN_EXE_touchdown"));
        c.args(args)
            .current_dir(&elsewhere)
            .env_remove("TOUCHDOWN_HOME");
        for (k, v) in envs {
            c.env(k, v);
        }
        c.output().unwrap()
    };
    let o = run(&[], &["validate", "--report-only", "--format", "json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let home = root();
    let o = run(
        &[("TOUCHDOWN_HOME", home.to_str().unwrap())],
        &["sensitivity", "--fraction", "0.1", "--format", "json"],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // Each parameter's value carries the unit of the scenario file it is written in.
    let table: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(table["schema"], "touchdown.sensitivity/1");
    let units: Vec<(&str, &str)> = table["parameters"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            (
                p["parameter"].as_str().unwrap(),
                p["unit"].as_str().unwrap(),
            )
        })
        .collect();
    assert!(units.contains(&("vehicle mass M", "slug")), "{units:?}");
    assert!(
        units.contains(&("primary onset rate", "lbf/ft")),
        "{units:?}"
    );
    assert!(units.iter().all(|(_, u)| !u.is_empty()), "{units:?}");
    let o = run(&[("TOUCHDOWN_HOME", "/nonexistent")], &["validate"]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("$TOUCHDOWN_HOME is /nonexistent") && err.contains("python/mujoco/run.py"),
        "{err}"
    );
    let o = run(&[], &["validate", "--root", elsewhere.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("expected the project's folder"));
}

/// A copied binary (nothing beside it) runs MuJoCo with `$TOUCHDOWN_HOME` alone: the library
/// is found in the project's build folders.
#[test]
fn a_copied_binary_runs_mujoco_with_touchdown_home_alone() {
    let dir = temp("copied-binary");
    std::fs::create_dir_all(&dir).unwrap();
    let copy = dir.join("touchdown");
    std::fs::copy(env!("CARGO_BIN_EXE_touchdown"), &copy).unwrap();
    let o = Command::new(&copy)
        .args([
            "run",
            "scenarios/flat-drop.toml",
            "--engine",
            "mujoco",
            "--format",
            "json",
        ])
        .current_dir(root())
        .env("TOUCHDOWN_HOME", root())
        .env_remove("TOUCHDOWN_MUJOCO_LIBRARY")
        .env_remove("TOUCHDOWN_PYTHON")
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let summary: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(summary["engine"], "mujoco");
    let _ = std::fs::remove_dir_all(&dir);
}
