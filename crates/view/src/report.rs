//! One page per landing (`touchdown run --out DIR --report`): a self-contained HTML page a
//! reviewer reads at a glance, with no script and no network: the outcome and why, each strut's
//! maximum stroke against its capacity with the time it came, the energy ledger as bars, and
//! the time histories that matter (strokes, pitch rate, stability distance, kinetic energy),
//! drawn as inline SVG from the landing's `history.csv` (the same columns on every engine).

use crate::page::escape_html as escape;
use std::fmt::Write;
use std::path::Path;
use touchdown_record::history::HistoryReadError;
use touchdown_record::{Outcome, Summary};

/// The time histories a page draws, SI, one value per history row.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Series {
    /// Time, s.
    pub t: Vec<f64>,
    /// Primary stroke per leg, m.
    pub primary: Vec<Vec<f64>>,
    /// Secondary strokes per leg (3-1, 4-1), m, tension positive.
    pub secondary: Vec<[Vec<f64>; 2]>,
    /// Pitch rate, rad/s.
    pub pitch_rate: Vec<f64>,
    /// The least stability distance over the walls, m (NaN where none is defined).
    pub stability_distance: Vec<f64>,
    /// The vehicle's kinetic energy, J.
    pub kinetic: Vec<f64>,
}

impl Series {
    /// The series of the `history.csv` at `path`.
    pub fn read(path: &Path) -> Result<Series, HistoryReadError> {
        let mut s = Series::default();
        touchdown_record::history::read(path, |row| {
            if s.primary.is_empty() {
                s.primary = vec![Vec::new(); row.legs.len()];
                s.secondary = vec![[Vec::new(), Vec::new()]; row.legs.len()];
            }
            s.t.push(row.t);
            for (i, leg) in row.legs.iter().enumerate() {
                s.primary[i].push(leg.primary_stroke);
                s.secondary[i][0].push(leg.secondary_stroke[0]);
                s.secondary[i][1].push(leg.secondary_stroke[1]);
            }
            s.pitch_rate.push(row.pitch_rate);
            let least = row
                .stability_distance
                .iter()
                .copied()
                .filter(|d| d.is_finite())
                .fold(f64::INFINITY, f64::min);
            s.stability_distance
                .push(if least.is_finite() { least } else { f64::NAN });
            s.kinetic.push(row.energy.kinetic_j);
        })?;
        Ok(s)
    }
}

/// The colours of legs 1, 2, 3, ... (repeated past eight).
const LEG_COLOURS: [&str; 8] = [
    "#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf",
];

/// Points kept a line at most: a page of a few hundred kilobytes however fine the history.
const MAX_POINTS: usize = 1500;

/// The page of the landing `summary` of the scenario `name` (from the file `source`), with its
/// time histories `series`.
pub fn landing_page(name: &str, source: &str, summary: &Summary, series: &Series) -> String {
    let mut o = String::new();
    let title = format!("{name} — {} engine", summary.engine);
    let _ = write!(
        o,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>{}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n<h1>{}</h1>\n<p class=\"source\">{} · touchdown {}</p>\n",
        escape(&title),
        escape(&title),
        escape(source),
        touchdown_record::document::TOUCHDOWN_VERSION
    );
    outcome(&mut o, summary);
    strokes(&mut o, summary);
    energy(&mut o, summary);
    histories(&mut o, summary, series);
    o.push_str("</body>\n</html>\n");
    o
}

const STYLE: &str = "body{font-family:system-ui,sans-serif;max-width:980px;margin:1.5em auto;padding:0 1em;color:#222}h1{font-size:1.4em;margin-bottom:.2em}h2{font-size:1.1em;margin-top:1.6em;border-bottom:1px solid #ccc}.source{color:#666;margin-top:0}.verdict{font-size:1.15em;padding:.6em .8em;border-radius:4px}.stable{background:#e6f4ea}.unstable{background:#fce8e6}.undecided{background:#fef7e0}table{border-collapse:collapse;font-size:.9em}td,th{padding:.15em .6em;text-align:right}th{border-bottom:1px solid #999}td.l,th.l{text-align:left}figure svg{display:block;margin:.4em 0}td svg{display:inline-block;vertical-align:middle}figure{margin:.8em 0}";

/// The outcome and why.
fn outcome(o: &mut String, s: &Summary) {
    let past = match s.past_capacity.len() {
        0 => String::new(),
        1 => ", with 1 strut past its capacity".into(),
        n => format!(", with {n} struts past their capacity"),
    };
    let (class, text) = match (s.outcome, s.decision_time_s) {
        (Outcome::Stable, Some(t)) => (
            if past.is_empty() { "stable" } else { "undecided" },
            format!(
                "<b>Stable{past}</b>: the four stable conditions of eqs. (105)-(107) held together at t = {t:.4} s (kinetic energy low, centre of mass inside its stability walls, the two footpads of the nearest wall on the ground, the centre of mass moving away from that wall); the run went on to {:.4} s so that no maximum is cut short.",
                s.t_end_s
            ),
        ),
        (Outcome::Unstable, Some(t)) => (
            "unstable",
            format!(
                "<b>Unstable{past}</b>: the centre of mass crossed a stability wall (eq. 105) at t = {t:.4} s at {:.3} m/s; the maxima are those up to the crossing.",
                s.overturn_velocity_m_s.unwrap_or_default()
            ),
        ),
        _ => (
            "undecided",
            format!(
                "<b>Undecided{past}</b>: no stability decision by the end time, {:.4} s, with {:.4} J of kinetic energy left: a longer run (integrator.t_end) may decide it.",
                s.t_end_s, s.energy.kinetic_j
            ),
        ),
    };
    let _ = writeln!(o, "<p class=\"verdict {class}\">{text}</p>");
    if !s.past_capacity.is_empty() {
        let names: Vec<String> = s
            .past_capacity
            .iter()
            .map(|p| {
                format!(
                    "{} ({:.1} mm past, stop force {:.0} N)",
                    p.strut,
                    1e3 * p.past_capacity_m,
                    p.peak_stop_force_n
                )
            })
            .collect();
        let _ = writeln!(
            o,
            "<p class=\"verdict unstable\"><b>Past capacity</b>, onto the end stops (an estimated law, docs/errata.md, \"End stops\"): {}.</p>",
            escape(&names.join(", "))
        );
    }
    let _ = writeln!(
        o,
        "<p>Peak pitch rate {:+.4} rad/s at {:.4} s (either way {:+.4} rad/s at {:.4} s and {:+.4} rad/s at {:.4} s); minimum stability distance {:.4} m at {:.4} s; peak specific force {:.2} m/s²; {} steps.</p>",
        s.peak_pitch_rate_rad_s,
        s.peak_pitch_rate_time_s,
        s.min_pitch_rate_rad_s,
        s.min_pitch_rate_time_s,
        s.max_pitch_rate_rad_s,
        s.max_pitch_rate_time_s,
        s.min_stability_distance_m,
        s.min_stability_distance_time_s,
        s.peak_specific_force_m_s2,
        s.steps
    );
}

/// Each strut's maximum stroke against its capacity, with the time it came.
fn strokes(o: &mut String, s: &Summary) {
    o.push_str("<h2>Strokes against capacity</h2>\n<table>\n<tr><th class=\"l\">strut</th><th>max stroke, m</th><th>at, s</th><th>capacity, m</th><th class=\"l\">of capacity</th></tr>\n");
    let caps = &s.strut_capacity;
    for leg in 0..s.max_primary_stroke_m.len() {
        let mut rows = vec![(
            format!("leg {} primary", leg + 1),
            s.max_primary_stroke_m[leg],
            s.max_primary_stroke_time_s[leg],
            caps.primary.stroke_m,
        )];
        for (j, name) in ["3-1", "4-1"].iter().enumerate() {
            rows.push((
                format!("leg {} {name} compression", leg + 1),
                s.max_secondary_compression_m[leg][j],
                s.max_secondary_compression_time_s[leg][j],
                caps.secondary_compression.stroke_m,
            ));
            rows.push((
                format!("leg {} {name} tension", leg + 1),
                s.max_secondary_tension_m[leg][j],
                s.max_secondary_tension_time_s[leg][j],
                caps.secondary_tension.stroke_m,
            ));
        }
        for (name, stroke, time, capacity) in rows {
            let fraction = if capacity > 0.0 {
                stroke / capacity
            } else {
                0.0
            };
            let at = if time > 0.0 {
                format!("{time:.4}")
            } else {
                "—".into()
            };
            let _ = writeln!(
                o,
                "<tr><td class=\"l\">{name}</td><td>{stroke:.4}</td><td>{at}</td><td>{capacity:.4}</td><td class=\"l\">{}</td></tr>",
                bar(fraction)
            );
        }
    }
    o.push_str("</table>\n");
}

/// A bar of `fraction` of capacity (the line at 100 %), red past it.
fn bar(fraction: f64) -> String {
    let (w, full) = (240.0, 200.0);
    let len = (fraction.max(0.0) * full).min(w);
    let colour = if fraction > 1.0 { "#d62728" } else { "#1f77b4" };
    format!(
        "<svg width=\"{w}\" height=\"12\" role=\"img\" aria-label=\"{p:.1} % of capacity\"><rect width=\"{len:.1}\" height=\"12\" fill=\"{colour}\"/><line x1=\"{full}\" x2=\"{full}\" y1=\"0\" y2=\"12\" stroke=\"#222\"/><title>{p:.1} % of capacity</title></svg> {p:.1} %",
        p = 100.0 * fraction
    )
}

/// The energy ledger as signed bars against the energy put in.
fn energy(o: &mut String, s: &Summary) {
    let e = &s.energy;
    let scale = e.scale();
    let _ = writeln!(
        o,
        "<h2>Energy since touchdown</h2>\n<p>The initial kinetic energy ({:.4} J) plus the potential energy released and any thrust go into the accounts below; the residual is the integration error ({:+.4} J, {:+.3} % of the {:.4} J put in).</p>\n<table>",
        e.kinetic_initial_j,
        e.residual_j,
        if scale > 0.0 {
            100.0 * e.residual_j / scale
        } else {
            0.0
        },
        scale
    );
    let lines = [
        ("kinetic energy now", e.kinetic_j),
        ("potential energy change", e.potential_change_j),
        ("gear masses", e.footpad_j),
        ("honeycomb stored (elastic)", e.honeycomb_stored_j),
        ("honeycomb dissipated", e.honeycomb_dissipated_j),
        ("viscous", e.viscous_j),
        ("bearing friction", e.bearing_friction_j),
        ("sliding friction", e.sliding_friction_j),
        ("mechanisms", e.mechanisms_j),
        ("absorbed by footpad impacts", -e.contact_events_j),
        ("residual", e.residual_j),
    ];
    for (name, value) in lines {
        let (w, mid) = (360.0, 180.0);
        let len = if scale > 0.0 {
            (value / scale * mid).clamp(-mid, mid)
        } else {
            0.0
        };
        let (x, colour) = if len < 0.0 {
            (mid + len, "#ff7f0e")
        } else {
            (mid, "#2ca02c")
        };
        let _ = writeln!(
            o,
            "<tr><td class=\"l\">{name}</td><td>{value:.4} J</td><td class=\"l\"><svg width=\"{w}\" height=\"12\" role=\"img\" aria-label=\"{value:.4} J\"><rect x=\"{x:.1}\" width=\"{:.1}\" height=\"12\" fill=\"{colour}\"/><line x1=\"{mid}\" x2=\"{mid}\" y1=\"0\" y2=\"12\" stroke=\"#222\"/></svg></td></tr>",
            len.abs()
        );
    }
    o.push_str("</table>\n");
}

/// The time histories.
fn histories(o: &mut String, s: &Summary, series: &Series) {
    o.push_str("<h2>Time histories</h2>\n");
    if series.t.is_empty() {
        o.push_str("<p>No history rows.</p>\n");
        return;
    }
    let leg_lines = |columns: Vec<&Vec<f64>>| -> Vec<Line> {
        columns
            .into_iter()
            .enumerate()
            .map(|(i, values)| Line {
                label: format!("leg {}", i + 1),
                values: values.clone(),
                colour: LEG_COLOURS[i % LEG_COLOURS.len()],
            })
            .collect()
    };
    let marks = decision_marks(s);
    chart(
        o,
        "Primary strokes, m (compression positive; the dashed line is the capacity)",
        &series.t,
        &leg_lines(series.primary.iter().collect()),
        &[s.strut_capacity.primary.stroke_m],
        &marks,
    );
    for (j, name) in ["3-1", "4-1"].iter().enumerate() {
        chart(
            o,
            &format!("Secondary {name} strokes, m (tension positive)"),
            &series.t,
            &leg_lines(series.secondary.iter().map(|s| &s[j]).collect()),
            &[
                s.strut_capacity.secondary_tension.stroke_m,
                -s.strut_capacity.secondary_compression.stroke_m,
            ],
            &marks,
        );
    }
    let single = |label: &str, values: &[f64]| {
        vec![Line {
            label: label.into(),
            values: values.to_vec(),
            colour: "#222",
        }]
    };
    chart(
        o,
        "Pitch rate, rad/s (about the inertial X axis)",
        &series.t,
        &single("pitch rate", &series.pitch_rate),
        &[],
        &marks,
    );
    chart(
        o,
        "Least stability distance, m (the centre of mass inside its walls above 0)",
        &series.t,
        &single("stability distance", &series.stability_distance),
        &[0.0],
        &marks,
    );
    chart(
        o,
        "Kinetic energy of the vehicle, J",
        &series.t,
        &single("kinetic energy", &series.kinetic),
        &[],
        &marks,
    );
}

/// The decision times drawn on every chart: (time, label).
fn decision_marks(s: &Summary) -> Vec<(f64, &'static str)> {
    let mut marks = Vec::new();
    if let Some(t) = s.stable_conditions_time_s {
        marks.push((t, "stable conditions"));
    }
    if let Some(t) = s.settled_time_s {
        marks.push((t, "proved settled"));
    }
    if s.outcome == Outcome::Unstable {
        if let Some(t) = s.decision_time_s {
            marks.push((t, "wall crossed"));
        }
    }
    marks
}

/// One line of a chart.
struct Line {
    label: String,
    values: Vec<f64>,
    colour: &'static str,
}

/// A line chart of `lines` over `t`, with dashed horizontal `levels` and vertical `marks`.
fn chart(
    o: &mut String,
    title: &str,
    t: &[f64],
    lines: &[Line],
    levels: &[f64],
    marks: &[(f64, &str)],
) {
    let (w, h, left, right, top, bottom) = (900.0, 220.0, 64.0, 12.0, 10.0, 28.0);
    let (t0, t1) = (t[0], t[t.len() - 1].max(t[0] + 1e-12));
    let finite = lines
        .iter()
        .flat_map(|l| l.values.iter().copied())
        .chain(levels.iter().copied())
        .filter(|v| v.is_finite());
    let (mut lo, mut hi) = finite.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
        (a.min(v), b.max(v))
    });
    if !lo.is_finite() {
        (lo, hi) = (0.0, 1.0);
    }
    if hi - lo < 1e-12 * lo.abs().max(1e-12) {
        (lo, hi) = (lo - 0.5 * lo.abs().max(1e-9), hi + 0.5 * hi.abs().max(1e-9));
    }
    let pad = 0.05 * (hi - lo);
    let (lo, hi) = (lo - pad, hi + pad);
    let x = |v: f64| left + (v - t0) / (t1 - t0) * (w - left - right);
    let y = |v: f64| top + (hi - v) / (hi - lo) * (h - top - bottom);
    let _ = writeln!(
        o,
        "<figure><figcaption>{}</figcaption><svg width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\" role=\"img\" aria-label=\"{}\" font-size=\"11\">",
        escape(title),
        escape(title)
    );
    let _ = writeln!(
        o,
        "<rect x=\"{left}\" y=\"{top}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#999\"/>",
        w - left - right,
        h - top - bottom
    );
    for v in ticks(lo, hi) {
        let _ = writeln!(
            o,
            "<line x1=\"{left}\" x2=\"{:.1}\" y1=\"{yy:.1}\" y2=\"{yy:.1}\" stroke=\"#eee\"/><text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"end\">{}</text>",
            w - right,
            left - 4.0,
            y(v) + 4.0,
            tick_label(v),
            yy = y(v)
        );
    }
    for v in ticks(t0, t1) {
        let _ = writeln!(
            o,
            "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{}</text>",
            x(v),
            h - bottom + 14.0,
            tick_label(v)
        );
    }
    let _ = writeln!(
        o,
        "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"end\">t, s</text>",
        w - right,
        h - 2.0
    );
    for level in levels {
        let _ = writeln!(
            o,
            "<line x1=\"{left}\" x2=\"{:.1}\" y1=\"{yy:.1}\" y2=\"{yy:.1}\" stroke=\"#555\" stroke-dasharray=\"6 4\"/>",
            w - right,
            yy = y(*level)
        );
    }
    for (t, label) in marks {
        let _ = writeln!(
            o,
            "<line x1=\"{xx:.1}\" x2=\"{xx:.1}\" y1=\"{top}\" y2=\"{:.1}\" stroke=\"#888\" stroke-dasharray=\"2 3\"/><text x=\"{:.1}\" y=\"{:.1}\" fill=\"#555\">{label}</text>",
            h - bottom,
            x(*t) + 3.0,
            top + 11.0,
            xx = x(*t)
        );
    }
    let every = t.len().div_ceil(MAX_POINTS).max(1);
    for (k, line) in lines.iter().enumerate() {
        // Each run of defined values one polyline (a NaN breaks the line).
        let mut runs: Vec<String> = vec![String::new()];
        for (i, (tv, v)) in t.iter().zip(&line.values).enumerate() {
            if i % every != 0 && i + 1 != t.len() {
                continue;
            }
            if v.is_finite() {
                let run = runs.last_mut().expect("one run at least");
                let _ = write!(run, "{:.1},{:.1} ", x(*tv), y(*v));
            } else if !runs.last().expect("one run at least").is_empty() {
                runs.push(String::new());
            }
        }
        for points in runs.iter().filter(|r| !r.is_empty()) {
            let _ = writeln!(
                o,
                "<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"1.4\" points=\"{}\"/>",
                line.colour,
                points.trim_end()
            );
        }
        if lines.len() > 1 {
            let _ = writeln!(
                o,
                "<text x=\"{:.1}\" y=\"{:.1}\" fill=\"{}\">{}</text>",
                left + 8.0 + 60.0 * k as f64,
                h - bottom - 6.0,
                line.colour,
                escape(&line.label)
            );
        }
    }
    o.push_str("</svg></figure>\n");
}

/// Round tick values across [lo, hi]: 1, 2 or 5 times a power of ten apart, four to eight.
fn ticks(lo: f64, hi: f64) -> Vec<f64> {
    let span = hi - lo;
    if !(span > 0.0 && span.is_finite()) {
        return vec![lo];
    }
    let raw = span / 5.0;
    let p = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * p)
        .find(|s| span / s <= 8.0)
        .unwrap_or(10.0 * p);
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last).map(|k| k as f64 * step).collect()
}

/// A tick's label: as few digits as tell it apart.
fn tick_label(v: f64) -> String {
    let v = if v.abs() < 1e-12 { 0.0 } else { v };
    let text = format!("{v:.6}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    text.to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_round_and_inside_their_range() {
        let labels: Vec<String> = ticks(0.0, 1.0).into_iter().map(tick_label).collect();
        assert_eq!(labels, ["0", "0.2", "0.4", "0.6", "0.8", "1"]);
        let t = ticks(-0.013, 0.087);
        assert!(t.len() >= 4 && t.len() <= 8, "{t:?}");
        assert!(t.iter().all(|v| (-0.013..=0.087).contains(v)));
        assert_eq!(tick_label(0.30000000000000004), "0.3");
        assert_eq!(tick_label(-1e-17), "0");
    }

    #[test]
    fn a_bar_past_capacity_is_red_and_says_how_far() {
        assert!(bar(1.2).contains("#d62728") && bar(1.2).contains("120.0 %"));
        assert!(bar(0.5).contains("#1f77b4") && bar(0.5).contains("width=\"100.0\""));
    }
}
