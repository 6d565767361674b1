//! One landing on the rapier multibody: steps of the base length, or longer between the end
//! stops (`touchdown_multibody::GearModel::next_step`), the strut laws applied before each step,
//! hysteresis committed after it, an energy ledger, the shared stability criteria and
//! divergence checks.
//!
//! Step:
//! 1. read every gear's strokes and rates, evaluate the laws with the committed memories, apply
//!    the explicit forces and set the motor and friction bounds (`struts`); apply the engine
//!    and RCS loads, if the scene has them, to the vehicle;
//! 2. let rapier step (contacts, joints, motors and dry friction are solved implicitly);
//! 3. book the work of each law over the step (explicit forces and bounds × the stroke
//!    increments), the work of the contact impulses, commit the honeycomb memories at the new
//!    strokes, update the stability criteria and the extremes, and check for divergence.

use crate::assembly::{
    self, body_state, to_na, to_rapier, Assembly, BodyState, Inertia, LinkMasses,
};
use crate::struts;
use nalgebra::Vector3;
use rapier3d_f64::prelude::*;
use touchdown_multibody::{
    BodyEnergy, BodyMotion, GearModel, GearState, PadStep, RapierSettings, Reading, StepTaken,
    StrutKinematics,
};
use touchdown_record::{EnergyReport, Landing, RunError, Sample, Summary};
use touchdown_scenario::schema::Engine;
use touchdown_scenario::Scenario;

/// A landing simulated on the rapier multibody.
pub struct RapierSimulation {
    name: String,
    assembly: Assembly,
    /// The gear as set up: geometry, surfaces, laws, curbs, criteria.
    gear: GearModel,
    /// The gear's memories, kinematics, contacts, ledger, stability and extremes.
    gear_state: GearState,
    /// Each gear's kinematics as read after the last step.
    kin: Vec<StrutKinematics>,
    /// Each footpad's contact over the last step.
    pad_steps: Vec<PadStep>,
    /// Vehicle, then per gear outer link and footpad: handle, mass and inertia.
    bodies: Vec<(RigidBodyHandle, Inertia)>,
    settings: serde_json::Map<String, serde_json::Value>,
    // state
    t: f64,
    steps: u64,
    /// Footpad states at the current state: before the coming step, and kept from the booking
    /// of the last one.
    pad_state: Vec<BodyState>,
    /// Vehicle and link positions at touchdown (for potential energies).
    position0: Vec<Vector3<f64>>,
    /// Kinetic energy of the gear links at touchdown, J.
    links_kinetic0: f64,
}

impl RapierSimulation {
    /// Builds the multibody of a scenario at its touchdown state.
    pub fn new(scenario: &Scenario) -> Result<RapierSimulation, RunError> {
        scenario.require_engine(Engine::Rapier, crate::unsupported)?;
        let rs = RapierSettings::new(scenario)?;
        let (gear, gear_state) = GearModel::new(scenario, rs.timestep, scenario.rapier.stride)?;
        let n = scenario.legs.len();
        let assembly = assembly::build(scenario, &rs)?;
        let settings = settings(&rs, &assembly.masses, gear.long_step());
        let mut sim = RapierSimulation {
            name: scenario.file.name.clone(),
            gear,
            gear_state,
            kin: vec![StrutKinematics::default(); n],
            pad_steps: vec![PadStep::default(); n],
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
            settings,
            t: 0.0,
            steps: 0,
            pad_state: Vec::new(),
            position0: Vec::new(),
            links_kinetic0: 0.0,
            assembly,
        };
        sim.pad_state = (sim.assembly.gears.iter())
            .map(|g| sim.state(g.footpad))
            .collect();
        sim.position0 = sim.body_positions();
        sim.links_kinetic0 = sim.gear_energy();
        sim.read_kinematics();
        let v = sim.vehicle_state();
        let now = sim.reading(&v);
        (sim.gear)
            .start_landing(
                &mut sim.gear_state,
                &sim.kin,
                &now,
                footpad_velocity(&sim.assembly),
            )
            .map_err(|f| f.at(sim.t, &v))?;
        Ok(sim)
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
        self.gear_state.max_penetration()
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
                    .gear
                    .gravity()
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
        self.gear.energy(&self.gear_state, &self.energies())
    }

    /// The bodies' energies now.
    fn energies(&self) -> BodyEnergy {
        let kinetic = self.kinetic_energy();
        BodyEnergy {
            kinetic_j: kinetic,
            potential_change_j: self.body_energy(0) - kinetic,
            gear_j: self.gear_energy(),
        }
    }

    /// The vehicle's state.
    fn vehicle_state(&self) -> BodyMotion {
        let v = self.vehicle();
        BodyMotion {
            position: v.point(&Vector3::zeros()),
            rotation: v.rotation(),
            velocity: v.linvel,
            angular_velocity: v.angvel,
        }
    }

    fn read_kinematics(&mut self) {
        for (i, (g, leg)) in self.assembly.gears.iter().zip(self.gear.legs()).enumerate() {
            self.kin[i] = struts::kinematics(&self.assembly.world, self.assembly.vehicle, g, leg);
        }
    }

    /// Velocity of a footpad's contact point (the bottom of its contact sphere), m/s.
    fn contact_velocity(&self, pad: &BodyState) -> Vector3<f64> {
        let r = Vector3::new(0.0, 0.0, -self.assembly.masses.contact_radius);
        pad.linvel + pad.angvel.cross(&r)
    }

    /// Contact states, penetration and the work of the contact impulses over the last step
    /// `dt` (s): normal impulses (and locked footpads' lateral impulses) into the contact-event
    /// account, sliding friction into the sliding account. Each impulse works on the mean of the
    /// contact point's velocities before the step (`pad_state`) and after it, plus the normal
    /// impulse's work on the footpad's normal drift: rapier's soft contact integrates positions
    /// with a velocity biased against the penetration, then removes the bias, so the footpad
    /// moves δ = Δz − v_z·Δt further than its final velocity v accounts for. Over δ the contact
    /// holds the footpad's other loads (−(J_z − m·Δv_z)/Δt: the strut pressing it into its
    /// surface; next to nothing in an impact) and does their work with the opposite sign.
    /// Unbooked, the 0.4 mm a footpad sinks under a bottoming strut left 57 J, 5 % of the
    /// touchdown energy, in the balance of a 30 ft/s drop, at every step size. The lateral
    /// drift is not a position correction but friction's lag (friction is solved in the
    /// unbiased pass only, after the positions moved): booking it too overbooked the sliding
    /// work, by 1 % of the touchdown energy on the 1-2-1 landing at 5 ft/s.
    fn book_contacts(&mut self, dt: f64) {
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
            let (before, after) = (&self.pad_state[i], self.state(g.footpad));
            let mass = g.footpad_inertia.mass;
            let drift_rate =
                (after.pose.translation.z - before.pose.translation.z) / dt - after.linvel.z;
            let pushed = impulse.z - mass * (after.linvel.z - before.linvel.z);
            let v_mean = 0.5 * (self.contact_velocity(before) + self.contact_velocity(&after));
            let work = impulse.component_mul(&v_mean) + Vector3::z() * (pushed * drift_rate);
            self.pad_steps[i] = PadStep {
                impulse,
                work,
                depth,
                touching: active,
            };
            self.pad_state[i] = after;
        }
    }

    /// What the book reads of the bodies now, the vehicle in state `v`.
    fn reading<'a>(&self, v: &'a BodyMotion) -> Reading<'a> {
        let finite = self.bodies.iter().all(|(h, _)| {
            let s = self.state(*h);
            s.pose.translation.is_finite()
                && s.linvel
                    .iter()
                    .chain(s.angvel.iter())
                    .all(|x| x.is_finite())
        });
        Reading {
            t: self.t,
            vehicle: v,
            finite,
            energy: self.energies(),
            steps: self.steps,
        }
    }
}

/// Each footpad's velocity at BP in `assembly`, m/s, inertial.
fn footpad_velocity(assembly: &Assembly) -> impl Fn(usize) -> Vector3<f64> + '_ {
    move |i| body_state(&assembly.world, assembly.gears[i].footpad).linvel
}

impl Landing for RapierSimulation {
    type Error = RunError;

    /// One step (see the module documentation): the base step, or the long one where no
    /// stop is engaged or can engage within it (`GearModel::next_step`).
    fn step(&mut self) -> Result<(), RunError> {
        let dt = self.gear.next_step(&self.gear_state, self.t);
        let p = &mut self.assembly.world.integration_parameters;
        // The contacts start from the last step's impulses, scaled to this step's length
        // (the same force), as rapier's one solver iteration a step needs them.
        p.warmstart_coefficient = dt / p.dt;
        p.dt = dt;
        // User forces and torques persist in rapier until cleared, and are cleared separately.
        for (h, _) in &self.bodies {
            let rb = &mut self.assembly.world.bodies[*h];
            rb.reset_forces(false);
            rb.reset_torques(false);
        }
        for i in 0..self.gear.legs().len() {
            let g = self.assembly.gears[i];
            struts::apply(
                &mut self.assembly.world,
                self.assembly.vehicle,
                &g,
                self.gear_state.kinematics(i),
                self.gear_state.forces(i),
            );
        }
        if !self.gear_state.applied().is_empty() {
            // eqs. (72)-(74), (80)-(82): the engine and RCS loads, held over the step.
            let a = self.gear_state.applied();
            let rb = &mut self.assembly.world.bodies[self.assembly.vehicle];
            rb.add_force(to_rapier(&a.force), true);
            rb.add_torque(to_rapier(&a.torque), true);
        }
        if self.gear.loads_footpads() {
            // eqs. (94)-(95) and the obstacle walls: the force on each footpad (at BP, its
            // centre of mass).
            for (i, g) in self.assembly.gears.iter().enumerate() {
                let rb = &mut self.assembly.world.bodies[g.footpad];
                rb.add_force(to_rapier(&self.gear_state.pad_force(i)), true);
            }
        }
        let before = self.vehicle_state();
        self.assembly.world.step();
        self.t += dt;
        self.steps += 1;
        self.read_kinematics();
        self.book_contacts(dt);
        let v = self.vehicle_state();
        let now = self.reading(&v);
        let step = StepTaken {
            before: &before,
            dt,
            kinematics: &self.kin,
            pads: &self.pad_steps,
        };
        (self.gear)
            .finish_step(
                &mut self.gear_state,
                &step,
                &now,
                footpad_velocity(&self.assembly),
            )
            .map_err(|f| f.at(self.t, &v))?;
        Ok(())
    }

    /// Whether the run has ended.
    fn finished(&self) -> bool {
        self.gear.finished(&self.gear_state, self.t)
    }

    /// Writes the current state into `out` (a sample made for as many legs).
    fn sample(&self, out: &mut Sample) {
        (self.gear).sample(
            &self.gear_state,
            out,
            self.t,
            &self.vehicle_state(),
            self.energy(),
        );
    }

    /// The summary at the current state.
    fn summary(&self) -> Summary {
        self.gear.summary(
            &self.gear_state,
            "rapier",
            &self.name,
            self.settings.clone(),
            self.t,
            self.steps,
            self.energy(),
        )
    }
}

/// The engine's settings as used, for the summary (names carry their units); `long_step`: the
/// step between the stops, s.
fn settings(
    r: &RapierSettings,
    masses: &LinkMasses,
    long_step: f64,
) -> serde_json::Map<String, serde_json::Value> {
    let mut m = serde_json::Map::new();
    m.insert("rapier3d_f64".into(), "0.36.1".into());
    m.insert("timestep_s".into(), r.timestep.into());
    m.insert("timestep_between_stops_s".into(), long_step.into());
    m.insert("solver_substeps".into(), 1.into());
    m.insert("contact_frequency_hz".into(), r.contact_frequency.into());
    m.insert(
        "contact_damping_ratio".into(),
        r.contact_damping_ratio.into(),
    );
    m.insert("length_unit_m".into(), r.length_unit.into());
    m.insert(
        "secondary_struts".into(),
        "massless two-force members".into(),
    );
    for (name, value) in touchdown_multibody::CONTACT_FLAG_SETTINGS {
        m.insert(name.into(), value.into());
    }
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
