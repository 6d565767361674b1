//! The comparison plots: data written by the Rust side, drawn by `python/figures/plot_compare.py` with
//! the pinned matplotlib of the project's Python environment.

use anyhow::{bail, Context, Result};
use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::Command;
use touchdown_compare::ScenarioComparison;

/// Runs `python/figures/plot_compare.py` with `args`.
fn draw(args: &[&OsStr]) -> Result<()> {
    run_script("plot_compare.py", args)
}

/// Runs the plotting script `python/figures/<name>` with `args`; its error output becomes the
/// error.
fn run_script(name: &str, args: &[&OsStr]) -> Result<()> {
    let python = touchdown_home::project_python("--plot")?;
    let script: PathBuf = touchdown_home::home()?.join("python/figures").join(name);
    let out = Command::new(&python)
        .arg(script)
        .args(args)
        .output()
        .with_context(|| format!("cannot start {}", python.display()))?;
    if !out.status.success() {
        bail!(
            "python/figures/{name} failed: {}",
            String::from_utf8_lossy(&out.stderr).trim()
        );
    }
    Ok(())
}

/// `touchdown campaign --out DIR --plot`: outcomes.png and strokes.png drawn into the campaign
/// folder `dir` from its records.
pub fn campaign(dir: &Path) -> Result<()> {
    run_script("plot_campaign.py", &[dir.as_os_str(), dir.as_os_str()])
}

/// `touchdown campaign --plot` of a paired campaign: disagreement.png and differences.png
/// (python/figures/plot_paired.py) into its folder `dir`.
pub fn paired(dir: &Path) -> Result<()> {
    run_script("plot_paired.py", &[dir.as_os_str(), dir.as_os_str()])
}

/// `touchdown compare --out DIR [--plot]`: the traces of `c` (run from `scenario`) as CSV, its
/// `document` (the comparison's JSON, with every verdict) as DIR/<stem>.json, and with `plot`
/// their overlay as DIR/<stem>.png.
pub fn comparison(
    c: &ScenarioComparison,
    document: &str,
    scenario: &Path,
    dir: &Path,
    plot: bool,
) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let stem = scenario
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "scenario".into());
    touchdown_compare::plot::write_traces(c, dir, &stem)
        .with_context(|| format!("cannot write the traces into {}", dir.display()))?;
    let comparison = dir.join(format!("{stem}.json"));
    std::fs::write(&comparison, document)
        .with_context(|| format!("cannot write {}", comparison.display()))?;
    if !plot {
        return Ok(());
    }
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
        "--report".as_ref(),
        comparison.as_os_str(),
        "--title".as_ref(),
        c.scenario.as_ref(),
        "--out".as_ref(),
        png.as_os_str(),
    ])
}

/// `touchdown boundary --out DIR --plot`: the boundary points (the JSON Lines file `data`)
/// overlaid per engine into `png`: the boundary (lowest stable → unstable transition) per
/// descent speed, every transition's bracket, the further transitions, the unresolved brackets
/// and the undecided landings, each kind with a legend entry. `unit` is the velocity unit of
/// the axes (the points are SI).
pub fn boundaries(data: &Path, title: &str, unit: &str, png: &Path) -> Result<()> {
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

/// `touchdown precision --out DIR --plot`: the work-precision study (the JSON file `data`) as
/// log-log plots of error against wall time, one line per engine and scheme, into `png`.
pub fn precision(data: &Path, title: &str, png: &Path) -> Result<()> {
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
