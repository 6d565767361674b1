//! The optional mechanisms of a scene, assembled from what it declares and nothing else: the
//! descent engine with nozzle crushing (eqs. 69-74), the RCS (eqs. 75-82), propellant
//! sloshing (eqs. 108-117), soil (eqs. 101-104), curbs with footpad crushing (eqs. 86-95) and
//! primary-strut bending (eqs. 40-48). A mechanism the scene leaves out is `None` here: it is
//! never built and never evaluated, and every evaluation of one that is present is counted
//! ([`Mechanisms::evaluations`]), which is how the tests show it.

use crate::vehicle::VehicleState;
use nalgebra::{Vector2, Vector3};
use touchdown_laws::scene::{self, AppliedLoads, Attitude, Propulsion, Reach};
use touchdown_laws::{Bending, CrushMemory, Curbs, Slosh, Soil};
use touchdown_scenario::model::Mechanism;
use touchdown_scenario::{Scenario, ScenarioError};

/// Evaluation counts per mechanism (plain data, counted where the evaluations happen).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Evaluations([u64; Mechanism::ALL.len()]);

impl Evaluations {
    /// Counts one evaluation of `m`.
    #[inline]
    pub fn tick(&mut self, m: Mechanism) {
        self.0[m as usize] += 1;
    }

    /// Evaluations of `m` so far.
    pub fn get(&self, m: Mechanism) -> u64 {
        self.0[m as usize]
    }
}

/// Power of the vehicle-level mechanisms on the vehicle, W: all of them (`applied`), and the
/// driving ones' part (`driving`: thrust and RCS, whose positive work is energy put in).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Power {
    pub(crate) applied: f64,
    pub(crate) driving: f64,
}

/// The scene's optional mechanisms: their laws, which the scenario fixes (part of what a
/// [`crate::Simulation`] keeps fixed for its landing); what they commit is in
/// [`MechanismState`].
#[derive(Debug, Clone)]
pub struct Mechanisms {
    /// Descent engine (thrust, amplification, nozzle crushing) and RCS.
    pub propulsion: Propulsion,
    /// Propellant slosh.
    pub slosh: Option<Slosh>,
    /// Soil surface.
    pub soil: Option<Soil>,
    /// Curbs and footpad crushing.
    pub curbs: Option<Curbs>,
    /// Primary-strut bending.
    pub bending: Option<Bending>,
    declared: Vec<Mechanism>,
}

/// What the mechanisms of a landing commit and count as it goes (part of the state a
/// [`crate::Simulation`] advances).
#[derive(Debug, Clone)]
pub struct MechanismState {
    /// Committed nozzle crush (shortening along Z_B), m.
    pub nozzle_crush: f64,
    /// The curbs' committed crush memories, one per curb of [`Mechanisms::curbs`].
    pub curb_memory: Vec<CrushMemory>,
    /// Specific force at the slosh mass, body axes, m/s², at the last accepted state: the
    /// slosh equations use it one step lagged, which breaks the algebraic loop between the
    /// vehicle's and the slosh mass's accelerations (docs/errata.md, "Eq. (108): effective axial
    /// acceleration, lagged one step").
    pub slosh_specific_force: Vector3<f64>,
    evaluations: Evaluations,
}

impl MechanismState {
    /// Counts one evaluation of `m` (for the mechanisms evaluated elsewhere: soil, curbs,
    /// bending).
    #[inline]
    pub fn tick(&mut self, m: Mechanism) {
        self.evaluations.tick(m);
    }
}

impl Mechanisms {
    /// Builds what `s` declares (and nothing else); `slosh` is the scene's slosh law, built
    /// from the total vehicle before `s` was re-referenced to the rigid one
    /// (`touchdown_laws::scene::rigid_vehicle`).
    pub fn new(s: &Scenario, slosh: Option<Slosh>) -> Result<Mechanisms, ScenarioError> {
        Ok(Mechanisms {
            // the rim arrested within the report scheme's longest step (the strides scheme
            // takes no longer one while the rim can reach the surface: State::stride_step)
            propulsion: Propulsion::from_scenario(s, s.integrator.dt_max)?,
            slosh,
            soil: scene::soil_from_scenario(s)?,
            curbs: scene::curbs_from_scenario(s)?,
            bending: scene::bending_from_scenario(s)?,
            declared: s.mechanisms(),
        })
    }

    /// The state of these mechanisms at the start of a landing in gravity `gravity` (m/s²):
    /// nothing crushed, nothing evaluated, the slosh mass's specific force that of rest.
    pub fn start(&self, gravity: f64) -> MechanismState {
        MechanismState {
            nozzle_crush: 0.0,
            curb_memory: self.curbs.as_ref().map_or_else(Vec::new, Curbs::memories),
            slosh_specific_force: Vector3::new(0.0, 0.0, gravity),
            evaluations: Evaluations::default(),
        }
    }

    /// Evaluations in `state` of each declared mechanism evaluated during a run so far, in the
    /// order of [`Mechanism::ALL`] (trunnion springs are folded into the diagrams when the laws
    /// are built, so they are not listed).
    pub fn evaluations(&self, state: &MechanismState) -> Vec<(Mechanism, u64)> {
        self.declared
            .iter()
            .filter(|m| **m != Mechanism::TrunnionSprings) // folded into the diagrams
            .map(|m| (*m, state.evaluations.get(*m)))
            .collect()
    }

    /// Position of the slosh mass from the rigid centre of mass, body axes, m: (0, 0, −d).
    fn slosh_arm(slosh: &Slosh) -> Vector3<f64> {
        Vector3::new(0.0, 0.0, -slosh.arm())
    }

    /// Loads of the descent engine, the RCS and the slosh mass on the vehicle at time `t` (s)
    /// and state `v`, their committed memories in `state` (where the evaluations are counted),
    /// or `None` when the scene has none of them; `first_contact` gives the first footpad
    /// contact (s), for the RCS delay.
    #[inline]
    pub fn vehicle_loads(
        &self,
        state: &mut MechanismState,
        t: f64,
        first_contact: impl Fn() -> Option<f64>,
        v: &VehicleState,
    ) -> Option<AppliedLoads> {
        let p = &self.propulsion;
        if p.is_empty() && self.slosh.is_none() {
            return None;
        }
        for m in p.mechanisms() {
            state.evaluations.tick(m);
        }
        let velocity = v.t_bi.transpose() * v.velocity;
        let attitude = Attitude {
            position: &v.position,
            velocity: &velocity,
            t_bi: &v.t_bi,
            theta: &v.euler.theta,
            omega: &v.omega,
        };
        let mut out = p.loads(t, first_contact, &attitude, state.nozzle_crush); // eqs. (72)-(73), (80)-(81)
        if let Some(slosh) = &self.slosh {
            state.evaluations.tick(Mechanism::Slosh);
            let axial = slosh.axial(&state.slosh_specific_force);
            let lateral = slosh.wall_force(&v.slosh_q, axial); // eqs. (108), (115)
                                                               // The slosh mass presses on the tank floor with M_s·Z̈_B,eff along −Z_B (the appendix
                                                               // drops this axial load: docs/errata.md, "The slosh mass's axial load — added"); it
                                                               // acts on the axis, so no moment.
            out.force += Vector3::new(lateral.x, lateral.y, -slosh.slosh_mass() * axial);
            out.torque += slosh.torque(&lateral); // eq. (117), corrected
        }
        Some(out)
    }

    /// Whether the nozzle's rim can reach the surface within `horizon` (s) from the vehicle
    /// at `v` with the crush committed in `state`.
    pub fn nozzle_within_reach(
        &self,
        state: &MechanismState,
        v: &VehicleState,
        horizon: f64,
    ) -> bool {
        let reach = Reach {
            position: &v.position,
            t_bi: &v.t_bi,
            omega: &v.omega,
            sink_rate: -v.velocity.z,
        };
        (self.propulsion).rim_within_reach(&reach, state.nozzle_crush, horizon)
    }

    /// Slosh acceleration q̈ at state `v` (eq. 109, corrected), the lagged specific force in
    /// `state`, m/s²; zero without slosh.
    #[inline]
    pub fn slosh_acceleration(&self, state: &MechanismState, v: &VehicleState) -> Vector2<f64> {
        match &self.slosh {
            None => Vector2::zeros(),
            Some(slosh) => {
                let f = &state.slosh_specific_force;
                let axial = slosh.axial(f);
                slosh.acceleration(&v.slosh_q, &Vector2::new(f.x, f.y), axial)
            }
        }
    }

    /// Commits the accepted state `v` into `state`: the nozzle crush grows by the rim's
    /// penetration, and the specific force at the slosh mass is taken for the next step.
    pub fn commit(&self, state: &mut MechanismState, v: &VehicleState, gravity: &Vector3<f64>) {
        (self.propulsion).commit(&v.position, &v.t_bi, &mut state.nozzle_crush);
        if let Some(slosh) = &self.slosh {
            // (A_tank − G) in body axes at r_s = (0, 0, −d) (docs/errata.md, "Eq. (109): 2-D
            // amplitude, lateral specific force").
            let r = Self::slosh_arm(slosh);
            state.slosh_specific_force = v.t_bi.transpose() * (v.acceleration - gravity)
                + v.omega_dot.cross(&r)
                + v.omega.cross(&v.omega.cross(&r));
        }
    }
}
