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
    /// Settings of the engines other than the core (ignored by the core).
    #[serde(default)]
    pub engines: Engines,
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
    /// Inverted tripod: secondary struts attached at the footpad (not yet supported by the core).
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
    /// L21: distance from B2 along the primary strut to the secondary attachment point 1; length.
    pub l21: f64,
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
/// its azimuth.
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
    pub z1: f64,
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
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Footpad {
    /// Effective footpad mass PMASS; mass.
    pub mass: f64,
    /// Undeformed footpad radius PR; length.
    pub radius: f64,
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
}

/// When a footpad that lifts off leaves the surface (review A2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ReleaseRule {
    /// When the primary-strut force F2P = FCP + FVP + FBR is no longer compressive (literal).
    StrutForce,
    /// When the honeycomb force FCP is zero (the strut is back at its permanent set).
    HoneycombForce,
}

fn default_release() -> ReleaseRule {
    ReleaseRule::StrutForce
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
    /// OBST_n: > 0 locks the footpad laterally after contact until it rises OBST above its
    /// plane; ≤ 0 lets it slide with Coulomb friction; length.
    pub obstacle: PerPad,
    /// U_n: sliding friction coefficient; dimensionless.
    pub friction: PerPad,
    /// When a footpad lifting off leaves the surface.
    #[serde(default = "default_release")]
    pub release: ReleaseRule,
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
}

/// Integration scheme.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Scheme {
    /// The report's linear-acceleration predictor-corrector with Δt = DIST/VEL (eqs. 20-25).
    Report,
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

/// Integration settings (eqs. 20-25).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Integrator {
    /// "report".
    #[serde(default = "default_scheme")]
    pub scheme: Scheme,
    /// DIST: allowed relative movement between any footpad and the centre of mass per step;
    /// length.
    pub dist: f64,
    /// Smallest step; time.
    pub dt_min: f64,
    /// Largest step; time. Keep it well below 2/ω of the stiffest strut mode.
    pub dt_max: f64,
    /// End time of the run (unless the stability criteria end it earlier); time.
    pub t_end: f64,
    /// Shorten a step so that an airborne footpad lands on its surface plane instead of
    /// overshooting it (not in the report; review A12).
    #[serde(default = "yes")]
    pub contact_step_limit: bool,
    /// Divergence guard: stop when the energy residual exceeds this fraction of the energy
    /// scale (initial kinetic energy plus all energy exchanged); dimensionless.
    #[serde(default = "default_energy_tolerance")]
    pub energy_tolerance: f64,
}

/// Which stability walls count for the unstable declaration.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum WallRule {
    /// Every wall between adjacent footpads (the report).
    All,
    /// Only walls whose two footpads have both touched down (avoids false alarms while
    /// footpads are still airborne; review A16).
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
    /// End the run as soon as the landing is declared stable or unstable.
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
            .ok_or_else(|| format!("unknown engine {s:?}; expected core, rapier or mujoco"))
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

/// Default fixed time step of the multibody engines, s.
fn default_rapier_timestep() -> f64 {
    2.0e-5
}
fn default_contact_frequency() -> f64 {
    5000.0
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

/// The rapier multibody rebuild (docs/engines.md): solver settings and the masses it adds to the
/// report's massless gear. Every default is in seconds or dimensionless.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Rapier {
    /// Fixed time step; time. The strut laws are applied explicitly once per step, so keep
    /// ω·timestep well below 2 for the stiffest strut mode (checked at start-up).
    #[serde(default = "default_rapier_timestep")]
    pub timestep: f64,
    /// Natural frequency of the footpad contact constraint (rapier's contact softness, used for
    /// both its moving-body and fixed-body settings); 1/time (Hz). High, so that the footpads do
    /// not sink: the contact must be much stiffer than the stiffest strut law.
    #[serde(default = "default_contact_frequency")]
    pub contact_frequency: f64,
    /// Damping ratio of the footpad contact constraint; dimensionless.
    #[serde(default = "one")]
    pub contact_damping_ratio: f64,
}

impl Default for Rapier {
    fn default() -> Self {
        Rapier {
            timestep: default_rapier_timestep(),
            contact_frequency: default_contact_frequency(),
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

fn default_mujoco_contact_timeconst() -> f64 {
    4.0e-5
}

/// The MuJoCo export (docs/engines.md). Every default is in seconds or dimensionless.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Mujoco {
    /// Fixed time step (`option/timestep`); time. The strut laws are applied explicitly once
    /// per step, as in the rapier rebuild.
    #[serde(default = "default_rapier_timestep")]
    pub timestep: f64,
    /// Time constant of the footpad contacts (`solref[0]`, on both geoms of every pair); time.
    /// Small, so that footpads do not sink; MuJoCo needs it at least twice the time step.
    #[serde(default = "default_mujoco_contact_timeconst")]
    pub contact_timeconst: f64,
    /// Damping ratio of the footpad contacts (`solref[1]`); dimensionless.
    #[serde(default = "one")]
    pub contact_damping_ratio: f64,
}

impl Default for Mujoco {
    fn default() -> Self {
        Mujoco {
            timestep: default_rapier_timestep(),
            contact_timeconst: default_mujoco_contact_timeconst(),
            contact_damping_ratio: one(),
        }
    }
}
