//! Struts past their capacity: a honeycomb stroked beyond the end of its last crush stage
//! bottoms on its end stop (docs/errata.md, "End stops"), whose law is an estimate acting at
//! loads the honeycomb was never sized for. Every outcome names such struts, how far past and
//! how hard the stop pushed, so that a landing with a bottomed strut is never read as simply
//! stable.

use serde::{Deserialize, Serialize};

/// Where one honeycomb's capacity ends and how stiff its stop is beyond it.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Capacity {
    /// Stroke at which the last crush stage ends and the stop begins, m (in the stroke every
    /// engine reports: behind a trunnion spring, the capacity of the modified diagram).
    pub stroke_m: f64,
    /// The stop's loading rate K_so, N/m: at a depth d past the capacity it carries K_so·d
    /// beyond the last crush load.
    pub stop_rate_n_m: f64,
}

/// The capacities of a lander's struts, the same on every leg (the scenario gives one primary
/// and one secondary strut).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct StrutCapacities {
    /// Primary strut, compression.
    pub primary: Capacity,
    /// Secondary struts, compression.
    pub secondary_compression: Capacity,
    /// Secondary struts, tension.
    pub secondary_tension: Capacity,
}

/// One strut that went past its capacity during a landing.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PastCapacity {
    /// The strut, named as in campaign records: `leg2.primary`,
    /// `leg1.secondary_3_1.tension`, `leg4.secondary_4_1.compression`.
    pub strut: String,
    /// Its largest stroke, m.
    pub max_stroke_m: f64,
    /// Its capacity, m.
    pub capacity_m: f64,
    /// How far past the capacity it went, m (> 0).
    pub past_capacity_m: f64,
    /// Its largest stroke as a fraction of the capacity (> 1).
    pub stroke_of_capacity: f64,
    /// The largest force its stop carried beyond the last crush load, N: K_so times the depth
    /// past the capacity (the stop loads linearly, so its deepest point is its peak).
    pub peak_stop_force_n: f64,
}

/// The two secondaries of a leg as named in records.
pub const SECONDARY_NAMES: [&str; 2] = ["3_1", "4_1"];

impl StrutCapacities {
    /// The capacities from (capacity m, stop rate N/m) of the primary in compression, the
    /// secondaries in compression and the secondaries in tension, as the gear laws give them.
    pub fn new([primary, compression, tension]: [(f64, f64); 3]) -> StrutCapacities {
        let c = |(stroke_m, stop_rate_n_m)| Capacity {
            stroke_m,
            stop_rate_n_m,
        };
        StrutCapacities {
            primary: c(primary),
            secondary_compression: c(compression),
            secondary_tension: c(tension),
        }
    }

    /// The struts past their capacity, in leg order (primary, then each secondary in
    /// compression and in tension), given each leg's largest primary stroke and its
    /// secondaries' largest compression and tension strokes (m, positive).
    pub fn past(
        &self,
        primary: &[f64],
        secondary_compression: &[[f64; 2]],
        secondary_tension: &[[f64; 2]],
    ) -> Vec<PastCapacity> {
        let mut out = Vec::new();
        for (i, &p) in primary.iter().enumerate() {
            let leg = i + 1;
            self.primary.check(format!("leg{leg}.primary"), p, &mut out);
            for (j, name) in SECONDARY_NAMES.iter().enumerate() {
                self.secondary_compression.check(
                    format!("leg{leg}.secondary_{name}.compression"),
                    secondary_compression[i][j],
                    &mut out,
                );
                self.secondary_tension.check(
                    format!("leg{leg}.secondary_{name}.tension"),
                    secondary_tension[i][j],
                    &mut out,
                );
            }
        }
        out
    }
}

impl Capacity {
    /// Adds `strut` to `out` if its largest stroke `max_stroke` (m) went past this capacity.
    fn check(&self, strut: String, max_stroke: f64, out: &mut Vec<PastCapacity>) {
        let past = max_stroke - self.stroke_m;
        if past > 0.0 {
            out.push(PastCapacity {
                strut,
                max_stroke_m: max_stroke,
                capacity_m: self.stroke_m,
                past_capacity_m: past,
                stroke_of_capacity: max_stroke / self.stroke_m,
                peak_stop_force_n: self.stop_rate_n_m * past,
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_struts_past_their_capacity_are_named_with_their_stop_force() {
        let caps = StrutCapacities {
            primary: Capacity {
                stroke_m: 0.1,
                stop_rate_n_m: 1e7,
            },
            secondary_compression: Capacity {
                stroke_m: 0.02,
                stop_rate_n_m: 2e6,
            },
            secondary_tension: Capacity {
                stroke_m: 0.03,
                stop_rate_n_m: 3e6,
            },
        };
        // Leg 1 at its capacities exactly (the stop carries nothing there); leg 2's primary
        // 1 mm past and its 4-1 secondary 2 mm past in tension.
        let past = caps.past(
            &[0.1, 0.101],
            &[[0.02, 0.0], [0.01, 0.0]],
            &[[0.0, 0.03], [0.0, 0.032]],
        );
        let names: Vec<&str> = past.iter().map(|p| p.strut.as_str()).collect();
        assert_eq!(names, ["leg2.primary", "leg2.secondary_4_1.tension"]);
        assert!((past[0].past_capacity_m - 0.001).abs() < 1e-12);
        assert!((past[0].peak_stop_force_n - 1e4).abs() < 1e-6);
        assert!((past[1].stroke_of_capacity - 0.032 / 0.03).abs() < 1e-12);
        assert!((past[1].peak_stop_force_n - 6e3).abs() < 1e-6);
    }
}
