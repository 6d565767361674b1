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
//! Nothing in the step allocates.

use crate::gear::{self, GearOptions, GearState};
use crate::kinematics::{euler_acceleration, t_eb, GIMBAL_LOCK_COS};
use crate::mechanisms::Mechanisms;
use crate::rigid_body::MassProperties;
use crate::surface::{advance_sliding, touch_down, ContactState, Footpad, SlidingForces};
use crate::CoreError;
use nalgebra::{Matrix3, Vector2, Vector3};
use touchdown_laws::{sliding_friction, GearLaws, GearMemory};
use touchdown_record::{
    Divergence, EnergyLedger, EnergyReport, Extremes, Landing, PadView, Progress, Sample,
    StabilityTracker, Summary,
};
use touchdown_scenario::frames::{self, gravity_inertial};
use touchdown_scenario::model::{Integrator, Leg, Mechanism, PadSurface};
use touchdown_scenario::schema::{Arrangement, Engine, ReleaseRule};
use touchdown_scenario::Scenario;

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
    /// T_BI (eq. 3) at θ.
    pub t_bi: Matrix3<f64>,
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
    /// Power of the vehicle-level mechanisms on the vehicle at the accepted state, W.
    applied_power: f64,
    ledger: EnergyLedger,
    potential0: f64,
    stability: StabilityTracker,
    extremes: Extremes,
    /// Footpad views for the stability criteria (reused every step).
    pad_views: Vec<PadView>,
}

/// Net loads on the vehicle (eqs. 66-68, 83-84): force in inertial axes excluding gravity,
/// torque in body axes, and the power of the vehicle-level mechanisms (thrust, nozzle, RCS,
/// slosh) on the vehicle, W.
struct Loads {
    force: Vector3<f64>,
    torque: Vector3<f64>,
    applied_power: f64,
}

impl Simulation {
    /// Sets up a landing from a resolved scenario: laws, initial state (eq. 19) and the
    /// contact of the first footpad.
    pub fn new(scenario: &Scenario) -> Result<Simulation, CoreError> {
        scenario.require_engine(Engine::Core)?;
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
            applied_power: 0.0,
            ledger: EnergyLedger::default(),
            potential0: 0.0,
            stability: StabilityTracker::new(&scenario.stability, gravity, n, 0.0),
            extremes: Extremes::new(n),
            pad_views: vec![PadView::default(); n],
        };
        sim.potential0 = sim.potential_energy();
        sim.stability =
            StabilityTracker::new(&scenario.stability, gravity, n, sim.kinetic_energy());
        // First contact at t = 0, then the accepted state's forces and accelerations.
        let before = sim.footpad_energy();
        sim.contact_logic();
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
        m.insert(
            "scheme".into(),
            "report predictor-corrector, eqs. (20)-(25)".into(),
        );
        m.insert("dist_m".into(), it.dist.into());
        m.insert("dt_min_s".into(), it.dt_min.into());
        m.insert("dt_max_s".into(), it.dt_max.into());
        m.insert("energy_tolerance".into(), it.energy_tolerance.into());
        m
    }

    /// Step size by eq. (25), Δt = DIST/VEL clamped to [Δt_min, Δt_max], shortened so that an
    /// airborne footpad lands on its plane (review A12) and so that the end time is met.
    fn step_size(&self) -> f64 {
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
        let mut dt = if vel > 0.0 { it.dist / vel } else { it.dt_max }; // eq. (25)
        dt = dt.clamp(it.dt_min, it.dt_max);
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
    fn loads(&self, t: f64, v: &VehicleState, out: &mut [GearState]) -> Result<Loads, CoreError> {
        let t_ib = v.t_bi.transpose();
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
            let bp = t_ib * (pad.position - v.position);
            let bp_dot = t_ib * (pad.velocity - v.velocity) - v.omega.cross(&bp);
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
            .map_err(|f| self.diverged(v, f.error.to_string(), f.law, i))?;
            torque += bp.cross(&(-slot.fp)); // eq. (66)
            force -= v.t_bi * slot.fp; // eqs. (67)-(68)
        }
        // eqs. (72)-(74), (80)-(82), (115)-(117): the scene's vehicle-level mechanisms, if any.
        let mut applied_power = 0.0;
        if let Some(a) = self.mechanisms.vehicle_loads(t, || self.first_contact(), v) {
            let applied_force = v.t_bi * a.force;
            force += applied_force; // eq. (83)
            torque += a.torque; // eq. (84)
            applied_power = applied_force.dot(&v.velocity) + a.torque.dot(&v.omega);
        }
        Ok(Loads {
            force,
            torque,
            applied_power,
        })
    }

    /// Time of the first footpad contact, s.
    fn first_contact(&self) -> Option<f64> {
        self.pads
            .iter()
            .filter_map(|p| p.first_contact)
            .reduce(f64::min)
    }

    /// Accelerations of `v` under `loads`: eqs. (10)-(12), (13)-(15) and (9a)-(9c).
    fn accelerate(&self, v: &mut VehicleState, loads: &Loads) -> Result<(), CoreError> {
        if v.theta.y.cos().abs() < GIMBAL_LOCK_COS {
            return Err(self.diverged(
                v,
                "Euler-angle singularity: θy reached ±90° (eqs. 5 and 9a divide by cos θy)".into(),
                "kinematics",
                usize::MAX,
            ));
        }
        v.acceleration = self.mass.linear_acceleration(&loads.force, &self.gravity);
        v.omega_dot = self.mass.angular_acceleration(&loads.torque, &v.omega);
        v.theta_ddot = euler_acceleration(&v.theta, &v.theta_dot, &v.omega, &v.omega_dot);
        v.slosh_q_ddot = self.mechanisms.slosh_acceleration(v); // eq. (109), corrected
        Ok(())
    }

    /// Evaluates the accepted state `v` into `self.gear` and sets its accelerations.
    fn accept(&mut self, v: &mut VehicleState) -> Result<(), CoreError> {
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

    /// Contact logic of the rigid surface (text before eq. 85; review A1-A2, A4-A5) at the
    /// current vehicle state. Returns whether any footpad changed state.
    fn contact_logic(&mut self) -> bool {
        let v = self.vehicle;
        let mut changed = false;
        for i in 0..self.pads.len() {
            let s = self.surfaces[i];
            let pad = &mut self.pads[i];
            match pad.state {
                ContactState::Free | ContactState::Detached => {
                    let tentative = v.point(&pad.bp_attached);
                    if tentative.z <= s.plane() {
                        let vel = v.point_velocity(&pad.bp_attached);
                        let v_normal = if self.mechanisms.soil.is_some() {
                            vel.z
                        } else {
                            0.0
                        };
                        touch_down(
                            pad,
                            &s,
                            Vector2::new(tentative.x, tentative.y),
                            Vector2::new(vel.x, vel.y),
                            v_normal,
                            self.t,
                        );
                        changed = true;
                    } else {
                        pad.position = tentative;
                        pad.velocity = v.point_velocity(&pad.bp_attached);
                    }
                }
                ContactState::Contact => {
                    // Tentative position with the previous step's geometry; the footpad stays
                    // on the surface while the primary strut is compressive.
                    let tentative = v.point(&pad.bp);
                    let g = &self.gear[i];
                    let compressive = match self.release {
                        ReleaseRule::StrutForce => g.f2p > 0.0,
                        ReleaseRule::HoneycombForce => g.fcp > 0.0,
                    };
                    // On soil the footpad leaves when it has risen out of the soil (A15).
                    let height = if self.mechanisms.soil.is_some() {
                        pad.position.z
                    } else {
                        tentative.z
                    };
                    if height > s.plane() && !compressive {
                        pad.state = ContactState::Detached;
                        pad.stuck = false;
                        pad.bp_attached = v.t_bi.transpose() * (pad.position - v.position);
                        pad.velocity = v.point_velocity(&pad.bp_attached);
                        changed = true;
                    }
                }
            }
        }
        changed
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
        }
    }

    /// Adds the strut work of the step with the forces the corrector used (eq. 24: the
    /// accepted state k and the trial at the prediction), so that the ledger and the vehicle's
    /// energy see the same forces even when a footpad leaves the surface in the step:
    /// honeycomb ½(F_k + F*)·(x_{k+1} − x_k), viscous and bearing friction ½(P_k + P*)·Δt.
    fn book_strut_work(&mut self, dt: f64) {
        let steps = self.previous.iter().zip(&self.trial).zip(&self.gear);
        for ((a, t), b) in steps {
            let l = &mut self.ledger;
            l.honeycomb += 0.5 * (a.fcp + t.fcp) * (b.primary_stroke - a.primary_stroke);
            l.viscous += 0.5 * (a.fvp * a.primary_rate + t.fvp * t.primary_rate) * dt;
            l.bearing += 0.5 * (a.fbr * a.primary_rate + t.fbr * t.primary_rate) * dt;
            for j in 0..2 {
                let (fa, ft) = (a.fc_secondary[j], t.fc_secondary[j]);
                l.honeycomb += 0.5 * (fa + ft) * (b.secondary_stroke[j] - a.secondary_stroke[j]);
                // The honeycombs see the bending-corrected strokes; the change of the bending
                // lengthening is work the vehicle did not do on the struts (eq. 47, lagged).
                let dl = b.bending_lengthening[j] - a.bending_lengthening[j];
                l.mechanisms -= 0.5 * (fa + ft) * dl;
                let (pa, pt) = (
                    a.fv_secondary[j] * a.secondary_rate[j],
                    t.fv_secondary[j] * t.secondary_rate[j],
                );
                l.viscous += 0.5 * (pa + pt) * dt;
            }
        }
    }

    /// A divergence diagnostic at state `v`; `leg` is usize::MAX when no leg is involved.
    fn diverged(&self, v: &VehicleState, message: String, law: &str, leg: usize) -> CoreError {
        CoreError::Diverged(Divergence {
            time: self.t,
            law: if leg == usize::MAX { law.to_string() } else { format!("{law} (leg {})", leg + 1) },
            message,
            state: format!(
                "R = [{:.6e}, {:.6e}, {:.6e}] m, V = [{:.6e}, {:.6e}, {:.6e}] m/s, θ = [{:.6e}, {:.6e}, {:.6e}] rad, ω = [{:.6e}, {:.6e}, {:.6e}] rad/s",
                v.position.x, v.position.y, v.position.z, v.velocity.x, v.velocity.y, v.velocity.z, v.theta.x, v.theta.y, v.theta.z, v.omega.x, v.omega.y, v.omega.z
            ),
        })
    }

    /// Stops a run whose state is not finite or whose energy balance (`e`, this state's report)
    /// has drifted beyond the tolerance, naming the law most involved.
    fn check_divergence(&self, e: &EnergyReport) -> Result<(), CoreError> {
        let v = &self.vehicle;
        for (i, g) in self.gear.iter().enumerate() {
            let checks = [
                ("primary honeycomb", g.fcp),
                ("primary viscous", g.fvp),
                ("bearing friction", g.fbr),
                ("secondary honeycomb", g.fc_secondary[0] + g.fc_secondary[1]),
                ("secondary viscous", g.fv_secondary[0] + g.fv_secondary[1]),
                (
                    "gear geometry",
                    g.primary_stroke + g.secondary_stroke[0] + g.secondary_stroke[1],
                ),
            ];
            if let Some((law, value)) = checks.iter().find(|(_, x)| !x.is_finite()) {
                return Err(self.diverged(v, format!("non-finite value {value}"), law, i));
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
                "equations of motion",
                usize::MAX,
            ));
        }
        self.ledger
            .check_balance(
                e,
                self.integrator.energy_tolerance,
                "step too large for the stiffest mode?",
            )
            .map_err(|message| self.diverged(v, message, "energy balance", usize::MAX))
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
}

impl Landing for Simulation {
    type Error = CoreError;

    /// One integration step (see the module documentation).
    fn step(&mut self) -> Result<(), CoreError> {
        let dt = self.step_size();
        let old = self.vehicle;
        self.previous.copy_from_slice(&self.gear);
        // 2. sliding footpads, forces frozen at t_k (eq. 97)
        let mut pad_work = 0.0;
        let mut pad_energy_change = 0.0;
        let (mut soil_work, mut curb_work) = (0.0, 0.0);
        for i in 0..self.pads.len() {
            if self.pads[i].state != ContactState::Contact || self.surfaces[i].locked() {
                continue;
            }
            let f = self.sliding_forces(i, &old);
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
                pad_work -= f.fzi * (pad.position.z - p0.z);
                soil_work += step.work;
            }
            let (p1, v1) = (self.pads[i].position, self.pads[i].velocity);
            let dp = Vector2::new(p1.x - p0.x, p1.y - p0.y);
            pad_work += f.gear_xy.dot(&dp);
            curb_work += f.curb_xy.dot(&dp);
            pad_energy_change += 0.5 * m * (v1.norm_squared() - v0.norm_squared())
                - m * self.gravity.dot(&(p1 - p0));
        }
        // 3. predictor, c = 0 (eqs. 22-23)
        let mut pred = old;
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
        let mut new = old;
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
        let power_old = self.applied_power;
        // 6. evaluate, contact logic, re-evaluate on a change
        self.t += dt;
        self.accept(&mut new)?;
        self.vehicle = new;
        let pads_before = self.footpad_energy();
        if self.contact_logic() {
            let events = self.footpad_energy() - pads_before;
            self.ledger.events += events;
            self.accept(&mut new)?;
            self.vehicle = new;
        }
        // 7. commit hysteresis at the accepted state
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
        // Work of the vehicle-level mechanisms on the vehicle with the forces the corrector
        // used (trapezoid of their power), and of the soil and curbs on the footpads.
        let applied_work = 0.5 * (power_old + loads.applied_power) * dt;
        self.ledger.mechanisms += -applied_work - soil_work - curb_work;
        self.ledger.sliding += pad_work + curb_work + soil_work - pad_energy_change;
        self.book_strut_work(dt);
        self.steps += 1;
        let energy = self.energy();
        self.check_divergence(&energy)?;
        self.update_stability(Some(&old), &energy);
        self.update_extremes();
        Ok(())
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
