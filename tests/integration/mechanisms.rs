//! The optional mechanisms of the core (docs/model.md): each scenario in `scenarios/` that declares one,
//! checked against an analytic or limiting case, and the proof that a mechanism a scene leaves
//! out is never built nor evaluated.

use nalgebra::Vector3;
use std::path::Path;
use touchdown_core::{Landing, Simulation};
use touchdown_laws::scene::curbs_from_scenario;
use touchdown_laws::{CrushMemory, Curbs};
use touchdown_mujoco::Launch;
use touchdown_rapier::RapierSimulation;
use touchdown_record::{History, Summary};
use touchdown_scenario::model::{LoadStroke, Mechanism};
use touchdown_scenario::schema::{Detached, Engine};
use touchdown_scenario::Scenario;
use touchdown_tests::{scenario, set_down_on_a_slope, variant, SLOPE_DEG};

const FT: f64 = 0.3048;
const LBF: f64 = 4.448_221_615_260_5;

fn load(name: &str, overrides: &[(&str, f64)]) -> Scenario {
    Scenario::load_with(scenario(name), overrides).expect("scenario loads")
}

/// The whole multibody's mass on rapier and MuJoCo, kg: the vehicle and, on every leg, the
/// footpad and its outer-cylinder link (`engines.links.outer_cylinder_mass_ratio` of it).
fn multibody_mass(sc: &Scenario) -> f64 {
    let link = sc.footpad.mass * (1.0 + sc.links.outer_cylinder_mass_ratio);
    sc.vehicle.mass + sc.legs.len() as f64 * link
}

/// The whole mass the thrust moves on `engine`, kg: the vehicle and its footpads, and on rapier
/// and MuJoCo their outer-cylinder links besides.
fn moving_mass(engine: Engine, sc: &Scenario) -> f64 {
    match engine {
        Engine::Core => sc.vehicle.mass + sc.legs.len() as f64 * sc.footpad.mass,
        _ => multibody_mass(sc),
    }
}

/// A variant `name` of `thrust-tailoff.toml` whose primaries are vertical (R3 = R1, fig. 23),
/// under thrust `thrust` (N) not amplified near the ground, with `extra` TOML, which begins in
/// the `[thrust]` table (its tailoff): the lander whose footpads hang on their struts of the
/// extension-stop and held-friction oracles.
fn hanging_footpads(name: &str, thrust: f64, extra: &str) -> std::path::PathBuf {
    let sc = load("thrust-tailoff.toml", &[]);
    let r1 = sc.legs[0].b2.xy().norm() / FT; // ft, the file's unit
    variant(
        "thrust-tailoff.toml",
        name,
        &format!(
            "[gear.parametric]\nr3 = {r1:.17e}\n\
             [thrust.amplification]\nclearance = [0.0, 1.0]\nfactor = [1.0, 1.0]\n\
             [thrust]\nthrust = {:.17e}\n{extra}",
            thrust / LBF
        ),
    )
}

fn run(sc: &Scenario) -> Simulation {
    let mut sim = Simulation::new(sc).expect("core builds");
    while !sim.finished() {
        sim.step().expect("core steps");
    }
    sim
}

/// A scene without optional mechanisms builds none; a scene with the descent engine evaluates
/// it (and its nozzle) once per force evaluation and nothing else.
#[test]
fn absent_mechanisms_are_never_built_nor_evaluated() {
    let sim = run(&load("flat-drop.toml", &[]));
    let m = sim.mechanisms();
    assert!(m.propulsion.is_empty() && m.slosh.is_none());
    assert!(m.soil.is_none() && m.curbs.is_none() && m.bending.is_none());
    assert!(sim.mechanism_evaluations().is_empty());
    assert!(sim.summary().mechanisms.is_empty());
    assert_eq!(sim.summary().energy.mechanisms_j, 0.0);

    let sim = run(&load("thrust-tailoff.toml", &[]));
    let evaluations = sim.summary().force_evaluations;
    assert_eq!(
        sim.mechanism_evaluations(),
        vec![
            (Mechanism::Thrust, evaluations),
            (Mechanism::NozzleCrushing, evaluations)
        ]
    );
}

/// Thrust equal to the weight with unit amplification holds the vehicle in hover (eqs. 69-74):
/// released 0.2 ft above the ground at rest with its footpads riding rigidly, it neither falls
/// nor rises. With footpads of their own mass the thrust carries the vehicle but not the
/// footpads: they settle on their struts' extension stops, and the lander's momentum is what
/// their weight gave it, −n·PMASS·g·t, with no stop on the energy guard while the energy put
/// in is smaller than the guard's floor (docs/errata.md, "Energy guard").
#[test]
fn thrust_equal_to_weight_holds_the_vehicle_in_hover() {
    let mut sc = load(
        "thrust-tailoff.toml",
        &[
            ("touchdown.vertical_velocity", 0.0),
            ("touchdown.clearance", 0.2),
            ("thrust.tailoff_start", 100.0),
            ("thrust.amplification.factor[0]", 1.0),
            ("thrust.amplification.factor[1]", 1.0),
            ("thrust.amplification.factor[2]", 1.0),
        ],
    );
    assert_eq!(sc.footpad.detached, Detached::Inertial, "the default");
    let mut sim = Simulation::new(&sc).unwrap();
    // The largest sine of the vehicle's tilt: the thrust, along its body z axis, has a lateral
    // part no larger than M·g times it.
    let mut tilt: f64 = 0.0;
    while !sim.finished() {
        sim.step().unwrap();
        tilt = tilt.max((sim.vehicle().t_bi * Vector3::z()).xy().norm());
    }
    let momentum = sc.vehicle.mass * sim.vehicle().velocity
        + sim
            .footpads()
            .iter()
            .map(|p| sc.footpad.mass * p.velocity)
            .sum::<Vector3<f64>>();
    let weight = sc.legs.len() as f64 * sc.footpad.mass * sc.vehicle.gravity;
    assert!(sim.time() > 0.09);
    let lateral = sc.vehicle.mass * sc.vehicle.gravity * sim.time() * tilt;
    assert!(
        (momentum.z + weight * sim.time()).abs() < 1e-6 * weight * sim.time()
            && momentum.xy().norm() <= lateral * (1.0 + 1e-6) + 1e-12,
        "{momentum:?} against {} (lateral bound {lateral:.3e})",
        -weight * sim.time()
    );
    assert!(sim.footpads().iter().all(|p| p.first_contact.is_none()));

    sc.footpad.detached = Detached::Rigid;
    let mut sim = Simulation::new(&sc).unwrap();
    let z0 = sim.vehicle().position.z;
    while !sim.finished() {
        sim.step().unwrap();
    }
    let v = sim.vehicle();
    assert!(sim.time() > 0.09);
    assert!((v.position.z - z0).abs() < 1e-9, "{}", v.position.z - z0);
    assert!(v.velocity.norm() < 1e-9 && v.acceleration.norm() < 1e-9);
    assert!(sim.footpads().iter().all(|p| p.first_contact.is_none()));
}

/// RCS (eqs. 75-80) in free flight with a yaw rate and rate gains only: the yaw torque fires
/// while k·ωz is outside the deadband, so ωz falls at TORQZ/Izz, and stops within one step of
/// the deadband's edge, where it stays. The footpads ride rigidly, so that the vehicle is one
/// rigid body turning at TORQZ/Izz.
#[test]
fn rcs_fires_outside_its_deadband_and_stops_inside() {
    let mut sc = load(
        "rcs-attitude-hold.toml",
        &[
            ("touchdown.clearance", 1.0),
            ("touchdown.vertical_velocity", 0.0),
            ("touchdown.horizontal_velocity[1]", 0.0),
            ("touchdown.attitude[1]", 0.0),
            ("touchdown.body_rates[2]", 60.0),
            ("rcs.attitude_gain[0]", 0.0),
            ("rcs.attitude_gain[1]", 0.0),
            ("rcs.attitude_gain[2]", 0.0),
            ("rcs.rate_gain[2]", 0.5),
            ("rcs.deadband[2]", 2.0),
            ("rcs.torque[2]", 10.0),
            ("integrator.t_end", 0.2),
        ],
    );
    sc.footpad.detached = Detached::Rigid;
    let alpha = 10.0 * LBF * FT / sc.vehicle.inertia[(2, 2)];
    let edge = 2.0f64.to_radians() / 0.5;
    let w0 = 60.0f64.to_radians();
    let dt_max = sc.integrator.dt_max;
    let mut sim = Simulation::new(&sc).unwrap();
    let mut stopped = None;
    while !sim.finished() {
        sim.step().unwrap();
        let (t, w) = (sim.time(), sim.vehicle().omega.z);
        if stopped.is_none() && w > edge {
            // Linear at TORQZ/Izz, except in the step where the torque switches off (the
            // corrector averages the torque at both ends of that step).
            let off_linear = (w - (w0 - alpha * t)).abs();
            assert!(
                off_linear < 1e-6 || w - edge < alpha * dt_max,
                "t = {t}: {w}"
            );
        } else {
            let w_stop = *stopped.get_or_insert(w);
            assert!(
                w <= edge && w > edge - alpha * dt_max * 1.01,
                "{w} vs {edge}"
            );
            assert!((w - w_stop).abs() < 1e-9, "inside the deadband: no torque");
        }
    }
    assert!(stopped.is_some(), "the rate reached the deadband");
    assert!(sim.footpads().iter().all(|p| p.first_contact.is_none()));
}

/// A slosh mass in hover (thrust = weight, the liquid pressed to the tank floor at 1 g) on a
/// vehicle made rotationally stiff oscillates at the two-body frequency of eq. (109)'s spring,
/// ω_n·√(1 + M_s/M_r), ω_n² = ω²·g (eqs. 108-112). The footpads ride rigidly, so that the
/// vehicle is the one rigid body of the two-body frequency.
#[test]
fn a_free_slosh_oscillates_at_its_natural_frequency() {
    let dir = std::env::temp_dir().join(format!("touchdown-slosh-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("hover.toml");
    let parent = scenario("slosh-drop.toml");
    std::fs::write(
        &file,
        format!(
            r#"schema_version = 1
extends = "{}"
name = "slosh in hover"
[vehicle]
inertia = {{ xx = 1.0e6, yy = 1.0e6, zz = 0.994 }}
[footpad]
detached = "rigid"
[touchdown]
vertical_velocity = 0.0
horizontal_velocity = [0.0, 0.5]
clearance = 0.5
[slosh]
initial_amplitude = [0.02, 0.0]
[thrust]
thrust = 64.348
tailoff_start = 100.0
polynomial = [64.348]
nozzle_exit = [0.0, 0.0, -0.8]
[integrator]
t_end = 0.6
"#,
            parent.display()
        ),
    )
    .unwrap();
    let sc = Scenario::load(&file).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    let p = sc.slosh.unwrap();
    let ms = p.force_coefficient / p.frequency_parameter;
    let mr = sc.vehicle.mass - ms;
    let wn = (p.frequency_parameter * sc.vehicle.gravity).sqrt();
    let expected = wn * (1.0 + ms / mr).sqrt();
    let mut sim = Simulation::new(&sc).unwrap();
    let mut crossings = Vec::new();
    let mut last = (sim.time(), sim.vehicle().slosh_q.x);
    while !sim.finished() {
        sim.step().unwrap();
        let now = (sim.time(), sim.vehicle().slosh_q.x);
        if last.1 * now.1 < 0.0 {
            crossings.push(last.0 + (now.0 - last.0) * last.1 / (last.1 - now.1));
        }
        last = now;
    }
    assert!(crossings.len() >= 4, "{crossings:?}");
    let half_periods = (crossings.len() - 1) as f64;
    let measured = std::f64::consts::PI * half_periods / (crossings.last().unwrap() - crossings[0]);
    assert!(
        (measured / expected - 1.0).abs() < 2e-3,
        "{measured} vs {expected} rad/s"
    );
    assert!(sim.footpads().iter().all(|p| p.first_contact.is_none()));
}

/// Footpads landing on soil (eqs. 101-104, rigid-plastic, no rate terms) sink until the bearing
/// AP·(K1 + K2·depth) carries the largest load they have seen, then are held there.
#[test]
fn a_footpad_on_soil_rests_where_bearing_equals_its_largest_load() {
    let sc = load("soil-drop.toml", &[("surface.soil.k3", 0.0)]);
    let soil = sc.surface.soil.unwrap();
    let area = std::f64::consts::PI * sc.footpad.radius.powi(2);
    let weight = sc.footpad.mass * sc.vehicle.gravity;
    let mut sim = Simulation::new(&sc).unwrap();
    let mut largest = [0.0f64; 4];
    while !sim.finished() {
        sim.step().unwrap();
        let t_bi = sim.vehicle().t_bi;
        for (i, g) in sim.gear().iter().enumerate() {
            let fzi = -(t_bi * g.fp).z;
            largest[i] = largest[i].max(fzi + weight);
        }
    }
    for (i, pad) in sim.footpads().iter().enumerate() {
        let depth = -pad.position.z;
        let bearing = area * (soil.k1 + soil.k2 * depth);
        assert!(depth > 0.0 && pad.velocity.z == 0.0, "pad {i} held");
        // The footpad's own momentum at touchdown pushes it a little deeper than the gear load
        // alone would.
        assert!(
            bearing >= largest[i] * (1.0 - 1e-3) && bearing < largest[i] * 1.05,
            "pad {i}: bearing {bearing} N at {depth} m, largest load {} N",
            largest[i]
        );
    }
    let e = sim.summary().energy;
    assert!(e.mechanisms_j > 0.0 && e.residual_j.abs() < 1e-3 * e.kinetic_initial_j);
}

/// The curb-slide scene with frictionless curbs, so that the curbs' work is the crushing's.
const FRICTIONLESS_CURBS: &str = "[[surface.curbs]]\nleg = 1\ndistance = 0.277\nangle = 90.0\n\
     [[surface.curbs]]\nleg = 2\ndistance = 0.277\nangle = 90.0\n\
     [[surface.curbs]]\nleg = 3\ndistance = 0.277\nangle = 90.0\n\
     [[surface.curbs]]\nleg = 4\ndistance = 0.277\nangle = 90.0\n";

/// The virgin area of a footpad crushing table (one stage, then its stroke-out stop) from zero
/// to `x_max`, m: the work of crushing to it, J.
fn virgin_area(sc: &Scenario, x_max: f64, what: &str) -> f64 {
    let table: &LoadStroke = sc.footpad.crush.as_ref().unwrap();
    let (f, end) = table.stages[0];
    let x_a = f / table.onset_rate;
    assert!(x_max > 0.0, "{what}: crush {x_max} m");
    if x_max <= x_a {
        0.5 * table.onset_rate * x_max * x_max
    } else if x_max <= end {
        0.5 * f * x_a + f * (x_max - x_a)
    } else {
        let d = x_max - end;
        0.5 * f * x_a + f * (end - x_a) + f * d + 0.5 * table.stroke_out_rate * d * d
    }
}

/// The work a footpad crushing table takes from a footpad crushed to `x_max` (`memory`, m) and
/// backed off to `x_now` (m) in contact: the virgin area to `x_max` less the elastic energy
/// given back, J.
fn crush_work(sc: &Scenario, curbs: &Curbs, memory: &CrushMemory, x_now: f64, what: &str) -> f64 {
    let x_max = memory.max_stroke();
    virgin_area(sc, x_max, what)
        - (curbs.crush.stored_energy(x_max, *memory) - curbs.crush.stored_energy(x_now, *memory))
}

/// Footpads sliding into curbs (eqs. 86-95) crush as the footpad table says: the energy the run
/// books for the curbs equals the table's crushing work at each curb's largest crush (on its
/// plateau or its stroke-out stop) less the elastic energy the curb gave back pushing its
/// footpad. A footpad with inertia is pushed by its curbs on the surface and off it alike (a
/// curb stands on the surface beside the footpad's first contact point), so a curb's elastic
/// energy is held until it is given back. (A massless footpad that leaves the surface takes no
/// more push: the curb's elastic energy at that moment is not given back, docs/errata.md,
/// "Contact and release"; that case is `rigid_footpads_leaving_curbs_keep_their_energy`.)
#[test]
fn footpads_sliding_into_curbs_crush_as_their_table_says() {
    curbs_crush_as_their_table_says(Detached::Inertial);
}

/// [`footpads_sliding_into_curbs_crush_as_their_table_says`] with the report's massless
/// footpad.
#[test]
fn rigid_footpads_leaving_curbs_keep_their_energy() {
    curbs_crush_as_their_table_says(Detached::Rigid);
}

fn curbs_crush_as_their_table_says(detached: Detached) {
    // one file per test: the two run at once
    let name = format!("core-curbs-{detached:?}");
    let mut sc = Scenario::load(variant("curb-slide.toml", &name, FRICTIONLESS_CURBS))
        .unwrap_or_else(|e| panic!("{e}"));
    sc.footpad.detached = detached;
    let mut sim = Simulation::new(&sc).expect("core builds");
    let r = sc.footpad.radius;
    // Per curb: its elastic energy at the last state its footpad pushed on it, and what a
    // massless footpad's leaving kept of it, J.
    let n = sim.mechanisms().curbs.as_ref().unwrap().list.len();
    let (mut held, mut kept) = (vec![0.0; n], 0.0);
    let pushed = |sim: &Simulation, leg: usize| {
        let pad = &sim.footpads()[leg];
        match detached {
            Detached::Inertial => pad.first_contact.is_some(),
            Detached::Rigid => pad.state == touchdown_core::ContactState::Contact,
        }
    };
    loop {
        let curbs = sim.mechanisms().curbs.as_ref().unwrap();
        let memories = &sim.mechanism_state().curb_memory;
        for (k, ((leg, curb), memory)) in curbs.list.iter().zip(memories).enumerate() {
            let pad = &sim.footpads()[*leg];
            if pushed(&sim, *leg) {
                let xy = nalgebra::Vector2::new(pad.position.x, pad.position.y);
                held[k] = curbs
                    .crush
                    .stored_energy(curb.crush(pad.touchdown_xy, xy, r), *memory);
            } else {
                kept += std::mem::take(&mut held[k]);
            }
        }
        if sim.finished() {
            break;
        }
        sim.step().expect("core steps");
    }
    let curbs = sim.mechanisms().curbs.as_ref().unwrap();
    let mut expected = kept + held.iter().sum::<f64>();
    let memories = &sim.mechanism_state().curb_memory;
    for (((_, _), memory), k) in curbs.list.iter().zip(memories).zip(0..) {
        let x_max = memory.max_stroke();
        // Crushing to x_max, less the elastic energy it holds there: the plastic work.
        expected += virgin_area(&sc, x_max, &format!("curb {k}"))
            - curbs.crush.stored_energy(x_max, *memory);
    }
    // The footpad equations freeze the curb force over a step (eq. 97), so the booked work
    // lags the table's area by the force's change over a step on the stiff onset, at every
    // loading and unloading (docs/errata.md, "Stability decisions and maxima"): within 2 % at
    // the end of the 1.5 s run, over which the rocking vehicle's footpads strike their curbs
    // again and again; measured 0.30 % with inertia, 0.87 % with the massless footpad (11.5 %
    // before the corrections of the contact logic).
    let booked = sim.summary().energy.mechanisms_j;
    assert!(
        (booked / expected - 1.0).abs() < 0.02,
        "{detached:?}: booked {booked} J vs table {expected} J"
    );
}

/// Bending (eqs. 40-48): a very stiff primary strut gives the rigid gear's landing to 1e-6 m;
/// the scenario's EI changes the secondary strokes by far more than that (0.45 mm with the
/// footpad with inertia) and keeps the energy balance. The limit is taken with lossless end
/// stops: a footpad hanging on a stop of restitution 0.5 amplifies any small difference, the
/// bending of EI = 1e11 lbf·ft² as well as a rounding one (docs/errata.md, "End stops"); and
/// over the landing up to its stable conditions, as when runs ended there: the vehicle's
/// rocking after them grows any difference as it grows rounding (2.8e-6 m at 1.5 s;
/// `tests/integration/symmetry.rs`).
#[test]
fn bending_tends_to_the_rigid_strut_and_eases_the_secondaries() {
    let lossless = [
        ("primary_strut.compression.stop_restitution", 1.0),
        ("secondary_strut.tension.stop_restitution", 1.0),
        ("secondary_strut.compression.stop_restitution", 1.0),
    ];
    let landing = run(&load("table-i-2-2-vv8.toml", &lossless))
        .summary()
        .stable_conditions_time_s
        .expect("the lossless landing meets the stable conditions");
    let to_them = [&lossless[..], &[("integrator.t_end", landing)]].concat();
    let rigid = run(&load("table-i-2-2-vv8.toml", &to_them)).summary();
    let stiff = run(&load(
        "bending-2-2-vv8.toml",
        &[&to_them[..], &[("primary_strut.bending.stiffness", 1.0e11)]].concat(),
    ))
    .summary();
    let bent = run(&load("bending-2-2-vv8.toml", &[])).summary();
    for i in 0..4 {
        assert!((stiff.max_primary_stroke_m[i] - rigid.max_primary_stroke_m[i]).abs() < 1e-6);
        for j in 0..2 {
            let d = stiff.max_secondary_tension_m[i][j] - rigid.max_secondary_tension_m[i][j];
            assert!(d.abs() < 1e-6, "leg {i} strut {j}: {d}");
        }
    }
    let rigid = run(&load("table-i-2-2-vv8.toml", &[])).summary();
    let moved = (0..4)
        .flat_map(|i| (0..2).map(move |j| (i, j)))
        .map(|(i, j)| {
            (bent.max_secondary_tension_m[i][j] - rigid.max_secondary_tension_m[i][j]).abs()
        })
        .fold(0.0, f64::max);
    assert!(
        moved > 1e-4,
        "bending moved the secondary strokes by {moved} m"
    );
    let e = &bent.energy;
    assert!(
        e.residual_j.abs() < 0.02 * e.kinetic_initial_j,
        "residual {} J of {} J",
        e.residual_j,
        e.kinetic_initial_j
    );
}

/// Trunnion springs on raw diagrams (eqs. 35-39) land exactly as the diagrams modified by hand:
/// onset, backoff and stroke-out rates in series with K_T, every stage end moved by F/K_T.
#[test]
fn trunnion_springs_equal_the_hand_modified_diagrams() {
    let springs = load("trunnion-springs.toml", &[]);
    let mut by_hand = load("table-i-2-2-vv8.toml", &[]);
    let modify = |ls: &mut LoadStroke, k: f64| {
        let series = |a: f64| a * k / (a + k); // eqs. (35)-(36)
        ls.onset_rate = series(ls.onset_rate);
        ls.backoff_rate = series(ls.backoff_rate);
        ls.stroke_out_rate = series(ls.stroke_out_rate);
        for (f, x) in &mut ls.stages {
            *x += *f / k; // eqs. (37)-(39), every stage (docs/errata.md, "Eqs. (35)-(39): trunnion modification — generalised")
        }
    };
    let (kp, ks) = (
        springs.primary.trunnion_rate.unwrap(),
        springs.secondary.trunnion_rate.unwrap(),
    );
    assert!((kp - 30000.0 * LBF / FT).abs() < 1e-6 && (ks - 20000.0 * LBF / FT).abs() < 1e-6);
    modify(&mut by_hand.primary.compression, kp);
    modify(&mut by_hand.secondary.tension, ks);
    modify(&mut by_hand.secondary.compression, ks);
    let a = run(&springs).summary();
    let b = run(&by_hand).summary();
    assert_eq!(a.steps, b.steps);
    for i in 0..4 {
        assert!((a.max_primary_stroke_m[i] - b.max_primary_stroke_m[i]).abs() < 1e-9);
        for j in 0..2 {
            let d = a.max_secondary_tension_m[i][j] - b.max_secondary_tension_m[i][j];
            assert!(d.abs() < 1e-9);
        }
    }
    // And the springs matter: the primary strokes move by millimetres.
    let rigid = run(&load("table-i-2-2-vv8.toml", &[])).summary();
    assert!((a.max_primary_stroke_m[0] - rigid.max_primary_stroke_m[0]).abs() > 1e-3);
}

/// The tripod gear (docs/errata.md, "Tripod gear") dropped level: four identical legs, its secondaries compressed,
/// no bearing friction, and the energy balance closed.
#[test]
fn tripod_drop_is_symmetric_and_closes_its_energy_balance() {
    let sim = run(&load("tripod-drop.toml", &[]));
    let s = sim.summary();
    for i in 1..4 {
        assert!((s.max_primary_stroke_m[i] - s.max_primary_stroke_m[0]).abs() < 1e-9);
        for j in 0..2 {
            let d = s.max_secondary_compression_m[i][j] - s.max_secondary_compression_m[0][j];
            assert!(d.abs() < 1e-9);
        }
    }
    assert!(s.max_primary_stroke_m[0] > 0.0 && s.max_secondary_compression_m[0][0] > 0.0);
    assert!(sim.gear().iter().all(|g| g.fbr == 0.0 && g.fm == 0.0));
    assert_eq!(s.energy.bearing_friction_j, 0.0);
    assert!(s.energy.residual_j.abs() < 1e-3 * s.energy.kinetic_initial_j);
}

/// The multibody engines refuse a mechanism they do not model, naming the scenario field and
/// saying why; they accept the engine, the RCS, the curbs and the tripod gear.
#[test]
fn multibody_engines_refuse_mechanisms_they_do_not_model() {
    for (name, field) in [
        ("soil-drop.toml", "surface.soil"),
        ("slosh-drop.toml", "slosh"),
        ("bending-2-2-vv8.toml", "primary_strut.bending"),
    ] {
        let sc = load(name, &[]);
        for engine in [Engine::Rapier, Engine::Mujoco] {
            let e = touchdown_registry::require(engine, &sc)
                .unwrap_err()
                .to_string();
            assert!(
                e.contains(field) && e.contains("does not model"),
                "{name} on {engine}: {e}"
            );
        }
        touchdown_registry::require(Engine::Core, &sc).unwrap();
    }
    for name in [
        "trunnion-springs.toml",
        "thrust-tailoff.toml",
        "rcs-attitude-hold.toml",
        "curb-slide.toml",
        "tripod-drop.toml",
    ] {
        let sc = load(name, &[]);
        for engine in Engine::ALL {
            touchdown_registry::require(engine, &sc).unwrap();
        }
    }
}

/// A landing's history, one row per step (`history.csv` as written).
pub(crate) struct Rows {
    header: Vec<String>,
    rows: Vec<Vec<f64>>,
}

impl Rows {
    fn read(path: &Path) -> Rows {
        let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{e}"));
        let mut lines = text.lines();
        let header = lines.next().unwrap().split(',').map(String::from).collect();
        let rows = lines
            .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
            .collect();
        Rows { header, rows }
    }

    /// The column `name` over the run.
    pub(crate) fn column(&self, name: &str) -> Vec<f64> {
        let k = self.header.iter().position(|h| h == name).unwrap();
        self.rows.iter().map(|r| r[k]).collect()
    }

    /// The body rates at the end, rad/s, body axes.
    fn final_omega(&self) -> Vector3<f64> {
        let last = |name: &str| *self.column(name).last().unwrap();
        Vector3::new(
            last("omega_x_rad_s"),
            last("omega_y_rad_s"),
            last("omega_z_rad_s"),
        )
    }
}

/// `sim` run to its end with every state written to the history file `path` (`legs` legs).
fn recorded<L: Landing>(mut sim: L, path: &Path, legs: usize) -> Summary
where
    L::Error: std::fmt::Display,
{
    let mut h = History::create(path, legs).unwrap();
    let summary = sim.run(&mut h).unwrap_or_else(|e| panic!("{e}"));
    h.finish().unwrap();
    summary
}

/// A landing on `engine`: its summary and its history, a row at the start and after every step.
pub(crate) fn landed_with_history(engine: Engine, path: &Path) -> (Summary, Rows) {
    let sc = Scenario::load(path).unwrap_or_else(|e| panic!("{e}"));
    let out = path.with_extension(engine.to_string());
    std::fs::create_dir_all(&out).unwrap();
    let history = out.join("history.csv");
    let summary = match engine {
        Engine::Core => recorded(
            Simulation::new(&sc).unwrap_or_else(|e| panic!("{e}")),
            &history,
            sc.legs.len(),
        ),
        Engine::Rapier => recorded(
            RapierSimulation::new(&sc).unwrap_or_else(|e| panic!("{e}")),
            &history,
            sc.legs.len(),
        ),
        Engine::Mujoco => {
            let launch = Launch::locate().unwrap_or_else(|e| panic!("{e}"));
            launch
                .run(path, &out, true)
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        }
    };
    let rows = Rows::read(&history);
    let _ = std::fs::remove_dir_all(&out);
    (summary, rows)
}

/// The multibody engines apply the descent engine's thrust through the shared law: thrust equal
/// to the weight of the whole multibody (vehicle and gear links) makes it descend at constant
/// velocity (0.5 ft/s, released 0.2 ft above the ground, so it never lands in 0.1 s), and the
/// thrust is evaluated once per step. (A descent rather than a hover at rest, so that the
/// energy balance has a scale to be checked against.)
#[test]
fn thrust_equal_to_weight_keeps_the_multibody_engines_descending_steadily() {
    // The hanging footpads settle on their primaries' extension stops; lossless stops keep
    // that settling from taking energy, so the vehicle's kinetic energy measures the thrust
    // alone.
    let sc = load("thrust-tailoff.toml", &[]);
    let thrust = multibody_mass(&sc) * sc.vehicle.gravity / LBF;
    let path = variant(
        "thrust-tailoff.toml",
        "multibody-descent",
        &format!(
            "[touchdown]\nvertical_velocity = -0.5\nclearance = 0.2\n\
             [thrust]\nthrust = {thrust:.17e}\ntailoff_start = 100.0\n\
             [thrust.amplification]\nclearance = [0.0, 1.0]\nfactor = [1.0, 1.0]\n\
             [integrator]\nt_end = 0.1\n\
             [primary_strut.compression]\nstop_restitution = 1.0\n"
        ),
    );
    let weight = sc.vehicle.mass * sc.vehicle.gravity;
    for engine in [Engine::Rapier, Engine::Mujoco] {
        let (s, _) = landed_with_history(engine, &path);
        let e = &s.energy;
        assert!(s.t_end_s > 0.099, "{engine}: ended at {} s", s.t_end_s);
        assert!(s.first_contact_s.iter().all(Option::is_none), "{engine}");
        // Constant velocity: the kinetic energy holds, the height falls by V·t.
        let fall = -e.potential_change_j / weight; // M·g·Δz, Δz = −fall
        let expected = 0.5 * FT * s.t_end_s;
        assert!(
            (e.kinetic_j / e.kinetic_initial_j - 1.0).abs() < 1e-4,
            "{engine}: kinetic energy {} J from {} J",
            e.kinetic_j,
            e.kinetic_initial_j
        );
        assert!(
            (fall / expected - 1.0).abs() < 1e-3,
            "{engine}: fell {fall} m, expected {expected} m"
        );
        assert!(
            e.residual_j.abs() < 1e-3 * e.kinetic_initial_j,
            "{engine}: {e:?}"
        );
        // One evaluation per step (for the step it starts; rapier also evaluates at its end).
        let n = s.mechanisms.get("thrust").copied().unwrap_or(0);
        assert!(
            (s.steps..=s.steps + 1).contains(&n),
            "{engine}: {n} evaluations in {} steps",
            s.steps
        );
    }
}

/// The primary's extension stop in a run, on every engine, against a closed form. The lander
/// hovers on thrust equal to its vehicle's weight, its primaries vertical (R3 = R1, fig. 23).
/// Its footpads start at full extension with no load and hang from their struts. Along a
/// vertical primary their load is axial: it passes through the trunnion B2, the secondaries
/// carry nothing, and each footpad moves along its strut alone. Relative to the parts above
/// it (the vehicle, and the outer-cylinder links of the multibody engines), a footpad of mass
/// m is a step load F* = m·T/(M_u + n·m) on the stop. T is the thrust, M_u the mass above the
/// footpads, n the number of legs.
///
/// On the stop's loading line F = K_so·d, the first deepest point is twice the static depth:
/// d₁ = 2·F*/K_so. The stop then unloads along K_so·d₁·(d/d₁)^k, k = 2/e² − 1 ("End stops",
/// docs/errata.md). The footpad rises to where that curve has given back the load's work,
/// r = d/d₁ with (1 − r^(k+1))/(k + 1) = (1 − r)/2. At e = 0.5 that is r = 0.787; at e = 1
/// the footpad comes back to full extension, r = 0, and a plastic stop (e = 0) keeps it at
/// d₁, r = 1. Nothing goes deeper than d₁ afterwards but on a plastic stop, which sinks
/// (docs/errata.md, "End stops"). The step is 5 µs on every engine:
/// ω·Δt ≈ 0.04 on the loading line and 0.1 on the unloading curve, so a sampled deepest point
/// is within (ω·Δt)²/8 = 2e-4 of the true one. Measured: d₁ within 1.2e-5 (core) and 6.3e-5
/// (rapier, MuJoCo) of the closed form; r within 1e-4 at e = 0.5 and 1, 4.2e-4 at e = 0; no
/// footpad deeper than d₁ by more than 4.4e-5 of it at e = 0.5 and 1 (at e = 0, 7 % on the
/// core and 13 % on rapier and MuJoCo within the 3 ms). Without the outer-cylinder links in
/// M_u the multibody engines' d₁ would be 0.25 % off, and the bar of 1e-3 fails it.
#[test]
fn hanging_footpads_stretch_their_extension_stops_as_a_step_load_does_on_every_engine() {
    let sc = load("thrust-tailoff.toml", &[]);
    let thrust = sc.vehicle.mass * sc.vehicle.gravity; // N
    let rate = sc.primary.compression.stroke_out_rate; // N/m
    let m = sc.footpad.mass;
    // r = d/d₁ where the footpad turns back up: bisection on the energy balance.
    let turning = |e: f64| {
        if e == 1.0 {
            return 0.0;
        }
        if e == 0.0 {
            return 1.0; // a plastic stop gives nothing back: the footpad stays at d₁
        }
        let k = 2.0 / (e * e) - 1.0;
        let gap = |r: f64| (1.0 - r.powf(k + 1.0)) / (k + 1.0) - 0.5 * (1.0 - r);
        let (mut lo, mut hi) = (0.0, 1.0 - 1e-9); // gap(0) < 0 < gap(just below 1)
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if gap(mid) < 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    };
    for e in [0.0, 0.5, 1.0] {
        let path = hanging_footpads(
            &format!("hanging-footpads-e{e}"),
            thrust,
            &format!(
                "tailoff_start = 100.0\n\
                 [touchdown]\nvertical_velocity = 0.0\nclearance = 0.2\n\
                 [primary_strut.compression]\nstop_restitution = {e}\n\
                 [integrator]\nt_end = 0.003\ndt_max = 5e-6\n\
                 [engines.rapier]\ntimestep = 5e-6\n[engines.mujoco]\ntimestep = 5e-6\n"
            ),
        );
        let r = turning(e);
        for engine in Engine::ALL {
            // M_u + n·m: the mass the thrust moves.
            let expected = 2.0 * m * thrust / moving_mass(engine, &sc) / rate;
            let (s, rows) = landed_with_history(engine, &path);
            assert!(
                s.t_end_s > 0.0029,
                "{engine} e = {e}: ended at {} s",
                s.t_end_s
            );
            assert!(s.first_contact_s.iter().all(Option::is_none), "{engine}");
            for leg in 1..=sc.legs.len() {
                let depth: Vec<f64> = rows
                    .column(&format!("leg{leg}_primary_stroke_m"))
                    .iter()
                    .map(|c| -c)
                    .collect();
                // The first deepest point, then the first highest after it.
                let deepest = (1..depth.len())
                    .find(|&k| depth[k] < depth[k - 1])
                    .map(|k| k - 1)
                    .unwrap_or_else(|| panic!("{engine} leg {leg}: no deepest point"));
                let d1 = depth[deepest];
                let highest = (deepest + 1..depth.len())
                    .find(|&k| depth[k] > depth[k - 1])
                    .map(|k| depth[k - 1])
                    .unwrap_or_else(|| panic!("{engine} leg {leg}: no turn after {d1} m"));
                assert!(
                    (d1 / expected - 1.0).abs() < 1e-3,
                    "{engine} e = {e} leg {leg}: deepest {d1:.6e} m, 2·F*/K_so = {expected:.6e} m"
                );
                assert!(
                    (highest / d1 - r).abs() < 2e-3,
                    "{engine} e = {e} leg {leg}: turned at {:.4} of the deepest, expected {r:.4}",
                    highest / d1
                );
                // Below d₁ the stop gives back what it took and no more, so nothing goes deeper.
                // A plastic stop does: it does not hold a load below its last force
                // (docs/errata.md, "End stops", "A plastic stop does not hold a lesser load").
                let deepest_ever = depth.iter().copied().fold(0.0, f64::max);
                assert!(
                    e == 0.0 || deepest_ever < d1 * (1.0 + 1e-3),
                    "{engine} e = {e} leg {leg}: {deepest_ever:.6e} m after a first deepest {d1:.6e} m"
                );
            }
        }
    }
}

/// The bearing friction holds a flying footpad's stroke up to its bound μB·(F1 + F2), F1 and F2
/// the inner cylinder's bearing loads under the side load FM (eqs. 59-63), on every engine. The
/// rig: the lander of `hanging_footpads_stretch_their_extension_stops_as_a_step_load_does_on_every_engine`
/// (primaries vertical), rising off the ground it starts above and spinning about its vertical
/// axis at ω, so that each footpad's centripetal force m·ω²·r is a side load FM across its
/// primary, under thrust of five times the vehicle's weight, so that each footpad hangs on its
/// primary's elastic extension stop (e = 1, K_so) with the axial load F_a = m·T/(M_u + n·m);
/// the stops are ten times softer than the vehicle's, so that the depths are micrometres, and
/// viscous dampers on the secondaries settle the footpads' swing as the spin loads them. Then
/// the thrust tails off (T = T₀·e^(−k·(t − t₂))) slowly against the stop's own mode: the stop
/// pushes the footpad back up as F_a falls, and the friction, at its bound while the footpad
/// slides, holds the stop at K_so·d = F_a + μB·(F1 + F2). Once the thrust is gone the footpad
/// should stay where it stopped, held at the bound: K_so·d = μB·(F1 + F2), with F1 + F2 =
/// FM·(2·D1 − D2)/D2 from the inner cylinder's moments (bearing 1 at D1 from the footpad,
/// bearing 2 at D1 − D2), worked out here from the run's own ω and footpad radius, not from the
/// laws' code.
///
/// rapier and MuJoCo take FM from the secondaries' force by the massless primary's moments
/// (eqs. 53-58), which on a gear with an outer-cylinder link also counts the link's own
/// centripetal load: their bound is larger by the link's moment over the footpad's,
/// m_o·(l_o/2)/(m·L), and they are held to that. The hold with the thrust gone is checked on the
/// core only: rapier's and MuJoCo's dry friction creep under a load below their bound
/// (docs/engines.md, "Shared laws and their oracles").
#[test]
fn spinning_footpads_hang_on_their_bearing_friction_as_its_statics_give_on_every_engine() {
    let sc = load("thrust-tailoff.toml", &[]);
    let omega: f64 = 5.0; // rad/s
    let thrust = 5.0 * sc.vehicle.mass * sc.vehicle.gravity; // N
    let (t2, k, t_end) = (0.1, 15.0, 0.6); // s, 1/s, s
    let path = hanging_footpads(
        "held-footpads",
        thrust,
        &format!(
            "tailoff_start = {t2}\ndecay_rate = {k}\n\
             [touchdown]\nvertical_velocity = 0.0\nclearance = 1.0\n\
             body_rates = [0.0, 0.0, {:.17e}]\n\
             [primary_strut.bearing]\nfriction = 0.3\n\
             [primary_strut.compression]\nstop_restitution = 1.0\nstroke_out_rate = 87000.0\n\
             [secondary_strut]\nviscous = {{ coefficient = 20.0, exponent = 1.0 }}\n\
             [integrator]\nt_end = {t_end}\n",
            omega.to_degrees()
        ),
    );
    let sc = Scenario::load(&path).unwrap();
    let m = sc.footpad.mass;
    let p = &sc.primary;
    let leg = &sc.legs[0];
    let outer = sc.links.outer_cylinder_mass_ratio * m;
    let l_outer = sc.links.outer_cylinder_length(leg, p, sc.arrangement);
    for engine in Engine::ALL {
        let total = moving_mass(engine, &sc);
        let links = match engine {
            Engine::Core => 1.0,
            _ => 1.0 + outer * 0.5 * l_outer / (m * leg.l2p),
        };
        let (s, rows) = landed_with_history(engine, &path);
        assert!(
            s.t_end_s > t_end - 1e-3,
            "{engine}: ended at {} s",
            s.t_end_s
        );
        assert!(s.first_contact_s.iter().all(Option::is_none), "{engine}");
        let time = rows.column("t_s");
        let w = rows.column("omega_z_rad_s");
        let (x, y) = (rows.column("x_m"), rows.column("y_m"));
        for i in 1..=sc.legs.len() {
            let col = |q: &str| rows.column(&format!("leg{i}_{q}"));
            let (px, py) = (col("pad_x_m"), col("pad_y_m"));
            let (c, stop) = (col("primary_stroke_m"), col("primary_stop_force_n"));
            // Each row's stop force over the load and the friction bound the statics give.
            let row = |j: usize| {
                let t = time[j];
                let f_a = m * thrust * (-k * (t - t2)).min(0.0).exp() / total; // eqs. (69)-(70)
                let f_m = m * w[j] * w[j] * (px[j] - x[j]).hypot(py[j] - y[j]);
                let d2 = p.initial_overlap + c[j];
                let bound = p.bearing_friction * f_m * (2.0 * p.inner_cylinder_length - d2) / d2;
                (t, -stop[j], f_a, bound)
            };
            let mean = |from: f64, to: f64, f: &dyn Fn(f64, f64, f64) -> f64| {
                let v: Vec<f64> = (0..time.len())
                    .map(row)
                    .filter(|(t, ..)| (from..=to).contains(t))
                    .map(|(_, s, f_a, b)| f(s, f_a, b))
                    .collect();
                (v.iter().sum::<f64>() / v.len() as f64, v)
            };
            // Sliding back as the thrust tails off: the friction at its bound.
            let (sliding, _) = mean(t2 + 0.05, t2 + 0.25, &|s, f_a, b| (s - f_a) / b);
            assert!(
                (sliding / links - 1.0).abs() < 5e-3,
                "{engine} leg {i}: (K_so·d − F_a)/(μB·(F1 + F2)) = {sliding:.5} while sliding, \
                 expected {links:.5}"
            );
            if engine == Engine::Core {
                // Held where it stopped once the thrust is gone.
                let (held, each) = mean(t_end - 0.1, t_end, &|s, f_a, b| s / (f_a + b));
                let worst = each.iter().map(|r| (r - 1.0).abs()).fold(0.0, f64::max);
                assert!(
                    (held - 1.0).abs() < 5e-3 && worst < 0.03,
                    "{engine} leg {i}: held at {held:.5} of its bound on average, {worst:.4} at worst"
                );
                eprintln!("{engine} leg {i}: held at {held:.5}, {worst:.4} at worst");
            }
            eprintln!("{engine} leg {i}: sliding {sliding:.5} (links {links:.5})");
        }
    }
}

/// The multibody engines apply the RCS through the shared law: a yaw rate in free flight falls
/// while the rate error is outside the deadband and the firing stops at its edge. The vehicle's
/// rate ends within 10 % below the edge, not at it: the gear links hang on free trunnion
/// joints, and as the spin slows they swing and trade angular momentum with the vehicle after
/// the jets stop (the core's gear is massless). Without the deadband logic the rate would fall
/// to zero; without the RCS it would stay at 60 deg/s.
#[test]
fn rcs_stops_the_multibody_engines_at_their_deadband_edge() {
    let path = variant(
        "rcs-attitude-hold.toml",
        "multibody-rcs",
        "[touchdown]\nclearance = 1.0\nvertical_velocity = 0.0\n\
         horizontal_velocity = [0.0, 0.0]\nattitude = [0.0, 0.0, 45.0]\n\
         body_rates = [0.0, 0.0, 60.0]\n\
         [rcs]\nattitude_gain = [0.0, 0.0, 0.0]\nrate_gain = [0.3, 0.3, 0.5]\n\
         deadband = [1.0, 1.0, 2.0]\ntorque = [2.0, 2.0, 10.0]\n\
         [integrator]\nt_end = 0.2\n",
    );
    let edge = 2.0f64.to_radians() / 0.5;
    for engine in [Engine::Rapier, Engine::Mujoco] {
        let (s, rows) = landed_with_history(engine, &path);
        let omega = rows.final_omega();
        assert!(s.t_end_s > 0.199, "{engine}: ended at {} s", s.t_end_s);
        assert!(
            omega.z <= edge && omega.z > 0.9 * edge,
            "{engine}: yaw rate {} rad/s, deadband edge {edge} rad/s",
            omega.z
        );
        // The torque worked against the spin: the RCS took energy out (negative work booked
        // as work done on the mechanisms, positive). The balance closes within the scenario's
        // tolerance; both engines leave the same residual, 0.8 % of the spin energy.
        assert!(
            s.energy.mechanisms_j > 0.0,
            "{engine}: {:e} J",
            s.energy.mechanisms_j
        );
        assert!(
            s.energy.residual_j.abs() < 2e-2 * s.energy.kinetic_initial_j,
            "{engine}: residual {:e} J of {:e} J",
            s.energy.residual_j,
            s.energy.kinetic_initial_j
        );
    }
}

/// The multibody engines apply the curbs through the shared law, as a force on each footpad
/// body: frictionless footpads sliding into curbs crush as the table says (the booked work equals
/// the table's crushing work at the largest crush, read from the footpad path, less the elastic
/// energy given back), the crush stays within the table, and the energy balance closes (rapier:
/// within 2e-3 of the touchdown kinetic energy at the file's step; MuJoCo below).
#[test]
fn footpads_crush_against_curbs_as_their_table_says_on_rapier() {
    let path = variant("curb-slide.toml", "multibody-curbs", FRICTIONLESS_CURBS);
    let s = assert_curbs_crush_as_their_table_says(Engine::Rapier, &path);
    let e = &s.energy;
    assert!(e.residual_j.abs() < 2e-3 * e.kinetic_initial_j, "{e:?}");
}

/// The same on MuJoCo, whose balance closes to second order in the step here: within 1e-3 of the
/// touchdown kinetic energy at the file's step (0.0199 J of 136 J) and within 2e-3 at a quarter
/// of it (5 µs, the contacts' time constant kept at 40 µs; 0.00050 J), at least 16 times less
/// (40; 0.0199, 0.0032, 0.00050 and −0.00005 J at 20, 10, 5 and 2.5 µs, 2026-12-03). While the
/// stroke joint's dry-friction row carried the crush plateau as well as the bearing friction
/// (docs/engines.md, "Model" of the MuJoCo engine) it was first order, 0.085 and 0.014 J (6.1
/// times less), and with that row a step late 0.28 and 0.066 J. The row is as stiff as the step allows, so the bearing
/// friction is held as the law books it at any step: with the contacts' 40 µs it lagged at the
/// shorter steps.
#[test]
fn footpads_crush_against_curbs_as_their_table_says_on_mujoco_to_second_order() {
    let path = |name: &str, extra: &str| {
        variant(
            "curb-slide.toml",
            name,
            &format!("{FRICTIONLESS_CURBS}{extra}"),
        )
    };
    let file = assert_curbs_crush_as_their_table_says(Engine::Mujoco, &path("mujoco-curbs", ""));
    let quarter = assert_curbs_crush_as_their_table_says(
        Engine::Mujoco,
        &path(
            "mujoco-curbs-quarter-step",
            "[engines.mujoco]\ntimestep = 5.0e-6\n",
        ),
    );
    let e = &quarter.energy;
    assert!(e.residual_j.abs() < 2e-3 * e.kinetic_initial_j, "{e:?}");
    let f = &file.energy;
    assert!(f.residual_j.abs() < 1e-3 * f.kinetic_initial_j, "{f:?}");
    let ratio = f.residual_j / e.residual_j;
    assert!(
        ratio >= 16.0,
        "residual {} J at 20 µs, {} J at 5 µs",
        f.residual_j,
        e.residual_j
    );
}

/// The assertions of the curb tests above but the balance's, on `engine`'s landing of the
/// scenario at `path`; returns its summary.
fn assert_curbs_crush_as_their_table_says(engine: Engine, path: &Path) -> Summary {
    let sc = Scenario::load(path).unwrap_or_else(|e| panic!("{e}"));
    let (s, rows) = landed_with_history(engine, path);
    let curbs = curbs_from_scenario(&sc).unwrap().unwrap();
    let mut expected = 0.0;
    for (n, (leg, curb)) in curbs.list.clone().into_iter().enumerate() {
        let column = |what: &str| rows.column(&format!("leg{}_{what}", leg + 1));
        let (x, y, contact) = (column("pad_x_m"), column("pad_y_m"), column("contact"));
        // The footpad's path from its first contact, as the engine commits it.
        let first = contact.iter().position(|c| *c != 0.0).unwrap();
        let xy = |k: usize| nalgebra::Vector2::new(x[k], y[k]);
        let mut memory = CrushMemory::default();
        for k in first..x.len() {
            curbs
                .crush
                .commit(curb.crush(xy(first), xy(k), sc.footpad.radius), &mut memory);
        }
        let x_now = curb.crush(xy(first), xy(x.len() - 1), sc.footpad.radius);
        expected += crush_work(&sc, &curbs, &memory, x_now, &format!("{engine}, curb {n}"));
    }
    let e = &s.energy;
    assert!(
        (e.mechanisms_j / expected - 1.0).abs() < 0.03,
        "{engine}: booked {} J vs table {expected} J",
        e.mechanisms_j
    );
    let n = s.mechanisms.get("curbs").copied().unwrap_or(0);
    assert!(
        (s.steps..=s.steps + 1).contains(&n),
        "{engine}: {n} evaluations"
    );
    s
}

/// End stops dissipate at every hit on the multibody engines too (docs/errata.md, "End stops —
/// a coefficient of restitution at every hit"): `stroke-out` run to 3 s with e = 0.5 bounces
/// lower at every rebound (each rise above the final rest height below half the one before;
/// with the stop lossless after its first hit it rose back to 106 % of its touchdown height on
/// rapier) and has stopped bouncing by the fourth. (The core meets the tighter bound e² of the
/// one before plus 5 % of the first: `physics::stroke_out_rebounds_lose_their_stops_energy_at_every_hit`;
/// the multibody engines' explicit strut forces over a step put back a little of what the stop
/// takes, docs/engines.md, "Energy ledger".)
#[test]
fn stroke_out_rebounds_die_out_on_the_multibody_engines() {
    let path = variant(
        "stroke-out.toml",
        "multibody-stroke-out",
        "[integrator]\nt_end = 3.0\n",
    );
    for engine in [Engine::Rapier, Engine::Mujoco] {
        let (_, rows) = landed_with_history(engine, &path);
        let (z, vz) = (rows.column("z_m"), rows.column("vz_m_s"));
        let rest = *z.last().unwrap();
        let rises: Vec<f64> = (1..z.len())
            .filter(|&k| vz[k - 1] > 0.0 && vz[k] <= 0.0)
            .map(|k| z[k] - rest)
            .collect();
        // Below half the one before (strictly: a lossless stop's rebound would equal it).
        let half = |before: f64, _| 0.5 * before * (1.0 - f64::EPSILON);
        touchdown_tests::assert_rebounds_fall(&engine.to_string(), &rises, 4, half);
    }
}

/// The viscous strut law in a run, on every engine: with C·|ċ|^γ on every strut (γ = 1 on the
/// primaries, 1.5 on the secondaries, so that the exponent counts), the energy the run books as
/// viscous is the law's dissipation along the run's own strokes, Σ C·|Δc|^(γ+1)/Δt^γ over the
/// history's steps, and the balance closes with it: a force booked and not applied, or
/// applied with another magnitude or exponent, leaves one or the other apart. (The history's
/// rate over a step is its mean, the engines' forces use their own rates within it: the two
/// sums part at first order in the step: 0.04 % on the core, 0.12 % on rapier and 0.06 % on
/// MuJoCo when this was written, a 4.8 % gap when the law ignored its exponent.)
#[test]
fn the_viscous_force_dissipates_what_its_law_gives_along_the_strokes_on_every_engine() {
    let path = variant(
        "table-i-2-2-vv8.toml",
        "viscous-struts",
        "[primary_strut.viscous]\ncoefficient = 5.0\nexponent = 1.0\n\
         [secondary_strut.viscous]\ncoefficient = 5.0\nexponent = 1.5\n\
         [integrator]\nt_end = 0.5\n",
    );
    let sc = Scenario::load(&path).unwrap();
    let laws = [
        ("primary_stroke_m", sc.primary.viscous),
        ("sec31_stroke_m", sc.secondary.viscous),
        ("sec41_stroke_m", sc.secondary.viscous),
    ];
    for engine in Engine::ALL {
        let (s, rows) = landed_with_history(engine, &path);
        let t = rows.column("t_s");
        let mut dissipated = 0.0;
        for leg in 1..=sc.legs.len() {
            for (column, law) in laws {
                let c = rows.column(&format!("leg{leg}_{column}"));
                for k in 1..t.len() {
                    let (dc, dt) = ((c[k] - c[k - 1]).abs(), t[k] - t[k - 1]);
                    dissipated +=
                        law.coefficient * dc.powf(law.exponent + 1.0) / dt.powf(law.exponent);
                }
            }
        }
        let e = &s.energy;
        let total = e.kinetic_initial_j - e.potential_change_j;
        assert!(
            e.viscous_j > 0.1 * total,
            "{engine}: the viscous force takes {} J of {total} J",
            e.viscous_j
        );
        assert!(
            (e.viscous_j / dissipated - 1.0).abs() < 0.01,
            "{engine}: booked {} J, the law gives {dissipated} J along the strokes",
            e.viscous_j
        );
        assert!(e.residual_j.abs() < 0.01 * total, "{engine}: {e:?}");
    }
}

/// The descent engine in free flight (eqs. 69-71), an independent solution: released 0.8 ft
/// above level ground at rest, the vehicle falls as m·z̈ = F1·e^(−K·t)·AMP(ZNOZ) − m·g, solved
/// here by RK4 at 1 µs with the tailoff (t2 = 0) and the amplification table's linear
/// interpolation in the nozzle clearance ZNOZ = z + R_T,z written out by hand; the nozzle
/// passes from 0.95 to 0.60 ft, where AMP rises from 1.003 to 1.029. On the core its
/// footpads ride rigidly, so m is the vehicle's; on rapier and MuJoCo the gear links hang on
/// their lossless extension stops and move with it, so m is the whole multibody's (the thrust
/// acts on the vehicle alone). Within 5e-4 of the fall and of the speed: the amplification's
/// whole effect is 3.7e-3 of the fall and 2.6e-3 of the speed, the tailoff's far more; the
/// core comes within 6e-7, rapier and MuJoCo within 6e-5 (their links ring on the stops).
#[test]
fn a_vehicle_falls_under_its_tailing_off_amplified_thrust_as_its_equation_of_motion_gives() {
    let free_flight = "[touchdown]\nvertical_velocity = 0.0\nclearance = 0.8\n\
                       [primary_strut.compression]\nstop_restitution = 1.0\n";
    for engine in Engine::ALL {
        let rigid = if engine == Engine::Core {
            "[footpad]\ndetached = \"rigid\"\n"
        } else {
            ""
        };
        let path = variant(
            "thrust-tailoff.toml",
            &format!("free-flight-{engine}"),
            &format!("{free_flight}{rigid}"),
        );
        let sc = Scenario::load(&path).unwrap();
        let thrust = sc.thrust.clone().unwrap();
        let (f1, k) = (thrust.thrust, thrust.decay_rate.unwrap());
        assert_eq!(
            (thrust.tailoff_start, thrust.clock_at_touchdown),
            (0.0, 0.0)
        );
        let table = thrust.amplification.unwrap();
        let amp = |znoz: f64| {
            let (first, last) = (table[0], table[table.len() - 1]);
            if znoz <= first.0 {
                return first.1;
            }
            if znoz >= last.0 {
                return last.1;
            }
            let i = table.iter().position(|p| p.0 > znoz).unwrap();
            let ((x0, y0), (x1, y1)) = (table[i - 1], table[i]);
            y0 + (y1 - y0) * (znoz - x0) / (x1 - x0)
        };
        let g = sc.vehicle.gravity;
        let mass = match engine {
            Engine::Core => sc.vehicle.mass,
            _ => multibody_mass(&sc),
        };
        let (_, rows) = landed_with_history(engine, &path);
        let (t, z, vz) = (
            rows.column("t_s"),
            rows.column("z_m"),
            rows.column("vz_m_s"),
        );
        let (t_end, z_end, vz_end) = (t[t.len() - 1], z[z.len() - 1], vz[vz.len() - 1]);
        // RK4 of (z, ż) from the run's start.
        let accel = |t: f64, z: f64| f1 * (-k * t).exp() * amp(z + thrust.nozzle_exit.z) / mass - g;
        let n = (t_end / 1e-6).round() as usize;
        let h = t_end / n as f64;
        let (mut zs, mut v) = (z[0], vz[0]);
        for i in 0..n {
            let ti = i as f64 * h;
            let (k1z, k1v) = (v, accel(ti, zs));
            let (k2z, k2v) = (v + 0.5 * h * k1v, accel(ti + 0.5 * h, zs + 0.5 * h * k1z));
            let (k3z, k3v) = (v + 0.5 * h * k2v, accel(ti + 0.5 * h, zs + 0.5 * h * k2z));
            let (k4z, k4v) = (v + h * k3v, accel(ti + h, zs + h * k3z));
            zs += h / 6.0 * (k1z + 2.0 * k2z + 2.0 * k3z + k4z);
            v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        }
        let fall = (z_end - zs) / (z[0] - zs);
        let speed = (vz_end - v) / v;
        assert!(
            fall.abs() < 5e-4 && speed.abs() < 5e-4,
            "{engine}: at t = {t_end} s z = {z_end} m (RK4 {zs} m, {fall:.2e} of the fall), \
             ż = {vz_end} m/s (RK4 {v} m/s, {speed:.2e})"
        );
    }
}

/// Nozzle crushing in a run (eqs. 72-73): a level vehicle descending at 2 ft/s under thrust
/// equal to its weight meets the ground with its nozzle 0.048 ft below its footpads, and the
/// rim's constant crush load F_c stops it before the footpads touch. On the core, whose
/// footpads ride rigidly, in d = m·v²/(2·F_c); on rapier and MuJoCo the gear's links hang
/// below the vehicle on lossless extension stops, and their weight W, which the thrust does
/// not carry, falls with it: d = (½·M·v² + W·h)/(F_c − W), M the whole multibody's mass and h
/// the rim's fall before it touches, less at most the links' share m_l/M, the kinetic energy
/// their stops may keep. The force starts at the first evaluation after the rim reaches the
/// ground, so the crush may overrun d by one step's travel, v·Δt (measured: 1.0 % of d on the
/// core, half its bound; 0.05 % short of d on rapier and MuJoCo).
///
/// Then the rim stands: the crush load is bounded by what stops the rim within a step
/// (`touchdown_laws::RimArrest`, docs/errata.md, "Eqs. (72)-(73): nozzle crushing"), and the
/// vehicle does not rise in the millisecond after its rim stops (the whole load for the step
/// in which the rim stopped left it rising at F_c·Δt/m: 6.1 mm/s on the core, 0.61 mm/s on
/// rapier and MuJoCo). On the core it never rises again, not by a rounding. On rapier and
/// MuJoCo the vehicle then rests on its rim while its links swing and bounce on their stops,
/// which move it by less than a micrometre (0.75 and 0.89 µm over the run).
#[test]
fn a_nozzle_crushes_to_the_depth_its_constant_load_gives_and_stands_on_every_engine() {
    let base = load("thrust-tailoff.toml", &[]);
    let (m, g) = (base.vehicle.mass, base.vehicle.gravity);
    let v0 = 2.0 * FT;
    let t_end = 0.2;
    for engine in Engine::ALL {
        let (mass, rigid) = match engine {
            Engine::Core => (m, "[footpad]\ndetached = \"rigid\"\n"),
            _ => (multibody_mass(&base), ""),
        };
        let thrust = m * g / LBF;
        let path = variant(
            "thrust-tailoff.toml",
            &format!("nozzle-crush-{engine}"),
            &format!(
                "[touchdown]\nvertical_velocity = -2.0\nclearance = 0.1\n\
                 [thrust]\nthrust = {thrust:.17e}\ntailoff_start = 100.0\n\
                 nozzle_exit = [0.0, 0.0, -1.0]\n\
                 [thrust.amplification]\nclearance = [0.0, 1.0]\nfactor = [1.0, 1.0]\n\
                 [primary_strut.compression]\nstop_restitution = 1.0\n\
                 [integrator]\nt_end = {t_end}\n{rigid}"
            ),
        );
        let sc = Scenario::load(&path).unwrap();
        let nozzle = sc.thrust.as_ref().unwrap();
        let crush_load = nozzle.nozzle_crushing.unwrap().1;
        let (s, rows) = landed_with_history(engine, &path);
        let (t, z) = (rows.column("t_s"), rows.column("z_m"));
        let at_ground = sc.surface.pads[0].plane() - nozzle.nozzle_exit.z;
        let hanging = (mass - m) * g;
        let expected =
            (0.5 * mass * v0 * v0 + hanging * (z[0] - at_ground)) / (crush_load - hanging);
        let lowest = z.iter().copied().fold(f64::INFINITY, f64::min);
        let crushed = at_ground - lowest;
        let dt = touchdown_registry::time_step(engine, &sc).unwrap();
        assert!(
            s.first_contact_s.iter().all(Option::is_none),
            "{engine}: a footpad touched"
        );
        let kept = expected * (mass - m) / mass;
        assert!(
            crushed >= expected - kept && crushed - expected <= 1.01 * v0 * dt,
            "{engine}: crushed {crushed} m, {expected} m expected, less at most {kept} m, \
             plus at most {} m",
            v0 * dt
        );
        // the rim has stopped once the vehicle descends at less than 1 % of v
        let vz = rows.column("vz_m_s");
        let touched = z.iter().position(|&x| x < at_ground).unwrap();
        let stop = touched + vz[touched..].iter().position(|&v| v > -0.01 * v0).unwrap();
        let (mut low, mut rise) = (z[stop], 0.0f64);
        for &x in &z[stop..] {
            low = low.min(x);
            rise = rise.max(x - low);
        }
        let settled = t.iter().position(|&x| x > t[stop] + 1e-3).unwrap();
        let rising = vz[stop..settled].iter().copied().fold(0.0, f64::max);
        assert!(
            rising == 0.0,
            "{engine}: the vehicle rose at {rising} m/s within 1 ms of its rim's stop at {} s \
             (a step's whole load gives {} m/s)",
            t[stop],
            crush_load * dt / m
        );
        assert!(
            engine != Engine::Core || (rise == 0.0 && vz[stop..].iter().all(|&v| v <= 0.0)),
            "core: the vehicle rose {rise} m after its rim stopped at {} s",
            t[stop]
        );
    }
}

/// The samples of a history after the strut's extreme stroke on one side (`side` +1: the
/// positive strokes, −1: the negative), checked against the backoff line of that side's
/// honeycomb, F = F_ext − K_B·(x_ext − x) in that side's direction, while the stroke stays on
/// that side; no load where the line has reached zero (shorter than the permanent set).
/// Returns how many samples were unloading along it.
fn assert_unloads_along_the_backoff_line(
    what: &str,
    x: &[f64],
    f: &[f64],
    side: f64,
    k_b: f64,
) -> usize {
    let top = (0..x.len()).fold(0, |m, k| if side * x[k] > side * x[m] { k } else { m });
    let (x_ext, f_ext) = (side * x[top], side * f[top]);
    assert!(
        x_ext > 0.0 && f_ext > 0.0,
        "{what}: not loaded on this side"
    );
    let mut unloaded = 0;
    for k in (top + 1..x.len()).take_while(|&k| side * x[k] > 0.0) {
        let line = (f_ext - k_b * (x_ext - side * x[k])).max(0.0);
        unloaded += usize::from(line > 0.0);
        assert!(
            (side * f[k] - line).abs() <= 1e-6 * f_ext,
            "{what}: {} N at stroke {} m, the backoff line from ({} m, {} N) gives {} N",
            f[k],
            x[k],
            side * x_ext,
            side * f_ext,
            side * line
        );
    }
    unloaded
}

/// The honeycomb's unloading branch in a run, on every engine (docs/engines.md, "Shared laws
/// and their oracles"): after its largest stroke x_max, where it carried F_max, a strut unloads
/// along the backoff line F = F_max − K_B·(x_max − x) of the scenario's own K_B while it carries
/// load, and carries none below it (shorter than its permanent set). The symmetric drop
/// checks the primaries in compression and the secondaries, which it pulls, on their tension
/// side; the 2-2 landing at 8 ft/s (to 0.5 s) the secondaries' compression side, two of which it
/// crushes 59 mm. This checks each engine's committed memories and forces against the closed
/// form, which the drop's largest-stroke test does not reach. Within 1e-6 of F_max; the history
/// prints 10 significant digits, and every engine comes within 1e-8.
#[test]
fn every_engine_unloads_its_struts_along_the_backoff_line() {
    let drop = scenario("flat-drop.toml");
    let two_two = variant(
        "table-i-2-2-vv8.toml",
        "unloading",
        "[integrator]\nt_end = 0.5\n",
    );
    for engine in Engine::ALL {
        for (path, sides) in [
            (
                &drop,
                [("primary", 1.0), ("sec31", 1.0), ("sec41", 1.0)].as_slice(),
            ),
            (&two_two, [("sec31", -1.0), ("sec41", -1.0)].as_slice()),
        ] {
            let sc = Scenario::load(path).unwrap();
            let (_, rows) = landed_with_history(engine, path);
            let mut unloaded = 0;
            for leg in 1..=sc.legs.len() {
                for &(strut, side) in sides {
                    let k_b = match (strut, side > 0.0) {
                        ("primary", _) => sc.primary.compression.backoff_rate,
                        (_, true) => sc.secondary.tension.backoff_rate,
                        (_, false) => sc.secondary.compression.backoff_rate,
                    };
                    let x = rows.column(&format!("leg{leg}_{strut}_stroke_m"));
                    let f = rows.column(&format!("leg{leg}_{strut}_force_n"));
                    let what = format!("{engine}, {}, leg {leg} {strut}", path.display());
                    let n = assert_unloads_along_the_backoff_line(&what, &x, &f, side, k_b);
                    if path == &drop {
                        assert!(n >= 10, "{what}: {n} samples unloading");
                    }
                    unloaded += n;
                }
            }
            assert!(
                unloaded >= 40,
                "{engine}, {}: {unloaded} samples unloading",
                path.display()
            );
        }
    }
}

/// Sliding friction in a run (eqs. 85, 96-100 on the core; rapier's and MuJoCo's own Coulomb
/// contact friction with the scenario's coefficient U): once the 2-2 lander set down at 1 ft/s
/// on level ground (U = 0.1) has settled on its gear, it slides on at the deceleration
/// Coulomb's law gives the whole lander, U·g, or in momentum form over a window,
/// −Δv_Y = U·(g·Δt + Δv_Z), whatever the footpads' share of the load. Over 0.5-1.0 s (before
/// it stops, at about 1.9 s): within 0.1 % of U, measured 0.01-0.02 % on rapier and MuJoCo and
/// 0.01 % on the core. The core took its drag on the gear's load alone, without the footpads'
/// weight (docs/errata.md, "Eq. (85): FDRAG is FDRAGP"), and slid as if U were 0.0975; before
/// its sliding footpads were corrected with the vehicle its energy guard stopped this landing
/// at 0.274 s.
#[test]
fn a_settled_lander_slides_at_the_deceleration_its_friction_gives_on_every_engine() {
    let path = variant(
        "level-sliding.toml",
        "settled-slide",
        "[surface]\nfriction = 0.1\n[touchdown]\nvertical_velocity = -1.0\n\
         [integrator]\nt_end = 1.0\n",
    );
    let sc = Scenario::load(&path).unwrap();
    let u = sc.surface.pads[0].friction;
    assert!(sc.surface.pads.iter().all(|p| p.friction == u));
    let g = sc.vehicle.gravity;
    for engine in Engine::ALL {
        let (_, rows) = landed_with_history(engine, &path);
        let (t, vy, vz) = (
            rows.column("t_s"),
            rows.column("vy_m_s"),
            rows.column("vz_m_s"),
        );
        let at = |time: f64| t.iter().position(|&x| x >= time - 1e-9).unwrap();
        let (a, b) = (at(0.5), t.len() - 1);
        assert!(
            vy[b] > 0.1 * vy[0],
            "{engine}: still sliding at the window's end"
        );
        let friction = -(vy[b] - vy[a]) / (g * (t[b] - t[a]) + vz[b] - vz[a]);
        assert!(
            (friction / u - 1.0).abs() < 1e-3,
            "{engine}: slides as if U = {friction}, the surface's is {u}"
        );
    }
}

/// Sliding friction's breakaway threshold (eqs. 96-100; the multibody engines' contact
/// friction with the same U), on every engine: a lander set down upright on a 10° slope (its
/// attitude the surface's, at 1 ft/s) slides iff U < tan α. Below it (U = 0.8·tan α) the
/// settled lander accelerates downhill as −Δv_Y = U·(g_n·Δt + Δv_Z) − g_t·Δt (g_t = g·sin α,
/// g_n = g·cos α; momentum along the slope of a body whose footpads all slide), within 0.1 % of
/// U: measured 0.01 % on every engine. Above it (U = 1.2·tan α) the footpads stand: their drift
/// over the last second is below 1e-4 of the free slide's ½·g_t·t² over that second (85 µm): 0 on
/// the core, whose stuck footpads hold exactly, 15 µm on MuJoCo, whose regularised friction
/// creeps, and 0.02-2.2 µm on rapier. With spherical trunnions rapier's footpads crept 0.97 mm:
/// each strut could spin about itself, and the friction force, 0.002 L2P below the strut axis,
/// spun it and rolled its footpad downhill (docs/engines.md, "Model" of the rapier rebuild).
#[test]
fn a_lander_on_a_slope_slides_below_its_friction_threshold_and_stands_above_it_on_every_engine() {
    let alpha = SLOPE_DEG.to_radians();
    let (window, hold) = (0.75, 0.5); // s: where the slide and the hold are measured
    for (factor, sliding) in [(0.8, true), (1.2, false)] {
        let u = factor * alpha.tan();
        let name = format!("slope-threshold-{factor}");
        let path = set_down_on_a_slope("level-sliding.toml", &name, u, 0.0);
        let g = Scenario::load(&path).unwrap().vehicle.gravity;
        let (g_t, g_n) = (g * alpha.sin(), g * alpha.cos());
        for engine in Engine::ALL {
            let (_, rows) = landed_with_history(engine, &path);
            let t = rows.column("t_s");
            let at = |time: f64| t.iter().position(|&x| x >= time - 1e-9).unwrap();
            let b = t.len() - 1;
            if sliding {
                let (vy, vz) = (rows.column("vy_m_s"), rows.column("vz_m_s"));
                let a = at(window);
                let dt = t[b] - t[a];
                let friction = (g_t * dt - (vy[b] - vy[a])) / (g_n * dt + vz[b] - vz[a]);
                assert!(
                    (friction / u - 1.0).abs() < 1e-3,
                    "{engine}: slides as if U = {friction}, the surface's is {u}"
                );
            } else {
                let a = at(hold);
                let free = 0.5 * g_t * (t[b] - t[a]).powi(2);
                for leg in 1..=4 {
                    let y = rows.column(&format!("leg{leg}_pad_y_m"));
                    let drift = y[b] - y[a];
                    assert!(
                        drift.abs() < 1e-4 * free,
                        "{engine}: footpad {leg} drifts {drift} m on a slope its friction holds"
                    );
                }
            }
        }
    }
}

/// A spiked footpad's restraint holds what its gear does not, and no more, on every engine:
/// on `fig-25-26` the leading footpads 1 and 2 stand held in their depressions from 0.12 to
/// 0.2 s while the vehicle pitches over them and their struts carry nothing. The restraint then
/// holds the footpad against the slope alone: the lateral share of its weight, m·g·sin α, with
/// m the footpad's mass (and on the multibody engines its outer-cylinder link's, 0.1 of it),
/// 0.16 N on the core, measured 0.21 N on rapier and MuJoCo; the test allows twice
/// (PMASS + link)·g·sin α. While the multibody engines also locked the footpad by its contact's
/// friction the two restraints fought as the footpad turned with its gear, and the wall held
/// 15-17 kN on rapier and 110-140 N on MuJoCo there (docs/engines.md, "The footpad's lateral
/// restraint").
#[test]
fn a_spiked_footpad_under_a_slack_gear_is_held_against_the_slope_alone_on_every_engine() {
    let path = variant(
        "fig-25-26.toml",
        "slack-hold",
        "[integrator]\nt_end = 0.25\n",
    );
    let sc = Scenario::load(&path).unwrap();
    let alpha = sc.surface.slope;
    let mass = sc.footpad.mass * (1.0 + sc.links.outer_cylinder_mass_ratio);
    let bound = 2.0 * mass * sc.vehicle.gravity * alpha.sin();
    for engine in Engine::ALL {
        let (_, rows) = landed_with_history(engine, &path);
        let t = rows.column("t_s");
        let window: Vec<usize> = (0..t.len())
            .filter(|&k| (0.12..=0.2).contains(&t[k]))
            .collect();
        assert!(window.len() > 10, "{engine}: {} samples", window.len());
        for leg in [1, 2] {
            let column = |name: &str| rows.column(&format!("leg{leg}_{name}"));
            let gear = ["primary_force_n", "sec31_force_n", "sec41_force_n"].map(column);
            let held = column("restraint_force_n");
            for &k in &window {
                assert!(
                    gear.iter().all(|f| f[k] == 0.0),
                    "{engine}: leg {leg}'s gear carries a force at {} s",
                    t[k]
                );
                assert!(
                    held[k] > 0.0 && held[k] <= bound,
                    "{engine}: leg {leg} held with {} N at {} s, its lateral weight {} N",
                    held[k],
                    t[k],
                    0.5 * bound
                );
            }
        }
    }
}

/// Curb friction UW (eqs. 94-95) in a run, on every engine: on a 10° frictionless slope a
/// lander set down in the slope's attitude moving at 3 ft/s along +X slides 6 mm downhill into
/// the curbs of `curb-slide.toml` (their normal +Y, UW = 0.2) and then along them, pressed into
/// them by its weight. The ground takes no horizontal force, so the curbs' normal impulse is the
/// momentum the slope gives less what the vehicle keeps, and their friction takes UW of it from
/// the motion along them: −Δv_X = UW·(g_t·Δt − Δv_Y), g_t = g·sin α. Over the last second of a
/// 1.5 s landing, within 1 % of UW (the vehicle's momentum alone, its gear rocking against the
/// curbs): measured 0.13 % on the core, 0.005 % on rapier and 0.05 % on MuJoCo. With UW = 0 the
/// measured value is 0, and a UW taken 5 % off fails.
#[test]
fn footpads_sliding_along_curbs_are_braked_by_their_curb_friction_on_every_engine() {
    let path = set_down_on_a_slope("curb-slide.toml", "curb-friction", 0.0, 3.0);
    let sc = Scenario::load(&path).unwrap();
    let uw = sc.surface.curbs[0].friction;
    assert!(uw > 0.0 && sc.surface.curbs.iter().all(|c| c.friction == uw));
    let g_t = sc.vehicle.gravity * SLOPE_DEG.to_radians().sin();
    for engine in Engine::ALL {
        let (_, rows) = landed_with_history(engine, &path);
        let (t, vx, vy) = (
            rows.column("t_s"),
            rows.column("vx_m_s"),
            rows.column("vy_m_s"),
        );
        let a = t.iter().position(|&x| x >= 0.5 - 1e-9).unwrap();
        let b = t.len() - 1;
        assert!(vx[b] > 0.0, "{engine}: stopped along its curbs");
        let friction = -(vx[b] - vx[a]) / (g_t * (t[b] - t[a]) - (vy[b] - vy[a]));
        assert!(
            (friction / uw - 1.0).abs() < 1e-2,
            "{engine}: braked along its curbs as if UW = {friction}, theirs is {uw}"
        );
    }
}

/// The primary's bearing friction (eqs. 59-63) in a run, on every engine: `flat-drop` with
/// μB = 0.3 strokes to the energy balance whose bearing-friction work
/// `touchdown_tests::analytic_drop_strokes` derives from the statics of the primary and its
/// inner cylinder along the drop's monotonic stroke, not from the laws' code: every primary
/// within 1 % of that stroke, each secondary within 1 % of the primary's, the balance closed to
/// 0.2 % of the touchdown energy. Measured: the primaries 0.006 % long on the core, 0.11 % on
/// rapier and 0.14 % on MuJoCo (the core's bearing friction is eq. 63's kinetic law in contact;
/// rapier's and MuJoCo's a dry-friction bound on the stroke joint). The friction shortens the
/// stroke by 15 % (62.2 to 52.6 mm), and with μB 25 % low in the balance every engine is
/// 3.7-3.8 % off it.
#[test]
fn a_drop_on_bearings_with_friction_strokes_to_the_balance_their_statics_give_on_every_engine() {
    let path = variant(
        "flat-drop.toml",
        "bearing-friction-drop",
        "[primary_strut.bearing]\nfriction = 0.3\n",
    );
    let sc = Scenario::load(&path).unwrap();
    let mut without = sc.clone();
    without.primary.bearing_friction = 0.0;
    let ([c, ..], [c0, ..]) = (
        touchdown_tests::analytic_drop_strokes(&sc),
        touchdown_tests::analytic_drop_strokes(&without),
    );
    assert!(
        c < 0.9 * c0,
        "the friction shortens the stroke: {c} m against {c0} m"
    );
    for engine in Engine::ALL {
        let (summary, _) = landed_with_history(engine, &path);
        touchdown_tests::assert_drop_strokes_to_the_energy_balance(&sc, &summary);
    }
}

/// The least-squares slope of `y` against `x`.
fn slope(x: &[f64], y: &[f64]) -> f64 {
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let (xm, ym) = (mean(x), mean(y));
    let (num, den) = x.iter().zip(y).fold((0.0, 0.0), |(n, d), (a, b)| {
        (n + (a - xm) * (b - ym), d + (a - xm) * (a - xm))
    });
    num / den
}

/// The RCS's attitude hold in a run (eqs. 75-80), on every engine: a level vehicle in free
/// flight spinning about Z_B at ω0 = 20 deg/s, holding its yaw with k1 = 1, k2 = 0.3 s, a
/// 1 deg deadband EM and a yaw torque T. While E = k1·Dψ + k2·ω ≥ EM the jets brake it at
/// a: ω = ω0 − a·t, Dψ = ω0·t − a·t²/2, until E falls below EM at the root t_off of
/// −(k1·a/2)·t² + (k1·ω0 − k2·a)·t + k2·ω0 − EM = 0; then it turns freely at
/// ω1 = ω0 − a·t_off (backwards: E keeps falling, and reaches −EM only 0.8 s later). On the
/// core, whose footpads ride rigidly off the surface, a is T/I_z of the vehicle, within 1e-6;
/// on rapier and MuJoCo the gear's links turn with it, and a is the run's own, the
/// least-squares slope of ω over the first 0.15 s (22 % below T/I_z). Given a, every engine's
/// jets stop within 1 ms of t_off (measured 0.2, 0.3 and 0.4 ms on the core, rapier and
/// MuJoCo; their steps are 0.2 ms and 20 µs, the links' swing blurs the multibody's) and it
/// then turns at ω1 within 1e-3 of ω0 (measured 1e-4, 4e-6 and 5e-4). Without the attitude
/// gain (k1 = 0) the jets would stop at 0.145 s and leave it turning forwards at +3.3 deg/s,
/// 0.29·ω0 away.
#[test]
fn the_rcs_attitude_hold_brakes_a_spin_as_its_switching_law_gives_on_every_engine() {
    let base = load("flat-drop.toml", &[]);
    let i_z = base.vehicle.inertia[(2, 2)];
    let (w0, a_core) = (20f64.to_radians(), 2.0); // rad/s, rad/s²
    let torque = a_core * i_z / (LBF * FT); // ft·lbf
    let (k1, k2, em) = (1.0, 0.3, 1f64.to_radians());
    for engine in Engine::ALL {
        let rigid = match engine {
            Engine::Core => "[footpad]\ndetached = \"rigid\"\n",
            _ => "",
        };
        let path = variant(
            "flat-drop.toml",
            &format!("rcs-hold-{engine}"),
            &format!(
                "[rcs]\nmode = \"attitude_hold\"\nattitude_gain = [{k1}, {k1}, {k1}]\n\
                 rate_gain = [{k2}, {k2}, {k2}]\ndeadband = [1.0, 1.0, 1.0]\n\
                 torque = [0.0, 0.0, {torque:.17e}]\ncommanded_attitude = [0.0, 0.0, 0.0]\n\
                 [touchdown]\nclearance = 20.0\nvertical_velocity = 0.0\n\
                 body_rates = [0.0, 0.0, 20.0]\n[integrator]\nt_end = 0.5\n{rigid}"
            ),
        );
        let (s, rows) = landed_with_history(engine, &path);
        assert!(
            s.first_contact_s.iter().all(Option::is_none),
            "{engine}: touched"
        );
        let (t, w) = (rows.column("t_s"), rows.column("omega_z_rad_s"));
        let tilt = ["theta_x_rad", "theta_y_rad"].map(|c| rows.column(c));
        let tilted = tilt.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
        assert!(tilted < 1e-6, "{engine}: tilted {tilted} rad");
        let at = |time: f64| t.iter().position(|&x| x >= time - 1e-12).unwrap();
        // the braking: the least-squares slope of ω over the first 0.15 s
        let k = at(0.15);
        let a = -slope(&t[..k], &w[..k]);
        if engine == Engine::Core {
            assert!(
                (a / a_core - 1.0).abs() < 1e-6,
                "core: brakes at {a} rad/s²"
            );
        }
        let (qa, qb, qc) = (-0.5 * k1 * a, k1 * w0 - k2 * a, k2 * w0 - em);
        let t_off = (-qb - (qb * qb - 4.0 * qa * qc).sqrt()) / (2.0 * qa);
        let w1 = w0 - a * t_off;
        // The jets' stop: the last 5 ms window braking at a/2 or more ends 2.5 ms after it
        // (the links' swing moves a multibody's ω by a few per cent of a·5 ms).
        let window = 5e-3;
        let off = (at(window)..w.len())
            .rev()
            .find(|&j| {
                let i = at(t[j] - window);
                w[i] - w[j] >= 0.5 * a * (t[j] - t[i])
            })
            .unwrap();
        let stopped = t[off] - 0.5 * window;
        assert!(
            (stopped - t_off).abs() <= 1e-3,
            "{engine}: the jets stopped at {stopped} s, the switching law gives {t_off} s"
        );
        let end = w.len() - 1;
        assert!(
            (w[end] - w1).abs() <= 1e-3 * w0,
            "{engine}: turns at {} rad/s after the jets stop, the switching law gives {w1}",
            w[end]
        );
    }
}

/// The RCS's downward translation in a run (eqs. 81-82), on every engine: on the symmetric drop,
/// with the attitude torques off and the translation 10 lbf along −Z_B from 0.02 s after the
/// first contact, the RCS does no work before its switch and afterwards exactly F·(z_s − z) on
/// the level vehicle, which the ledger books (negative, as driving work) and the balance
/// closes with. The switch falls within a step (between the last sample before it, z_{s−1},
/// and the first after, z_s): the booked work is between F·(z_s − z_end) and
/// F·(z_{s−1} − z_end), within 1 % (measured: 0.2 % above on the core, 0.4 % below on rapier
/// and MuJoCo); a force 5 % off, upwards, or from the contact on is far outside.
#[test]
fn the_rcs_translation_does_its_work_from_its_switch_on_every_engine() {
    let path = variant(
        "flat-drop.toml",
        "rcs-translation",
        "[rcs]\nmode = \"attitude_hold\"\nattitude_gain = [1.0, 1.0, 1.0]\n\
         rate_gain = [0.3, 0.3, 0.3]\ndeadband = [1.0, 1.0, 1.0]\ntorque = [0.0, 0.0, 0.0]\n\
         commanded_attitude = [0.0, 0.0, 0.0]\n\
         [rcs.downward_translation]\ndelay = 0.02\nforce = 10.0\n",
    );
    let force = 10.0 * LBF;
    for engine in Engine::ALL {
        let (s, rows) = landed_with_history(engine, &path);
        let (t, z, work) = (
            rows.column("t_s"),
            rows.column("z_m"),
            rows.column("mechanisms_j"),
        );
        let switch = t.iter().position(|&x| x >= 0.02 - 1e-12).unwrap();
        assert!(
            work[..switch].iter().all(|&w| w == 0.0),
            "{engine}: the RCS worked before its switch"
        );
        let end = z.len() - 1;
        let bounds = [switch, switch - 1].map(|k| force * (z[k] - z[end]));
        let booked = -work[end];
        assert!(
            booked >= bounds[0].min(bounds[1]) * 0.99 && booked <= bounds[0].max(bounds[1]) * 1.01,
            "{engine}: booked {booked} J, F·Δz from the switch {bounds:?} J"
        );
        let e = &s.energy;
        assert!(
            e.residual_j.abs() < 0.01 * (e.kinetic_initial_j - e.potential_change_j),
            "{engine}: {e:?}"
        );
    }
}
