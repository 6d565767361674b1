//! The TN D-7045 lander as a MuJoCo model (MJCF), generated from a scenario (docs/engines.md,
//! "The MuJoCo export").
//!
//! | module | content |
//! |---|---|
//! | [`mjcf`] | the MJCF document: vehicle, gear links, joints, secondary tendons, actuators, footpad planes, touchdown keyframe |
//!
//! Frames: MuJoCo's world frame is the report's inertial (surface) frame, Z normal to the
//! surface, so the slope is a tilted gravity vector, as in the other engines.

pub mod mjcf;

pub use mjcf::export;
