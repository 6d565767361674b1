//! The scenario file schema (TOML), in the file's own units (`[units]`).
//!
//! Every struct rejects unknown fields. Each field's doc gives its dimension; the unit is the
//! one `[units]` declares for that dimension (e.g. "force/length" in a file with
//! `force = "lbf"`, `length = "ft"` is lbf/ft). Fields with defaults are dimensionless or zero,
//! so no default depends on the unit system; the resolved scenario written by
//! `touchdown run --out` states every default explicitly.

use crate::units::Units;
use serde::{Deserialize, Serialize};

/// Current schema version.
pub const SCHEMA_VERSION: u32 = 1;

/// A scenario file as written (after `extends` has been merged).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScenarioFile {
    /// Schema version; must be 1.
    pub schema_version: u32,
    /// Scenario file (relative to this one) whose tables this file extends and overrides.
    /// Removed once merged; the resolved scenario has none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub extends: Option<String>,
    /// Short name.
    pub name: String,
    /// What the scenario is and where its data come from.
    #[serde(default)]
    pub description: String,
    /// Unit system of every dimensional value in the file.
    pub units: Units,
    /// A dynamically similar vehicle: every dimensional value of the file, defaults included,
    /// read at these ratios of length, mass and time; absent: the file's vehicle itself.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub similarity: Option<Similarity>,
    /// The rigid vehicle.
    pub vehicle: Vehicle,
    /// Landing-gear arrangement and geometry.
    pub gear: Gear,
    /// Primary strut (same for every leg).
    pub primary_strut: PrimaryStrut,
    /// Secondary struts (same for every leg and both struts of a leg).
    pub secondary_strut: SecondaryStrut,
    /// Footpads (same for every leg).
    pub footpad: Footpad,
    /// Landing surface.
    pub surface: Surface,
    /// Touchdown (initial) conditions.
    pub touchdown: Touchdown,
    /// Integration settings.
    pub integrator: Integrator,
    /// Stability criteria, eqs. (105)-(107).
    #[serde(default)]
    pub stability: Stability,
    /// Descent-engine thrust, tailoff and nozzle crushing, eqs. (69)-(74); absent: no engine
    /// (nothing is built or evaluated).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thrust: Option<Thrust>,
    /// Reaction control system, eqs. (75)-(82); absent: no RCS.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rcs: Option<Rcs>,
    /// Propellant sloshing, appendix eqs. (108)-(117); absent: the propellant is rigid.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub slosh: Option<Slosh>,
    /// Settings of the engines other than the core (ignored by the core).
    #[serde(default)]
    pub engines: Engines,
    /// Tolerances of `touchdown compare` this landing sets (each a ratio); absent: the
    /// testbench's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub comparison: Option<Comparison>,
}

/// Ratios of a dynamically similar vehicle to the one the file describes (docs/scenario-format.md,
/// "Similarity"); each dimensionless. Every dimension follows from the three: a force scales
/// as mass·length/time², a stiffness as mass/time², a velocity as length/time, an angle not at
/// all. A Froude twin, `length` times as large under gravity g/k, has `time` = √(length·k):
/// the 1/6-scale drop-test model (Earth gravity) at full scale on the Moon is `length = 6`,
/// `time = 6`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Similarity {
    /// Length of the similar vehicle per length of the file's; dimensionless.
    pub length: f64,
    /// Mass of the similar vehicle per mass of the file's; dimensionless.
    pub mass: f64,
    /// Time of the similar vehicle per time of the file's; dimensionless.
    pub time: f64,
}

impl ScenarioFile {
    /// The units the file's numbers are read in: its `[units]` with its `[similarity]` applied
    /// (one file unit in SI; `units` alone names them). The ratios are checked positive when
    /// the file is resolved.
    pub fn read_units(&self) -> Units {
        match &self.similarity {
            None => self.units,
            Some(s) => self.units.similar(s.length, s.mass, s.time),
        }
    }
}

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

/// One honeycomb stage (cartridge).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Stage {
    /// Crush (plateau) load; force.
    pub crush_load: f64,
    /// Stroke at the end of this stage's plateau (figs. 8, 9: B, D, F); length.
    pub stroke_end: f64,
}

/// A load-stroke diagram for one loading direction (figs. 8, 9).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadStroke {
    /// Onset (elastic loading) rate K_o; force/length.
    pub onset_rate: f64,
    /// Backoff (elastic rebound) rate K_B; force/length.
    pub backoff_rate: f64,
    /// Rate beyond the end of the last stage (bottoming); force/length. The report does not
    /// specify stroke-out; give a rate well above the onset rate.
    pub stroke_out_rate: f64,
    /// Stages in loading order (1 to 3 for the primary, 1 to 4 for a secondary side).
    pub stages: Vec<Stage>,
    /// Coefficient of restitution e of this diagram's end stops (bottoming past the last
    /// stage; for the primary strut also its full-extension stop): a stop returns e² of the
    /// energy it takes and dissipates the rest; dimensionless, in [0, 1]. Default 0.5: the
    /// report gives no stroke-out law, and a bottoming honeycomb (densified core on its end
    /// fitting) or a metal end stop dissipates much of its impact; 0.5 (a quarter of the
    /// energy back) is a middle value for such impacts, not a measurement (docs/errata.md,
    /// "End stops", with what the choice moves).
    #[serde(default = "default_stop_restitution")]
    pub stop_restitution: f64,
}

fn default_stop_restitution() -> f64 {
    0.5
}

/// A trunnion spring: `"rigid"` (the load-stroke diagrams are already trunnion-modified, as
/// the report feeds them) or a spring rate (force/length) applied per eqs. (35)-(39).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(
    untagged,
    expecting = "\"rigid\" or a trunnion spring rate (a number, force/length)"
)]
pub enum Trunnion {
    /// The string "rigid".
    Rigid(RigidTag),
    /// Trunnion spring rate K_T; force/length.
    Rate(f64),
}

/// The literal `"rigid"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RigidTag {
    /// rigid
    Rigid,
}

impl Default for Trunnion {
    fn default() -> Self {
        Trunnion::Rigid(RigidTag::Rigid)
    }
}

/// Viscous law of eq. (49): F = C·sgn(v)·|v|^γ.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Viscous {
    /// C (report CP or CS); force/(length/time)^exponent.
    pub coefficient: f64,
    /// γ; dimensionless, > 0.
    pub exponent: f64,
}

impl Default for Viscous {
    fn default() -> Self {
        Viscous {
            coefficient: 0.0,
            exponent: 1.0,
        }
    }
}

/// Primary-strut bearings (fig. 14).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Bearing {
    /// Bearing friction coefficient μB; dimensionless.
    pub friction: f64,
    /// D1: inner-cylinder length, footpad to bearing 1; length.
    pub inner_cylinder_length: f64,
    /// Initial bearing separation (overlap) D2 at zero stroke; length.
    pub initial_overlap: f64,
}

/// The primary strut: compression-only honeycomb, viscous force, bearing friction.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PrimaryStrut {
    /// Compression load-stroke diagram (fig. 8), up to 3 stages.
    pub compression: LoadStroke,
    /// Trunnion spring K_TP.
    #[serde(default)]
    pub trunnion: Trunnion,
    /// Viscous law (CP, γp).
    #[serde(default)]
    pub viscous: Viscous,
    /// Bearings.
    pub bearing: Bearing,
    /// Primary-strut bending (eqs. 40-48); absent: the primary strut is rigid in bending.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bending: Option<Bending>,
}

/// Primary-strut bending as a beam-column (eqs. 40-48, corrected): the deflection of point 1
/// under the secondaries' normal load and the strut's axial load changes the secondaries'
/// apparent lengths.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Bending {
    /// Bending stiffness EI of the primary strut (uniform beam); force·length².
    pub stiffness: f64,
}

/// The secondary struts: tension and compression honeycombs (fig. 9), viscous force.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SecondaryStrut {
    /// Tension load-stroke diagram, up to 4 stages.
    pub tension: LoadStroke,
    /// Compression load-stroke diagram, up to 4 stages.
    pub compression: LoadStroke,
    /// Trunnion spring K_TS.
    #[serde(default)]
    pub trunnion: Trunnion,
    /// Viscous law (CS, γs).
    #[serde(default)]
    pub viscous: Viscous,
}

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

/// The soil model of eqs. (101)-(102) (corrected: docs/errata.md). Pressures are force/length²
/// in the file's units (the report gives psi). The footpad bottom area AP is π·PR².
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Soil {
    /// K1, bearing strength at the surface; force/length².
    pub k1: f64,
    /// K2, increase of bearing strength with penetration depth; force/length³.
    pub k2: f64,
    /// K3, increase of bearing strength with penetration rate; force·time/length³.
    #[serde(default)]
    pub k3: f64,
    /// K4, increase of bearing strength with the penetration rate squared; force·time²/length⁴.
    #[serde(default)]
    pub k4: f64,
    /// K5, static resistance to horizontal movement; force/length².
    #[serde(default)]
    pub k5: f64,
    /// K6, increase of lateral resistance with lateral displacement; force/length³.
    #[serde(default)]
    pub k6: f64,
    /// K7, increase of lateral resistance with penetration depth; force/length³.
    #[serde(default)]
    pub k7: f64,
    /// K8, increase of lateral resistance with the horizontal speed squared;
    /// force·time²/length⁴.
    #[serde(default)]
    pub k8: f64,
}

/// One curb beside a footpad (fig. 19), placed relative to the footpad's first contact point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Curb {
    /// The leg whose footpad meets this curb, 1-based in leg order.
    pub leg: usize,
    /// DWALLI: normal distance from the footpad centre to the curb at first contact; length.
    pub distance: f64,
    /// WALANG: angle from +X to the curb's normal (from the footpad toward the curb) in the
    /// surface plane; angle.
    pub angle: f64,
    /// UW: friction coefficient between the footpad and the curb; dimensionless.
    #[serde(default)]
    pub friction: f64,
}

/// The descent engine (eqs. 69-74): thrust along +Z_B through the nozzle exit centroid, its
/// tailoff, amplification near the surface and nozzle crushing.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Thrust {
    /// F1, thrust before the tailoff (eq. 69); force.
    pub thrust: f64,
    /// t2, start of the tailoff on the thrust-curve clock (fig. 15); time.
    pub tailoff_start: f64,
    /// t_p, the thrust-curve clock at touchdown (simulation time 0); time.
    #[serde(default)]
    pub clock_at_touchdown: f64,
    /// K, exponential decay rate of the tailoff (eq. 70); 1/time. Absent: no exponential term.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub decay_rate: Option<f64>,
    /// M0, M1, M2, ... polynomial tailoff coefficients (eq. 70); force, force/time,
    /// force/time², ... The curve must be continuous at t2: M0 = 0 with the exponential,
    /// M0 = F1 without it.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub polynomial: Vec<f64>,
    /// R_T, centroid of the nozzle exit plane in body axes; length.
    pub nozzle_exit: [f64; 3],
    /// AMP(ZNOZ), the thrust amplification table of fig. 16 (eq. 71); absent: AMP = 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub amplification: Option<Amplification>,
    /// Nozzle crushing (eqs. 72-73); absent: the nozzle never touches.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nozzle_crushing: Option<NozzleCrushing>,
}

/// The thrust amplification factor as a function of nozzle clearance, linear between points
/// and constant beyond the ends.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Amplification {
    /// ZNOZ, clearance of the nozzle exit centroid above the surface, increasing; length.
    pub clearance: Vec<f64>,
    /// AMP at each clearance; dimensionless.
    pub factor: Vec<f64>,
}

/// The nozzle's crushing under constant load (eqs. 72-73, docs/errata.md, "Eqs. (72)-(73): nozzle crushing").
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NozzleCrushing {
    /// Radius of the nozzle exit rim; length.
    pub exit_radius: f64,
    /// Crushing load of the whole rim, shared in proportion to the rim in contact; force.
    pub crush_load: f64,
}

/// RCS control mode of eqs. (78)-(79).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RcsMode {
    /// Attitude hold: errors from attitude and rate.
    AttitudeHold,
    /// Rate command: the attitude gains are zero.
    RateCommand,
}

/// The reaction control system (eqs. 75-82): fixed torques about each body axis switched on
/// outside a deadband, then optionally a downward translation force.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Rcs {
    /// Control mode.
    pub mode: RcsMode,
    /// k11, k21, k31: attitude gains (eq. 78); dimensionless. Ignored (zero) in rate command.
    #[serde(default)]
    pub attitude_gain: [f64; 3],
    /// k12, k22, k32: rate gains (eq. 78); time.
    pub rate_gain: [f64; 3],
    /// EXM, EYM, EZM: deadbands of the errors (eq. 79); angle.
    pub deadband: [f64; 3],
    /// TORQX, TORQY, TORQZ: torque magnitudes about the body axes; force·length.
    pub torque: [f64; 3],
    /// Cθx, Cθy, Cθz: commanded Euler angles (eq. 76); angle.
    #[serde(default)]
    pub commanded_attitude: [f64; 3],
    /// Cωx, Cωy, Cωz: commanded body rates (eq. 75); angle/time.
    #[serde(default)]
    pub commanded_rates: [f64; 3],
    /// Downward translation after a delay from first contact (eq. 81); absent: none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub downward_translation: Option<DownwardTranslation>,
}

/// The downward-translation mode: no couples, a force down the centre line.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DownwardTranslation {
    /// Delay from the first footpad contact; time.
    pub delay: f64,
    /// FRCSZ, the force along −Z_B; force.
    pub force: f64,
}

/// Propellant sloshing, first mode (appendix, eqs. 108-117, corrected): a slosh mass
/// M_s = F_s/ω² on a spring in the X_B-Y_B plane, ℓ1 + ℓ below the total centre of mass.
/// The vehicle's mass and inertia include the propellant as rigid.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Slosh {
    /// F_s, wall force per unit axial acceleration per unit amplitude (eq. 108);
    /// mass/length (F_s = M_s·ω², eq. 112).
    pub force_coefficient: f64,
    /// ω², slosh frequency squared per unit axial acceleration (eq. 109); 1/length.
    pub frequency_parameter: f64,
    /// ℓ1, from the total centre of mass down to the quiescent free surface; length.
    pub free_surface_depth: f64,
    /// ℓ, from the free surface down to the slosh mass (and the force centroid); length.
    pub mass_depth: f64,
    /// Initial slosh amplitude q (X_B, Y_B); length.
    #[serde(default)]
    pub initial_amplitude: [f64; 2],
}

/// Frame an initial attitude is given in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AttitudeReference {
    /// Relative to the horizontal (gravity frame G): composed with the slope, T_BI = T_GI·T_BG.
    Horizontal,
    /// Relative to the sloped surface (the report's inertial frame I).
    Surface,
}

/// Touchdown conditions.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Touchdown {
    /// Euler angles (θx, θy, θz), rotation order x, then y', then z'' (fig. 3); angle.
    pub attitude: [f64; 3],
    /// Frame the attitude is relative to.
    pub attitude_reference: AttitudeReference,
    /// Vertical velocity of the centre of mass along Z_G (up positive; descending is
    /// negative, as in Table I); length/time.
    pub vertical_velocity: f64,
    /// Horizontal velocity (X_G, Y_G) of the centre of mass; +Y_G is horizontal downhill;
    /// length/time.
    pub horizontal_velocity: [f64; 2],
    /// Body angular rates (ωx, ωy, ωz); angle/time.
    #[serde(default)]
    pub body_rates: [f64; 3],
    /// Height of the first footpad above its plane at the start (free flight before
    /// touchdown; not in the report, which starts at contact: used to hover under thrust, to
    /// fire the RCS or slosh in free flight); length, ≥ 0.
    #[serde(default)]
    pub clearance: f64,
}

/// Integration scheme.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Scheme {
    /// The report's linear-acceleration predictor-corrector with Δt = DIST/VEL (eqs. 20-25).
    Report,
    /// The classical fourth-order Runge–Kutta method at the fixed step `dt_max` (shortened only
    /// to land an airborne footpad on its plane and to meet the end time).
    Rk4,
    /// The Dormand–Prince 5(4) embedded Runge–Kutta pair with error control (`rtol`, `atol`),
    /// its steps within [`dt_min`, `dt_max`].
    Dopri5,
    /// The report's predictor-corrector and step rule with the gear's stiff modes taken in its
    /// stride: every strut of a footpad off the surface corrected implicitly, and a step
    /// longer than `dt_max` (up to `stride` times it) where the gear's engaged stiffness
    /// allows it (not in the report; docs/errata.md, "Long strides where the gear is soft").
    Strides,
}

/// How the core represents the vehicle's attitude.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum AttitudeForm {
    /// Euler angles θ (eqs. 3-9, the report): singular at θy = ±90°.
    #[default]
    Euler,
    /// A unit quaternion, q̇ = ½·q⊗ω: no singularity (not in the report; with the `rk4` and
    /// `dopri5` schemes only). The Euler angles are still reported, read from T_BI.
    Quaternion,
}

fn default_scheme() -> Scheme {
    Scheme::Report
}
fn yes() -> bool {
    true
}
fn default_energy_tolerance() -> f64 {
    0.02
}
/// Default run budget, accepted steps (`integrator.max_steps`): about 10 s of the core, a few
/// minutes of a multibody engine; a Table I landing takes about a thousand steps on the core
/// and a hundred thousand on a multibody engine at 20 µs.
pub const DEFAULT_MAX_STEPS: f64 = 1e7;
fn default_max_steps() -> f64 {
    DEFAULT_MAX_STEPS
}
fn default_rtol() -> f64 {
    1e-6
}
fn default_atol() -> f64 {
    1e-9
}
/// The longest step of the `strides` scheme as a multiple of `dt_max`, unless the file sets
/// `integrator.stride`.
pub const DEFAULT_STRIDE: f64 = 8.0;
/// The `strides` scheme's ω·Δt on the gear's stiffest engaged mode (its trace bound), unless the
/// file sets `integrator.mode_step`: the report's scheme is stable to 2.
pub const DEFAULT_MODE_STEP: f64 = 1.0;

/// Integration settings (eqs. 20-25).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Integrator {
    /// "report" (default), "strides", "rk4" or "dopri5".
    #[serde(default = "default_scheme")]
    pub scheme: Scheme,
    /// DIST: allowed relative movement between any footpad and the centre of mass per step
    /// (the `report` scheme's step rule, eq. 25); length.
    pub dist: f64,
    /// Smallest step; time.
    pub dt_min: f64,
    /// Largest step; time. Keep it well below 2/ω of the stiffest strut mode.
    pub dt_max: f64,
    /// End time of the run (unless the stability criteria end it earlier); time.
    pub t_end: f64,
    /// Shorten a step so that an airborne footpad lands on its surface plane instead of
    /// overshooting it (not in the report; docs/errata.md, "Eq. (25): VEL and first contacts").
    #[serde(default = "yes")]
    pub contact_step_limit: bool,
    /// Divergence guard: stop when the energy residual exceeds this fraction of the energy
    /// put in (touchdown kinetic energy, potential energy released, thrust and RCS input);
    /// dimensionless.
    #[serde(default = "default_energy_tolerance")]
    pub energy_tolerance: f64,
    /// Run budget: the most accepted steps a landing takes on any engine (ten times as many
    /// force evaluations on the core); a run that reaches it stops with a diagnostic, and a
    /// multibody step that could not reach `t_end` within it is refused (default 1e7).
    #[serde(default = "default_max_steps")]
    pub max_steps: f64,
    /// "euler" (default) or "quaternion" (`rk4` and `dopri5` only).
    #[serde(default)]
    pub attitude: AttitudeForm,
    /// `dopri5`: relative error tolerance per step; dimensionless (default 1e-6).
    #[serde(default = "default_rtol")]
    pub rtol: f64,
    /// `dopri5`: absolute error tolerance per step, applied to every state component in SI
    /// units (m, m/s, rad, rad/s; whatever the file's units); default 1e-9.
    #[serde(default = "default_atol")]
    pub atol: f64,
    /// `strides`: the longest step as a multiple of `dt_max` (dimensionless, ≥ 1; default
    /// [`DEFAULT_STRIDE`]); the step goes past `dt_max` only where the gear's engaged
    /// stiffness allows it (docs/errata.md, "Long strides where the gear is soft").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stride: Option<f64>,
    /// `strides`: the largest ω·Δt a step may reach on the gear's stiffest engaged mode, ω
    /// from the trace bound of the vehicle on its struts (dimensionless, in (0, 2); default
    /// [`DEFAULT_MODE_STEP`]; docs/errata.md, "Long strides where the gear is soft").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mode_step: Option<f64>,
}

impl Integrator {
    /// The settings refined by `factor` (> 1) for the scheme they name: every step limit
    /// (`dt_max`, and `dt_min` where it would exceed it) divided by `factor`; the report's step
    /// rule also takes DIST ÷ `factor` (eq. 25: Δt = DIST/VEL), and the `strides` scheme also
    /// its `mode_step` ÷ `factor` (its step on the gear's modes, Δt = mode_step/ω, with the
    /// longest, `stride`·`dt_max`, ÷ `factor` through `dt_max`); the Dormand–Prince pair also
    /// takes `rtol` and `atol` ÷ `factor`⁵ (its local error is of fifth order in the step: the
    /// same local error as a step `factor` times shorter). The run's budget of steps,
    /// `max_steps`, grows by `factor`: a refined run is the same landing in more steps.
    pub fn refine(&mut self, factor: f64) {
        self.max_steps *= factor;
        self.dt_max /= factor;
        self.dt_min = self.dt_min.min(self.dt_max);
        match self.scheme {
            Scheme::Report => self.dist /= factor,
            Scheme::Strides => {
                self.dist /= factor;
                self.mode_step = Some(self.mode_step.unwrap_or(DEFAULT_MODE_STEP) / factor);
            }
            Scheme::Rk4 => {}
            Scheme::Dopri5 => {
                let tolerance = factor.powi(5);
                self.rtol /= tolerance;
                self.atol /= tolerance;
            }
        }
    }
}

/// Which stability walls count for the unstable declaration.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum WallRule {
    /// Every wall between adjacent footpads (the report).
    All,
    /// Only walls whose two footpads have both touched down (avoids false alarms while
    /// footpads are still airborne; docs/errata.md, "Eqs. (105)-(107): stability — interpreted").
    TouchedDown,
}

/// The energy condition 1 compares with the touchdown kinetic energy.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CountedEnergy {
    /// The vehicle's kinetic energy alone (the report's text).
    Kinetic,
    /// The kinetic energy plus the elastic energy stored in the honeycombs, which the gear
    /// returns to the vehicle as it unloads (docs/errata.md: an elastic stroke-out stop can
    /// hold most of the touchdown energy for a few milliseconds).
    KineticAndStored,
}

fn default_counted_energy() -> CountedEnergy {
    CountedEnergy::KineticAndStored
}
fn default_walls() -> WallRule {
    WallRule::All
}
fn default_ke_fraction() -> f64 {
    0.1
}

/// Stability criteria (eqs. 105-107 and the four conditions of the text).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Stability {
    /// Condition 1: kinetic energy below this fraction of the touchdown kinetic energy;
    /// dimensionless.
    #[serde(default = "default_ke_fraction")]
    pub kinetic_energy_fraction: f64,
    /// Condition 1: the energy compared with the touchdown kinetic energy.
    #[serde(default = "default_counted_energy")]
    pub counted_energy: CountedEnergy,
    /// Condition 4: the centre of mass moves away from the critical wall at least this fast;
    /// length/time.
    #[serde(default)]
    pub min_separation_velocity: f64,
    /// Walls counted for the unstable declaration.
    #[serde(default = "default_walls")]
    pub walls: WallRule,
    /// End the run when the centre of mass crosses a wall (the landing is unstable). A stable
    /// landing always runs to its end time, so that no maximum is cut short.
    #[serde(default = "yes")]
    pub terminate_on_decision: bool,
}

impl Default for Stability {
    fn default() -> Self {
        Stability {
            kinetic_energy_fraction: default_ke_fraction(),
            counted_energy: default_counted_energy(),
            min_separation_velocity: 0.0,
            walls: default_walls(),
            terminate_on_decision: true,
        }
    }
}

/// The tolerances `touchdown compare` judges two engines' landings by, each a dimensionless
/// ratio as docs/engines.md ("Comparing the engines") measures its channel: a field left out
/// keeps the testbench's tolerance, which the same page gives with its reason.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Comparison {
    /// Maximum primary strokes; dimensionless (fraction of the larger maximum).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub primary_stroke: Option<f64>,
    /// Maximum secondary strokes; dimensionless (fraction of the larger maximum).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub secondary_stroke: Option<f64>,
    /// Peak pitch rate; dimensionless (fraction of the larger peak).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub peak_pitch_rate: Option<f64>,
    /// Time of the peak pitch rate; dimensionless (fraction of the vehicle's time scale).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub peak_pitch_rate_time: Option<f64>,
    /// RMS difference of the pitch-rate histories; dimensionless (fraction of the peak).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pitch_rate_history_rms_difference: Option<f64>,
    /// Largest difference of the pitch-rate histories; dimensionless (fraction of the peak).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pitch_rate_history_largest_difference: Option<f64>,
    /// Peak vertical acceleration; dimensionless (fraction of the larger peak).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub peak_vertical_acceleration: Option<f64>,
    /// Minimum stability distance; dimensionless (fraction of the footprint radius).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_stability_distance: Option<f64>,
    /// Overturning velocity; dimensionless (fraction of the vehicle's velocity scale).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub overturn_velocity: Option<f64>,
    /// Strokes past capacity; dimensionless (fraction of the capacity).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub past_capacity: Option<f64>,
    /// Energy per account; dimensionless (fraction of the touchdown kinetic energy).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub energy: Option<f64>,
}

impl Comparison {
    /// Each tolerance the file sets, with its field name (the quantity of its channel).
    pub fn set(&self) -> impl Iterator<Item = (&'static str, f64)> {
        [
            ("primary_stroke", self.primary_stroke),
            ("secondary_stroke", self.secondary_stroke),
            ("peak_pitch_rate", self.peak_pitch_rate),
            ("peak_pitch_rate_time", self.peak_pitch_rate_time),
            (
                "pitch_rate_history_rms_difference",
                self.pitch_rate_history_rms_difference,
            ),
            (
                "pitch_rate_history_largest_difference",
                self.pitch_rate_history_largest_difference,
            ),
            (
                "peak_vertical_acceleration",
                self.peak_vertical_acceleration,
            ),
            ("min_stability_distance", self.min_stability_distance),
            ("overturn_velocity", self.overturn_velocity),
            ("past_capacity", self.past_capacity),
            ("energy", self.energy),
        ]
        .into_iter()
        .filter_map(|(name, v)| v.map(|v| (name, v)))
    }
}

/// An engine of the testbench.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Engine {
    /// The report-faithful core.
    Core,
    /// The rapier multibody rebuild.
    Rapier,
    /// The MuJoCo model driven by the shared laws.
    Mujoco,
}

impl Engine {
    /// Every engine, in comparison order.
    pub const ALL: [Engine; 3] = [Engine::Core, Engine::Rapier, Engine::Mujoco];

    /// The engine's name, as in scenario files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Engine::Core => "core",
            Engine::Rapier => "rapier",
            Engine::Mujoco => "mujoco",
        }
    }
}

impl std::fmt::Display for Engine {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Engine {
    type Err = String;
    fn from_str(s: &str) -> Result<Engine, String> {
        Engine::ALL
            .into_iter()
            .find(|e| e.name() == s)
            .ok_or_else(|| {
                let names: Vec<&str> = Engine::ALL.iter().map(|e| e.name()).collect();
                format!("unknown engine {s:?}; expected one of {}", names.join(", "))
            })
    }
}

fn all_engines() -> Vec<Engine> {
    Engine::ALL.to_vec()
}

/// The engines that apply to the scenario, and the settings of those other than the core.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Engines {
    /// The engines that apply to this scenario (`touchdown run` refuses the others and
    /// `touchdown compare` leaves them out); default all three.
    #[serde(default = "all_engines")]
    pub applicable: Vec<Engine>,
    /// The rapier multibody rebuild (`touchdown run --engine rapier`).
    #[serde(default)]
    pub rapier: Rapier,
    /// The MuJoCo export (`touchdown export-mjcf`, `touchdown run --engine mujoco`).
    #[serde(default)]
    pub mujoco: Mujoco,
    /// The gear links the multibody engines (rapier, MuJoCo) add to the report's massless gear.
    #[serde(default)]
    pub links: GearLinks,
}

impl Default for Engines {
    fn default() -> Self {
        Engines {
            applicable: all_engines(),
            rapier: Rapier::default(),
            mujoco: Mujoco::default(),
            links: GearLinks::default(),
        }
    }
}

fn one() -> f64 {
    1.0
}
fn default_outer_cylinder_mass_ratio() -> f64 {
    0.1
}
fn default_link_radius_ratio() -> f64 {
    0.03
}

/// The rapier multibody rebuild (docs/engines.md): solver settings. A setting left out is
/// derived from the scenario's own scales (docs/engines.md, "Step and contact from the
/// scenario's scale"), so that no default depends on the vehicle's size.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Rapier {
    /// Fixed time step; time. The strut laws are applied explicitly once per step, so keep
    /// ω·timestep well below 2 for the stiffest strut mode (checked at start-up). Absent: 0.16
    /// over the stiffest gear mode's angular frequency.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub timestep: Option<f64>,
    /// Natural frequency of the footpad contact constraint (rapier's contact softness, used for
    /// both its moving-body and fixed-body settings); 1/time (Hz). High, so that the footpads do
    /// not sink: the contact must be much stiffer than the stiffest strut law. Absent: four times
    /// the stiffest gear mode's frequency.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact_frequency: Option<f64>,
    /// Damping ratio of the footpad contact constraint; dimensionless.
    #[serde(default = "one")]
    pub contact_damping_ratio: f64,
}

impl Default for Rapier {
    fn default() -> Self {
        Rapier {
            timestep: None,
            contact_frequency: None,
            contact_damping_ratio: one(),
        }
    }
}

/// The gear links of the multibody engines: the masses they add to the report's massless gear
/// (stated in every multibody summary). Dimensionless.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GearLinks {
    /// Mass of each primary outer-cylinder link as a fraction of the effective footpad mass;
    /// dimensionless (the report's gear is massless; the link needs some mass).
    #[serde(default = "default_outer_cylinder_mass_ratio")]
    pub outer_cylinder_mass_ratio: f64,
    /// Radius of the gear links' solid-cylinder inertia as a fraction of the primary strut
    /// length L2P; dimensionless.
    #[serde(default = "default_link_radius_ratio")]
    pub link_radius_ratio: f64,
}

impl Default for GearLinks {
    fn default() -> Self {
        GearLinks {
            outer_cylinder_mass_ratio: default_outer_cylinder_mass_ratio(),
            link_radius_ratio: default_link_radius_ratio(),
        }
    }
}

/// The MuJoCo export (docs/engines.md). A setting left out is derived from the scenario's own
/// scales (docs/engines.md, "Step and contact from the scenario's scale").
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Mujoco {
    /// Fixed time step (`option/timestep`); time. The strut laws are applied explicitly once
    /// per step, as in the rapier rebuild. Absent: 0.16 over the stiffest gear mode's angular
    /// frequency.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub timestep: Option<f64>,
    /// Time constant of the footpad contacts (`solref[0]`, on both geoms of every pair); time.
    /// Small, so that footpads do not sink; MuJoCo needs it at least twice the time step.
    /// Absent: twice the time step.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact_timeconst: Option<f64>,
    /// Damping ratio of the footpad contacts (`solref[1]`); dimensionless.
    #[serde(default = "one")]
    pub contact_damping_ratio: f64,
    /// Penetration over which the footpad contacts' impedance rises from 0.99 to 0.999
    /// (`solimp[2]`); length. Absent: a tenth of the contact sphere's radius.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact_width: Option<f64>,
}

impl Default for Mujoco {
    fn default() -> Self {
        Mujoco {
            timestep: None,
            contact_timeconst: None,
            contact_damping_ratio: one(),
            contact_width: None,
        }
    }
}
