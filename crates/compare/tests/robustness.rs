//! The reduced stiff and extreme catalogue (docs/robustness.md) and the work-precision study
//! (docs/performance.md): every run completes with a bounded energy balance and strokes within
//! the struts, or stops with a diagnostic that names the time and the law; never a garbage
//! result.

use touchdown_compare::precision::{self, Method, REFERENCE_STROKE_AGREEMENT};
use touchdown_compare::robustness::{self, Verdict, CATALOGUE};
use touchdown_compare::Engine;

fn scenarios() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios")
}

#[test]
fn every_case_completes_or_stops_with_a_named_cause_on_the_core() {
    let r =
        robustness::run_catalogue(&scenarios(), CATALOGUE, &[Engine::Core], false, |_| {}).unwrap();
    assert_eq!(r.runs.len(), CATALOGUE.len());
    for run in &r.runs {
        match run.verdict {
            Verdict::Completed => {
                let e = run.energy_residual.unwrap();
                assert!(
                    e.is_finite() && e.abs() <= 0.02,
                    "{}: residual {e}",
                    run.case
                );
            }
            Verdict::Stopped => {
                let m = run.message.as_deref().unwrap();
                assert!(
                    m.contains("simulation stopped at t =") && m.contains("state:"),
                    "{}: {m}",
                    run.case
                );
            }
            v => panic!("{}: {v:?}: {:?}", run.case, run.message),
        }
    }
    // ×100 completes at the default step; ×1000 sits at the edge of it (its largest stable step
    // is the default one: the_largest_stable_step_is_bracketed_by_a_named_failure).
    let verdict = |name: &str| r.runs.iter().find(|x| x.case == name).unwrap();
    assert_eq!(verdict("onset-x100").verdict, Verdict::Completed);
    // Bottoming: the primaries go past their capacity on the elastic stop, a little.
    let out = verdict("vv-30").primary_stroke_over_capacity.unwrap();
    assert!((1.0..1.2).contains(&out), "{out}");
}

#[test]
fn the_overturn_passes_theta_y_90_degrees_with_the_quaternion_attitude() {
    let case = CATALOGUE
        .iter()
        .find(|c| c.name == "overturn-through-90")
        .unwrap();
    let (path, sc) = case.scenario(&scenarios()).unwrap();
    let run = touchdown_compare::run(Engine::Core, &path, &sc).unwrap();
    let peak = run
        .trace
        .attitude
        .iter()
        .map(|a| a[1])
        .fold(0.0f64, f64::max);
    // The trace's samples straddle 90° (its largest θy is that of the sample nearest it).
    assert!(peak > 1.56, "θy peaks at {peak} rad");
    // Past 90° the Euler angles flip: θx and θz jump to ±π while θy comes back down.
    let last = run.trace.attitude.last().unwrap();
    assert!(last[0].abs() > 3.0 && last[2].abs() > 3.0, "{last:?}");
}

#[test]
fn cheap_cases_complete_or_stop_with_a_named_cause_on_the_multibody_engines() {
    let cases: Vec<_> = CATALOGUE
        .iter()
        .filter(|c| ["attitude-30", "onset-x1000", "vv-30"].contains(&c.name))
        .copied()
        .collect();
    let r = robustness::run_catalogue(
        &scenarios(),
        &cases,
        &[Engine::Rapier, Engine::Mujoco],
        false,
        |_| {},
    )
    .unwrap();
    assert_eq!(r.runs.len(), 6);
    for run in &r.runs {
        assert_ne!(run.verdict, Verdict::Failed, "{run:?}");
        if run.verdict != Verdict::Completed {
            assert!(!run.message.as_deref().unwrap_or("").is_empty(), "{run:?}");
        }
        // The bottomed struts throw the vehicle back up onto its primaries' extension stops.
        // An elastic stop, hit explicitly at 20 µs, cost the balance more than the guard
        // allows; the stops' restitution (docs/errata.md, "End stops") takes that energy out
        // as dissipation, and both engines complete within the balance tolerance.
        if run.case == "vv-30" {
            assert_eq!(run.verdict, Verdict::Completed, "{run:?}");
            let e = run.energy_residual.unwrap();
            assert!(e.abs() <= 0.02, "{run:?}");
        }
    }
}

#[test]
fn the_largest_stable_step_is_bracketed_by_a_named_failure() {
    let case = CATALOGUE.iter().find(|c| c.name == "onset-x1000").unwrap();
    let (path, sc) = case.scenario(&scenarios()).unwrap();
    // The report's scheme lands this case at its default step and is stopped at some
    // multiple of it by a named law, with the time and the state (docs/robustness.md).
    let s = robustness::largest_stable_step(case.name, &path, &sc, Method::Report);
    let dt = s.largest_stable_step_s.expect("a stable step");
    assert!(dt >= s.default_step_s.expect("a default step"), "{s:?}");
    let (above, why) = s.first_unstable.expect("an unstable step above it");
    assert!((above / dt - 2.0).abs() < 1e-9, "{dt} {above}");
    let law = why
        .split("simulation stopped at t =")
        .nth(1)
        .and_then(|rest| rest.split_once(" s in "))
        .map(|(_, law)| law);
    assert!(
        law.is_some_and(|l| !l.is_empty()) && why.contains("; state: R ="),
        "{why}"
    );
}

#[test]
fn work_precision_has_a_converged_reference_and_converging_ladders() {
    let path = scenarios().join("flat-drop.toml");
    let w = precision::work_precision(
        &path,
        &[Method::Report, Method::Rk4, Method::Dopri5],
        Some(3),
        1,
        |_| {},
    )
    .unwrap();
    let a = w.reference.agreement;
    assert!(a.max_stroke <= REFERENCE_STROKE_AGREEMENT, "{a:?}");
    // The flat drop comes to rest: its reference resolves the pitch rate and attitude too.
    assert!(
        a.pitch_rate_rms <= 1e-3 && a.final_attitude_rad <= 1e-5,
        "{a:?}"
    );
    assert_eq!(w.rungs.len(), 9);
    let errors: Vec<f64> = w
        .rungs
        .iter()
        .map(|r| {
            r.measured
                .as_ref()
                .expect("every rung runs")
                .errors
                .max_stroke
        })
        .collect();
    // The report's scheme and RK4 converge as their steps shrink.
    assert!(errors[2] < errors[0], "report: {errors:?}");
    assert!(errors[5] < errors[3], "rk4: {errors:?}");
    assert!(
        errors.iter().all(|e| e.is_finite() && *e < 0.05),
        "{errors:?}"
    );
    // Each method's cheapest rung within 1 % is found, the fastest has ratio 1.
    assert_eq!(w.at_error.len(), 3);
    let ratios: Vec<f64> = w
        .at_error
        .iter()
        .filter_map(|x| x.ratio_to_fastest)
        .collect();
    assert!(ratios.contains(&1.0), "{ratios:?}");
    assert!(precision::text(&w).contains("core dopri5"));
}

#[test]
fn footpads_sinking_into_a_soft_contact_fail_the_checks() {
    // rapier's contact at 100 Hz instead of 5 kHz: the footpads sink 2.4 mm into the ground
    // (a hundred times as deep), the balance still closes (the contact's work is booked), and the run
    // must not pass as completed.
    let path = scenarios().join("flat-drop.toml");
    let sc = touchdown_scenario::Scenario::load(&path)
        .unwrap()
        .with_rapier(|r| r.contact_frequency = Some(100.0))
        .unwrap();
    let run = robustness::classify("soft-contact", &path, &sc, Engine::Rapier);
    assert_eq!(run.verdict, Verdict::Failed, "{run:?}");
    let m = run.message.as_deref().unwrap();
    assert!(m.contains("into its surface"), "{m}");
    // At the default 5 kHz it completes.
    let sc = touchdown_scenario::Scenario::load(&path).unwrap();
    let run = robustness::classify("flat-drop", &path, &sc, Engine::Rapier);
    assert_eq!(run.verdict, Verdict::Completed, "{run:?}");
}

#[test]
fn a_multibody_step_refused_only_for_its_size_is_searched_downward() {
    // Rates ×100 make rapier's own 20 µs step too large for the stiffest explicit strut law,
    // a refusal when the scenario is read; the search halves it to a step that lands rather
    // than calling rapier inapplicable (docs/robustness.md, "Largest stable step"). A short
    // landing keeps the test fast: the refusal does not depend on the end time.
    let case = CATALOGUE.iter().find(|c| c.name == "onset-x100").unwrap();
    let (path, sc) = case.scenario(&scenarios()).unwrap();
    let sc = sc.with_integrator(|it| it.t_end = 0.02).unwrap();
    let s = robustness::largest_stable_step(case.name, &path, &sc, Method::Rapier);
    assert!(s.refused.is_none(), "{s:?}");
    let default = s.default_step_s.expect("rapier's own step");
    let dt = s.largest_stable_step_s.expect("a step that lands");
    assert!(dt < default, "{s:?}");
    let above = s
        .first_unstable
        .as_ref()
        .expect("the step above it is refused")
        .0;
    assert!((above / dt - 2.0).abs() < 1e-9, "{s:?}");
}

/// The `strides` scheme (docs/errata.md, "Long strides where the gear is soft") on every case
/// of the catalogue it applies to (not on soil; a quaternion attitude needs a Runge–Kutta
/// scheme): it ends each as the report's scheme does, completed with the same outcome and a
/// residual within 0.5 % of the energy scale, or stopped with a named cause; and it takes the
/// stiff gear in its stride, where the report's scheme shortens its steps with the stiffness.
#[test]
fn the_strides_scheme_ends_every_case_as_the_reports_scheme_does() {
    use touchdown_scenario::schema::Scheme;
    let mut steps = std::collections::BTreeMap::new();
    let mut landed = 0;
    for case in CATALOGUE {
        let (path, sc) = case.scenario(&scenarios()).unwrap();
        let Ok(strided) = sc.clone().with_integrator(|it| it.scheme = Scheme::Strides) else {
            continue;
        };
        landed += 1;
        let report = robustness::classify(case.name, &path, &sc, Engine::Core);
        let run = robustness::classify(case.name, &path, &strided, Engine::Core);
        assert_eq!(run.verdict, report.verdict, "{}: {run:?}", case.name);
        match run.verdict {
            Verdict::Completed => {
                assert_eq!(run.outcome, report.outcome, "{}", case.name);
                let e = run.energy_residual.unwrap();
                assert!(e.abs() <= 0.005, "{}: residual {e}", case.name);
            }
            _ => assert!(
                run.message
                    .as_deref()
                    .unwrap()
                    .contains("simulation stopped at t ="),
                "{run:?}"
            ),
        }
        steps.insert(case.name, (report.steps, run.steps));
    }
    eprintln!("steps (report, strides): {steps:?}");
    assert!(landed >= 12, "{steps:?}");
    // From onset rates ×100 to ×1000 the report's scheme shortens its steps to follow the
    // stiffer gear, the strides do not: 13,288 → 31,442 steps against 7,632 → 7,667. (Written
    // as "4× fewer steps at ×1000", the test passed by a margin rounding decides: before the
    // 2-2 landing was made its own mirror image, docs/errata.md "The 2-2 landing, its own
    // mirror image", the report's scheme took 13,791 → 55,393 steps and the strides 7,633 →
    // 7,719; with that change and the old calibration 31,021 steps at ×1000 against 7,794,
    // failing it by 0.5 %.)
    let growth = |name: &str| {
        let (report, strided) = steps[name];
        (report.unwrap() as f64, strided.unwrap() as f64)
    };
    let (report_100, strided_100) = growth("onset-x100");
    let (report_1000, strided_1000) = growth("onset-x1000");
    assert!(report_1000 > 2.0 * report_100, "{steps:?}");
    assert!(strided_1000 < 1.25 * strided_100, "{steps:?}");
}
