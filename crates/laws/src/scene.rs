//! The vehicle-level laws of a scene, built from a resolved scenario only for the mechanisms it
//! declares: the descent engine (eqs. 69-74), the RCS (eqs. 75-82) and propellant sloshing
//! (eqs. 108-117). Every engine builds them here, so the mapping from scenario to law exists
//! once; a parameter a law rejects is reported against its scenario field.

use crate::thrust::{
    engine_loads, nozzle_clearance, Amplification, EngineLoads, Nozzle, RimArrest, Tailoff,
};
use crate::{LawError, Rcs, Slosh};
use nalgebra::{Matrix3, Vector3};
use touchdown_scenario::model::Mechanism;
use touchdown_scenario::{Scenario, ScenarioError};

/// Height of the surface plane the nozzle meets, m: the nominal plane Z = 0 (the holes of the
/// report are per footpad, not under the engine).
pub const NOZZLE_SURFACE_Z: f64 = 0.0;

fn field(s: &Scenario, field: &str) -> impl Fn(LawError) -> ScenarioError {
    let file = s.file_of(field).to_string();
    let field = field.to_string();
    move |e| ScenarioError::field(&file, &field, e.to_string())
}

/// The descent engine: thrust along +Z_B at the nozzle exit centroid R_T with its tailoff
/// (eqs. 69-70) and ground amplification (eq. 71), and, if the scene declares it, the nozzle
/// crushing under constant load in proportion to the rim in contact (eqs. 72-73).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DescentEngine {
    /// F_THRUST(t), eqs. (69)-(70).
    pub tailoff: Tailoff,
    /// AMP(ZNOZ), eq. (71).
    pub amplification: Amplification,
    /// R_T, centroid of the nozzle exit plane, body axes, m.
    pub exit: Vector3<f64>,
    /// The crushing nozzle (`thrust.nozzle_crushing`); `None`: the nozzle never touches.
    pub nozzle: Option<Nozzle>,
}

impl DescentEngine {
    /// The scene's descent engine, if it declares one, for an engine whose steps are at most
    /// `longest_step` (s): the nozzle's rim is arrested within it ([`RimArrest`]).
    pub fn from_scenario(
        s: &Scenario,
        longest_step: f64,
    ) -> Result<Option<DescentEngine>, ScenarioError> {
        let Some(t) = &s.thrust else { return Ok(None) };
        let tailoff = Tailoff::new(
            t.thrust,
            t.tailoff_start,
            t.clock_at_touchdown,
            t.decay_rate,
            &t.polynomial,
        )
        .map_err(field(s, "thrust.polynomial"))?;
        let amplification = match &t.amplification {
            None => Amplification::unit(),
            Some(table) => {
                let (z, k): (Vec<f64>, Vec<f64>) = table.iter().copied().unzip();
                Amplification::new(&z, &k).map_err(field(s, "thrust.amplification"))?
            }
        };
        let nozzle = match t.nozzle_crushing {
            None => None,
            Some((radius, load)) => {
                let v = &s.vehicle;
                let arrest = RimArrest::new(v.mass, &v.inertia, longest_step)
                    .map_err(field(s, "thrust.nozzle_crushing"))?;
                Some(
                    Nozzle::new(t.nozzle_exit, radius, load, arrest)
                        .map_err(field(s, "thrust.nozzle_crushing"))?,
                )
            }
        };
        Ok(Some(DescentEngine {
            tailoff,
            amplification,
            exit: t.nozzle_exit,
            nozzle,
        }))
    }

    /// F_TF and MTF in body axes (eqs. 72-73) at simulation time `t` (s) with the vehicle at
    /// `a` and the committed nozzle crush `crush` (m along Z_B).
    #[inline]
    pub fn loads(&self, t: f64, a: &Attitude, crush: f64) -> EngineLoads {
        let (position, t_bi) = (a.position, a.t_bi);
        let clearance = nozzle_clearance(&self.exit, crush, position, t_bi, NOZZLE_SURFACE_Z);
        let taf = self.amplification.factor(clearance) * self.tailoff.thrust(t); // eq. (71)
        let (ffl, r_f) = match &self.nozzle {
            Some(n) => {
                let rim = n.rim_contact(crush, position, t_bi, NOZZLE_SURFACE_Z);
                (n.force(&rim, a.velocity, a.omega), rim.centroid)
            }
            None => (0.0, self.exit),
        };
        engine_loads(taf, &self.exit, ffl, &r_f) // eqs. (72)-(73)
    }

    /// Whether the nozzle's rim, with the committed crush `crush` (m), can reach the surface
    /// within `horizon` (s) from the vehicle at `reach`: its lowest point is at most the
    /// distance any rim point can descend in that time at the vehicle's present rates (|ω|
    /// times the farthest rim point's reach, plus the centre of mass's sink rate). False
    /// without nozzle crushing.
    pub fn rim_within_reach(&self, reach: &Reach, crush: f64, horizon: f64) -> bool {
        let Some(n) = &self.nozzle else { return false };
        let t_bi = reach.t_bi;
        let centre = self.exit + Vector3::new(0.0, 0.0, crush);
        let tilt = t_bi[(2, 0)].hypot(t_bi[(2, 1)]); // the rim's lowest point, closed form
        let lowest = nozzle_clearance(&self.exit, crush, reach.position, t_bi, NOZZLE_SURFACE_Z)
            - n.exit_radius() * tilt;
        let descent = reach.sink_rate + reach.omega.norm() * (centre.norm() + n.exit_radius());
        lowest <= horizon * descent.max(0.0)
    }

    /// How far the nozzle rim penetrates the surface beyond the committed crush `crush` (m),
    /// at an accepted state: the caller adds it to the crush memory (docs/errata.md, "Eqs. (72)-(73):
    /// nozzle crushing"); 0 without
    /// nozzle crushing.
    pub fn crush_increment(&self, position: &Vector3<f64>, t_bi: &Matrix3<f64>, crush: f64) -> f64 {
        self.nozzle.map_or(0.0, |n| {
            n.rim_contact(crush, position, t_bi, NOZZLE_SURFACE_Z)
                .penetration
        })
    }
}

/// Loads of the vehicle-level mechanisms on the vehicle, body axes.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct AppliedLoads {
    /// Force, N (body axes; the caller applies T_BI, eqs. 74, 82, 116).
    pub force: Vector3<f64>,
    /// Torque about the centre of mass, N·m (body axes; MTF + MRCS + T_f, eqs. 73, 80, 117).
    pub torque: Vector3<f64>,
    /// The driving mechanisms' part of `force` and `torque` (the engine's thrust and the RCS;
    /// not the nozzle's crushing load or the slosh mass, which only exchange energy), N and
    /// N·m, body axes: the energy balance counts their positive work as energy put in.
    pub driving: (Vector3<f64>, Vector3<f64>),
}

impl AppliedLoads {
    /// Power of the driving part on a vehicle whose centre of mass moves at `velocity` (m/s,
    /// body axes) and which turns at `omega` (rad/s, body axes), W.
    pub fn driving_power(&self, velocity: &Vector3<f64>, omega: &Vector3<f64>) -> f64 {
        self.driving.0.dot(velocity) + self.driving.1.dot(omega)
    }
}

/// The vehicle's attitude and rates, as the propulsion laws read them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Attitude<'a> {
    /// Centre of mass, inertial (surface) frame, m.
    pub position: &'a Vector3<f64>,
    /// Velocity of the centre of mass, body axes, m/s.
    pub velocity: &'a Vector3<f64>,
    /// T_BI, body → inertial.
    pub t_bi: &'a Matrix3<f64>,
    /// Euler angles θ (eq. 1 order), rad.
    pub theta: &'a Vector3<f64>,
    /// Angular velocity ω, body axes, rad/s.
    pub omega: &'a Vector3<f64>,
}

/// How far and how fast the vehicle can carry its nozzle's rim, as
/// [`Propulsion::rim_within_reach`] reads it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reach<'a> {
    /// Centre of mass, inertial (surface) frame, m.
    pub position: &'a Vector3<f64>,
    /// T_BI, body → inertial.
    pub t_bi: &'a Matrix3<f64>,
    /// Angular velocity ω, rad/s (its magnitude is read).
    pub omega: &'a Vector3<f64>,
    /// The centre of mass's descent rate −Ż, inertial, m/s.
    pub sink_rate: f64,
}

/// The scene's propulsion: the descent engine with its nozzle (eqs. 69-74) and the RCS
/// (eqs. 75-82), the vehicle-level mechanisms every engine applies the same way, as a force
/// and a torque on the vehicle. The committed nozzle crush is the caller's (docs/errata.md,
/// "Eqs. (72)-(73): nozzle crushing").
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Propulsion {
    /// Descent engine (`thrust`), if declared.
    pub engine: Option<DescentEngine>,
    /// Reaction control system (`rcs`), if declared.
    pub rcs: Option<Rcs>,
}

impl Propulsion {
    /// What `s` declares of the engine and the RCS, for an engine whose steps are at most
    /// `longest_step` (s).
    pub fn from_scenario(s: &Scenario, longest_step: f64) -> Result<Propulsion, ScenarioError> {
        Ok(Propulsion {
            engine: DescentEngine::from_scenario(s, longest_step)?,
            rcs: rcs_from_scenario(s)?,
        })
    }

    /// Whether the scene declares neither an engine nor an RCS.
    pub fn is_empty(&self) -> bool {
        self.engine.is_none() && self.rcs.is_none()
    }

    /// The mechanisms each evaluation of [`Propulsion::loads`] evaluates: thrust, nozzle
    /// crushing and the RCS, as declared.
    pub fn mechanisms(&self) -> impl Iterator<Item = Mechanism> {
        let nozzle = self.engine.is_some_and(|e| e.nozzle.is_some());
        [
            (Mechanism::Thrust, self.engine.is_some()),
            (Mechanism::NozzleCrushing, nozzle),
            (Mechanism::Rcs, self.rcs.is_some()),
        ]
        .into_iter()
        .filter_map(|(m, declared)| declared.then_some(m))
    }

    /// Engine and RCS loads in body axes at simulation time `t` (s) with the vehicle at `a`
    /// and the committed nozzle crush `nozzle_crush` (shortening along Z_B, m);
    /// `first_contact` gives the first footpad contact (s), for the RCS delay (asked only if
    /// the RCS translates).
    #[inline]
    pub fn loads(
        &self,
        t: f64,
        first_contact: impl Fn() -> Option<f64>,
        a: &Attitude,
        nozzle_crush: f64,
    ) -> AppliedLoads {
        let mut out = AppliedLoads::default();
        if let Some(engine) = &self.engine {
            let e = engine.loads(t, a, nozzle_crush);
            out.force += e.force; // eq. (72)
            out.torque += e.torque; // eq. (73)
            out.driving.0 += e.thrust.0;
            out.driving.1 += e.thrust.1;
        }
        if let Some(rcs) = &self.rcs {
            let first = if rcs.translates() {
                first_contact()
            } else {
                None
            };
            let r = rcs.loads(t, first, a.theta, a.omega);
            out.force += r.force; // eq. (81)
            out.torque += r.torque; // eq. (80)
            out.driving.0 += r.force;
            out.driving.1 += r.torque;
        }
        out
    }

    /// Whether the nozzle's rim can reach the surface within `horizon` (s) from the vehicle at
    /// `reach` with the committed crush `nozzle_crush` (m) ([`DescentEngine::rim_within_reach`]);
    /// false without nozzle crushing.
    pub fn rim_within_reach(&self, reach: &Reach, nozzle_crush: f64, horizon: f64) -> bool {
        (self.engine).is_some_and(|e| e.rim_within_reach(reach, nozzle_crush, horizon))
    }

    /// Commits an accepted state (vehicle at `position`, m, attitude `t_bi`): the nozzle crush
    /// `nozzle_crush` (m) grows by the rim's penetration.
    pub fn commit(&self, position: &Vector3<f64>, t_bi: &Matrix3<f64>, nozzle_crush: &mut f64) {
        if let Some(engine) = &self.engine {
            *nozzle_crush += engine.crush_increment(position, t_bi, *nozzle_crush);
        }
    }
}

/// The scene's RCS, if it declares one.
pub fn rcs_from_scenario(s: &Scenario) -> Result<Option<Rcs>, ScenarioError> {
    let Some(r) = &s.rcs else { return Ok(None) };
    Rcs::new(*r).map(Some).map_err(field(s, "rcs"))
}

/// The scene's propellant slosh, if it declares one (the vehicle mass includes the
/// propellant).
pub fn slosh_from_scenario(s: &Scenario) -> Result<Option<Slosh>, ScenarioError> {
    let Some(p) = &s.slosh else { return Ok(None) };
    Slosh::new(
        p.force_coefficient,
        p.frequency_parameter,
        p.free_surface_depth,
        p.mass_depth,
        s.vehicle.mass,
    )
    .map(Some)
    .map_err(field(s, "slosh"))
}

/// The rigid vehicle of a scene with sloshing (eqs. 113-114): mass M − M_s, the inertia of
/// eq. (114), and every body-frame point (gear, nozzle) re-referenced to the rigid centre of
/// mass, which lies ℓ2 above the total one along +Z_B (docs/errata.md, "Eqs. (113)-(114): geometry re-referenced to the rigid centre of mass"). The touchdown state is
/// placed with this geometry (eq. 19), so the footpads start where the scene puts them.
pub fn rigid_vehicle(s: &Scenario, slosh: &Slosh) -> Result<Scenario, ScenarioError> {
    let mut out = s.clone();
    out.vehicle.mass = slosh.rigid_mass();
    out.vehicle.inertia = slosh.rigid_inertia(&s.vehicle.inertia);
    if out.vehicle.inertia.cholesky().is_none() {
        return Err(ScenarioError::field(
            s.file_of("slosh"),
            "slosh",
            "removing the slosh mass leaves an inertia that is not positive definite (eq. 114): check ℓ1, ℓ and the vehicle's inertia",
        ));
    }
    let shift = Vector3::new(0.0, 0.0, slosh.cm_shift());
    for leg in &mut out.legs {
        leg.b2 -= shift;
        leg.b3 -= shift;
        leg.b4 -= shift;
        leg.bp -= shift;
    }
    if let Some(t) = &mut out.thrust {
        t.nozzle_exit -= shift;
    }
    Ok(out)
}

/// The scene's soil (eqs. 101-104), if its surface is soil: AP = π·PR², the frontal area
/// bounded by the footpad height.
pub fn soil_from_scenario(s: &Scenario) -> Result<Option<crate::Soil>, ScenarioError> {
    let Some(k) = &s.surface.soil else {
        return Ok(None);
    };
    let r = s.footpad.radius;
    let height = s.footpad.height.unwrap_or(0.0);
    crate::Soil::new(*k, std::f64::consts::PI * r * r, r, height)
        .map(Some)
        .map_err(field(s, "surface.soil"))
}

/// The scene's curbs (eqs. 86-95); `None` when the scene has no curbs.
pub fn curbs_from_scenario(s: &Scenario) -> Result<Option<crate::Curbs>, ScenarioError> {
    let Some(table) = &s.footpad.crush else {
        return Ok(None);
    };
    if s.surface.curbs.is_empty() {
        return Ok(None);
    }
    let crush = crate::FootpadCrush::new(crate::gear::honeycomb(s, "footpad.crush", table, None)?);
    let mut curbs = Vec::with_capacity(s.surface.curbs.len());
    for (i, c) in s.surface.curbs.iter().enumerate() {
        let curb = crate::Curb::new(c.distance, c.angle, c.friction)
            .map_err(field(s, &format!("surface.curbs[{i}]")))?;
        curbs.push((c.leg, curb));
    }
    Ok(Some(crate::Curbs { list: curbs, crush }))
}

/// The scene's primary-strut bending law (eqs. 40-48), if it declares one. The coupling is
/// lagged one step (docs/errata.md, "Eqs. (47)-(48): bending coupling"), which converges only while the beam is stiffer than the
/// secondaries it carries: the loop gain K_S·a²b²/(3·EI·L) (secondary onset rate times the
/// beam's compliance at point 1, eq. 46 corrected) must stay below 1/2, else the scenario is
/// refused.
pub fn bending_from_scenario(s: &Scenario) -> Result<Option<crate::Bending>, ScenarioError> {
    let Some(ei) = s.primary.bending_stiffness else {
        return Ok(None);
    };
    let name = "primary_strut.bending.stiffness";
    let law = crate::Bending::new(ei).map_err(field(s, name))?;
    let k = s
        .secondary
        .tension
        .onset_rate
        .max(s.secondary.compression.onset_rate);
    for leg in &s.legs {
        let (a, l) = (leg.l21, leg.l2p);
        let b = l - a;
        let gain = 2.0 * k * a * a * b * b / (3.0 * ei * l);
        if gain >= 1.0 {
            return Err(ScenarioError::field(
                s.file_of(name),
                name,
                format!(
                    "EI = {ei:.4e} N·m² is too soft for the lagged bending coupling: the loop gain 2·K_S·a²b²/(3·EI·L) = {gain:.3} must stay below 1 (EI above {:.4e} N·m²)",
                    ei * gain
                ),
            ));
        }
    }
    Ok(Some(law))
}
