//! The comparison plots: data written by the Rust side, drawn by `python/plot_compare.py` with
//! the pinned matplotlib of the project's Python environment.

use anyhow::{bail, Context, Result};
use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::Command;
use touchdown_compare::ScenarioComparison;

/// Runs `python/plot_compare.py` with `args`.
fn draw(args: &[&OsStr]) -> Result<()> {
    run_script("plot_compare.py", args)
}

/// Runs the plotting script `python/<name>` with `args`; its error output becomes the error.
fn run_script(name: &str, args: &[&OsStr]) -> Result<()> {
    let python = touchdown_mujoco::launch::project_python("--plot")?;
    let script: PathBuf = touchdown_mujoco::launch::home()?.join("python").join(name);
    let out = Command::new(&python)
        .arg(script)
        .args(args)
        .output()
        .with_context(|| format!("cannot start {}", python.display()))?;
    if !out.status.success() {
        bail!(
            "python/{name} failed: {}",
            String::from_utf8_lossy(&out.stderr).trim()
        );
    }
    Ok(())
}

/// `touchdown campaign --plot DIR`: outcomes.png and strokes.png drawn into `plots` from the
/// campaign folder `records`.
pub fn campaign(records: &Path, plots: &Path) -> Result<()> {
    run_script(
        "plot_campaign.py",
        &[records.as_os_str(), plots.as_os_str()],
    )
}

/// `touchdown compare --plot DIR`: the traces of `c` (run from `scenario`) as CSV and their
/// overlay as DIR/<stem>.png.
pub fn comparison(c: &ScenarioComparison, scenario: &Path, dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let stem = scenario
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "scenario".into());
    touchdown_compare::plot::write_traces(c, dir, &stem)
        .with_context(|| format!("cannot write the traces into {}", dir.display()))?;
    let engines: Vec<&str> = c.runs.iter().map(|r| r.engine.name()).collect();
    let png = dir.join(format!("{stem}.png"));
    draw(&[
        "traces".as_ref(),
        "--data".as_ref(),
        dir.as_os_str(),
        "--stem".as_ref(),
        stem.as_ref(),
        "--engines".as_ref(),
        engines.join(",").as_ref(),
        "--title".as_ref(),
        c.scenario.as_ref(),
        "--out".as_ref(),
        png.as_os_str(),
    ])
}

/// Writes `json` beside `png` (same stem, .json), creating its folder; returns the data file.
fn data_beside(json: &str, png: &Path) -> Result<PathBuf> {
    if let Some(dir) = png.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    let data = png.with_extension("json");
    std::fs::write(&data, json).with_context(|| format!("cannot write {}", data.display()))?;
    Ok(data)
}

/// `touchdown boundary --plot FILE`: the boundary points (JSON, written beside FILE) overlaid
/// per engine into FILE: the boundary (lowest stable → unstable transition) per descent speed,
/// every transition's bracket, the further transitions, the unresolved brackets and the
/// undecided landings, each kind with a legend entry.
/// `unit` is the velocity unit of the points.
pub fn boundaries(json: &str, title: &str, unit: &str, png: &Path) -> Result<()> {
    let data = data_beside(json, png)?;
    draw(&[
        "boundaries".as_ref(),
        "--data".as_ref(),
        data.as_os_str(),
        "--title".as_ref(),
        title.as_ref(),
        "--unit".as_ref(),
        unit.as_ref(),
        "--out".as_ref(),
        png.as_os_str(),
    ])
}

/// `touchdown precision --plot FILE`: the work-precision study (JSON, written beside FILE) as
/// log-log plots of error against wall time, one line per engine and scheme, into FILE.
pub fn precision(json: &str, title: &str, png: &Path) -> Result<()> {
    let data = data_beside(json, png)?;
    draw(&[
        "precision".as_ref(),
        "--data".as_ref(),
        data.as_os_str(),
        "--title".as_ref(),
        title.as_ref(),
        "--out".as_ref(),
        png.as_os_str(),
    ])
}
