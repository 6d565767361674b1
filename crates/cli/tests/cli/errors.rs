//! Errors and exit statuses: bad input, a failing verdict, a closed pipe, a full disk.

use super::{extending, root, touchdown};
use std::process::Command;

#[test]
fn bad_input_fails_with_the_file_and_field() {
    let f = extending(
        "bad",
        "bad.toml",
        "flat-drop.toml",
        "bad",
        "[vehicle]\nmass = -2.0\n",
    );
    let out = touchdown(&["run", f.to_str().unwrap()]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("bad.toml") && err.contains("vehicle.mass") && err.contains("positive"),
        "{err}"
    );
    assert!(out.stdout.is_empty(), "nothing is written on failure");
    // A missing file: its path and the cause, once.
    let out = touchdown(&["run", "scenarios/nope.toml"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(
        err.trim(),
        "error: scenarios/nope.toml: cannot read the scenario file: No such file or directory (os error 2)"
    );
}

/// A failing verdict exits with its own status (3), distinct from an input error (1) and a usage
/// error (2), unless the user asks for the report only.
#[test]
fn a_failing_verdict_exits_3_unless_only_the_report_is_asked_for() {
    // The slow 2-2 landing with the report's massless footpad: the core and rapier part on its
    // secondary strokes (a FAIL).
    let args = [
        "compare",
        "scenarios/table-i-2-2-vv4.toml",
        "--engines",
        "core,rapier",
        "--set",
        "footpad.detached=rigid",
    ];
    let out = touchdown(&args);
    assert_eq!(
        out.status.code(),
        Some(3),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(String::from_utf8_lossy(&out.stdout).contains("core vs rapier: FAIL"));
    let out = touchdown(&[&args[..], &["--report-only"]].concat());
    assert_eq!(out.status.code(), Some(0));
    assert_eq!(
        touchdown(&["compare", "no-such.toml"]).status.code(),
        Some(1)
    );
    assert_eq!(
        touchdown(&["compare", "--no-such-flag"]).status.code(),
        Some(2)
    );
}

/// Output to a closed pipe ends the process quietly, killed by SIGPIPE as other tools are, not
/// with a panic message.
#[cfg(unix)]
#[test]
fn output_to_a_closed_pipe_ends_quietly() {
    use std::io::Read;
    use std::os::unix::process::ExitStatusExt;
    use std::process::Stdio;
    let mut child = Command::new(env!("CARGO_BIN_EXE_touchdown"))
        .args([
            "compare",
            "scenarios/flat-drop.toml",
            "scenarios/flat-drop.toml",
        ])
        .args(["--engines", "core,rapier", "--report-only"])
        .current_dir(root())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = [0u8; 16];
    child
        .stdout
        .as_mut()
        .unwrap()
        .read_exact(&mut first)
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.signal(), Some(libc::SIGPIPE), "{:?}", out.status);
    assert!(
        out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Output to a full disk is an error naming standard output (exit 1), not a panic (exit 101),
/// for every command that writes results on standard output.
#[cfg(unix)]
#[test]
fn output_to_a_full_disk_is_an_error_naming_standard_output() {
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    for args in [
        &["run", "scenarios/flat-drop.toml"][..],
        &["completions", "bash"],
        &[
            "campaign",
            "scenarios/campaigns/small.toml",
            "--format",
            "json",
        ],
        &[
            "boundary",
            "scenarios/table-i-2-2-vv8.toml",
            "--vv=-8:-8:2",
            "--vh-step",
            "8",
            "--vh-max",
            "8",
            "--format",
            "json",
        ],
    ] {
        let out = Command::new(env!("CARGO_BIN_EXE_touchdown"))
            .args(args)
            .current_dir(root())
            .stdout(full.try_clone().unwrap())
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
        assert!(
            err.contains("error: cannot write to standard output: No space left on device"),
            "{args:?}: {err}"
        );
    }
}

/// A time step the engine refuses is blamed on the argument that set it.
#[test]
fn a_refused_timestep_names_the_argument() {
    for t in ["1e-300", "nan"] {
        let out = touchdown(&[
            "run",
            "scenarios/flat-drop.toml",
            "--engine",
            "rapier",
            "--timestep",
            t,
        ]);
        assert_eq!(out.status.code(), Some(1));
        let err = String::from_utf8_lossy(&out.stderr);
        let line = err.lines().find(|l| l.starts_with("error:")).unwrap_or("");
        assert!(line.starts_with("error: --timestep"), "{err}");
    }
}
