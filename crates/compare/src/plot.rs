//! What `touchdown compare --plot DIR` hands to the plotting script (`python/plot_compare.py`):
//! one CSV per engine and scenario with the traces the comparison measured, so that the plots
//! show exactly the series the metrics were computed from (the 2 ms vertical acceleration of
//! [`Trace::vertical_acceleration`] included), and no series is recomputed in Python.
//!
//! `<stem>.<engine>.csv` columns: `t_s`, `pitch_rate_rad_s`, `leg<n>_primary_stroke_m` per leg,
//! then `acceleration_t_s` and `vertical_acceleration_m_s2` (the window's middle and the
//! windowed acceleration, positive up), empty in the last rows, whose window would end after the
//! trace. Rows are thinned to one per [`PLOT_INTERVAL`] at most (a multibody's 20 µs steps would
//! give 15,000 rows a landing for a plot 1,000 pixels wide).

use crate::{ScenarioComparison, Trace};
use std::path::{Path, PathBuf};

/// Smallest time between two plotted rows, s.
pub const PLOT_INTERVAL: f64 = 5.0e-5;

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
    header.extend([
        "acceleration_t_s".into(),
        "vertical_acceleration_m_s2".into(),
    ]);
    w.write_record(&header)?;
    let mut acceleration = trace.vertical_acceleration();
    let mut last = f64::NEG_INFINITY;
    for (i, &t) in trace.t.iter().enumerate() {
        let a = acceleration.next();
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
        match a {
            Some((ta, a)) => row.extend([format!("{ta:.7}"), format!("{a:.6e}")]),
            None => row.extend([String::new(), String::new()]),
        }
        w.write_record(&row)?;
    }
    w.flush()?;
    Ok(())
}
