//! The command line fuzzed: hostile arguments to `run`, `boundary` and `compare` (numbers of
//! every magnitude, NaN, infinities, inverted and empty ranges, unknown engines and formats,
//! special files), each run as a process with a wall-clock guard. For every command line:
//! nothing panics, nothing hangs, the exit status is one of the documented ones (0, 1, 2, 3;
//! docs/robustness.md, "Exit statuses"), and a refusal's message starts with `error:` and names
//! an argument or a file. The suite runs a fixed, seeded sample; `TOUCHDOWN_FUZZ_CASES` and
//! `TOUCHDOWN_FUZZ_SEED` run more (docs/robustness.md, "Fuzzing").

use proptest::prelude::*;
use proptest::test_runner::TestCaseError;
use std::io::Read;
use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Command lines the test suite tries.
const SUITE_CASES: u32 = 24;

/// Wall-clock guard on one command line: a process still going after it is a hang.
const GUARD: Duration = Duration::from_secs(120);

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Numbers as a hostile user types them.
const NUMBERS: &[&str] = &[
    "0", "-1", "1", "2", "4", "6", "12", "36", "1e-300", "5e-324", "1e300", "-1e300", "nan", "inf",
    "-inf", "1e9", "1e-3", "0.1", "abc", "",
];

/// A `FROM:TO:STEP` range from three picks, or a malformed one.
fn range(a: &str, b: &str, c: &str, shape: usize) -> String {
    match shape % 4 {
        0 => format!("{a}:{b}:{c}"),
        1 => format!("{a}:{b}"),
        2 => a.to_string(),
        _ => format!("{a}:{b}:{c}:{a}"),
    }
}

/// One command line from a handful of picks.
fn command_line(picks: &[usize; 8]) -> Vec<String> {
    let n = |i: usize| NUMBERS[picks[i] % NUMBERS.len()].to_string();
    let scenarios = [
        "scenarios/flat-drop.toml",
        "scenarios/fig-25-26.toml",
        "no-such-file.toml",
        "/dev/null",
        "scenarios",
        "scenarios/vehicles/lm-1-6.toml",
    ];
    let scenario = scenarios[picks[1] % scenarios.len()].to_string();
    let engines = [
        "core",
        "rapier",
        "mujoco",
        "core,rapier",
        "core,nonsense",
        "",
    ];
    match picks[0] % 3 {
        0 => {
            let mut v = vec!["run".to_string(), scenario];
            if picks[2].is_multiple_of(2) {
                v.extend(["--engine".into(), engines[picks[3] % 3].into()]);
            }
            if picks[4].is_multiple_of(2) {
                v.extend(["--timestep".into(), n(5)]);
            }
            if picks[6].is_multiple_of(3) {
                v.extend([
                    "--format".into(),
                    ["json", "text", "xml"][picks[7] % 3].into(),
                ]);
            }
            v
        }
        1 => {
            let mut v = vec![
                "boundary".to_string(),
                scenario,
                "--vv".into(),
                range(&n(2), &n(3), &n(4), picks[5]),
            ];
            let flags = ["--vh-step", "--vh-max", "--tol", "--vh-start"];
            v.extend([flags[picks[6] % 4].to_string(), n(7)]);
            v
        }
        _ => {
            let mut v = vec!["compare".to_string(), scenario, "--report-only".into()];
            v.extend(["--engines".into(), engines[picks[2] % engines.len()].into()]);
            if picks[3].is_multiple_of(3) {
                v.extend([
                    "--format".into(),
                    ["json", "text", "csv"][picks[4] % 3].into(),
                ]);
            }
            v
        }
    }
}

/// Runs the binary on `args` with the guard: (exit code, stderr), or why it broke a property.
fn run(args: &[String]) -> Result<(i32, String), String> {
    let mut child = Command::new(env!("CARGO_BIN_EXE_touchdown"))
        .args(args)
        .current_dir(root())
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| e.to_string())?;
    let mut pipe = child.stderr.take().unwrap();
    let reader = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = pipe.read_to_string(&mut s);
        s
    });
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().map_err(|e| e.to_string())? {
            break status;
        }
        if start.elapsed() > GUARD {
            let _ = child.kill();
            let _ = child.wait();
            return Err(format!("still running after {GUARD:?}"));
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    let stderr = reader.join().unwrap_or_default();
    let code = status
        .code()
        .ok_or_else(|| format!("killed by a signal: {status:?}; {stderr}"))?;
    Ok((code, stderr))
}

/// The properties of one command line's run.
fn check(args: &[String]) -> Result<i32, String> {
    let (code, stderr) = run(args)?;
    if stderr.contains("panicked") || stderr.contains("RUST_BACKTRACE") {
        return Err(format!("panicked: {stderr}"));
    }
    if !matches!(code, 0..=3) {
        return Err(format!("undocumented exit status {code}: {stderr}"));
    }
    if code == 1 || code == 2 {
        // Warnings may come first; the refusal is the line that starts with `error:`.
        let first = stderr
            .lines()
            .find(|l| l.starts_with("error:"))
            .unwrap_or("");
        let names_something = stderr.contains("--")
            || stderr.contains(".toml")
            || stderr.contains("/dev/null")
            || stderr.contains("scenarios")
            || stderr.contains("<SCENARIO")
            || stderr.contains("Usage");
        if !first.starts_with("error:") || !names_something {
            return Err(format!(
                "a refusal that names no argument or file: {stderr}"
            ));
        }
    }
    Ok(code)
}

#[test]
fn hostile_command_lines_are_refused_naming_the_argument_and_never_panic_or_hang() {
    let (mut runner, cases, seed) = touchdown_tests::fuzz_runner(SUITE_CASES);
    let tally = std::cell::RefCell::new([0usize; 4]);
    let result = runner.run(&prop::array::uniform8(0usize..1000), |picks| {
        let args = command_line(&picks);
        let code = check(&args)
            .map_err(|why| TestCaseError::fail(format!("touchdown {}: {why}", args.join(" "))))?;
        tally.borrow_mut()[code as usize] += 1;
        Ok(())
    });
    if let Err(e) = result {
        panic!("{e}");
    }
    let t = tally.into_inner();
    eprintln!(
        "command-line fuzz: {cases} command lines (seed {seed}): exit 0: {}, 1: {}, 2: {}, 3: {}",
        t[0], t[1], t[2], t[3]
    );
}
