//! `touchdown check`: a vehicle and its landing reviewed before they run (`touchdown-review`).

use crate::args::{Format, Set};
use crate::{load, out, outln, settings};
use anyhow::Result;
use std::fmt::Write;
use std::path::Path;
use touchdown_review::{Concern, Review};

/// `touchdown check`: the review of `scenario` with `set`, as text or its JSON document;
/// whether it found nothing.
pub fn check(scenario: &Path, set: &[Set], format: Format) -> Result<bool> {
    let sc = load(scenario, set)?.1;
    let review = touchdown_review::review(&sc)?;
    match format {
        Format::Text => out!("{}", text(&sc, &review, set))?,
        Format::Json => {
            let id = touchdown_record::ScenarioId::new(scenario.display(), &sc);
            let settings = settings(set, serde_json::json!({}));
            outln!("{}", review.document(&id, &settings))?
        }
    }
    Ok(review.findings.is_empty())
}

/// The findings of the review of `sc` that its loader did not already warn of (those it
/// prints itself), for `run` and the other commands to print as warnings.
pub fn findings(sc: &touchdown_scenario::Scenario) -> Vec<touchdown_review::Finding> {
    touchdown_review::review(sc)
        .map(|r| {
            r.findings
                .into_iter()
                .filter(|f| f.concern != Concern::Value)
                .collect()
        })
        .unwrap_or_default()
}

/// The review as text: the figures, then the findings.
fn text(sc: &touchdown_scenario::Scenario, r: &Review, set: &[Set]) -> String {
    let f = &r.figures;
    let mut o = String::new();
    let _ = writeln!(
        o,
        "touchdown {} — check before landing",
        env!("CARGO_PKG_VERSION")
    );
    let _ = writeln!(o, "scenario: {} ({})", sc.file.name, sc.source);
    for change in set {
        let _ = writeln!(o, "  with --set {change} (the scenario's units)");
    }
    let times = |x: Option<f64>, of: &str| match x {
        Some(x) => format!("{} × {of}", sig(x)),
        None => "—".to_string(),
    };
    let rows = [
        (
            "weight".to_string(),
            format!("{} N", sig(f.weight_n)),
            format!(
                "M·g: {} kg under {} m/s²",
                sig(sc.vehicle.mass),
                sig(sc.vehicle.gravity)
            ),
        ),
        (
            "gear crush load".to_string(),
            format!("{} N", sig(f.gear_crush_load_n)),
            format!(
                "{}: the {} primaries' first crush loads on the vertical; below 1 the gear crushes standing",
                times(f.gear_crush_load_of_weight, "the weight"),
                f.legs
            ),
        ),
        (
            "touchdown energy".to_string(),
            format!("{} J", sig(f.touchdown_energy_j)),
            format!(
                "kinetic {} J + the weight over a primary's vertical stroke {} J",
                sig(f.touchdown_kinetic_energy_j),
                sig(f.stroke_potential_energy_j)
            ),
        ),
        (
            "stroke energy".to_string(),
            format!("{} J", sig(f.stroke_energy_j)),
            format!(
                "{}: every strut crushed to its capacity (a primary {} J, a secondary {} J); below 1 the honeycomb alone cannot take the landing",
                times(f.stroke_energy_of_touchdown, "the touchdown energy"),
                sig(f.primary_stroke_energy_j),
                sig(f.secondary_stroke_energy_j)
            ),
        ),
        (
            "static tip-over angle".to_string(),
            format!("{:.2} deg", f.static_tip_over_angle_rad.to_degrees()),
            format!(
                "footprint inner radius {:.4} m, centre of mass {:.4} m above the footpads",
                f.footprint_inner_radius_m, f.centre_of_mass_height_m
            ),
        ),
        (
            "slope".to_string(),
            format!("{:.2} deg", f.slope_rad.to_degrees()),
            format!(
                "tip-over margin {:.2} deg",
                f.tip_over_margin_rad.to_degrees()
            ),
        ),
        (
            "principal moments".to_string(),
            f.principal_moments_kg_m2
                .map(sig)
                .join(", "),
            "kg·m², smallest first".to_string(),
        ),
    ];
    let _ = writeln!(o);
    for (name, value, note) in rows {
        let _ = writeln!(o, "{name:<22} {value:>22}  {note}");
    }
    if r.findings.is_empty() {
        let _ = writeln!(
            o,
            "\nno findings (a landing may still fail: `touchdown run` lands it)"
        );
    } else {
        let _ = writeln!(o, "\nfindings ({}):", r.findings.len());
        for finding in &r.findings {
            let _ = writeln!(o, "  {finding}");
        }
    }
    o
}

/// `x` with four significant digits, in plain notation (no exponent for the figures of a
/// lander of any size: newtons, joules, kg·m²).
fn sig(x: f64) -> String {
    let digits = if x == 0.0 {
        0
    } else {
        (3 - x.abs().log10().floor() as i32).clamp(0, 9) as usize
    };
    format!("{x:.digits$}")
}
