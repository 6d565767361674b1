//! Text and JSON summaries.

use std::fmt::Write;
use touchdown_record::{Outcome, Summary};
use touchdown_scenario::Scenario;

/// The resolved scenario (every default written out), with a provenance header.
pub fn resolved_scenario(sc: &Scenario) -> String {
    format!("# Resolved from {} by touchdown {}: every default written out; units as declared in [units].\n{}", sc.source, env!("CARGO_PKG_VERSION"), sc.to_toml())
}

/// A readable summary: SI, and the scenario's length unit where it is not metres.
pub fn text(sc: &Scenario, s: &Summary, set: &[crate::Set]) -> String {
    let u = sc.file.units;
    let (lu, lname) = (u.length(), u.length_label());
    let len = |m: f64| {
        if lname == "m" {
            format!("{m:9.4} m")
        } else {
            format!("{m:9.4} m  {:9.4} {lname}", m / lu)
        }
    };
    let mut o = String::new();
    let _ = writeln!(
        o,
        "touchdown {} — {} engine",
        env!("CARGO_PKG_VERSION"),
        s.engine
    );
    let _ = writeln!(o, "scenario: {} ({})", s.scenario, sc.source);
    for change in set {
        let _ = writeln!(o, "  with --set {change} (the scenario's units)");
    }
    if !s.mechanisms.is_empty() {
        let list: Vec<String> = s
            .mechanisms
            .iter()
            .map(|(m, n)| format!("{m} ({n} evaluations, one a leg or a footpad)"))
            .collect();
        let _ = writeln!(o, "mechanisms: {}", list.join(", "));
    }
    let bottomed = match s.past_capacity.len() {
        0 => String::new(),
        1 => " WITH 1 STRUT PAST ITS CAPACITY".to_string(),
        n => format!(" WITH {n} STRUTS PAST THEIR CAPACITY"),
    };
    let outcome = match (s.outcome, s.decision_time_s) {
        (Outcome::Stable, Some(t)) => format!(
            "STABLE{bottomed} (the stable conditions held at t = {t:.4} s; {})",
            match s.settled_time_s {
                Some(e) => format!("proved settled at t = {e:.4} s, where the run ended: no maximum stroke could grow, nor the least stability distance fall, by more than stability.settled_tolerance, and no peak or outcome could change (docs/errata.md, \"Settled landings: an early end with a proof\")"),
                None => "maxima over the whole run".to_string(),
            }
        ),
        (Outcome::Unstable, Some(t)) => format!(
            "UNSTABLE{bottomed} (centre of mass crossed a stability wall at t = {t:.4} s, overturning velocity {:.3} m/s{}; maxima up to the crossing)",
            s.overturn_velocity_m_s.unwrap_or(f64::NAN),
            match s.stable_conditions_time_s {
                Some(c) => format!(", after the stable conditions held at t = {c:.4} s"),
                None => String::new(),
            }
        ),
        _ => format!(
            "UNDECIDED{bottomed} (no stability decision before the end time, {:.4} s: the four stable conditions of docs/errata.md, \"Eqs. (105)-(107)\", never held together and no wall was crossed; with {:.4} J of kinetic energy left, a longer run may decide it: --set integrator.t_end={} (in the file's time unit))",
            s.t_end_s,
            s.energy.kinetic_j,
            2.0 * s.t_end_s / u.time()
        ),
    };
    let _ = writeln!(o, "outcome:  {outcome}");
    let _ = writeln!(
        o,
        "run:      {:.4} s simulated, {} steps, {} force evaluations",
        s.t_end_s, s.steps, s.force_evaluations
    );
    strokes(&mut o, s, 1.0, "m");
    if lname != "m" {
        strokes(&mut o, s, lu, lname);
    }
    stroke_times(&mut o, s);
    past_capacity(&mut o, s);
    let _ = writeln!(
        o,
        "\npeak pitch rate:            {:+.4} rad/s at t = {:.4} s",
        s.peak_pitch_rate_rad_s, s.peak_pitch_rate_time_s
    );
    let _ = writeln!(
        o,
        "  in each sense:            {:+.4} rad/s at t = {:.4} s, {:+.4} rad/s at t = {:.4} s",
        s.min_pitch_rate_rad_s,
        s.min_pitch_rate_time_s,
        s.max_pitch_rate_rad_s,
        s.max_pitch_rate_time_s
    );
    let _ = writeln!(
        o,
        "minimum stability distance: {} at t = {:.4} s{}",
        len(s.min_stability_distance_m),
        s.min_stability_distance_time_s,
        if s.min_stability_distance_time_s == 0.0 {
            " (touchdown: the vehicle never came closer to a wall)"
        } else {
            ""
        }
    );
    let e = &s.energy;
    // The balance of the record's EnergyLedger::report: the initial kinetic energy plus the
    // residual is the sum of the lines marked +.
    let _ = writeln!(
        o,
        "\nenergy since touchdown, J: initial kinetic energy + residual = the sum of the lines marked +"
    );
    let line = |o: &mut String, sign: &str, name: &str, v: f64, note: &str| {
        let text = format!("  {sign} {name:<30}{v:12.4}  {note}");
        let _ = writeln!(o, "{}", text.trim_end());
    };
    line(
        &mut o,
        " ",
        "initial kinetic energy",
        e.kinetic_initial_j,
        "the vehicle's, at first contact",
    );
    let terms = [
        ("+", "kinetic energy now", e.kinetic_j, ""),
        (
            "+",
            "potential energy change",
            e.potential_change_j,
            "negative: released by the descent",
        ),
        (
            "+",
            "gear masses",
            e.footpad_j,
            "footpads in contact (core), all (core, inertial), gear links (multibody)",
        ),
        (
            "+",
            "honeycomb stored (elastic)",
            e.honeycomb_stored_j,
            "recoverable",
        ),
        ("+", "honeycomb dissipated", e.honeycomb_dissipated_j, ""),
        ("+", "viscous", e.viscous_j, ""),
        ("+", "bearing friction", e.bearing_friction_j, ""),
        ("+", "sliding friction", e.sliding_friction_j, ""),
        (
            "+",
            "mechanisms (soil, curbs, ...)",
            e.mechanisms_j,
            "work done on them; thrust and RCS count negative",
        ),
        (
            "+",
            "absorbed by footpad impacts",
            -e.contact_events_j,
            "by contact; negative: given to the footpads",
        ),
    ];
    for (sign, name, v, note) in terms {
        line(&mut o, sign, name, v, note);
    }
    let scale = e.scale();
    let rel = if scale > 0.0 {
        format!(
            "{:+.3} % of the energy put in",
            100.0 * e.residual_j / scale
        )
    } else {
        "no energy put in".to_string()
    };
    line(
        &mut o,
        " ",
        "balance residual",
        e.residual_j,
        &format!("integration error: {rel}"),
    );
    line(
        &mut o,
        " ",
        "energy put in",
        scale,
        "touchdown kinetic, potential released, thrust and RCS input (the residual's scale)",
    );
    o
}

/// The struts past their capacity, or that every strut stayed within it.
fn past_capacity(o: &mut String, s: &Summary) {
    if s.past_capacity.is_empty() {
        let _ = writeln!(o, "\nevery strut stayed within its capacity");
        return;
    }
    let _ = writeln!(
        o,
        "\nstruts past their capacity, onto their end stops (the stop's law is an estimate: docs/errata.md, \"End stops\")"
    );
    let rows = s.past_capacity.iter().map(|p| {
        vec![
            p.strut.clone(),
            format!("{:.4}", p.max_stroke_m),
            format!("{:.4}", p.capacity_m),
            format!("{:.1}", 1e3 * p.past_capacity_m),
            format!("{:.1}", 100.0 * p.stroke_of_capacity),
            format!("{:.0}", p.peak_stop_force_n),
        ]
    });
    o.push_str(&touchdown_compare::report::text_table(
        &[
            "strut",
            "max stroke m",
            "capacity m",
            "past mm",
            "% of capacity",
            "peak stop force N",
        ],
        &[1, 2, 3, 4, 5],
        rows,
    ));
}

/// The table of the times each maximum stroke was first reached, s ("—" where the strut never
/// stroked that way).
fn stroke_times(o: &mut String, s: &Summary) {
    let _ = writeln!(
        o,
        "\ntime of each maximum stroke, s (a touchdown peak or a late rock)"
    );
    let rows = (0..s.max_primary_stroke_time_s.len()).map(|i| {
        let (ct, tt) = (
            s.max_secondary_compression_time_s[i],
            s.max_secondary_tension_time_s[i],
        );
        // A maximum never reached past the time resolution keeps the run's start: "—".
        let at = |time: f64| {
            if time > 0.0 {
                format!("{time:.4}")
            } else {
                "—".to_string()
            }
        };
        vec![
            (i + 1).to_string(),
            at(s.max_primary_stroke_time_s[i]),
            at(ct[0]),
            at(tt[0]),
            at(ct[1]),
            at(tt[1]),
        ]
    });
    o.push_str(&touchdown_compare::report::text_table(
        &[
            "leg",
            "primary",
            "3-1 compr",
            "3-1 tension",
            "4-1 compr",
            "4-1 tension",
        ],
        &[0, 1, 2, 3, 4, 5],
        rows,
    ));
}

/// The table of maximum strokes per leg, in `unit` (`scale` metres each).
fn strokes(o: &mut String, s: &Summary, scale: f64, unit: &str) {
    let _ = writeln!(
        o,
        "\nmaximum strokes, {unit} (compression and tension positive)"
    );
    let rows = s.max_primary_stroke_m.iter().enumerate().map(|(i, p)| {
        let contact = match s.first_contact_s.get(i).copied().flatten() {
            Some(t) => format!("{t:.4} s"),
            None => "never".to_string(),
        };
        let (c, t) = (
            s.max_secondary_compression_m[i],
            s.max_secondary_tension_m[i],
        );
        let mut row = vec![(i + 1).to_string(), contact];
        row.extend([p, &c[0], &t[0], &c[1], &t[1]].map(|x| format!("{:.4}", x / scale)));
        row
    });
    o.push_str(&touchdown_compare::report::text_table(
        &[
            "leg",
            "first contact",
            "primary",
            "3-1 compr",
            "3-1 tension",
            "4-1 compr",
            "4-1 tension",
        ],
        &[0, 1, 2, 3, 4, 5, 6],
        rows,
    ));
}
