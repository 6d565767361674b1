//! The tolerances `touchdown compare` judges two engines' landings by.

use serde::{Deserialize, Serialize};

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
