//! The rapier rebuild (docs/engines.md, "The rapier rebuild"): it starts where the core starts, closes its energy balance,
//! agrees with the core on every Table I
//! outcome, and the two mechanisms that make it part from the core on some strokes
//! (docs/engines.md, "Where the rebuild parts from the core") are pinned here.

use touchdown_core::Simulation;
use touchdown_rapier::{RapierSimulation, RunError};
use touchdown_record::{Landing, Observer, Sample};
use touchdown_scenario::initial::initial_state;
use touchdown_scenario::schema::Detached;
use touchdown_scenario::{Scenario, ScenarioError};
use touchdown_tests::{scenario, validation_landings};

/// The history of a landing on one engine, one sample per step (a template sample sized for
/// the scenario's legs, then the samples).
struct History(Sample, Vec<Sample>);

impl<L: Landing> Observer<L> for History {
    fn observe(&mut self, landing: &L) {
        landing.sample(&mut self.0);
        self.1.push(self.0.clone());
    }
}

fn histories(name: &str) -> (History, History) {
    histories_of(&Scenario::load(scenario(name)).unwrap())
}

/// The histories of `sc` on the core and on the rebuild.
fn histories_of(sc: &Scenario) -> (History, History) {
    let mut core = History(Sample::new(sc.legs.len()), Vec::new());
    Simulation::new(sc).unwrap().run(&mut core).unwrap();
    let mut rapier = History(Sample::new(sc.legs.len()), Vec::new());
    RapierSimulation::new(sc).unwrap().run(&mut rapier).unwrap();
    (core, rapier)
}

fn flat_drop() -> Scenario {
    Scenario::load(scenario("flat-drop.toml")).unwrap()
}

#[test]
fn starts_from_the_shared_touchdown_state() {
    let sc = Scenario::load(scenario("table-i-2-2-vv8.toml")).unwrap();
    let init = initial_state(&sc);
    let sim = RapierSimulation::new(&sc).unwrap();
    let mut s = Sample::new(sc.legs.len());
    sim.sample(&mut s);
    assert!(
        (s.position - init.position).norm() < 1e-12,
        "{:?}",
        s.position
    );
    assert!((s.velocity - init.velocity).norm() < 1e-12);
    assert!(
        (s.theta - init.theta).norm() < 1e-9,
        "{:?} {:?}",
        s.theta,
        init.theta
    );
    for (leg, g) in sc.legs.iter().zip(&s.legs) {
        let pad = init.position + init.t_bi * leg.bp;
        assert!((g.pad_position - pad).norm() < 1e-9);
        assert!(g.primary_stroke.abs() < 1e-12 && g.secondary_stroke[0].abs() < 1e-12);
    }
    // The first footpad is on its plane; the engine starts undecided with no energy exchanged.
    let lowest = (s.legs.iter().zip(&sc.surface.pads))
        .map(|(g, pad)| g.pad_position.z - pad.plane())
        .fold(f64::INFINITY, f64::min);
    assert!(lowest.abs() < 1e-12, "{lowest}");
    assert_eq!(s.energy.residual_j, 0.0);
}

#[test]
fn the_footpads_impact_is_booked_as_contact_work() {
    // Level drop: the four footpads (PMASS each) stop on the first step; the kinetic energy
    // they lose is the work of the contact impulses, and the balance closes over the impact.
    let sc = flat_drop();
    let mut sim = RapierSimulation::new(&sc).unwrap();
    for _ in 0..10 {
        sim.step().unwrap();
    }
    let e = sim.energy();
    let v = sc.touchdown.velocity_g.z;
    let pads = 4.0 * 0.5 * sc.footpad.mass * v * v;
    assert!(
        (e.contact_events_j + pads).abs() < 0.02 * pads,
        "contact work {} J, footpads' kinetic energy {pads} J",
        e.contact_events_j
    );
    assert!(e.residual_j.abs() < 1e-3 * e.kinetic_initial_j, "{e:?}");
}

#[test]
fn a_footpad_pressed_into_its_contact_books_the_work_of_its_sinking() {
    // A 30 ft/s drop bottoms every primary: 7e4 N press each footpad 0.4 mm into its soft
    // contact, a motion rapier's position correction makes without a velocity. Its work is
    // booked: unbooked, it left a residual of 57 J (4.5 % of the energy put in) whatever the
    // step; booked, what is left is within half a per cent of it at 20 and 10 µs (-2.2 and
    // -1.7 J of 1.26 kJ, the step's own error, docs/engines.md "Energy ledger").
    let residual = |dt: f64| {
        let sc = Scenario::load_with(
            scenario("stroke-out.toml"),
            &[("touchdown.vertical_velocity", -30.0)],
        )
        .unwrap()
        .with_integrator(|i| {
            i.t_end = 0.03;
            i.energy_tolerance = 1.0;
        })
        .unwrap()
        .with_rapier(|r| r.timestep = Some(dt))
        .unwrap();
        let mut sim = RapierSimulation::new(&sc).unwrap();
        sim.run(&mut ()).unwrap();
        let e = sim.energy();
        assert!(e.contact_events_j < 0.0, "{e:?}");
        (e.residual_j, e.scale())
    };
    for dt in [2e-5, 1e-5] {
        let (r, scale) = residual(dt);
        assert!(
            r.abs() < 5e-3 * scale,
            "residual {r} J of {scale} J at {dt} s"
        );
    }
}

#[test]
fn a_time_step_too_large_for_the_stiffest_law_is_refused() {
    let sc = flat_drop()
        .with_rapier(|r| r.timestep = Some(1e-3))
        .unwrap();
    match RapierSimulation::new(&sc) {
        Err(RunError::Refused(ScenarioError::Field { field, message, .. })) => {
            assert_eq!(field, "engines.rapier.timestep");
            assert!(message.contains("ω·Δt"), "{message}");
        }
        Err(e) => panic!("unexpected error {e}"),
        Ok(_) => panic!("a 1 ms step was accepted"),
    }
}

#[test]
fn a_time_step_beyond_the_run_budget_is_refused_before_the_run() {
    let sc = flat_drop()
        .with_rapier(|r| r.timestep = Some(1e-300))
        .unwrap();
    match RapierSimulation::new(&sc) {
        Err(RunError::Refused(ScenarioError::Field { field, message, .. })) => {
            assert_eq!(field, "engines.rapier.timestep");
            assert!(message.contains("run budget"), "{message}");
        }
        Err(e) => panic!("unexpected error {e}"),
        Ok(_) => panic!("a 1e-300 s step was accepted"),
    }
}

#[test]
fn engine_settings_are_checked_like_file_fields() {
    let e = flat_drop()
        .with_rapier(|r| r.timestep = Some(0.0))
        .unwrap_err();
    assert!(e.to_string().contains("engines.rapier.timestep"), "{e}");
    let e = flat_drop()
        .with_rapier(|r| r.contact_frequency = Some(-1.0))
        .unwrap_err();
    assert!(
        e.to_string().contains("engines.rapier.contact_frequency"),
        "{e}"
    );
}

/// Between the end stops the rebuild may take several base steps at once
/// (`engines.rapier.stride`; docs/engines.md, "A longer step between the stops"), but not on a
/// scene whose obstacle walls or spikes hold its footpads: they are built for the base step,
/// as the curbs and a descent engine's nozzle are. The 2-2 landing at 8 ft/s takes the same
/// steps with stride 2 as without, on its spikes; with them left out (its footpads sliding
/// frictionless), at a base step of 10 µs, where no stop engages, two base steps at once take
/// about half the steps over the impacts' 0.5 s, close the energy balance, and move each leg's
/// maxima by no more than twice the base step's own convergence (the step halved): at first
/// order an error C·h at the base step is C·h/2 at half of it and at most 2·C·h at the long
/// step, so the long step's change from the base step is at most C·h, twice the convergence.
#[test]
fn a_longer_step_between_the_stops_halves_the_steps_within_the_step_convergence() {
    let spiked = (Scenario::load(scenario("table-i-2-2-vv8.toml")).unwrap())
        .with_integrator(|it| it.t_end = 0.5)
        .unwrap();
    let file_step = spiked.rapier.timestep.unwrap();
    let land = |sc: &Scenario, timestep: f64, stride: f64| {
        let sc = (sc.clone())
            .with_rapier(|r| {
                r.timestep = Some(timestep);
                r.stride = Some(stride);
            })
            .unwrap();
        touchdown_rapier::run(&sc).unwrap()
    };
    for step in [file_step, 0.5 * file_step] {
        assert_eq!(
            land(&spiked, step, 2.0).steps,
            land(&spiked, step, 1.0).steps,
            "the spikes' walls keep the base step of {step} s"
        );
    }
    let path = touchdown_tests::variant(
        "table-i-2-2-vv8.toml",
        "vv8-sliding",
        "[surface]\nspike_depth = 0.0\n[integrator]\nt_end = 0.5\n",
    );
    let sc = Scenario::load(&path).unwrap();
    let land = |timestep: f64, stride: f64| land(&sc, timestep, stride);
    let base = 0.5 * file_step;
    let (fixed, half, long) = (land(base, 1.0), land(0.5 * base, 1.0), land(base, 2.0));
    assert!(
        (long.steps as f64) < 0.55 * fixed.steps as f64,
        "{} steps against {}",
        long.steps,
        fixed.steps
    );
    let e = &long.energy;
    assert!(
        e.residual_j.abs() < 0.01 * e.kinetic_initial_j,
        "residual {} J of {} J",
        e.residual_j,
        e.kinetic_initial_j
    );
    assert_eq!(long.outcome, fixed.outcome);
    let channels = |s: &touchdown_record::Summary| {
        let mut c = s.max_primary_stroke_m.clone();
        c.extend(s.max_secondary_compression_m.iter().flatten());
        c.extend(s.max_secondary_tension_m.iter().flatten());
        c
    };
    let (f, h, l) = (channels(&fixed), channels(&half), channels(&long));
    let convergence = f
        .iter()
        .zip(&h)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    for (i, (a, b)) in f.iter().zip(&l).enumerate() {
        assert!(
            (a - b).abs() <= 2.0 * convergence,
            "channel {i}: {b} m against {a} m at the base step; the step halved moves a maximum by up to {convergence} m"
        );
    }
}

#[test]
fn every_table_i_landing_closes_its_balance_and_agrees_on_the_outcome() {
    for name in validation_landings() {
        let sc = Scenario::load(scenario(&name)).unwrap();
        let core = touchdown_core::run(&sc).unwrap();
        let rapier = touchdown_rapier::run(&sc).unwrap_or_else(|e| panic!("{name}: {e}"));
        let e = &rapier.energy;
        assert!(
            e.residual_j.abs() < 0.01 * e.kinetic_initial_j,
            "{name}: residual {} J of {} J",
            e.residual_j,
            e.kinetic_initial_j
        );
        assert_eq!(core.outcome, rapier.outcome, "{name}");
    }
}

/// The report's massless footpad (`footpad.detached = "rigid"`) relaxes a leaving gear to zero
/// force and then keeps it rigid (docs/errata.md, "Contact and release"); the footpad with
/// inertia (the default) and the multibody's gear keep moving, the footpad held by its wall
/// while the vehicle moves on, within the play its crushed honeycomb leaves. On the 2-2 landing
/// at 8 ft/s leg 4's secondary strut keeps its stroke under the massless footpad while the
/// footpad is off the ground, and changes by more than 5 mm with the footpad's inertia and in
/// the rebuild before the footpad lands again.
#[test]
fn a_detached_gear_is_frozen_only_under_the_massless_footpad() {
    let (inertial, rapier) = histories("table-i-2-2-vv8.toml");
    let mut sc = Scenario::load(scenario("table-i-2-2-vv8.toml")).unwrap();
    sc.footpad.detached = Detached::Rigid;
    let mut rigid = History(Sample::new(sc.legs.len()), Vec::new());
    Simulation::new(&sc).unwrap().run(&mut rigid).unwrap();
    // Range of leg 4's 3-1 stroke over its longest stretch off the ground (the rebuild's
    // footpad also bounces for a few steps at its impact).
    let detached_range = |h: &History| {
        let mut longest: &[Sample] = &[];
        for stretch in h.1.chunk_by(|a, b| a.legs[3].contact == b.legs[3].contact) {
            if stretch[0].legs[3].contact == 2 && stretch.len() > longest.len() {
                longest = stretch;
            }
        }
        assert!(longest.len() > 10, "leg 4 never left the surface");
        let strokes = longest.iter().map(|s| s.legs[3].secondary_stroke[0]);
        let max = strokes.clone().fold(f64::MIN, f64::max);
        let min = strokes.fold(f64::MAX, f64::min);
        max - min
    };
    assert!(detached_range(&rigid) < 1e-9);
    assert!(
        detached_range(&inertial) > 5e-3,
        "{}",
        detached_range(&inertial)
    );
    assert!(detached_range(&rapier) > 5e-3);
}

/// The report's wall (fig. 17; `touchdown_multibody::wall`) holds a lifted footpad where it
/// stood until it rises above the wall: on the 2-2 landing at 8 ft/s with a 1 ft wall in place
/// of its spikes, leg 4's footpad, off the ground for tens of milliseconds below the wall,
/// moves less than 0.1 mm sideways in the rebuild, while the vehicle moves on by centimetres.
#[test]
fn a_wall_holds_a_lifted_footpad_in_the_rebuild() {
    let walled = Scenario::load_with(
        scenario("table-i-2-2-vv8.toml"),
        &[("surface.spike_depth", 0.0), ("surface.obstacle", 1.0)],
    )
    .unwrap();
    let (_, rapier) = histories_of(&walled);
    let mut longest: &[Sample] = &[];
    for stretch in rapier
        .1
        .chunk_by(|a, b| a.legs[3].contact == b.legs[3].contact)
    {
        if stretch[0].legs[3].contact == 2 && stretch.len() > longest.len() {
            longest = stretch;
        }
    }
    assert!(
        longest.len() > 500,
        "leg 4 never left the surface for 10 ms"
    );
    let (first, last) = (&longest[0], &longest[longest.len() - 1]);
    let lifted = longest
        .iter()
        .map(|s| s.legs[3].pad_position.z - first.legs[3].pad_position.z)
        .fold(f64::MIN, f64::max);
    assert!(lifted > 1e-3, "leg 4's footpad rose {lifted} m");
    let sideways = longest
        .iter()
        .map(|s| (s.legs[3].pad_position.xy() - first.legs[3].pad_position.xy()).norm())
        .fold(0.0, f64::max);
    let vehicle = (last.position - first.position).xy().norm();
    assert!(
        sideways < 1e-4 && vehicle > 1e-2,
        "leg 4's footpad moved {sideways} m sideways while the vehicle moved {vehicle} m"
    );
}

/// Spikes, not a wall (docs/errata.md, "Spikes, not a wall"), on the core and the rebuild
/// (`touchdown_tests::assert_spikes_let_go_of_flying_footpads`; MuJoCo's in
/// `mujoco.rs`).
#[test]
fn a_spike_lets_go_of_a_footpad_that_lifts_out() {
    let sc = Scenario::load(touchdown_tests::spiked_fig_25_26("spiked")).unwrap();
    let (core, rapier) = histories_of(&sc);
    for (engine, h) in [("core", &core.1), ("rapier", &rapier.1)] {
        touchdown_tests::assert_spikes_let_go_of_flying_footpads(engine, &sc, h);
    }
}
