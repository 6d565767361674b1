//! The gear bookkeeping a multibody engine keeps around its own stepping, the same for every
//! multibody engine: each gear's kinematics before and after a step, the laws' forces, the
//! honeycomb memories (committed once per step), the footpads' contact states, the energy
//! ledger, the stability criteria, the extremes, and what the summary and the history report;
//! and the loads applied to its bodies: the engine and RCS on the vehicle, the curbs on the
//! footpads (eqs. 86-95, the crush memory committed once per step).
//!
//! As the core splits its `Model` from its `State` (MuJoCo's `mjModel` and `mjData`), the book
//! is two values: a [`GearModel`], the gear as set up, which no step changes, and a
//! [`GearState`], what the steps change; every call that books takes the model by reference and
//! the state by mutable reference, and the order of a step is in the arguments:
//!
//! - at touchdown, [`GearModel::new`] gives both, and [`GearModel::start_landing`] takes the
//!   engine's kinematics read at touchdown;
//! - before each step the engine applies what the state holds for it, its own way: each gear's
//!   strut forces ([`GearState::forces`], on [`GearState::kinematics`]), the vehicle loads
//!   ([`GearState::applied`]) and, if [`GearModel::loads_footpads`], each footpad's force
//!   ([`GearState::pad_force`]);
//! - after it, [`GearModel::finish_step`] takes the step as a [`StepTaken`]: the vehicle before
//!   it, its length, the kinematics the engine read after it and each footpad's contact over it,
//!   and books it in one order for every engine: the contacts, the struts' work, the
//!   honeycomb memories committed and the laws at the new state, the applied loads' work, the
//!   divergence checks, the stability criteria, the extremes, and the applied loads for the
//!   next step (if the landing goes on).

use crate::applied::VehicleLoads;
use crate::motion::{BodyMotion, Fault};
use crate::step::stiffest_rate;
use crate::stride::StepRule;
use crate::strut::{strut_forces, StrutForces, StrutKinematics};
use crate::wall::ObstacleWall;
use nalgebra::{Vector2, Vector3};
use touchdown_laws::{CrushMemory, Curbs, GearLaws, GearMemory, StrutLoad};
use touchdown_record::{
    EnergyLedger, EnergyReport, Extremes, Law, PadView, Progress, Sample, StabilityTracker,
    StrutCapacities, Summary,
};
use touchdown_scenario::model::{Leg, Mechanism, PadSurface, Stability};
use touchdown_scenario::schema::Arrangement;
use touchdown_scenario::{Scenario, ScenarioError};

/// How long a footpad stays in contact after its last pushing normal impulse, s: longer than
/// the engines' contact rebounds between steps (a few steps of 2e-5 s), shorter than the
/// footpad's modes on its gear (3.6-9.3 ms on the 1/6-scale model). See
/// [`PadContact::update`].
pub const CONTACT_HOLD_S: f64 = 1.0e-3;

/// How far above its plane a footpad may hop and still count as in contact, m: the engines'
/// footpads rebound off their compliant contacts by 0.01-1 mm while their gear presses them
/// (docs/engines.md, "The contact flag"). See [`PadContact::update`].
pub const CONTACT_CLEARANCE_M: f64 = 1.0e-3;

/// The contact flag's rule as the summaries' `engine_settings` state it: names (with units)
/// and values of `CONTACT_HOLD_S` and `CONTACT_CLEARANCE_M`.
pub const CONTACT_FLAG_SETTINGS: [(&str, f64); 2] = [
    ("contact_hold_s", CONTACT_HOLD_S),
    ("contact_clearance_m", CONTACT_CLEARANCE_M),
];

/// Contact state of one footpad.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PadContact {
    /// Bearing on its surface now, by the rule of [`PadContact::update`].
    pub in_contact: bool,
    /// Time of the first contact, s.
    pub first_contact: Option<f64>,
    /// Time of the last step with a pushing normal impulse, s.
    last_push: Option<f64>,
}

impl PadContact {
    /// Updates the flag at the end of a step `dt` s long ending at time `t` (s), on which the
    /// footpad received a pushing normal impulse (`pushed`) and stands `clearance` (m) above its
    /// plane. A footpad is in contact from its first step with a pushing impulse until it has
    /// received none for [`CONTACT_HOLD_S`] and stands more than [`CONTACT_CLEARANCE_M`] above
    /// its plane: a footpad that rebounds off its compliant contact between steps, or hops a
    /// fraction of a millimetre while its gear presses it, stays down; one that its gear
    /// lifts clear leaves. (The step's half-length absorbs the rounding of `t`.)
    pub fn update(&mut self, pushed: bool, t: f64, dt: f64, clearance: f64) {
        if pushed {
            self.in_contact = true;
            self.last_push = Some(t);
            if self.first_contact.is_none() {
                self.first_contact = Some(t);
            }
        } else if let Some(last) = self.last_push {
            let quiet = t - last >= CONTACT_HOLD_S - 0.5 * dt;
            if quiet && clearance > CONTACT_CLEARANCE_M {
                self.in_contact = false;
            }
        }
    }
}

/// One footpad's contact over a step, as the engine read it (see [`GearModel::finish_step`]).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PadStep {
    /// The impulse its surface gave it over the step, N·s, inertial.
    pub impulse: Vector3<f64>,
    /// That impulse's work along each inertial axis, J: the impulse on the mean of the contact
    /// point's velocities before and after the step, plus whatever the engine's contact solver
    /// moved the footpad by beyond its velocities.
    pub work: Vector3<f64>,
    /// Its penetration into its plane, m.
    pub depth: f64,
    /// Whether the engine found it touching its surface.
    pub touching: bool,
}

/// The energies of an engine's bodies at a state, for the energy report
/// ([`GearModel::energy`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyEnergy {
    /// The vehicle's kinetic energy, J.
    pub kinetic_j: f64,
    /// The vehicle's potential-energy change since touchdown, J.
    pub potential_change_j: f64,
    /// The gear links' energy change since touchdown, J.
    pub gear_j: f64,
}

/// What an engine read of its bodies at a state (see [`GearModel::finish_step`]).
#[derive(Debug, Clone, Copy)]
pub struct Reading<'a> {
    /// Time, s.
    pub t: f64,
    /// The vehicle.
    pub vehicle: &'a BodyMotion,
    /// Whether every body state the engine reads is finite.
    pub finite: bool,
    /// The bodies' energies.
    pub energy: BodyEnergy,
    /// Accepted steps so far.
    pub steps: u64,
}

/// A step an engine has taken, as [`GearModel::finish_step`] books it.
#[derive(Debug, Clone, Copy)]
pub struct StepTaken<'a> {
    /// The vehicle before the step.
    pub before: &'a BodyMotion,
    /// The step's length, s.
    pub dt: f64,
    /// Each gear's kinematics after the step, as the engine read them.
    pub kinematics: &'a [StrutKinematics],
    /// Each footpad's contact over the step, as the engine read it.
    pub pads: &'a [PadStep],
}

/// The gear of a multibody landing as set up, which no step changes (see the module
/// documentation).
pub struct GearModel {
    /// The gear geometry.
    legs: Vec<Leg>,
    /// Where the secondaries meet the primary (point 1 or the footpad).
    arrangement: Arrangement,
    /// Each footpad's surface.
    surfaces: Vec<PadSurface>,
    /// The shared laws.
    laws: GearLaws,
    /// The curbs with their footpad crushing (nothing without them).
    curbs: Option<Curbs>,
    /// Whether any footpad has an obstacle wall (OBST > 0).
    walls: bool,
    criteria: Stability,
    gravity: Vector3<f64>,
    /// Undeformed footpad radius PR, m (eq. 93).
    pad_radius: f64,
    /// The divergence guard's tolerance, a fraction of the energy put in
    /// (`integrator.energy_tolerance`).
    energy_tolerance: f64,
    /// The guard's least scale, J (`Scenario::energy_floor_j`).
    energy_floor_j: f64,
    /// The run budget, accepted steps (`integrator.max_steps`).
    max_steps: u64,
    /// End of the run, s (`integrator.t_end`).
    t_end: f64,
    /// The engine's step, base and long (`crate::stride`).
    rule: StepRule,
}

/// What the steps of a multibody landing change (see the module documentation).
pub struct GearState {
    /// Committed honeycomb memories.
    memory: Vec<GearMemory>,
    /// Kinematics at the current state.
    kin: Vec<StrutKinematics>,
    /// Kinematics before the step being booked.
    previous: Vec<StrutKinematics>,
    /// The laws' forces at the current state (applied over the next step).
    forces: Vec<StrutForces>,
    /// Contact states.
    contacts: Vec<PadContact>,
    /// The engine and RCS loads on the vehicle (nothing without them).
    applied: VehicleLoads,
    /// The curbs' committed crush memories, one per curb of the model's curbs.
    curb_memory: Vec<CrushMemory>,
    /// The curbs' force on each footpad over the current step, N, inertial axes (z = 0).
    curb_forces: Vec<Vector3<f64>>,
    /// Each locked footpad's obstacle wall (none where OBST ≤ 0).
    walls: Vec<Option<ObstacleWall>>,
    /// The walls' force on each footpad over the current step, N, inertial axes (z = 0).
    wall_forces: Vec<Vector3<f64>>,
    /// Each footpad's velocity at BP at the start of the current step, m/s, inertial.
    pad_velocity: Vec<Vector3<f64>>,
    /// Work exchanged with each mechanism.
    ledger: EnergyLedger,
    /// Deepest footpad penetration into its plane so far, m.
    max_penetration: f64,
    /// Stability criteria, eqs. (105)-(107).
    stability: StabilityTracker,
    /// Running extremes.
    extremes: Extremes,
    pad_views: Vec<PadView>,
    /// Each footpad's first contact point (XPI, YPI), m (eq. 86).
    touchdown_xy: Vec<Vector2<f64>>,
    curb_evaluations: u64,
    /// The last step's length, s (zero before the first).
    last_dt: f64,
}

impl GearState {
    /// Gear `i`'s kinematics at the current state.
    pub fn kinematics(&self, i: usize) -> &StrutKinematics {
        &self.kin[i]
    }

    /// The laws' forces on gear `i` at the current state, applied over the coming step.
    pub fn forces(&self, i: usize) -> &StrutForces {
        &self.forces[i]
    }

    /// The engine and RCS loads on the vehicle over the coming step.
    pub fn applied(&self) -> &VehicleLoads {
        &self.applied
    }

    /// The force on footpad `i` over the coming step (at BP, its centre of mass), N, inertial
    /// axes: its curbs' (eqs. 94-95) and its obstacle wall's (`crate::wall`).
    pub fn pad_force(&self, i: usize) -> Vector3<f64> {
        self.curb_forces[i] + self.wall_forces[i]
    }

    /// Deepest footpad penetration into its plane so far, m.
    pub fn max_penetration(&self) -> f64 {
        self.max_penetration
    }
}

impl GearModel {
    /// The gear of `sc` and its state at touchdown, nothing booked yet, for an engine whose
    /// base step is `dt` (s) and that takes steps of up to `max_stride` base steps between
    /// the stops where the scene allows them ([`GearModel::next_step`]; 1: `dt` throughout).
    pub fn new(
        sc: &Scenario,
        dt: f64,
        max_stride: u32,
    ) -> Result<(GearModel, GearState), ScenarioError> {
        let n = sc.legs.len();
        let gravity = touchdown_frames::gravity_inertial(sc.vehicle.gravity, sc.surface.slope);
        let laws = GearLaws::from_scenario(sc)?;
        let capacities = StrutCapacities::new(laws.capacities());
        let primary_rate = stiffest_rate(&laws.primary.honeycomb);
        let walls: Vec<Option<ObstacleWall>> = (sc.surface.pads.iter())
            .map(|p| {
                p.locked()
                    .then(|| ObstacleWall::new(p.hold_height(), sc.footpad.mass, primary_rate, dt))
            })
            .collect();
        let curbs = touchdown_laws::scene::curbs_from_scenario(sc)?;
        let applied = VehicleLoads::new(sc, dt)?;
        // The curbs, the nozzle and the walls are explicit at rates tied to the base step.
        let tied = curbs.is_some() || !applied.is_empty() || walls.iter().any(Option::is_some);
        let max_stride = if tied { 1 } else { max_stride };
        let rule = StepRule::new(sc, &laws, dt, max_stride);
        let state = GearState {
            memory: vec![GearMemory::default(); n],
            kin: vec![StrutKinematics::default(); n],
            previous: vec![StrutKinematics::default(); n],
            forces: vec![StrutForces::default(); n],
            contacts: vec![PadContact::default(); n],
            applied,
            curb_memory: curbs.as_ref().map_or_else(Vec::new, Curbs::memories),
            curb_forces: vec![Vector3::zeros(); n],
            wall_forces: vec![Vector3::zeros(); n],
            pad_velocity: vec![Vector3::zeros(); n],
            ledger: EnergyLedger::default(),
            max_penetration: 0.0,
            stability: StabilityTracker::new(&sc.stability, gravity, n, 0.0),
            extremes: Extremes::new(n, capacities),
            pad_views: vec![PadView::default(); n],
            touchdown_xy: vec![Vector2::zeros(); n],
            curb_evaluations: 0,
            last_dt: 0.0,
            walls,
        };
        let model = GearModel {
            legs: sc.legs.clone(),
            arrangement: sc.arrangement,
            surfaces: sc.surface.pads.clone(),
            laws,
            walls: state.walls.iter().any(Option::is_some),
            curbs,
            criteria: sc.stability.clone(),
            gravity,
            pad_radius: sc.footpad.radius,
            energy_tolerance: sc.integrator.energy_tolerance,
            energy_floor_j: sc.energy_floor_j(),
            max_steps: sc.integrator.max_steps,
            t_end: sc.integrator.t_end,
            rule,
        };
        Ok((model, state))
    }

    /// The gear geometry, one leg per gear.
    pub fn legs(&self) -> &[Leg] {
        &self.legs
    }

    /// Footpad `i`'s surface.
    pub fn surface(&self, i: usize) -> &PadSurface {
        &self.surfaces[i]
    }

    /// Gravity in the inertial frame, m/s².
    pub fn gravity(&self) -> Vector3<f64> {
        self.gravity
    }

    /// Whether the gear applies forces to the footpads ([`GearState::pad_force`]): curbs or
    /// obstacle walls.
    pub fn loads_footpads(&self) -> bool {
        self.curbs.is_some() || self.walls
    }

    /// The length of the next step from time `t` (s) in `state`, s: the long step where no
    /// stop is engaged or can engage within it, the base step otherwise (`crate::stride`).
    pub fn next_step(&self, state: &GearState, t: f64) -> f64 {
        self.rule.next(
            &state.kin,
            &state.previous,
            &state.memory,
            state.last_dt,
            t,
            self.t_end,
        )
    }

    /// The step between the stops, s: the long step of [`GearModel::next_step`] (the base
    /// step where the scene allows none longer).
    pub fn long_step(&self) -> f64 {
        self.rule.long()
    }

    /// Whether the landing in `state` has ended at time `t` (s): an unstable decision, if the
    /// scenario terminates on one, or the end time.
    pub fn finished(&self, state: &GearState, t: f64) -> bool {
        t >= self.t_end * (1.0 - 1e-12) || state.stability.terminates()
    }

    /// Starts the landing in `state` at touchdown, with the engine's gear `kinematics` and its
    /// bodies as read (`now`): the stability criteria started with the vehicle's kinetic energy,
    /// the laws evaluated, the checks, the stability distances, and the applied loads for the
    /// first step (the footpads' velocities at BP `pad_velocity(i)`, m/s, inertial). Returns the
    /// energy report of the state.
    pub fn start_landing(
        &self,
        state: &mut GearState,
        kinematics: &[StrutKinematics],
        now: &Reading,
        pad_velocity: impl Fn(usize) -> Vector3<f64>,
    ) -> Result<EnergyReport, Fault> {
        state.kin.copy_from_slice(kinematics);
        state.stability = StabilityTracker::new(
            &self.criteria,
            self.gravity,
            self.legs.len(),
            now.energy.kinetic_j,
        );
        self.evaluate(state)?;
        self.settle(state, now, None, pad_velocity)
    }

    /// Books the `step` just taken into `state`, the bodies as read after it in `now`, in one
    /// order for every engine: the contacts, the struts' work with the honeycomb memories
    /// committed at the new strokes and the laws at the new state, the applied loads' work, the
    /// divergence checks (the run budget, non-finite values, the energy balance), the stability
    /// criteria, the extremes, and, if the landing goes on, the applied loads for the next step
    /// (the footpads' velocities at BP `pad_velocity(i)`, m/s, inertial). Returns the energy
    /// report of the new state.
    pub fn finish_step(
        &self,
        state: &mut GearState,
        step: &StepTaken,
        now: &Reading,
        pad_velocity: impl Fn(usize) -> Vector3<f64>,
    ) -> Result<EnergyReport, Fault> {
        let StepTaken {
            before,
            dt,
            kinematics,
            pads,
        } = *step;
        state.previous.copy_from_slice(&state.kin);
        state.kin.copy_from_slice(kinematics);
        state.last_dt = dt;
        for (i, pad) in pads.iter().enumerate() {
            self.book_contact(state, i, pad, now.t, dt);
        }
        self.book_struts(state)?;
        self.book_applied(state, before, now.vehicle, dt, &pad_velocity);
        let energy = self.settle(state, now, Some(&before.velocity), pad_velocity)?;
        Self::update_extremes(state, now.t, now.vehicle);
        state.extremes.update_acceleration(
            &before.velocity,
            &now.vehicle.velocity,
            dt,
            &self.gravity,
        );
        state.extremes.follow(&state.stability);
        Ok(energy)
    }

    /// The checks, the stability criteria and the applied loads for the next step at the state
    /// `now` whose laws are evaluated; `old_velocity` is the vehicle's velocity before the step
    /// (m/s; `None` at touchdown).
    fn settle(
        &self,
        state: &mut GearState,
        now: &Reading,
        old_velocity: Option<&Vector3<f64>>,
        pad_velocity: impl Fn(usize) -> Vector3<f64>,
    ) -> Result<EnergyReport, Fault> {
        let energy = self.energy(state, &now.energy);
        self.check(state, &energy, now.finite, now.steps)?;
        Self::update_stability(state, now.t, now.vehicle, old_velocity, &energy);
        if !self.finished(state, now.t) {
            self.evaluate_applied(state, now.t, now.vehicle, pad_velocity)?;
        }
        Ok(energy)
    }

    /// Books the work of the laws over the step just taken (`previous` → `kin`), their path
    /// integral from their forces at both ends ([`StrutForces::work`]; at the end with the
    /// memory committed before the step, the memory the step's strokes load), commits the
    /// honeycomb memories at the new strokes, and leaves the laws' forces at the new state:
    /// those at the end, unless the commit changed the memory they were evaluated with.
    fn book_struts(&self, state: &mut GearState) -> Result<(), Fault> {
        for i in 0..self.legs.len() {
            let (a, b) = (&state.previous[i], &state.kin[i]);
            let end = self.forces_at(i, &state.memory[i], b)?;
            let w = state.forces[i].work(&end, a, b);
            state.ledger.honeycomb += w.honeycomb;
            state.ledger.viscous += w.viscous;
            state.ledger.bearing += w.bearing;
            let loaded = state.memory[i];
            self.laws.commit(b.c, b.s, &mut state.memory[i]);
            state.forces[i] = if state.memory[i] == loaded {
                end
            } else {
                self.forces_at(i, &state.memory[i], b)?
            };
        }
        Ok(())
    }

    /// Books footpad `i`'s contact `pad` over the step ending at time `t` (s): the normal part of
    /// its work (and a locked footpad's lateral part) into the contact-event account, sliding
    /// friction into the sliding account; its penetration; whether it is in contact
    /// ([`PadContact::update`]); the step was `dt` s long.
    fn book_contact(&self, state: &mut GearState, i: usize, pad: &PadStep, t: f64, dt: f64) {
        let PadStep {
            impulse,
            work,
            depth,
            touching,
        } = *pad;
        let normal_work = work.z;
        let lateral_work = work.x + work.y;
        state.ledger.events += normal_work;
        if self.surfaces[i].locked() {
            state.ledger.events += lateral_work;
        } else {
            state.ledger.sliding -= lateral_work;
        }
        state.max_penetration = state.max_penetration.max(depth);
        let clearance = state.kin[i].footpad.z - self.surfaces[i].plane();
        let pushed = touching && impulse.z > 0.0;
        if let Some(wall) = &mut state.walls[i] {
            wall.update(pushed, state.kin[i].footpad.xy(), clearance);
        }
        let c = &mut state.contacts[i];
        let first = c.first_contact.is_none();
        c.update(pushed, t, dt, clearance);
        if first && c.first_contact.is_some() {
            state.touchdown_xy[i] = state.kin[i].footpad.xy();
        }
    }

    /// The laws' forces on gear `i` at the kinematics `k` with the honeycomb memory `memory`.
    fn forces_at(
        &self,
        i: usize,
        memory: &GearMemory,
        k: &StrutKinematics,
    ) -> Result<StrutForces, Fault> {
        strut_forces(&self.laws, memory, &self.legs[i], self.arrangement, k).map_err(|e| Fault {
            law: Law::BearingFriction,
            leg: Some(i),
            message: e.to_string(),
        })
    }

    /// Evaluates the laws at the current kinematics with the committed memories.
    fn evaluate(&self, state: &mut GearState) -> Result<(), Fault> {
        for i in 0..self.legs.len() {
            state.forces[i] = self.forces_at(i, &state.memory[i], &state.kin[i])?;
        }
        Ok(())
    }

    /// Evaluates the loads applied over the coming step at time `t` (s) with the vehicle in
    /// state `v`: the engine and RCS loads on the vehicle, committing the nozzle crush there,
    /// each obstacle wall's force on its footpad (`crate::wall`), and the curbs' force on each
    /// footpad that has touched down (eqs. 91-95), committing the footpad crush there (the
    /// footpad's velocity at BP `pad_velocity(i)`, m/s, inertial).
    /// Each is evaluated with the memory of the state before and committed after, as the core
    /// does at an accepted state.
    fn evaluate_applied(
        &self,
        state: &mut GearState,
        t: f64,
        v: &BodyMotion,
        pad_velocity: impl Fn(usize) -> Vector3<f64>,
    ) -> Result<(), Fault> {
        let contacts = &state.contacts;
        let first_contact = || {
            contacts
                .iter()
                .filter_map(|c| c.first_contact)
                .reduce(f64::min)
        };
        state.applied.evaluate(t, v, first_contact)?;
        for (i, wall) in state.walls.iter().enumerate() {
            state.pad_velocity[i] = pad_velocity(i);
            if let Some(w) = wall {
                state.wall_forces[i] = w.force(state.kin[i].footpad.xy(), &state.pad_velocity[i]);
            }
        }
        let Some(curbs) = &self.curbs else {
            return Ok(());
        };
        state.curb_evaluations += 1;
        for (i, f) in state.curb_forces.iter_mut().enumerate() {
            *f = Vector3::zeros();
            // The curbs stand from the surface up (their height is not modelled): they act on
            // a footpad from its first contact on, bearing or not. (The core applies them in
            // the footpad's sliding equations, eq. 97, while it bears.)
            if state.contacts[i].first_contact.is_none() {
                continue;
            }
            let (td, xy) = (state.touchdown_xy[i], state.kin[i].footpad.xy());
            let memory = &mut state.curb_memory;
            let on_pad = curbs.force(memory, i, td, xy, pad_velocity(i).xy(), self.pad_radius);
            curbs.commit(memory, i, td, xy, self.pad_radius);
            if !on_pad.norm().is_finite() {
                return Err(Fault {
                    law: Law::Curbs,
                    leg: Some(i),
                    message: format!("non-finite curb force {on_pad:?} N"),
                });
            }
            *f = Vector3::new(on_pad.x, on_pad.y, 0.0);
        }
        Ok(())
    }

    /// Books the work of the applied loads over the step from `before` to `after` (`dt` s long)
    /// into the mechanisms account (done on the vehicle and the footpads, so it counts
    /// negative): the engine and RCS loads', and the curbs' on the footpads' displacements (a
    /// crush law's plateau); the thrust's and the RCS's positive work is also booked as energy
    /// put in. The walls' work is the contact's, as a locked footpad's lateral impulses are,
    /// booked as their impulses' on the mean of the footpad's velocities at BP before and after
    /// the step (`pad_velocity(i)` after, m/s, inertial): the stiff spring-damper's work on the
    /// footpad's motion, not its force on a displacement one step late.
    fn book_applied(
        &self,
        state: &mut GearState,
        before: &BodyMotion,
        after: &BodyMotion,
        dt: f64,
        pad_velocity: impl Fn(usize) -> Vector3<f64>,
    ) {
        let applied = state.applied.step_work(before, after, dt);
        state.ledger.mechanisms -= applied.applied;
        state.ledger.driving_input += applied.driving.max(0.0);
        if self.curbs.is_some() {
            let steps = state
                .previous
                .iter()
                .zip(&state.kin)
                .zip(&state.curb_forces);
            let work: f64 = steps
                .map(|((a, b), f)| f.dot(&(b.footpad - a.footpad)))
                .sum();
            state.ledger.mechanisms -= work;
        }
        if self.walls {
            let pads = state
                .wall_forces
                .iter()
                .zip(&state.pad_velocity)
                .enumerate();
            let work: f64 = pads
                .map(|(i, (f, v))| f.dot(&(0.5 * (v + pad_velocity(i)) * dt)))
                .sum();
            state.ledger.events += work;
        }
    }

    /// The divergence checks after a step: the run budget (`integrator.max_steps`) spent after
    /// `steps` accepted steps,
    /// the first non-finite force or gear geometry, a non-finite body state (`state_finite`
    /// false, as the engine reads its bodies), or an energy balance `e` (this landing's report)
    /// beyond `integrator.energy_tolerance` of the energy scale.
    fn check(
        &self,
        state: &GearState,
        e: &EnergyReport,
        state_finite: bool,
        steps: u64,
    ) -> Result<(), Fault> {
        // One force evaluation a step.
        touchdown_record::check_budget(steps, steps, self.max_steps).map_err(|budget| Fault {
            law: Law::RunBudget,
            leg: None,
            message: budget.to_string(),
        })?;
        for (i, (k, f)) in state.kin.iter().zip(&state.forces).enumerate() {
            let geometry = k.c + k.s[0] + k.s[1] + k.footpad.norm() + k.axis.norm();
            let bad = f
                .non_finite()
                .or_else(|| (!geometry.is_finite()).then_some((Law::GearGeometry, geometry)));
            if let Some((law, value)) = bad {
                return Err(Fault {
                    law,
                    leg: Some(i),
                    message: format!("non-finite value {value}"),
                });
            }
        }
        if !state_finite {
            return Err(Fault {
                law: Law::EquationsOfMotion,
                leg: None,
                message: "non-finite body state".into(),
            });
        }
        state
            .ledger
            .check_balance(
                e,
                self.energy_tolerance,
                self.energy_floor_j,
                "time step too large for the stiffest strut law, or contact too soft?",
            )
            .map_err(|imbalance| Fault {
                law: Law::EnergyBalance,
                leg: None,
                message: format!("{imbalance}; {}", self.stiffest_strut_law(state)),
            })
    }

    /// The stiffest strut law engaged at the current state, with its leg, strut, branch, rate,
    /// force and stroke (a diagnostic's text, [`StrutLoad::stiffest`]).
    fn stiffest_strut_law(&self, state: &GearState) -> String {
        let loads = (state.kin.iter().zip(&state.forces).zip(&state.memory))
            .enumerate()
            .flat_map(|(i, ((k, f), m))| {
                self.laws
                    .strut_loads(i, m, (k.c, f.axial()), (k.s, f.secondary()))
            });
        StrutLoad::stiffest(loads)
    }

    /// Updates the stability criteria at time `t` (s) with the vehicle in state `v`, its
    /// velocity before the step `old_velocity` (m/s; `None` at touchdown) and the energy report
    /// of this state `energy` (the one [`GearModel::check`] was given).
    fn update_stability(
        state: &mut GearState,
        t: f64,
        v: &BodyMotion,
        old_velocity: Option<&Vector3<f64>>,
        energy: &EnergyReport,
    ) {
        for i in 0..state.pad_views.len() {
            state.pad_views[i] = PadView {
                position: state.kin[i].footpad,
                in_contact: state.contacts[i].in_contact,
                touched: state.contacts[i].first_contact.is_some(),
            };
        }
        state.stability.update(
            t,
            &v.position,
            &v.velocity,
            old_velocity,
            energy,
            &state.pad_views,
        );
    }

    /// Updates the extremes with the current strokes, strut forces and the pitch rate at time
    /// `t`, s.
    fn update_extremes(state: &mut GearState, t: f64, v: &BodyMotion) {
        for (i, (k, f)) in state.kin.iter().zip(&state.forces).enumerate() {
            state
                .extremes
                .update_leg(t, i, k.c, k.s, f.primary(k.c_dot), f.secondary());
        }
        state.extremes.update_pitch_rate(t, v.pitch_rate());
    }

    /// The energy report of `state` with the bodies' energies `bodies`.
    pub fn energy(&self, state: &GearState, bodies: &BodyEnergy) -> EnergyReport {
        state.ledger.report(
            state.stability.initial_kinetic_energy(),
            bodies.kinetic_j,
            bodies.potential_change_j,
            bodies.gear_j,
            self.stored_energy(state),
        )
    }

    /// Elastic energy stored in the gear's honeycombs at the current strokes, J.
    fn stored_energy(&self, state: &GearState) -> f64 {
        state
            .kin
            .iter()
            .zip(&state.memory)
            .map(|(k, m)| self.laws.stored_energy(k.c, k.s, m))
            .sum()
    }

    /// The summary of `engine`'s run on scenario `name` in `state` at time `t` (s) after `steps`
    /// steps, with the engine's `settings` (the deepest footpad penetration added) and the energy
    /// report `energy`.
    #[allow(clippy::too_many_arguments)]
    pub fn summary(
        &self,
        state: &GearState,
        engine: &str,
        name: &str,
        mut settings: serde_json::Map<String, serde_json::Value>,
        t: f64,
        steps: u64,
        energy: EnergyReport,
    ) -> Summary {
        settings.insert(
            "max_footpad_penetration_m".into(),
            state.max_penetration.into(),
        );
        let progress = Progress {
            t,
            steps,
            force_evaluations: steps,
            first_contact_s: state.contacts.iter().map(|c| c.first_contact).collect(),
        };
        let mut summary = Summary::new(
            engine,
            name,
            settings,
            progress,
            &state.stability,
            &state.extremes,
            energy,
        );
        let curbs = self
            .curbs
            .is_some()
            .then_some((Mechanism::Curbs, state.curb_evaluations));
        summary.mechanisms = (state.applied)
            .evaluations()
            .chain(curbs)
            .map(|(m, n)| (m.name().to_string(), n))
            .collect();
        summary
    }

    /// Writes `state` at time `t` (s), the vehicle in state `v`, into `out` (a sample made for as
    /// many legs), with the energy report `energy`.
    pub fn sample(
        &self,
        state: &GearState,
        out: &mut Sample,
        t: f64,
        v: &BodyMotion,
        energy: EnergyReport,
    ) {
        let r = v.rotation;
        out.t = t;
        out.position = v.position;
        out.velocity = v.velocity;
        out.theta = touchdown_frames::euler_from_t_bi(&r);
        out.omega = r.transpose() * v.angular_velocity;
        out.pitch_rate = v.pitch_rate();
        for (i, slot) in out.legs.iter_mut().enumerate() {
            let (k, f, c) = (&state.kin[i], &state.forces[i], &state.contacts[i]);
            slot.primary_stroke = k.c;
            slot.primary_force = f.primary(k.c_dot);
            slot.secondary_stroke = k.s;
            slot.secondary_force = f.secondary();
            slot.stop_force = self.laws.stop_forces(k.c, k.s, &state.memory[i]);
            slot.pad_position = k.footpad;
            slot.restraint_force = state.wall_forces[i].norm();
            slot.contact = match (c.in_contact, c.first_contact) {
                (true, _) => 1,
                (false, Some(_)) => 2,
                (false, None) => 0,
            };
        }
        out.stability_distance
            .copy_from_slice(state.stability.distances());
        out.energy = energy;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const DT: f64 = 2.0e-5;

    /// Steps `contact` from `t0` (s) for `n` steps of `DT` with the same `pushed` and
    /// `clearance` (m); returns the time reached.
    fn steps(contact: &mut PadContact, t0: f64, n: usize, pushed: bool, clearance: f64) -> f64 {
        let mut t = t0;
        for _ in 0..n {
            t += DT;
            contact.update(pushed, t, DT, clearance);
        }
        t
    }

    #[test]
    fn a_rebound_between_steps_keeps_the_footpad_in_contact() {
        let mut c = PadContact::default();
        let mut t = 0.0;
        for _ in 0..100 {
            t = steps(&mut c, t, 1, true, 0.0);
            t = steps(&mut c, t, 1, false, 5.0e-5);
            assert!(c.in_contact);
        }
        assert_eq!(c.first_contact, Some(DT));
    }

    #[test]
    fn a_footpad_lifted_clear_leaves_after_the_hold() {
        let mut c = PadContact::default();
        let t = steps(&mut c, 0.0, 10, true, 0.0);
        // Lifted 2 mm: in contact through the hold, out after it.
        let hold = (CONTACT_HOLD_S / DT).round() as usize;
        let t = steps(&mut c, t, hold - 1, false, 2.0e-3);
        assert!(c.in_contact);
        steps(&mut c, t, 1, false, 2.0e-3);
        assert!(!c.in_contact);
    }

    #[test]
    fn a_footpad_hovering_within_the_clearance_stays_in_contact() {
        let mut c = PadContact::default();
        let t = steps(&mut c, 0.0, 10, true, 0.0);
        steps(&mut c, t, 1000, false, 0.5 * CONTACT_CLEARANCE_M);
        assert!(c.in_contact);
    }

    #[test]
    fn a_footpad_that_never_pushed_is_not_in_contact() {
        let mut c = PadContact::default();
        steps(&mut c, 0.0, 10, false, 0.0);
        assert!(!c.in_contact);
        assert_eq!(c.first_contact, None);
    }
}
