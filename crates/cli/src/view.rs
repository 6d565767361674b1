//! `touchdown view` and `touchdown compare --view`: a landing's trajectory file and the page that
//! plays it (docs/engines.md, "Watching the engines land"; docs/outputs.md, "The trajectory
//! file").

use crate::{load, out_file, settings, warn, Set};
use anyhow::{bail, Context, Result};
use std::path::{Path, PathBuf};
use touchdown_compare::EngineRun;
use touchdown_record::{Document, ScenarioId};
use touchdown_scenario::schema::Engine;
use touchdown_scenario::Scenario;

/// The options a trajectory records in its settings: the engines and the frame interval.
pub fn options(engines: &[Engine], frame_interval: f64) -> serde_json::Value {
    serde_json::json!({ "engines": engines, "frame_interval_s": frame_interval })
}

/// Checks `--frame-interval`.
pub fn check_interval(frame_interval: f64) -> Result<()> {
    if !(frame_interval.is_finite() && frame_interval > 0.0) {
        bail!("--frame-interval: expected a time between frames > 0 s, got {frame_interval}");
    }
    Ok(())
}

/// Writes `DIR/<scenario>.trajectory.json` (the trajectory document of the runs, which recorded
/// their frames) and `DIR/<scenario>.html` (the page that plays it); returns both paths.
pub fn write(
    dir: &Path,
    path: &Path,
    sc: &Scenario,
    runs: &[EngineRun],
    settings: &serde_json::Value,
) -> Result<(PathBuf, PathBuf)> {
    let body = touchdown_compare::trajectory(sc, runs);
    let id = ScenarioId::new(path.display(), sc);
    let json = Document::new("trajectory", Some(&id), settings, &body).line();
    let data = out_file(dir, "", path, "trajectory.json")?;
    std::fs::write(&data, &json).with_context(|| format!("cannot write {}", data.display()))?;
    let page = out_file(dir, "", path, "html")?;
    let title = format!("{}: touchdown view", sc.file.name);
    std::fs::write(&page, touchdown_view::page::page(&title, &json))
        .with_context(|| format!("cannot write {}", page.display()))?;
    Ok((data, page))
}

/// `touchdown view`: the scenario on each of `engines` it applies to, recorded, written as a
/// trajectory file and its page into `dir`.
pub fn view(
    scenario: &Path,
    set: &[Set],
    engines: &[Engine],
    frame_interval: f64,
    dir: &Path,
) -> Result<()> {
    check_interval(frame_interval)?;
    let sc = load(scenario, set)?.1;
    warn(&sc);
    let mut chosen = engines.to_vec();
    chosen.sort();
    chosen.dedup();
    let (run, skipped): (Vec<Engine>, Vec<Engine>) = chosen
        .into_iter()
        .partition(|e| sc.applicable_engines.contains(e));
    if run.is_empty() {
        bail!(
            "--engines: none of {} applies to {} (its engines.applicable: {})",
            names(&skipped),
            scenario.display(),
            names(&sc.applicable_engines)
        );
    }
    for e in &skipped {
        eprintln!(
            "{e}: not in {}'s engines.applicable, not run",
            scenario.display()
        );
    }
    let runs = run
        .iter()
        .map(|&e| touchdown_compare::run_recorded(e, scenario, &sc, Some(frame_interval)))
        .collect::<Result<Vec<_>, _>>()?;
    for r in &runs {
        let frames = r.recording.as_ref().map_or(0, |f| f.frames.t_s.len());
        println!(
            "{}: {} after {:.4} s, {} steps, {} frames",
            r.engine,
            format!("{:?}", r.summary.outcome).to_lowercase(),
            r.summary.t_end_s,
            r.summary.steps,
            frames
        );
    }
    let settings = settings(set, options(&run, frame_interval));
    let (data, page) = write(dir, scenario, &sc, &runs, &settings)?;
    println!("wrote {}\nwrote {}", data.display(), page.display());
    Ok(())
}

/// Engine names, comma-separated.
fn names(engines: &[Engine]) -> String {
    engines
        .iter()
        .map(|e| e.name())
        .collect::<Vec<_>>()
        .join(",")
}
