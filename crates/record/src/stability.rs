//! Stability distance, overturning velocity and the stable-landing conditions, eqs. (105)-(107)
//! and the text after them (docs/errata.md, "Eqs. (105)-(107): stability — interpreted"), shared by every engine so that they decide alike.
//!
//! Walls are vertical planes (parallel to G) through adjacent footpads, in leg order, which the
//! scenario guarantees is counter-clockwise seen from above. With ACM = r_A − r_CM and
//! n̂ = G×AB/|G×AB| (the outward normal), SD = ACM·n̂ is positive while the centre of mass is
//! inside the wall.

use crate::energy::EnergyReport;
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};
use touchdown_scenario::model::Stability;
use touchdown_scenario::schema::{CountedEnergy, WallRule};

/// Rounding allowance on condition 4, m/s: a centre of mass that does not move across the
/// critical wall at all (a symmetric landing) has an outward velocity of rounding noise, about
/// 1e-15 m/s in the core and 1e-11 m/s in the rapier multibody, of either sign. Without the
/// allowance the default threshold 0 would turn on the sign of that noise.
pub const SEPARATION_VELOCITY_ROUNDING: f64 = 1.0e-9;

/// Landing outcome.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Outcome {
    /// All four conditions of a stable landing held at one instant.
    Stable,
    /// The centre of mass crossed a stability wall.
    Unstable,
    /// Neither before the end time.
    Undecided,
}

/// Stability distance of the centre of mass `cm` to the wall through footpads `a` → `b`, m,
/// and the wall's outward unit normal, eq. (105). `None` if the wall is parallel to G.
pub fn stability_distance(
    gravity: &Vector3<f64>,
    cm: &Vector3<f64>,
    a: &Vector3<f64>,
    b: &Vector3<f64>,
) -> Option<(f64, Vector3<f64>)> {
    let ab = b - a;
    let n = gravity.cross(&ab);
    let len = n.norm();
    if len <= 1e-12 * gravity.norm() * ab.norm() {
        return None;
    }
    let n = n / len;
    Some(((a - cm).dot(&n), n)) // eq. (105); eq. (106): SD_vec = SD·n̂
}

/// Overturning velocity, m/s, eq. (107) with n̂ in place of the 0/0 direction ŜD at the
/// crossing: V_o = V·n̂_out (positive: moving out of the footprint).
pub fn overturn_velocity(v: &Vector3<f64>, n_out: &Vector3<f64>) -> f64 {
    v.dot(n_out) // eq. (107)
}

/// What the criteria need of one footpad.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PadView {
    /// Footpad position (the ball joint), inertial, m.
    pub position: Vector3<f64>,
    /// In contact with its surface now.
    pub in_contact: bool,
    /// Has touched its surface at least once.
    pub touched: bool,
}

/// The fraction of a length scale (a strut's capacity, the footprint's size) within which an
/// extreme counts as reached: an extreme's time moves only when the value passes the value at
/// that time by more, so that rounding (a mirror image's stroke 1e-16 m apart, dwelling at its
/// maximum) cannot move it across a whole dwell (docs/outputs.md, the summary's `*_time_s`).
pub const TIME_RESOLUTION: f64 = 1e-9;

/// A running minimum with the time it was first reached to within a resolution.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Timed {
    /// The minimum.
    value: f64,
    /// When it was reached, s.
    time: f64,
    /// The value at `time`.
    at_time: f64,
}

impl Default for Timed {
    fn default() -> Timed {
        Timed {
            value: f64::INFINITY,
            time: 0.0,
            at_time: f64::INFINITY,
        }
    }
}

impl Timed {
    /// Lowers the minimum to `x` at time `t`; the time moves only where `x` is below the value
    /// at the time by more than `resolution`.
    fn lower(&mut self, x: f64, t: f64, resolution: f64) {
        if x < self.value {
            self.value = x;
            if x < self.at_time - resolution {
                (self.time, self.at_time) = (t, x);
            }
        }
    }
}

/// Stability distances over time and the decision of eqs. (105)-(107).
#[derive(Debug, Clone, PartialEq)]
pub struct StabilityTracker {
    criteria: Stability,
    gravity: Vector3<f64>,
    /// Current SD per wall (NaN where undefined), m.
    sd: Vec<f64>,
    /// Outward normals per wall.
    normal: Vec<Vector3<f64>>,
    /// Minimum over time of the smallest counted SD, m, with the time it was first reached
    /// to within [`TIME_RESOLUTION`] of the footprint's size.
    min_sd: Timed,
    /// Minimum over time of the smallest SD of any wall, counted or not, m, and its time.
    min_any: Timed,
    /// The first smallest SD, m: the footprint's size the times' resolution is a fraction of.
    sd_scale: f64,
    /// Vehicle kinetic energy at first contact, J.
    ke0: f64,
    /// When the four stable conditions first held, s.
    stable_conditions: Option<f64>,
    /// When the centre of mass crossed a counted wall, s.
    crossing: Option<f64>,
    overturn_velocity: Option<f64>,
}

impl StabilityTracker {
    /// A tracker for `legs` footpads under `gravity` (inertial, m/s²), with the vehicle's
    /// kinetic energy at first contact `ke0`, J. Without gravity the distances are measured
    /// along the surface's normal (inertial −Z) instead, so that they stay defined.
    pub fn new(
        criteria: &Stability,
        gravity: Vector3<f64>,
        legs: usize,
        ke0: f64,
    ) -> StabilityTracker {
        StabilityTracker {
            criteria: criteria.clone(),
            gravity: if gravity.norm() > 0.0 {
                gravity
            } else {
                -Vector3::z()
            },
            sd: vec![f64::NAN; legs],
            normal: vec![Vector3::zeros(); legs],
            min_sd: Timed::default(),
            min_any: Timed::default(),
            sd_scale: 0.0,
            ke0,
            stable_conditions: None,
            crossing: None,
            overturn_velocity: None,
        }
    }

    /// Updates the distances and, until the landing overturns, their minimum and the unstable
    /// crossing, and until they first hold the four stable conditions, at time `t` (s) with the
    /// centre of mass at `cm` (m) moving at `velocity` (m/s; `previous_velocity` at the previous
    /// accepted state, to interpolate the velocity at a crossing), the engine's energy report at
    /// this state `energy` (its kinetic energy, and its honeycomb stored energy unless the
    /// criteria count the kinetic energy alone, enter condition 1) and the footpads `pads`.
    /// Allocates nothing.
    pub fn update(
        &mut self,
        t: f64,
        cm: &Vector3<f64>,
        velocity: &Vector3<f64>,
        previous_velocity: Option<&Vector3<f64>>,
        energy: &EnergyReport,
        pads: &[PadView],
    ) {
        let n = pads.len();
        let failed = self.overturned();
        let mut min_now = f64::INFINITY;
        let mut any_now = f64::INFINITY;
        let mut min_wall = usize::MAX;
        let mut crossing: Option<(usize, f64)> = None;
        for i in 0..n {
            let j = (i + 1) % n;
            let counted = match self.criteria.walls {
                WallRule::All => true,
                WallRule::TouchedDown => pads[i].touched && pads[j].touched,
            };
            let prev = self.sd[i];
            match stability_distance(&self.gravity, cm, &pads[i].position, &pads[j].position) {
                Some((sd, normal)) => {
                    self.sd[i] = sd;
                    self.normal[i] = normal;
                    any_now = any_now.min(sd);
                    if counted && sd < min_now {
                        min_now = sd;
                        min_wall = i;
                    }
                    if counted && sd < 0.0 && crossing.is_none() {
                        // Fraction of the step at which SD crossed zero.
                        let f = if prev.is_finite() && prev > 0.0 {
                            prev / (prev - sd)
                        } else {
                            1.0
                        };
                        crossing = Some((i, f));
                    }
                }
                None => self.sd[i] = f64::NAN,
            }
        }
        if failed {
            // The landing has failed: what follows is the overturn, not the landing, and
            // measures nothing of it (docs/errata.md, "Stability decisions and maxima").
            return;
        }
        if self.sd_scale == 0.0 && any_now.is_finite() {
            self.sd_scale = any_now.abs();
        }
        let resolution = TIME_RESOLUTION * self.sd_scale;
        self.min_sd.lower(min_now, t, resolution);
        self.min_any.lower(any_now, t, resolution);
        // A crossing decides the landing unstable even after the stable conditions held: they
        // are a prediction, the crossing is the event.
        if let Some((wall, f)) = crossing {
            let v_cross = match previous_velocity {
                Some(o) => o + (velocity - o) * f,
                None => *velocity,
            };
            self.overturn_velocity = Some(overturn_velocity(&v_cross, &self.normal[wall]));
            self.crossing = Some(t);
            return;
        }
        if min_wall == usize::MAX || self.stable_conditions.is_some() {
            return;
        }
        let j = (min_wall + 1) % n;
        let energy = match self.criteria.counted_energy {
            CountedEnergy::Kinetic => energy.kinetic_j,
            CountedEnergy::KineticAndStored => energy.kinetic_j + energy.honeycomb_stored_j,
        };
        let stable = energy < self.criteria.kinetic_energy_fraction * self.ke0 // 1
            && min_now > 0.0 // 2
            && pads[min_wall].in_contact && pads[j].in_contact // 3
            && -velocity.dot(&self.normal[min_wall])
                >= self.criteria.min_separation_velocity - SEPARATION_VELOCITY_ROUNDING; // 4
        if stable {
            self.stable_conditions = Some(t);
        }
    }

    /// Whether the centre of mass has crossed a counted wall: the landing has failed.
    pub fn overturned(&self) -> bool {
        self.crossing.is_some()
    }

    /// When the four stable conditions first held, s, even if a later crossing decided the
    /// landing unstable; `None` if they never held. The report ends its runs here.
    pub fn stable_conditions_time(&self) -> Option<f64> {
        self.stable_conditions
    }

    /// Current stability distance per wall (wall i joins footpads i and i+1), m; NaN where the
    /// wall is undefined.
    pub fn distances(&self) -> &[f64] {
        &self.sd
    }

    /// Minimum over time of the smallest counted stability distance, m; if no wall was ever
    /// counted (walls counted only once touched down, and no two neighbouring footpads down),
    /// the smallest distance of any wall.
    pub fn min_distance(&self) -> f64 {
        self.min_timed().value
    }

    /// When [`Self::min_distance`] was first reached, to within 1e-9 of the footprint's size
    /// (so that rounding cannot move it along a dwell), s.
    pub fn min_distance_time(&self) -> f64 {
        self.min_timed().time
    }

    fn min_timed(&self) -> Timed {
        if self.min_sd.value.is_finite() {
            self.min_sd
        } else {
            self.min_any
        }
    }

    /// Vehicle kinetic energy at first contact, J.
    pub fn initial_kinetic_energy(&self) -> f64 {
        self.ke0
    }

    /// The decision and its time, s, if one was made: the crossing, or else the instant the
    /// stable conditions first held.
    pub fn decision(&self) -> Option<(Outcome, f64)> {
        match (self.crossing, self.stable_conditions) {
            (Some(t), _) => Some((Outcome::Unstable, t)),
            (None, Some(t)) => Some((Outcome::Stable, t)),
            (None, None) => None,
        }
    }

    /// Overturning velocity at the wall crossing, m/s (unstable landings only).
    pub fn overturn_velocity(&self) -> Option<f64> {
        self.overturn_velocity
    }

    /// Whether the run should end now: the landing overturned and the criteria end runs on a
    /// decision. A stable decision never ends a run: the gear can still stroke and the
    /// footpads still strike after the four conditions hold, and a crossing can still follow,
    /// so a stable landing runs to its end time (docs/errata.md, "Stability decisions and
    /// maxima").
    pub fn terminates(&self) -> bool {
        self.criteria.terminate_on_decision && self.overturned()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A running minimum's time moves only past the resolution: rounding along a dwell keeps
    /// the time it was first reached.
    #[test]
    fn a_minimums_time_moves_only_past_its_resolution() {
        let mut m = Timed::default();
        m.lower(1.0, 0.0, 1e-9);
        m.lower(1.0 - 1e-12, 0.5, 1e-9);
        assert_eq!((m.value, m.time), (1.0 - 1e-12, 0.0));
        m.lower(0.9, 0.7, 1e-9);
        assert_eq!((m.value, m.time), (0.9, 0.7));
    }

    fn square() -> [Vector3<f64>; 4] {
        [
            Vector3::new(1.0, 0.0, 0.0),
            Vector3::new(0.0, 1.0, 0.0),
            Vector3::new(-1.0, 0.0, 0.0),
            Vector3::new(0.0, -1.0, 0.0),
        ]
    }

    #[test]
    fn inside_is_positive_for_counter_clockwise_pads() {
        let g = Vector3::new(0.0, 0.0, -9.81);
        let pads = square();
        let cm = Vector3::new(0.1, 0.2, 1.0);
        for i in 0..4 {
            let (sd, n) = stability_distance(&g, &cm, &pads[i], &pads[(i + 1) % 4]).unwrap();
            assert!(sd > 0.0);
            // n points away from the footprint centre.
            assert!(n.dot(&((pads[i] + pads[(i + 1) % 4]) * 0.5)) > 0.0);
        }
        // Moving the CM outside wall 0-1 makes its SD negative, by the distance outside.
        let out = Vector3::new(1.0, 1.0, 0.5);
        let (sd, n) = stability_distance(&g, &out, &pads[0], &pads[1]).unwrap();
        assert!((sd + (2.0f64).sqrt() / 2.0).abs() < 1e-12);
        assert!(overturn_velocity(&Vector3::new(1.0, 1.0, 0.0), &n) > 0.0);
    }

    fn e(kinetic: f64, stored: f64) -> EnergyReport {
        EnergyReport {
            kinetic_j: kinetic,
            honeycomb_stored_j: stored,
            ..EnergyReport::default()
        }
    }

    fn tracker() -> StabilityTracker {
        let criteria = Stability {
            kinetic_energy_fraction: 0.1,
            counted_energy: CountedEnergy::KineticAndStored,
            min_separation_velocity: 0.0,
            walls: WallRule::All,
            terminate_on_decision: true,
            settled_tolerance: None,
        };
        StabilityTracker::new(&criteria, Vector3::new(0.0, 0.0, -9.81), 4, 100.0)
    }

    fn pads(in_contact: bool) -> [PadView; 4] {
        square().map(|position| PadView {
            position,
            in_contact,
            touched: true,
        })
    }

    #[test]
    fn distances_stay_defined_without_gravity_and_before_any_wall_counts() {
        // No gravity: measured along the surface normal, the same as under a vertical g.
        let criteria = Stability {
            walls: WallRule::TouchedDown,
            ..tracker().criteria
        };
        let mut t = StabilityTracker::new(&criteria, Vector3::zeros(), 4, 100.0);
        let airborne = square().map(|position| PadView {
            position,
            in_contact: false,
            touched: false,
        });
        let cm = Vector3::new(0.1, 0.2, 1.0);
        t.update(0.0, &cm, &Vector3::zeros(), None, &e(50.0, 0.0), &airborne);
        let mut g = tracker();
        g.update(0.0, &cm, &Vector3::zeros(), None, &e(50.0, 0.0), &airborne);
        for (a, b) in t.distances().iter().zip(g.distances()) {
            assert!((a - b).abs() < 1e-15, "{a} vs {b}");
        }
        assert!(t.distances().iter().all(|d| d.is_finite()));
        // No wall counted yet (no footpad down): the summary's minimum is that of every wall.
        let smallest = t.distances().iter().copied().fold(f64::INFINITY, f64::min);
        assert_eq!(t.min_distance(), smallest);
    }

    #[test]
    fn crossing_a_wall_is_unstable_with_the_interpolated_velocity() {
        let mut t = tracker();
        let v0 = Vector3::new(1.0, 1.0, 0.0);
        t.update(
            0.0,
            &Vector3::new(0.4, 0.4, 1.0),
            &v0,
            None,
            &e(50.0, 0.0),
            &pads(true),
        );
        assert_eq!(t.decision(), None);
        // From SD = +0.1/√2 to −0.1/√2: the crossing is halfway, at the mean velocity.
        let v1 = Vector3::new(3.0, 3.0, 0.0);
        t.update(
            0.1,
            &Vector3::new(0.6, 0.6, 1.0),
            &v1,
            Some(&v0),
            &e(50.0, 0.0),
            &pads(true),
        );
        assert_eq!(t.decision(), Some((Outcome::Unstable, 0.1)));
        let expected: f64 = Vector3::new(2.0, 2.0, 0.0).norm();
        assert!((t.overturn_velocity().unwrap() - expected).abs() < 1e-12);
        assert!(t.terminates());
    }

    #[test]
    fn stable_needs_low_energy_and_both_critical_pads_down() {
        let mut t = tracker();
        let cm = Vector3::new(0.0, 0.0, 1.0);
        let v = Vector3::zeros();
        t.update(0.0, &cm, &v, None, &e(20.0, 0.0), &pads(true));
        assert_eq!(t.decision(), None, "kinetic energy above 10 %");
        t.update(0.1, &cm, &v, None, &e(5.0, 0.0), &pads(false));
        assert_eq!(t.decision(), None, "critical footpads off the surface");
        t.update(0.2, &cm, &v, None, &e(5.0, 0.0), &pads(true));
        assert_eq!(t.decision(), Some((Outcome::Stable, 0.2)));
        assert!((t.min_distance() - (0.5f64).sqrt()).abs() < 1e-12);
    }

    #[test]
    fn a_crossing_after_the_stable_conditions_decides_unstable_and_closes_the_measurements() {
        let mut t = tracker();
        let v = Vector3::zeros();
        let inside = Vector3::new(0.0, 0.0, 1.0);
        t.update(0.1, &inside, &v, None, &e(5.0, 0.0), &pads(true));
        assert_eq!(t.decision(), Some((Outcome::Stable, 0.1)));
        assert!(!t.terminates(), "a stable decision ends no run");
        let mut x = crate::summary::Extremes::new(4, Default::default());
        x.follow(&t);
        x.update_pitch_rate(0.1, 0.5);
        // The vehicle later tips over wall 0 (pads 0-1).
        let out = Vector3::new(0.6, 0.6, 1.0);
        let toward = Vector3::new(1.0, 1.0, 0.0);
        t.update(0.2, &out, &toward, Some(&v), &e(5.0, 0.0), &pads(true));
        assert_eq!(t.decision(), Some((Outcome::Unstable, 0.2)));
        assert_eq!(t.stable_conditions_time(), Some(0.1));
        assert!(t.terminates());
        let at_crossing = t.min_distance();
        x.update_pitch_rate(0.2, 0.7);
        x.follow(&t);
        // Past the crossing nothing more is measured.
        let further = Vector3::new(2.0, 2.0, 1.0);
        t.update(
            0.3,
            &further,
            &toward,
            Some(&toward),
            &e(5.0, 0.0),
            &pads(true),
        );
        x.update_pitch_rate(0.3, 3.0);
        assert_eq!(t.min_distance(), at_crossing);
        assert_eq!(t.decision(), Some((Outcome::Unstable, 0.2)));
        let s = crate::summary::Summary::new(
            "test",
            "test",
            Default::default(),
            crate::summary::Progress {
                t: 0.3,
                steps: 3,
                force_evaluations: 3,
                first_contact_s: vec![Some(0.0); 4],
            },
            &t,
            &x,
            EnergyReport::default(),
        );
        assert_eq!(s.peak_pitch_rate_rad_s, 0.7);
        assert_eq!(s.stable_conditions_time_s, Some(0.1));
    }

    #[test]
    fn rounding_noise_across_the_critical_wall_does_not_block_a_stable_decision() {
        let cm = Vector3::new(0.0, 0.0, 1.0);
        // Wall 0 (pads 0-1) has outward normal (1, 1, 0)/√2: noise toward it, then a real
        // velocity toward it.
        let noise = Vector3::new(1e-11, 1e-11, 0.0);
        let mut t = tracker();
        t.update(0.0, &cm, &noise, None, &e(5.0, 0.0), &pads(true));
        assert_eq!(t.decision(), Some((Outcome::Stable, 0.0)));
        let mut t = tracker();
        let toward = Vector3::new(1e-3, 1e-3, 0.0);
        t.update(0.0, &cm, &toward, None, &e(5.0, 0.0), &pads(true));
        assert_eq!(t.decision(), None, "moving toward the critical wall");
    }

    #[test]
    fn energy_parked_in_the_gear_blocks_a_stable_decision_unless_kinetic_alone_counts() {
        let cm = Vector3::new(0.0, 0.0, 1.0);
        let v = Vector3::zeros();
        // 5 J kinetic (below 10 % of 100 J) but 30 J stored in bottomed struts.
        let mut t = tracker();
        t.update(0.0, &cm, &v, None, &e(5.0, 30.0), &pads(true));
        assert_eq!(t.decision(), None, "the gear still holds 35 % of KE0");
        t.update(0.1, &cm, &v, None, &e(5.0, 4.0), &pads(true));
        assert_eq!(t.decision(), Some((Outcome::Stable, 0.1)));
        let criteria = Stability {
            counted_energy: CountedEnergy::Kinetic,
            ..t.criteria.clone()
        };
        let mut t = StabilityTracker::new(&criteria, Vector3::new(0.0, 0.0, -9.81), 4, 100.0);
        t.update(0.0, &cm, &v, None, &e(5.0, 30.0), &pads(true));
        assert_eq!(
            t.decision(),
            Some((Outcome::Stable, 0.0)),
            "the report's text"
        );
    }
}
