//! The landing summary every engine reports (same fields, same signs, SI units).

use crate::stability::{Outcome, StabilityTracker};
use serde::Serialize;

/// Energy bookkeeping since touchdown, J. The balance
/// `kinetic + potential_change + footpad + honeycomb_stored + honeycomb_dissipated + viscous +
/// bearing_friction + sliding_friction − contact_events − kinetic_initial` is `residual`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct EnergyReport {
    /// Vehicle kinetic energy at first contact, J.
    pub kinetic_initial_j: f64,
    /// Vehicle kinetic energy now, J.
    pub kinetic_j: f64,
    /// Change of the vehicle's potential energy since touchdown, J.
    pub potential_change_j: f64,
    /// Energy of the gear's own masses, J: kinetic + potential of the footpads in contact (core),
    /// or the change since touchdown of the kinetic plus potential energy of every gear link
    /// (multibody engines).
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
    /// Energy given to the footpads by contact events, J: velocity set at touchdown and removed
    /// at lift-off (core), or the work of the surface's normal contact impulses and obstacle
    /// locks (multibody engines; negative, the impacts absorb energy).
    pub contact_events_j: f64,
    /// Balance residual (integration error), J.
    pub residual_j: f64,
}

/// Running extremes of the strokes and the pitch rate.
#[derive(Debug, Clone, PartialEq)]
pub struct Extremes {
    primary: Vec<f64>,
    sec_compression: Vec<[f64; 2]>,
    sec_tension: Vec<[f64; 2]>,
    pitch_rate: f64,
    pitch_rate_time: f64,
}

impl Extremes {
    /// Extremes of `legs` legs, all zero.
    pub fn new(legs: usize) -> Extremes {
        Extremes {
            primary: vec![0.0; legs],
            sec_compression: vec![[0.0; 2]; legs],
            sec_tension: vec![[0.0; 2]; legs],
            pitch_rate: 0.0,
            pitch_rate_time: 0.0,
        }
    }

    /// Updates leg `i` with its primary compression stroke (m) and secondary strokes (m,
    /// tension positive).
    pub fn update_leg(&mut self, i: usize, primary: f64, secondary: [f64; 2]) {
        self.primary[i] = self.primary[i].max(primary);
        for (j, s) in secondary.into_iter().enumerate() {
            self.sec_tension[i][j] = self.sec_tension[i][j].max(s);
            self.sec_compression[i][j] = self.sec_compression[i][j].max(-s);
        }
    }

    /// Updates the pitch rate of largest magnitude with `q` (rad/s, about the inertial X axis,
    /// the cross-slope axis normal to the plane of a planar landing) at time `t`, s.
    pub fn update_pitch_rate(&mut self, t: f64, q: f64) {
        if q.abs() > self.pitch_rate.abs() {
            self.pitch_rate = q;
            self.pitch_rate_time = t;
        }
    }
}

/// Summary of one landing.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// Engine that produced it ("core", "rapier").
    pub engine: String,
    /// Scenario name.
    pub scenario: String,
    /// The engine's settings as used (names carry their units), including any masses the
    /// engine adds to the report's model.
    pub engine_settings: serde_json::Map<String, serde_json::Value>,
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

/// How far a run went: time, steps, force evaluations and first contacts.
#[derive(Debug, Clone, PartialEq)]
pub struct Progress {
    /// Time reached, s.
    pub t: f64,
    /// Accepted steps.
    pub steps: u64,
    /// Gear force evaluations.
    pub force_evaluations: u64,
    /// Time of each footpad's first contact, s (`None` if it never touched).
    pub first_contact_s: Vec<Option<f64>>,
}

impl Summary {
    /// The summary of a run by `engine` on `scenario`.
    pub fn new(
        engine: &str,
        scenario: &str,
        engine_settings: serde_json::Map<String, serde_json::Value>,
        progress: Progress,
        stability: &StabilityTracker,
        extremes: &Extremes,
        energy: EnergyReport,
    ) -> Summary {
        let (outcome, decision) = match stability.decision() {
            Some((o, t)) => (o, Some(t)),
            None => (Outcome::Undecided, None),
        };
        Summary {
            engine: engine.to_string(),
            scenario: scenario.to_string(),
            engine_settings,
            outcome,
            decision_time_s: decision,
            t_end_s: progress.t,
            steps: progress.steps,
            force_evaluations: progress.force_evaluations,
            max_primary_stroke_m: extremes.primary.clone(),
            max_secondary_compression_m: extremes.sec_compression.clone(),
            max_secondary_tension_m: extremes.sec_tension.clone(),
            peak_pitch_rate_rad_s: extremes.pitch_rate,
            peak_pitch_rate_time_s: extremes.pitch_rate_time,
            min_stability_distance_m: stability.min_distance(),
            overturn_velocity_m_s: stability.overturn_velocity(),
            first_contact_s: progress.first_contact_s,
            energy_residual_j: energy.residual_j,
            energy,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extremes_keep_maxima_and_the_signed_peak_rate() {
        let mut x = Extremes::new(2);
        x.update_leg(1, 0.1, [0.02, -0.03]);
        x.update_leg(1, 0.05, [-0.01, 0.04]);
        assert_eq!(x.primary, vec![0.0, 0.1]);
        assert_eq!(x.sec_tension[1], [0.02, 0.04]);
        assert_eq!(x.sec_compression[1], [0.01, 0.03]);
        x.update_pitch_rate(0.1, 0.5);
        x.update_pitch_rate(0.2, -0.7);
        x.update_pitch_rate(0.3, 0.6);
        assert_eq!((x.pitch_rate, x.pitch_rate_time), (-0.7, 0.2));
    }
}
