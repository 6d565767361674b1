//! The least energy a strut takes to reach a stroke from its committed state: a convex
//! minorant of its stored energy plus the work it dissipates on the way, with the convex
//! conjugate the settled end's certificate needs (docs/errata.md, "Settled landings: an early
//! end with a proof").
//!
//! On one side (the loading direction of a honeycomb, or the primary's extension stop) the
//! strut carries nothing up to its permanent set `x₀`, then loads along its rebound line at K_B
//! up to its largest stroke x_max, then crushes on its virgin curve, whose load at x_max is at
//! least the rebound line's and whose slope over the next ε is at least the curve's least
//! slope k_v there. So the energy to reach x on that side is at least
//!
//! `Ê(x) = 0` (x ≤ x₀), `½·K_B·(x − x₀)²` (x₀ ≤ x ≤ x_max),
//! `Ê(x_max) + S·(x − x_max) + ½·k_v·(x − x_max)²` past x_max, with `S = K_B·(x_max − x₀)`,
//!
//! a convex function of x (its slope never falls) that lies at or below the stored energy
//! `F²/(2·K_B)` the energy report counts on the rebound line and below the stored energy plus
//! the crush work past x_max. The two sides join at zero stroke through the band where the
//! strut carries nothing.

use super::{CrushMemory, DoubleActingHoneycomb, DoubleActingMemory, Honeycomb, Stop};

/// One side of a strut's minorant, in that side's own stroke (m, positive into the side).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Side {
    /// Where the side starts to load (its permanent set x₀, ≥ 0), m.
    start: f64,
    /// Its elastic rate K_B (the extension stop's loading rate), N/m.
    rate: f64,
    /// Its largest stroke x_max, m (for an engaged end stop, its deepest depth; infinite
    /// for a stop not engaged).
    top: f64,
    /// The least slope of the virgin curve over the tolerance past x_max, N/m (≥ 0).
    beyond: f64,
    /// The exponent n of the load between x₀ and x_max, `F = S·((x − x₀)/(x_max − x₀))^n`:
    /// 1 on a rebound line, 2/e² − 1 on an engaged stop's reloading curve ([`crate::Stop`];
    /// infinite for a plastic stop, which carries nothing below its deepest depth).
    exponent: f64,
    /// Whether the side's largest stroke is a maximum the summary reports (a honeycomb's;
    /// not the extension stop's).
    reported: bool,
}

impl Side {
    /// The side of honeycomb `h` with the committed `memory`, if the certificate can hold on
    /// it: its end stop not engaged (a stroke past the capacity is left to run), and its
    /// virgin curve not falling over the `tolerance` (m) past x_max. Past the capacity the
    /// curve goes on at the stroke-out rate, the exhausted honeycomb's plateau load plus a
    /// freshly loaded stop.
    fn honeycomb(h: &Honeycomb, memory: CrushMemory, tolerance: f64) -> Option<Side> {
        let top = memory.max_stroke();
        if memory.stop_depth > 0.0 {
            return None;
        }
        let beyond = h.curve.least_slope(top, top + tolerance);
        (beyond >= 0.0).then_some(Side {
            start: h.permanent_set(memory),
            rate: h.backoff_rate,
            top,
            beyond,
            exponent: 1.0,
            reported: true,
        })
    }

    /// The primary's extension stop `stop` at the depth `deepest` (m) of its current
    /// engagement (0: open, loading afresh from zero extension at its rate): below the
    /// deepest depth it reloads along its unloading curve, then along its loading line.
    fn extension_stop(stop: &Stop, deepest: f64) -> Side {
        let e2 = stop.restitution * stop.restitution;
        Side {
            start: 0.0,
            rate: stop.rate,
            top: if deepest > 0.0 {
                deepest
            } else {
                f64::INFINITY
            },
            beyond: stop.rate,
            exponent: if deepest > 0.0 { 2.0 / e2 - 1.0 } else { 1.0 },
            reported: false,
        }
    }

    /// The energy under the load from x₀ to stroke `x` in [x₀, x_max], J.
    fn below_top(&self, x: f64) -> f64 {
        let span = self.top - self.start;
        let u = x - self.start;
        if self.exponent == 1.0 || !span.is_finite() {
            return 0.5 * self.rate * u * u;
        }
        let load = self.rate * span * (u / span).powf(self.exponent);
        load * u / (self.exponent + 1.0)
    }

    /// The slope of the rebound line at x_max, S = K_B·(x_max − x₀), N.
    fn top_slope(&self) -> f64 {
        self.rate * (self.top - self.start)
    }

    /// Ê at stroke `x` (m, this side's sense), J.
    fn energy(&self, x: f64) -> f64 {
        if x <= self.start {
            0.0
        } else if x <= self.top {
            self.below_top(x)
        } else {
            let d = x - self.top;
            self.energy(self.top) + self.top_slope() * d + 0.5 * self.beyond * d * d
        }
    }

    /// The conjugate sup_x (f·x − Ê(x)) for a load `f` ≥ 0 (N) into the side, J; `None`
    /// where it is infinite (the side would crush on a plateau under `f`).
    fn conjugate(&self, f: f64) -> Option<f64> {
        let slope = self.top_slope();
        if f <= slope {
            // Where the load reaches f: x − x₀ = (x_max − x₀)·(f/S)^(1/n), and the energy
            // under the curve up to there is f·(x − x₀)/(n + 1).
            let n = self.exponent;
            let u = if n == 1.0 || !slope.is_finite() {
                f / self.rate
            } else {
                (self.top - self.start) * (f / slope).powf(1.0 / n)
            };
            // n/(n + 1) as 1/(1 + 1/n): 1 for a plastic stop (n infinite).
            return Some(f * self.start + f * u / (1.0 + 1.0 / n));
        }
        if self.beyond <= 0.0 {
            return None;
        }
        let x = self.top + (f - slope) / self.beyond;
        Some(f * x - self.energy(x))
    }
}

/// A strut's minorant over both sides, in its stroke (m, the strut's positive sense: the
/// primary's compression, a secondary's tension).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StrutReach {
    upper: Side,
    lower: Side,
}

impl StrutReach {
    /// A primary strut's compression honeycomb `h` with its committed `memory` above, and
    /// below it the honeycomb's own stop as the strut's extension stop at the depth
    /// `extension_depth` (m) of its current engagement; `None` while its bottoming stop is
    /// engaged.
    pub fn crushing_with_extension_stop(
        h: &Honeycomb,
        memory: CrushMemory,
        extension_depth: f64,
        tolerance: f64,
    ) -> Option<Self> {
        Some(StrutReach {
            upper: Side::honeycomb(h, memory, tolerance)?,
            lower: Side::extension_stop(&h.stop, extension_depth),
        })
    }

    /// A secondary strut's double-acting honeycomb `h` with the committed `memory`: tension
    /// above, compression below; `None` as for [`StrutReach::crushing_with_extension_stop`].
    pub fn secondary(
        h: &DoubleActingHoneycomb,
        memory: DoubleActingMemory,
        tolerance: f64,
    ) -> Option<Self> {
        Some(StrutReach {
            upper: Side::honeycomb(&h.tension, memory.tension, tolerance)?,
            lower: Side::honeycomb(&h.compression, memory.compression, tolerance)?,
        })
    }

    /// The band of strokes (m) where the strut carries nothing: from the lower side's
    /// permanent set to the upper's.
    pub fn band(&self) -> (f64, f64) {
        (-self.lower.start, self.upper.start)
    }

    /// The minorant Ê at stroke `s`, J.
    pub fn energy(&self, s: f64) -> f64 {
        if s >= 0.0 {
            self.upper.energy(s)
        } else {
            self.lower.energy(-s)
        }
    }

    /// Its conjugate Ê*(f) = sup_s (f·s − Ê(s)) at load `f` (N, the strut's positive sense),
    /// J; `None` where infinite.
    pub fn conjugate(&self, f: f64) -> Option<f64> {
        if f >= 0.0 {
            self.upper.conjugate(f)
        } else {
            self.lower.conjugate(-f)
        }
    }

    /// The Fenchel–Young gap Ê(s) + Ê*(f) − f·s ≥ 0 at stroke `s` (m) and load `f` (N), J:
    /// the least energy the strut holds at `s` beyond what the load `f` accounts for. `None`
    /// where the conjugate is infinite.
    pub fn gap(&self, s: f64, f: f64) -> Option<f64> {
        Some((self.energy(s) + self.conjugate(f)? - f * s).max(0.0))
    }

    /// The strokes the reported maxima would have to pass to move by the tolerance, m: x_max +
    /// ε above, −(x_max + ε) below (−∞ for the primary, whose extension has no maximum).
    pub fn limits(&self, tolerance: f64) -> (f64, f64) {
        let lower = if self.lower.reported {
            -(self.lower.top + tolerance)
        } else {
            f64::NEG_INFINITY
        };
        (lower, self.upper.top + tolerance)
    }

    /// The interval of strokes (m) around `s` (m) where the gap at load `f` (N) stays within
    /// `budget` (J), clipped to `bounds`: by bisection on the convex gap, `s` inside it.
    pub fn reach(&self, s: f64, f: f64, budget: f64, bounds: (f64, f64)) -> (f64, f64) {
        let within = |x: f64| self.gap(x, f).is_some_and(|g| g <= budget);
        let edge = |mut inside: f64, mut outside: f64| {
            if within(outside) {
                return outside;
            }
            for _ in 0..48 {
                let mid = 0.5 * (inside + outside);
                if within(mid) {
                    inside = mid;
                } else {
                    outside = mid;
                }
            }
            outside
        };
        (edge(s, bounds.0), edge(s, bounds.1))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gear::{PrimaryMemory, PrimaryStrutLaw};
    use crate::honeycomb::{LoadStroke, Stage};

    fn honeycomb() -> Honeycomb {
        let stages = [Stage {
            crush_load: 1000.0,
            stroke_end: 0.1,
        }];
        Honeycomb::new(LoadStroke::new(1e5, &stages, 1e7).unwrap(), 1e6, 0.5).unwrap()
    }

    /// The minorant lies below the energy the strut really takes: its stored energy on the
    /// rebound line, that plus the crush work past x_max (the area under the virgin curve).
    #[test]
    fn the_minorant_lies_below_the_energy_to_reach_a_stroke() {
        let h = honeycomb();
        let mut memory = CrushMemory::default();
        h.commit(0.05, &mut memory);
        let side = Side::honeycomb(&h, memory, 1e-3).unwrap();
        for i in 0..=100 {
            let x = 0.04 + 1e-4 * f64::from(i);
            let stored_then_crushed = if x <= 0.05 {
                h.stored_energy(x, memory)
            } else {
                // Rebound energy at x_max plus the plateau work from x_max to x.
                h.stored_energy(0.05, memory) + 1000.0 * (x - 0.05)
            };
            assert!(
                side.energy(x) <= stored_then_crushed * (1.0 + 1e-12) + 1e-12,
                "x = {x}"
            );
        }
        // On the rebound line the minorant is the stored energy itself.
        let x = 0.0495;
        assert!((side.energy(x) - h.stored_energy(x, memory)).abs() < 1e-9);
    }

    /// The conjugate is the supremum it claims: no stroke beats it, and the gap is zero where
    /// the minorant's slope equals the load.
    #[test]
    fn the_conjugate_is_the_supremum_and_the_gap_vanishes_at_equilibrium() {
        let h = honeycomb();
        let mut memory = DoubleActingMemory::default();
        let d = DoubleActingHoneycomb {
            tension: h,
            compression: h,
        };
        d.commit(0.03, &mut memory);
        d.commit(-0.02, &mut memory);
        let reach = StrutReach::secondary(&d, memory, 1e-3).unwrap();
        for f in [-900.0, -300.0, 0.0, 200.0, 950.0] {
            let conj = reach.conjugate(f).unwrap();
            for i in -400..=400 {
                let s = 1e-4 * f64::from(i);
                assert!(f * s - reach.energy(s) <= conj + 1e-9, "f = {f}, s = {s}");
            }
        }
        // The load 500 N on the tension rebound line: the gap vanishes at its stroke.
        let s = 0.03 - (1000.0 - 500.0) / 1e6;
        assert!(reach.gap(s, 500.0).unwrap() < 1e-9);
        // A load past the plateau crushes without end: no finite conjugate.
        assert!(reach.conjugate(1500.0).is_none());
    }

    /// The reachable interval: the strokes where the gap is within the budget, and no further.
    #[test]
    fn the_reach_is_where_the_gap_fits_the_budget() {
        let h = honeycomb();
        let mut memory = PrimaryMemory::default();
        let law = PrimaryStrutLaw {
            honeycomb: h,
            viscous: crate::Viscous::NONE,
            bearing: crate::Bearing {
                friction_coefficient: 0.0,
                inner_cylinder_length: 1.0,
                initial_overlap: 0.5,
            },
        };
        law.commit(0.05, &mut memory);
        let reach = law.reach(memory, 1e-3).unwrap();
        let f = 400.0;
        let s = 0.05 - (1000.0 - f) / 1e6;
        let (lo, hi) = reach.reach(s, f, 0.02, (-1.0, 0.051));
        // ½·K_B·Δ² = 0.02 J on the rebound line: Δ = 0.2 mm either way.
        assert!((hi - (s + 2e-4)).abs() < 1e-9, "{hi}");
        assert!((lo - (s - 2e-4)).abs() < 1e-9, "{lo}");
        // Past the limit it reports the limit.
        assert_eq!(reach.reach(s, f, 10.0, (-1.0, 0.051)).1, 0.051);
        // Hanging on its extension stop (e = 0.5, n = 7) at 1 mm of its deepest 2 mm: the
        // minorant is the stop's reloading curve, its conjugate the supremum.
        let mut hanging = PrimaryMemory::default();
        law.commit(0.05, &mut hanging);
        law.commit(-0.002, &mut hanging);
        law.commit(-0.001, &mut hanging);
        let reach = law.reach(hanging, 1e-3).unwrap();
        let f = law.stroke_force(-0.001, hanging);
        assert!(f < 0.0);
        assert!(reach.gap(-0.001, f).unwrap() < 1e-9 * f.abs() * 1e-3);
        assert!((reach.energy(-0.001) - law.stored_energy(-0.001, hanging)).abs() < 1e-9);
        for g in [-30.0, -10.0, f] {
            let conj = reach.conjugate(g).unwrap();
            for i in 0..=300 {
                let s = -1e-5 * f64::from(i);
                assert!(g * s - reach.energy(s) <= conj + 1e-9, "g = {g}, s = {s}");
            }
        }
        assert_eq!(reach.limits(1e-3).0, f64::NEG_INFINITY);
        // A plastic extension stop (e = 0) carries nothing below its deepest depth: the
        // conjugate is the load times that depth, finite.
        let plastic = PrimaryStrutLaw {
            honeycomb: Honeycomb {
                stop: Stop::new(law.honeycomb.stop.rate, 0.0).unwrap(),
                ..law.honeycomb
            },
            ..law
        };
        let reach = plastic.reach(hanging, 1e-3).unwrap();
        assert_eq!(reach.energy(-0.001), 0.0);
        let conj = reach.conjugate(-10.0).unwrap();
        assert!((conj - 10.0 * 0.002).abs() < 1e-12, "{conj}");
        // On its bottoming stop there is no certificate.
        law.commit(0.101, &mut memory);
        assert!(law.reach(memory, 1e-3).is_none());
    }
}
