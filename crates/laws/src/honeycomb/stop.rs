//! The end stop: bottoming or full extension, loading at K_so and returning e² of its energy.

use crate::positive;
use crate::LawError;

/// An end stop: a strut bottoming past its capacity, or a primary strut pulled past its full
/// extension. Past its start by a depth d (m) it loads at `rate` K_so (N/m); below the deepest
/// depth d_max of its current engagement it unloads (and reloads) along
/// `K_so·d_max·(d/d_max)^n` with `n = 2/e² − 1`, which leaves d_max with the loading force,
/// returns to the stop's start with no permanent set, and gives back the fraction e² of the
/// energy K_so·d_max²/2 the stop took. An engagement ends when the stroke comes back to the
/// stop's start ([`Stop::commit`]): the next hit loads the stop afresh, so every hit returns e²
/// of what it brought (docs/errata.md, "End stops").
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stop {
    /// Loading rate K_so, N/m.
    pub rate: f64,
    /// Coefficient of restitution e, in [0, 1]: the stop returns e² of its loading energy.
    pub restitution: f64,
}

impl Stop {
    /// A stop loading at `rate` (N/m, > 0) with restitution `restitution` (in [0, 1]).
    pub fn new(rate: f64, restitution: f64) -> Result<Self, LawError> {
        positive("stop rate", rate)?;
        if !(0.0..=1.0).contains(&restitution) {
            return Err(LawError::Restitution(restitution));
        }
        Ok(Stop { rate, restitution })
    }

    /// The exponent n = 2/e² − 1 of the unloading curve (1 for an elastic stop; infinite for
    /// a plastic one).
    #[inline]
    fn exponent(&self) -> f64 {
        2.0 / (self.restitution * self.restitution) - 1.0
    }

    /// The stop's force beyond its start load, N (≥ 0), at depth `d` (m) past its start, its
    /// deepest committed depth being `d_max` (m).
    #[inline]
    pub fn force(&self, d: f64, d_max: f64) -> f64 {
        if d <= 0.0 {
            0.0
        } else if d >= d_max {
            self.rate * d
        } else if self.restitution == 0.0 {
            0.0
        } else {
            self.rate * d_max * (d / d_max).powf(self.exponent())
        }
    }

    /// The deepest point below d_max (m) at which the stop carries no force, m: 0, or d_max
    /// for a plastic stop.
    #[inline]
    pub fn slack(&self, d_max: f64) -> f64 {
        if self.restitution == 0.0 {
            d_max.max(0.0)
        } else {
            0.0
        }
    }

    /// The unloading rate at the deepest point, n·K_so, N/m. A plastic stop (e = 0) has none:
    /// below its deepest point it carries nothing, and leaving that point is a release of its
    /// load, not a stiffness (the limit of a curve that carries e²·K_so·d_max²/2 and falls to
    /// zero within d_max/n of the deepest point, both vanishing as e → 0; docs/errata.md,
    /// "End stops").
    pub fn unloading_rate(&self) -> f64 {
        if self.restitution == 0.0 {
            0.0
        } else {
            self.rate * self.exponent()
        }
    }

    /// The stiffest the stop gets, loading or unloading, N/m: max(K_so, n·K_so).
    pub fn stiffest_rate(&self) -> f64 {
        self.rate.max(self.unloading_rate())
    }

    /// Commits an accepted depth `d` (m) past the stop's start into the depth of the current
    /// engagement `deepest` (m): the deeper of the two while engaged; zero once the stroke is
    /// back at or before the stop's start, which ends the engagement.
    #[inline]
    pub fn commit(d: f64, deepest: &mut f64) {
        *deepest = if d > 0.0 { deepest.max(d) } else { 0.0 };
    }

    /// The energy the stop alone returns unloading from depth `d` (m), where it carries `f`
    /// (N), J: `f·d/(n + 1) = e²·f·d/2`, on its loading line and on its unloading curve alike.
    #[inline]
    pub fn returned_energy(&self, d: f64, f: f64) -> f64 {
        0.5 * self.restitution * self.restitution * f * d.max(0.0)
    }
}
