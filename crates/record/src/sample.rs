//! One row of a landing's time history (`history.csv`), the same for every engine.

use crate::energy::EnergyReport;
use nalgebra::Vector3;

/// One gear at one instant.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LegSample {
    /// Primary compression stroke, m (compression positive).
    pub primary_stroke: f64,
    /// Primary axial force F2P, N (compression positive).
    pub primary_force: f64,
    /// Secondary strokes S31, S41, m (tension positive).
    pub secondary_stroke: [f64; 2],
    /// Secondary axial forces F31, F41, N (tension positive).
    pub secondary_force: [f64; 2],
    /// The end stops' forces of the primary, 3-1 and 4-1 struts, N, in their struts' signs:
    /// what a strut past its capacity (or a primary past its full extension) carries beyond
    /// its last crush load; zero within the stroke range.
    pub stop_force: [f64; 3],
    /// Footpad position (ball joint), inertial, m.
    pub pad_position: Vector3<f64>,
    /// The lateral force of the footpad's restraint (an obstacle's wall or its spikes) on it,
    /// N (magnitude): zero for a footpad that slides, and once it has risen above the wall
    /// or out of the ground (docs/engines.md, "The footpad's lateral restraint").
    pub restraint_force: f64,
    /// Contact state: 0 never touched, 1 in contact, 2 left the surface.
    pub contact: u8,
}

/// The state of a landing at one instant (inertial frame = the surface frame).
#[derive(Debug, Clone, PartialEq)]
pub struct Sample {
    /// Time, s.
    pub t: f64,
    /// Vehicle centre-of-mass position, m.
    pub position: Vector3<f64>,
    /// Vehicle centre-of-mass velocity, m/s.
    pub velocity: Vector3<f64>,
    /// Euler angles θ relative to the surface frame (eq. 3 order), rad.
    pub theta: Vector3<f64>,
    /// Body rates ω in body axes, rad/s.
    pub omega: Vector3<f64>,
    /// Pitch rate: angular velocity about the inertial X axis, rad/s.
    pub pitch_rate: f64,
    /// One entry per leg.
    pub legs: Vec<LegSample>,
    /// Stability distance per wall (wall i joins footpads i and i+1), m; NaN if undefined.
    pub stability_distance: Vec<f64>,
    /// Energy bookkeeping.
    pub energy: EnergyReport,
}

impl Sample {
    /// An empty sample for `legs` legs (allocate once, fill at every step).
    pub fn new(legs: usize) -> Sample {
        Sample {
            t: 0.0,
            position: Vector3::zeros(),
            velocity: Vector3::zeros(),
            theta: Vector3::zeros(),
            omega: Vector3::zeros(),
            pitch_rate: 0.0,
            legs: vec![LegSample::default(); legs],
            stability_distance: vec![f64::NAN; legs],
            energy: EnergyReport::default(),
        }
    }
}
