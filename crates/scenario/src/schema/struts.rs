//! The primary and secondary struts: load-stroke diagrams, trunnions, viscous law, bearings.

use serde::{Deserialize, Serialize};

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
