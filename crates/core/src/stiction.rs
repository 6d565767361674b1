//! The primary strut's bearing friction on a footpad off the surface (eqs. 59-63, extended:
//! docs/errata.md, "Footpads with inertia", "Bearing friction off the surface"). In contact the
//! surface fixes the footpad and the stroking rate follows from the vehicle's motion, so the
//! report's kinetic friction μB·(F1 + F2)·sgn(ċ) applies. Off the surface the stroke is a
//! degree of freedom of the footpad's own mass: a kinetic law whose sign flips with ċ would make
//! it chatter about ċ = 0 at the step rate. There the friction is what holds the stroke (the
//! force that brings the stroking to rest over [`relaxation`], given every other force on the
//! footpad and the vehicle's acceleration), as long as that is within the bound μB·(F1 + F2);
//! beyond it, the bound, opposing the stroking.

use crate::gear::{GearState, PrimaryAxis};
use crate::model::Model;
use crate::vehicle::VehicleState;
use nalgebra::Vector3;
use touchdown_laws::GearLaws;

/// The time over which the bearing friction brings a footpad's stroking to rest off the
/// surface, s: 1/ω of the footpad on the honeycombs' rebound rates K_B (the struts' elastic
/// stiffness, a constant of the laws, so that no decision at rounding level sets it),
/// ω² = (K_B,2P + K_B,31 + K_B,41)/PMASS, the secondaries' stiffer side.
pub(crate) fn relaxation(laws: &GearLaws, footpad_mass: f64) -> f64 {
    let s = &laws.secondary.honeycomb;
    let k = laws.primary.honeycomb.backoff_rate
        + 2.0 * s.tension.backoff_rate.max(s.compression.backoff_rate);
    (footpad_mass / k).sqrt()
}

/// A footpad off the surface whose bearing friction is to be set once the vehicle's
/// acceleration is known: its leg, its body-frame position BP (m) and velocity relative to the
/// body (m/s), both in body axes, and its primary strut as its gear's evaluation found it
/// (eqs. 27-28).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Held {
    pub(crate) leg: usize,
    pub(crate) bp: Vector3<f64>,
    pub(crate) bp_dot: Vector3<f64>,
    pub(crate) primary: PrimaryAxis,
}

/// The bearing friction FBR (N, compression positive) on the primary strut of the footpad `h`
/// off the surface of `model` (`walled` while its obstacle's wall holds it), its gear in state `g` evaluated without friction, the vehicle at `v`
/// accelerating at `acceleration` (m/s², inertial, gravity included) and `omega_dot`
/// (rad/s², body): the force that makes the compression rate ċ relax to zero with the time
/// constant [`relaxation`], clamped to the
/// bound μB·(F1 + F2) of eq. (63). The footpad's acceleration is its gear's force over its
/// mass plus gravity, vertical only while its obstacle's wall holds it.
#[inline]
pub(crate) fn held_friction(
    model: &Model,
    walled: bool,
    h: &Held,
    g: &GearState,
    v: &VehicleState,
    acceleration: &Vector3<f64>,
    omega_dot: &Vector3<f64>,
) -> Result<f64, touchdown_laws::LawError> {
    let bound = (model.laws.primary.bearing).friction_bound(g.fm, g.primary_stroke)?;
    if bound == 0.0 {
        return Ok(0.0);
    }
    let (bp, bp_dot, w) = (h.bp, h.bp_dot, v.omega);
    let (e, len) = (h.primary.axis, h.primary.length);
    let c_dot = -e.dot(&bp_dot);
    let across = bp_dot - e * e.dot(&bp_dot);
    // The footpad's inertial acceleration per unit of FBR along T_BI·ê, and without it.
    let m = model.footpad_mass;
    let project = |f: Vector3<f64>| {
        if walled {
            Vector3::new(0.0, 0.0, f.z)
        } else {
            f
        }
    };
    let e_inertial = v.t_bi * e;
    let per_unit = e_inertial.dot(&project(e_inertial)) / m;
    if per_unit <= 0.0 {
        // A walled footpad on a horizontal strut: friction cannot move it; kinetic law.
        return (model.laws.primary.bearing).friction(g.fm, g.primary_stroke, c_dot);
    }
    let free = e_inertial.dot(&project(v.t_bi * g.fp / m + model.gravity));
    // c̈ = −ê·B̈P − |ḂP⊥|²/|BP − B2|, with
    // ê·B̈P = ê·T_IB·(P̈ − R̈) − ê·(2ω×ḂP + ω̇×BP + ω×(ω×BP)); set c̈ = −ċ/τ.
    let frame = e.dot(&(w.cross(&bp_dot) * 2.0 + omega_dot.cross(&bp) + w.cross(&w.cross(&bp))));
    let relax = c_dot / model.held_relaxation;
    let wanted = relax - across.norm_squared() / len + e_inertial.dot(acceleration) + frame;
    let required = (wanted - free) / per_unit;
    Ok(required.clamp(-bound, bound))
}
