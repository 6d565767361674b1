//! One landing on the rapier multibody: fixed steps, the strut laws applied before each step,
//! hysteresis committed after it, an energy ledger, the shared stability criteria and
//! divergence checks.
//!
//! Step:
//! 1. read every gear's strokes and rates, evaluate the laws with the committed memories, apply
//!    the explicit forces and set the motor and friction bounds (`struts`);
//! 2. let rapier step (contacts, joints, motors and dry friction are solved implicitly);
//! 3. book the work of each law over the step (explicit forces and bounds × the stroke
//!    increments), the work of the contact impulses, commit the honeycomb memories at the new
//!    strokes, update the stability criteria and the extremes, and check for divergence.

use crate::assembly::{
    self, body_state, to_na, Assembly, BodyState, Inertia, LinkMasses, LOCK_FRICTION,
};
use crate::struts;
use crate::RapierError;
use nalgebra::Vector3;
use rapier3d_f64::prelude::*;
use touchdown_laws::multibody::{
    check_explicit_timestep, strut_forces, StrutForces, StrutKinematics,
};
use touchdown_laws::{GearLaws, GearMemory};
use touchdown_record::{
    Divergence, EnergyLedger, EnergyReport, Extremes, PadView, Progress, Sample, StabilityTracker,
    Summary,
};
use touchdown_scenario::frames;
use touchdown_scenario::model::{Leg, PadSurface};
use touchdown_scenario::Scenario;

/// Something that watches a landing after every step (and at t = 0).
pub trait Observer {
    /// Called with the simulation after a step.
    fn observe(&mut self, sim: &RapierSimulation);
}

impl Observer for () {
    fn observe(&mut self, _: &RapierSimulation) {}
}

/// Contact state of one footpad.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct PadContact {
    in_contact: bool,
    first_contact: Option<f64>,
}

/// A landing simulated on the rapier multibody.
pub struct RapierSimulation {
    name: String,
    assembly: Assembly,
    legs: Vec<Leg>,
    surfaces: Vec<PadSurface>,
    laws: GearLaws,
    /// Vehicle, then per gear outer link and footpad: handle, mass and inertia.
    bodies: Vec<(RigidBodyHandle, Inertia)>,
    gravity: Vector3<f64>,
    t_end: f64,
    energy_tolerance: f64,
    settings: serde_json::Map<String, serde_json::Value>,
    // state
    t: f64,
    steps: u64,
    memory: Vec<GearMemory>,
    kin: Vec<StrutKinematics>,
    /// Kinematics before the current step (reused every step).
    previous: Vec<StrutKinematics>,
    /// Footpad contact-point velocities before the current step, m/s (reused every step).
    pad_velocity: Vec<Vector3<f64>>,
    forces: Vec<StrutForces>,
    contacts: Vec<PadContact>,
    ledger: EnergyLedger,
    /// Vehicle and link positions at touchdown (for potential energies).
    position0: Vec<Vector3<f64>>,
    /// Kinetic energy of the gear links at touchdown, J.
    links_kinetic0: f64,
    max_penetration: f64,
    stability: StabilityTracker,
    extremes: Extremes,
    pad_views: Vec<PadView>,
}

impl RapierSimulation {
    /// Builds the multibody of a scenario at its touchdown state.
    pub fn new(scenario: &Scenario) -> Result<RapierSimulation, RapierError> {
        let laws = GearLaws::from_scenario(scenario)?;
        let assembly = assembly::build(scenario)?;
        check_timestep(scenario, &laws)?;
        let n = scenario.legs.len();
        let gravity = frames::gravity_inertial(scenario.vehicle.gravity, scenario.surface.slope);
        let settings = settings(scenario, &assembly.masses);
        let mut sim = RapierSimulation {
            name: scenario.file.name.clone(),
            legs: scenario.legs.clone(),
            surfaces: scenario.surface.pads.clone(),
            laws,
            bodies: std::iter::once((
                assembly.vehicle,
                Inertia {
                    mass: scenario.vehicle.mass,
                    tensor: scenario.vehicle.inertia,
                },
            ))
            .chain(
                assembly
                    .gears
                    .iter()
                    .flat_map(|g| [(g.outer, g.outer_inertia), (g.footpad, g.footpad_inertia)]),
            )
            .collect(),
            gravity,
            t_end: scenario.integrator.t_end,
            energy_tolerance: scenario.integrator.energy_tolerance,
            settings,
            t: 0.0,
            steps: 0,
            memory: vec![GearMemory::default(); n],
            kin: vec![StrutKinematics::default(); n],
            previous: vec![StrutKinematics::default(); n],
            pad_velocity: vec![Vector3::zeros(); n],
            forces: vec![StrutForces::default(); n],
            contacts: vec![PadContact::default(); n],
            ledger: EnergyLedger::default(),
            position0: Vec::new(),
            links_kinetic0: 0.0,
            max_penetration: 0.0,
            stability: StabilityTracker::new(&scenario.stability, gravity, n, 0.0),
            extremes: Extremes::new(n),
            pad_views: vec![PadView::default(); n],
            assembly,
        };
        sim.position0 = sim.body_positions();
        sim.links_kinetic0 = sim.gear_energy();
        sim.stability =
            StabilityTracker::new(&scenario.stability, gravity, n, sim.kinetic_energy());
        sim.read_kinematics();
        sim.evaluate()?;
        sim.update_stability(None);
        Ok(sim)
    }

    /// Runs to a decision (if the scenario terminates on one) or to the end time.
    pub fn run(&mut self, observer: &mut impl Observer) -> Result<Summary, RapierError> {
        observer.observe(self);
        while !self.finished() {
            self.step()?;
            observer.observe(self);
        }
        Ok(self.summary())
    }

    /// Whether the run has ended.
    pub fn finished(&self) -> bool {
        self.t >= self.t_end * (1.0 - 1e-12) || self.stability.terminates()
    }

    /// Current time, s.
    pub fn time(&self) -> f64 {
        self.t
    }

    /// The masses the rebuild adds to the report's model.
    pub fn link_masses(&self) -> LinkMasses {
        self.assembly.masses
    }

    /// Deepest footpad penetration into its plane so far, m.
    pub fn max_penetration(&self) -> f64 {
        self.max_penetration
    }

    fn state(&self, body: RigidBodyHandle) -> BodyState {
        body_state(&self.assembly.world, body)
    }

    fn body_positions(&self) -> Vec<Vector3<f64>> {
        self.bodies
            .iter()
            .map(|(h, _)| self.state(*h).point(&Vector3::zeros()))
            .collect()
    }

    fn vehicle(&self) -> BodyState {
        self.state(self.assembly.vehicle)
    }

    /// Vehicle kinetic energy ½MV² + ½ωᵀJω, J.
    pub fn kinetic_energy(&self) -> f64 {
        self.bodies[0].1.kinetic_energy(&self.vehicle())
    }

    /// Kinetic energy plus potential energy of body `i` relative to touchdown position, J.
    fn body_energy(&self, i: usize) -> f64 {
        let (h, inertia) = &self.bodies[i];
        let s = self.state(*h);
        inertia.kinetic_energy(&s)
            - inertia.mass
                * self
                    .gravity
                    .dot(&(s.point(&Vector3::zeros()) - self.position0[i]))
    }

    /// Kinetic energy plus potential-energy change of the gear links since touchdown, J.
    fn gear_energy(&self) -> f64 {
        (1..self.bodies.len())
            .map(|i| self.body_energy(i))
            .sum::<f64>()
            - self.links_kinetic0
    }

    /// Energy report at the current state.
    pub fn energy(&self) -> EnergyReport {
        let stored: f64 = self
            .kin
            .iter()
            .zip(&self.memory)
            .map(|(k, m)| self.laws.stored_energy(k.c, k.s, m))
            .sum();
        let kinetic = self.kinetic_energy();
        self.ledger.report(
            self.stability.initial_kinetic_energy(),
            kinetic,
            self.body_energy(0) - kinetic,
            self.gear_energy(),
            stored,
        )
    }

    /// The summary at the current state.
    pub fn summary(&self) -> Summary {
        let mut settings = self.settings.clone();
        settings.insert(
            "max_footpad_penetration_m".into(),
            self.max_penetration.into(),
        );
        let progress = Progress {
            t: self.t,
            steps: self.steps,
            force_evaluations: self.steps,
            first_contact_s: self.contacts.iter().map(|c| c.first_contact).collect(),
        };
        Summary::new(
            "rapier",
            &self.name,
            settings,
            progress,
            &self.stability,
            &self.extremes,
            self.energy(),
        )
    }

    /// Writes the current state into `out` (a sample made for as many legs).
    pub fn sample(&self, out: &mut Sample) {
        let v = self.vehicle();
        let r = v.rotation();
        let w = v.angvel;
        out.t = self.t;
        out.position = v.point(&Vector3::zeros());
        out.velocity = v.linvel;
        out.theta = frames::euler_from_t_bi(&r);
        out.omega = r.transpose() * w;
        out.pitch_rate = w.x;
        for (i, slot) in out.legs.iter_mut().enumerate() {
            let (k, f, c) = (&self.kin[i], &self.forces[i], &self.contacts[i]);
            slot.primary_stroke = k.c;
            slot.primary_force = f.primary(k.c_dot);
            slot.secondary_stroke = k.s;
            slot.secondary_force = f.secondary();
            slot.pad_position = k.footpad;
            slot.contact = match (c.in_contact, c.first_contact) {
                (true, _) => 1,
                (false, Some(_)) => 2,
                (false, None) => 0,
            };
        }
        out.stability_distance
            .copy_from_slice(self.stability.distances());
        out.energy = self.energy();
    }

    fn read_kinematics(&mut self) {
        for (i, (g, leg)) in self.assembly.gears.iter().zip(&self.legs).enumerate() {
            self.kin[i] = struts::kinematics(&self.assembly.world, self.assembly.vehicle, g, leg);
        }
    }

    /// Evaluates the laws at the current kinematics (nothing applied yet).
    fn evaluate(&mut self) -> Result<(), RapierError> {
        for i in 0..self.legs.len() {
            self.forces[i] = strut_forces(&self.laws, &self.memory[i], &self.legs[i], &self.kin[i])
                .map_err(|e| self.diverged(e.to_string(), "bearing friction", Some(i)))?;
        }
        Ok(())
    }

    /// One fixed step (see the module documentation).
    pub fn step(&mut self) -> Result<(), RapierError> {
        let dt = self.assembly.world.integration_parameters.dt;
        // User forces and torques persist in rapier until cleared, and are cleared separately.
        for (h, _) in &self.bodies {
            let rb = &mut self.assembly.world.bodies[*h];
            rb.reset_forces(false);
            rb.reset_torques(false);
        }
        for i in 0..self.legs.len() {
            let g = self.assembly.gears[i];
            struts::apply(
                &mut self.assembly.world,
                self.assembly.vehicle,
                &g,
                &self.kin[i],
                &self.forces[i],
            );
        }
        self.previous.copy_from_slice(&self.kin);
        for i in 0..self.legs.len() {
            self.pad_velocity[i] = self.contact_velocity(self.assembly.gears[i].footpad);
        }
        let old_velocity = self.vehicle().linvel;
        self.assembly.world.step();
        self.t += dt;
        self.steps += 1;
        self.read_kinematics();
        let steps = self.previous.iter().zip(&self.kin).zip(&self.forces);
        for (((a, b), f), memory) in steps.zip(&mut self.memory) {
            let w = f.work(a, b);
            self.ledger.honeycomb += w.honeycomb;
            self.ledger.viscous += w.viscous;
            self.ledger.bearing += w.bearing;
            self.laws.commit(b.c, b.s, memory);
        }
        self.book_contacts();
        self.evaluate()?;
        self.check_divergence()?;
        self.update_stability(Some(&old_velocity));
        for (i, k) in self.kin.iter().enumerate() {
            self.extremes.update_leg(i, k.c, k.s);
        }
        let q = self.vehicle().angvel.x;
        self.extremes.update_pitch_rate(self.t, q);
        Ok(())
    }

    /// Velocity of a footpad's contact point (the bottom of its contact sphere), m/s.
    fn contact_velocity(&self, footpad: RigidBodyHandle) -> Vector3<f64> {
        let pad = self.state(footpad);
        let r = Vector3::new(0.0, 0.0, -self.assembly.masses.contact_radius);
        pad.linvel + pad.angvel.cross(&r)
    }

    /// Contact states, penetration and the work of the contact impulses over the last step:
    /// normal impulses (and locked footpads' lateral impulses) into the contact-event account,
    /// sliding friction into the sliding account. Each impulse works on the mean of the contact
    /// point's velocities before the step (`pad_velocity`) and after it.
    fn book_contacts(&mut self) {
        let world = &self.assembly.world;
        for (i, g) in self.assembly.gears.iter().enumerate() {
            let mut impulse = Vector3::zeros();
            let mut depth: f64 = 0.0;
            let mut active = false;
            if let Some(pair) = world
                .narrow_phase
                .contact_pair(g.footpad_collider, g.plane_collider)
            {
                active = pair.has_any_active_contact();
                // rapier's multibody contact constraint pushes collider 1 along −n̂·λn and
                // along its friction impulse as stored (with one solver substep per step, the
                // last substep's `warmstart_tangent_world` is the step's); the footpad gets that
                // impulse or its opposite.
                let sign = if pair.collider1 == g.footpad_collider {
                    1.0
                } else {
                    -1.0
                };
                for m in pair.manifolds() {
                    let normal = to_na(m.data.normal);
                    for p in &m.points {
                        depth = depth.max(-p.dist);
                        let on_collider1 =
                            -normal * p.data.impulse + to_na(p.data.warmstart_tangent_world);
                        impulse += on_collider1 * sign;
                    }
                }
            }
            let v_mean = 0.5 * (self.pad_velocity[i] + self.contact_velocity(g.footpad));
            let normal_work = impulse.z * v_mean.z;
            let lateral_work = impulse.x * v_mean.x + impulse.y * v_mean.y;
            self.ledger.events += normal_work;
            if self.surfaces[i].locked() {
                self.ledger.events += lateral_work;
            } else {
                self.ledger.sliding -= lateral_work;
            }
            self.max_penetration = self.max_penetration.max(depth);
            let c = &mut self.contacts[i];
            c.in_contact = active && impulse.z > 0.0;
            if c.in_contact && c.first_contact.is_none() {
                c.first_contact = Some(self.t);
            }
        }
    }

    fn update_stability(&mut self, old_velocity: Option<&Vector3<f64>>) {
        for i in 0..self.legs.len() {
            self.pad_views[i] = PadView {
                position: self.kin[i].footpad,
                in_contact: self.contacts[i].in_contact,
                touched: self.contacts[i].first_contact.is_some(),
            };
        }
        let ke = self.kinetic_energy();
        let v = self.vehicle();
        let (x, u) = (v.point(&Vector3::zeros()), v.linvel);
        self.stability
            .update(self.t, &x, &u, old_velocity, ke, &self.pad_views);
    }

    fn diverged(&self, message: String, law: &str, leg: Option<usize>) -> RapierError {
        let v = self.vehicle();
        let (x, u, w) = (v.point(&Vector3::zeros()), v.linvel, v.angvel);
        RapierError::Diverged(Divergence {
            time: self.t,
            law: match leg {
                Some(i) => format!("{law} (leg {})", i + 1),
                None => law.to_string(),
            },
            message,
            state: format!(
                "R = [{:.6e}, {:.6e}, {:.6e}] m, V = [{:.6e}, {:.6e}, {:.6e}] m/s, ω = [{:.6e}, {:.6e}, {:.6e}] rad/s (inertial)",
                x.x, x.y, x.z, u.x, u.y, u.z, w.x, w.y, w.z
            ),
        })
    }

    /// Stops a run whose state is not finite or whose energy balance has drifted beyond the
    /// scenario's tolerance.
    fn check_divergence(&self) -> Result<(), RapierError> {
        for (i, (k, f)) in self.kin.iter().zip(&self.forces).enumerate() {
            let geometry = k.c + k.s[0] + k.s[1] + k.footpad.norm();
            let bad = f
                .non_finite()
                .or_else(|| (!geometry.is_finite()).then_some(("gear geometry", geometry)));
            if let Some((law, value)) = bad {
                return Err(self.diverged(format!("non-finite value {value}"), law, Some(i)));
            }
        }
        let finite = self.bodies.iter().all(|(h, _)| {
            let s = self.state(*h);
            s.pose.translation.is_finite()
                && s.linvel
                    .iter()
                    .chain(s.angvel.iter())
                    .all(|x| x.is_finite())
        });
        if !finite {
            return Err(self.diverged("non-finite body state".into(), "equations of motion", None));
        }
        let e = self.energy();
        self.ledger
            .check_balance(
                &e,
                self.energy_tolerance,
                "time step too large for the stiffest strut law, or contact too soft?",
            )
            .map_err(|message| self.diverged(message, "energy balance", None))
    }
}

/// The engine's settings as used, for the summary (names carry their units).
fn settings(sc: &Scenario, masses: &LinkMasses) -> serde_json::Map<String, serde_json::Value> {
    let r = &sc.rapier;
    let mut m = serde_json::Map::new();
    m.insert("rapier3d_f64".into(), "0.36.1".into());
    m.insert("timestep_s".into(), r.timestep.into());
    m.insert("solver_substeps".into(), 1.into());
    m.insert("contact_frequency_hz".into(), r.contact_frequency.into());
    m.insert(
        "contact_damping_ratio".into(),
        r.contact_damping_ratio.into(),
    );
    m.insert(
        "secondary_struts".into(),
        "massless two-force members".into(),
    );
    m.insert("obstacle_lock_friction".into(), LOCK_FRICTION.into());
    m.insert(
        "outer_cylinder_mass_kg".into(),
        masses.outer_cylinder.into(),
    );
    m.insert(
        "outer_cylinder_length_m".into(),
        masses.outer_cylinder_length.into(),
    );
    m.insert("footpad_body_mass_kg".into(), masses.footpad.into());
    m.insert("link_radius_m".into(), masses.link_radius.into());
    m.insert("contact_radius_m".into(), masses.contact_radius.into());
    m
}

/// Refuses a time step too large for the stiffest explicit strut law.
fn check_timestep(sc: &Scenario, laws: &GearLaws) -> Result<(), RapierError> {
    check_explicit_timestep(sc, laws, sc.rapier.timestep).map_err(|message| {
        RapierError::Unsupported {
            file: sc.file_of("engines.rapier.timestep").to_string(),
            field: "engines.rapier.timestep".into(),
            message,
        }
    })
}
