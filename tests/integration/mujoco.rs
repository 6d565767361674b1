//! The MuJoCo export and runner (docs/engines.md, "The MuJoCo engine"): every scenario in `scenarios/` exports to MJCF that
//! the pinned MuJoCo (`mujoco-core` in the project's venv) loads, the model's keyframe is the
//! shared touchdown state, and the law-driven run (python/mujoco/run.py with the touchdown C
//! library) reproduces the analytic drop, closes its energy balance, and agrees with the core's
//! outcomes and with the other multibody (the rapier rebuild) on the strokes. A missing venv
//! fails with the command that creates it.

use std::process::Command;
use touchdown_mujoco::{GearIndex, MjArrays, ModelSizes};
use touchdown_mujoco::{MujocoError, MujocoLanding};
use touchdown_registry::{time_step, Engine};
use touchdown_scenario::schema::Detached;
use touchdown_scenario::{Scenario, ScenarioError};
use touchdown_tests::{
    assert_drop_strokes_to_the_energy_balance, mujoco, python, root, scenario, validation_landings,
    variant, FROUDE_TWIN,
};

#[test]
fn every_scenario_exports_to_a_model_mujoco_loads_in_the_touchdown_state() {
    let dir = std::env::temp_dir().join(format!("touchdown-mjcf-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut cases = Vec::new();
    for entry in std::fs::read_dir(scenario("")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let sc = Scenario::load(&path).unwrap();
            let xml = touchdown_mujoco::export(&sc).unwrap();
            let file = dir.join(path.file_stem().unwrap()).with_extension("xml");
            std::fs::write(&file, xml).unwrap();
            cases.push((file, sc));
        }
    }
    assert!(cases.len() >= 10, "{} scenarios", cases.len());
    let out = Command::new(python())
        .arg(root().join("python/mujoco/check_model.py"))
        .args(cases.iter().map(|(f, _)| f))
        .output()
        .expect("the venv's python runs");
    assert!(
        out.status.success(),
        "check_model.py failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let reports: Vec<serde_json::Value> = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(reports.len(), cases.len());
    for ((file, sc), r) in cases.iter().zip(&reports) {
        let name = file.display();
        let n = sc.legs.len();
        // A free joint (7 + 6) and per gear two trunnion hinges and the stroke.
        assert_eq!(r["nq"], 7 + 3 * n, "{name}");
        assert_eq!(r["nv"], 6 + 3 * n, "{name}");
        let actuators: Vec<&str> = r["actuators"]
            .as_array()
            .unwrap()
            .iter()
            .map(|a| a.as_str().unwrap())
            .collect();
        let expected: Vec<String> = (1..=n)
            .flat_map(|i| ["primary", "s31", "s41"].map(|a| format!("leg{i}_{a}")))
            .collect();
        assert_eq!(actuators, expected, "{name}: stable actuator names");
        // The secondary tendons start at the struts' lengths L31, L41.
        let lengths = r["tendon_lengths_m"].as_array().unwrap();
        for (i, leg) in sc.legs.iter().enumerate() {
            for (j, l0) in [leg.l31, leg.l41].into_iter().enumerate() {
                let l = lengths[2 * i + j].as_f64().unwrap();
                assert!(
                    (l - l0).abs() < 1e-9,
                    "{name}: leg {} tendon {j}: {l} vs {l0}",
                    i + 1
                );
            }
        }
        // The first footpad is on its plane (its sphere's centre one radius above the plane,
        // BP on it), touching; the others are above theirs.
        let heights = r["footpad_heights_m"].as_array().unwrap();
        let lowest = (0..sc.legs.len())
            .map(|k| heights[k].as_f64().unwrap() - sc.surface.pads[k].plane())
            .fold(f64::INFINITY, f64::min);
        assert!(lowest.abs() < 1e-9, "{name}: first footpad {lowest} m off");
        assert!(r["contacts"].as_u64().unwrap() >= 1, "{name}: no contact");
        // Only what the scene needs: a footpad on a frictionless surface has a frictionless
        // contact, locked or not (its restraint is the wall's, not the contact's).
        for (i, pad) in sc.surface.pads.iter().enumerate() {
            let want = if pad.friction > 0.0 { 3 } else { 1 };
            assert_eq!(r["footpad_condim"][i], want, "{name}: leg {} condim", i + 1);
        }
        let step = time_step(Engine::Mujoco, sc).unwrap();
        assert_eq!(r["timestep_s"], step, "{name}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_export_is_deterministic_and_names_its_scenario() {
    let sc = Scenario::load(scenario("fig-25-26.toml")).unwrap();
    let a = touchdown_mujoco::export(&sc).unwrap();
    let b = touchdown_mujoco::export(&Scenario::load(scenario("fig-25-26.toml")).unwrap()).unwrap();
    assert_eq!(a, b);
    let hash = sc.sha256();
    assert_eq!(hash.len(), 64);
    assert!(a.contains(&hash) && a.contains(touchdown_mujoco::GENERATOR));
    let other = Scenario::load(scenario("table-i-2-2-vv8.toml")).unwrap();
    assert_ne!(other.sha256(), hash);
}

/// The symmetric vertical drop strokes to the energy balance on MuJoCo, on both gear
/// arrangements (`tests/integration/physics.rs` for the core and rapier).
#[test]
fn the_symmetric_drop_strokes_as_the_analytic_value_on_mujoco() {
    for name in ["flat-drop.toml", "tripod-drop.toml"] {
        let path = scenario(name);
        let sc = Scenario::load(&path).unwrap();
        let s = mujoco(&path, "engine");
        assert_eq!(s.engine, "mujoco");
        assert_drop_strokes_to_the_energy_balance(&sc, &s);
    }
}

/// The stroke joints' dry friction, the bearing friction μB·(F1 + F2), acts in the step the laws
/// computed it for: the runner writes it into the joint's friction row after `mj_step1` has built
/// the rows (`FRICTION_ROW_PLACEHOLDER`, crates/mujoco/src/mjcf.rs). Written into the model's
/// `dof_frictionloss`, as it once was, it acts a step late, and each hand-over of the bound
/// leaves about Δt·F·v in the balance. The 2-2 landing at 8 ft/s with μB = 0.3, whose bearings
/// take 19 J of its 136 J, closes its balance within 1e-4 of its touchdown kinetic energy at
/// 20 µs and at 10 µs: +0.0061 J and +0.0030 J; with the row a step late (a scratch build,
/// 2026-12-03) +0.054 J and +0.027 J (docs/engines.md, "Energy ledger").
///
/// Until 2026-12-03 the row carried the crush plateau too, and this test held the hard landing
/// of the paired campaign (Vh 26.8 ft/s, Vv 5 ft/s, slope 8°, heading 10°) to the same bound:
/// −0.014 J and +0.049 J of 1,008 J, 0.60 J and 0.30 J with the row a step late. With the
/// plateau an explicit force (docs/engines.md, "Model" of the MuJoCo engine) that landing gave
/// +0.103, +0.042, +0.017 and −0.0006 J at 20, 10, 5 and 2.5 µs (+0.53 and +0.18 J with the
/// bearing row a step late): its first-order part at 20 µs, 1.03e-4 of its energy, accrued as
/// the secondaries' end stops let go of an airborne footpad, not in the row. Without the
/// contacts' lock friction ("The footpad's lateral restraint") it gives +0.125, +0.028, +0.025
/// and +0.008 J.
#[test]
fn the_stroke_joints_bearing_friction_acts_in_its_own_step_on_mujoco() {
    let rough = "[primary_strut.bearing]\nfriction = 0.3\n";
    for step in ["2.0e-5", "1.0e-5"] {
        let name = format!("bearing-friction-{step}");
        let extra = format!("{rough}[engines.mujoco]\ntimestep = {step}\n");
        let s = mujoco(&variant("table-i-2-2-vv8.toml", &name, &extra), &name);
        let (r, energy) = (s.energy.residual_j, s.energy.kinetic_initial_j);
        // The bearings do a part of the landing's work that a row a step late would show.
        assert!(
            s.energy.bearing_friction_j > 0.1 * energy,
            "{} J of bearing work of {energy} J at a step of {step} s",
            s.energy.bearing_friction_j
        );
        assert!(
            r.abs() < 1e-4 * energy,
            "{r} J of {energy} J at a step of {step} s"
        );
    }
}

/// A honeycomb held below its crush load does not crush, and gives back its rebound: after its
/// second impact (0.34 s) the 2-2 landing at 8 ft/s rocks on its leading legs, whose primaries
/// carry at most 764 N of their 1,136 N crush load and stroke between 34.6 and 43.8 mm from 0.36
/// to 0.62 s (the core 34.5 to 43.7 mm, rapier 34.6 to 43.8). The test asks each of them to
/// stroke over at least 4 mm there. With the crush load in the stroke joint's dry-friction row,
/// as it was until 2026-12-03, the row held the strut both ways and its soft creep kept it on
/// the plateau: the leading primaries stayed between 43.86 and 43.89 mm, the honeycomb crushing
/// below its crush load and keeping its rebound (docs/engines.md, "Model" of the MuJoCo engine).
#[test]
fn a_honeycomb_below_its_crush_load_gives_back_its_rebound_on_mujoco() {
    let path = variant(
        "table-i-2-2-vv8.toml",
        "rocking-on-the-leading-legs",
        "[integrator]\nt_end = 0.62\n",
    );
    let (_, rows) =
        crate::mechanisms::landed_with_history(touchdown_scenario::schema::Engine::Mujoco, &path);
    let t = rows.column("t_s");
    for leg in [1, 2] {
        let stroke = rows.column(&format!("leg{leg}_primary_stroke_m"));
        let window = || {
            t.iter()
                .zip(&stroke)
                .filter(|(t, _)| (0.36..=0.62).contains(*t))
                .map(|(_, c)| *c)
        };
        let low = window().fold(f64::INFINITY, f64::min);
        let high = window().fold(f64::NEG_INFINITY, f64::max);
        assert!(
            high - low > 4e-3,
            "leg {leg}: its primary between {low} and {high} m from 0.36 to 0.62 s"
        );
    }
}

/// A footpad that starts on its plane bears from the first step, on the model and on its Froude
/// twin alike: the contacts' margin of a millionth of the contact width (docs/engines.md,
/// "Froude twins") keeps the last bit of the touchdown pose from deciding it. Without it the
/// flat drop's four footpads, exactly on their planes, first bore at the end of the second
/// step, and `fig-25-26`'s twin parted from its model from that step on.
#[test]
fn footpads_on_their_planes_at_touchdown_bear_from_the_first_step_on_mujoco() {
    let window = "[integrator]\nt_end = 0.001\n";
    for (name, extra) in [
        ("model", window.to_string()),
        ("twin", format!("{FROUDE_TWIN}{window}")),
    ] {
        let path = variant("flat-drop.toml", &format!("first-step-{name}"), &extra);
        let sc = Scenario::load(&path).unwrap();
        let step = time_step(Engine::Mujoco, &sc).unwrap();
        let s = mujoco(&path, &format!("first-step-{name}"));
        for (leg, first) in s.first_contact_s.iter().enumerate() {
            assert_eq!(*first, Some(step), "{name} leg {}: {first:?}", leg + 1);
        }
    }
}

/// A fully plastic end stop (e = 0) lands on MuJoCo, to its bottomed secondaries, with its
/// balance within 1 % of the energy put in (0.03 %); the core and rapier:
/// `physics::a_plastic_stop_lands_on_every_engine`.
#[test]
fn a_plastic_stop_lands_on_mujoco() {
    let (name, extra) = crate::physics::PLASTIC_STOPS_TO_THE_BOTTOMING;
    let s = mujoco(&variant("fig-25-26.toml", name, extra), name);
    crate::physics::assert_plastic_stops_land(&s);
}

/// The landings and legs whose largest primary strokes MuJoCo and rapier land 3 % to 5 % of the
/// landing's largest stroke apart, where both are determined
/// (`every_table_i_landing_on_mujoco_closes_its_balance_and_agrees_with_core_and_rapier`).
const APART_FROM_RAPIER: [(&str, usize); 1] = [("fig-25-26.toml", 3)];

/// Every Table I landing and `fig-25-26` on MuJoCo: its balance, its outcome, and its primaries
/// against rapier's and the core's wherever they are determined. Two probes say where they are
/// not (docs/engines.md, "Rounding-decided channels"): the core's copies, and on a landing that
/// is its own mirror image each multibody engine's two mirror legs, one stroke landed twice,
/// which its copies do not probe (rapier's solver takes the joints in the legs' order, and
/// neither engine's arithmetic is mirror-exact under the 2-2 landings' mirror, which exchanges
/// the body's x and y: `a_mirror_symmetric_landing_starts_symmetric_on_mujoco`). The second
/// probe replaced a list of known disagreements: MuJoCo's uphill primaries of `fig-25-26`
/// (12.4 and 16.0 mm on its mirror legs 3 and 4, rapier 16.5 and 19.0 mm) and of
/// `table-i-2-2-vv4` (6.17 and 6.85 mm, rapier 6.03 and 6.03 mm) while the core made the 2-2
/// landings its own mirror images only to rounding and MuJoCo's trunnions took their hinges in
/// an order set by the body axes.
///
/// One disagreement with rapier is listed, [`APART_FROM_RAPIER`], and the test fails if it goes
/// away or grows past 5 % of the largest stroke: `fig-25-26`'s uphill primary of leg 3, made as
/// the vehicle rocks back onto it at about 0.7 s, 15.39 mm on MuJoCo against 13.03 mm on rapier
/// (3.4 % of the largest stroke; its mirror leg 4, 15.21 against 13.21 mm, 2.9 %), the core's
/// 16.64 mm. Until 2026-12-03 the list was the leading primaries, 68.54 and 68.78 mm on MuJoCo
/// against 65.75 and 65.92 mm on rapier (4.1 and 4.2 %); they are 67.04 and 66.77 against 68.57
/// and 68.21 mm since rapier's trunnions are universal joints and neither engine locks a
/// footpad by its contact's friction beside its spikes' wall (docs/engines.md, "Model" of the
/// rapier rebuild, "The footpad's lateral restraint").
#[test]
fn every_table_i_landing_on_mujoco_closes_its_balance_and_agrees_with_core_and_rapier() {
    let mut failures = vec![];
    let mut undetermined = vec![];
    let mut apart = vec![];
    for name in validation_landings() {
        let path = scenario(&name);
        let sc = Scenario::load(&path).unwrap();
        // The core's footpad with inertia (the default), held by the same restraint as the
        // multibody engines' (docs/errata.md, "Footpads with inertia"): the same model as
        // theirs. (The report's massless footpad parts from them by up to 26 %:
        // docs/engines.md.)
        assert_eq!(sc.footpad.detached, Detached::Inertial, "{name}");
        let core = touchdown_core::run(&sc).unwrap();
        // The core's rounding ensemble (docs/engines.md, "Rounding-decided channels"): its
        // copies with the touchdown velocity moved by one unit in the last place across.
        let copies = touchdown_compare::rounding::CROSSWISE_ULPS.map(|u| {
            touchdown_core::run(&touchdown_compare::rounding::crosswise(&sc, u).unwrap()).unwrap()
        });
        let rapier = touchdown_rapier::run(&sc).unwrap();
        let mj = mujoco(&path, "engine");
        // On a landing that is its own mirror image (leg i's image is leg `mirror.legs[i]`)
        // an engine's two mirror legs are one stroke landed twice: how far apart it lands them
        // is its own arithmetic's, a spread its copies do not probe on rapier and MuJoCo, whose
        // solvers are not mirror-symmetric (docs/engines.md, "Rounding-decided channels").
        let mirror = touchdown_scenario::mirror::self_mirror(&sc);
        let e = &mj.energy;
        assert!(
            e.residual_j.abs() < 0.01 * e.kinetic_initial_j,
            "{name}: residual {} J of {} J",
            e.residual_j,
            e.kinetic_initial_j
        );
        assert_eq!(mj.outcome, core.outcome, "{name}: outcome");
        let largest = core
            .max_primary_stroke_m
            .iter()
            .cloned()
            .fold(0.0, f64::max);
        for (i, ((m, c), r)) in mj
            .max_primary_stroke_m
            .iter()
            .zip(&core.max_primary_stroke_m)
            .zip(&rapier.max_primary_stroke_m)
            .enumerate()
        {
            // Both multibody engines carry the same gear: they agree with each other. (MuJoCo's
            // mirror-twin legs on the slow 2-2 landing parted by 2 mm while its detached
            // trailing gears swung free; the restraint now holds them,
            // touchdown_multibody::wall.)
            let partner = mirror.as_ref().map(|legs| legs[i]).filter(|&p| p != i);
            let own_gap = |s: &[f64]| partner.map_or(0.0, |p| (s[i] - s[p]).abs());
            let mj_gap = own_gap(&mj.max_primary_stroke_m);
            let gaps = [mj_gap, own_gap(&rapier.max_primary_stroke_m)];
            if gaps.iter().any(|g| *g >= 0.03 * largest) {
                undetermined.push(format!(
                    "{name} leg {}: mujoco {m:.5} m, rapier {r:.5} m; each one's mirror legs {:.5} and {:.5} m apart",
                    i + 1,
                    gaps[0],
                    gaps[1]
                ));
            } else if (m - r).abs() >= 0.03 * largest {
                apart.push((name.clone(), i + 1));
                if (m - r).abs() >= 0.05 * largest {
                    failures.push(format!("{name} leg {}: mujoco {m} m, rapier {r} m", i + 1));
                }
            }
            // Within 10 % of the core's stroke (of a tenth of the largest, for small strokes):
            // the agreement docs/validation.md states as the target for the core and the
            // multibody engines, on every landing. Where the core's own copies part by more
            // than that, or give different verdicts, rounding decides the stroke and there is
            // no verdict (the uphill primaries of the slow 2-2 landings, which the vehicle
            // makes as it rocks back onto them: 8-14 %).
            let limit = |c: f64| 0.10 * c.max(0.1 * largest);
            let members = [
                *c,
                copies[0].max_primary_stroke_m[i],
                copies[1].max_primary_stroke_m[i],
            ];
            let (lo, hi) = members
                .iter()
                .fold((f64::MAX, 0.0_f64), |(lo, hi), &x| (lo.min(x), hi.max(x)));
            let verdicts: Vec<bool> = members.iter().map(|&c| (m - c).abs() < limit(c)).collect();
            if hi - lo >= limit(*c)
                || mj_gap >= limit(*c)
                || verdicts.iter().any(|&v| v != verdicts[0])
            {
                undetermined.push(format!(
                    "{name} leg {}: mujoco {m:.5} m, core {lo:.5}-{hi:.5} m",
                    i + 1
                ));
            } else if !verdicts[0] {
                failures.push(format!("{name} leg {}: mujoco {m} m, core {c} m", i + 1));
            }
        }
    }
    eprintln!(
        "not determined at this precision:\n{}",
        undetermined.join("\n")
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    let listed: Vec<(String, usize)> = APART_FROM_RAPIER
        .iter()
        .map(|&(name, leg)| (name.to_string(), leg))
        .collect();
    assert_eq!(apart, listed, "primaries 3 % or more apart from rapier's");
    // Seven today: `fig-25-26`'s uphill primary of leg 4 against the core's copies, the uphill
    // primaries of the 2-2 landings at 4 and 6 ft/s against the core's copies, and those at
    // 6 ft/s against rapier, which parts its mirror legs by 1.1 mm there; more is a landing
    // that rounding newly decides, to look at.
    assert!(undetermined.len() <= 7, "{}", undetermined.join("\n"));
}

#[test]
fn a_time_step_too_large_for_the_stiffest_law_is_refused_by_the_mujoco_engine() {
    let sc = Scenario::load(scenario("flat-drop.toml"))
        .unwrap()
        .with_mujoco(|m| {
            m.timestep = Some(1e-3);
            m.contact_timeconst = Some(2e-3);
        })
        .unwrap();
    match MujocoLanding::new(&sc, Vec::new(), ModelSizes::default(), "test", None) {
        Err(MujocoError::Scenario(ScenarioError::Field { field, message, .. })) => {
            assert_eq!(field, "engines.mujoco.timestep");
            assert!(message.contains("ω·Δt"), "{message}");
        }
        Err(e) => panic!("unexpected error {e}"),
        Ok(_) => panic!("a 1 ms step was accepted"),
    }
}

#[test]
fn a_mujoco_warning_stops_the_run_with_a_diagnostic() {
    // MuJoCo answers a bad acceleration by resetting the state and counting a warning: the
    // landing must stop there, naming the warning, rather than go on from the reset state.
    let sc = Scenario::load(scenario("flat-drop.toml")).unwrap();
    let n = sc.legs.len();
    let index: Vec<GearIndex> = (0..n as i32)
        .map(|i| GearIndex {
            stroke_qpos: 7 + 3 * i + 2,
            stroke_dof: 6 + 3 * i + 2,
            tendon: [2 * i, 2 * i + 1],
            primary: 3 * i,
            secondary: [3 * i + 1, 3 * i + 2],
            trunnion: [2 * i, 2 * i + 1],
            point1: 2 * n as i32 + i,
            outer: 1 + 2 * i,
            footpad: 2 + 2 * i,
            contact: 10 * i,
            pad_velocity: 10 * i + 4,
            pad_rate: 10 * i + 7,
        })
        .collect();
    let sizes = ModelSizes {
        nq: 7 + 3 * n as i32,
        nv: 6 + 3 * n as i32,
        nu: 3 * n as i32,
        ntendon: 2 * n as i32,
        nsite: 3 * n as i32,
        nbody: 1 + 2 * n as i32,
        nsensordata: 10 * n as i32,
    };
    let mut landing = MujocoLanding::new(&sc, index, sizes, "test", None).unwrap();
    let mut qpos = vec![0.0; sizes.nq as usize];
    qpos[3] = 1.0;
    let qvel = vec![0.0; sizes.nv as usize];
    let tendons = vec![1.0; 2 * n];
    let sites = vec![0.0; 9 * n];
    let mut xpos = vec![0.0; 3 * (1 + 2 * n)];
    for i in 0..n {
        xpos[3 * (2 + 2 * i) + 2] = -1.0; // footpads below their trunnions
    }
    let sensors = vec![0.0; 10 * n];
    let energy = [0.0; 2];
    let mut warnings = [0; 7];
    warnings[5] = 1; // mjWARN_BADQACC
    let mut ctrl = vec![0.0; 3 * n];
    let mut friction = vec![0.0; n];
    let mut applied = vec![0.0; sizes.nv as usize];
    let mut body_applied = vec![0.0; 6 * sizes.nbody as usize];
    let mut arrays = MjArrays {
        qpos: &qpos,
        qvel: &qvel,
        ten_length: &tendons,
        ten_velocity: &tendons,
        site_xpos: &sites,
        xpos: &xpos,
        sensordata: &sensors,
        energy: &energy,
        warnings: &warnings,
        ctrl: &mut ctrl,
        friction_bound: &mut friction,
        qfrc_applied: &mut applied,
        xfrc_applied: &mut body_applied,
    };
    match landing.advance(&mut arrays) {
        Err(MujocoError::Diverged(d)) => {
            assert_eq!(d.law, touchdown_record::Law::Solver);
            assert!(d.message.contains("bad qacc"), "{}", d.message);
        }
        Err(e) => panic!("unexpected error {e}"),
        Ok(_) => panic!("a MuJoCo warning went unnoticed"),
    }
}

/// A runner (in `dir`) that is `python/mujoco/run.py` with every model's arena cut to 12 KiB
/// (`<size memory>`): enough to start the 2-2 landing at 8 ft/s, too little for MuJoCo's
/// constraint solver once its footpads touch (`mj_stackAlloc: out of memory`, an `mju_error`).
fn runner_with_a_small_arena(dir: &std::path::Path) -> std::path::PathBuf {
    let wrapper = dir.join("small_arena_run.py");
    let runner = root().join("python/mujoco/run.py");
    std::fs::write(
        &wrapper,
        format!(
            r#"import re, runpy, sys
import mujoco
compile_xml = mujoco.MjModel.from_xml_string
mujoco.MjModel.from_xml_string = lambda xml: compile_xml(
    re.sub(r"(<mujoco[^>]*>)", r'\1<size memory="12K"/>', xml, count=1)
)
sys.argv[0] = {runner:?}
runpy.run_path({runner:?}, run_name="__main__")
"#
        ),
    )
    .unwrap();
    wrapper
}

#[test]
fn a_mujoco_error_in_a_step_stops_the_landing_with_a_diagnostic_on_every_loop() {
    // An `mju_error` never returns to MuJoCo's caller. In the library's loop the runner's
    // handler writes the landing's diagnostic and ends the process with the stopped status; a
    // serving runner then ends too, and says so; in a loop Python keeps (`--profile`) the error
    // comes back as `mujoco.FatalError` and stops the landing the same way.
    let dir = tempfile::tempdir().unwrap();
    let located = touchdown_mujoco::Launch::locate().unwrap_or_else(|e| panic!("{e}"));
    let launch = touchdown_mujoco::Launch {
        runner: runner_with_a_small_arena(dir.path()),
        ..located
    };
    let path = scenario("table-i-2-2-vv8.toml");
    let t_end = Scenario::load(&path).unwrap().integrator.t_end;
    let stopped_in_the_step = |result: Result<touchdown_record::Summary, MujocoError>| match result
    {
        Err(MujocoError::Diverged(d)) => {
            assert_eq!(d.law, touchdown_record::Law::Solver);
            assert!(d.message.contains("mj_stackAlloc"), "{}", d.message);
            assert!(!d.message.contains('\n'), "one line: {}", d.message);
            assert!(d.time_s > 0.0 && d.time_s < t_end, "t = {} s", d.time_s);
            assert!(d.state.position_m.iter().all(|x| x.is_finite()));
        }
        Err(e) => panic!("unexpected error {e}"),
        Ok(_) => panic!("the landing completed in a 12 KiB arena"),
    };
    let out = dir.path().join("plain");
    stopped_in_the_step(launch.run(&path, &out, false));
    assert!(
        !out.join("MUJOCO_LOG.TXT").exists(),
        "the error is the diagnostic's, not a log's"
    );

    let mut worker = launch.worker().unwrap();
    stopped_in_the_step(worker.run(&path, &dir.path().join("served"), false));
    assert!(
        worker.ended(),
        "a serving runner that met a MuJoCo error has ended"
    );

    let profiled = dir.path().join("profiled");
    let status = Command::new(&launch.python)
        .arg(&launch.runner)
        .arg(&path)
        .arg("--out")
        .arg(&profiled)
        .arg("--library")
        .arg(&launch.library)
        .arg("--profile")
        .output()
        .unwrap();
    assert_eq!(
        status.status.code(),
        Some(touchdown_mujoco::RUNNER_STOPPED_STATUS),
        "{}",
        String::from_utf8_lossy(&status.stderr)
    );
    let diagnostic = std::fs::read_to_string(profiled.join("divergence.json")).unwrap();
    let d: touchdown_record::Divergence = serde_json::from_str(&diagnostic).unwrap();
    stopped_in_the_step(Err(MujocoError::Diverged(Box::new(d))));
}

/// Spikes, not a wall (docs/errata.md, "Spikes, not a wall"), on MuJoCo: its obstacle wall
/// lets go of a footpad that lifts out of the ground, as the core's and the rebuild's do
/// (`rapier.rs`, `a_spike_lets_go_of_a_footpad_that_lifts_out`).
#[test]
fn a_spike_lets_go_of_a_footpad_that_lifts_out_on_mujoco() {
    let path = touchdown_tests::spiked_fig_25_26("spiked-mujoco");
    let sc = Scenario::load(&path).unwrap();
    let out = tempfile::tempdir().unwrap();
    let launch = touchdown_mujoco::Launch::locate().unwrap_or_else(|e| panic!("{e}"));
    launch
        .run(&path, out.path(), true)
        .unwrap_or_else(|e| panic!("{e}"));
    let mut samples = Vec::new();
    touchdown_record::history::read(&out.path().join("history.csv"), |s| samples.push(s.clone()))
        .unwrap();
    touchdown_tests::assert_spikes_let_go_of_flying_footpads("mujoco", &sc, &samples);
}

/// A landing that is its own mirror image starts mirror-symmetric on MuJoCo: `fig-25-26` (a
/// 2-2 landing straight down its slope: leg 1's image is leg 2, leg 3's leg 4, each one's
/// secondaries exchanged), run through its uphill footpads' landing on their spikes (20 ms),
/// lands each mirror pair's strut and restraint forces alike within 1e-8 of the largest of
/// them, as the core does bit for bit. Later its rocking amplifies what asymmetry the solver's
/// arithmetic leaves (docs/engines.md, "Rounding-decided channels"). With the trunnions'
/// universal joints taking their hinges in an order set by the body axes (the tangential hinge
/// first on legs 1 and 3, last on legs 2 and 4), the restraint forces of legs 3 and 4 parted by
/// 7e-5 of the largest at the first step, and the uphill primaries came to 10.0 and 16.3 mm.
/// (rapier's part by 3e-5 within 2 ms: its solver takes the joints in the legs' order.)
#[test]
fn a_mirror_symmetric_landing_starts_symmetric_on_mujoco() {
    let path = variant(
        "fig-25-26.toml",
        "mirror-start",
        "[integrator]\nt_end = 0.02\n",
    );
    let sc = Scenario::load(&path).unwrap();
    let image = touchdown_scenario::mirror::self_mirror(&sc).expect("its own mirror image");
    let (_, rows) =
        crate::mechanisms::landed_with_history(touchdown_scenario::schema::Engine::Mujoco, &path);
    let pairs = [
        ("primary", "primary"),
        ("sec31", "sec41"),
        ("sec41", "sec31"),
        ("restraint", "restraint"),
    ];
    let mut columns = vec![];
    for (i, &j) in image.iter().enumerate() {
        for (a, b) in pairs {
            let force = |leg: usize, strut: &str| rows.column(&format!("leg{leg}_{strut}_force_n"));
            columns.push((
                format!("leg {} {a} and leg {} {b}", i + 1, j + 1),
                force(i + 1, a),
                force(j + 1, b),
            ));
        }
    }
    let largest = columns
        .iter()
        .flat_map(|(_, x, _)| x.iter())
        .fold(0.0_f64, |m, f| m.max(f.abs()));
    assert!(
        largest > 100.0,
        "the uphill footpads land within the run: {largest} N"
    );
    for (name, x, y) in &columns {
        let worst = x
            .iter()
            .zip(y)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(
            worst <= 1e-8 * largest,
            "{name}: {worst} N apart, {:.1e} of the largest force {largest} N",
            worst / largest
        );
    }
}
