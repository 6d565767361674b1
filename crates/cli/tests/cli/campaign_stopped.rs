//! A campaign stopped part-way (killed, signalled, out of room) claims nothing and resumes.

use super::{root, temp, touchdown};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Every file under `dir` with its bytes, by path relative to `dir`.
fn files_of(dir: &Path) -> std::collections::BTreeMap<PathBuf, Vec<u8>> {
    let mut files = std::collections::BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else {
                let bytes = std::fs::read(&path).unwrap();
                files.insert(path.strip_prefix(dir).unwrap().to_path_buf(), bytes);
            }
        }
    }
    files
}

/// A copy of the TN D-3117-style campaign with `landings` landings, its base scenario named by
/// its full path, written into `dir`.
fn d3117_with(dir: &Path, landings: u64) -> PathBuf {
    let text = std::fs::read_to_string(root().join("scenarios/campaigns/lm-1-6-d3117.toml"))
        .unwrap()
        .replace("landings = 3000", &format!("landings = {landings}"))
        .replace(
            "scenario = \"../table-i-2-2-vv8.toml\"",
            &format!(
                "scenario = {:?}",
                root().join("scenarios/table-i-2-2-vv8.toml")
            ),
        );
    std::fs::create_dir_all(dir).unwrap();
    let file = dir.join("campaign.toml");
    std::fs::write(&file, text).unwrap();
    file
}

/// A campaign killed (SIGKILL) at any moment and continued with `--resume` into the same
/// folder ends byte for byte as an uninterrupted run, and a killed run never leaves a folder
/// that looks complete. Ten kill points spread over the run (its start-up, its landings, the
/// writing of its Parquet file and statistics) by a fixed low-discrepancy sequence.
#[test]
fn a_campaign_killed_at_any_moment_resumes_to_the_same_bytes() {
    let dir = temp("resume");
    let file = d3117_with(&dir, 120);
    let file = file.to_str().unwrap();
    let whole = dir.join("whole");
    let started = std::time::Instant::now();
    let out = touchdown(&["campaign", file, "--out", whole.to_str().unwrap()]);
    assert!(out.status.success(), "{out:?}");
    let span = started.elapsed();
    let expected = files_of(&whole);
    for k in 0..10 {
        let killed = dir.join(format!("killed-{k}"));
        // Fractions 0.05 to 1.15 of the uninterrupted run's time, in a scrambled order.
        let fraction = 0.05 + 1.1 * ((k as f64 * 0.618_034) % 1.0);
        let mut child = Command::new(env!("CARGO_BIN_EXE_touchdown"))
            .args(["campaign", file, "--out", killed.to_str().unwrap()])
            .current_dir(root())
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(span.mul_f64(fraction));
        let _ = child.kill(); // SIGKILL
        child.wait().unwrap();
        // Either nothing is there yet, or the run had finished: a complete folder.
        if killed.exists() {
            assert_eq!(
                files_of(&killed),
                expected,
                "kill {k} left a folder that differs"
            );
        }
        let out = touchdown(&[
            "campaign",
            file,
            "--out",
            killed.to_str().unwrap(),
            "--resume",
        ]);
        assert!(out.status.success(), "kill {k}: {out:?}");
        assert!(
            files_of(&killed) == expected,
            "kill {k} at {fraction:.2} of the run: the resumed folder differs"
        );
        assert!(!dir.join(format!("killed-{k}.partial")).exists());
    }
}

/// A campaign ended by SIGINT, SIGTERM or SIGHUP says what it keeps and the command that goes
/// on from it, ends with the status a shell gives a process the signal ended, and that command
/// completes the campaign.
#[cfg(unix)]
#[test]
fn a_campaign_ended_by_a_signal_says_what_it_keeps_and_how_to_go_on() {
    let dir = temp("signals");
    let file = d3117_with(&dir, 400);
    for signal in [libc::SIGINT, libc::SIGTERM, libc::SIGHUP] {
        let out = dir.join(format!("out-{signal}"));
        let records = dir.join(format!("out-{signal}.partial/landings.jsonl"));
        let child = Command::new(env!("CARGO_BIN_EXE_touchdown"))
            .args([
                "campaign",
                file.to_str().unwrap(),
                "--out",
                out.to_str().unwrap(),
            ])
            .current_dir(root())
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        let deadline = std::time::Instant::now() + std::time::Duration::from_secs(120);
        while std::fs::metadata(&records).map_or(true, |m| m.len() == 0) {
            assert!(
                std::time::Instant::now() < deadline,
                "no record within 120 s"
            );
            std::thread::sleep(std::time::Duration::from_millis(10));
        }
        // SAFETY: sending a signal to the child this test started and has not waited for.
        unsafe {
            libc::kill(child.id() as libc::pid_t, signal);
        }
        let ended = child.wait_with_output().unwrap();
        assert_eq!(ended.status.code(), Some(128 + signal), "{ended:?}");
        let err = String::from_utf8_lossy(&ended.stderr);
        let kept = format!("kept in {}", records.parent().unwrap().display());
        assert!(
            err.contains("stopped by a signal") && err.contains(&kept),
            "{err}"
        );
        let command = err.lines().last().unwrap().trim();
        assert!(command.ends_with("--resume"), "{err}");
        if signal == libc::SIGINT {
            let args: Vec<String> = shlex::split(command).unwrap();
            assert_eq!(args[0], "touchdown");
            let args: Vec<&str> = args[1..].iter().map(String::as_str).collect();
            let resumed = touchdown(&args);
            assert!(resumed.status.success(), "{resumed:?}");
            assert!(out.join("manifest.json").is_file());
        }
    }
}

/// A campaign that cannot write its records (here a file-size limit, as a full disk would)
/// ends with an error naming the file and a non-zero status, and leaves no folder that looks
/// complete; a single landing's `--out` names the file it could not write.
#[test]
fn a_campaign_that_cannot_write_ends_with_the_path_and_claims_nothing() {
    let dir = temp("full");
    let file = d3117_with(&dir, 120);
    let out_dir = dir.join("out");
    // `ulimit -f` in 512-byte blocks: 64 blocks, 32 kB, about ten records. SIGXFSZ ignored (as
    // `trap` leaves it for the program), so that a write past the limit fails with EFBIG.
    let past_the_limit = |args: String| {
        let command = format!(
            "trap '' XFSZ; ulimit -f 64; exec {} {args}",
            env!("CARGO_BIN_EXE_touchdown")
        );
        let out = Command::new("sh")
            .args(["-c", &command])
            .current_dir(root())
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr).to_string();
        assert_eq!(out.status.code(), Some(1), "{stderr}");
        stderr
    };
    let stderr = past_the_limit(format!(
        "campaign {} --out {}",
        file.display(),
        out_dir.display()
    ));
    // The first file past the limit (a history or the records), in the folder being built.
    assert!(
        stderr.contains("out.partial/") && stderr.contains("File too large"),
        "the error names the file: {stderr}"
    );
    assert!(!out_dir.exists(), "nothing claimed complete");
    // One landing's files past the same limit: the error names the file that failed.
    let run_dir = dir.join("run");
    let stderr = past_the_limit(format!(
        "run scenarios/fig-25-26.toml --out {}",
        run_dir.display()
    ));
    assert!(
        stderr.contains("cannot write") && stderr.contains("run/history.csv"),
        "the error names the file: {stderr}"
    );
}
