//! The touchdown (initial) conditions: attitude, velocities and clearance.

use serde::{Deserialize, Serialize};

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
