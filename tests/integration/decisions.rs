//! A stability decision never cuts a measurement (docs/errata.md, "Stability decisions and
//! maxima"): a stable landing runs to its end time, and an unstable one is measured up to its
//! crossing, so that the summary of every bundled landing is the same whether or not the run
//! ends at the decision, on every engine.

use touchdown_record::{Outcome, Summary};
use touchdown_scenario::schema::Engine;
use touchdown_scenario::Scenario;
use touchdown_tests::{mujoco, scenario, variant};

/// Relative agreement required of every maximum.
const TOLERANCE: f64 = 1e-9;

/// The rapier rebuild's runs end here at the latest (s): its 20 µs steps make a 1.5 s landing
/// cost 6 s, and the rule under test is the shared tracker's, not the engine's. Every bundled
/// landing's decision falls before it.
const RAPIER_T_END_S: f64 = 0.4;

/// Every bundled landing (scenarios/*.toml), loaded, with its file name.
fn landings() -> Vec<(String, Scenario)> {
    let mut out: Vec<(String, Scenario)> = std::fs::read_dir(scenario(""))
        .expect("scenarios/ is readable")
        .filter_map(|e| {
            let path = e.ok()?.path();
            (path.extension()? == "toml").then_some(path)
        })
        .map(|path| {
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            let sc = Scenario::load(&path).unwrap_or_else(|e| panic!("{e}"));
            (name, sc)
        })
        .collect();
    out.sort_by(|a, b| a.0.cmp(&b.0));
    assert!(out.len() >= 20, "{} bundled landings", out.len());
    out
}

/// Every maximum of a summary, named.
fn maxima(s: &Summary) -> Vec<(String, f64)> {
    let mut out = vec![
        (
            "peak specific force".to_string(),
            s.peak_specific_force_m_s2,
        ),
        ("peak pitch rate".to_string(), s.peak_pitch_rate_rad_s),
        ("smallest pitch rate".to_string(), s.min_pitch_rate_rad_s),
        ("largest pitch rate".to_string(), s.max_pitch_rate_rad_s),
        (
            "minimum stability distance".to_string(),
            s.min_stability_distance_m,
        ),
    ];
    for i in 0..s.max_primary_stroke_m.len() {
        let leg = i + 1;
        out.push((
            format!("leg {leg} primary stroke"),
            s.max_primary_stroke_m[i],
        ));
        out.push((
            format!("leg {leg} primary force"),
            s.peak_primary_force_n[i],
        ));
        for (j, side) in ["3-1", "4-1"].iter().enumerate() {
            let each = [
                ("compression stroke", s.max_secondary_compression_m[i][j]),
                ("tension stroke", s.max_secondary_tension_m[i][j]),
                (
                    "compression force",
                    s.peak_secondary_compression_force_n[i][j],
                ),
                ("tension force", s.peak_secondary_tension_force_n[i][j]),
            ];
            for (what, v) in each {
                out.push((format!("leg {leg} secondary {side} {what}"), v));
            }
        }
    }
    out
}

/// The two summaries agree on the outcome, its time and every maximum; a stable landing ran to
/// its end time both ways.
fn same_maxima(what: &str, ended: &Summary, went_on: &Summary, t_end: f64) {
    assert_eq!(ended.outcome, went_on.outcome, "{what}: outcome");
    assert_eq!(ended.decision_time_s, went_on.decision_time_s, "{what}");
    if ended.outcome == Outcome::Stable {
        assert!(
            ended.t_end_s >= t_end * (1.0 - 1e-12),
            "{what}: a stable landing ended at {} s, before its end time {t_end} s",
            ended.t_end_s
        );
    }
    for ((name, a), (_, b)) in maxima(ended).iter().zip(maxima(went_on)) {
        assert!(
            (a - b).abs() <= TOLERANCE * a.abs().max(b.abs()),
            "{what}: {name} is {a} ending at the decision and {b} going on"
        );
    }
}

#[test]
fn no_decision_cuts_a_maximum_on_the_core() {
    let mut unstable = 0;
    for (name, sc) in landings() {
        let mut on = sc.clone();
        on.stability.terminate_on_decision = false;
        let ended = touchdown_core::run(&sc).unwrap_or_else(|e| panic!("{name}: {e}"));
        let went_on = touchdown_core::run(&on).unwrap_or_else(|e| panic!("{name}: {e}"));
        same_maxima(&name, &ended, &went_on, sc.integrator.t_end);
        if ended.outcome == Outcome::Unstable {
            unstable += 1;
            assert!(went_on.t_end_s > ended.t_end_s, "{name}: the run went on");
        }
    }
    assert!(unstable >= 1, "an unstable landing is among them");
}

#[test]
fn no_decision_cuts_a_maximum_on_the_rapier_rebuild() {
    for (name, mut sc) in landings() {
        if !sc.applicable_engines.contains(&Engine::Rapier) {
            continue;
        }
        sc.integrator.t_end = sc.integrator.t_end.min(RAPIER_T_END_S);
        let mut on = sc.clone();
        on.stability.terminate_on_decision = false;
        let ended = touchdown_rapier::run(&sc).unwrap_or_else(|e| panic!("{name}: {e}"));
        let went_on = touchdown_rapier::run(&on).unwrap_or_else(|e| panic!("{name}: {e}"));
        same_maxima(&name, &ended, &went_on, sc.integrator.t_end);
    }
}

#[test]
fn no_decision_cuts_a_maximum_on_mujoco() {
    for (name, sc) in landings() {
        if !sc.applicable_engines.contains(&Engine::Mujoco) {
            continue;
        }
        let stem = name.trim_end_matches(".toml");
        let on = variant(
            &name,
            &format!("{stem}-going-on"),
            "[stability]\nterminate_on_decision = false\n",
        );
        let ended = mujoco(&scenario(&name), "ended");
        let went_on = mujoco(&on, "going-on");
        same_maxima(&name, &ended, &went_on, sc.integrator.t_end);
    }
}

/// Every bundled landing's end time is enough (docs/errata.md, "Stability decisions and
/// maxima"): landed again on the core to twice its end time, no maximum moves by more than a
/// tenth of the tolerance `touchdown compare` judges it by, measured as that tolerance measures
/// it (the strokes, the peak pitch rate and its time, the peak vertical acceleration, the
/// minimum stability distance, the struts past their capacity). The energy accounts go on
/// accumulating with time and the pitch-rate histories are compared over their common span, so
/// neither says whether a maximum is final.
#[test]
fn every_bundled_landing_ends_when_its_maxima_are_final() {
    use touchdown_compare::metrics::{ENERGY, PITCH_RATE_MAX, PITCH_RATE_RMS};
    let mut failures = vec![];
    for (name, sc) in landings() {
        let path = scenario(&name);
        let mut longer = sc.clone();
        longer.integrator.t_end *= 2.0;
        let run = |s: &Scenario| {
            touchdown_compare::run(Engine::Core, &path, s).unwrap_or_else(|e| panic!("{e}"))
        };
        let pair = touchdown_compare::pair::compare(&run(&sc), &run(&longer));
        let history_or_energy = [
            ENERGY.quantity,
            PITCH_RATE_RMS.quantity,
            PITCH_RATE_MAX.quantity,
        ];
        for c in &pair.channels {
            if !history_or_energy.contains(&c.quantity) && c.difference > 0.1 * c.tolerance {
                failures.push(format!(
                    "{name}: {} moves by {:.3e} {} from t_end {} s to twice that (a tenth of its tolerance is {:.3e})",
                    c.name(),
                    c.difference,
                    c.difference_unit,
                    sc.integrator.t_end,
                    0.1 * c.tolerance
                ));
            }
        }
        assert_eq!(pair.outcome_a, pair.outcome_b, "{name}: outcome");
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
