//! A scenario's comparison as text and JSON. The text rounds every number to three significant
//! figures (and anything under 1e-6 in SI to 0, rounding noise such as a symmetric landing's
//! pitch rate), so that it is stable across machines and fit for snapshot review.

use crate::metrics::{Verdict, TOLERANCES};
use crate::{Engine, ScenarioComparison};
use std::fmt::Write;
use touchdown_record::{Document, ScenarioId};
use touchdown_scenario::scales::VelocityScale;

/// Below this magnitude (SI) a number is written as 0.
pub const NOISE: f64 = 1e-6;

/// `x` to three significant figures, `0` below [`NOISE`].
pub fn sig3(x: f64) -> String {
    if !x.is_finite() {
        return "-".into();
    }
    if x.abs() < NOISE {
        return "0".into();
    }
    let rounded: f64 = format!("{x:.2e}").parse().unwrap_or(x);
    let magnitude = rounded.abs().log10().floor() as i32;
    if (-3..6).contains(&magnitude) {
        let decimals = (2 - magnitude).max(0) as usize;
        format!("{rounded:.decimals$}")
    } else {
        format!("{rounded:.2e}")
    }
}

/// The comparison as text: runs, then each pair's channels with pass or fail and the worst.
pub fn text(c: &ScenarioComparison) -> String {
    let mut o = String::new();
    let _ = writeln!(o, "scenario: {} ({})", c.scenario, c.file);
    let _ = writeln!(o, "scenario sha256: {}", c.scenario_sha256);
    let v = &c.scales;
    let _ = writeln!(
        o,
        "vehicle scales: footprint radius ℓ {} m, velocity v {} m/s ({}), time τ {} s",
        sig3(v.length_m),
        sig3(v.velocity_m_s),
        match v.velocity_from {
            VelocityScale::Froude => "√(g·ℓ)",
            VelocityScale::TouchdownSpeed => "the touchdown speed: no gravity",
        },
        sig3(v.time_s)
    );
    for (run, (engine, version)) in c.runs.iter().zip(&c.engines) {
        let s = &run.summary;
        let decision = s
            .decision_time_s
            .map(|t| format!(" at {} s", sig3(t)))
            .unwrap_or_default();
        let _ = writeln!(
            o,
            "{:<7} {:?}{decision} ({version})",
            engine.name(),
            s.outcome
        );
    }
    for engine in &c.not_applicable {
        let _ = writeln!(
            o,
            "{:<7} not run: the scenario does not apply to it (engines.applicable)",
            engine.name()
        );
    }
    if c.pairs.is_empty() {
        let _ = writeln!(o, "\nno pair of engines to compare");
    }
    for p in &c.pairs {
        let _ = writeln!(
            o,
            "\n{} vs {}: {}; outcomes {:?} / {:?}{}; worst: {}",
            p.a.name(),
            p.b.name(),
            p.verdict.label().to_uppercase(),
            p.outcome_a,
            p.outcome_b,
            if p.outcome_determined {
                ""
            } else {
                " (not determined at this precision)"
            },
            p.worst()
        );
        let rows = p.channels.iter().map(|ch| {
            // a count is a whole number, not a measurement to three figures
            let number = |x: f64| {
                if ch.counts() {
                    format!("{x:.0}")
                } else {
                    sig3(x)
                }
            };
            let value = |v: Option<f64>| v.map_or_else(|| "-".to_string(), number);
            vec![
                ch.name(),
                value(ch.a),
                value(ch.b),
                number(ch.absolute_difference),
                ch.unit.to_string(),
                with_unit(ch.difference, ch.difference_unit),
                with_unit(ch.tolerance, ch.difference_unit),
                ch.verdict.label().to_string(),
            ]
        });
        o.push_str(&text_table(
            &[
                "channel",
                p.a.name(),
                p.b.name(),
                "|a - b|",
                "unit",
                "difference",
                "tolerance",
                "",
            ],
            &[1, 2, 3, 5, 6],
            rows,
        ));
        undetermined(&mut o, p);
    }
    o
}

/// The channels of a pair that rounding decides, each with its spread over the ensembles.
fn undetermined(o: &mut String, p: &crate::metrics::PairComparison) {
    let channels: Vec<_> = p
        .channels
        .iter()
        .filter(|c| c.verdict == Verdict::NotDetermined)
        .collect();
    if channels.is_empty() {
        return;
    }
    let _ = writeln!(
        o,
        "not determined at this precision (the touchdown velocity moved by {} unit in the last place across, each way; on a landing that is its own mirror image, each leg against its image):",
        crate::rounding::CROSSWISE_ULPS[0]
    );
    let range = |engine: Engine, r: Option<[f64; 2]>, unit: &str| {
        r.map(|[lo, hi]| format!("{} {}-{} {unit}, ", engine.name(), sig3(lo), sig3(hi)))
            .unwrap_or_default()
    };
    for c in channels {
        let [lo, hi] = c.ensemble_difference;
        let u = c.difference_unit;
        let _ = writeln!(
            o,
            "  {}: {}{}difference {} to {} (tolerance {}); rounding alone moves {} by {}, {} by {}",
            c.name(),
            range(p.a, c.a_range, c.unit),
            range(p.b, c.b_range, c.unit),
            with_unit(lo, u),
            with_unit(hi, u),
            with_unit(c.tolerance, u),
            p.a.name(),
            with_unit(c.rounding_spread[0], u),
            p.b.name(),
            with_unit(c.rounding_spread[1], u),
        );
    }
}

/// What the rounding ensemble says of one engine's landing, as text (`touchdown run
/// --rounding`).
pub fn determinacy_text(d: &crate::rounding::Determinacy) -> String {
    let mut o = String::new();
    let _ = writeln!(
        o,
        "rounding: the landing again with its touchdown velocity moved by {} unit in the last place across, each way (on a landing that is its own mirror image, each leg against its image too)",
        d.crosswise_ulps[0]
    );
    let _ = writeln!(
        o,
        "  outcome: {}",
        if d.outcome_determined {
            "the same on every copy"
        } else {
            "NOT DETERMINED at this precision (the copies differ)"
        }
    );
    if d.undetermined.is_empty() {
        let _ = writeln!(
            o,
            "  every maximum within the tolerance `touchdown compare` judges it by"
        );
        return o;
    }
    let _ = writeln!(
        o,
        "  not determined at this precision (the copies, or a leg's mirror image, move them by more than the tolerance `touchdown compare` judges them by):"
    );
    // every maximum listed has a range (`rounding::undetermined`)
    for (u, [lo, hi]) in d.undetermined.iter().filter_map(|u| Some((u, u.range?))) {
        let _ = writeln!(
            o,
            "    {}: {}-{} {}, moved by {} (tolerance {})",
            u.channel,
            sig3(lo),
            sig3(hi),
            u.unit,
            with_unit(u.spread, u.difference_unit),
            with_unit(u.tolerance, u.difference_unit)
        );
    }
    o
}

/// `x` in `unit` to three significant figures: a fraction of the channel's own value as a
/// percentage, a fraction of one of the vehicle's scales as a percentage of its symbol (ℓ the
/// footprint radius, τ the time scale, v the velocity scale), an SI value with its unit.
pub fn with_unit(x: f64, unit: &str) -> String {
    use crate::metrics::{FOOTPRINT_RADIUS, OWN_VALUE, TIME_SCALE, VELOCITY_SCALE};
    let percent = sig3(100.0 * x);
    match unit {
        OWN_VALUE => format!("{percent} %"),
        FOOTPRINT_RADIUS => format!("{percent} % ℓ"),
        TIME_SCALE => format!("{percent} % τ"),
        VELOCITY_SCALE => format!("{percent} % v"),
        unit => format!("{} {unit}", sig3(x)),
    }
}

/// A plain-text table: a header, then rows, with no borders, each column padded to its widest
/// cell and the columns `right` (indices) right-aligned (numbers). Its layout never depends on
/// the terminal. Every table the commands print is one of these.
pub fn text_table<R>(header: &[&str], right: &[usize], rows: R) -> String
where
    R: IntoIterator<Item = Vec<String>>,
{
    let mut table = comfy_table::Table::new();
    table
        .load_preset(comfy_table::presets::NOTHING)
        .set_content_arrangement(comfy_table::ContentArrangement::Disabled)
        .set_header(header.to_vec());
    for row in rows {
        table.add_row(row);
    }
    for &i in right {
        if let Some(column) = table.column_mut(i) {
            column.set_cell_alignment(comfy_table::CellAlignment::Right);
        }
    }
    let mut out = String::new();
    for line in table.to_string().lines() {
        out.push_str(line.trim_end());
        out.push('\n');
    }
    out
}

/// The tolerances with their reasons, as text.
pub fn tolerances_text() -> String {
    let mut o = String::new();
    for t in &TOLERANCES {
        let _ = writeln!(
            o,
            "{}: {}, {}: {}",
            t.channel,
            with_unit(t.limit, t.difference_unit),
            t.measured_as,
            t.reason
        );
    }
    o
}

/// The comparison as one line of `touchdown compare --format json`'s JSON Lines
/// (docs/schemas/compare.schema.json): the envelope naming the scenario and the `settings`,
/// then the comparison (the engines with their versions, every pair with its channels).
pub fn json_line(c: &ScenarioComparison, settings: &serde_json::Value) -> String {
    let id = ScenarioId {
        path: c.file.clone(),
        sha256: c.scenario_sha256.clone(),
    };
    Document::new("compare", Some(&id), settings, c).line()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn three_significant_figures_and_noise() {
        assert_eq!(sig3(0.075612), "0.0756");
        assert_eq!(sig3(-4.6532), "-4.65");
        assert_eq!(sig3(135.58), "136");
        assert_eq!(sig3(0.0009996), "0.00100");
        assert_eq!(sig3(1.23456e-5), "1.23e-5");
        assert_eq!(sig3(3.0e-12), "0");
        assert_eq!(sig3(f64::NAN), "-");
        assert_eq!(sig3(123456.0), "123000");
        assert_eq!(sig3(1.0e7), "1.00e7");
    }
}
