//! The vehicle-level laws of a scene, built from a resolved scenario only for the mechanisms it
//! declares: the descent engine (eqs. 69-74), the RCS (eqs. 75-82) and propellant sloshing
//! (eqs. 108-117). Every engine builds them here, so the mapping from scenario to law exists
//! once; a parameter a law rejects is reported against its scenario field.

use crate::thrust::{engine_loads, Amplification, EngineLoads, Nozzle, RimContact, Tailoff};
use crate::{LawError, Rcs, RcsParams, Slosh, Translation};
use nalgebra::{Matrix3, Vector3};
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
/// (eqs. 69-70) and ground amplification (eq. 71), and the nozzle crushing under constant load
/// in proportion to the rim in contact (eqs. 72-73).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DescentEngine {
    /// F_THRUST(t), eqs. (69)-(70).
    pub tailoff: Tailoff,
    /// AMP(ZNOZ), eq. (71).
    pub amplification: Amplification,
    /// The nozzle (R_T, exit radius, crush load).
    pub nozzle: Nozzle,
    /// Whether the nozzle crushes (the scene declares `thrust.nozzle_crushing`).
    pub crushing: bool,
}

/// The descent engine's loads at one state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EngineState {
    /// F_TF and MTF in body axes (eqs. 72-73).
    pub loads: EngineLoads,
    /// TAF, the amplified thrust, N (eq. 71).
    pub thrust: f64,
    /// The rim in contact (zero when the nozzle does not crush).
    pub rim: RimContact,
}

impl DescentEngine {
    /// The scene's descent engine, if it declares one.
    pub fn from_scenario(s: &Scenario) -> Result<Option<DescentEngine>, ScenarioError> {
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
        let (radius, load) = t.nozzle_crushing.unwrap_or((1.0, 0.0));
        let nozzle =
            Nozzle::new(t.nozzle_exit, radius, load).map_err(field(s, "thrust.nozzle_crushing"))?;
        Ok(Some(DescentEngine {
            tailoff,
            amplification,
            nozzle,
            crushing: t.nozzle_crushing.is_some(),
        }))
    }

    /// Loads at simulation time `t` (s) with the vehicle's centre of mass at `position` (m,
    /// inertial), attitude `t_bi` and the committed nozzle crush `crush` (m along Z_B).
    #[inline]
    pub fn state(
        &self,
        t: f64,
        position: &Vector3<f64>,
        t_bi: &Matrix3<f64>,
        crush: f64,
    ) -> EngineState {
        let clearance = self
            .nozzle
            .clearance(crush, position, t_bi, NOZZLE_SURFACE_Z);
        let taf = self.amplification.factor(clearance) * self.tailoff.thrust(t); // eq. (71)
        let r_t = self.nozzle.exit_centroid();
        let rim = if self.crushing {
            self.nozzle
                .rim_contact(crush, position, t_bi, NOZZLE_SURFACE_Z)
        } else {
            RimContact {
                fraction: 0.0,
                centroid: r_t,
                penetration: 0.0,
            }
        };
        let ffl = self.nozzle.force(&rim);
        EngineState {
            loads: engine_loads(taf, &r_t, ffl, &rim.centroid), // eqs. (72)-(73)
            thrust: taf,
            rim,
        }
    }
}

/// The scene's RCS, if it declares one.
pub fn rcs_from_scenario(s: &Scenario) -> Result<Option<Rcs>, ScenarioError> {
    let Some(r) = &s.rcs else { return Ok(None) };
    Rcs::new(RcsParams {
        mode: r.mode,
        attitude_gain: r.attitude_gain,
        rate_gain: r.rate_gain,
        deadband: r.deadband,
        torque: r.torque,
        commanded_angles: r.commanded_attitude,
        commanded_rates: r.commanded_rates,
        translation: r
            .downward_translation
            .map(|(delay, force)| Translation { delay, force }),
    })
    .map(Some)
    .map_err(field(s, "rcs"))
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
/// mass, which lies ℓ2 above the total one along +Z_B (review row 113). The touchdown state is
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
    crate::Soil::new(
        [k.k1, k.k2, k.k3, k.k4, k.k5, k.k6, k.k7, k.k8],
        std::f64::consts::PI * r * r,
        r,
        height,
    )
    .map(Some)
    .map_err(field(s, "surface.soil"))
}

/// A scene's curbs: (leg index, curb) in the scenario's order, and the footpad crushing
/// diagram (fig. 18) they share.
pub type SceneCurbs = (Vec<(usize, crate::Curb)>, crate::FootpadCrush);

/// The scene's curbs (eqs. 86-95); `None` when the scene has no curbs.
pub fn curbs_from_scenario(s: &Scenario) -> Result<Option<SceneCurbs>, ScenarioError> {
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
    Ok(Some((curbs, crush)))
}

/// The scene's primary-strut bending law (eqs. 40-48), if it declares one. The coupling is
/// lagged one step (review A8), which converges only while the beam is stiffer than the
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
