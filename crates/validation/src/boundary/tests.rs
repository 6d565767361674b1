//! The search on landings whose outcome is known by construction, and its settings.

use super::*;
use crate::ValidationError;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use touchdown_core::Outcome;
use touchdown_scenario::schema::Engine;
use touchdown_scenario::Scenario;

#[test]
fn the_defaults_are_ratios_of_the_vehicle_s_velocity_scale() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios/fig-25-26.toml");
    let sc = Scenario::load(&path).unwrap();
    let twin = Scenario::load_with(
        &path,
        &[
            ("similarity.length", 6.0),
            ("similarity.mass", 216.0),
            ("similarity.time", 6.0),
        ],
    )
    .unwrap();
    // The 1/6-scale model in ft/s: √(32.174 ft/s² · 2.221 ft) = 8.4533 ft/s.
    let v = (32.174f64 * 2.221).sqrt();
    let close = |x: f64, y: f64| (x - y).abs() <= 1e-9 * y.abs();
    let s = Asked::default().settings(&sc).unwrap();
    assert_eq!(s.vh_start, 0.0);
    assert!(close(s.vh_step, DEFAULT_VH_STEP * v), "{s:?}");
    assert!(close(s.vh_max, DEFAULT_VH_MAX * v), "{s:?}");
    assert!(close(s.tolerance, DEFAULT_TOLERANCE * v), "{s:?}");
    assert_eq!(s.scan_step, Some(DEFAULT_SCAN_STEP * s.vh_step), "{s:?}");
    s.validate().unwrap();
    // the Froude twin moves as fast: the same settings in its (the same) velocity unit
    let t = Asked::default().settings(&twin).unwrap();
    for (x, y) in [
        (t.vh_step, s.vh_step),
        (t.vh_max, s.vh_max),
        (t.tolerance, s.tolerance),
        (t.scan_step.unwrap(), s.scan_step.unwrap()),
    ] {
        assert!(close(x, y), "{t:?} {s:?}");
    }
    // what is asked is kept, the scan an eighth of the grid's step (0.25 ft/s on 2 ft/s)
    let asked = Asked {
        vh_start: Some(1.0),
        vh_step: Some(2.0),
        vh_max: Some(30.0),
        tolerance: Some(0.05),
        scan_step: None,
    };
    let expected = settings_from(1.0, 2.0, 30.0, 0.05, Some(0.25));
    assert_eq!(asked.settings(&sc).unwrap(), expected);
    let grid_only = Asked {
        scan_step: Some(0.0),
        ..Asked::default()
    };
    assert_eq!(grid_only.settings(&sc).unwrap().scan_step, None);
}

fn settings_from(
    vh_start: f64,
    vh_step: f64,
    vh_max: f64,
    tolerance: f64,
    scan_step: Option<f64>,
) -> Settings {
    Settings {
        vh_start,
        vh_step,
        vh_max,
        tolerance,
        scan_step,
    }
}

fn settings(vh_step: f64, vh_max: f64, tolerance: f64) -> Settings {
    Settings {
        vh_start: 0.0,
        vh_step,
        vh_max,
        tolerance,
        scan_step: None,
    }
}

/// By construction: a landing that overturns exactly when Vh > 3.7 + 0.1·Vv.
#[test]
fn bisection_finds_a_boundary_known_by_construction() {
    let settings = settings(1.0, 10.0, 1e-3);
    let landing = |vv: f64, vh: f64| {
        Ok(if vh > 3.7 + 0.1 * vv {
            Outcome::Unstable
        } else {
            Outcome::Stable
        })
    };
    let points = search(&[0.0, 5.0, 10.0], settings, landing, &|| {}).unwrap();
    for p in &points {
        let exact = 3.7 + 0.1 * p.vv;
        let vh = p.vh.unwrap();
        assert!(
            (vh - exact).abs() <= 0.5e-3 + 1e-12,
            "Vv {}: {vh} vs {exact}",
            p.vv
        );
        assert!(p.stable_at.unwrap() <= exact && p.unstable_at.unwrap() > exact);
        assert_eq!(p.transitions.len(), 1);
        assert!(p.transitions[0].resolved);
        assert_eq!(p.transitions[0].vh, p.vh);
    }
    // Never unstable: no boundary; unstable from the start: no stable point. The whole
    // grid (0, 1, ..., 10) is landed either way.
    let never = search(&[1.0], settings, |_, _| Ok(Outcome::Stable), &|| {}).unwrap();
    assert_eq!(
        (never[0].vh, never[0].stable_at, never[0].unstable_at),
        (None, Some(10.0), None)
    );
    assert_eq!(never[0].landings, 11);
    let always = search(&[1.0], settings, |_, _| Ok(Outcome::Unstable), &|| {}).unwrap();
    assert_eq!(
        (always[0].vh, always[0].stable_at, always[0].unstable_at),
        (None, None, Some(0.0))
    );
    assert_eq!(always[0].landings, 11);
    assert!(never[0].transitions.is_empty() && always[0].transitions.is_empty());
}

/// Unstable on (10 + s, 14 + s) and above 20 + s (s = 0.1·Vv), stable elsewhere, undecided
/// exactly at the grid point 17.
fn non_monotonic(vv: f64, vh: f64) -> Result<Outcome, ValidationError> {
    let s = 0.1 * vv;
    Ok(if vh == 17.0 {
        Outcome::Undecided
    } else if (vh > 10.0 + s && vh < 14.0 + s) || vh > 20.0 + s {
        Outcome::Unstable
    } else {
        Outcome::Stable
    })
}

#[test]
fn every_transition_is_found_whatever_the_step_when_the_grid_resolves_them() {
    let tol = 1e-3;
    let vvs = [0.0, 3.0];
    let ticks = AtomicUsize::new(0);
    let tick = || {
        ticks.fetch_add(1, Ordering::Relaxed);
    };
    let coarse = search(&vvs, settings(1.0, 30.0, tol), non_monotonic, &tick).unwrap();
    let fine = search(&vvs, settings(0.5, 30.0, tol), non_monotonic, &tick).unwrap();
    let landings: usize = coarse.iter().chain(&fine).map(|p| p.landings).sum();
    assert_eq!(
        ticks.load(Ordering::Relaxed),
        landings,
        "one tick per landing"
    );
    for (a, b) in coarse.iter().zip(&fine) {
        assert_eq!(a.vv, b.vv);
        let s = 0.1 * a.vv;
        let exact = [
            (Direction::StableToUnstable, 10.0 + s),
            (Direction::UnstableToStable, 14.0 + s),
            (Direction::StableToUnstable, 20.0 + s),
        ];
        for p in [a, b] {
            assert_eq!(p.transitions.len(), 3, "{p:?}");
            for (t, &(direction, vh)) in p.transitions.iter().zip(&exact) {
                assert_eq!(t.direction, direction);
                assert!(t.resolved && t.undecided_at.is_empty());
                assert!((t.vh.unwrap() - vh).abs() <= 0.5 * tol + 1e-12, "{t:?}");
                assert!((t.stable_at - t.unstable_at).abs() <= tol);
                // The stable end is stable and the unstable end unstable.
                assert_eq!(non_monotonic(p.vv, t.stable_at).unwrap(), Outcome::Stable);
                assert_eq!(
                    non_monotonic(p.vv, t.unstable_at).unwrap(),
                    Outcome::Unstable
                );
            }
            // The reported boundary is the lowest stable -> unstable transition.
            assert_eq!(p.vh, p.transitions[0].vh);
            assert_eq!(p.stable_at, Some(p.transitions[0].stable_at));
            assert_eq!(p.unstable_at, Some(p.transitions[0].unstable_at));
            // The undecided grid point is listed, between two stable ones: no transition.
            assert_eq!((p.undecided, &p.undecided_at[..]), (1, &[17.0][..]));
        }
        // The steps agree on every transition to the tolerance.
        assert!((a.vh.unwrap() - b.vh.unwrap()).abs() <= tol);
        for (ta, tb) in a.transitions.iter().zip(&b.transitions) {
            assert_eq!(ta.direction, tb.direction);
            assert!((ta.vh.unwrap() - tb.vh.unwrap()).abs() <= tol);
        }
    }
    // Deterministic, however the landings were scheduled.
    let again = search(&vvs, settings(1.0, 30.0, tol), non_monotonic, &|| {}).unwrap();
    assert_eq!(again, coarse);
}

#[test]
fn undecided_landings_are_counted_and_listed_never_taken_as_stable_or_unstable() {
    let s = settings(1.0, 10.0, 1e-3);
    // Stable up to 3, undecided on [4, 6], unstable from 7: the change lies somewhere in
    // (3, 7) and is not bisected across the undecided points.
    let gap = |_: f64, vh: f64| {
        Ok(match vh {
            v if v < 3.5 => Outcome::Stable,
            v if v < 6.5 => Outcome::Undecided,
            _ => Outcome::Unstable,
        })
    };
    let p = &search(&[2.0], s, gap, &|| {}).unwrap()[0];
    assert_eq!(p.landings, 11, "no bisection across undecided points");
    assert_eq!(
        (p.undecided, &p.undecided_at[..]),
        (3, &[4.0, 5.0, 6.0][..])
    );
    assert_eq!(
        p.transitions,
        vec![Transition {
            direction: Direction::StableToUnstable,
            stable_at: 3.0,
            unstable_at: 7.0,
            vh: None,
            resolved: false,
            undecided_at: vec![4.0, 5.0, 6.0],
            stable_stops: Stops::default(),
            unstable_stops: Stops::default(),
            refined: None,
        }]
    );
    assert_eq!(
        (p.vh, p.stable_at, p.unstable_at),
        (None, Some(3.0), Some(7.0))
    );
    // Undecided on top of the grid: neither stable nor unstable, so no boundary and the
    // largest stable point is the last stable one, not vh_max.
    let top = |_: f64, vh: f64| {
        Ok(if vh < 7.5 {
            Outcome::Stable
        } else {
            Outcome::Undecided
        })
    };
    let p = &search(&[2.0], s, top, &|| {}).unwrap()[0];
    assert!(p.transitions.is_empty());
    assert_eq!((p.vh, p.stable_at, p.unstable_at), (None, Some(7.0), None));
    assert_eq!(
        (p.undecided, &p.undecided_at[..]),
        (3, &[8.0, 9.0, 10.0][..])
    );
    // All undecided: nothing stable, nothing unstable.
    let none = search(&[2.0], s, |_, _| Ok(Outcome::Undecided), &|| {}).unwrap();
    assert_eq!((none[0].stable_at, none[0].unstable_at), (None, None));
    assert_eq!((none[0].undecided, none[0].landings), (11, 11));
    // An undecided point below a resolved boundary leaves it alone.
    let low = |_: f64, vh: f64| {
        Ok(if vh == 2.0 {
            Outcome::Undecided
        } else if vh > 5.25 {
            Outcome::Unstable
        } else {
            Outcome::Stable
        })
    };
    let p = &search(&[2.0], s, low, &|| {}).unwrap()[0];
    assert_eq!(p.transitions.len(), 1);
    assert!((p.vh.unwrap() - 5.25).abs() <= 0.5e-3 + 1e-12);
    assert_eq!(p.undecided_at, vec![2.0]);
}

#[test]
fn an_undecided_midpoint_leaves_its_transition_unresolved_with_its_bracket() {
    // Stable up to 5.7, undecided on (5.7, 5.8), unstable from 5.8: grid bracket [5, 6],
    // midpoint 5.5 stable, midpoint 5.75 undecided.
    let landing = |_: f64, vh: f64| {
        Ok(match vh {
            v if v <= 5.7 => Outcome::Stable,
            v if v < 5.8 => Outcome::Undecided,
            _ => Outcome::Unstable,
        })
    };
    let p = &search(&[4.0], settings(1.0, 10.0, 1e-3), landing, &|| {}).unwrap()[0];
    let t = &p.transitions[..];
    assert_eq!(
        t,
        [Transition {
            direction: Direction::StableToUnstable,
            stable_at: 5.5,
            unstable_at: 6.0,
            vh: None,
            resolved: false,
            undecided_at: vec![5.75],
            stable_stops: Stops::default(),
            unstable_stops: Stops::default(),
            refined: None,
        }]
    );
    assert_eq!(
        (p.vh, p.stable_at, p.unstable_at),
        (None, Some(5.5), Some(6.0))
    );
    assert_eq!(
        (p.landings, p.undecided, &p.undecided_at[..]),
        (13, 1, &[5.75][..])
    );
}

/// Stable up to 11.3, unstable on (11.3, 11.6), stable again up to 12.2, unstable above:
/// an island narrower than the grid step, next to the change the grid sees.
fn island(_: f64, vh: f64) -> Result<Outcome, ValidationError> {
    Ok(if (vh > 11.3 && vh < 11.6) || vh > 12.2 {
        Outcome::Unstable
    } else {
        Outcome::Stable
    })
}

#[test]
fn the_scan_finds_an_island_the_grid_steps_over_and_reports_a_band() {
    let tol = 1e-3;
    let grid_only = &search(&[1.0], settings(1.0, 20.0, tol), island, &|| {}).unwrap()[0];
    assert_eq!(grid_only.transitions.len(), 1, "the grid sees one change");
    assert_eq!(grid_only.band, None);
    let scanned = Settings {
        scan_step: Some(0.25),
        ..settings(1.0, 20.0, tol)
    };
    let p = &search(&[1.0], scanned, island, &|| {}).unwrap()[0];
    let exact = [
        (Direction::StableToUnstable, 11.3),
        (Direction::UnstableToStable, 11.6),
        (Direction::StableToUnstable, 12.2),
    ];
    assert_eq!(p.transitions.len(), 3, "{p:?}");
    for (t, (direction, vh)) in p.transitions.iter().zip(exact) {
        assert_eq!(t.direction, direction);
        assert!((t.vh.unwrap() - vh).abs() <= 0.5 * tol + 1e-12, "{t:?}");
    }
    // The boundary is still the lowest stable -> unstable transition, inside its band.
    assert!((p.vh.unwrap() - 11.3).abs() <= 0.5 * tol + 1e-12);
    let band = p.band.unwrap();
    assert_eq!(band.changes, 3);
    assert!(band.from <= 11.3 && band.from > 11.3 - tol);
    assert!(band.to >= 12.2 && band.to < 12.2 + tol);
    // Every landing counted: 21 grid points, the scan of [11, 14] every 0.25 less its
    // grid points (9), and the bisections.
    assert!(p.landings > 30, "{}", p.landings);
}

/// Past a strut's capacity above 7.4 (one strut, stop force 1 kN per unit of Vh beyond),
/// two struts above 10; unstable above 12.2.
fn bottoming(_: f64, vh: f64) -> Result<Landed, ValidationError> {
    let struts = (vh > 7.4) as usize + (vh > 10.0) as usize;
    Ok(Landed {
        outcome: if vh > 12.2 {
            Outcome::Unstable
        } else {
            Outcome::Stable
        },
        stops: Stops {
            struts_past_capacity: struts,
            peak_stop_force_n: if struts > 0 { 1e3 * (vh - 7.4) } else { 0.0 },
        },
    })
}

#[test]
fn the_first_speed_past_capacity_and_the_safe_envelope_are_found_with_their_stops() {
    let tol = 1e-3;
    let p = &search(&[1.0], settings(1.0, 20.0, tol), bottoming, &|| {}).unwrap()[0];
    let c = p.capacity.unwrap();
    assert!((c.vh.unwrap() - 7.4).abs() <= 0.5 * tol + 1e-12, "{c:?}");
    assert!(c.within_at.unwrap() <= 7.4 && c.past_at > 7.4);
    assert_eq!(c.stops.struts_past_capacity, 1);
    assert!(c.stops.peak_stop_force_n > 0.0 && c.stops.peak_stop_force_n <= 1e3 * tol);
    // Safe up to the capacity, not to the overturn.
    assert_eq!(p.safe.limit, Some(Limit::Capacity));
    assert_eq!(p.safe.safe_to, c.within_at);
    assert_eq!(p.safe.unsafe_at, Some(c.past_at));
    // The overturn's ends say which stops they engaged.
    let t = &p.transitions[0];
    assert!((t.vh.unwrap() - 12.2).abs() <= 0.5 * tol + 1e-12);
    assert_eq!(t.stable_stops.struts_past_capacity, 2);
    assert_eq!(t.unstable_stops.struts_past_capacity, 2);
    assert!((t.unstable_stops.peak_stop_force_n - 1e3 * (t.unstable_at - 7.4)).abs() < 1e-9);
    // Past capacity from the first landing: no bracket; never past: no edge.
    let early = |vv: f64, vh: f64| bottoming(vv, vh + 8.0);
    let p = &search(&[1.0], settings(1.0, 20.0, tol), early, &|| {}).unwrap()[0];
    let c = p.capacity.unwrap();
    assert_eq!((c.within_at, c.past_at, c.vh), (None, 0.0, None));
    assert_eq!((p.safe.safe_to, p.safe.unsafe_at), (None, Some(0.0)));
    let p = &search(&[1.0], settings(1.0, 5.0, tol), bottoming, &|| {}).unwrap()[0];
    assert_eq!(p.capacity, None);
    assert_eq!(
        p.safe,
        SafeEdge {
            safe_to: Some(5.0),
            unsafe_at: None,
            limit: None
        }
    );
}

#[test]
fn bad_settings_are_refused_naming_the_argument() {
    let panics = |_: f64, _: f64| -> Result<Outcome, ValidationError> {
        panic!("no landing with bad settings")
    };
    let cases = [
        (settings(0.0, 10.0, 0.1), "--vh-step"),
        (settings(-1.0, 10.0, 0.1), "--vh-step"),
        (settings(f64::NAN, 10.0, 0.1), "--vh-step"),
        (settings(f64::INFINITY, 10.0, 0.1), "--vh-step"),
        (settings(1.0, 10.0, 0.0), "--tol"),
        (settings(1.0, 10.0, -0.1), "--tol"),
        (settings(1.0, 10.0, f64::NAN), "--tol"),
        (settings(1.0, 10.0, f64::INFINITY), "--tol"),
        (settings(1.0, 1e3, 1e-7), "--tol"), // below 1e-9·1000
        (settings(1.0, -1.0, 0.1), "--vh-max"),
        (settings(1.0, f64::NAN, 0.1), "--vh-max"),
        (settings(1e-3, 100.0, 0.1), "--vh-step"), // 100,001 points
        (settings(1e-300, 1e300, 1e292), "--vh-step"),
        (
            Settings {
                scan_step: Some(1.0),
                ..settings(1.0, 10.0, 0.1)
            },
            "--scan-step",
        ),
        (
            Settings {
                scan_step: Some(0.0),
                ..settings(1.0, 10.0, 0.1)
            },
            "--scan-step",
        ),
    ];
    for (s, argument) in cases {
        let e = search(&[1.0], s, panics, &|| {}).unwrap_err();
        assert!(
            matches!(e, ValidationError::Setting { argument: a, .. } if a == argument),
            "{s:?}: {e}"
        );
        let message = e.to_string();
        assert!(message.starts_with(argument), "{message}");
        assert!(message.contains("expected"), "{message}");
        assert_eq!(s.validate().unwrap_err().to_string(), message);
    }
    let e = settings(1e-3, 100.0, 0.1)
        .validate()
        .unwrap_err()
        .to_string();
    assert!(e.contains("10000"), "{e}");
    let e = settings(1.0, 1e3, 1e-7).validate().unwrap_err().to_string();
    assert!(e.contains("1e-06"), "{e}");
    // At the limits: accepted.
    assert_eq!(settings(1e-2, 99.99, 0.1).grid().unwrap().len(), 10_000);
    assert!(settings(1.0, 1e3, 1e-6).validate().is_ok());
    let e = search(&[f64::NAN], settings(1.0, 2.0, 0.1), panics, &|| {}).unwrap_err();
    assert!(e.to_string().starts_with("--vv"), "{e}");
}

#[test]
fn the_grid_is_computed_not_accumulated_and_includes_vh_max() {
    // 0.1 + 0.1 + 0.1 > 0.3 and 0.3 / 0.1 < 3: still four points, each i·0.1.
    let g = settings(0.1, 0.3, 0.01).grid().unwrap();
    assert_eq!(g, vec![0.0, 0.1, 0.2, 0.1 * 3.0]);
    let g = Settings {
        vh_start: 1.0,
        vh_step: 0.7,
        vh_max: 3.0,
        tolerance: 0.1,
        scan_step: None,
    }
    .grid()
    .unwrap();
    assert_eq!(g, vec![1.0, 1.7, 1.0 + 2.0 * 0.7]);
    // Just over one step beyond vh_max by less than 1e-9 relative: included.
    let g = settings(1.0, 3.0 - 1e-12, 0.1).grid().unwrap();
    assert_eq!(g.len(), 4);
    let g = settings(2.0, 2.0, 0.1).grid().unwrap();
    assert_eq!(g, vec![0.0, 2.0]);
    assert_eq!(settings(5.0, 0.0, 0.1).grid().unwrap(), vec![0.0]);
}

// The table and the CSV of two points: one with several transitions, a band, a capacity edge
// and undecided landings, one stable throughout.

fn transition(direction: Direction, s: f64, u: f64, vh: Option<f64>) -> Transition {
    Transition {
        direction,
        stable_at: s,
        unstable_at: u,
        vh,
        resolved: vh.is_some(),
        undecided_at: if vh.is_some() {
            vec![]
        } else {
            vec![s.max(u) - 1.0]
        },
        stable_stops: Stops::default(),
        unstable_stops: Stops {
            struts_past_capacity: 2,
            peak_stop_force_n: 38_000.0,
        },
        refined: None,
    }
}

fn points() -> Vec<EnginePoint> {
    let non_monotonic = BoundaryPoint {
        vv: 8.0,
        vh: Some(10.0),
        stable_at: Some(9.99),
        unstable_at: Some(10.01),
        transitions: vec![
            transition(Direction::StableToUnstable, 9.99, 10.01, Some(10.0)),
            Transition {
                refined: Some(Refined::new(8.0, Outcome::Stable, Outcome::Stable)),
                ..transition(Direction::UnstableToStable, 14.01, 13.99, Some(14.0))
            },
            transition(Direction::StableToUnstable, 18.0, 22.0, None),
        ],
        band: Some(Band {
            from: 9.99,
            to: 22.0,
            changes: 3,
        }),
        capacity: Some(CapacityEdge {
            within_at: Some(9.0),
            past_at: 9.05,
            vh: Some(9.025),
            stops: Stops {
                struts_past_capacity: 1,
                peak_stop_force_n: 500.0,
            },
        }),
        safe: SafeEdge {
            safe_to: Some(9.0),
            unsafe_at: Some(9.05),
            limit: Some(Limit::Capacity),
        },
        undecided_at: vec![17.0, 21.0],
        landings: 40,
        undecided: 2,
    };
    let stable = BoundaryPoint {
        vv: 10.0,
        vh: None,
        stable_at: Some(30.0),
        unstable_at: None,
        transitions: vec![],
        band: None,
        capacity: None,
        safe: SafeEdge {
            safe_to: Some(30.0),
            unsafe_at: None,
            limit: None,
        },
        undecided_at: vec![],
        landings: 16,
        undecided: 0,
    };
    [non_monotonic, stable]
        .into_iter()
        .map(|point| EnginePoint {
            engine: Engine::Core,
            stop_restitution: None,
            point,
        })
        .collect()
}

#[test]
fn boundary_csv_has_one_row_per_transition() {
    // In SI (a velocity unit of 0.5 m/s), the vertical velocity negative down.
    let csv = super::document::csv(&points(), 0.5).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(
        lines,
        [
            "engine,stop_restitution,vv_m_s,direction,stable_at_vh_m_s,unstable_at_vh_m_s,vh_m_s,resolved,undecided,past_capacity_vh_m_s,safe_to_vh_m_s,safe_until,refined_holds",
            "core,,-4,stable_to_unstable,4.995,5.005,5,true,2,4.5125,4.5,capacity,",
            "core,,-4,unstable_to_stable,7.005,6.995,7,true,2,4.5125,4.5,capacity,false",
            "core,,-4,stable_to_unstable,9,11,,false,2,4.5125,4.5,capacity,",
            "core,,-5,none,15,,,,0,,15,,",
        ]
    );
}

#[test]
fn boundary_text_lists_every_transition_the_band_the_capacity_and_the_undecided() {
    let s = Settings {
        vh_start: 0.0,
        vh_step: 2.0,
        vh_max: 30.0,
        tolerance: 0.05,
        scan_step: Some(0.25),
    };
    let text = super::text::table(&points(), "ft/s", s);
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines[0].contains("negative down"), "{text}");
    assert!(lines[1].contains("ft/s") && lines[1].contains("tolerance 0.05"));
    assert!(lines[1].contains("scanned every 0.25"), "{text}");
    // The row: boundary 10, first past capacity 9.025, safe to 9 ended by the capacity.
    let row: Vec<&str> = lines[3].split_whitespace().collect();
    assert_eq!(
        row,
        [
            "core", "file", "-8.000", "10.000", "9.990", "10.010", "9.025", "9.000", "capacity",
            "40", "2"
        ],
        "{text}"
    );
    assert!(lines[4].contains("band") && lines[4].contains("9.990 to 22.000"));
    assert!(lines[4].contains("changes 3 times"), "{text}");
    // Every transition, each end with its stops.
    assert!(lines[5].contains("stable → unstable") && lines[5].contains("at Vh 10.000"));
    assert!(
        lines[5].contains("stable at 9.990: within capacity"),
        "{text}"
    );
    assert!(
        lines[5].contains("2 struts past capacity, stop 38.0 kN"),
        "{text}"
    );
    assert!(lines[6].contains("unstable → stable") && lines[6].contains("at Vh 14.000"));
    assert!(lines[7].contains("unresolved") && lines[7].contains("undecided at 21.000"));
    assert!(lines[8].contains("capacity") && lines[8].contains("first past at 9.050"));
    assert!(lines[8].contains("1 strut past capacity, stop 0.5 kN (within at 9.000)"));
    assert!(lines[9].contains("undecided") && lines[9].ends_with("17.000, 21.000"));
    let row: Vec<&str> = lines[10].split_whitespace().collect();
    assert_eq!(
        row,
        ["core", "file", "-10.000", "—", "30.000", "—", "never", "30.000", "—", "16", "0"],
        "{text}"
    );
    // No spread table with one stop law.
    assert!(!text.contains("by end-stop restitution"), "{text}");
}

#[test]
fn the_spread_over_stop_laws_is_the_largest_less_the_smallest_boundary() {
    let mut points = Vec::new();
    for (e, vh) in [(0.5, Some(10.0)), (1.0, Some(7.5)), (0.1, Some(12.25))] {
        let mut p = points_at(e);
        p.point.vh = vh;
        points.push(p);
    }
    let text = super::text::spread_text(&points);
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines[1].contains("restitution"), "{text}");
    assert!(
        lines[2].contains("e = 0.1") && lines[2].ends_with("spread"),
        "{text}"
    );
    let row: Vec<&str> = lines[3].split_whitespace().collect();
    assert_eq!(
        row,
        ["core", "-8.000", "12.250", "10.000", "7.500", "4.750"]
    );
    assert_eq!(lines.len(), 4, "one row per engine and Vv: {text}");
    // A law that never overturns up to the largest Vh tried bounds the spread from below.
    points[0].point.vh = None;
    points[0].point.unstable_at = None;
    points[0].point.stable_at = Some(30.0);
    let text = super::text::spread_text(&points);
    let row: Vec<&str> = text.lines().nth(3).unwrap().split_whitespace().collect();
    assert_eq!(
        row,
        ["core", "-8.000", "12.250", ">", "30.000", "7.500", ">", "22.500"],
        "{text}"
    );
    // No law overturns: the spread is open, not zero.
    for p in &mut points {
        p.point.vh = None;
        p.point.unstable_at = None;
        p.point.stable_at = Some(36.0);
    }
    let text = super::text::spread_text(&points);
    let row: Vec<&str> = text.lines().nth(3).unwrap().split_whitespace().collect();
    assert_eq!(row.last(), Some(&"—"), "{text}");
}

fn points_at(e: f64) -> EnginePoint {
    let mut p = points().remove(0);
    p.stop_restitution = Some(e);
    p
}

/// With a refined landing, every transition's bracket ends are landed again by it: a boundary
/// the finer steps keep within the bracket holds; one they move past an end is said to move,
/// with the ends' refined outcomes; every refined landing ticks the progress.
#[test]
fn refined_bracket_ends_hold_or_say_the_boundary_moved() {
    let s = settings(1.0, 20.0, 0.01);
    let at = |boundary: f64| {
        move |_: f64, vh: f64| -> Result<Outcome, ValidationError> {
            Ok(match vh < boundary {
                true => Outcome::Stable,
                false => Outcome::Unstable,
            })
        }
    };
    let ticks = AtomicUsize::new(0);
    let tick = || {
        ticks.fetch_add(1, Ordering::Relaxed);
    };
    let found = |refined_boundary: f64| {
        let fine = at(refined_boundary);
        let p = search::search_streaming(&[2.0], s, at(10.0), Some((8.0, &fine)), &tick, &|_| ())
            .unwrap();
        p[0].transitions[0].clone()
    };
    // The bracket is bisected from (9, 10] to (9.9921875, 10]: a boundary at 9.995 in the
    // finer steps holds.
    let before = ticks.load(Ordering::Relaxed);
    let t = found(9.995);
    assert_eq!(
        (t.stable_at, t.unstable_at, t.resolved),
        (9.9921875, 10.0, true)
    );
    assert_eq!(
        t.refined,
        Some(Refined::new(8.0, Outcome::Stable, Outcome::Unstable))
    );
    assert!(t.refined.unwrap().holds);
    let plain = search(&[2.0], s, at(10.0), &|| {}).unwrap()[0].landings;
    assert_eq!(ticks.load(Ordering::Relaxed) - before, plain + 2);
    // Finer steps that overturn from 9.5: the stable end overturns, and it is said.
    let moved = found(9.5).refined.unwrap();
    assert_eq!(
        (moved.stable_end, moved.unstable_end, moved.holds),
        (Outcome::Unstable, Outcome::Unstable, false)
    );
    // Without a refined landing nothing is refined.
    assert!(
        search(&[2.0], s, at(10.0), &|| {}).unwrap()[0].transitions[0]
            .refined
            .is_none()
    );
}
