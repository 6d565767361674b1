//! The one-sided crushable honeycomb: its law, its crush memory, the branch a stroke lies on.

use super::{LoadStroke, Stop};
use crate::positive;
use crate::{series_rate, LawError};

/// The branch of a honeycomb law a stroke lies on (for diagnostics).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Branch {
    /// On the virgin curve, on an elastic onset ramp.
    Onset,
    /// On the virgin curve, on a crush plateau.
    Plateau,
    /// Below the largest stroke reached: the elastic backoff (rebound) line.
    Rebound,
    /// Past the capacity: the elastic stroke-out (bottoming) stop.
    StrokeOut,
    /// A primary strut past its full extension: its elastic extension stop.
    ExtensionStop,
}

impl std::fmt::Display for Branch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Branch::Onset => "its elastic onset ramp",
            Branch::Plateau => "its crush plateau",
            Branch::Rebound => "its elastic rebound",
            Branch::StrokeOut => "its stroke-out (bottoming) stop",
            Branch::ExtensionStop => "its extension stop",
        })
    }
}

/// Crush memory of one loading direction: the largest stroke reached, and the depth of its
/// end stop's current engagement; written only by [`Honeycomb::commit`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CrushMemory {
    /// Largest stroke reached so far on this side (x_max), m.
    pub(super) max_stroke: f64,
    /// The virgin curve's load at x_max, F_v(min(x_max, capacity)), N: where the rebound line
    /// starts, kept with x_max so that a rebounding stroke does not look it up again.
    max_stroke_force: f64,
    /// Deepest depth past the capacity reached in the end stop's current engagement, m: zero
    /// while the stop is open (the stroke at or below the capacity at the last accepted state).
    pub stop_depth: f64,
}

impl CrushMemory {
    /// Largest stroke reached so far on this side (x_max), m.
    pub fn max_stroke(&self) -> f64 {
        self.max_stroke
    }
}

/// A one-sided crushable honeycomb (the primary strut: compression only).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Honeycomb {
    /// Virgin loading curve.
    pub curve: LoadStroke,
    /// Backoff (rebound) rate K_B, N/m.
    pub backoff_rate: f64,
    /// The bottoming stop past the capacity (its rate is the curve's stroke-out rate).
    pub stop: Stop,
}

impl Honeycomb {
    /// A honeycomb from its virgin curve, backoff rate (N/m) and the restitution of its
    /// bottoming stop (in [0, 1]).
    pub fn new(curve: LoadStroke, backoff_rate: f64, restitution: f64) -> Result<Self, LawError> {
        positive("backoff rate", backoff_rate)?;
        Ok(Honeycomb {
            curve,
            backoff_rate,
            stop: Stop::new(curve.stroke_out_rate(), restitution)?,
        })
    }

    /// The same honeycomb behind a trunnion spring `k_t` (N/m): curve per
    /// [`LoadStroke::with_trunnion`], backoff rate `K'_B` of eq. (36), the stop's rate the
    /// series stroke-out rate and its restitution unchanged.
    pub fn with_trunnion(&self, k_t: f64) -> Result<Self, LawError> {
        let curve = self.curve.with_trunnion(k_t)?;
        Ok(Honeycomb {
            curve,
            backoff_rate: series_rate(self.backoff_rate, k_t),
            stop: Stop::new(curve.stroke_out_rate(), self.stop.restitution)?,
        })
    }

    /// Honeycomb force, N (≥ 0), at stroke `x` (m, in this side's loading direction), given the
    /// committed memory: the crushing honeycomb's ([`Honeycomb::crush_force`]) plus its bottoming
    /// stop's ([`Honeycomb::stop_force`]).
    #[inline]
    pub fn force(&self, x: f64, memory: CrushMemory) -> f64 {
        self.crush_force(x, memory) + self.stop_force(x, memory)
    }

    /// The honeycomb's own force at stroke `x` (m), N (≥ 0): the virgin curve up to the
    /// capacity, its last plateau load F_c past it (the exhausted honeycomb crushes on through
    /// the stop's depth), and below the largest stroke x_max the rebound along K_B from
    /// (x_max, F_v(min(x_max, capacity))).
    #[inline]
    pub fn crush_force(&self, x: f64, memory: CrushMemory) -> f64 {
        let cap = self.curve.capacity();
        if x >= memory.max_stroke {
            return self.curve.force(x.min(cap));
        }
        let (x_top, f_top) = self.rebound_start(memory);
        (f_top - self.backoff_rate * (x_top - x)).max(0.0)
    }

    /// The crush load, N, if the honeycomb is crushing at stroke `x` (m): on its virgin curve
    /// (`x` at or past the committed x_max) and on a plateau. A multibody engine holds such a
    /// stroke with a one-sided velocity motor bounded by this load.
    #[inline]
    pub fn crush_load(&self, x: f64, memory: CrushMemory) -> Option<f64> {
        if x >= memory.max_stroke {
            self.curve.plateau(x)
        } else {
            None
        }
    }

    /// The force of the bottoming stop alone at stroke `x` (m), beyond the honeycomb's own, N
    /// (≥ 0; zero within the capacity), given the committed memory.
    #[inline]
    pub fn stop_force(&self, x: f64, memory: CrushMemory) -> f64 {
        self.stop
            .force(x - self.curve.capacity(), memory.stop_depth)
    }

    /// Where the elastic rebound along K_B starts, (stroke m, force N): the largest stroke
    /// x_max and the virgin curve's load there, the last plateau load past the capacity.
    #[inline]
    fn rebound_start(&self, memory: CrushMemory) -> (f64, f64) {
        (memory.max_stroke, memory.max_stroke_force)
    }

    /// The branch stroke `x` (m, ≥ 0) lies on, given the committed memory, and its rate
    /// (the law's local stiffness; on a stop's unloading curve its largest), N/m: past the
    /// capacity the stop's, loading or unloading, plus K_B while the honeycomb rebounds.
    pub fn branch(&self, x: f64, memory: CrushMemory) -> (Branch, f64) {
        let cap = self.curve.capacity();
        let rebounding = x < self.rebound_start(memory).0;
        if x > cap {
            let stop = if x - cap >= memory.stop_depth {
                self.stop.rate
            } else {
                self.stop.unloading_rate()
            };
            let crush = if rebounding { self.backoff_rate } else { 0.0 };
            (Branch::StrokeOut, stop + crush)
        } else if rebounding {
            (Branch::Rebound, self.backoff_rate)
        } else {
            match self.curve.slope(x) {
                0.0 => (Branch::Plateau, 0.0),
                k => (Branch::Onset, k),
            }
        }
    }

    /// Commits an accepted stroke `x` (m, this side's loading direction; any sign) into the
    /// memory: the largest stroke, and the stop's engagement ([`Stop::commit`]).
    #[inline]
    pub fn commit(&self, x: f64, memory: &mut CrushMemory) {
        if x > memory.max_stroke {
            memory.max_stroke = x;
            memory.max_stroke_force = self.curve.force(x.min(self.curve.capacity()));
        }
        Stop::commit(x - self.curve.capacity(), &mut memory.stop_depth);
    }

    /// The end of the strokes over which the strut carries no force, m (never negative): the
    /// permanent set where the rebound line from (x_max, F_v) reaches zero load, but no
    /// further than the stop's start while the stop pushes back ([`Stop::slack`]).
    pub fn permanent_set(&self, memory: CrushMemory) -> f64 {
        let (x, f) = self.rebound_start(memory);
        let stop_start = self.curve.capacity() + self.stop.slack(memory.stop_depth);
        (x - f / self.backoff_rate).min(stop_start).max(0.0)
    }

    /// Elastic energy stored at stroke `x` and recoverable, J: `F²/(2·K_B)` of the honeycomb's
    /// own force on its rebound line, plus what the stop returns ([`Stop::returned_energy`]).
    #[inline]
    pub fn stored_energy(&self, x: f64, memory: CrushMemory) -> f64 {
        self.stored_energy_at(x, self.force(x, memory), memory)
    }

    /// [`Honeycomb::stored_energy`] at stroke `x` (m) where the law gives the force `f` (N)
    /// with the committed `memory`: a caller that has the force need not evaluate the
    /// honeycomb's law again.
    #[inline]
    pub fn stored_energy_at(&self, x: f64, f: f64, memory: CrushMemory) -> f64 {
        let stop = self.stop_force(x, memory);
        let crush = f - stop;
        crush * crush / (2.0 * self.backoff_rate)
            + self.stop.returned_energy(x - self.curve.capacity(), stop)
    }
}
