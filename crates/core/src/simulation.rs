//! One landing: the vehicle, its gear and footpads, the laws and the ledger (`Physics`),
//! advanced by the scheme the scenario chose ([`crate::stepper`]); the accepted state's
//! evaluation, commit and bookkeeping common to every scheme (steps 6-8 of a step, see
//! [`crate::stepper`]), and the stability criteria (eqs. 105-107).
//!
//! The physics is in its own modules: the state in [`crate::state`], the loads in
//! [`crate::loads`], the contact logic in [`crate::contact`], the work and energies in
//! [`crate::ledger`], the diagnostics in [`crate::diagnostics`].

use crate::gear::GearState;
use crate::ledger::{Power, Quadrature};
use crate::mechanisms::Mechanisms;
use crate::rigid_body::MassProperties;
use crate::state::VehicleState;
use crate::stepper::{Advance, Schemes, Scratch};
use crate::stiction::Held;
use crate::summation::SumOrder;
use crate::surface::{ContactState, Footpad};
use nalgebra::{UnitQuaternion, Vector2, Vector3};
use touchdown_frames::gravity_inertial;
use touchdown_laws::{GearLaws, GearMemory};
use touchdown_record::{
    EnergyLedger, EnergyReport, Extremes, Landing, PadView, Progress, RunError, Sample,
    StabilityTracker, StrutCapacities, Summary,
};
use touchdown_scenario::initial::initial_state;
use touchdown_scenario::model::{Integrator, Leg, Mechanism, PadSurface};
use touchdown_scenario::schema::{
    Arrangement, AttitudeForm, Detached, Engine, ReleaseRule, Scheme,
};
use touchdown_scenario::Scenario;

/// A landing simulated by the report-faithful core: its physics and the stepper that advances
/// it.
#[derive(Debug, Clone)]
pub struct Simulation {
    physics: Physics,
    stepper: Schemes,
}

/// The physics of a landing: the scene's configuration and laws, the vehicle, its gear and
/// footpads at the accepted state, the work ledger and the criteria. Everything a step changes
/// but the stepper's scratch space.
#[derive(Debug, Clone)]
pub(crate) struct Physics {
    pub(crate) name: String,
    pub(crate) legs: Vec<Leg>,
    pub(crate) laws: GearLaws,
    pub(crate) mass: MassProperties,
    /// Gravity in inertial axes, m/s².
    pub(crate) gravity: Vector3<f64>,
    pub(crate) surfaces: Vec<PadSurface>,
    /// Footpad mass, kg.
    pub(crate) footpad_mass: f64,
    /// Whether the footpads have inertia off the surface (`footpad.detached = "inertial"`), or
    /// ride rigidly with the vehicle on a relaxed massless gear (`"rigid"`, the report's).
    pub(crate) inertial: bool,
    pub(crate) release: ReleaseRule,
    pub(crate) integrator: Integrator,
    /// The energy guard's least scale, J (`Scenario::energy_floor_j`).
    pub(crate) energy_floor_j: f64,
    pub(crate) arrangement: Arrangement,
    /// Footpad radius, m.
    pub(crate) footpad_radius: f64,
    pub(crate) mechanisms: Mechanisms,
    /// Footpads this close to their planes (m) touch: 1e-10 of the primary strut's length, far
    /// above the rounding of positions, so mirror-image footpads touch together.
    pub(crate) contact_tolerance: f64,
    /// Forces within this of zero (N) count as zero in the contact decisions: 1e-9 of the
    /// primary strut's last crush load.
    pub(crate) force_rounding: f64,
    // state
    /// Time, s.
    pub(crate) t: f64,
    pub(crate) steps: u64,
    pub(crate) evaluations: u64,
    pub(crate) vehicle: VehicleState,
    pub(crate) pads: Vec<Footpad>,
    pub(crate) memory: Vec<GearMemory>,
    /// Gear states at the accepted state.
    pub(crate) gear: Vec<GearState>,
    /// Point-1 bending displacement per leg at the last accepted state (lagged: docs/errata.md,
    /// "Eqs. (47)-(48): bending coupling"), m.
    pub(crate) bending_lag: Vec<Vector3<f64>>,
    /// Per leg, how far the strokes went back when its rigid footpad left in this step and its
    /// gear relaxed (primary, secondaries), m: not work of the vehicle, so the strut work of the
    /// step is booked to the strokes before it.
    pub(crate) relaxation: Vec<(f64, [f64; 2])>,
    /// Per rigid footpad, the accepted states in a row it has been in contact: the adaptive
    /// scheme locates the leaving of a footpad that has stayed (a footpad that lands and is
    /// pulled off at once, as a dragged footpad of a massless gear does step after step, is not
    /// located: locating it would hold the step at dt_min).
    pub(crate) contact_steps: Vec<u32>,
    /// Power of the vehicle-level mechanisms on the vehicle at the accepted state, W.
    pub(crate) applied_power: Power,
    pub(crate) ledger: EnergyLedger,
    /// Potential energy at the start, J.
    pub(crate) potential0: f64,
    /// Kinetic plus potential energy of the footpads with inertia at the start, J.
    pub(crate) footpad0: f64,
    pub(crate) stability: StabilityTracker,
    pub(crate) extremes: Extremes,
    /// Footpad views for the stability criteria (reused every step).
    pub(crate) pad_views: Vec<PadView>,
    /// Footpad positions and velocities at the start of the step (Runge–Kutta stages
    /// interpolate the sliding footpads between these and their end of step; the footpads off
    /// the surface start their stages from them), m, m/s.
    pub(crate) pad_start: Vec<(Vector3<f64>, Vector3<f64>)>,
    /// The footpads off the surface whose bearing friction an evaluation sets last (reused).
    pub(crate) held: Vec<Held>,
    /// The time over which that friction brings their stroking to rest, s
    /// ([`crate::stiction::relaxation`]).
    pub(crate) held_relaxation: f64,
    /// The order in which the legs' loads are summed ([`crate::summation`]).
    pub(crate) sum_order: SumOrder,
    /// Each leg's force on the vehicle (inertial axes, N) and torque about its centre of mass
    /// (body axes, N·m) at the last evaluation (reused).
    pub(crate) leg_loads: (Vec<Vector3<f64>>, Vec<Vector3<f64>>),
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
            theta: init.theta,
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
        let mut physics = Physics {
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
            mechanisms,
            contact_tolerance: 1e-10 * scenario.legs[0].l2p,
            force_rounding,
            t: 0.0,
            steps: 0,
            evaluations: 0,
            vehicle,
            pads,
            memory: vec![GearMemory::default(); n],
            gear: vec![GearState::default(); n],
            bending_lag: vec![Vector3::zeros(); n],
            relaxation: vec![(0.0, [0.0; 2]); n],
            contact_steps: vec![0; n],
            applied_power: Power::default(),
            ledger: EnergyLedger::default(),
            potential0: 0.0,
            footpad0: 0.0,
            stability: StabilityTracker::new(&scenario.stability, gravity, n, 0.0),
            extremes: Extremes::new(n, capacities),
            pad_views: vec![PadView::default(); n],
            pad_start: vec![(Vector3::zeros(), Vector3::zeros()); n],
            held: Vec::with_capacity(n),
            held_relaxation,
            sum_order: SumOrder::new(&scenario.legs),
            leg_loads: (vec![Vector3::zeros(); n], vec![Vector3::zeros(); n]),
        };
        physics.potential0 = physics.potential_energy();
        if physics.inertial {
            physics.footpad0 = physics.footpad_energy();
        }
        physics.stability =
            StabilityTracker::new(&scenario.stability, gravity, n, physics.kinetic_energy());
        let it = &scenario.integrator;
        let mut stepper = Schemes::new(it.scheme, n, &physics.vehicle, it.dt_max);
        // First contact at t = 0, then the accepted state's forces and accelerations.
        let before = physics.footpad_energy();
        physics.contact_logic()?;
        physics.ledger.events += physics.footpad_energy() - before;
        let mut v = physics.vehicle;
        physics.accept(&mut v, &mut stepper.get().scratch().spare)?;
        physics.vehicle = v;
        physics.update_pad_accelerations();
        let energy = physics.energy();
        physics.update_stability(None, &energy);
        physics.update_extremes();
        Ok(Simulation { physics, stepper })
    }

    /// Current time, s.
    pub fn time(&self) -> f64 {
        self.physics.t
    }

    /// Accepted steps so far.
    pub fn steps(&self) -> u64 {
        self.physics.steps
    }

    /// Rigid-vehicle state.
    pub fn vehicle(&self) -> &VehicleState {
        &self.physics.vehicle
    }

    /// Evaluations of each mechanism the scene declares (and only those), in the order of
    /// [`Mechanism::ALL`].
    pub fn mechanism_evaluations(&self) -> Vec<(Mechanism, u64)> {
        self.physics.mechanisms.evaluations()
    }

    /// The scene's optional mechanisms as built.
    pub fn mechanisms(&self) -> &Mechanisms {
        &self.physics.mechanisms
    }

    /// Footpads.
    pub fn footpads(&self) -> &[Footpad] {
        &self.physics.pads
    }

    /// Gear states at the accepted state.
    pub fn gear(&self) -> &[GearState] {
        &self.physics.gear
    }

    /// Current stability distance per wall (wall i joins footpads i and i+1), m; NaN if the
    /// wall is undefined.
    pub fn stability_distances(&self) -> &[f64] {
        self.physics.stability.distances()
    }

    /// Vehicle kinetic energy ½MV² + ½ωᵀJω, J.
    pub fn kinetic_energy(&self) -> f64 {
        self.physics.kinetic_energy()
    }

    /// Energy report at the current state.
    pub fn energy(&self) -> EnergyReport {
        self.physics.energy()
    }

    /// The integrator settings, for the summary.
    fn settings(&self) -> serde_json::Map<String, serde_json::Value> {
        let it = &self.physics.integrator;
        let mut m = serde_json::Map::new();
        let scheme = match it.scheme {
            Scheme::Report => "report predictor-corrector, eqs. (20)-(25)",
            Scheme::Rk4 => "classical fourth-order Runge-Kutta, fixed step dt_max",
            Scheme::Dopri5 => "Dormand-Prince 5(4), error control",
        };
        m.insert("scheme".into(), scheme.into());
        let attitude = match it.attitude {
            AttitudeForm::Euler => "Euler angles, eqs. (5)-(9)",
            AttitudeForm::Quaternion => "unit quaternion",
        };
        m.insert("attitude".into(), attitude.into());
        if it.scheme == Scheme::Report {
            m.insert("dist_m".into(), it.dist.into());
        }
        m.insert("dt_min_s".into(), it.dt_min.into());
        m.insert("dt_max_s".into(), it.dt_max.into());
        if it.scheme == Scheme::Dopri5 {
            m.insert("rtol".into(), it.rtol.into());
            m.insert("atol".into(), it.atol.into());
            self.stepper.get_ref().describe(&mut m);
        }
        m.insert("energy_tolerance".into(), it.energy_tolerance.into());
        m
    }
}

impl Physics {
    /// Evaluates the accepted state `v` into `spare`, which then becomes the accepted gear
    /// states (the ones they replace go to `spare`), and sets its accelerations.
    pub(crate) fn accept(
        &mut self,
        v: &mut VehicleState,
        spare: &mut Vec<GearState>,
    ) -> Result<(), RunError> {
        let loads = self.loads(self.t, v, spare);
        self.evaluations += 1;
        let loads = loads?;
        self.accelerate(v, &loads)?;
        self.applied_power = loads.applied_power;
        std::mem::swap(&mut self.gear, spare);
        Ok(())
    }

    /// Steps 6-8 for every scheme: the new state (in the stepper's `scratch`) after `step` (its
    /// length, quadrature and footpad work) from `old` is evaluated, the contact logic runs, the
    /// hysteresis is committed, the work of the step booked (`power_old` the mechanisms' power
    /// at `old`, W), the divergence checks and the stability criteria run.
    pub(crate) fn finish_step(
        &mut self,
        old: &VehicleState,
        step: &Advance,
        power_old: Power,
        scratch: &mut Scratch,
    ) -> Result<(), RunError> {
        let Advance {
            dt,
            quadrature,
            pads,
        } = step;
        let dt = *dt;
        let Scratch {
            new,
            previous,
            trial,
            spare,
        } = scratch;
        // The curbs' work on the footpads with inertia off the surface, their force frozen over
        // the step (the footpads' energy change is in the footpad energy).
        if self.inertial && self.mechanisms.curbs.is_some() {
            let mut curbs_off_surface = 0.0;
            for (p, (p0, _)) in self.pads.iter().zip(&self.pad_start) {
                if p.state != ContactState::Contact {
                    curbs_off_surface += p.curb_xy.dot(&(p.position - p0).xy());
                }
            }
            self.ledger.mechanisms -= curbs_off_surface;
        }
        // 6. evaluate (unless the last stage did), contact logic, re-evaluate on a change
        self.t += dt;
        match quadrature {
            Quadrature::Stages {
                evaluated: Some(power),
                ..
            } => {
                std::mem::swap(&mut self.gear, trial);
                self.applied_power = *power;
            }
            _ => self.accept(new, spare)?,
        }
        self.vehicle = *new;
        let pads_before = self.footpad_energy();
        if self.contact_logic()? {
            // The impacts' loss (and the footpads put on their planes) is a contact event.
            let events = self.footpad_energy() - pads_before;
            self.ledger.events += events;
            self.accept(new, spare)?;
            self.vehicle = *new;
        }
        self.update_pad_accelerations();
        // 7. commit hysteresis at the accepted state: every gear with inertial footpads (they
        // stroke on the surface or off it), the gears in contact with rigid ones
        if !self.inertial {
            for (n, p) in self.contact_steps.iter_mut().zip(&self.pads) {
                *n = if p.state == ContactState::Contact {
                    n.saturating_add(1)
                } else {
                    0
                };
            }
        }
        for i in 0..self.legs.len() {
            let pad = &self.pads[i];
            if !self.inertial && pad.state != ContactState::Contact {
                continue;
            }
            let g = &self.gear[i];
            self.laws
                .commit(g.primary_stroke, g.secondary_stroke, &mut self.memory[i]);
            self.bending_lag[i] = g.point1_deflection;
            // A curb is crushed by a footpad on the surface, and by one with inertia off it.
            let crushing = pad.state == ContactState::Contact
                || (self.inertial && pad.first_contact.is_some());
            if let (Some(curbs), true) = (&mut self.mechanisms.curbs, crushing) {
                let xy = Vector2::new(pad.position.x, pad.position.y);
                curbs.commit(i, pad.touchdown_xy, xy, self.footpad_radius);
            }
        }
        self.mechanisms.commit(new, &self.gravity);
        // Work of the vehicle-level mechanisms on the vehicle with the forces the step used
        // (the report: trapezoid of their power), and of the soil and curbs on the footpads.
        let applied_work = match quadrature {
            Quadrature::Trapezoid { trial_power } => 0.5 * (power_old.applied + trial_power) * dt,
            Quadrature::Stages { work, .. } => work.applied,
        };
        self.ledger.mechanisms += -applied_work - pads.soil - pads.curbs;
        // The energy the driving mechanisms put in (a trapezoid of their positive power at the
        // accepted states): the balance's scale, not the balance (docs/errata.md, "Energy guard").
        let driving = 0.5 * (power_old.driving.max(0.0) + self.applied_power.driving.max(0.0));
        self.ledger.driving_input += driving * dt;
        self.ledger.sliding += pads.gear + pads.curbs + pads.soil - pads.energy_change;
        self.book_strut_work(dt, quadrature, previous, trial);
        self.steps += 1;
        let energy = self.energy();
        self.check_divergence(&energy)?;
        self.update_stability(Some(old), &energy);
        self.update_extremes();
        self.extremes
            .update_acceleration(&old.velocity, &self.vehicle.velocity, dt, &self.gravity);
        self.extremes.follow(&self.stability);
        Ok(())
    }

    /// Stability distances, the unstable crossing and the four stable conditions
    /// (eqs. 105-107, `touchdown_record::stability`). `old` is the previous accepted vehicle
    /// state, `energy` the energy report of this state.
    pub(crate) fn update_stability(&mut self, old: Option<&VehicleState>, energy: &EnergyReport) {
        for i in 0..self.pads.len() {
            let p = &self.pads[i];
            self.pad_views[i] = PadView {
                position: self.pad_position(i),
                in_contact: p.state == ContactState::Contact,
                touched: p.first_contact.is_some(),
            };
        }
        let v = &self.vehicle;
        self.stability.update(
            self.t,
            &v.position,
            &v.velocity,
            old.map(|o| &o.velocity),
            energy,
            &self.pad_views,
        );
    }

    /// Inertial position of footpad `i`, m: a rigid footpad off the surface where its gear
    /// holds it.
    fn pad_position(&self, i: usize) -> Vector3<f64> {
        let p = &self.pads[i];
        if self.inertial || p.state == ContactState::Contact {
            p.position
        } else {
            self.vehicle.point(&p.bp_attached)
        }
    }

    /// The accelerations of the footpads with inertia off the surface at the accepted state
    /// (eqs. 16-18), their gears evaluated there.
    pub(crate) fn update_pad_accelerations(&mut self) {
        if !self.inertial {
            return;
        }
        for i in 0..self.pads.len() {
            if self.pads[i].state != ContactState::Contact {
                self.pads[i].acceleration = self.pad_acceleration(i, &self.vehicle, &self.gear[i]);
            }
        }
    }

    /// Running maxima of strokes, strut forces and the pitch rate (angular velocity about the
    /// inertial X axis).
    pub(crate) fn update_extremes(&mut self) {
        for (i, g) in self.gear.iter().enumerate() {
            self.extremes.update_leg(
                i,
                g.primary_stroke,
                g.secondary_stroke,
                g.f2p,
                g.f_secondary(),
            );
        }
        self.extremes
            .update_pitch_rate(self.t, self.vehicle.omega_inertial().x);
    }
}

impl Landing for Simulation {
    type Error = RunError;

    /// One integration step (see the module documentation).
    fn step(&mut self) -> Result<(), RunError> {
        self.stepper.get().step(&mut self.physics)
    }

    /// Whether the run has ended (end time, or an unstable decision with termination on).
    fn finished(&self) -> bool {
        self.physics.t >= self.physics.integrator.t_end * (1.0 - 1e-12)
            || self.physics.stability.terminates()
    }

    /// Writes the current state into `out` (a sample made for as many legs), allocating
    /// nothing.
    fn sample(&self, out: &mut Sample) {
        let p = &self.physics;
        let v = &p.vehicle;
        out.t = p.t;
        out.position = v.position;
        out.velocity = v.velocity;
        out.theta = v.theta;
        out.omega = v.omega;
        out.pitch_rate = v.omega_inertial().x;
        for (((slot, g), pad), memory) in (out.legs.iter_mut().zip(&p.gear))
            .zip(&p.pads)
            .zip(&p.memory)
        {
            slot.primary_stroke = g.primary_stroke;
            slot.primary_force = g.f2p;
            slot.secondary_stroke = g.secondary_stroke;
            slot.secondary_force = g.f_secondary();
            slot.stop_force = p
                .laws
                .stop_forces(g.primary_stroke, g.secondary_stroke, memory);
            slot.pad_position = pad.position;
            slot.contact = pad.state.code();
        }
        out.stability_distance
            .copy_from_slice(p.stability.distances());
        out.energy = p.energy();
    }

    /// The summary at the current state.
    fn summary(&self) -> Summary {
        let p = &self.physics;
        let progress = Progress {
            t: p.t,
            steps: p.steps,
            force_evaluations: p.evaluations,
            first_contact_s: p.pads.iter().map(|pad| pad.first_contact).collect(),
        };
        let mut summary = Summary::new(
            "core",
            &p.name,
            self.settings(),
            progress,
            &p.stability,
            &p.extremes,
            p.energy(),
        );
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
