//! What `touchdown compare --plot DIR` hands to the plotting script (`python/figures/plot_compare.py`):
//! one CSV per engine and scenario with the traces the comparison measured, so that the plots
//! show exactly the series the metrics were computed from (the windowed vertical acceleration
//! of [`Trace::vertical_acceleration`] included), and no series is recomputed in Python.
//!
//! `<stem>.<engine>.csv` columns: `t_s`, `pitch_rate_rad_s`, `leg<n>_primary_stroke_m` per leg,
//! then `vertical_acceleration_m_s2`, the acceleration averaged over the window centred on
//! `t_s` ([`Trace::vertical_acceleration_at`], positive up; `acceleration_window_s` of the
//! comparison's document, 2 ms on the 1/6-scale model), empty within half a window of either
//! end, where the window would leave the trace. `<stem>.json` beside them is the
//! comparison's document (`touchdown compare --format json`), with every channel's verdict.
//! Rows are thinned to one per [`PLOT_INTERVAL`] at most (a multibody's 20 µs steps would give
//! 25,000 rows for a 0.5 s landing drawn 1,000 pixels wide, 0.5 ms a pixel; the rows are
//! committed beside the docs' plots).

use crate::{ScenarioComparison, Trace};
use std::path::{Path, PathBuf};

/// Smallest time between two plotted rows, s.
pub const PLOT_INTERVAL: f64 = 2.0e-4;

/// Writes `<stem>.<engine>.csv` into `dir` for every engine run of `c`; returns the files.
pub fn write_traces(
    c: &ScenarioComparison,
    dir: &Path,
    stem: &str,
) -> Result<Vec<PathBuf>, csv::Error> {
    c.runs
        .iter()
        .map(|run| {
            let path = dir.join(format!("{stem}.{}.csv", run.engine.name()));
            write_trace(&run.trace, &path)?;
            Ok(path)
        })
        .collect()
}

fn write_trace(trace: &Trace, path: &Path) -> Result<(), csv::Error> {
    let mut w = csv::Writer::from_path(path)?;
    let mut header = vec!["t_s".to_string(), "pitch_rate_rad_s".to_string()];
    header.extend((1..=trace.legs).map(|n| format!("leg{n}_primary_stroke_m")));
    header.push("vertical_acceleration_m_s2".into());
    w.write_record(&header)?;
    let mut last = f64::NEG_INFINITY;
    for (i, &t) in trace.t.iter().enumerate() {
        if t - last < PLOT_INTERVAL && i + 1 < trace.t.len() {
            continue;
        }
        last = t;
        let mut row = vec![format!("{t:.7}"), format!("{:.6e}", trace.pitch_rate[i])];
        row.extend(
            trace
                .primary_strokes_at(i)
                .iter()
                .map(|s| format!("{s:.6e}")),
        );
        row.push(
            trace
                .vertical_acceleration_at(t)
                .map_or_else(String::new, |a| format!("{a:.6e}")),
        );
        w.write_record(&row)?;
    }
    w.flush()?;
    Ok(())
}
