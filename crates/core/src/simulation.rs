//! One landing on the core: its [`Model`] (what the scenario fixes), its [`State`] (what a step
//! changes) and the scheme that advances it ([`crate::stepper`]), set up from a scenario; and
//! the [`Landing`] interface every engine shares.
//!
//! The physics is in its own modules: the rigid vehicle in [`crate::vehicle`], the loads in
//! [`crate::loads`], the contact logic in [`crate::contact`] and [`crate::release`], the work
//! and energies in [`crate::ledger`], the diagnostics in [`crate::diagnostics`], the step in
//! [`crate::stepper`].

use crate::gear::GearState;
use crate::mechanisms::{MechanismState, Mechanisms, Power};
use crate::model::Model;
use crate::rigid_body::MassProperties;
use crate::settling::{LegTerms, Settling};
use crate::state::{Relaxation, State};
use crate::stepper::Schemes;
use crate::summation::SumOrder;
use crate::surface::Footpad;
use crate::vehicle::VehicleState;
use nalgebra::{UnitQuaternion, Vector2, Vector3};
use touchdown_frames::{gravity_inertial, EulerTrig};
use touchdown_laws::{GearLaws, GearMemory};
use touchdown_record::{
    EnergyLedger, EnergyReport, Extremes, Landing, PadView, Progress, RunError, Sample,
    StabilityTracker, StrutCapacities, Summary,
};
use touchdown_scenario::initial::initial_state;
use touchdown_scenario::model::Mechanism;
use touchdown_scenario::schema::{AttitudeForm, Detached, Engine, Scheme};
use touchdown_scenario::Scenario;

/// A landing simulated by the report-faithful core: its model, its state and the stepper that
/// advances it.
#[derive(Debug, Clone)]
pub struct Simulation {
    model: Model,
    state: State,
    stepper: Schemes,
}

impl Simulation {
    /// Sets up a landing from a resolved scenario: laws, initial state (eq. 19) and the
    /// contact of the first footpad.
    pub fn new(scenario: &Scenario) -> Result<Simulation, RunError> {
        scenario.require_engine(Engine::Core, crate::unsupported)?;
        // With sloshing the rigid vehicle excludes the slosh mass (eqs. 113-114); the slosh law
        // itself refers to the total vehicle.
        let slosh = touchdown_laws::scene::slosh_from_scenario(scenario)?;
        let rigid;
        let scenario = match &slosh {
            Some(slosh) => {
                rigid = touchdown_laws::scene::rigid_vehicle(scenario, slosh)?;
                &rigid
            }
            None => scenario,
        };
        let mechanisms = Mechanisms::new(scenario, slosh)?;
        let laws = GearLaws::from_scenario(scenario)?;
        let capacities = StrutCapacities::new(laws.capacities());
        let init = initial_state(scenario);
        let n = scenario.legs.len();
        let mut vehicle = VehicleState {
            position: init.position,
            velocity: init.velocity,
            acceleration: Vector3::zeros(),
            euler: EulerTrig::new(&init.theta),
            theta_dot: Vector3::zeros(),
            theta_ddot: Vector3::zeros(),
            omega: init.omega,
            omega_dot: Vector3::zeros(),
            t_bi: init.t_bi,
            quaternion: UnitQuaternion::from_matrix(&init.t_bi).into_inner(),
            slosh_q: scenario
                .slosh
                .map_or(Vector2::zeros(), |s| Vector2::from(s.initial_amplitude)),
            slosh_q_dot: Vector2::zeros(),
            slosh_q_ddot: Vector2::zeros(),
        };
        let theta_dot = touchdown_frames::t_be(&init.theta) * init.omega; // eq. (7)
        vehicle.set_attitude(init.theta, theta_dot);
        let pads = scenario
            .legs
            .iter()
            .map(|l| Footpad {
                position: vehicle.point(&l.bp),
                velocity: vehicle.point_velocity(&l.bp),
                bp_attached: l.bp,
                ..Default::default()
            })
            .collect();
        let mass = MassProperties::new(scenario.vehicle.mass, scenario.vehicle.inertia);
        let gravity = gravity_inertial(scenario.vehicle.gravity, scenario.surface.slope);
        let curve = &laws.primary.honeycomb.curve;
        let force_rounding = 1e-9 * curve.force(curve.capacity());
        let held_relaxation = crate::stiction::relaxation(&laws, scenario.footpad.mass);
        let stroke_mobility = crate::stepper::stroke_mobility(&scenario.legs, &laws, &mass);
        let mut model = Model {
            name: scenario.file.name.clone(),
            legs: scenario.legs.clone(),
            laws,
            mass,
            gravity,
            surfaces: scenario.surface.pads.clone(),
            footpad_mass: scenario.footpad.mass,
            inertial: scenario.footpad.detached == Detached::Inertial,
            release: scenario.surface.release,
            integrator: scenario.integrator.clone(),
            energy_floor_j: scenario.energy_floor_j(),
            arrangement: scenario.arrangement,
            footpad_radius: scenario.footpad.radius,
            contact_tolerance: 1e-10 * scenario.legs[0].l2p,
            force_rounding,
            held_relaxation,
            stroke_mobility,
            sum_order: SumOrder::new(&scenario.legs),
            mechanisms,
            settling: Settling::new(scenario)?,
            potential0: 0.0,
            footpad0: 0.0,
        };
        let mut state = State {
            t: 0.0,
            steps: 0,
            evaluations: 0,
            vehicle,
            pads,
            memory: vec![GearMemory::default(); n],
            gear: vec![GearState::default(); n],
            mechanisms: model.mechanisms.start(scenario.vehicle.gravity),
            bending_lag: vec![Vector3::zeros(); n],
            relaxation: vec![Relaxation::default(); n],
            contact_steps: vec![0; n],
            applied_power: Power::default(),
            ledger: EnergyLedger::default(),
            stability: StabilityTracker::new(&scenario.stability, gravity, n, 0.0),
            extremes: Extremes::new(n, capacities),
            pad_views: vec![PadView::default(); n],
            pad_start: vec![(Vector3::zeros(), Vector3::zeros()); n],
            sliding_start: vec![None; n],
            held: Vec::with_capacity(n),
            leg_loads: (vec![Vector3::zeros(); n], vec![Vector3::zeros(); n]),
            settled: None,
            next_settling_check: 0.0,
            settling_terms: vec![LegTerms::default(); n],
        };
        // The energies are measured from the start.
        model.potential0 = state.potential_energy(&model);
        if model.inertial {
            model.footpad0 = state.footpad_energy(&model);
        }
        let model = model;
        state.stability = StabilityTracker::new(
            &scenario.stability,
            gravity,
            n,
            state.kinetic_energy(&model),
        );
        let it = &scenario.integrator;
        let mut stepper = Schemes::new(it.scheme, n, &state.vehicle, it.dt_max);
        // First contact at t = 0, then the accepted state's forces and accelerations.
        let before = state.footpad_energy(&model);
        state.contact_logic(&model)?;
        state.ledger.events += state.footpad_energy(&model) - before;
        let mut v = state.vehicle;
        state.accept(&model, &mut v, &mut stepper.get().scratch().spare)?;
        state.vehicle = v;
        state.update_pad_accelerations(&model);
        let energy = state.energy(&model);
        state.update_stability(&model, None, &energy);
        state.update_extremes();
        Ok(Simulation {
            model,
            state,
            stepper,
        })
    }

    /// Current time, s.
    pub fn time(&self) -> f64 {
        self.state.t
    }

    /// Accepted steps so far.
    pub fn steps(&self) -> u64 {
        self.state.steps
    }

    /// Rigid-vehicle state.
    pub fn vehicle(&self) -> &VehicleState {
        &self.state.vehicle
    }

    /// Evaluations of each mechanism the scene declares (and only those), in the order of
    /// [`Mechanism::ALL`].
    pub fn mechanism_evaluations(&self) -> Vec<(Mechanism, u64)> {
        self.model.mechanisms.evaluations(&self.state.mechanisms)
    }

    /// The scene's optional mechanisms as built.
    pub fn mechanisms(&self) -> &Mechanisms {
        &self.model.mechanisms
    }

    /// What the scene's mechanisms have committed so far (the nozzle crush, the curbs' crush
    /// memories) and counted.
    pub fn mechanism_state(&self) -> &MechanismState {
        &self.state.mechanisms
    }

    /// Footpads.
    pub fn footpads(&self) -> &[Footpad] {
        &self.state.pads
    }

    /// Gear states at the accepted state.
    pub fn gear(&self) -> &[GearState] {
        &self.state.gear
    }

    /// Current stability distance per wall (wall i joins footpads i and i+1), m; NaN if the
    /// wall is undefined.
    pub fn stability_distances(&self) -> &[f64] {
        self.state.stability.distances()
    }

    /// Vehicle kinetic energy ½MV² + ½ωᵀJω, J.
    pub fn kinetic_energy(&self) -> f64 {
        self.state.kinetic_energy(&self.model)
    }

    /// Energy report at the current state.
    pub fn energy(&self) -> EnergyReport {
        self.state.energy(&self.model)
    }

    /// The integrator settings, for the summary.
    fn settings(&self) -> serde_json::Map<String, serde_json::Value> {
        let it = &self.model.integrator;
        let mut m = serde_json::Map::new();
        let scheme = match it.scheme {
            Scheme::Report => "report predictor-corrector, eqs. (20)-(25)",
            Scheme::Strides => "report predictor-corrector, eqs. (20)-(25), in long strides",
            Scheme::Rk4 => "classical fourth-order Runge-Kutta, fixed step dt_max",
            Scheme::Dopri5 => "Dormand-Prince 5(4), error control",
        };
        m.insert("scheme".into(), scheme.into());
        let attitude = match it.attitude {
            AttitudeForm::Euler => "Euler angles, eqs. (5)-(9)",
            AttitudeForm::Quaternion => "unit quaternion",
        };
        m.insert("attitude".into(), attitude.into());
        if matches!(it.scheme, Scheme::Report | Scheme::Strides) {
            m.insert("dist_m".into(), it.dist.into());
        }
        m.insert("dt_min_s".into(), it.dt_min.into());
        m.insert("dt_max_s".into(), it.dt_max.into());
        if it.scheme == Scheme::Strides {
            m.insert("stride".into(), it.stride.into());
            m.insert("mode_step".into(), it.mode_step.into());
        }
        if it.scheme == Scheme::Dopri5 {
            m.insert("rtol".into(), it.rtol.into());
            m.insert("atol".into(), it.atol.into());
            self.stepper.get_ref().describe(&mut m);
        }
        m.insert("energy_tolerance".into(), it.energy_tolerance.into());
        m
    }
}

impl Landing for Simulation {
    type Error = RunError;

    /// One integration step (see the module documentation).
    fn step(&mut self) -> Result<(), RunError> {
        self.stepper.get().step(&self.model, &mut self.state)?;
        if let Some(settling) = &self.model.settling {
            self.state.check_settled(&self.model, settling);
        }
        Ok(())
    }

    /// Whether the run has ended (end time, an unstable decision with termination on, or the
    /// landing proved settled).
    fn finished(&self) -> bool {
        self.state.t >= self.model.integrator.t_end * (1.0 - 1e-12)
            || self.state.stability.terminates()
            || self.state.settled.is_some()
    }

    /// Writes the current state into `out` (a sample made for as many legs), allocating
    /// nothing.
    fn sample(&self, out: &mut Sample) {
        let (m, p) = (&self.model, &self.state);
        let v = &p.vehicle;
        out.t = p.t;
        out.position = v.position;
        out.velocity = v.velocity;
        out.theta = v.euler.theta;
        out.omega = v.omega;
        out.pitch_rate = v.omega_inertial().x;
        for (i, (((slot, g), pad), memory)) in (out.legs.iter_mut().zip(&p.gear))
            .zip(&p.pads)
            .zip(&p.memory)
            .enumerate()
        {
            slot.primary_stroke = g.primary_stroke;
            slot.primary_force = g.f2p;
            slot.secondary_stroke = g.secondary_stroke;
            slot.secondary_force = g.f_secondary();
            slot.stop_force = m
                .laws
                .stop_forces(g.primary_stroke, g.secondary_stroke, memory);
            slot.pad_position = pad.position;
            slot.restraint_force = p.restraint_force(m, i);
            slot.contact = pad.state.code();
        }
        out.stability_distance
            .copy_from_slice(p.stability.distances());
        out.energy = p.energy(m);
    }

    /// The summary at the current state.
    fn summary(&self) -> Summary {
        let (m, p) = (&self.model, &self.state);
        let progress = Progress {
            t: p.t,
            steps: p.steps,
            force_evaluations: p.evaluations,
            first_contact_s: p.pads.iter().map(|pad| pad.first_contact).collect(),
        };
        let mut summary = Summary::new(
            "core",
            &m.name,
            self.settings(),
            progress,
            &p.stability,
            &p.extremes,
            p.energy(m),
        );
        summary.settled_time_s = p.settled;
        summary.mechanisms = self
            .mechanism_evaluations()
            .into_iter()
            .map(|(m, n)| (m.name().to_string(), n))
            .collect();
        summary
    }
}

#[cfg(test)]
mod tests {
    use super::Simulation;

    /// A simulation can be moved to and shared between threads (no interior mutability): this
    /// test fails to compile otherwise.
    #[test]
    fn a_simulation_is_send_and_sync() {
        fn send_sync<T: Send + Sync>() {}
        send_sync::<Simulation>();
    }
}
