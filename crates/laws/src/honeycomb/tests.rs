//! The honeycomb laws against closed forms: stations, rebound, permanent set, stops, trunnions.

use super::*;
use crate::{series_rate, LawError};

fn primary() -> Honeycomb {
    // Onset 1e5 N/m, FP1 = 1000 N to 0.1 m, FP2 = 3000 N to 0.2 m, stroke-out 1e7 N/m.
    let stages = [
        Stage {
            crush_load: 1000.0,
            stroke_end: 0.1,
        },
        Stage {
            crush_load: 3000.0,
            stroke_end: 0.2,
        },
    ];
    Honeycomb::new(LoadStroke::new(1e5, &stages, 1e7).unwrap(), 1e6, 1.0).unwrap()
}

#[test]
fn the_energy_to_capacity_is_the_area_under_the_virgin_curve() {
    let c = primary().curve;
    // Onset to 1000 N over 10 mm (5 J), plateau to 0.1 m (90 J), onset to 3000 N over
    // 20 mm (40 J), plateau to 0.2 m (240 J).
    assert!((c.energy_to_capacity() - 375.0).abs() < 1e-9);
    // The same by the midpoint rule on the force itself.
    let n = 200_000;
    let h = c.capacity() / n as f64;
    let sum: f64 = (0..n).map(|i| c.force((i as f64 + 0.5) * h) * h).sum();
    assert!((sum - 375.0).abs() < 1e-6, "{sum}");
}

#[test]
fn virgin_curve_stations() {
    let h = primary();
    let c = &h.curve;
    assert_eq!(c.force(-0.01), 0.0);
    assert!((c.force(0.005) - 500.0).abs() < 1e-9, "onset");
    assert!((c.force(0.01) - 1000.0).abs() < 1e-9, "station A");
    assert!((c.force(0.05) - 1000.0).abs() < 1e-9, "first plateau");
    assert!(
        (c.force(0.11) - 2000.0).abs() < 1e-9,
        "onset to the second stage"
    );
    assert!((c.force(0.15) - 3000.0).abs() < 1e-9, "second plateau");
    assert!((c.force(0.201) - 13000.0).abs() < 1e-6, "stroke-out");
    assert_eq!(c.capacity(), 0.2);
}

#[test]
fn crushing_only_on_a_plateau_of_the_virgin_curve() {
    let h = primary();
    let fresh = CrushMemory::default();
    assert_eq!(h.crush_load(0.005, fresh), None, "onset ramp is elastic");
    assert_eq!(h.crush_load(0.05, fresh), Some(1000.0));
    assert_eq!(h.crush_load(0.11, fresh), None, "ramp to the second stage");
    assert_eq!(h.crush_load(0.15, fresh), Some(3000.0));
    assert_eq!(h.crush_load(0.201, fresh), None, "bottoming is elastic");
    let mut crushed = CrushMemory::default();
    h.commit(0.06, &mut crushed);
    assert_eq!(h.crush_load(0.05, crushed), None, "rebound line");
    assert_eq!(
        h.crush_load(0.06, crushed),
        Some(1000.0),
        "back at the front"
    );
}

#[test]
fn load_unload_reload_keeps_permanent_set() {
    let h = primary();
    let mut m = CrushMemory::default();
    // Load to 0.05 m on the first plateau and commit.
    for i in 0..=50 {
        let x = 0.001 * i as f64;
        h.commit(x, &mut m);
    }
    assert_eq!(m.max_stroke, 0.05);
    // Unload: linear at K_B, reaches zero at G = 0.05 − 1000/1e6 = 0.049.
    assert!((h.force(0.0495, m) - 500.0).abs() < 1e-6);
    assert!((h.permanent_set(m) - 0.049).abs() < 1e-12);
    assert_eq!(h.force(0.03, m), 0.0, "no tension in a crushed cartridge");
    // Reload: zero load until G, then back up the backoff line to the virgin curve.
    assert_eq!(h.force(0.0489, m), 0.0);
    assert!((h.force(0.05, m) - 1000.0).abs() < 1e-9);
    assert!(
        (h.force(0.06, m) - 1000.0).abs() < 1e-9,
        "continues on the plateau"
    );
    // The memory never shrinks.
    h.commit(0.02, &mut m);
    assert_eq!(m.max_stroke, 0.05);
    // Stored energy on the rebound line is F²/(2 K_B).
    assert!((h.stored_energy(0.0495, m) - 500.0 * 500.0 / 2e6).abs() < 1e-12);
}

#[test]
fn a_bottomed_strut_crushes_through_the_stop_depth() {
    let h = primary(); // e = 1
    let mut m = CrushMemory::default();
    h.commit(0.21, &mut m); // 0.01 m into stroke-out: 3000 + 1e7·0.01 N
    assert_eq!((m.max_stroke, m.stop_depth), (0.21, 0.21 - 0.2));
    assert!((h.force(0.21, m) - 103_000.0).abs() < 1e-6);
    // Unloading: the honeycomb's 3000 N rebounds along K_B from 0.21 m (gone by 0.207 m),
    // the lossless stop retraces its line to the capacity.
    assert!((h.crush_force(0.209, m) - 2000.0).abs() < 1e-6);
    assert!((h.force(0.209, m) - 92_000.0).abs() < 1e-6);
    assert!((h.force(0.205, m) - 50_000.0).abs() < 1e-6);
    assert_eq!(h.force(0.2, m), 0.0);
    assert_eq!(h.force(0.199, m), 0.0);
    // The stop pushes the strut back to the capacity; no force below it.
    assert_eq!(h.permanent_set(m), 0.2);
    // Stored: the honeycomb's rebound triangle and the stop's own K_so·d²/2, not F_c·d.
    let e = 3000.0f64.powi(2) / 2e6 + 0.5 * 1e7 * 0.01f64.powi(2);
    assert!((h.stored_energy(0.21, m) - e).abs() < 1e-9);
}

/// Work done on the strut along strokes `path` (committing each), by the trapezoid rule on
/// fine steps, J.
fn work_along(h: &Honeycomb, m: &mut CrushMemory, path: &[f64]) -> f64 {
    let mut w = 0.0;
    for pair in path.windows(2) {
        let n = 20_000;
        for i in 0..n {
            let a = pair[0] + (pair[1] - pair[0]) * i as f64 / n as f64;
            let b = pair[0] + (pair[1] - pair[0]) * (i + 1) as f64 / n as f64;
            w += 0.5 * (h.force(a, *m) + h.force(b, *m)) * (b - a);
            h.commit(b, m);
        }
    }
    w
}

/// A bottomed strut with restitution e returns, at every hit, the honeycomb's rebound
/// triangle and e² of what the stop's own spring took; the plateau load carried through
/// the stop's depth is crushed; the stored energy is what unloading returns.
#[test]
fn a_stop_returns_the_square_of_its_restitution_at_every_hit() {
    for e in [0.0, 0.5, 0.8, 1.0] {
        let stages = [Stage {
            crush_load: 3000.0,
            stroke_end: 0.2,
        }];
        let h = Honeycomb::new(LoadStroke::new(1e5, &stages, 1e7).unwrap(), 1e6, e).unwrap();
        let mut m = CrushMemory::default();
        h.commit(0.2, &mut m);
        let triangle = 3000.0f64.powi(2) / 2e6;
        let own = 0.5 * 1e7 * 0.01f64.powi(2);
        // First hit: 10 mm deep from the capacity, F_c·d crushed plus the stop's own.
        let taken = work_along(&h, &mut m, &[0.2, 0.21]);
        assert!((taken - (3000.0 * 0.01 + own)).abs() < 1e-6);
        let expected = triangle + e * e * own;
        let stored = h.stored_energy(0.21, m);
        assert!((stored - expected).abs() < 1e-9 * taken, "e = {e}");
        // Unloading to below the capacity gives back what is stored, continuously from
        // the deepest point unless the stop is plastic.
        if e > 0.0 {
            let drop = 103_000.0 - h.force(0.21 - 1e-9, m);
            let rate = h.stop.unloading_rate() + h.backoff_rate;
            assert!(drop > 0.0 && drop < 2e-9 * rate, "{drop}");
        }
        let returned = -work_along(&h, &mut m, &[0.21, 0.199]);
        assert!(
            (returned - expected).abs() < 2e-3 * taken,
            "e = {e}: {returned} vs {expected}"
        );
        assert_eq!(m.stop_depth, 0.0, "the engagement ended at the capacity");
        // Second, shallower hit (6 mm): the stop loads afresh from its start, and gives
        // back e² of its own spring's energy again (not lossless below the first depth).
        let taken2 = work_along(&h, &mut m, &[0.199, 0.206]);
        let own2 = 0.5 * 1e7 * 0.006f64.powi(2);
        let returned2 = -work_along(&h, &mut m, &[0.206, 0.199]);
        assert!((taken2 - own2).abs() < 2e-3 * own2, "e = {e}: {taken2}");
        assert!(
            (returned2 - e * e * own2).abs() < 2e-3 * own2,
            "e = {e}: {returned2} vs {}",
            e * e * own2
        );
        // The stop alone is the force beyond the honeycomb's own, on every branch.
        for x in [0.15, 0.2, 0.205, 0.21, 0.211] {
            let beyond = h.force(x, m) - h.crush_force(x, m);
            assert!(
                (h.stop_force(x, m) - beyond).abs() < 1e-6,
                "e = {e}, x = {x}"
            );
        }
    }
    assert!(Stop::new(1e7, 1.2).is_err() && Stop::new(1e7, -0.1).is_err());
    assert!(Stop::new(1e7, f64::NAN).is_err());
}

/// The closed form of restitution: a mass that strikes a stop at speed v leaves it at
/// e·v, at every hit (its flight between hits is ballistic and gives it back the speed it
/// left with, so the hits are taken one after the other; velocity Verlet, each accepted
/// depth committed, as an engine does). A plastic stop keeps it.
#[test]
fn a_mass_striking_a_stop_leaves_at_e_times_its_speed_at_every_hit() {
    for e in [0.0, 0.3, 0.5, 0.8, 1.0] {
        let stop = Stop::new(1e6, e).unwrap();
        let mass = 2.0;
        let dt = 1e-3 * (mass / stop.stiffest_rate()).sqrt();
        let mut deepest = 0.0;
        let mut speed: f64 = 1.5;
        for hit in 0..4 {
            let (mut d, mut v) = (0.0, speed);
            let accel = |d: f64, deepest: f64| -stop.force(d, deepest) / mass;
            let mut steps = 0;
            while d >= 0.0 && steps < 10_000_000 {
                let a0 = accel(d, deepest);
                d += v * dt + 0.5 * a0 * dt * dt;
                let a1 = accel(d, deepest);
                v += 0.5 * (a0 + a1) * dt;
                Stop::commit(d, &mut deepest);
                steps += 1;
                if e == 0.0 && v <= 0.0 {
                    break;
                }
            }
            if e == 0.0 {
                assert!(v.abs() < 1e-3 * speed, "a plastic stop keeps it: {v}");
                break;
            }
            assert_eq!(deepest, 0.0, "the engagement ended as it left");
            assert!(
                (-v / speed - e).abs() < 2e-3 * e,
                "e = {e}, hit {hit}: {} after {speed}",
                -v
            );
            speed = -v;
        }
    }
}

/// The plastic stop's force, stored energy and rates are the limits of those of small
/// restitutions: below the deepest point the force and the energy returned vanish as e → 0,
/// and the steep start of the unloading curve narrows to nothing.
#[test]
fn a_plastic_stop_is_the_limit_of_small_restitutions() {
    let stop = |e: f64| Stop::new(1e7, e).unwrap();
    let (d_max, d) = (0.01, 0.0099);
    // The force 1 % below the deepest point, K_so·d_max·0.99^(2/e² − 1): 1.35e4 N at
    // e = 0.1, 1e-82 N at 0.01, nothing at 0.
    assert!((stop(0.1).force(d, d_max) - 1e5 * 0.99f64.powi(199)).abs() < 1.0);
    assert!(stop(1e-2).force(d, d_max) < 1e-80);
    assert_eq!(stop(0.0).force(d, d_max), 0.0);
    // Loading is the same line whatever e.
    assert_eq!(stop(0.0).force(0.011, d_max), stop(0.5).force(0.011, d_max));
    // What unloading returns: e²·f·d/2, to nothing.
    let f = 1e5;
    assert_eq!(stop(0.0).returned_energy(d_max, f), 0.0);
    assert!(stop(1e-3).returned_energy(d_max, f) < 1e-3);
    // No unloading stiffness at e = 0; the stiffest rate is the loading rate there and the
    // unloading one, n·K_so, above.
    assert_eq!(stop(0.0).unloading_rate(), 0.0);
    assert_eq!(stop(0.0).stiffest_rate(), 1e7);
    assert!((stop(0.5).stiffest_rate() - 7e7).abs() < 1e-3);
    assert_eq!(stop(1.0).stiffest_rate(), 1e7);
}

#[test]
fn each_stroke_names_its_branch() {
    let h = primary();
    let mut m = CrushMemory::default();
    assert_eq!(h.branch(0.005, m), (Branch::Onset, 1e5));
    assert_eq!(h.branch(0.05, m), (Branch::Plateau, 0.0));
    let (b, k) = h.branch(0.105, m);
    assert_eq!(b, Branch::Onset, "onset to the second stage");
    assert!((k - 1e5).abs() < 1e-6, "{k}");
    assert_eq!(h.branch(0.21, m), (Branch::StrokeOut, 1e7));
    h.commit(0.15, &mut m);
    assert_eq!(h.branch(0.149, m), (Branch::Rebound, 1e6));
    assert_eq!(h.branch(0.15, m), (Branch::Plateau, 0.0));
    assert_eq!(
        Branch::StrokeOut.to_string(),
        "its stroke-out (bottoming) stop"
    );
}

#[test]
fn tension_and_compression_are_independent() {
    let side = |f: f64| {
        Honeycomb::new(
            LoadStroke::new(
                2e5,
                &[Stage {
                    crush_load: f,
                    stroke_end: 0.05,
                }],
                1e7,
            )
            .unwrap(),
            1e6,
            1.0,
        )
        .unwrap()
    };
    let s = DoubleActingHoneycomb {
        tension: side(400.0),
        compression: side(600.0),
    };
    let mut m = DoubleActingMemory::default();
    // Tension to 0.02 m.
    assert!((s.force(0.02, m) - 400.0).abs() < 1e-9);
    s.commit(0.02, &mut m);
    // Back through zero into compression: no force between the permanent sets.
    assert_eq!(s.force(0.0, m), 0.0);
    assert!(
        (s.force(-0.001, m) + 200.0).abs() < 1e-9,
        "compression onset from the original zero"
    );
    assert!((s.force(-0.01, m) + 600.0).abs() < 1e-9);
    s.commit(-0.01, &mut m);
    // Back to tension: the tension memory is intact (reload from its permanent set).
    let g_t = s.tension.permanent_set(m.tension);
    assert!((g_t - (0.02 - 400.0 / 1e6)).abs() < 1e-12);
    assert_eq!(s.force(g_t - 1e-6, m), 0.0);
    assert!((s.force(0.02, m) - 400.0).abs() < 1e-9);
    assert_eq!(m.compression.max_stroke, 0.01);
}

#[test]
fn trunnion_spring_gives_series_rates_and_shifts_every_stage() {
    let h = primary();
    let kt = 4e5;
    let t = h.with_trunnion(kt).unwrap();
    // eq. (35): onset slope K' = K_T K / (K_T + K).
    let k_onset = series_rate(1e5, kt);
    assert!((t.curve.force(0.001) - k_onset * 0.001).abs() < 1e-6);
    // eq. (36): backoff.
    assert!((t.backoff_rate - series_rate(1e6, kt)).abs() < 1e-6);
    // eq. (37) for stage 1, and its generalisation F_i/K_T for stage 2.
    let v: Vec<_> = t.curve.vertices().collect();
    assert!((v[1].0 - (0.01 + 1000.0 / kt)).abs() < 1e-12);
    assert!((v[4].0 - (0.2 + 3000.0 / kt)).abs() < 1e-12);
    // The capacity moves with the last vertex: the stop starts where the shifted curve ends.
    assert_eq!(t.curve.capacity(), v[v.len() - 1].0);
    assert!(t.curve.capacity() > h.curve.capacity());
    // Permanent set is unchanged by the trunnion spring: x_max − F/K_B.
    let mut m = CrushMemory::default();
    t.commit(0.05 + 1000.0 / kt, &mut m);
    assert!((t.permanent_set(m) - (0.05 - 1000.0 / 1e6)).abs() < 1e-12);
}

#[test]
fn stage_tables_out_of_order_are_rejected() {
    let bad_load = [
        Stage {
            crush_load: 1000.0,
            stroke_end: 0.1,
        },
        Stage {
            crush_load: 900.0,
            stroke_end: 0.2,
        },
    ];
    assert!(matches!(
        LoadStroke::new(1e5, &bad_load, 1e7),
        Err(LawError::StageTable(_))
    ));
    let bad_end = [Stage {
        crush_load: 1000.0,
        stroke_end: 0.005,
    }];
    assert!(matches!(
        LoadStroke::new(1e5, &bad_end, 1e7),
        Err(LawError::StageTable(_))
    ));
    assert!(matches!(
        LoadStroke::new(-1.0, &bad_end, 1e7),
        Err(LawError::NotPositive { .. })
    ));
    assert!(matches!(
        LoadStroke::new(1e5, &[], 1e7),
        Err(LawError::StageTable(_))
    ));
}
