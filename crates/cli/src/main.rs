//! `touchdown`: runs landing scenarios and reports them.
//!
//! The argument structs' doc comments are the command line's help text, where `<scenario>` is
//! the usage's placeholder for an argument, not an HTML tag.
#![allow(rustdoc::invalid_html_tags)]

mod args;
mod boundary;
mod campaign;
mod check;
mod compare;
mod draft;
mod landing;
mod manual;
mod plots;
mod precision;
mod report;
mod robustness;
mod signals;
mod validation;
mod view;

use anyhow::{bail, Context, Result};
use args::{Cli, Command, Format, ValidationProtocol};
use std::path::{Path, PathBuf};
use touchdown_scenario::schema::Engine;
use touchdown_scenario::Scenario;

pub(crate) use args::{load, overrides, settings, Set};

/// What a command found, for its exit status: 0 when it passes (or has no verdict), 3 when
/// its verdict fails (`compare` with a failing pair, `validate` with a target not met; see
/// `--report-only`); an error in the input or a run exits 1, a usage error 2 (clap's).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Verdict {
    Pass,
    Fail,
}

/// Exit status of a failing verdict.
const VERDICT_FAILED: u8 = 3;

fn main() -> std::process::ExitCode {
    // Output to a closed pipe (`touchdown compare ... | head -1`) ends the process quietly with
    // the conventional status (killed by SIGPIPE), as other command-line tools do, instead of
    // a panic in `println!`.
    #[cfg(unix)]
    // SAFETY: restoring the default disposition of SIGPIPE at start-up, before any thread or
    // child process exists.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let cli = Cli::parse_arguments();
    QUIET.store(cli.quiet, std::sync::atomic::Ordering::Relaxed);
    match run(cli) {
        Ok(Verdict::Pass) => std::process::ExitCode::SUCCESS,
        Ok(Verdict::Fail) => std::process::ExitCode::from(VERDICT_FAILED),
        Err(e) => {
            eprintln!("error: {e:#}");
            std::process::ExitCode::FAILURE
        }
    }
}

/// Writes to standard output (`out!` as `print!`, `outln!` as `println!`), flushed, and
/// returns what stops it (a full disk) as an error naming standard output, where `print!`
/// panics.
macro_rules! out {
    ($($arg:tt)*) => {
        $crate::write_stdout(format_args!($($arg)*))
    };
}
macro_rules! outln {
    ($($arg:tt)*) => {
        $crate::write_stdout(format_args!("{}\n", format_args!($($arg)*)))
    };
}
pub(crate) use {out, outln};

/// What `out!` and `outln!` do.
pub fn write_stdout(text: std::fmt::Arguments) -> Result<()> {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    stdout
        .write_fmt(text)
        .and_then(|()| stdout.flush())
        .context("cannot write to standard output")
}

/// Prints the scenario's warnings (values legal but outside their usual range) on stderr.
pub fn warn(sc: &Scenario) {
    for w in sc.warnings() {
        eprintln!("warning: {}: field `{}`: {}", w.file, w.field, w.message);
    }
    // What `touchdown check` finds besides: the stroke energy, the tip-over angle.
    for f in check::findings(sc) {
        eprintln!("warning: {f}");
    }
}

/// Whether `--quiet` was given: no progress bars.
static QUIET: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// A progress bar of `len` steps of `unit` (a plural noun: "landings") on standard error, with
/// the rate and, when `len` is known (non-zero), the time left; a counter with the rate and the
/// time spent when it is not. Hidden when standard error is not a terminal (a pipe, a log file,
/// CI) or with `--quiet`.
pub fn progress_bar(len: u64, unit: &'static str) -> indicatif::ProgressBar {
    use indicatif::{ProgressBar, ProgressStyle};
    use std::io::IsTerminal;
    if QUIET.load(std::sync::atomic::Ordering::Relaxed) || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let (bar, template) = if len > 0 {
        (
            ProgressBar::new(len),
            "[{elapsed_precise}] {wide_bar} {human_pos}/{human_len} {prefix} · {rate} · {eta} left",
        )
    } else {
        (
            ProgressBar::new_spinner(),
            "{spinner} [{elapsed_precise}] {human_pos} {prefix} · {rate}",
        )
    };
    if let Ok(style) = ProgressStyle::with_template(template) {
        // The rate to a tenth (not indicatif's four decimals), or the time each takes when
        // fewer than one a second finish.
        let rate = |s: &indicatif::ProgressState, w: &mut dyn std::fmt::Write| {
            let _ = match s.per_sec() {
                r if r >= 1.0 => write!(w, "{r:.1}/s"),
                r if r > 0.0 => write!(w, "{:.1} s each", 1.0 / r),
                _ => write!(w, "—"),
            };
        };
        bar.set_style(style.with_key("rate", rate));
    }
    bar.set_prefix(unit);
    bar.enable_steady_tick(std::time::Duration::from_millis(250));
    bar
}

/// The verdict of a command with one: `Fail` only if it failed and the user did not ask for
/// the report only.
fn verdict(passed: bool, report_only: bool) -> Verdict {
    if passed || report_only {
        Verdict::Pass
    } else {
        Verdict::Fail
    }
}

fn run(cli: Cli) -> Result<Verdict> {
    let done = |r: Result<()>| r.map(|()| Verdict::Pass);
    match cli.command {
        Command::Run(a) => done(landing::run(a)),
        Command::New(a) => draft::new(a).map(|passed| verdict(passed, false)),
        Command::Check(a) => {
            check::check(&a.scenario, &a.set.set, a.format).map(|passed| verdict(passed, false))
        }
        Command::Compare(a) => {
            let report_only = a.report_only;
            compare::compare(a).map(|passed| verdict(passed, report_only))
        }
        Command::View(a) => done(view::view(a)),
        Command::Precision(a) => done(precision::precision(a)),
        Command::Robustness(a) => done(robustness::robustness(
            &home(a.root)?,
            &a.engines,
            a.cases,
            a.search,
            a.format,
        )),
        Command::ExportMjcf(a) => done(export_mjcf(&a.scenario, &a.set.set, &a.out)),
        Command::Validate(a) => {
            let (root, json) = (home(a.root)?, a.format == Format::Json);
            let passed = match a.protocol {
                ValidationProtocol::TwoRow => validation::validate(&root, json, a.out.as_deref()),
                ValidationProtocol::Cv => validation::cross_validate(&root, json, a.out.as_deref()),
            }?;
            Ok(verdict(passed, a.report_only))
        }
        Command::Calibrate(a) => done(validation::calibrate(
            &home(a.root)?,
            a.rows,
            a.out.as_deref(),
        )),
        Command::Estimate(a) => done(validation::estimate(&home(a.root)?)),
        Command::Sensitivity(a) => done(validation::sensitivity(
            &home(a.root)?,
            a.fraction,
            a.format == Format::Json,
        )),
        Command::Boundary(a) => done(boundary::boundary(a)),
        Command::Completions(a) => done(manual::completions(a.shell)),
        Command::Man(a) => done(manual::man_pages(&a.out)),
        Command::Campaign(a) => done(campaign::command(a)),
    }
}

/// The file `DIR/<prefix><scenario's stem>.<ext>` of an output folder `dir`, the folder
/// created.
pub fn out_file(dir: &Path, prefix: &str, scenario: &Path, ext: &str) -> Result<PathBuf> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let stem = scenario
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "scenario".into());
    Ok(dir.join(format!("{prefix}{stem}.{ext}")))
}

/// The project's folder: `--root` if given, else found as the MuJoCo engine finds its runner
/// (`touchdown_home::home`).
fn home(root: Option<PathBuf>) -> Result<PathBuf> {
    match root {
        Some(r) if r.join("reference").is_dir() && r.join("scenarios").is_dir() => Ok(r),
        Some(r) => bail!(
            "--root {}: expected the project's folder, holding reference/ and scenarios/",
            r.display()
        ),
        None => Ok(touchdown_home::home()?),
    }
}

/// `touchdown export-mjcf`: the scenario's MuJoCo model (MJCF) into `out`.
fn export_mjcf(scenario: &Path, set: &[Set], out: &Path) -> Result<()> {
    let sc = load(scenario, set)?.1;
    warn(&sc);
    touchdown_registry::require(Engine::Mujoco, &sc)?;
    let xml = touchdown_mujoco::export(&sc)?;
    let path = out_file(out, "", scenario, "xml")?;
    std::fs::write(&path, xml).with_context(|| format!("cannot write {}", path.display()))?;
    outln!("wrote {}", path.display())?;
    Ok(())
}
