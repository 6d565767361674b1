//! The scenario file schema (TOML), in the file's own units (`[units]`).
//!
//! Every struct rejects unknown fields. Each field's doc gives its dimension; the unit is the
//! one `[units]` declares for that dimension (e.g. "force/length" in a file with
//! `force = "lbf"`, `length = "ft"` is lbf/ft). Fields with defaults are dimensionless or zero,
//! so no default depends on the unit system; the resolved scenario written by
//! `touchdown run --out` states every default explicitly.

mod comparison;
mod engines;
mod integrator;
mod mechanisms;
mod stability;
mod struts;
mod surface;
mod touchdown;
mod vehicle;

pub use comparison::Comparison;
pub use engines::{Engine, Engines, GearLinks, Mujoco, Rapier};
pub use integrator::{
    AttitudeForm, Integrator, Scheme, ACCURACY_REFINEMENT, DEFAULT_MAX_STEPS, DEFAULT_MODE_STEP,
    DEFAULT_STRIDE,
};
pub use mechanisms::{
    Amplification, Curb, DownwardTranslation, NozzleCrushing, Rcs, RcsMode, Slosh, Soil, Thrust,
};
pub use stability::{CountedEnergy, Stability, WallRule};
pub use struts::{
    Bearing, Bending, LoadStroke, PrimaryStrut, RigidTag, SecondaryStrut, Stage, Trunnion, Viscous,
};
pub use surface::{Detached, Footpad, PerPad, ReleaseRule, Surface, SurfaceKind};
pub use touchdown::{AttitudeReference, Touchdown};
pub use vehicle::{Arrangement, BetaConvention, Gear, Inertia, Leg, Parametric, Vehicle};

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

// The serde default of `integrator.contact_step_limit` and `stability.terminate_on_decision`.
fn yes() -> bool {
    true
}
