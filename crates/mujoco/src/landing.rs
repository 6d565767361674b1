//! One landing on the MuJoCo model, driven by the shared strut laws.
//!
//! The Python runner owns MuJoCo's `MjModel`/`MjData`; the step loop (the C ABI's
//! `touchdown_mujoco_run`) calls [`MujocoLanding::advance`] between `mj_step1` and `mj_step2`
//! of every step, handing over MuJoCo's own arrays
//! ([`MjArrays`]) located by the element names of the export ([`GearIndex`]). At state n:
//! 1. read the vehicle's state, every gear's strokes and rates (stroke joint, secondary tendons,
//!    sites) and the footpads' velocities (sensors);
//! 2. book the step n−1 → n: the work of the forces applied over it on the stroke increments
//!    (`StrutForces::work`), the work of the contact forces MuJoCo applied (contact sensors) on
//!    the mean of the contact point's velocities; commit the honeycomb memories at state n;
//! 3. evaluate the laws at state n with the committed memories, check for divergence, update the
//!    stability criteria, the extremes and the history;
//! 4. unless the run has ended, write the forces for the step n → n+1: the engine and RCS loads
//!    on the vehicle (`qfrc_applied`, if the scene has them), the curbs' and obstacle walls'
//!    force on the footpads (`xfrc_applied`, if the scene has either), the explicit primary
//!    force (the honeycomb's whole law, crush plateau included, as the core applies it, and the
//!    viscous force) and the secondary tendon forces into `ctrl` (overwritten every step), and
//!    the stroke joint's dry-friction bound, the bearing bound. The step loop puts
//!    that bound into the joint's friction row of this step (`efc_frictionloss`): MuJoCo builds
//!    its constraint rows in `mj_step1`, from the model's `dof_frictionloss`, so a bound written
//!    into the model here would act one step late (docs/engines.md, "The MuJoCo engine").

use crate::MujocoError;
use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3};
use touchdown_multibody::{
    BodyEnergy, BodyMotion, Fault, GearModel, GearState, MujocoSettings, PadStep, Reading,
    StepTaken, StrutKinematics,
};
use touchdown_record::{EnergyReport, History, Law, Sample, Summary};
use touchdown_scenario::schema::Engine;
use touchdown_scenario::{Scenario, ScenarioError};

/// Where one gear's quantities are in MuJoCo's arrays: ids and addresses the runner resolves
/// from the export's element names (`legN_*`). `repr(C)`: 15 `i32` in this order.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct GearIndex {
    /// `qpos` address of the stroke joint `legN_stroke`.
    pub stroke_qpos: i32,
    /// `qvel` (dof) address of the stroke joint.
    pub stroke_dof: i32,
    /// Tendon ids of `legN_s31`, `legN_s41`.
    pub tendon: [i32; 2],
    /// Actuator id of `legN_primary`.
    pub primary: i32,
    /// Actuator ids of `legN_s31`, `legN_s41`.
    pub secondary: [i32; 2],
    /// Site ids of the secondary trunnions `legN_b3`, `legN_b4`.
    pub trunnion: [i32; 2],
    /// Site id of point 1, `legN_point1`.
    pub point1: i32,
    /// Body id of the outer cylinder `legN_outer` (origin at the trunnion B2).
    pub outer: i32,
    /// Body id of the footpad `legN_footpad` (origin at the ball joint BP).
    pub footpad: i32,
    /// `sensordata` address of `legN_contact` (found, Fx, Fy, Fz).
    pub contact: i32,
    /// `sensordata` address of `legN_pad_velocity` (3).
    pub pad_velocity: i32,
    /// `sensordata` address of `legN_pad_rate` (3).
    pub pad_rate: i32,
}

/// Sizes of the loaded model, to check indices against.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ModelSizes {
    /// Position coordinates.
    pub nq: i32,
    /// Degrees of freedom.
    pub nv: i32,
    /// Actuators.
    pub nu: i32,
    /// Tendons.
    pub ntendon: i32,
    /// Sites.
    pub nsite: i32,
    /// Bodies.
    pub nbody: i32,
    /// Sensor data length.
    pub nsensordata: i32,
}

/// MuJoCo's warnings (`mjtWarning` order), named for a diagnostic.
pub const MUJOCO_WARNINGS: [&str; 7] = [
    "near-singular inertia",
    "contact buffer full",
    "constraint buffer full",
    "bad qpos (MuJoCo resets the state)",
    "bad qvel (MuJoCo resets the state)",
    "bad qacc (MuJoCo resets the state)",
    "bad ctrl",
];

/// MuJoCo's arrays at one call (after `mj_step1`), and the model fields the laws drive.
pub struct MjArrays<'a> {
    /// `qpos` (nq): vehicle position (m) and quaternion (w, x, y, z), then per gear the two
    /// trunnion angles (rad) and the stroke extension q (m).
    pub qpos: &'a [f64],
    /// `qvel` (nv): vehicle velocity (m/s, world) and angular velocity (rad/s, body axes), then
    /// per gear the joint rates.
    pub qvel: &'a [f64],
    /// `ten_length` (ntendon), m.
    pub ten_length: &'a [f64],
    /// `ten_velocity` (ntendon), m/s.
    pub ten_velocity: &'a [f64],
    /// `site_xpos` (nsite × 3), m, world.
    pub site_xpos: &'a [f64],
    /// `xpos` (nbody × 3), m, world.
    pub xpos: &'a [f64],
    /// `sensordata` (nsensordata).
    pub sensordata: &'a [f64],
    /// `energy` (2): potential and kinetic energy of the whole model, J.
    pub energy: &'a [f64],
    /// Number of times each MuJoCo warning has been raised (`MUJOCO_WARNINGS` order).
    pub warnings: &'a [i32],
    /// `ctrl` (nu), written: N.
    pub ctrl: &'a mut [f64],
    /// The stroke joints' dry-friction bounds for the coming step, one per gear in gear order,
    /// written: N (the runner copies them into the joints' friction rows, `efc_frictionloss`).
    pub friction_bound: &'a mut [f64],
    /// `qfrc_applied` (nv), written: the engine and RCS loads on the vehicle's free joint
    /// (force N, world axes; torque N·m, body axes); the gear's entries stay 0.
    pub qfrc_applied: &'a mut [f64],
    /// `xfrc_applied` (nbody × 6), written: the curbs' and obstacle walls' force on each footpad
    /// body at its centre
    /// of mass BP (force N, then torque N·m, world axes); the other bodies' entries stay 0.
    pub xfrc_applied: &'a mut [f64],
}

/// A landing driven on MuJoCo's arrays (see the module documentation).
pub struct MujocoLanding {
    name: String,
    /// The gear as set up: geometry, surfaces, laws, curbs, criteria.
    gear: GearModel,
    /// The gear's memories, kinematics, contacts, ledger, stability and extremes.
    gear_state: GearState,
    /// Each gear's kinematics as read at this state.
    kin: Vec<StrutKinematics>,
    /// Each footpad's contact over the last step.
    pad_steps: Vec<PadStep>,
    index: Vec<GearIndex>,
    sizes: ModelSizes,
    mass: f64,
    inertia: Matrix3<f64>,
    contact_radius: Vec<f64>,
    dt: f64,
    settings: serde_json::Map<String, serde_json::Value>,
    // state
    started: bool,
    t: f64,
    steps: u64,
    vehicle: BodyMotion,
    /// Angular velocity in body axes, rad/s (MuJoCo's free-joint rates).
    omega_body: Vector3<f64>,
    /// Footpad contact-point velocities at this state and before the last step, m/s.
    pad_velocity: Vec<Vector3<f64>>,
    old_pad_velocity: Vec<Vector3<f64>>,
    /// Footpad velocities at BP at this state, m/s.
    footpad_velocity: Vec<Vector3<f64>>,
    /// Vehicle position at touchdown, m.
    position0: Vector3<f64>,
    /// Kinetic plus potential energy of the gear links (MuJoCo's total minus the vehicle's), J.
    gear_energy: f64,
    gear_energy0: f64,
    history: Option<History>,
}

/// Index of a `GearIndex` field against its array length.
fn check(what: &str, leg: usize, id: i32, len: i32) -> Result<usize, MujocoError> {
    if id < 0 || id >= len {
        return Err(MujocoError::Binding(format!(
            "leg {}: {what} = {id} is outside the model's range 0..{len}",
            leg + 1
        )));
    }
    Ok(id as usize)
}

/// The gear book of a MuJoCo landing of `sc`, or why the engine refuses the scenario: not
/// applicable, a mechanism it does not model, laws that do not build, or a time step too large
/// for the stiffest strut law; with the settings it runs with.
fn book_for(sc: &Scenario) -> Result<((GearModel, GearState), MujocoSettings), ScenarioError> {
    sc.require_engine(Engine::Mujoco, crate::unsupported)?;
    let settings = MujocoSettings::new(sc)?;
    Ok((GearModel::new(sc, settings.timestep, 1)?, settings))
}

/// Refuses `sc` as a MuJoCo landing would, in this process: the command line asks before it
/// starts the Python runner, so that a refusal comes back as the scenario's error (the file and
/// the field), not as the runner's words.
pub fn refusal(sc: &Scenario) -> Result<(), ScenarioError> {
    book_for(sc).map(|_| ())
}

impl MujocoLanding {
    /// A landing of `sc` on the model exported from it (`mjcf::export`), whose arrays the
    /// runner located with `index` (one entry per gear) in a model of `sizes`; MuJoCo's version
    /// is recorded in the summary; with `history`, one row per step goes into that file.
    pub fn new(
        sc: &Scenario,
        index: Vec<GearIndex>,
        sizes: ModelSizes,
        mujoco_version: &str,
        history: Option<History>,
    ) -> Result<MujocoLanding, MujocoError> {
        let ((gear, gear_state), mj) = book_for(sc)?;
        let n = sc.legs.len();
        if index.len() != n {
            return Err(MujocoError::Binding(format!(
                "{} gear indices for a scenario with {n} legs",
                index.len()
            )));
        }
        let expected = (7 + 3 * n as i32, 6 + 3 * n as i32, 3 * n as i32);
        if (sizes.nq, sizes.nv, sizes.nu) != expected {
            return Err(MujocoError::Binding(format!(
                "model sizes nq, nv, nu = {}, {}, {}; expected {}, {}, {} for {n} legs (was the model exported from this scenario?)",
                sizes.nq, sizes.nv, sizes.nu, expected.0, expected.1, expected.2
            )));
        }
        for (i, g) in index.iter().enumerate() {
            check("stroke_qpos", i, g.stroke_qpos, sizes.nq)?;
            check("stroke_dof", i, g.stroke_dof, sizes.nv)?;
            for j in 0..2 {
                check("tendon", i, g.tendon[j], sizes.ntendon)?;
                check("secondary actuator", i, g.secondary[j], sizes.nu)?;
                check("trunnion site", i, g.trunnion[j], sizes.nsite)?;
            }
            check("primary actuator", i, g.primary, sizes.nu)?;
            check("point1 site", i, g.point1, sizes.nsite)?;
            check("outer body", i, g.outer, sizes.nbody)?;
            check("footpad body", i, g.footpad, sizes.nbody)?;
            check("contact sensor", i, g.contact + 3, sizes.nsensordata)?;
            check("velocity sensor", i, g.pad_velocity + 2, sizes.nsensordata)?;
            check("rate sensor", i, g.pad_rate + 2, sizes.nsensordata)?;
        }
        Ok(MujocoLanding {
            name: sc.file.name.clone(),
            gear,
            gear_state,
            kin: vec![StrutKinematics::default(); n],
            pad_steps: vec![PadStep::default(); n],
            index,
            sizes,
            mass: sc.vehicle.mass,
            inertia: sc.vehicle.inertia,
            contact_radius: sc.legs.iter().map(|l| sc.links.contact_radius(l)).collect(),
            dt: mj.timestep,
            settings: settings(sc, &mj, mujoco_version),
            started: false,
            t: 0.0,
            steps: 0,
            vehicle: BodyMotion {
                position: Vector3::zeros(),
                rotation: Matrix3::identity(),
                velocity: Vector3::zeros(),
                angular_velocity: Vector3::zeros(),
            },
            omega_body: Vector3::zeros(),
            pad_velocity: vec![Vector3::zeros(); n],
            old_pad_velocity: vec![Vector3::zeros(); n],
            footpad_velocity: vec![Vector3::zeros(); n],
            position0: Vector3::zeros(),
            gear_energy: 0.0,
            gear_energy0: 0.0,
            history,
        })
    }

    /// The model sizes the landing was bound to.
    pub fn sizes(&self) -> ModelSizes {
        self.sizes
    }

    /// The number of gears (legs).
    pub fn legs(&self) -> usize {
        self.index.len()
    }

    /// Current time, s.
    pub fn time(&self) -> f64 {
        self.t
    }

    /// Whether the run has ended (an unstable decision, if the scenario terminates on one, or
    /// the end time).
    pub fn finished(&self) -> bool {
        self.gear.finished(&self.gear_state, self.t)
    }

    /// One call per step, between `mj_step1` and `mj_step2` (module documentation). Returns
    /// whether the run has ended (then nothing is written and the runner stops stepping).
    pub fn advance(&mut self, mj: &mut MjArrays) -> Result<bool, MujocoError> {
        self.check_warnings(mj)?;
        let before = self.vehicle;
        self.read_state(mj);
        let first = !self.started;
        if first {
            self.started = true;
            self.position0 = self.vehicle.position;
            self.gear_energy0 = self.gear_energy;
        } else {
            self.t += self.dt;
            self.steps += 1;
            self.book_contacts(mj);
        }
        let vehicle = self.vehicle;
        let now = self.reading(&vehicle);
        let pads = &self.footpad_velocity;
        let booked = if first {
            (self.gear).start_landing(&mut self.gear_state, &self.kin, &now, |i| pads[i])
        } else {
            let step = StepTaken {
                before: &before,
                dt: self.dt,
                kinematics: &self.kin,
                pads: &self.pad_steps,
            };
            (self.gear).finish_step(&mut self.gear_state, &step, &now, |i| pads[i])
        };
        booked.map_err(|f| self.diverged(f))?;
        self.record();
        self.old_pad_velocity.copy_from_slice(&self.pad_velocity);
        if self.finished() {
            return Ok(true);
        }
        self.apply(mj);
        Ok(false)
    }

    fn check_warnings(&self, mj: &MjArrays) -> Result<(), MujocoError> {
        match mj
            .warnings
            .iter()
            .zip(MUJOCO_WARNINGS)
            .find(|(n, _)| **n > 0)
        {
            Some((n, what)) => Err(self.diverged(Fault {
                law: Law::Solver,
                leg: None,
                message: format!("MuJoCo warned: {what} ({n} times); the step is not trustworthy"),
            })),
            None => Ok(()),
        }
    }

    fn read_state(&mut self, mj: &MjArrays) {
        let q = mj.qpos;
        let v = mj.qvel;
        let quat = UnitQuaternion::from_quaternion(Quaternion::new(q[3], q[4], q[5], q[6]));
        let rotation = quat.to_rotation_matrix().into_inner();
        self.omega_body = Vector3::new(v[3], v[4], v[5]);
        self.vehicle = BodyMotion {
            position: Vector3::new(q[0], q[1], q[2]),
            rotation,
            velocity: Vector3::new(v[0], v[1], v[2]),
            angular_velocity: rotation * self.omega_body,
        };
        let point = |a: &[f64], id: i32| {
            let k = 3 * id as usize;
            Vector3::new(a[k], a[k + 1], a[k + 2])
        };
        let sensor = |adr: i32| point(&mj.sensordata[adr as usize..], 0);
        for (i, (g, leg)) in self.index.iter().zip(self.gear.legs()).enumerate() {
            let b2 = point(mj.xpos, g.outer);
            let footpad = point(mj.xpos, g.footpad);
            let point1 = point(mj.site_xpos, g.point1);
            let mut k = StrutKinematics {
                c: -q[g.stroke_qpos as usize],
                c_dot: -v[g.stroke_dof as usize],
                point1,
                axis: (footpad - b2).normalize(),
                footpad,
                ..Default::default()
            };
            for (j, l0) in [leg.l31, leg.l41].into_iter().enumerate() {
                let trunnion = point(mj.site_xpos, g.trunnion[j]);
                let t = g.tendon[j] as usize;
                k.trunnion[j] = trunnion;
                k.u[j] = (point1 - trunnion).normalize();
                k.s[j] = mj.ten_length[t] - l0;
                k.s_dot[j] = mj.ten_velocity[t];
            }
            self.kin[i] = k;
            // The contact point: the bottom of the footpad's contact sphere.
            let r = Vector3::new(0.0, 0.0, -self.contact_radius[i]);
            self.footpad_velocity[i] = sensor(g.pad_velocity);
            self.pad_velocity[i] = self.footpad_velocity[i] + sensor(g.pad_rate).cross(&r);
        }
        let total = mj.energy[0] + mj.energy[1];
        self.gear_energy = total - self.kinetic_energy()
            + self.mass * self.gear.gravity().dot(&self.vehicle.position);
    }

    /// Contact states, penetration and the work of the contact forces over the last step:
    /// normal forces (and locked footpads' lateral forces) into the contact-event account,
    /// sliding friction into the sliding account, each on the mean of the contact point's
    /// velocities before and after the step.
    fn book_contacts(&mut self, mj: &MjArrays) {
        for (i, g) in self.index.iter().enumerate() {
            let adr = g.contact as usize;
            let found = mj.sensordata[adr];
            let force = Vector3::new(
                mj.sensordata[adr + 1],
                mj.sensordata[adr + 2],
                mj.sensordata[adr + 3],
            );
            let impulse = force * self.dt;
            let v_mean = 0.5 * (self.old_pad_velocity[i] + self.pad_velocity[i]);
            // The contact sphere is centred on BP; its plane is lowered by its radius.
            let depth = self.gear.surface(i).plane() - self.kin[i].footpad.z;
            self.pad_steps[i] = PadStep {
                impulse,
                work: impulse.component_mul(&v_mean),
                depth,
                touching: found > 0.0,
            };
        }
    }

    /// Writes the forces for the coming step (overwriting the last step's).
    fn apply(&self, mj: &mut MjArrays) {
        for (i, g) in self.index.iter().enumerate() {
            let f = self.gear_state.forces(i);
            // A compression-positive strut force pushes the footpad away: it extends q. The crush
            // plateau is a force here, not a bound: a friction row holds a stroke both ways
            // (docs/engines.md, "Model" of the MuJoCo engine).
            mj.ctrl[g.primary as usize] = f.axial();
            // A tension pulls the tendon shorter.
            for (j, force) in f.secondary().into_iter().enumerate() {
                mj.ctrl[g.secondary[j] as usize] = -force;
            }
            mj.friction_bound[i] = f.bearing_bound;
        }
        if !self.gear_state.applied().is_empty() {
            // eqs. (72)-(74), (80)-(82): the free joint's generalized forces are the force in
            // world axes and the torque in body axes.
            let a = self.gear_state.applied();
            let torque = self.vehicle.rotation.transpose() * a.torque;
            mj.qfrc_applied[..3].copy_from_slice(a.force.as_slice());
            mj.qfrc_applied[3..6].copy_from_slice(torque.as_slice());
        }
        if self.gear.loads_footpads() {
            // eqs. (94)-(95) and the obstacle walls: the force on each footpad body, at BP (its
            // centre of mass).
            for (i, g) in self.index.iter().enumerate() {
                let k = 6 * g.footpad as usize;
                let force = self.gear_state.pad_force(i);
                mj.xfrc_applied[k..k + 3].copy_from_slice(force.as_slice());
            }
        }
    }

    /// Vehicle kinetic energy ½MV² + ½ωᵀJω, J.
    pub fn kinetic_energy(&self) -> f64 {
        let w = &self.omega_body;
        0.5 * self.mass * self.vehicle.velocity.norm_squared() + 0.5 * w.dot(&(self.inertia * w))
    }

    /// Energy report at the current state.
    pub fn energy(&self) -> EnergyReport {
        self.gear.energy(&self.gear_state, &self.energies())
    }

    /// The summary at the current state.
    pub fn summary(&self) -> Summary {
        self.gear.summary(
            &self.gear_state,
            "mujoco",
            &self.name,
            self.settings.clone(),
            self.t,
            self.steps,
            self.energy(),
        )
    }

    /// Flushes the history file, if any (reporting a write error met while running).
    pub fn finish_history(&mut self) -> std::io::Result<()> {
        match self.history.take() {
            Some(h) => h.finish(),
            None => Ok(()),
        }
    }

    /// Writes the current state into `out` (a sample made for as many legs).
    pub fn sample(&self, out: &mut Sample) {
        (self.gear).sample(&self.gear_state, out, self.t, &self.vehicle, self.energy());
    }

    fn record(&mut self) {
        if let Some(mut h) = self.history.take() {
            self.sample(h.sample_mut());
            h.write();
            self.history = Some(h);
        }
    }

    /// The diagnostic of an error MuJoCo raised in its own step (`mju_error`, `what` in its
    /// words, its lines joined into one): the landing stops in the engine's solver, at the
    /// state the last step booked.
    pub fn engine_error(&self, what: &str) -> touchdown_record::Divergence {
        let what = what
            .lines()
            .map(str::trim)
            .filter(|l| !l.is_empty())
            .collect::<Vec<_>>()
            .join("; ");
        Fault {
            law: Law::Solver,
            leg: None,
            message: format!("MuJoCo stopped with an error in its step: {what}"),
        }
        .at(self.t, &self.vehicle)
    }

    fn diverged(&self, fault: Fault) -> MujocoError {
        MujocoError::Diverged(Box::new(fault.at(self.t, &self.vehicle)))
    }

    /// The bodies' energies now.
    fn energies(&self) -> BodyEnergy {
        BodyEnergy {
            kinetic_j: self.kinetic_energy(),
            potential_change_j: -self.mass
                * self
                    .gear
                    .gravity()
                    .dot(&(self.vehicle.position - self.position0)),
            gear_j: self.gear_energy - self.gear_energy0,
        }
    }

    /// What the book reads of the bodies now, the vehicle in state `vehicle` (as read).
    fn reading<'a>(&self, vehicle: &'a BodyMotion) -> Reading<'a> {
        Reading {
            t: self.t,
            vehicle,
            finite: vehicle.is_finite() && self.gear_energy.is_finite(),
            energy: self.energies(),
            steps: self.steps,
        }
    }
}

/// The engine's settings as used, for the summary (names carry their units).
fn settings(
    sc: &Scenario,
    mj: &MujocoSettings,
    mujoco_version: &str,
) -> serde_json::Map<String, serde_json::Value> {
    let l = &sc.links;
    let leg = &sc.legs[0];
    let mut m = serde_json::Map::new();
    m.insert("mujoco".into(), mujoco_version.into());
    m.insert("generator".into(), crate::mjcf::GENERATOR.into());
    m.insert("timestep_s".into(), mj.timestep.into());
    m.insert("integrator".into(), "implicitfast".into());
    m.insert("contact_timeconst_s".into(), mj.contact_timeconst.into());
    m.insert(
        "contact_damping_ratio".into(),
        mj.contact_damping_ratio.into(),
    );
    m.insert("contact_width_m".into(), mj.contact_width.into());
    m.insert(
        "secondary_struts".into(),
        "massless two-force members (spatial tendons)".into(),
    );
    for (name, value) in touchdown_multibody::CONTACT_FLAG_SETTINGS {
        m.insert(name.into(), value.into());
    }
    m.insert(
        "outer_cylinder_mass_kg".into(),
        (l.outer_cylinder_mass_ratio * sc.footpad.mass).into(),
    );
    m.insert(
        "outer_cylinder_length_m".into(),
        l.outer_cylinder_length(leg, &sc.primary, sc.arrangement)
            .into(),
    );
    m.insert("footpad_body_mass_kg".into(), sc.footpad.mass.into());
    m.insert("link_radius_m".into(), l.radius(leg).into());
    m.insert("contact_radius_m".into(), l.contact_radius(leg).into());
    m
}
