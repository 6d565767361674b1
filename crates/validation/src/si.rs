//! The report's units turned to SI where a document is written (docs/outputs.md, "The
//! convention"): Table I states strokes in inches and velocities in ft/s, and the validation
//! computes in them so that every figure it prints is the report's; its JSON is SI with the
//! unit in each name (`experiment_m`, `vv_m_s`).

use serde::Serializer;

/// Metres per inch.
pub const INCH_M: f64 = 0.0254;
/// Metres per foot.
pub const FOOT_M: f64 = 0.3048;

/// Serialises a length in inches as metres.
pub fn inches<S: Serializer>(x: &f64, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_f64(x * INCH_M)
}

/// Serialises a pair of lengths in inches as metres.
pub fn inches_pair<S: Serializer>(x: &[f64; 2], s: S) -> Result<S::Ok, S::Error> {
    use serde::Serialize;
    [x[0] * INCH_M, x[1] * INCH_M].serialize(s)
}

/// Serialises a velocity in ft/s as m/s.
pub fn feet_per_second<S: Serializer>(x: &f64, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_f64(x * FOOT_M)
}
