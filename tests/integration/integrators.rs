//! The core's integration schemes beyond the report's (docs/model.md, "Integration schemes"): the fourth-order Runge–Kutta
//! method and the adaptive Dormand–Prince pair converge to the report scheme's fine-step answer,
//! the quaternion attitude agrees with the Euler angles away from their singularity and goes
//! through it, and the report's scheme refuses the quaternion.

use nalgebra::{Matrix3, Vector3};
use touchdown_core::{Landing, Simulation, Summary};
use touchdown_scenario::schema::Scheme;
use touchdown_scenario::Scenario;
use touchdown_tests::variant;

/// Runs `name` (a variant of `base` with `extra` TOML) on the core to its end.
fn run(base: &str, name: &str, extra: &str) -> (Simulation, Summary) {
    let sc = Scenario::load(variant(base, name, extra)).unwrap_or_else(|e| panic!("{e}"));
    let mut sim = Simulation::new(&sc).unwrap_or_else(|e| panic!("{e}"));
    while !sim.finished() {
        sim.step().unwrap_or_else(|e| panic!("{name}: {e}"));
    }
    let summary = sim.summary();
    (sim, summary)
}

/// The largest relative difference between two landings' maximum strokes (primary, secondary
/// compression and tension), relative to the largest primary stroke.
fn stroke_difference(a: &Summary, b: &Summary) -> f64 {
    let scale = a.max_primary_stroke_m.iter().copied().fold(0.0, f64::max);
    let mut d: f64 = 0.0;
    for i in 0..a.max_primary_stroke_m.len() {
        d = d.max((a.max_primary_stroke_m[i] - b.max_primary_stroke_m[i]).abs());
        for j in 0..2 {
            d = d.max(
                (a.max_secondary_compression_m[i][j] - b.max_secondary_compression_m[i][j]).abs(),
            );
            d = d.max((a.max_secondary_tension_m[i][j] - b.max_secondary_tension_m[i][j]).abs());
        }
    }
    d / scale
}

/// On the Table I 2-2 landing at 8 ft/s, the report's scheme at a hundredth of its steps, the
/// fourth-order Runge–Kutta method at 5 µs and the Dormand–Prince pair at 1e-6 agree on every
/// maximum stroke within 0.3 % of the largest; the adaptive pair rejects steps (its error control
/// and contact-event location at work) and its energy balance closes as tightly as the others'.
///
/// The landing is run with its footpads held by a wall (`surface.obstacle = 1` ft), as the
/// Table I files stood before they stood on spikes. On spikes (the file as bundled) the
/// fixed-step schemes converge (the report's scheme at 2 and 1 µs 0.007 % apart, RK4 at 5 µs
/// 0.012 % from them) and the adaptive pair, at 1e-6, does not: 0.37 %, with more steps
/// rejected than taken where the vehicle rocks slowly on its four footpads, each primary's
/// kinetic bearing friction jumping as its stroking rate crosses zero. An open defect
/// (docs/errata.md, "Numerics", "the adaptive pair and the bearing friction in contact") this
/// test keeps in view: it fails once the pair converges there, to be tightened then.
#[test]
fn runge_kutta_schemes_converge_to_the_reports_fine_step_answer() {
    let base = "table-i-2-2-vv8.toml";
    let wall = "[surface]\nobstacle = 1.0\nspike_depth = 0.0\n";
    let fine = "[integrator]\ndist = 1.4e-5\ndt_max = 2.0e-6\n";
    let rk4 = "[integrator]\nscheme = \"rk4\"\ndt_max = 5.0e-6\n";
    let dopri5 = "[integrator]\nscheme = \"dopri5\"\nrtol = 1e-6\natol = 1e-6\n";
    let (_, report) = run(base, "fine-report", &format!("{wall}{fine}"));
    // RK4 at a fixed step locates no contact event: a footpad leaving within a step leaves at
    // its end, an error first order in the step (49.59, 49.96, 50.05 mm of the largest
    // secondary stroke at 20, 10 and 5 µs against the fine step's 50.15 mm).
    let (_, rk4_held) = run(base, "rk4", &format!("{wall}{rk4}"));
    let (_, dopri) = run(base, "dopri5", &format!("{wall}{dopri5}"));
    for (name, s) in [("rk4", &rk4_held), ("dopri5", &dopri)] {
        let d = stroke_difference(&report, s);
        assert!(d < 3e-3, "{name}: strokes differ by {d} of the largest");
        let e = &s.energy;
        assert!(
            e.residual_j.abs() < 1e-4 * e.kinetic_initial_j,
            "{name}: {e:?}"
        );
    }
    let rejected = dopri.engine_settings["rejected_steps"].as_u64().unwrap();
    assert!(rejected > 0, "the adaptive scheme never rejected a step");
    assert!(
        dopri.steps < rk4_held.steps / 2,
        "{} vs {} steps",
        dopri.steps,
        rk4_held.steps
    );
    // On spikes, as bundled: RK4 converges, the adaptive pair does not yet.
    let (_, spiked) = run(base, "fine-report-spiked", fine);
    let (_, rk4_spiked) = run(base, "rk4-spiked", rk4);
    let d = stroke_difference(&spiked, &rk4_spiked);
    assert!(
        d < 3e-3,
        "rk4 on spikes: strokes differ by {d} of the largest"
    );
    let (_, dopri_spiked) = run(base, "dopri5-spiked", dopri5);
    let d = stroke_difference(&spiked, &dopri_spiked);
    assert!(
        d >= 3e-3,
        "dopri5 on spikes now converges ({d} of the largest): tighten this test"
    );
}

/// Away from θy = ±90° the quaternion attitude gives the Euler angles' landing: the same
/// maximum strokes and peak pitch rate within 1e-6.
#[test]
fn quaternion_attitude_matches_euler_angles_away_from_the_singularity() {
    let base = "table-i-2-2-vv8.toml";
    let scheme = "[integrator]\nscheme = \"rk4\"\ndt_max = 2.0e-5\nt_end = 0.15\n";
    let (_, euler) = run(base, "euler", scheme);
    let (_, quaternion) = run(
        base,
        "quaternion",
        &format!("{scheme}attitude = \"quaternion\"\n"),
    );
    assert!(stroke_difference(&euler, &quaternion) < 1e-6);
    assert!((euler.peak_pitch_rate_rad_s - quaternion.peak_pitch_rate_rad_s).abs() < 1e-6);
}

/// A vehicle tumbling in free flight about its body y axis (a principal axis) at 5 rad/s passes
/// θy = 90° at 0.31 s. The Euler angles stop there with a diagnostic naming the singularity; the
/// quaternion goes through, keeps the kinetic energy, and ends at the analytic attitude
/// T_BI = R_y(ω·t). The footpads ride rigidly, so that the lander is one rigid body.
#[test]
fn quaternion_attitude_goes_through_theta_y_90_degrees() {
    let tumble =
        "[footpad]\ndetached = \"rigid\"\n[touchdown]\nclearance = 10.0\nvertical_velocity = 0.0\n\
                  horizontal_velocity = [0.0, 0.0]\nattitude = [0.0, 0.0, 0.0]\n\
                  body_rates = [0.0, 286.4788975654116, 0.0]\n\
                  [stability]\nterminate_on_decision = false\n\
                  [integrator]\nscheme = \"rk4\"\ndt_max = 1.0e-3\nt_end = 0.4\n";
    let sc = Scenario::load(variant("flat-drop.toml", "tumble-euler", tumble)).unwrap();
    let mut sim = Simulation::new(&sc).unwrap();
    let error = loop {
        match sim.step() {
            Ok(()) if sim.finished() => panic!("the Euler angles went through θy = 90°"),
            Ok(()) => {}
            Err(e) => break e.to_string(),
        }
    };
    assert!(
        error.contains("singularity") && error.contains("quaternion"),
        "{error}"
    );
    let (sim, s) = run(
        "flat-drop.toml",
        "tumble-quaternion",
        &format!("{tumble}attitude = \"quaternion\"\n"),
    );
    assert!(s.t_end_s > 0.399, "ended at {} s", s.t_end_s);
    let e = &s.energy;
    assert!(
        (e.kinetic_j - e.kinetic_initial_j - (-e.potential_change_j)).abs()
            < 1e-6 * e.kinetic_initial_j,
        "{e:?}"
    );
    let omega = 5.0;
    let (sn, cs) = (omega * s.t_end_s).sin_cos();
    let expected = Matrix3::new(cs, 0.0, sn, 0.0, 1.0, 0.0, -sn, 0.0, cs);
    let t_bi = touchdown_frames::t_bi(&sim.vehicle().euler.theta);
    assert!((t_bi - expected).abs().max() < 1e-9, "{t_bi} vs {expected}");
    assert!((sim.vehicle().omega - Vector3::new(0.0, omega, 0.0)).norm() < 1e-12);
}

/// The report's predictor-corrector integrates Euler angles: asked for a quaternion, the
/// scenario is refused, naming the field.
#[test]
fn the_reports_scheme_refuses_the_quaternion_attitude() {
    let path = variant(
        "flat-drop.toml",
        "report-quaternion",
        "[integrator]\nattitude = \"quaternion\"\n",
    );
    let e = Scenario::load(&path).unwrap_err().to_string();
    assert!(
        e.contains("integrator.attitude") && e.contains("rk4") && e.contains("report-quaternion"),
        "{e}"
    );
}

/// The `strides` scheme (docs/errata.md, "Long strides where the gear is soft") on every
/// bundled landing it applies to (none on soil or beside curbs), against the report's scheme
/// eight times finer (DIST and dt_max ÷ 8): the same outcome; the largest primary stroke within
/// 1 % of the stroke, or twice the report's own error at its settings where that is larger; the
/// energy balance within 0.5 % of its scale, or 1.5 times the report's residual where that is
/// larger; and never more steps than the report's scheme. The strides are not more accurate
/// than the report's steps: the widest when written, `fig-25-26` at 3.8 % against the report's
/// 2.2 % (neither converged by ÷ 8 on its late rocking onto its uphill legs) and
/// `table-i-1-2-1-vv5` at 0.65 % against 0.30 % (`cargo test --test integration strides_scheme
/// -- --nocapture` prints every landing's).
#[test]
fn the_strides_scheme_lands_every_bundled_landing_as_closely_as_the_reports() {
    let largest = |s: &Summary| s.max_primary_stroke_m.iter().copied().fold(0.0, f64::max);
    let residual = |s: &Summary| (s.energy_residual_j / s.energy.scale()).abs();
    let mut landed = vec![];
    for name in touchdown_tests::bundled_landings() {
        let sc = Scenario::load(touchdown_tests::scenario(&name)).unwrap();
        let Ok(strided) = sc.clone().with_integrator(|it| it.scheme = Scheme::Strides) else {
            continue;
        };
        let fine = sc.clone().with_integrator(|it| it.refine(8.0)).unwrap();
        let land = |sc: &Scenario| touchdown_core::run(sc).unwrap_or_else(|e| panic!("{e}"));
        let (report, fine, strides) = (land(&sc), land(&fine), land(&strided));
        let error = |s: &Summary| (largest(s) - largest(&fine)).abs() / largest(&fine);
        eprintln!(
            "{name}: steps {} / {}, largest primary off by {:.3} % / {:.3} %, residual {:.2e} / {:.2e} (report / strides)",
            report.steps,
            strides.steps,
            100.0 * error(&report),
            100.0 * error(&strides),
            residual(&report),
            residual(&strides)
        );
        assert_eq!(strides.outcome, fine.outcome, "{name}");
        assert!(
            error(&strides) <= (2.0 * error(&report)).max(1e-2),
            "{name}: largest primary off by {} against the report's {}",
            error(&strides),
            error(&report)
        );
        assert!(
            residual(&strides) <= (1.5 * residual(&report)).max(5e-3),
            "{name}: residual {} against the report's {}",
            residual(&strides),
            residual(&report)
        );
        assert!(strides.steps <= report.steps, "{name}");
        landed.push(name);
    }
    assert!(landed.len() >= 20, "{landed:?}");
}
