//! Runs a scenario on MuJoCo end to end: the project's Python environment (`.venv`, made by
//! `scripts/setup-python` with the pinned `mujoco`), the runner `python/mujoco/run.py` and this
//! crate's C library, which cargo builds next to every binary that depends on this crate
//! (`target/<profile>/deps/`).
//!
//! Nothing is skipped silently: a missing interpreter, venv, `mujoco` package or library is a
//! [`MujocoError::Setup`] that names the command to run.

use crate::MujocoError;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};
use touchdown_record::Summary;

/// Exit status of the runner when `mujoco` cannot be imported.
pub const RUNNER_SETUP_STATUS: i32 = 3;

/// Exit status of the runner when the landing stopped with a diagnostic, which it wrote as
/// JSON to [`DIVERGENCE_FILE`] in its output folder.
pub const RUNNER_STOPPED_STATUS: i32 = 4;

/// The file, in the runner's output folder, that holds the diagnostic of a stopped landing.
pub const DIVERGENCE_FILE: &str = "divergence.json";

/// Wall-clock guard on one run of the runner, s: a runner still going after it is stopped and
/// the run fails saying so. The run budget (`integrator.max_steps` steps, by default a few
/// minutes of MuJoCo) ends every run well before it; the guard is for a runner that hangs.
pub const RUNNER_WALL_CLOCK_S: u64 = 1800;

/// File name of this crate's C library on this platform.
pub fn library_name() -> String {
    format!(
        "{}touchdown_mujoco{}",
        std::env::consts::DLL_PREFIX,
        std::env::consts::DLL_SUFFIX
    )
}

/// What a MuJoCo run needs: the interpreter, the runner script and the library.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Launch {
    /// Python interpreter (the venv's).
    pub python: PathBuf,
    /// The runner script.
    pub runner: PathBuf,
    /// This crate's C library.
    pub library: PathBuf,
}

fn setup_error(what: String) -> MujocoError {
    MujocoError::Setup(format!("{what}; {}", touchdown_home::setup_hint()))
}

impl Launch {
    /// Finds the interpreter (`$TOUCHDOWN_PYTHON`, else the project's `.venv`), the runner and
    /// the library (`$TOUCHDOWN_MUJOCO_LIBRARY`, else next to the running executable or in its
    /// `deps/`, else in the project's `target/release/` or `target/debug/`), or says which is
    /// missing and how to set it up.
    pub fn locate() -> Result<Launch, MujocoError> {
        let root = touchdown_home::home()?;
        let python = touchdown_home::project_python("the MuJoCo engine")?;
        let runner = root.join("python").join("mujoco").join("run.py");
        if !runner.is_file() {
            return Err(MujocoError::Setup(format!(
                "the runner {} is missing from the workspace",
                runner.display()
            )));
        }
        let library = match std::env::var_os("TOUCHDOWN_MUJOCO_LIBRARY") {
            Some(p) => PathBuf::from(p),
            None => find_library()?,
        };
        Ok(Launch {
            python,
            runner,
            library,
        })
    }

    /// Runs `scenario` and writes `summary.json`, and with `history` also `history.csv`, into
    /// `out`; returns the summary. (A changed time step travels in the scenario: write the
    /// resolved scenario of `Scenario::with_mujoco`.)
    pub fn run(&self, scenario: &Path, out: &Path, history: bool) -> Result<Summary, MujocoError> {
        let mut cmd = Command::new(&self.python);
        cmd.arg(&self.runner)
            .arg(scenario)
            .arg("--out")
            .arg(out)
            .arg("--library")
            .arg(&self.library);
        if history {
            cmd.arg("--history");
        }
        let (status, stderr) = run_guarded(cmd, Duration::from_secs(RUNNER_WALL_CLOCK_S))
            .map_err(|e| setup_error(format!("cannot start {}: {e}", self.python.display())))?;
        let Some(status) = status else {
            return Err(MujocoError::Runner(format!(
                "the runner was still going after the {RUNNER_WALL_CLOCK_S} s wall-clock guard and was stopped"
            )));
        };
        outcome(status.code(), stderr, out)
    }

    /// A runner kept alive to land scenario after scenario ([`Worker`]).
    pub fn worker(&self) -> Result<Worker, MujocoError> {
        let mut child = Command::new(&self.python)
            .arg(&self.runner)
            .arg("--serve")
            .arg("--library")
            .arg(&self.library)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .map_err(|e| setup_error(format!("cannot start {}: {e}", self.python.display())))?;
        let (Some(stdin), Some(stdout), Some(mut stderr)) =
            (child.stdin.take(), child.stdout.take(), child.stderr.take())
        else {
            return Err(MujocoError::Runner("the runner's pipes are missing".into()));
        };
        let (tx, replies) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            use std::io::BufRead;
            for line in std::io::BufReader::new(stdout)
                .lines()
                .map_while(Result::ok)
            {
                if let Some(reply) = line.strip_prefix(REPLY_PREFIX) {
                    if tx.send(reply.to_string()).is_err() {
                        break;
                    }
                }
            }
        });
        let errors = std::sync::Arc::new(std::sync::Mutex::new(String::new()));
        let sink = errors.clone();
        std::thread::spawn(move || {
            let mut text = String::new();
            let _ = stderr.read_to_string(&mut text);
            if let Ok(mut e) = sink.lock() {
                *e = text;
            }
        });
        Ok(Worker {
            child,
            stdin: Some(stdin),
            replies,
            errors,
        })
    }
}

/// The prefix of the runner's reply lines in `--serve` mode.
const REPLY_PREFIX: &str = "touchdown-reply ";

/// A MuJoCo runner (`run.py --serve`) that lands scenario after scenario: Python's and
/// MuJoCo's start-up (150-240 ms) paid once, not once per landing. Each landing is the same
/// code as a runner started for it alone, on a fresh model; the runner ends when the worker is
/// dropped.
#[derive(Debug)]
pub struct Worker {
    child: std::process::Child,
    stdin: Option<std::process::ChildStdin>,
    replies: std::sync::mpsc::Receiver<String>,
    errors: std::sync::Arc<std::sync::Mutex<String>>,
}

impl Worker {
    /// Lands `scenario` and writes `summary.json`, and with `history` also `history.csv`, into
    /// `out`, as [`Launch::run`] does. A worker that fails outside a landing (it died, it hung
    /// past the wall-clock guard), or that [`Worker::ended`] on one (a MuJoCo error in a step),
    /// is of no further use: start another.
    pub fn run(
        &mut self,
        scenario: &Path,
        out: &Path,
        history: bool,
    ) -> Result<Summary, MujocoError> {
        use std::io::Write;
        let request = serde_json::json!({
            "scenario": scenario,
            "out": out,
            "history": history,
        });
        let sent = match self.stdin.as_mut() {
            Some(stdin) => writeln!(stdin, "{request}").and_then(|()| stdin.flush()),
            None => Err(std::io::Error::other("the runner's input is closed")),
        };
        if let Err(e) = sent {
            return Err(self.died(&format!("cannot send it the landing: {e}"), None));
        }
        match self
            .replies
            .recv_timeout(Duration::from_secs(RUNNER_WALL_CLOCK_S))
        {
            Ok(line) => {
                // {"status": S, "message": "..."}: S as the runner's exit status.
                let reply: serde_json::Value = serde_json::from_str(&line).map_err(|e| {
                    MujocoError::Runner(format!("the runner's reply {line:?} is not JSON: {e}"))
                })?;
                let status = reply["status"].as_i64().and_then(|s| i32::try_from(s).ok());
                let message = reply["message"].as_str().unwrap_or_default().to_string();
                outcome(status, message, out)
            }
            Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {
                let _ = self.child.kill();
                Err(MujocoError::Runner(format!(
                    "the runner was still going after the {RUNNER_WALL_CLOCK_S} s wall-clock guard and was stopped"
                )))
            }
            Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => {
                Err(self.died("it ended", Some(out)))
            }
        }
    }

    /// Whether the runner has ended (it cannot land another scenario).
    pub fn ended(&mut self) -> bool {
        !matches!(self.child.try_wait(), Ok(None))
    }

    /// The error of a runner that ended or cannot be reached: what it said on standard error,
    /// or the diagnostic it left in `out` when it ended on a stopped landing (a MuJoCo error in
    /// the library's loop, `ffi::on_mujoco_message`).
    fn died(&mut self, what: &str, out: Option<&Path>) -> MujocoError {
        let status = self.child.wait().ok().and_then(|s| s.code());
        let said = self
            .errors
            .lock()
            .map(|e| e.trim().to_string())
            .unwrap_or_default();
        match (status, out) {
            (Some(RUNNER_SETUP_STATUS), _) => setup_error(said),
            (Some(RUNNER_STOPPED_STATUS), Some(out)) => stopped(said, out),
            _ => MujocoError::Runner(format!("the serving runner failed ({what}): {said}")),
        }
    }
}

impl Drop for Worker {
    /// Closes the runner's input (it ends after its current landing) and waits for it.
    fn drop(&mut self) {
        drop(self.stdin.take());
        let _ = self.child.wait();
    }
}

/// What a runner's exit status (or a serving runner's reply status) and message mean for the
/// landing whose files it wrote into `out`.
fn outcome(status: Option<i32>, message: String, out: &Path) -> Result<Summary, MujocoError> {
    match status {
        Some(0) => {}
        Some(RUNNER_SETUP_STATUS) => return Err(setup_error(message)),
        Some(RUNNER_STOPPED_STATUS) => return Err(stopped(message, out)),
        _ => return Err(MujocoError::Runner(message)),
    }
    let path = out.join("summary.json");
    let text = std::fs::read_to_string(&path).map_err(|e| {
        std::io::Error::new(e.kind(), format!("cannot read {}: {e}", path.display()))
    })?;
    serde_json::from_str(&text)
        .map_err(|e| MujocoError::Runner(format!("{}: not a summary: {e}", path.display())))
}

/// The error of a landing the runner stopped with a diagnostic, which it wrote into `out`
/// (`message`: what it said).
fn stopped(message: String, out: &Path) -> MujocoError {
    let path = out.join(DIVERGENCE_FILE);
    let read = std::fs::read_to_string(&path)
        .map_err(|e| e.to_string())
        .and_then(|text| serde_json::from_str(&text).map_err(|e| e.to_string()));
    let _ = std::fs::remove_file(&path);
    match read {
        Ok(d) => MujocoError::Diverged(Box::new(d)),
        Err(e) => MujocoError::Runner(format!(
            "{message} (and its diagnostic {} cannot be read: {e})",
            path.display()
        )),
    }
}

/// Runs `cmd` (its standard output discarded, its standard error collected) for at most
/// `limit`: its exit status, `None` if it was stopped at the limit, and its standard error.
fn run_guarded(
    mut cmd: Command,
    limit: Duration,
) -> std::io::Result<(Option<std::process::ExitStatus>, String)> {
    let mut child = cmd
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()?;
    let mut pipe = child.stderr.take().expect("stderr is piped");
    let reader = std::thread::spawn(move || {
        let mut text = Vec::new();
        let _ = pipe.read_to_end(&mut text);
        text
    });
    let deadline = Instant::now() + limit;
    let status = loop {
        if let Some(status) = child.try_wait()? {
            break Some(status);
        }
        if Instant::now() >= deadline {
            let _ = child.kill();
            let _ = child.wait();
            break None;
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let stderr = reader.join().unwrap_or_default();
    Ok((status, String::from_utf8_lossy(&stderr).trim().to_string()))
}

/// The library next to the running executable (a binary in `target/<profile>/`, or a test or
/// bench in `target/<profile>/deps/`); else the most recently built of the project's
/// (`target/release/`, `target/debug/` and their `deps/`, [`touchdown_home::home`]): what a copied or
/// installed binary with `TOUCHDOWN_HOME`, and the Python package (whose executable is the
/// interpreter), find.
fn find_library() -> Result<PathBuf, MujocoError> {
    let name = library_name();
    let exe = std::env::current_exe()?;
    let dir = exe.parent().unwrap_or(Path::new("."));
    let mut candidates = vec![dir.join("deps").join(&name), dir.join(&name)];
    if let Some(beside) = candidates.iter().find(|p| p.is_file()) {
        return Ok(beside.clone());
    }
    let root = touchdown_home::home().ok();
    if let Some(root) = &root {
        for profile in ["release", "debug"] {
            let target = root.join("target").join(profile);
            candidates.push(target.join(&name));
            candidates.push(target.join("deps").join(&name));
        }
    }
    let built = |p: &PathBuf| std::fs::metadata(p).and_then(|m| m.modified()).ok();
    candidates
        .iter()
        .filter_map(|p| Some((built(p)?, p)))
        .max()
        .map(|(_, p)| p.clone())
        .ok_or_else(|| {
            MujocoError::Setup(format!(
                "the touchdown MuJoCo library {name} was not found (looked in {}); build it with `cargo build --release -p touchdown-mujoco` in {} (scripts/setup-python puts it there), or set TOUCHDOWN_MUJOCO_LIBRARY to it",
                candidates
                    .iter()
                    .map(|p| p.display().to_string())
                    .collect::<Vec<_>>()
                    .join(", "),
                root.unwrap_or_else(touchdown_home::home_shown).display()
            ))
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[cfg(unix)]
    #[test]
    fn a_runner_past_its_guard_is_stopped_and_one_within_it_reports_its_status() {
        let mut sleeper = Command::new("sleep");
        sleeper.arg("5");
        let start = Instant::now();
        let (status, _) = run_guarded(sleeper, Duration::from_millis(100)).unwrap();
        assert!(status.is_none(), "stopped at the guard");
        assert!(start.elapsed() < Duration::from_secs(4));
        let mut failing = Command::new("sh");
        failing.args(["-c", "echo 'run.py: why' >&2; exit 1"]);
        let (status, stderr) = run_guarded(failing, Duration::from_secs(10)).unwrap();
        assert_eq!(status.and_then(|s| s.code()), Some(1));
        assert_eq!(stderr, "run.py: why");
    }
}
