//! The footpads and the landing surface they meet: slope, holes, restraints, friction.

use super::{Curb, LoadStroke, Soil};
use serde::{Deserialize, Serialize};

/// Effective footpad.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Footpad {
    /// Effective footpad mass PMASS; mass.
    pub mass: f64,
    /// Undeformed footpad radius PR; length.
    pub radius: f64,
    /// Footpad height (the cylinder's height bounds the frontal area APF of eq. 102 in soil);
    /// length. Required with a soil surface.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<f64>,
    /// Footpad crushing against curbs (fig. 18): a load-deflection diagram with memory, in the
    /// honeycomb format (onset, plateaus, backoff, stroke-out). Required with curbs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub crush: Option<LoadStroke>,
    /// How a footpad moves off the surface (default `inertial`; `rigid` is the report's;
    /// docs/errata.md, "Footpads with inertia").
    #[serde(default)]
    pub detached: Detached,
}

/// How a footpad moves when it is not on its surface (docs/errata.md, "Footpads with
/// inertia").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Detached {
    /// The report's footpad (text after eq. 100): attached rigidly to the vehicle by its
    /// massless gear, whose struts relax to zero force when it leaves the surface
    /// (`surface.release` says when).
    Rigid,
    /// A point mass PMASS in every phase (eqs. 16-18): off the surface it moves under its
    /// gear's force and its weight, its struts keep their strokes and loads, it leaves when the
    /// surface would have to pull and lands again as a plastic impact of its own mass; its
    /// obstacle's wall holds it laterally until it rises above the wall.
    #[default]
    Inertial,
}

/// Zero for every footpad: no obstacle, no spikes.
fn none_per_pad() -> PerPad {
    PerPad::All(0.0)
}

/// A per-footpad value: one number for every footpad, or a list with one per leg.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(
    untagged,
    expecting = "one number for every footpad or a list of numbers, one per leg"
)]
pub enum PerPad {
    /// Same value for every footpad.
    All(f64),
    /// One value per leg, in leg order.
    Each(Vec<f64>),
}

/// Surface kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SurfaceKind {
    /// Rigid surface (eqs. 85-100).
    Rigid,
    /// Non-rigid surface (soil), eqs. (101)-(104), with the constants of `[surface.soil]`.
    Soil,
}

/// What keeps a footpad in contact with its surface (docs/errata.md, "Contact and
/// release"): it stays while its gear presses it onto the surface and leaves as soon as it does
/// not, whatever its tentative rigid height. The rules differ in the force that stands for
/// "presses".
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ReleaseRule {
    /// The normal component of the gear's force on the footpad (FZI of eqs. 85 and 103, the
    /// gear pressing the footpad into the surface) is positive: the physical condition, since
    /// a surface cannot pull.
    GearForce,
    /// The primary-strut force F2P = FCP + FVP + FBR is compressive (the report's "compressive
    /// forces remain", a stand-in for the normal force).
    StrutForce,
    /// The primary honeycomb force FCP is compressive (the strut is not back at its permanent
    /// set).
    HoneycombForce,
}

fn default_release() -> ReleaseRule {
    ReleaseRule::GearForce
}

/// Landing surface: the inertial X-Y plane, sloped by α about X (+Y is downhill).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Surface {
    /// "rigid".
    pub kind: SurfaceKind,
    /// Slope α (eq. 1); angle. Gravity in the surface frame is (0, g·sin α, −g·cos α).
    pub slope: f64,
    /// HOLE_n: depth of the local surface plane below Z = 0 under each footpad (> 0 is a
    /// depression); length.
    pub hole: PerPad,
    /// OBST_n: > 0 an obstacle's wall this high holds the footpad laterally after contact
    /// until it rises OBST above its plane (fig. 17); ≤ 0 none (default); length.
    #[serde(default = "none_per_pad")]
    pub obstacle: PerPad,
    /// Spikes under the footpad that penetrate the surface (the 1/6-scale model's, on
    /// plywood): > 0 holds the footpad laterally from its landing while it is within this
    /// engagement depth of its plane, and lets it go when it lifts out; 0 none (default);
    /// length. A footpad held by neither slides with Coulomb friction.
    #[serde(default = "none_per_pad")]
    pub spike_depth: PerPad,
    /// U_n: sliding friction coefficient; dimensionless.
    pub friction: PerPad,
    /// What keeps a footpad in contact (default `gear_force`).
    #[serde(default = "default_release")]
    pub release: ReleaseRule,
    /// Soil constants K1-K8 (eqs. 101-102); required with `kind = "soil"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub soil: Option<Soil>,
    /// Curbs on the rigid surface (eqs. 86-95), at most two per footpad; default none.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub curbs: Vec<Curb>,
}
