//! The multibody step between the end stops (docs/engines.md, "A longer step between the
//! stops").
//!
//! The engines' base step resolves the stiffest explicit gear mode ([`crate::step`]): on a
//! gear whose end stops (bottoming past a capacity, the primary's extension stop) load far
//! more stiffly than its honeycombs rebound, that mode is a stop's, and it exists only while a
//! stop is engaged. Between the stops the stiffest explicit mode is the honeycombs' (their
//! rebound K_B and onset ramps, eqs. 49-52), ω_soft; the engine may then take `m` base steps
//! at once, the largest integer with m·ω_soft ≤ ω_max (so every mode it still integrates
//! explicitly keeps the base step's ω·Δt), at most the scenario's `engines.rapier.stride`.
//! A long step is taken only when no stop is engaged and none can engage within it: every
//! strut's gap to each of its stops is more than twice what the strut can stroke in the long
//! step at its current rate plus the rate's change over the last step, scaled to the long
//! step. The stops thus always engage, load and release under the base step, and the long
//! step never spans an engagement. A scene whose own explicit mechanisms are tied to the base
//! step (curbs, a descent engine's nozzle, the obstacle walls and spikes, `crate::wall`, which
//! is as stiff as the base step resolves) keeps the base step throughout: the stride changes
//! no law. Every rule is a ratio of like
//! quantities and holds over all legs alike, so a Froude twin and a mirrored landing step
//! alike.

use crate::step::{gear_modes, soft_rate, stiffest_rate, Mode};
use crate::strut::StrutKinematics;
use touchdown_laws::{GearLaws, GearMemory};
use touchdown_scenario::Scenario;

/// Safety factor on what a strut can stroke in a long step, against its gap to a stop.
const REACH_FACTOR: f64 = 2.0;

/// The step rule of a multibody landing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepRule {
    /// The base step, s: the stiffest explicit gear mode's ([`crate::step`]).
    base: f64,
    /// Base steps per long step (1: the base step throughout).
    stride: u32,
    /// Each honeycomb's capacity, m: primary, secondary compression, secondary tension.
    capacity: [f64; 3],
}

impl StepRule {
    /// The rule of `sc` with its `laws`, on an engine whose base step is `base` (s) and whose
    /// long step may take up to `max_stride` base steps (1 where the scene's own explicit
    /// mechanisms tie it to the base step).
    pub fn new(sc: &Scenario, laws: &GearLaws, base: f64, max_stride: u32) -> StepRule {
        let stiffest = omega_max(&gear_modes(sc, laws, stiffest_rate));
        let soft = omega_max(&gear_modes(sc, laws, soft_rate));
        // stiffest ≥ soft by construction: the soft rates are among the stiffest's.
        let by_modes = if soft > 0.0 {
            (stiffest / soft).floor()
        } else {
            1.0
        };
        let stride = by_modes.min(f64::from(max_stride)).max(1.0) as u32;
        let c = laws.capacities();
        StepRule {
            base,
            stride,
            capacity: [c[0].0, c[1].0, c[2].0],
        }
    }

    /// The long step, s (the base step where the scene allows none longer).
    pub fn long(&self) -> f64 {
        self.base * f64::from(self.stride)
    }

    /// The next step, s, at the gears' kinematics `kin` with the committed `memory`, the
    /// kinematics before the last step `previous` (which was `last` s long), the landing at
    /// `t` s of `t_end`: the long step if no stop is engaged and none can engage within it,
    /// and it ends by `t_end`; the base step otherwise.
    pub fn next(
        &self,
        kin: &[StrutKinematics],
        previous: &[StrutKinematics],
        memory: &[GearMemory],
        last: f64,
        t: f64,
        t_end: f64,
    ) -> f64 {
        let long = self.long();
        if self.stride == 1 || t + long > t_end * (1.0 + 1e-12) || last <= 0.0 {
            return self.base;
        }
        let [cap_p, cap_c, cap_t] = self.capacity;
        let clear = |gaps: &[f64], rate: f64, rate_before: f64| {
            let reach =
                REACH_FACTOR * long * (rate.abs() + (rate - rate_before).abs() * long / last);
            gaps.iter().all(|&g| g > reach)
        };
        let all_clear = kin.iter().zip(previous).zip(memory).all(|((k, p), m)| {
            let open = m.primary.extension_depth == 0.0
                && m.primary.compression.stop_depth == 0.0
                && m.secondary
                    .iter()
                    .all(|s| s.tension.stop_depth == 0.0 && s.compression.stop_depth == 0.0);
            open && clear(&[k.c, cap_p - k.c], k.c_dot, p.c_dot)
                && (0..2).all(|j| clear(&[cap_t - k.s[j], cap_c + k.s[j]], k.s_dot[j], p.s_dot[j]))
        });
        if all_clear {
            long
        } else {
            self.base
        }
    }
}

/// The largest angular frequency among `modes`, rad/s.
fn omega_max(modes: &[Mode; 2]) -> f64 {
    modes[0].omega.max(modes[1].omega)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scenario(name: &str) -> (Scenario, GearLaws) {
        let path = format!("{}/../../scenarios/{name}", env!("CARGO_MANIFEST_DIR"));
        let sc = Scenario::load(&path).unwrap();
        let laws = GearLaws::from_scenario(&sc).unwrap();
        (sc, laws)
    }

    #[test]
    fn the_long_step_is_the_base_step_times_the_stops_stiffness_ratio_where_the_scene_allows() {
        // The 1/6-scale model: stops at 870,000 lbf/ft against a rebound of 40,000, an ω ratio
        // of √21.75 = 4.66: four base steps at most.
        let (sc, laws) = scenario("table-i-2-2-vv8.toml");
        for (max, long) in [(1, 1), (2, 2), (4, 4), (8, 4)] {
            let rule = StepRule::new(&sc, &laws, 2.0e-5, max);
            assert_eq!(rule.long(), 2.0e-5 * f64::from(long), "at most {max}");
        }
        // Curbs, a descent engine and the spikes' walls are applied explicitly at the base
        // step's rates.
        for tied in [
            "curb-slide.toml",
            "thrust-tailoff.toml",
            "table-i-2-2-vv8.toml",
        ] {
            let (sc, _) = scenario(tied);
            let (gear, _) = crate::GearModel::new(&sc, 1.0e-5, 4).unwrap();
            assert_eq!(gear.long_step(), 1.0e-5, "{tied}");
        }
    }

    #[test]
    fn a_long_step_is_taken_only_clear_of_every_stop() {
        let (sc, laws) = scenario("table-i-2-2-vv8.toml");
        let rule = StepRule::new(&sc, &laws, 1.0e-4, 2);
        let [cap_p, cap_c, cap_t] = rule.capacity;
        let h = rule.long();
        // A gear stroking at 1 m/s, half-way along each stroke.
        let mid = StrutKinematics {
            c: 0.5 * cap_p,
            c_dot: 1.0,
            s: [0.5 * cap_t, -0.5 * cap_c],
            s_dot: [1.0, -1.0],
            ..Default::default()
        };
        let memory = [GearMemory::default()];
        let next = |k: StrutKinematics, before: StrutKinematics, m: &[GearMemory], t: f64| {
            rule.next(&[k], &[before], m, rule.base, t, 1.0)
        };
        assert_eq!(next(mid, mid, &memory, 0.0), h);
        // Not before the first step, nor past the end time.
        assert_eq!(rule.next(&[mid], &[mid], &memory, 0.0, 0.0, 1.0), rule.base);
        assert_eq!(next(mid, mid, &memory, 1.0 - 0.5 * h), rule.base);
        // Within twice a long step's stroke of each stop, or accelerating towards it.
        let gap = 2.0 * h * 1.0;
        let cases = [
            StrutKinematics {
                c: cap_p - 0.9 * gap,
                ..mid
            },
            StrutKinematics {
                c: 0.9 * gap,
                c_dot: -1.0,
                ..mid
            },
            StrutKinematics {
                s: [cap_t - 0.9 * gap, mid.s[1]],
                ..mid
            },
            StrutKinematics {
                s: [mid.s[0], -cap_c + 0.9 * gap],
                ..mid
            },
        ];
        for k in cases {
            assert_eq!(next(k, k, &memory, 0.0), rule.base, "{k:?}");
        }
        // At rest 0.9 of the gap from the stop, but accelerated from rest to 1 m/s over the
        // last base step: the rate and its change reach it.
        let near = StrutKinematics {
            c: cap_p - 0.9 * gap,
            c_dot: 0.0,
            ..mid
        };
        assert_eq!(next(near, near, &memory, 0.0), h);
        let moving = StrutKinematics { c_dot: 0.5, ..near };
        assert_eq!(next(moving, near, &memory, 0.0), rule.base);
        // An engaged stop, whatever the stroke now.
        let mut engaged = memory;
        engaged[0].primary.extension_depth = 1.0e-6;
        assert_eq!(next(mid, mid, &engaged, 0.0), rule.base);
        let mut engaged = memory;
        engaged[0].secondary[1].compression.stop_depth = 1.0e-6;
        assert_eq!(next(mid, mid, &engaged, 0.0), rule.base);
    }
}
