//! The landing summary every engine reports (same fields, same signs, SI units).

use crate::stability::Outcome;
use serde::Serialize;

/// Energy bookkeeping since touchdown, J. The balance
/// `kinetic + potential_change + footpad + honeycomb_stored + honeycomb_dissipated + viscous +
/// bearing_friction + sliding_friction − contact_events − kinetic_initial` is `residual`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EnergyReport {
    /// Vehicle kinetic energy at first contact, J.
    pub kinetic_initial_j: f64,
    /// Vehicle kinetic energy now, J.
    pub kinetic_j: f64,
    /// Change of the vehicle's potential energy since touchdown, J.
    pub potential_change_j: f64,
    /// Kinetic + potential energy of the footpads in contact, J.
    pub footpad_j: f64,
    /// Elastic energy stored in the honeycombs (recoverable), J.
    pub honeycomb_stored_j: f64,
    /// Energy dissipated by crushing honeycomb, J.
    pub honeycomb_dissipated_j: f64,
    /// Energy dissipated by the viscous strut forces, J.
    pub viscous_j: f64,
    /// Energy dissipated by primary-strut bearing friction, J.
    pub bearing_friction_j: f64,
    /// Energy dissipated by footpad sliding friction (and sliding footpads stopping), J.
    pub sliding_friction_j: f64,
    /// Energy given to footpads by contact-state changes (velocity set at touchdown, removed
    /// at lift-off), J.
    pub contact_events_j: f64,
    /// Balance residual (integration error), J.
    pub residual_j: f64,
}

/// Summary of one landing.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// Engine that produced it ("core").
    pub engine: String,
    /// Scenario name.
    pub scenario: String,
    /// Stability outcome.
    pub outcome: Outcome,
    /// Time of the stability decision, s (null if undecided).
    pub decision_time_s: Option<f64>,
    /// Time the run ended, s.
    pub t_end_s: f64,
    /// Accepted integration steps.
    pub steps: u64,
    /// Gear force evaluations.
    pub force_evaluations: u64,
    /// Maximum primary compression stroke per leg, m (compression positive).
    pub max_primary_stroke_m: Vec<f64>,
    /// Maximum compression stroke of the two secondaries (3-1, 4-1) per leg, m (positive).
    pub max_secondary_compression_m: Vec<[f64; 2]>,
    /// Maximum tension stroke of the two secondaries per leg, m (positive).
    pub max_secondary_tension_m: Vec<[f64; 2]>,
    /// Pitch rate (about the inertial X axis) of largest magnitude, signed, rad/s.
    pub peak_pitch_rate_rad_s: f64,
    /// Time of that peak, s.
    pub peak_pitch_rate_time_s: f64,
    /// Minimum over time of the smallest stability distance, m.
    pub min_stability_distance_m: f64,
    /// Overturning velocity at the wall crossing, m/s (null unless unstable).
    pub overturn_velocity_m_s: Option<f64>,
    /// Time of each footpad's first contact, s (null if it never touched).
    pub first_contact_s: Vec<Option<f64>>,
    /// Energy balance residual at the end, J.
    pub energy_residual_j: f64,
    /// Energy bookkeeping at the end.
    pub energy: EnergyReport,
}
