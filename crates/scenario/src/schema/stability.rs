//! The stability criteria: the energy, wall and separation conditions.

use super::yes;
use serde::{Deserialize, Serialize};

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
    /// End a stable landing early once no maximum stroke can grow by more than this length
    /// and no overturn is reachable (the core's settled end: docs/errata.md, "Settled
    /// landings: an early end with a proof"); length. Absent: every landing runs to its end
    /// time.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub settled_tolerance: Option<f64>,
}

impl Default for Stability {
    fn default() -> Self {
        Stability {
            kinetic_energy_fraction: default_ke_fraction(),
            counted_energy: default_counted_energy(),
            min_separation_velocity: 0.0,
            walls: default_walls(),
            terminate_on_decision: true,
            settled_tolerance: None,
        }
    }
}
