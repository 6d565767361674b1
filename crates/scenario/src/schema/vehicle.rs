//! The rigid vehicle and its landing gear's arrangement and geometry (legs or parameters).

use serde::{Deserialize, Serialize};

/// The idealised rigid vehicle (report M, I, g).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Vehicle {
    /// Rigid-vehicle mass M, excluding the effective footpad masses; mass.
    pub mass: f64,
    /// Inertia tensor about the centre of mass in body axes.
    pub inertia: Inertia,
    /// Magnitude of the gravitational acceleration g; length/time².
    pub gravity: f64,
}

/// Inertia about the centre of mass, body axes; mass·length². Products of inertia follow the
/// report: Ixy = ∫xy dm (so the tensor is [[Ixx, −Ixy, −Ixz], [−Ixy, Iyy, −Iyz], ...]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Inertia {
    /// Ixx; mass·length².
    pub xx: f64,
    /// Iyy; mass·length².
    pub yy: f64,
    /// Izz; mass·length².
    pub zz: f64,
    /// Ixy = ∫xy dm; mass·length².
    #[serde(default)]
    pub xy: f64,
    /// Ixz = ∫xz dm; mass·length².
    #[serde(default)]
    pub xz: f64,
    /// Iyz = ∫yz dm; mass·length².
    #[serde(default)]
    pub yz: f64,
}

/// Landing-gear arrangement (fig. 4).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Arrangement {
    /// Secondary struts attached to the primary outer cylinder at point 1 (the LM gear).
    Cantilever,
    /// Inverted tripod: secondary struts attached at the footpad (B1 = BP; eqs. 29-30, 64-65
    /// rows of the review: no bearing side load, no bending).
    Tripod,
}

/// Gear arrangement and geometry: give exactly one of `legs` (points directly) or
/// `parametric` (the report's R1..ZC, β parameterisation).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Gear {
    /// "cantilever" or "tripod".
    pub arrangement: Arrangement,
    /// Per-leg points in body axes (origin at the centre of mass), listed counter-clockwise
    /// seen from above (+Z_B): the stability walls join consecutive legs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub legs: Option<Vec<Leg>>,
    /// The report's parameterisation (fig. 23).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub parametric: Option<Parametric>,
}

/// One leg's points in body axes (origin at the rigid-vehicle centre of mass); length.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Leg {
    /// B2: primary-strut upper trunnion; length.
    pub b2: [f64; 3],
    /// B3: first secondary-strut trunnion; length.
    pub b3: [f64; 3],
    /// B4: second secondary-strut trunnion; length.
    pub b4: [f64; 3],
    /// BP: footpad ball joint, undeformed gear; length.
    pub bp: [f64; 3],
    /// L21: distance from B2 along the primary strut to the secondary attachment point 1;
    /// length. Required for the cantilever arrangement; the tripod has none (point 1 is the
    /// footpad).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub l21: Option<f64>,
}

/// How β places the secondary trunnions (fig. 23(b) is missing; both readings are kept).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BetaConvention {
    /// B3, B4 = (R2·cos β, ±R2·sin β, Z2): β is the trunnions' azimuth from the leg plane.
    TrunnionAzimuth,
    /// B3, B4 = (R2, ±(x1 − R2)·tan β, Z2): β is the top-view angle of each secondary strut
    /// from the leg plane, x1 being the radius of point 1.
    StrutAngle,
}

/// The report's gear parameterisation (fig. 23, values in its text). Leg frame: x radial along
/// the leg, z up, datum z = 0 at the undeformed footpad plane; the body origin is the centre of
/// mass at height ZC. B2 = (R1, 0, Z3), BP = (R3, 0, 0), point 1 on the primary axis at height
/// Z1 (so L21 follows), B3/B4 per `beta_convention`. Each leg is this frame rotated about Z_B by
/// its azimuth. The tripod takes the same form without Z1: its point 1 is the footpad (so
/// `strut_angle` reads x1 = R3).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Parametric {
    /// R1: radius of the primary trunnion B2; length.
    pub r1: f64,
    /// R2: radius of the secondary trunnions; length.
    pub r2: f64,
    /// R3: radius of the footpad BP; length.
    pub r3: f64,
    /// Z1: height of the secondary attachment point 1 above the footpad plane; length.
    /// Required for the cantilever; the tripod has none (its point 1 is the footpad).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub z1: Option<f64>,
    /// Z2: height of the secondary trunnions; length.
    pub z2: f64,
    /// Z3: height of the primary trunnion; length.
    pub z3: f64,
    /// ZC: height of the centre of mass; length.
    pub zc: f64,
    /// β: secondary strut angle (fig. 23(b)); angle.
    pub beta: f64,
    /// Reading of β.
    pub beta_convention: BetaConvention,
    /// Azimuth of each leg, from +X_B toward +Y_B, counter-clockwise seen from above; angle.
    pub leg_azimuths: Vec<f64>,
}
