//! Froude twins: the 1/6-scale model and the same vehicle six times as large under a sixth of
//! the gravity (`[similarity]` length 6, time 6, mass 216: the drop-test model at full scale on
//! the Moon) land alike on every engine, within that engine's own step convergence: the twin
//! differs from the model by no more than the model does from itself at half its step
//! (docs/engines.md, "Step and contact from the scenario's scale").

use touchdown_record::Summary;
use touchdown_registry::{time_step, Engine};
use touchdown_scenario::Scenario;
use touchdown_tests::{mujoco, variant, FROUDE_TWIN};

const LENGTH: f64 = 6.0;
const TIME: f64 = 6.0;
const BASE: &str = "fig-25-26.toml";
/// The landing's first 0.3 s: first contact at 0.053 s, every maximum, the pitch-rate peak at
/// 0.057 s and the stops' engagement; the twin's window is six times as long.
const WINDOW: &str = "[integrator]\nt_end = 0.3\n";

/// The landing's measures in the model's dimensions, each a list over the legs or struts:
/// a twin's lengths divided by [`LENGTH`], its rates multiplied by [`TIME`].
fn measures(s: &Summary, length: f64, time: f64) -> [(&'static str, Vec<f64>); 7] {
    let flat = |v: &[[f64; 2]]| v.iter().flatten().map(|x| x / length).collect();
    [
        (
            "maximum primary strokes",
            s.max_primary_stroke_m.iter().map(|x| x / length).collect(),
        ),
        (
            "maximum secondary tensions",
            flat(&s.max_secondary_tension_m),
        ),
        (
            "maximum secondary compressions",
            flat(&s.max_secondary_compression_m),
        ),
        (
            "minimum stability distance",
            vec![s.min_stability_distance_m / length],
        ),
        ("peak pitch rate", vec![s.peak_pitch_rate_rad_s * time]),
        (
            "pitch rate extremes",
            vec![s.min_pitch_rate_rad_s * time, s.max_pitch_rate_rad_s * time],
        ),
        (
            "peak specific force",
            vec![s.peak_specific_force_m_s2 * time * time / length],
        ),
    ]
}

/// For each measure, the largest difference between `a` and `b` over its entries as a
/// fraction of the largest magnitude of `a`'s.
fn differences(
    a: &[(&'static str, Vec<f64>)],
    b: &[(&'static str, Vec<f64>)],
) -> Vec<(&'static str, f64)> {
    a.iter()
        .zip(b)
        .map(|((name, x), (_, y))| {
            let scale = x.iter().fold(0.0_f64, |m, v| m.max(v.abs())).max(1e-300);
            let d = x
                .iter()
                .zip(y)
                .fold(0.0_f64, |m, (p, q)| m.max((p - q).abs()));
            (*name, d / scale)
        })
        .collect()
}

/// The twin's difference from the model is within the model's own step convergence (its
/// difference at half the step), measure by measure, and the outcome is the same.
fn assert_twins(engine: &str, model: &Summary, half_step: &Summary, twin: &Summary) {
    assert_eq!(model.outcome, twin.outcome, "{engine}: outcome");
    let m = measures(model, 1.0, 1.0);
    let step = differences(&m, &measures(half_step, 1.0, 1.0));
    let similar = differences(&m, &measures(twin, LENGTH, TIME));
    let table: Vec<String> = step
        .iter()
        .zip(&similar)
        .map(|((name, s), (_, t))| {
            format!(
                "{name}: twin {:.4} %, half step {:.4} %",
                100.0 * t,
                100.0 * s
            )
        })
        .collect();
    eprintln!("{engine}: {}", table.join("; "));
    for ((name, s), (_, t)) in step.iter().zip(&similar) {
        assert!(
            *t <= s.max(1e-9),
            "{engine}: the Froude twin's {name} differs by more than the step convergence\n{}",
            table.join("\n")
        );
    }
}

/// The core's model, its half step and its twin with the integrator table `integrator` (the
/// TOML lines after `[integrator]`), the twin within the step convergence.
fn core_twins(engine: &str, integrator: &str) {
    let window = format!("{WINDOW}{integrator}");
    let model = Scenario::load(variant(BASE, &format!("{engine}-model"), &window)).unwrap();
    let half = model
        .clone()
        .with_integrator(|it| {
            it.dt_max /= 2.0;
            it.dist /= 2.0;
        })
        .unwrap();
    let twin = Scenario::load(variant(BASE, engine, &format!("{FROUDE_TWIN}{window}"))).unwrap();
    assert_eq!(twin.vehicle.gravity * LENGTH, model.vehicle.gravity);
    let run = |sc: &Scenario| touchdown_core::run(sc).unwrap();
    assert_twins("core", &run(&model), &run(&half), &run(&twin));
}

#[test]
fn froude_twins_land_alike_on_the_core() {
    core_twins("twin-core", "");
}

/// The `strides` scheme's step comes from the gear's stiffness and mobility
/// (docs/errata.md, "Long strides where the gear is soft"), in the vehicle's own scale: its
/// twin lands as its model does too.
#[test]
fn froude_twins_land_alike_on_the_core_in_strides() {
    core_twins("twin-core-strides", "scheme = \"strides\"\n");
}

#[test]
fn froude_twins_land_alike_on_the_rapier_rebuild() {
    let model = Scenario::load(variant(BASE, "twin-rapier-model", WINDOW)).unwrap();
    let step = time_step(Engine::Rapier, &model).unwrap();
    let half = model
        .clone()
        .with_rapier(|r| r.timestep = Some(step / 2.0))
        .unwrap();
    let twin = Scenario::load(variant(
        BASE,
        "twin-rapier",
        &format!("{FROUDE_TWIN}{WINDOW}"),
    ))
    .unwrap();
    let twin_step = time_step(Engine::Rapier, &twin).unwrap();
    assert!((twin_step / step - TIME).abs() < 1e-12, "{twin_step} s");
    let run = |sc: &Scenario| touchdown_rapier::run(sc).unwrap();
    assert_twins("rapier", &run(&model), &run(&half), &run(&twin));
}

#[test]
fn froude_twins_land_alike_on_mujoco() {
    let model_path = variant(BASE, "twin-mujoco-model", WINDOW);
    let step = time_step(Engine::Mujoco, &Scenario::load(&model_path).unwrap()).unwrap();
    let half_path = variant(
        BASE,
        "twin-mujoco-half-step",
        &format!("{WINDOW}[engines.mujoco]\ntimestep = {:e}\n", step / 2.0),
    );
    let twin_path = variant(BASE, "twin-mujoco", &format!("{FROUDE_TWIN}{WINDOW}"));
    assert_twins(
        "MuJoCo",
        &mujoco(&model_path, "twin-model"),
        &mujoco(&half_path, "twin-half"),
        &mujoco(&twin_path, "twin"),
    );
}

#[test]
fn a_similar_vehicle_is_every_quantity_scaled_by_its_dimensions() {
    let model = Scenario::load(variant(BASE, "twin-units-model", "")).unwrap();
    let twin = Scenario::load(variant(BASE, "twin-units", FROUDE_TWIN)).unwrap();
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * a.abs().max(b.abs());
    assert!(close(twin.vehicle.mass, 216.0 * model.vehicle.mass));
    assert!(close(
        twin.vehicle.inertia[(1, 1)],
        216.0 * 36.0 * model.vehicle.inertia[(1, 1)]
    ));
    assert!(close(twin.vehicle.gravity, model.vehicle.gravity / 6.0));
    assert!(close(twin.legs[0].l2p, 6.0 * model.legs[0].l2p));
    assert!(close(twin.integrator.t_end, 6.0 * model.integrator.t_end));
    // Velocities of a Froude twin are the model's; angular rates a sixth.
    assert!(close(
        twin.touchdown.velocity_g.z,
        model.touchdown.velocity_g.z
    ));
    assert!(close(
        twin.touchdown.body_rates.y,
        model.touchdown.body_rates.y / 6.0
    ));
    // Forces scale as mass·length/time² = 36, stiffnesses as mass/time² = 6.
    let (a, b) = (&model.primary.compression, &twin.primary.compression);
    assert!(close(b.onset_rate, 6.0 * a.onset_rate));
    // Settings a file leaves out are derived from its scale: the robotic lander states none,
    // and its twin's are its own in the twin's time.
    let lander = Scenario::load(variant(
        "robotic-lander-nominal.toml",
        "twin-derived-model",
        "",
    ))
    .unwrap();
    let lander_twin = Scenario::load(variant(
        "robotic-lander-nominal.toml",
        "twin-derived",
        FROUDE_TWIN,
    ))
    .unwrap();
    for engine in [Engine::Rapier, Engine::Mujoco] {
        let (a, b) = (
            time_step(engine, &lander).unwrap(),
            time_step(engine, &lander_twin).unwrap(),
        );
        assert!(close(b, TIME * a), "{engine}: {a} s and {b} s");
    }
    // A bad ratio is refused naming its field.
    let e = Scenario::load(variant(
        BASE,
        "twin-bad",
        "[similarity]\nlength = 0.0\nmass = 1.0\ntime = 1.0\n",
    ))
    .unwrap_err()
    .to_string();
    assert!(e.contains("similarity.length"), "{e}");
}
