//! `touchdown compare`: scenarios through several engines, every pair compared.

use crate::args::{CompareArgs, Format};
use crate::{load, out, outln, plots, settings, view, warn};
use anyhow::{Context, Result};

use touchdown_compare::metrics::Verdict;

/// `touchdown compare`: every scenario through every engine asked for, every pair compared;
/// whether no pair failed on any scenario (a pair rounding decides does not fail).
pub fn compare(args: CompareArgs) -> Result<bool> {
    let CompareArgs {
        scenarios,
        set,
        engines,
        format,
        out,
        plot,
        view,
        frame_interval,
        report_only: _,
    } = args;
    let (set, out) = (set.set.as_slice(), out.as_deref());
    let watch = view.as_deref().map(|dir| (dir, frame_interval));
    let engines = touchdown_compare::engine_set(&engines).context("--engines")?;
    let settings = settings(set, serde_json::json!({ "engines": engines }));
    let mut passed = true;
    for path in &scenarios {
        let sc = load(path, set)?.1;
        warn(&sc);
        let interval = watch.map(|(_, f)| f);
        let c = touchdown_compare::compare_recorded(path, &sc, &engines, interval)?;
        passed &= c.pairs.iter().all(|p| p.verdict != Verdict::Fail);
        let document = touchdown_compare::report::json_line(&c, &settings);
        if let Some(dir) = out {
            plots::comparison(&c, &document, path, dir, plot)?;
        }
        if let Some((dir, interval)) = watch {
            let (data, page) = view::write(dir, (path, &sc, set), &c.runs, interval)?;
            eprintln!("wrote {} and {}", page.display(), data.display());
        }
        // One line per scenario as it finishes (JSON Lines).
        match format {
            Format::Text => outln!("{}", touchdown_compare::report::text(&c))?,
            Format::Json => outln!("{document}")?,
        }
    }
    if let Format::Text = format {
        out!(
            "tolerances (the testbench's; a scenario's [comparison] table sets its own)\n{}",
            touchdown_compare::report::tolerances_text()
        )?;
    }
    Ok(passed)
}
