//! `touchdown view` and `touchdown compare --view`: a landing's trajectory file and the page that
//! plays it (docs/engines.md, "Watching the engines land"; docs/outputs.md, "The trajectory
//! file").

use crate::args::ViewArgs;
use crate::outln;
use crate::{load, out_file, warn, Set};
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};
use touchdown_compare::EngineRun;
use touchdown_scenario::Scenario;

/// Writes `DIR/<scenario>.trajectory.json` (the trajectory document of the runs of the scenario
/// at `path`, resolved into `sc` with the overrides `set`, which recorded their frames every
/// `frame_interval` s) and `DIR/<scenario>.html` (the page that plays it); returns both paths.
pub fn write(
    dir: &Path,
    (path, sc, set): (&Path, &Scenario, &[Set]),
    runs: &[EngineRun],
    frame_interval: f64,
) -> Result<(PathBuf, PathBuf)> {
    let overrides = set.iter().map(|s| (s.field.as_str(), &s.value));
    let (json, html) =
        touchdown_compare::trajectory_files(path, sc, runs, overrides, frame_interval);
    let data = out_file(dir, "", path, "trajectory.json")?;
    std::fs::write(&data, json).with_context(|| format!("cannot write {}", data.display()))?;
    let page = out_file(dir, "", path, "html")?;
    std::fs::write(&page, html).with_context(|| format!("cannot write {}", page.display()))?;
    Ok((data, page))
}

/// `touchdown view`: the scenario on each of `engines` it applies to, recorded, written as a
/// trajectory file and its page into `dir`.
pub fn view(args: ViewArgs) -> Result<()> {
    let ViewArgs {
        scenario,
        set,
        engines,
        frame_interval,
        out,
    } = args;
    let (scenario, set, engines, dir) = (scenario.as_path(), &set.set, &engines, out.as_path());
    let sc = load(scenario, set)?.1;
    warn(&sc);
    let (runs, skipped) = touchdown_compare::watch(scenario, &sc, engines, frame_interval)?;
    for e in &skipped {
        eprintln!(
            "{e}: not in {}'s engines.applicable, not run",
            scenario.display()
        );
    }
    for r in &runs {
        let frames = r.recording.as_ref().map_or(0, |f| f.frames.t_s.len());
        // The outcome's own time, then how far the landing ran: a landing decided at 0.08 s
        // and run on to its end time is not "stable after" the end time.
        let decided = r
            .summary
            .decision_time_s
            .map_or(String::new(), |t| format!(" (decided at {t:.4} s)"));
        outln!(
            "{}: {}{decided}, run to {:.4} s, {} steps, {} frames",
            r.engine,
            format!("{:?}", r.summary.outcome).to_lowercase(),
            r.summary.t_end_s,
            r.summary.steps,
            frames
        )?;
    }
    let (data, page) = write(dir, (scenario, &sc, set), &runs, frame_interval)?;
    outln!("wrote {}\nwrote {}", data.display(), page.display())?;
    Ok(())
}
