//! One landing: state, the report's integration step (eqs. 20-25), contact logic, energy
//! bookkeeping, stability criteria and divergence diagnostics.
//!
//! Step ordering (not stated by the report; review A11):
//! 1. at t_k the state, the committed hysteresis and the accelerations a_k are known;
//! 2. footpads in sliding contact advance over Δt with their forces frozen at t_k (eq. 97);
//! 3. the vehicle is predicted with c = 0 (eqs. 22-23);
//! 4. forces and accelerations are evaluated at the prediction (trial, nothing committed);
//! 5. the vehicle is corrected with c from eq. (24);
//! 6. forces are evaluated at the corrected state, the contact logic runs, and if a footpad
//!    changed state the forces are evaluated again;
//! 7. the honeycomb memories are committed at that accepted state, whose accelerations are
//!    a_{k+1}; energy and stability are updated;
//! 8. the next Δt follows eq. (25).
//!
//! With a Runge–Kutta scheme (`integrator.scheme = "rk4"` or `"dopri5"`, [`crate::integrator`])
//! steps 3-5 are the method's stages instead: each evaluates the forces at its stage state (the
//! sliding footpads interpolated along their step, nothing committed); the strut and mechanism
//! work is the method's quadrature of the stage powers. An adaptive step whose error estimate
//! exceeds the tolerance is rejected: the footpads go back to the start and the step is retried
//! shorter. Steps 6-8 are the same for every scheme, so the hysteresis is committed only at
//! accepted states.
//!
//! Nothing in the step allocates.

use crate::gear::{self, GearOptions, GearState};
use crate::integrator::{self, Ode, Tableau, DOPRI5, MAX_STAGES, RK4};
use crate::kinematics::{euler_acceleration, t_be, t_eb, GIMBAL_LOCK_COS};
use crate::mechanisms::Mechanisms;
use crate::rigid_body::MassProperties;
use crate::surface::{advance_sliding, touch_down, ContactState, Footpad, SlidingForces};
use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector2, Vector3};
use touchdown_laws::{sliding_friction, GearLaws, GearMemory, StrutLoad};
use touchdown_record::{
    Divergence, EnergyLedger, EnergyReport, Extremes, Landing, Law, PadView, Progress, RunError,
    Sample, StabilityTracker, StateAtStop, Summary,
};
use touchdown_scenario::frames::{self, gravity_inertial};
use touchdown_scenario::model::{Integrator, Leg, Mechanism, PadSurface};
use touchdown_scenario::schema::{Arrangement, AttitudeForm, Engine, ReleaseRule, Scheme};
use touchdown_scenario::Scenario;

/// How far past its plane a footpad may be at the end of an adaptive step (an airborne one
/// below, a leaving one above) before the step is shortened to locate the event, m.
pub const CONTACT_EVENT_DEPTH: f64 = 1e-9;

/// Rigid-vehicle state (inertial frame; Euler angles relative to the surface frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VehicleState {
    /// Centre-of-mass position, m.
    pub position: Vector3<f64>,
    /// Centre-of-mass velocity, m/s.
    pub velocity: Vector3<f64>,
    /// Centre-of-mass acceleration, m/s² (including gravity).
    pub acceleration: Vector3<f64>,
    /// Euler angles θ, rad.
    pub theta: Vector3<f64>,
    /// Euler rates θ̇, rad/s.
    pub theta_dot: Vector3<f64>,
    /// Euler accelerations θ̈, rad/s².
    pub theta_ddot: Vector3<f64>,
    /// Body rates ω, rad/s.
    pub omega: Vector3<f64>,
    /// Body angular acceleration ω̇, rad/s² (eqs. 13-15).
    pub omega_dot: Vector3<f64>,
    /// T_BI (eq. 3) at θ (or from the quaternion).
    pub t_bi: Matrix3<f64>,
    /// Body → inertial unit quaternion (with `integrator.attitude = "quaternion"`; else the
    /// quaternion of the touchdown attitude, unused).
    pub quaternion: Quaternion<f64>,
    /// Slosh amplitude q (X_B, Y_B), m (eq. 109; zero without sloshing).
    pub slosh_q: Vector2<f64>,
    /// Slosh rate q̇, m/s.
    pub slosh_q_dot: Vector2<f64>,
    /// Slosh acceleration q̈, m/s².
    pub slosh_q_ddot: Vector2<f64>,
}

impl VehicleState {
    /// Sets θ (and T_BI, ω = T_EB·θ̇, eq. 6).
    fn set_attitude(&mut self, theta: Vector3<f64>, theta_dot: Vector3<f64>) {
        self.theta = theta;
        self.theta_dot = theta_dot;
        self.t_bi = frames::t_bi(&theta);
        self.omega = t_eb(&theta) * theta_dot; // eq. (6)
    }

    /// Sets θ and ω (rad, rad/s), with θ̇ = T_BE·ω (eq. 7) and T_BI.
    fn set_euler(&mut self, theta: Vector3<f64>, omega: Vector3<f64>) {
        self.theta = theta;
        self.omega = omega;
        self.t_bi = frames::t_bi(&theta);
        self.theta_dot = t_be(&theta) * omega; // eq. (7)
    }

    /// Sets the attitude from a quaternion `q` (normalised here) and ω (rad/s); θ is read from
    /// T_BI for the output, θ̇ by eq. (7) where it is defined.
    fn set_quaternion(&mut self, q: Quaternion<f64>, omega: Vector3<f64>) {
        let q = UnitQuaternion::from_quaternion(q);
        self.quaternion = q.into_inner();
        self.omega = omega;
        self.t_bi = q.to_rotation_matrix().into_inner();
        self.theta = frames::euler_from_t_bi(&self.t_bi);
        self.theta_dot = if self.theta.y.cos().abs() < GIMBAL_LOCK_COS {
            Vector3::zeros()
        } else {
            t_be(&self.theta) * omega
        };
    }

    /// The integrated part of the state.
    fn ode(&self) -> Ode {
        Ode {
            position: self.position,
            velocity: self.velocity,
            theta: self.theta,
            quaternion: self.quaternion,
            omega: self.omega,
            slosh_q: self.slosh_q,
            slosh_q_dot: self.slosh_q_dot,
        }
    }

    /// Its time derivative (the accelerations set), the attitude in the form `form` (the other
    /// form's rate is zero).
    fn rate(&self, form: AttitudeForm) -> Ode {
        let (theta, quaternion) = match form {
            AttitudeForm::Euler => (self.theta_dot, Quaternion::new(0.0, 0.0, 0.0, 0.0)),
            AttitudeForm::Quaternion => (
                Vector3::zeros(),
                integrator::quaternion_rate(&self.quaternion, &self.omega),
            ),
        };
        Ode {
            position: self.velocity,
            velocity: self.acceleration,
            theta,
            quaternion,
            omega: self.omega_dot,
            slosh_q: self.slosh_q_dot,
            slosh_q_dot: self.slosh_q_ddot,
        }
    }

    /// Sets the integrated part of the state from `y`, the attitude in the form `form`.
    fn set_ode(&mut self, y: &Ode, form: AttitudeForm) {
        self.position = y.position;
        self.velocity = y.velocity;
        self.slosh_q = y.slosh_q;
        self.slosh_q_dot = y.slosh_q_dot;
        match form {
            AttitudeForm::Euler => self.set_euler(y.theta, y.omega),
            AttitudeForm::Quaternion => self.set_quaternion(y.quaternion, y.omega),
        }
    }

    /// Inertial position of a body-fixed point `b` (body axes), m.
    pub fn point(&self, b: &Vector3<f64>) -> Vector3<f64> {
        self.position + self.t_bi * b
    }

    /// Inertial velocity of a body-fixed point `b`, m/s.
    pub fn point_velocity(&self, b: &Vector3<f64>) -> Vector3<f64> {
        self.velocity + self.t_bi * self.omega.cross(b)
    }

    /// Angular velocity in inertial axes, rad/s.
    pub fn omega_inertial(&self) -> Vector3<f64> {
        self.t_bi * self.omega
    }
}

/// A landing simulated by the report-faithful core.
#[derive(Debug, Clone)]
pub struct Simulation {
    name: String,
    legs: Vec<Leg>,
    laws: GearLaws,
    mass: MassProperties,
    gravity: Vector3<f64>,
    surfaces: Vec<PadSurface>,
    footpad_mass: f64,
    release: ReleaseRule,
    integrator: Integrator,
    arrangement: Arrangement,
    footpad_radius: f64,
    mechanisms: Mechanisms,
    /// Footpads this close to their planes (m) touch: 1e-10 of the primary strut's length, far
    /// above the rounding of positions, so mirror-image footpads touch together.
    contact_tolerance: f64,
    /// Forces within this of zero (N) count as zero in the contact decisions: 1e-9 of the
    /// primary strut's last crush load.
    force_rounding: f64,
    // state
    t: f64,
    steps: u64,
    evaluations: u64,
    vehicle: VehicleState,
    pads: Vec<Footpad>,
    memory: Vec<GearMemory>,
    gear: Vec<GearState>,
    trial: Vec<GearState>,
    previous: Vec<GearState>,
    scratch: Vec<GearState>,
    /// Point-1 bending displacement per leg at the last accepted state (lagged, review A8), m.
    bending_lag: Vec<Vector3<f64>>,
    /// Per leg, how far the strokes went back when its footpad left in this step and its gear
    /// relaxed (primary, secondaries), m: not work of the vehicle, so the strut work of the
    /// step is booked to the strokes before it.
    relaxation: Vec<(f64, [f64; 2])>,
    /// Per footpad, the accepted states in a row it has been in contact: the adaptive scheme
    /// locates the leaving of a footpad that has stayed (a footpad that lands and is pulled off
    /// at once, as a dragged footpad of a massless gear does step after step, is not located:
    /// locating it would hold the step at dt_min).
    contact_steps: Vec<u32>,
    /// Power of the vehicle-level mechanisms on the vehicle at the accepted state, W.
    applied_power: Power,
    ledger: EnergyLedger,
    potential0: f64,
    stability: StabilityTracker,
    extremes: Extremes,
    /// Footpad views for the stability criteria (reused every step).
    pad_views: Vec<PadView>,
    /// Footpad positions and velocities at the start of the step (Runge–Kutta stages
    /// interpolate the sliding footpads between these and their end of step), m, m/s.
    pad_start: Vec<(Vector3<f64>, Vector3<f64>)>,
    /// The footpads at the start of the step, restored when an adaptive step is rejected.
    pads_saved: Vec<Footpad>,
    /// The adaptive scheme's next step, s.
    next_dt: f64,
    /// Steps the adaptive scheme rejected, and steps it took at `dt_min` without meeting its
    /// tolerance.
    rejected: u64,
    forced: u64,
}

/// Work of the struts and the vehicle-level mechanisms over one Runge–Kutta step: the method's
/// quadrature Δt·Σ b_i·P_i of each power, J.
#[derive(Debug, Clone, Copy, Default)]
struct StageWork {
    honeycomb: f64,
    viscous: f64,
    bearing: f64,
    applied: f64,
}

impl StageWork {
    /// Adds weight `w` (s) of the powers of the gear states `gear` and the applied power
    /// `applied` (W).
    fn add(&mut self, w: f64, gear: &[GearState], applied: f64) {
        for g in gear {
            self.honeycomb += w
                * (g.fcp * g.primary_rate
                    + g.fc_secondary[0] * g.secondary_rate[0]
                    + g.fc_secondary[1] * g.secondary_rate[1]);
            self.viscous += w
                * (g.fvp * g.primary_rate
                    + g.fv_secondary[0] * g.secondary_rate[0]
                    + g.fv_secondary[1] * g.secondary_rate[1]);
            self.bearing += w * g.fbr * g.primary_rate;
        }
        self.applied += w * applied;
    }
}

/// How the strut work of a step is booked.
enum Quadrature {
    /// The report's scheme: trapezoids of the accepted and trial forces (eq. 24), with the
    /// mechanisms' power at the trial, W.
    Trapezoid { trial_power: f64 },
    /// A Runge–Kutta method's own quadrature; `evaluated` is the mechanisms' power at the new
    /// state when the method's last stage already evaluated it (its forces in the trial gear
    /// states).
    Stages {
        work: StageWork,
        evaluated: Option<Power>,
    },
}

/// Work of the sliding footpads' step (eq. 97), J.
#[derive(Debug, Clone, Copy, Default)]
struct PadWork {
    gear: f64,
    energy_change: f64,
    soil: f64,
    curbs: f64,
}

/// Net loads on the vehicle (eqs. 66-68, 83-84): force in inertial axes excluding gravity,
/// torque in body axes, and the power of the vehicle-level mechanisms (thrust, nozzle, RCS,
/// slosh) on the vehicle.
struct Loads {
    force: Vector3<f64>,
    torque: Vector3<f64>,
    applied_power: Power,
}

/// Power of the vehicle-level mechanisms on the vehicle, W: all of them (`applied`), and the
/// driving ones' part (`driving`: thrust and RCS, whose positive work is energy put in).
#[derive(Debug, Clone, Copy, Default)]
struct Power {
    applied: f64,
    driving: f64,
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
        let init = frames::initial_state(scenario);
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
        let theta_dot = crate::kinematics::t_be(&init.theta) * init.omega; // eq. (7)
        vehicle.set_attitude(init.theta, theta_dot);
        let pads = scenario
            .legs
            .iter()
            .map(|l| Footpad {
                position: vehicle.point(&l.bp),
                velocity: vehicle.point_velocity(&l.bp),
                bp_attached: l.bp,
                bp: l.bp,
                ..Default::default()
            })
            .collect();
        let mass = MassProperties::new(scenario.vehicle.mass, scenario.vehicle.inertia);
        let gravity = gravity_inertial(scenario.vehicle.gravity, scenario.surface.slope);
        let curve = &laws.primary.honeycomb.curve;
        let force_rounding = 1e-9 * curve.force(curve.capacity());
        let mut sim = Simulation {
            name: scenario.file.name.clone(),
            legs: scenario.legs.clone(),
            laws,
            mass,
            gravity,
            surfaces: scenario.surface.pads.clone(),
            footpad_mass: scenario.footpad.mass,
            release: scenario.surface.release,
            integrator: scenario.integrator.clone(),
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
            trial: vec![GearState::default(); n],
            previous: vec![GearState::default(); n],
            scratch: vec![GearState::default(); n],
            bending_lag: vec![Vector3::zeros(); n],
            relaxation: vec![(0.0, [0.0; 2]); n],
            contact_steps: vec![0; n],
            applied_power: Power::default(),
            ledger: EnergyLedger::default(),
            potential0: 0.0,
            stability: StabilityTracker::new(&scenario.stability, gravity, n, 0.0),
            extremes: Extremes::new(n),
            pad_views: vec![PadView::default(); n],
            pad_start: vec![(Vector3::zeros(), Vector3::zeros()); n],
            pads_saved: vec![Footpad::default(); n],
            next_dt: scenario.integrator.dt_max,
            rejected: 0,
            forced: 0,
        };
        sim.potential0 = sim.potential_energy();
        sim.stability =
            StabilityTracker::new(&scenario.stability, gravity, n, sim.kinetic_energy());
        // First contact at t = 0, then the accepted state's forces and accelerations.
        let before = sim.footpad_energy();
        sim.contact_logic()?;
        sim.ledger.events += sim.footpad_energy() - before;
        let mut v = sim.vehicle;
        sim.accept(&mut v)?;
        sim.vehicle = v;
        let energy = sim.energy();
        sim.update_stability(None, &energy);
        sim.update_extremes();
        Ok(sim)
    }

    /// Current time, s.
    pub fn time(&self) -> f64 {
        self.t
    }

    /// Accepted steps so far.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Rigid-vehicle state.
    pub fn vehicle(&self) -> &VehicleState {
        &self.vehicle
    }

    /// Evaluations of each mechanism the scene declares (and only those), in the order of
    /// [`Mechanism::ALL`].
    pub fn mechanism_evaluations(&self) -> Vec<(Mechanism, u64)> {
        self.mechanisms.evaluations()
    }

    /// The scene's optional mechanisms as built.
    pub fn mechanisms(&self) -> &Mechanisms {
        &self.mechanisms
    }

    /// Footpads.
    pub fn footpads(&self) -> &[Footpad] {
        &self.pads
    }

    /// Gear states at the accepted state.
    pub fn gear(&self) -> &[GearState] {
        &self.gear
    }

    /// Current stability distance per wall (wall i joins footpads i and i+1), m; NaN if the
    /// wall is undefined.
    pub fn stability_distances(&self) -> &[f64] {
        self.stability.distances()
    }

    /// Vehicle kinetic energy ½MV² + ½ωᵀJω, J.
    pub fn kinetic_energy(&self) -> f64 {
        self.mass
            .kinetic_energy(&self.vehicle.velocity, &self.vehicle.omega)
    }

    /// Vehicle potential energy −M·G·R, J.
    fn potential_energy(&self) -> f64 {
        -self.mass.mass * self.gravity.dot(&self.vehicle.position)
    }

    /// Kinetic + potential energy of the footpads in contact (the only ones with dynamics), J.
    fn footpad_energy(&self) -> f64 {
        let m = self.footpad_mass;
        self.pads
            .iter()
            .filter(|p| p.state == ContactState::Contact)
            .map(|p| 0.5 * m * p.velocity.norm_squared() - m * self.gravity.dot(&p.position))
            .sum()
    }

    /// Elastic energy stored in the gear's honeycombs now, J.
    fn stored_energy(&self) -> f64 {
        (0..self.legs.len())
            .map(|i| {
                let g = &self.gear[i];
                self.laws
                    .stored_energy(g.primary_stroke, g.secondary_stroke, &self.memory[i])
            })
            .sum()
    }

    /// Energy report at the current state.
    pub fn energy(&self) -> EnergyReport {
        self.ledger.report(
            self.stability.initial_kinetic_energy(),
            self.kinetic_energy(),
            self.potential_energy() - self.potential0,
            self.footpad_energy(),
            self.stored_energy(),
        )
    }

    /// The integrator settings, for the summary.
    fn settings(&self) -> serde_json::Map<String, serde_json::Value> {
        let it = &self.integrator;
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
            m.insert("rejected_steps".into(), self.rejected.into());
            m.insert("steps_forced_at_dt_min".into(), self.forced.into());
        }
        m.insert("energy_tolerance".into(), it.energy_tolerance.into());
        m
    }

    /// Step size by eq. (25), Δt = DIST/VEL clamped to [Δt_min, Δt_max].
    fn report_step_size(&self) -> f64 {
        let it = &self.integrator;
        let v = &self.vehicle;
        let mut vel: f64 = 0.0;
        for p in &self.pads {
            let rel = if p.state == ContactState::Contact {
                p.velocity - v.velocity
            } else {
                v.t_bi * v.omega.cross(&p.bp_attached)
            };
            vel = vel.max(rel.norm());
        }
        let dt = if vel > 0.0 { it.dist / vel } else { it.dt_max }; // eq. (25)
        dt.clamp(it.dt_min, it.dt_max)
    }

    /// `dt` (s) shortened so that an airborne footpad lands on its plane (review A12) and so
    /// that the end time is met.
    fn limit_step(&self, mut dt: f64) -> f64 {
        let it = &self.integrator;
        let v = &self.vehicle;
        if it.contact_step_limit {
            for (p, s) in self.pads.iter().zip(&self.surfaces) {
                if p.state != ContactState::Contact {
                    let gap = v.point(&p.bp_attached).z - s.plane();
                    let approach = -v.point_velocity(&p.bp_attached).z;
                    if gap > 0.0 && approach > 0.0 && gap < approach * dt {
                        dt = (gap / approach).max(it.dt_min);
                    }
                }
            }
        }
        dt.min(it.t_end - self.t).max(f64::MIN_POSITIVE)
    }

    /// Gear forces and net loads on the vehicle at `v` with the footpads as they are now,
    /// written into `out` (eqs. 26-68, 83-84). Footpads not in contact carry no load.
    fn loads(&self, t: f64, v: &VehicleState, out: &mut [GearState]) -> Result<Loads, RunError> {
        self.loads_at(t, v, 1.0, out)
    }

    /// [`Simulation::loads`] with each sliding footpad a fraction `blend` of the way from its
    /// start of step to where it is now (a Runge–Kutta stage; 1 is now).
    fn loads_at(
        &self,
        t: f64,
        v: &VehicleState,
        blend: f64,
        out: &mut [GearState],
    ) -> Result<Loads, RunError> {
        let mut force = Vector3::zeros();
        let mut torque = Vector3::zeros();
        for (i, slot) in out.iter_mut().enumerate() {
            let pad = &self.pads[i];
            if pad.state != ContactState::Contact {
                let prev = &self.gear[i];
                *slot = GearState {
                    primary_stroke: prev.primary_stroke,
                    secondary_stroke: prev.secondary_stroke,
                    ..GearState::default()
                };
                continue;
            }
            let (position, velocity) = if blend >= 1.0 {
                (pad.position, pad.velocity)
            } else {
                let (p0, v0) = self.pad_start[i];
                (p0.lerp(&pad.position, blend), v0.lerp(&pad.velocity, blend))
            };
            let bp = self.evaluate_leg(i, v, &position, &velocity, slot)?;
            torque += bp.cross(&(-slot.fp)); // eq. (66)
            force -= v.t_bi * slot.fp; // eqs. (67)-(68)
        }
        // eqs. (72)-(74), (80)-(82), (115)-(117): the scene's vehicle-level mechanisms, if any.
        let mut applied_power = Power::default();
        if let Some(a) = self.mechanisms.vehicle_loads(t, || self.first_contact(), v) {
            let applied_force = v.t_bi * a.force;
            force += applied_force; // eq. (83)
            torque += a.torque; // eq. (84)
            applied_power = Power {
                applied: applied_force.dot(&v.velocity) + a.torque.dot(&v.omega),
                driving: a.driving_power(&(v.t_bi.transpose() * v.velocity), &v.omega),
            };
        }
        Ok(Loads {
            force,
            torque,
            applied_power,
        })
    }

    /// Evaluates gear `i` (eqs. 26-65) into `slot` with the vehicle at `v` and its footpad at
    /// `position` moving at `velocity` (inertial, m and m/s); returns the footpad's body-frame
    /// position BP, m.
    fn evaluate_leg(
        &self,
        i: usize,
        v: &VehicleState,
        position: &Vector3<f64>,
        velocity: &Vector3<f64>,
        slot: &mut GearState,
    ) -> Result<Vector3<f64>, RunError> {
        let t_ib = v.t_bi.transpose();
        let bp = t_ib * (position - v.position);
        let bp_dot = t_ib * (velocity - v.velocity) - v.omega.cross(&bp);
        if self.arrangement == Arrangement::Tripod {
            self.mechanisms.tick(Mechanism::Tripod);
        }
        let options = GearOptions {
            arrangement: self.arrangement,
            bending: self.mechanisms.bending.as_ref().map(|b| {
                self.mechanisms.tick(Mechanism::Bending);
                (b, self.bending_lag[i])
            }),
        };
        gear::evaluate(
            &self.legs[i],
            &self.laws,
            &self.memory[i],
            &bp,
            &bp_dot,
            &options,
            slot,
        )
        .map_err(|f| self.diverged(v, f.error.to_string(), f.law, Some(i)))?;
        Ok(bp)
    }

    /// Time of the first footpad contact, s.
    fn first_contact(&self) -> Option<f64> {
        self.pads
            .iter()
            .filter_map(|p| p.first_contact)
            .reduce(f64::min)
    }

    /// Accelerations of `v` under `loads`: eqs. (10)-(12), (13)-(15) and (9a)-(9c).
    fn accelerate(&self, v: &mut VehicleState, loads: &Loads) -> Result<(), RunError> {
        let euler = self.integrator.attitude == AttitudeForm::Euler;
        // θy stays within ±90° unless it crossed the singularity (cos θy < 0 beyond).
        if euler && v.theta.y.cos() < GIMBAL_LOCK_COS {
            return Err(self.diverged(
                v,
                "Euler-angle singularity: θy reached or crossed ±90° (eqs. 5 and 9a divide by cos θy); integrator.attitude = \"quaternion\" (schemes rk4, dopri5) goes through it".into(),
                Law::Kinematics,
                None,
            ));
        }
        v.acceleration = self.mass.linear_acceleration(&loads.force, &self.gravity);
        v.omega_dot = self.mass.angular_acceleration(&loads.torque, &v.omega);
        if euler {
            v.theta_ddot = euler_acceleration(&v.theta, &v.theta_dot, &v.omega, &v.omega_dot);
        }
        v.slosh_q_ddot = self.mechanisms.slosh_acceleration(v); // eq. (109), corrected
        Ok(())
    }

    /// Evaluates the accepted state `v` into `self.gear` and sets its accelerations.
    fn accept(&mut self, v: &mut VehicleState) -> Result<(), RunError> {
        let mut out = std::mem::take(&mut self.scratch);
        let loads = self.loads(self.t, v, &mut out);
        self.evaluations += 1;
        let loads = match loads {
            Ok(l) => l,
            Err(e) => {
                self.scratch = out;
                return Err(e);
            }
        };
        self.accelerate(v, &loads)?;
        self.applied_power = loads.applied_power;
        self.scratch = std::mem::replace(&mut self.gear, out);
        Ok(())
    }

    /// Contact logic of the surface (text before eq. 85; docs/errata.md, "Contact and release")
    /// at the current vehicle state, the gear evaluated there: an airborne footpad whose
    /// tentative rigid position reaches its plane (within [`Simulation::contact_tolerance`])
    /// touches down unless its gear would pull it there; a footpad in contact leaves as soon as
    /// its gear no longer presses it onto the surface, and its gear relaxes. Returns whether any
    /// footpad changed state.
    fn contact_logic(&mut self) -> Result<bool, RunError> {
        let v = self.vehicle;
        let soil = self.mechanisms.soil.is_some();
        let mut changed = false;
        for i in 0..self.pads.len() {
            let s = self.surfaces[i];
            match self.pads[i].state {
                ContactState::Free | ContactState::Detached => {
                    let attached = self.pads[i].bp_attached;
                    let tentative = v.point(&attached);
                    let vel = v.point_velocity(&attached);
                    self.pads[i].position = tentative;
                    self.pads[i].velocity = vel;
                    if tentative.z > s.plane() + self.contact_tolerance {
                        continue;
                    }
                    let airborne = self.pads[i];
                    let v_normal = if soil { vel.z } else { 0.0 };
                    let mut xy = Vector2::new(tentative.x, tentative.y);
                    if let (Some(curbs), true) =
                        (&self.mechanisms.curbs, airborne.first_contact.is_some())
                    {
                        xy = curbs.landing(i, airborne.touchdown_xy, xy, self.footpad_radius);
                    }
                    touch_down(
                        &mut self.pads[i],
                        &s,
                        xy,
                        Vector2::new(vel.x, vel.y),
                        v_normal,
                        self.t,
                    );
                    // A (re)contact whose first evaluation would pull the footpad, load its
                    // primary's extension stop (a footpad put on its plane from just above it) or
                    // stretch its strut past its bearings is no contact.
                    let pad = self.pads[i];
                    let mut g = GearState::default();
                    let fits = self
                        .evaluate_leg(i, &v, &pad.position, &pad.velocity, &mut g)
                        .is_ok();
                    let tol = self.force_rounding;
                    if !fits || self.pressing(&v, &g) < -tol || g.fcp < -tol {
                        self.pads[i] = airborne;
                    } else {
                        changed = true;
                    }
                }
                ContactState::Contact => {
                    if self.leaves(i, &v, &self.gear[i]) {
                        self.release(i, &v)?;
                        changed = true;
                    }
                }
            }
        }
        Ok(changed)
    }

    /// The force that keeps a footpad on its surface under the release rule, with the vehicle
    /// at `v` and its gear in state `g`, N (positive pressing): the surface's normal reaction on
    /// the footpad at rest on it, FZI (the normal component of the gear's force on it, eqs. 67,
    /// 85) plus its weight PMASS·g_n (a footpad is lifted only by a pull larger than its own
    /// weight), or the report's stand-ins F2P or FCP.
    fn pressing(&self, v: &VehicleState, g: &GearState) -> f64 {
        match self.release {
            ReleaseRule::GearForce => -(v.t_bi * g.fp).z - self.footpad_mass * self.gravity.z,
            ReleaseRule::StrutForce => g.f2p,
            ReleaseRule::HoneycombForce => g.fcp,
        }
    }

    /// Whether footpad `i`, in contact, leaves its surface with the vehicle in state `v` and its
    /// gear in state `g`: its gear pulls it (beyond rounding), or its primary strut's extension
    /// stop is loaded (the vehicle is lifting it: no stop is loaded through a contact); a slack
    /// gear (no force either way, within rounding) lets it go when the point of the vehicle it
    /// hangs from moves away from the surface, and leaves it resting there otherwise (a massless
    /// footpad between a slack gear and its surface is held by neither; its lightest-mass limit
    /// rests). On soil, a footpad leaves once it is no longer pressed and has risen out of the
    /// soil (docs/errata.md, "Eq. (101)").
    fn leaves(&self, i: usize, v: &VehicleState, g: &GearState) -> bool {
        let pressing = self.pressing(v, g);
        let tol = self.force_rounding;
        if self.mechanisms.soil.is_some() {
            return pressing <= tol && self.pads[i].position.z > self.surfaces[i].plane();
        }
        if pressing < -tol || g.fcp < -tol {
            return true;
        }
        if pressing > tol {
            return false;
        }
        let bp = v.t_bi.transpose() * (self.pads[i].position - v.position);
        v.point_velocity(&bp).z > 0.0
    }

    /// Footpad `i`, no longer pressed, leaves its surface at the accepted state `v`: its leaving
    /// strokes are committed, its massless gear relaxes to strokes at which no strut carries a
    /// force (the stored energy it releases counts as dissipated by the honeycombs, whose work
    /// the ledger already holds) and the footpad is attached rigidly where the relaxed struts
    /// put it. A relaxed gear that cannot be assembled is an error.
    fn release(&mut self, i: usize, v: &VehicleState) -> Result<(), RunError> {
        let g = self.gear[i];
        let (c, s) = (g.primary_stroke, g.secondary_stroke);
        self.laws.commit(c, s, &mut self.memory[i]);
        let bp = v.t_bi.transpose() * (self.pads[i].position - v.position);
        let relaxed = gear::relax(
            &self.legs[i],
            &self.laws,
            &self.memory[i],
            self.arrangement,
            &bp,
            c,
            s,
        )
        .ok_or_else(|| {
            self.diverged(
                v,
                "the struts of a leaving gear, relaxed to zero force, no longer meet".into(),
                Law::GearRelaxation,
                Some(i),
            )
        })?;
        let relaxed = self.above_plane(i, v, relaxed, c);
        self.relaxation[i] = (
            c - relaxed.primary_stroke,
            [0, 1].map(|j| s[j] - relaxed.secondary_stroke[j]),
        );
        self.gear[i].primary_stroke = relaxed.primary_stroke;
        self.gear[i].secondary_stroke = relaxed.secondary_stroke;
        self.bending_lag[i] = Vector3::zeros();
        let pad = &mut self.pads[i];
        pad.state = ContactState::Detached;
        pad.stuck = false;
        pad.bp_attached = relaxed.bp;
        pad.position = v.point(&relaxed.bp);
        pad.velocity = v.point_velocity(&relaxed.bp);
        Ok(())
    }

    /// A leaving cantilever gear relaxed from primary stroke `c` (m) whose footpad would end
    /// below its plane (relaxing a primary strut extends it toward the surface) keeps its
    /// primary as compressed as puts the footpad on the plane: a footpad cannot leave through
    /// its surface. That primary stroke's small load stays in the detached gear, stored and
    /// counted, until the footpad lands again.
    fn above_plane(
        &self,
        i: usize,
        v: &VehicleState,
        relaxed: gear::Relaxed,
        c: f64,
    ) -> gear::Relaxed {
        let plane = self.surfaces[i].plane();
        let leg = &self.legs[i];
        let axis = (relaxed.bp - leg.b2).normalize();
        let down = (v.t_bi * axis).z;
        if self.arrangement != Arrangement::Cantilever
            || v.point(&relaxed.bp).z >= plane
            || down >= 0.0
        {
            return relaxed;
        }
        // (R + T_BI·(B2 + V̂2P·(L2P − c')))_z = plane
        let length = (plane - v.point(&leg.b2).z) / down;
        let held = (leg.l2p - length).clamp(relaxed.primary_stroke, c.max(relaxed.primary_stroke));
        gear::Relaxed {
            bp: leg.b2 + axis * (leg.l2p - held),
            primary_stroke: held,
            ..relaxed
        }
    }

    /// Frozen in-plane forces on footpad `i` at the accepted state `v` (eqs. 85, 96-99
    /// corrected: the footpad receives −FPI = T_BI·FP).
    fn sliding_forces(&self, i: usize, v: &VehicleState) -> SlidingForces {
        let on_pad = v.t_bi * self.gear[i].fp; // −FPI, eq. (67) reversed
        let fzi = -on_pad.z; // FZI = (FPI)_z, positive pressing into the surface
        let pad = &self.pads[i];
        let xy = Vector2::new(pad.position.x, pad.position.y);
        let v_xy = Vector2::new(pad.velocity.x, pad.velocity.y);
        let mut drag = sliding_friction(self.surfaces[i].friction, fzi); // eq. (85)
        if let Some(soil) = &self.mechanisms.soil {
            // eqs. (102), (104): FGRND = FDRAG + FDRAGP, both along −v̂
            self.mechanisms.tick(Mechanism::Soil);
            let depth = self.surfaces[i].plane() - pad.position.z;
            let sp = (xy - pad.touchdown_xy).norm();
            drag += soil.lateral_drag(depth, sp, v_xy.norm());
        }
        let curb_xy = match &self.mechanisms.curbs {
            Some(curbs) => {
                self.mechanisms.tick(Mechanism::Curbs);
                curbs.force(i, pad.touchdown_xy, xy, v_xy, self.footpad_radius)
            }
            None => Vector2::zeros(),
        };
        SlidingForces {
            gear_xy: Vector2::new(on_pad.x, on_pad.y),
            curb_xy,
            drag,
            gravity_xy: Vector2::new(self.gravity.x, self.gravity.y),
            fzi,
            mass: self.footpad_mass,
            rounding: self.force_rounding,
        }
    }

    /// Adds the strut work of the step. The report's scheme books it with the forces the
    /// corrector used (eq. 24: the accepted state k and the trial at the prediction), so that
    /// the ledger and the vehicle's energy see the same forces even when a footpad leaves the
    /// surface in the step: honeycomb ½(F_k + F*)·(x_{k+1} − x_k), viscous and bearing
    /// friction ½(P_k + P*)·Δt. A Runge–Kutta scheme books its own quadrature of the stage
    /// powers.
    fn book_strut_work(&mut self, dt: f64, quadrature: &Quadrature) {
        let steps = self.previous.iter().zip(&self.trial).zip(&self.gear);
        for (((a, t), b), relaxed) in steps.zip(&mut self.relaxation) {
            let l = &mut self.ledger;
            // The strokes at the end of the step, before a leaving gear relaxed.
            let (dc, ds) = std::mem::take(relaxed);
            let c_end = b.primary_stroke + dc;
            // The force at the end of the step: the trial's (report) or the accepted state's.
            let end = match quadrature {
                Quadrature::Trapezoid { .. } => {
                    l.honeycomb += 0.5 * (a.fcp + t.fcp) * (c_end - a.primary_stroke);
                    l.viscous += 0.5 * (a.fvp * a.primary_rate + t.fvp * t.primary_rate) * dt;
                    l.bearing += 0.5 * (a.fbr * a.primary_rate + t.fbr * t.primary_rate) * dt;
                    t
                }
                Quadrature::Stages { .. } => b,
            };
            for (j, ds) in ds.into_iter().enumerate() {
                let (fa, ft) = (a.fc_secondary[j], end.fc_secondary[j]);
                // The honeycombs see the bending-corrected strokes; the change of the bending
                // lengthening is work the vehicle did not do on the struts (eq. 47, lagged).
                let dl = b.bending_lengthening[j] - a.bending_lengthening[j];
                l.mechanisms -= 0.5 * (fa + ft) * dl;
                if let Quadrature::Trapezoid { .. } = quadrature {
                    let s_end = b.secondary_stroke[j] + ds;
                    l.honeycomb += 0.5 * (fa + ft) * (s_end - a.secondary_stroke[j]);
                    let (pa, pt) = (
                        a.fv_secondary[j] * a.secondary_rate[j],
                        t.fv_secondary[j] * t.secondary_rate[j],
                    );
                    l.viscous += 0.5 * (pa + pt) * dt;
                }
            }
        }
        if let Quadrature::Stages { work: w, .. } = quadrature {
            self.ledger.honeycomb += w.honeycomb;
            self.ledger.viscous += w.viscous;
            self.ledger.bearing += w.bearing;
        }
    }

    /// A divergence diagnostic at state `v`: `law` failed, on the leg of index `leg` if one is
    /// involved.
    fn diverged(
        &self,
        v: &VehicleState,
        message: String,
        law: Law,
        leg: Option<usize>,
    ) -> RunError {
        RunError::Stopped(Box::new(Divergence {
            time_s: self.t,
            law,
            leg: leg.map(|i| i + 1),
            message,
            state: StateAtStop {
                position_m: v.position.into(),
                velocity_m_s: v.velocity.into(),
                euler_angles_rad: Some(v.theta.into()),
                angular_velocity_rad_s: v.omega_inertial().into(),
            },
        }))
    }

    /// Stops a run whose state is not finite or whose energy balance (`e`, this state's report)
    /// has drifted beyond the tolerance, naming the law most involved.
    fn check_divergence(&self, e: &EnergyReport) -> Result<(), RunError> {
        let v = &self.vehicle;
        let max_steps = self.integrator.max_steps;
        if let Err(budget) = touchdown_record::check_budget(self.steps, self.evaluations, max_steps)
        {
            return Err(self.diverged(v, budget.to_string(), Law::RunBudget, None));
        }
        for (i, g) in self.gear.iter().enumerate() {
            let checks = [
                (Law::PrimaryHoneycomb, g.fcp),
                (Law::PrimaryViscous, g.fvp),
                (Law::BearingFriction, g.fbr),
                (
                    Law::SecondaryHoneycomb,
                    g.fc_secondary[0] + g.fc_secondary[1],
                ),
                (Law::SecondaryViscous, g.fv_secondary[0] + g.fv_secondary[1]),
                (
                    Law::GearGeometry,
                    g.primary_stroke + g.secondary_stroke[0] + g.secondary_stroke[1],
                ),
            ];
            if let Some((law, value)) = checks.iter().find(|(_, x)| !x.is_finite()) {
                return Err(self.diverged(v, format!("non-finite value {value}"), *law, Some(i)));
            }
        }
        let finite = [
            v.position,
            v.velocity,
            v.acceleration,
            v.theta,
            v.theta_dot,
            v.theta_ddot,
        ]
        .iter()
        .all(|x| x.iter().all(|c| c.is_finite()))
            && self.pads.iter().all(|p| {
                p.position
                    .iter()
                    .chain(p.velocity.iter())
                    .all(|c| c.is_finite())
            });
        if !finite {
            return Err(self.diverged(
                v,
                "non-finite vehicle or footpad state".into(),
                Law::EquationsOfMotion,
                None,
            ));
        }
        self.ledger
            .check_balance(
                e,
                self.integrator.energy_tolerance,
                "step too large for the stiffest mode?",
            )
            .map_err(|imbalance| {
                let loads =
                    (self.gear.iter().zip(&self.memory))
                        .enumerate()
                        .flat_map(|(i, (g, m))| {
                            let primary = (g.primary_stroke, g.fcp + g.fvp + g.fbr);
                            let secondary = [0, 1].map(|j| g.fc_secondary[j] + g.fv_secondary[j]);
                            self.laws
                                .strut_loads(i, m, primary, (g.secondary_stroke, secondary))
                        });
                let message = format!("{imbalance}; {}", StrutLoad::stiffest(loads));
                self.diverged(v, message, Law::EnergyBalance, None)
            })
    }

    /// Stability distances, the unstable crossing and the four stable conditions
    /// (eqs. 105-107, `touchdown_record::stability`). `old` is the previous accepted vehicle
    /// state, `energy` the energy report of this state.
    fn update_stability(&mut self, old: Option<&VehicleState>, energy: &EnergyReport) {
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

    /// Inertial position of footpad `i`, m.
    fn pad_position(&self, i: usize) -> Vector3<f64> {
        let p = &self.pads[i];
        if p.state == ContactState::Contact {
            p.position
        } else {
            self.vehicle.point(&p.bp_attached)
        }
    }

    /// Running maxima of strokes and the pitch rate (angular velocity about the inertial X
    /// axis).
    fn update_extremes(&mut self) {
        for (i, g) in self.gear.iter().enumerate() {
            self.extremes
                .update_leg(i, g.primary_stroke, g.secondary_stroke);
        }
        self.extremes
            .update_pitch_rate(self.t, self.vehicle.omega_inertial().x);
    }

    /// Step 2: the sliding footpads advance over `dt` (s) with their forces frozen at the
    /// accepted state `old` (eq. 97); their start is kept for the stages.
    fn advance_pads(&mut self, dt: f64, old: &VehicleState) -> PadWork {
        let mut w = PadWork::default();
        for i in 0..self.pads.len() {
            self.pad_start[i] = (self.pads[i].position, self.pads[i].velocity);
            if self.pads[i].state != ContactState::Contact || self.surfaces[i].locked() {
                continue;
            }
            let f = self.sliding_forces(i, old);
            let m = self.footpad_mass;
            let (p0, v0) = (self.pads[i].position, self.pads[i].velocity);
            advance_sliding(&mut self.pads[i], &f, dt);
            if let Some(soil) = &self.mechanisms.soil {
                // eq. (103) with constant forces over the step; the soil only resists
                // penetration and holds a resting footpad rigid-plastically (eq. 101 row).
                let load = f.fzi - m * self.gravity.z; // FZI + weight, downward positive
                let plane = self.surfaces[i].plane();
                let step = soil.advance_vertical(plane - p0.z, -v0.z, load, m, dt);
                let pad = &mut self.pads[i];
                pad.position.z = plane - step.depth;
                pad.velocity.z = -step.rate;
                w.gear -= f.fzi * (pad.position.z - p0.z);
                w.soil += step.work;
            }
            let (p1, v1) = (self.pads[i].position, self.pads[i].velocity);
            let dp = Vector2::new(p1.x - p0.x, p1.y - p0.y);
            w.gear += f.gear_xy.dot(&dp);
            w.curbs += f.curb_xy.dot(&dp);
            w.energy_change += 0.5 * m * (v1.norm_squared() - v0.norm_squared())
                - m * self.gravity.dot(&(p1 - p0));
        }
        w
    }

    /// Steps 3-5 of the report's scheme from the accepted state `old` over `dt` (s): the
    /// corrected state, and the vehicle-level mechanisms' power at the trial (W).
    fn predict_correct(
        &mut self,
        dt: f64,
        old: &VehicleState,
    ) -> Result<(VehicleState, f64), RunError> {
        // 3. predictor, c = 0 (eqs. 22-23)
        let mut pred = *old;
        pred.position = old.position + old.velocity * dt + old.acceleration * (0.5 * dt * dt);
        pred.velocity = old.velocity + old.acceleration * dt;
        pred.set_attitude(
            old.theta + old.theta_dot * dt + old.theta_ddot * (0.5 * dt * dt),
            old.theta_dot + old.theta_ddot * dt,
        );
        if self.mechanisms.slosh.is_some() {
            pred.slosh_q = old.slosh_q + old.slosh_q_dot * dt + old.slosh_q_ddot * (0.5 * dt * dt);
            pred.slosh_q_dot = old.slosh_q_dot + old.slosh_q_ddot * dt;
        }
        // 4. trial evaluation
        let mut trial = std::mem::take(&mut self.trial);
        let loads = self.loads(self.t + dt, &pred, &mut trial);
        self.trial = trial;
        let loads = loads?;
        self.evaluations += 1;
        self.accelerate(&mut pred, &loads)?;
        // 5. corrector: c = (a* − a_k)/Δt (eq. 24) in eqs. (22)-(23)
        let mut new = *old;
        new.velocity = old.velocity + (old.acceleration + pred.acceleration) * (0.5 * dt);
        new.position = old.position
            + old.velocity * dt
            + (old.acceleration / 3.0 + pred.acceleration / 6.0) * (dt * dt);
        let theta_dot = old.theta_dot + (old.theta_ddot + pred.theta_ddot) * (0.5 * dt);
        let theta = old.theta
            + old.theta_dot * dt
            + (old.theta_ddot / 3.0 + pred.theta_ddot / 6.0) * (dt * dt);
        new.set_attitude(theta, theta_dot);
        if self.mechanisms.slosh.is_some() {
            new.slosh_q_dot = old.slosh_q_dot + (old.slosh_q_ddot + pred.slosh_q_ddot) * (0.5 * dt);
            new.slosh_q = old.slosh_q
                + old.slosh_q_dot * dt
                + (old.slosh_q_ddot / 3.0 + pred.slosh_q_ddot / 6.0) * (dt * dt);
        }
        Ok((new, loads.applied_power.applied))
    }

    /// One step of the Runge–Kutta method `tab` from the accepted state `old` over `dt` (s),
    /// the sliding footpads already advanced: the new state, the step's quadrature and the error
    /// ratio (0 without an embedded estimate). Each stage evaluates the forces at its own state
    /// into the trial gear states, committing nothing. With a first-same-as-last method the last
    /// stage is the new state: it comes back evaluated, its forces in the trial gear states.
    fn runge_kutta(
        &mut self,
        dt: f64,
        old: &VehicleState,
        tab: &Tableau,
    ) -> Result<(VehicleState, Quadrature, f64), RunError> {
        let form = self.integrator.attitude;
        let y0 = old.ode();
        let mut k = [Ode::zeros(); MAX_STAGES];
        k[0] = old.rate(form);
        let mut work = StageWork::default();
        work.add(tab.b[0] * dt, &self.previous, self.applied_power.applied);
        let mut v = *old;
        let mut last_power = Power::default();
        let mut trial = std::mem::take(&mut self.trial);
        let mut stages = || -> Result<(), RunError> {
            for i in 1..tab.stages {
                let mut y = y0;
                for (a, kj) in tab.a[i].iter().zip(&k).take(i) {
                    if *a != 0.0 {
                        y.add_scaled(dt * a, kj);
                    }
                }
                v.set_ode(&y, form);
                let loads = self.loads_at(self.t + tab.c[i] * dt, &v, tab.c[i], &mut trial)?;
                self.evaluations += 1;
                self.accelerate(&mut v, &loads)?;
                k[i] = v.rate(form);
                work.add(tab.b[i] * dt, &trial, loads.applied_power.applied);
                last_power = loads.applied_power;
            }
            Ok(())
        };
        let result = stages();
        self.trial = trial;
        result?;
        let mut y1 = y0;
        for (b, ki) in tab.b.iter().zip(&k).take(tab.stages) {
            y1.add_scaled(dt * b, ki);
        }
        let ratio = match &tab.e {
            Some(e) => {
                let mut error = Ode::zeros();
                for (w, ki) in e.iter().zip(&k).take(tab.stages) {
                    error.add_scaled(dt * w, ki);
                }
                let it = &self.integrator;
                integrator::error_ratio(&y0, &y1, &error, it.rtol, it.atol)
            }
            None => 0.0,
        };
        if tab.fsal {
            // The last stage's state is y1 (its coupling row is b).
            let evaluated = Some(last_power);
            return Ok((v, Quadrature::Stages { work, evaluated }, ratio));
        }
        let mut new = *old;
        new.set_ode(&y1, form);
        let evaluated = None;
        Ok((new, Quadrature::Stages { work, evaluated }, ratio))
    }

    /// One accepted step of the adaptive Dormand–Prince scheme from `old`: steps whose error
    /// ratio exceeds 1 are rejected (the footpads restored) and retried shorter; a step at
    /// `dt_min` is accepted whatever its error, and counted.
    fn adaptive_step(
        &mut self,
        old: &VehicleState,
    ) -> Result<(f64, VehicleState, Quadrature, PadWork), RunError> {
        let (dt_min, dt_max) = (self.integrator.dt_min, self.integrator.dt_max);
        self.pads_saved.copy_from_slice(&self.pads);
        loop {
            let planned = self.next_dt.clamp(dt_min, dt_max);
            let dt = self.limit_step(planned);
            let pads = self.advance_pads(dt, old);
            let floor = dt <= dt_min * (1.0 + 1e-9);
            // A stage that takes a law out of its domain (a strut stretched past its bearings
            // by a step too long to see its footpad leave) rejects the step, above dt_min.
            let (new, quadrature, ratio) = match self.runge_kutta(dt, old, &DOPRI5) {
                Ok(step) => step,
                Err(_) if !floor => {
                    self.rejected += 1;
                    self.next_dt = 0.5 * dt;
                    self.pads.copy_from_slice(&self.pads_saved);
                    continue;
                }
                Err(e) => return Err(e),
            };
            let ratio = if ratio.is_finite() {
                ratio
            } else {
                f64::INFINITY
            };
            // A footpad that lands or leaves within the step is located to dt_min: the step is
            // retried at half its length until it ends within dt_min of the event.
            let event = !floor && self.contact_event(&new);
            if (ratio <= 1.0 && !event) || floor {
                self.forced += u64::from(ratio > 1.0);
                let proposal = integrator::next_step(dt, ratio, DOPRI5.error_order);
                // A step shortened to land a footpad or to end keeps the plan it cut short.
                let shortened = dt < planned * (1.0 - 1e-9);
                self.next_dt = if shortened {
                    proposal.max(planned)
                } else {
                    proposal
                };
                return Ok((dt, new, quadrature, pads));
            }
            self.rejected += 1;
            self.next_dt = if ratio <= 1.0 {
                0.5 * dt
            } else {
                integrator::next_step(dt, ratio, DOPRI5.error_order)
            };
            self.pads.copy_from_slice(&self.pads_saved);
        }
    }

    /// Whether a footpad's contact changes within the step just taken to `v`, the gear's forces
    /// there in the trial states (the Dormand–Prince pair's last stage is the new state): a
    /// footpad that has stayed in contact and leaves ([`Simulation::contact_steps`]), or an
    /// airborne one that crossed its plane in the step by
    /// more than [`CONTACT_EVENT_DEPTH`] (one already below it at the start, kept off by a gear
    /// that would pull it, is no event).
    fn contact_event(&self, v: &VehicleState) -> bool {
        self.pads.iter().enumerate().any(|(i, p)| match p.state {
            ContactState::Contact => self.contact_steps[i] > 1 && self.leaves(i, v, &self.trial[i]),
            ContactState::Free | ContactState::Detached => {
                let depth = self.surfaces[i].plane() - CONTACT_EVENT_DEPTH;
                self.pad_start[i].0.z >= depth && v.point(&p.bp_attached).z < depth
            }
        })
    }

    /// Steps 6-8 for every scheme: the new state `new` after `dt` (s) from `old` is evaluated,
    /// the contact logic runs, the hysteresis is committed, the work of the step booked
    /// (`quadrature`, the footpads' `pads`, `power_old` the mechanisms' power at `old`, W), the
    /// divergence checks and the stability criteria run.
    fn finish_step(
        &mut self,
        dt: f64,
        old: &VehicleState,
        mut new: VehicleState,
        quadrature: &Quadrature,
        pads: &PadWork,
        power_old: Power,
    ) -> Result<(), RunError> {
        // 6. evaluate (unless the last stage did), contact logic, re-evaluate on a change
        self.t += dt;
        match quadrature {
            Quadrature::Stages {
                evaluated: Some(power),
                ..
            } => {
                std::mem::swap(&mut self.gear, &mut self.trial);
                self.applied_power = *power;
            }
            _ => self.accept(&mut new)?,
        }
        self.vehicle = new;
        let pads_before = self.footpad_energy();
        if self.contact_logic()? {
            let events = self.footpad_energy() - pads_before;
            self.ledger.events += events;
            self.accept(&mut new)?;
            self.vehicle = new;
        }
        // 7. commit hysteresis at the accepted state
        for (n, p) in self.contact_steps.iter_mut().zip(&self.pads) {
            *n = if p.state == ContactState::Contact {
                n.saturating_add(1)
            } else {
                0
            };
        }
        for i in 0..self.legs.len() {
            if self.pads[i].state == ContactState::Contact {
                let g = &self.gear[i];
                self.laws
                    .commit(g.primary_stroke, g.secondary_stroke, &mut self.memory[i]);
                self.bending_lag[i] = g.point1_deflection;
                let pad = &mut self.pads[i];
                let bp = new.t_bi.transpose() * (pad.position - new.position);
                pad.bp = bp;
                if let Some(curbs) = &mut self.mechanisms.curbs {
                    let xy = Vector2::new(pad.position.x, pad.position.y);
                    curbs.commit(i, pad.touchdown_xy, xy, self.footpad_radius);
                }
            }
        }
        self.mechanisms.commit(&new, &self.gravity);
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
        self.book_strut_work(dt, quadrature);
        self.steps += 1;
        let energy = self.energy();
        self.check_divergence(&energy)?;
        self.update_stability(Some(old), &energy);
        self.update_extremes();
        Ok(())
    }
}

impl Landing for Simulation {
    type Error = RunError;

    /// One integration step (see the module documentation).
    fn step(&mut self) -> Result<(), RunError> {
        let old = self.vehicle;
        self.previous.copy_from_slice(&self.gear);
        let power_old = self.applied_power;
        let (dt, new, quadrature, pads) = match self.integrator.scheme {
            Scheme::Report => {
                let dt = self.limit_step(self.report_step_size());
                let pads = self.advance_pads(dt, &old);
                let (new, trial_power) = self.predict_correct(dt, &old)?;
                (dt, new, Quadrature::Trapezoid { trial_power }, pads)
            }
            Scheme::Rk4 => {
                let dt = self.limit_step(self.integrator.dt_max);
                let pads = self.advance_pads(dt, &old);
                let (new, quadrature, _) = self.runge_kutta(dt, &old, &RK4)?;
                (dt, new, quadrature, pads)
            }
            Scheme::Dopri5 => self.adaptive_step(&old)?,
        };
        self.finish_step(dt, &old, new, &quadrature, &pads, power_old)
    }
    /// Whether the run has ended (end time, or a decision with termination on).
    fn finished(&self) -> bool {
        self.t >= self.integrator.t_end * (1.0 - 1e-12) || self.stability.terminates()
    }

    /// Writes the current state into `out` (a sample made for as many legs), allocating
    /// nothing.
    fn sample(&self, out: &mut Sample) {
        let v = &self.vehicle;
        out.t = self.t;
        out.position = v.position;
        out.velocity = v.velocity;
        out.theta = v.theta;
        out.omega = v.omega;
        out.pitch_rate = v.omega_inertial().x;
        for ((slot, g), p) in out.legs.iter_mut().zip(&self.gear).zip(&self.pads) {
            slot.primary_stroke = g.primary_stroke;
            slot.primary_force = g.f2p;
            slot.secondary_stroke = g.secondary_stroke;
            slot.secondary_force = g.f_secondary();
            slot.pad_position = p.position;
            slot.contact = p.state.code();
        }
        out.stability_distance
            .copy_from_slice(self.stability.distances());
        out.energy = self.energy();
    }

    /// The summary at the current state.
    fn summary(&self) -> Summary {
        let progress = Progress {
            t: self.t,
            steps: self.steps,
            force_evaluations: self.evaluations,
            first_contact_s: self.pads.iter().map(|p| p.first_contact).collect(),
        };
        let mut summary = Summary::new(
            "core",
            &self.name,
            self.settings(),
            progress,
            &self.stability,
            &self.extremes,
            self.energy(),
        );
        summary.mechanisms = self
            .mechanism_evaluations()
            .into_iter()
            .map(|(m, n)| (m.name().to_string(), n))
            .collect();
        summary
    }
}
