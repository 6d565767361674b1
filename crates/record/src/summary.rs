//! The landing summary every engine reports (same fields, same signs, SI units).

use crate::capacity::{PastCapacity, StrutCapacities};
use crate::energy::EnergyReport;
use crate::stability::{Outcome, StabilityTracker, TIME_RESOLUTION};
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

/// Running extremes of one leg: strokes (m) with the times they were reached (s), and strut
/// forces (N).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct LegExtremes {
    primary: f64,
    sec_compression: [f64; 2],
    sec_tension: [f64; 2],
    primary_time: f64,
    sec_compression_time: [f64; 2],
    sec_tension_time: [f64; 2],
    /// The strokes at those times (each within [`TIME_RESOLUTION`] of a capacity of its
    /// maximum).
    primary_timed: f64,
    sec_compression_timed: [f64; 2],
    sec_tension_timed: [f64; 2],
    primary_force: f64,
    sec_compression_force: [f64; 2],
    sec_tension_force: [f64; 2],
}

/// Running extremes of the strokes, the strut forces, the vehicle's acceleration and the pitch
/// rate.
#[derive(Debug, Clone, PartialEq)]
pub struct Extremes {
    legs: Vec<LegExtremes>,
    specific_force: f64,
    /// The pitch rate's extremes so far in each sense, (rad/s, s at which it came): the
    /// smallest (≤ 0) and the largest (≥ 0).
    pitch_rate: [(f64, f64); 2],
    /// Closed: the landing overturned, later states measure the overturn, not the landing.
    closed: bool,
    /// The struts' capacities, to name those the strokes went past.
    capacities: StrutCapacities,
}

impl Extremes {
    /// Extremes of `legs` legs whose struts have the capacities `capacities`, all zero.
    pub fn new(legs: usize, capacities: StrutCapacities) -> Extremes {
        Extremes {
            legs: vec![LegExtremes::default(); legs],
            specific_force: 0.0,
            pitch_rate: [(0.0, 0.0); 2],
            closed: false,
            capacities,
        }
    }

    /// Closes the extremes once `stability` has decided the landing unstable: the state at
    /// the crossing is the last one measured, whether or not the run goes on
    /// (docs/errata.md, "Stability decisions and maxima").
    #[inline]
    pub fn follow(&mut self, stability: &StabilityTracker) {
        self.closed |= stability.overturned();
    }

    /// Updates leg `i` at time `t` (s) with its primary compression stroke (m) and force (N,
    /// compression positive), and its secondary strokes (m) and forces (N), tension positive.
    /// Each stroke's maximum keeps the time it was first reached to within
    /// [`TIME_RESOLUTION`] of its strut's capacity.
    #[inline]
    pub fn update_leg(
        &mut self,
        t: f64,
        i: usize,
        primary: f64,
        secondary: [f64; 2],
        primary_force: f64,
        secondary_force: [f64; 2],
    ) {
        if self.closed {
            return;
        }
        /// Raises `max` to `x`; `time` to `t` (and `timed` to `x`) where `x` passes the stroke
        /// at `time` by more than `resolution`.
        fn raise(
            max: &mut f64,
            (time, timed): (&mut f64, &mut f64),
            x: f64,
            t: f64,
            resolution: f64,
        ) {
            if x > *max {
                *max = x;
                if x > *timed + resolution {
                    (*time, *timed) = (t, x);
                }
            }
        }
        let c = &self.capacities;
        let resolution = [
            c.primary.stroke_m,
            c.secondary_tension.stroke_m,
            c.secondary_compression.stroke_m,
        ]
        .map(|s| TIME_RESOLUTION * s);
        let leg = &mut self.legs[i];
        raise(
            &mut leg.primary,
            (&mut leg.primary_time, &mut leg.primary_timed),
            primary,
            t,
            resolution[0],
        );
        leg.primary_force = leg.primary_force.max(primary_force);
        for j in 0..2 {
            raise(
                &mut leg.sec_tension[j],
                (&mut leg.sec_tension_time[j], &mut leg.sec_tension_timed[j]),
                secondary[j],
                t,
                resolution[1],
            );
            raise(
                &mut leg.sec_compression[j],
                (
                    &mut leg.sec_compression_time[j],
                    &mut leg.sec_compression_timed[j],
                ),
                -secondary[j],
                t,
                resolution[2],
            );
            leg.sec_tension_force[j] = leg.sec_tension_force[j].max(secondary_force[j]);
            leg.sec_compression_force[j] = leg.sec_compression_force[j].max(-secondary_force[j]);
        }
    }

    /// Updates the largest specific force on the vehicle (what an accelerometer at its centre
    /// of mass reads, m/s²) with an accepted step: the velocity went from `before` to `after`
    /// (m/s, inertial) in `dt` s under `gravity` (m/s², inertial), so the mean specific force
    /// over the step is |(after − before)/dt − gravity|. A step of no length changes nothing.
    #[inline]
    pub fn update_acceleration(
        &mut self,
        before: &Vector3<f64>,
        after: &Vector3<f64>,
        dt: f64,
        gravity: &Vector3<f64>,
    ) {
        if dt > 0.0 && !self.closed {
            let a = ((after - before) / dt - gravity).norm();
            self.specific_force = self.specific_force.max(a);
        }
    }

    /// Updates the pitch rate's extremes in each sense with `q` (rad/s, about the inertial X
    /// axis, the cross-slope axis normal to the plane of a planar landing) at time `t`, s.
    #[inline]
    pub fn update_pitch_rate(&mut self, t: f64, q: f64) {
        if self.closed {
            return;
        }
        let [low, high] = &mut self.pitch_rate;
        if q < low.0 {
            *low = (q, t);
        }
        if q > high.0 {
            *high = (q, t);
        }
    }

    /// Leg `i`'s largest strut forces so far, N: the primary's axial force F2P (compression
    /// positive), and each secondary's in tension and in compression (positive).
    pub fn peak_forces(&self, i: usize) -> (f64, [f64; 2], [f64; 2]) {
        let l = &self.legs[i];
        (
            l.primary_force,
            l.sec_tension_force,
            l.sec_compression_force,
        )
    }

    /// The largest specific force on the vehicle so far, m/s².
    pub fn specific_force(&self) -> f64 {
        self.specific_force
    }

    /// The pitch rate's extremes so far, each with the time it came (rad/s, s): the smallest
    /// (≤ 0) and the largest (≥ 0).
    pub fn pitch_rate_extremes(&self) -> [(f64, f64); 2] {
        self.pitch_rate
    }

    /// The pitch rate of largest magnitude so far and its time, (rad/s signed, s): of two
    /// senses' extremes of one magnitude, the earlier.
    pub fn peak_pitch_rate(&self) -> (f64, f64) {
        let [low, high] = self.pitch_rate;
        if high.0 > -low.0 || (high.0 == -low.0 && high.1 <= low.1) {
            high
        } else {
            low
        }
    }

    /// One value per leg.
    fn per_leg<T>(&self, f: impl Fn(&LegExtremes) -> T) -> Vec<T> {
        self.legs.iter().map(f).collect()
    }
}

/// Summary of one landing.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Summary {
    /// Engine that produced it ("core", "rapier").
    pub engine: String,
    /// Scenario name (its `name` field).
    #[serde(rename = "scenario_name")]
    pub scenario: String,
    /// The engine's settings as used (names carry their units), including any masses the
    /// engine adds to the report's model.
    pub engine_settings: serde_json::Map<String, serde_json::Value>,
    /// Stability outcome.
    pub outcome: Outcome,
    /// Time of the stability decision, s (left out of the JSON if undecided): when the four
    /// stable conditions first held, or when the centre of mass crossed a wall.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub decision_time_s: Option<f64>,
    /// When the four stable conditions of eqs. (105)-(107) first held, s, where the report
    /// ends its runs; the run goes on to its end time so that no maximum is cut short, and a
    /// later crossing still decides the landing unstable (left out of the JSON if they never
    /// held).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stable_conditions_time_s: Option<f64>,
    /// When the core proved the landing settled and ended it, s: no maximum stroke could grow
    /// by more than the scenario's `stability.settled_tolerance` and no overturn was
    /// reachable (docs/errata.md, "Settled landings: an early end with a proof"); left out of
    /// the JSON where the run went to its end time.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub settled_time_s: Option<f64>,
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
    /// Time each leg's maximum primary stroke was first reached to within 1e-9 of the strut's
    /// capacity, s (so that rounding cannot move it; the run's start where the strut never
    /// compressed).
    pub max_primary_stroke_time_s: Vec<f64>,
    /// Time each maximum secondary compression stroke was first reached, s (the start where
    /// it is 0).
    pub max_secondary_compression_time_s: Vec<[f64; 2]>,
    /// Time each maximum secondary tension stroke was first reached, s (the start where it is
    /// 0).
    pub max_secondary_tension_time_s: Vec<[f64; 2]>,
    /// Largest primary axial force F2P per leg, N (compression positive).
    pub peak_primary_force_n: Vec<f64>,
    /// Largest compression force of the two secondaries (3-1, 4-1) per leg, N (positive).
    pub peak_secondary_compression_force_n: Vec<[f64; 2]>,
    /// Largest tension force of the two secondaries per leg, N (positive).
    pub peak_secondary_tension_force_n: Vec<[f64; 2]>,
    /// Largest specific force on the vehicle's centre of mass (its acceleration less gravity,
    /// what an accelerometer there reads), the mean over each accepted step, m/s².
    pub peak_specific_force_m_s2: f64,
    /// Pitch rate (about the inertial X axis) of largest magnitude, signed, rad/s.
    pub peak_pitch_rate_rad_s: f64,
    /// Time of that peak, s.
    pub peak_pitch_rate_time_s: f64,
    /// Smallest pitch rate (the largest in the negative sense), rad/s, ≤ 0: 0 if the vehicle
    /// never pitched that way. With [`Summary::max_pitch_rate_rad_s`] it describes a rocking
    /// landing continuously, where the signed peak jumps sign between two swings of nearly
    /// one magnitude.
    pub min_pitch_rate_rad_s: f64,
    /// Time of the smallest pitch rate, s (0 if it is 0).
    pub min_pitch_rate_time_s: f64,
    /// Largest pitch rate (the largest in the positive sense), rad/s, ≥ 0: 0 if the vehicle
    /// never pitched that way.
    pub max_pitch_rate_rad_s: f64,
    /// Time of the largest pitch rate, s (0 if it is 0).
    pub max_pitch_rate_time_s: f64,
    /// The struts' capacities and their stops' rates, the same on every leg.
    pub strut_capacity: StrutCapacities,
    /// The struts whose largest stroke went past their capacity onto their end stop, how far
    /// and with what stop force (an empty list when every strut stayed within its capacity):
    /// the stop's law is an estimate, so an outcome that depends on it is flagged.
    pub past_capacity: Vec<PastCapacity>,
    /// Minimum over time of the smallest stability distance, m.
    pub min_stability_distance_m: f64,
    /// When that minimum was first reached, to within 1e-9 of the footprint's size, s (0: the
    /// vehicle never came closer to a wall than at touchdown).
    pub min_stability_distance_time_s: f64,
    /// Overturning velocity at the wall crossing, m/s (left out of the JSON unless unstable).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub overturn_velocity_m_s: Option<f64>,
    /// Time of each footpad's first contact, s (`None` if it never touched); in the JSON an
    /// object with a key per footpad that touched, `{"leg1": 0.0, "leg3": 0.05}`, so that no
    /// number is ever null.
    #[serde(with = "per_leg_times")]
    pub first_contact_s: Vec<Option<f64>>,
    /// Energy balance residual at the end, J.
    pub energy_residual_j: f64,
    /// Energy bookkeeping at the end.
    pub energy: EnergyReport,
    /// Evaluations of each optional mechanism the scene declares (name → count); empty, and
    /// left out of the JSON, when it declares none.
    #[serde(default, skip_serializing_if = "std::collections::BTreeMap::is_empty")]
    pub mechanisms: std::collections::BTreeMap<String, u64>,
}

/// Per-leg optional times as a JSON object keyed `legN` (N from 1), the legs without a time
/// left out.
mod per_leg_times {
    use serde::{Deserialize, Deserializer, Serializer};
    use std::collections::BTreeMap;

    pub fn serialize<S: Serializer>(times: &[Option<f64>], s: S) -> Result<S::Ok, S::Error> {
        // Written in leg order (a BTreeMap would put leg10 before leg2).
        use serde::ser::SerializeMap;
        let mut map = s.serialize_map(None)?;
        for (i, t) in times.iter().enumerate() {
            if let Some(t) = t {
                map.serialize_entry(&format!("leg{}", i + 1), t)?;
            }
        }
        map.end()
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<Option<f64>>, D::Error> {
        let map = BTreeMap::<String, f64>::deserialize(d)?;
        let mut out = Vec::new();
        for (key, t) in map {
            let leg: usize = key
                .strip_prefix("leg")
                .and_then(|n| n.parse().ok())
                .filter(|n| *n >= 1)
                .ok_or_else(|| {
                    serde::de::Error::custom(format!("expected a key legN, got {key}"))
                })?;
            if out.len() < leg {
                out.resize(leg, None);
            }
            out[leg - 1] = Some(t);
        }
        Ok(out)
    }
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
    /// The summary alone as pretty JSON (what the MuJoCo runner hands back to the engine;
    /// deterministic: fields in declaration order).
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("a summary serialises: plain numbers and strings")
    }

    /// The summary as the document `touchdown run --format json` prints and `summary.json`
    /// holds (docs/schemas/run.schema.json): the envelope naming `scenario` and the
    /// `settings` it ran with, then the summary's fields.
    pub fn document(&self, scenario: &crate::ScenarioId, settings: &serde_json::Value) -> String {
        crate::Document::new("run", Some(scenario), settings, self).pretty()
    }

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
        let max_primary = extremes.per_leg(|l| l.primary);
        let max_compression = extremes.per_leg(|l| l.sec_compression);
        let max_tension = extremes.per_leg(|l| l.sec_tension);
        let past_capacity = extremes
            .capacities
            .past(&max_primary, &max_compression, &max_tension);
        let (peak_pitch_rate, peak_pitch_rate_time) = extremes.peak_pitch_rate();
        let [low, high] = extremes.pitch_rate;
        Summary {
            engine: engine.to_string(),
            scenario: scenario.to_string(),
            engine_settings,
            outcome,
            decision_time_s: decision,
            stable_conditions_time_s: stability.stable_conditions_time(),
            settled_time_s: None,
            t_end_s: progress.t,
            steps: progress.steps,
            force_evaluations: progress.force_evaluations,
            max_primary_stroke_m: max_primary,
            max_secondary_compression_m: max_compression,
            max_secondary_tension_m: max_tension,
            max_primary_stroke_time_s: extremes.per_leg(|l| l.primary_time),
            max_secondary_compression_time_s: extremes.per_leg(|l| l.sec_compression_time),
            max_secondary_tension_time_s: extremes.per_leg(|l| l.sec_tension_time),
            peak_primary_force_n: extremes.per_leg(|l| l.primary_force),
            peak_secondary_compression_force_n: extremes.per_leg(|l| l.sec_compression_force),
            peak_secondary_tension_force_n: extremes.per_leg(|l| l.sec_tension_force),
            peak_specific_force_m_s2: extremes.specific_force,
            peak_pitch_rate_rad_s: peak_pitch_rate,
            peak_pitch_rate_time_s: peak_pitch_rate_time,
            min_pitch_rate_rad_s: low.0,
            min_pitch_rate_time_s: low.1,
            max_pitch_rate_rad_s: high.0,
            max_pitch_rate_time_s: high.1,
            strut_capacity: extremes.capacities,
            past_capacity,
            min_stability_distance_m: stability.min_distance(),
            min_stability_distance_time_s: stability.min_distance_time(),
            overturn_velocity_m_s: stability.overturn_velocity(),
            first_contact_s: progress.first_contact_s,
            energy_residual_j: energy.residual_j,
            energy,
            mechanisms: Default::default(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extremes_keep_maxima_and_the_signed_peak_rate() {
        let mut x = Extremes::new(2, StrutCapacities::default());
        x.update_leg(0.5, 1, 0.1, [0.02, -0.03], 900.0, [-40.0, 25.0]);
        x.update_leg(0.7, 1, 0.05, [-0.01, 0.04], 700.0, [10.0, -5.0]);
        // An equal stroke later keeps the time the maximum was first reached.
        x.update_leg(0.9, 1, 0.1, [0.0, 0.0], 0.0, [0.0, 0.0]);
        // With capacities, a rise within 1e-9 of the capacity keeps the time too; a larger
        // one moves it.
        let mut c = StrutCapacities::default();
        c.primary.stroke_m = 0.2;
        let mut y = Extremes::new(1, c);
        y.update_leg(0.1, 0, 0.1, [0.0; 2], 0.0, [0.0; 2]);
        y.update_leg(0.2, 0, 0.1 + 1e-11, [0.0; 2], 0.0, [0.0; 2]);
        assert_eq!(
            (y.legs[0].primary, y.legs[0].primary_time),
            (0.1 + 1e-11, 0.1)
        );
        y.update_leg(0.3, 0, 0.1 + 1e-9, [0.0; 2], 0.0, [0.0; 2]);
        assert_eq!(y.legs[0].primary_time, 0.3);
        assert_eq!(x.per_leg(|l| l.primary), vec![0.0, 0.1]);
        assert_eq!(x.per_leg(|l| l.primary_time), vec![0.0, 0.5]);
        assert_eq!(x.legs[1].sec_tension, [0.02, 0.04]);
        assert_eq!(x.legs[1].sec_tension_time, [0.5, 0.7]);
        assert_eq!(x.legs[1].sec_compression, [0.01, 0.03]);
        assert_eq!(x.legs[1].sec_compression_time, [0.7, 0.5]);
        assert_eq!(x.per_leg(|l| l.primary_force), vec![0.0, 900.0]);
        assert_eq!(x.legs[1].sec_tension_force, [10.0, 25.0]);
        assert_eq!(x.legs[1].sec_compression_force, [40.0, 5.0]);
        x.update_pitch_rate(0.1, 0.5);
        x.update_pitch_rate(0.2, -0.7);
        x.update_pitch_rate(0.3, 0.6);
        assert_eq!(x.peak_pitch_rate(), (-0.7, 0.2));
        assert_eq!(x.pitch_rate, [(-0.7, 0.2), (0.6, 0.3)]);
        // Of two extremes of one magnitude the earlier is the peak, either way round.
        x.update_pitch_rate(0.4, 0.7);
        assert_eq!(x.peak_pitch_rate(), (-0.7, 0.2));
        let mut y = Extremes::new(1, StrutCapacities::default());
        y.update_pitch_rate(0.1, 0.7);
        y.update_pitch_rate(0.2, -0.7);
        assert_eq!(y.peak_pitch_rate(), (0.7, 0.1));
        assert_eq!(y.pitch_rate_extremes(), [(-0.7, 0.2), (0.7, 0.1)]);
    }

    #[test]
    fn the_specific_force_is_zero_in_free_fall_and_reads_the_gear_load() {
        let g = Vector3::new(0.0, 0.0, -9.81);
        let mut x = Extremes::new(1, StrutCapacities::default());
        // Free fall: the velocity changes by g·dt, the accelerometer reads nothing.
        x.update_acceleration(&Vector3::zeros(), &(g * 0.01), 0.01, &g);
        assert!(x.specific_force < 1e-12, "{}", x.specific_force);
        // Brought to rest from 2 m/s down in 0.1 s: 20 m/s² of deceleration plus 1 g held off.
        x.update_acceleration(&Vector3::new(0.0, 0.0, -2.0), &Vector3::zeros(), 0.1, &g);
        assert!(
            (x.specific_force - 29.81).abs() < 1e-9,
            "{}",
            x.specific_force
        );
        // A step of no length is no measurement.
        x.update_acceleration(&Vector3::zeros(), &Vector3::new(0.0, 0.0, 5.0), 0.0, &g);
        assert!((x.specific_force - 29.81).abs() < 1e-9);
    }
}
