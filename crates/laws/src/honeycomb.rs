//! Crushable honeycomb load-stroke law with elastic onset, plateaus, rebound and permanent set
//! (figs. 8 and 9), the trunnion-spring modification of eqs. (35)-(39), and the end stops.
//!
//! Each loading direction is a *virgin curve* `F_v(x)`: from 0 the load rises at the onset rate
//! to the first crush load FP1 (station A), stays on that plateau to the end of the first stage
//! (B), rises at the onset rate to FP2 (C), and so on. Beyond the end of the last stage the strut
//! bottoms (strokes out): the load rises at the stroke-out rate, a steep final segment the report
//! leaves unspecified (docs/errata.md, "Modelling choices the report leaves open").
//!
//! The memory is the largest stroke reached, `x_max` ([`CrushMemory`]). At stroke x:
//! `F = F_v(x)` if `x ≥ x_max`, otherwise `F = max(0, F_v(x_max) − K_B·(x_max − x))` (elastic
//! rebound along the backoff rate K_B, F → G in fig. 8). The permanent set is
//! `G = x_max − F_v(x_max)/K_B`. Memories are committed only at accepted states.
//!
//! Bottoming is a [`Stop`] with a coefficient of restitution e, in parallel with the exhausted
//! honeycomb: past the capacity the last stage goes on crushing at its plateau load F_c (the
//! work F_c·d carried through the stop's depth d is crushing, not stored: it rebounds along
//! K_B from the deepest stroke like any crush), and the stop's own spring loads at the
//! stroke-out rate K_so and unloads along the stiffer curve of [`Stop::force`], returning e² of
//! the energy it took. The stop's memory is its deepest depth in the current engagement, cleared
//! when the stroke comes back to the stop's start, so every hit loads the stop afresh and loses
//! (1 − e²) of what its spring took (docs/errata.md, "End stops"). e = 1 is the lossless stop,
//! e = 0 a perfectly plastic one.

use crate::positive;
use crate::{series_rate, LawError};

/// Maximum number of honeycomb stages on one side (the report allows 3 primary, 4 secondary).
pub const MAX_STAGES: usize = 4;
const MAX_VERTICES: usize = 2 * MAX_STAGES + 1;

/// One honeycomb cartridge: its crush load and the stroke at which its plateau ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stage {
    /// Crush (plateau) load, N (report FP1, FP2, FST1, FSC1, ...).
    pub crush_load: f64,
    /// Stroke at the end of this stage's plateau (stations B, D, F), m.
    pub stroke_end: f64,
}

/// A virgin load-stroke curve, piecewise linear through (0, 0), stroke in m, force in N.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoadStroke {
    x: [f64; MAX_VERTICES],
    f: [f64; MAX_VERTICES],
    n: usize,
    stroke_out_rate: f64,
}

impl LoadStroke {
    /// Builds the virgin curve from the onset rate (N/m), the stage table (in loading order)
    /// and the stroke-out rate (N/m) that applies beyond the last stage.
    ///
    /// Errors if a rate is not positive, if there are no or more than [`MAX_STAGES`] stages, if
    /// loads do not increase from stage to stage, or if a stage's plateau would end before the
    /// onset ramp reaches its load (stage table out of order).
    pub fn new(onset_rate: f64, stages: &[Stage], stroke_out_rate: f64) -> Result<Self, LawError> {
        positive("onset rate", onset_rate)?;
        positive("stroke-out rate", stroke_out_rate)?;
        if stages.is_empty() || stages.len() > MAX_STAGES {
            return Err(LawError::StageTable(format!(
                "expected 1 to {MAX_STAGES} stages, got {}",
                stages.len()
            )));
        }
        let mut x = [0.0; MAX_VERTICES];
        let mut f = [0.0; MAX_VERTICES];
        let mut n = 1;
        for (i, s) in stages.iter().enumerate() {
            positive("stage crush load", s.crush_load)?;
            positive("stage stroke end", s.stroke_end)?;
            let (x0, f0) = (x[n - 1], f[n - 1]);
            if s.crush_load <= f0 {
                return Err(LawError::StageTable(format!(
                    "stage {} crush load {} N is not above the previous stage's {} N",
                    i + 1,
                    s.crush_load,
                    f0
                )));
            }
            let plateau_start = x0 + (s.crush_load - f0) / onset_rate;
            if s.stroke_end <= plateau_start {
                return Err(LawError::StageTable(format!(
                    "stage {} ends at stroke {} m, before its onset ramp reaches {} N at {} m",
                    i + 1,
                    s.stroke_end,
                    s.crush_load,
                    plateau_start
                )));
            }
            x[n] = plateau_start;
            f[n] = s.crush_load;
            x[n + 1] = s.stroke_end;
            f[n + 1] = s.crush_load;
            n += 2;
        }
        Ok(LoadStroke {
            x,
            f,
            n,
            stroke_out_rate,
        })
    }

    /// The segment i of the curve, from vertex i − 1 to vertex i, that holds stroke `x` (m,
    /// > 0); `None` past the capacity.
    #[inline]
    fn segment(&self, x: f64) -> Option<usize> {
        (1..self.n).find(|&i| x <= self.x[i])
    }

    /// Virgin-curve force F_v(x), N, at stroke `x`, m (zero for x ≤ 0).
    #[inline]
    pub fn force(&self, x: f64) -> f64 {
        if x <= 0.0 {
            return 0.0;
        }
        match self.segment(x) {
            Some(i) => {
                let (x0, x1, f0, f1) = (self.x[i - 1], self.x[i], self.f[i - 1], self.f[i]);
                f0 + (f1 - f0) * (x - x0) / (x1 - x0)
            }
            None => self.f[self.n - 1] + self.stroke_out_rate * (x - self.x[self.n - 1]),
        }
    }

    /// The crush load, N, if stroke `x` (m) lies on a plateau of the curve (a stage crushing at
    /// constant load, x > 0 and not past the capacity); `None` on an onset ramp or beyond.
    #[inline]
    pub fn plateau(&self, x: f64) -> Option<f64> {
        if x <= 0.0 {
            return None;
        }
        self.segment(x)
            .filter(|&i| self.f[i] == self.f[i - 1])
            .map(|i| self.f[i])
    }

    /// Slope of the virgin curve at stroke `x` (m), N/m: its segment's up to the capacity
    /// (zero on a plateau), the stroke-out rate beyond; zero for x ≤ 0.
    pub fn slope(&self, x: f64) -> f64 {
        if x <= 0.0 {
            return 0.0;
        }
        match self.segment(x) {
            Some(i) => (self.f[i] - self.f[i - 1]) / (self.x[i] - self.x[i - 1]),
            None => self.stroke_out_rate,
        }
    }

    /// Stroke at which the last stage is exhausted (bottoming begins), m.
    pub fn capacity(&self) -> f64 {
        self.x[self.n - 1]
    }

    /// Vertices (stroke m, force N) of the curve, from (0, 0) to the end of the last stage.
    pub fn vertices(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.x[..self.n]
            .iter()
            .copied()
            .zip(self.f[..self.n].iter().copied())
    }

    /// The work the virgin curve takes from no stroke to its capacity, J: the area under it,
    /// onset ramps and plateaus (what the strut can absorb before it bottoms).
    pub fn energy_to_capacity(&self) -> f64 {
        (1..self.n)
            .map(|i| 0.5 * (self.f[i] + self.f[i - 1]) * (self.x[i] - self.x[i - 1]))
            .sum()
    }

    /// Stroke-out (bottoming) rate beyond the last stage, N/m.
    pub fn stroke_out_rate(&self) -> f64 {
        self.stroke_out_rate
    }

    /// The curve seen through a trunnion spring `k_t` (N/m) in series, eqs. (35)-(39): every
    /// point moves by F/K_T (`x' = x + F_v(x)/K_T`), which gives the series onset rates of
    /// eq. (35) and the plateau shifts of eqs. (37)-(39) for every stage (the report prints
    /// only the first-stage shift; docs/errata.md, "Eqs. (35)-(39): trunnion modification — generalised").
    pub fn with_trunnion(&self, k_t: f64) -> Result<Self, LawError> {
        positive("trunnion spring rate", k_t)?;
        let mut out = *self;
        for i in 0..self.n {
            out.x[i] = self.x[i] + self.f[i] / k_t;
        }
        out.stroke_out_rate = series_rate(self.stroke_out_rate, k_t);
        Ok(out)
    }
}

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
    max_stroke: f64,
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

/// Memories of a double-acting honeycomb: tension and compression, both referenced to the
/// original zero stroke.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DoubleActingMemory {
    /// Tension-side memory.
    pub tension: CrushMemory,
    /// Compression-side memory.
    pub compression: CrushMemory,
}

/// A double-acting honeycomb (the secondary struts): independent tension and compression
/// cartridges, fig. 9. Stroke and force are **tension positive**, as eq. (34) defines S31.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DoubleActingHoneycomb {
    /// Tension side (stations A-D, rebound D-E).
    pub tension: Honeycomb,
    /// Compression side (stations F-I, rebound I-J).
    pub compression: Honeycomb,
}

impl DoubleActingHoneycomb {
    /// The cartridge stroke `s` (m, tension positive) loads: the tension side for s ≥ 0, the
    /// compression side below.
    #[inline]
    pub fn side(&self, s: f64) -> &Honeycomb {
        if s >= 0.0 {
            &self.tension
        } else {
            &self.compression
        }
    }

    /// Force, N (tension positive), at stroke `s` (m, tension positive). Zero between the two
    /// permanent sets (J < s < E in fig. 9).
    #[inline]
    pub fn force(&self, s: f64, memory: DoubleActingMemory) -> f64 {
        if s >= 0.0 {
            self.tension.force(s, memory.tension)
        } else {
            -self.compression.force(-s, memory.compression)
        }
    }

    /// Commits an accepted stroke `s` (m, tension positive) into both sides' memories (a
    /// side's largest stroke only grows on its own side; its stop's engagement ends on the
    /// other).
    #[inline]
    pub fn commit(&self, s: f64, memory: &mut DoubleActingMemory) {
        self.tension.commit(s, &mut memory.tension);
        self.compression.commit(-s, &mut memory.compression);
    }

    /// The force of the stop the stroke `s` (m, tension positive) is on, beyond its side's last
    /// crush load, N (tension positive; zero within both capacities).
    #[inline]
    pub fn stop_force(&self, s: f64, memory: DoubleActingMemory) -> f64 {
        if s >= 0.0 {
            self.tension.stop_force(s, memory.tension)
        } else {
            -self.compression.stop_force(-s, memory.compression)
        }
    }

    /// The branch stroke `s` (m, tension positive) lies on and its rate, N/m: the tension
    /// side's for s ≥ 0, the compression side's below.
    pub fn branch(&self, s: f64, memory: DoubleActingMemory) -> (Branch, f64) {
        if s >= 0.0 {
            self.tension.branch(s, memory.tension)
        } else {
            self.compression.branch(-s, memory.compression)
        }
    }

    /// Recoverable elastic energy at stroke `s`, J.
    #[inline]
    pub fn stored_energy(&self, s: f64, memory: DoubleActingMemory) -> f64 {
        self.stored_energy_at(s, self.force(s, memory), memory)
    }

    /// [`DoubleActingHoneycomb::stored_energy`] at stroke `s` (m, tension positive) where the
    /// law gives the force `f` (N, tension positive).
    #[inline]
    pub fn stored_energy_at(&self, s: f64, f: f64, memory: DoubleActingMemory) -> f64 {
        if s >= 0.0 {
            self.tension.stored_energy_at(s, f, memory.tension)
        } else {
            self.compression
                .stored_energy_at(-s, -f, memory.compression)
        }
    }

    /// The same strut behind a trunnion spring `k_t`, N/m (both sides, eqs. 35-36, 38-39).
    pub fn with_trunnion(&self, k_t: f64) -> Result<Self, LawError> {
        Ok(DoubleActingHoneycomb {
            tension: self.tension.with_trunnion(k_t)?,
            compression: self.compression.with_trunnion(k_t)?,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn primary() -> Honeycomb {
        // Onset 1e5 N/m, FP1 = 1000 N to 0.1 m, FP2 = 3000 N to 0.2 m, stroke-out 1e7 N/m.
        let stages = [
            Stage {
                crush_load: 1000.0,
                stroke_end: 0.1,
            },
            Stage {
                crush_load: 3000.0,
                stroke_end: 0.2,
            },
        ];
        Honeycomb::new(LoadStroke::new(1e5, &stages, 1e7).unwrap(), 1e6, 1.0).unwrap()
    }

    #[test]
    fn the_energy_to_capacity_is_the_area_under_the_virgin_curve() {
        let c = primary().curve;
        // Onset to 1000 N over 10 mm (5 J), plateau to 0.1 m (90 J), onset to 3000 N over
        // 20 mm (40 J), plateau to 0.2 m (240 J).
        assert!((c.energy_to_capacity() - 375.0).abs() < 1e-9);
        // The same by the midpoint rule on the force itself.
        let n = 200_000;
        let h = c.capacity() / n as f64;
        let sum: f64 = (0..n).map(|i| c.force((i as f64 + 0.5) * h) * h).sum();
        assert!((sum - 375.0).abs() < 1e-6, "{sum}");
    }

    #[test]
    fn virgin_curve_stations() {
        let h = primary();
        let c = &h.curve;
        assert_eq!(c.force(-0.01), 0.0);
        assert!((c.force(0.005) - 500.0).abs() < 1e-9, "onset");
        assert!((c.force(0.01) - 1000.0).abs() < 1e-9, "station A");
        assert!((c.force(0.05) - 1000.0).abs() < 1e-9, "first plateau");
        assert!(
            (c.force(0.11) - 2000.0).abs() < 1e-9,
            "onset to the second stage"
        );
        assert!((c.force(0.15) - 3000.0).abs() < 1e-9, "second plateau");
        assert!((c.force(0.201) - 13000.0).abs() < 1e-6, "stroke-out");
        assert_eq!(c.capacity(), 0.2);
    }

    #[test]
    fn crushing_only_on_a_plateau_of_the_virgin_curve() {
        let h = primary();
        let fresh = CrushMemory::default();
        assert_eq!(h.crush_load(0.005, fresh), None, "onset ramp is elastic");
        assert_eq!(h.crush_load(0.05, fresh), Some(1000.0));
        assert_eq!(h.crush_load(0.11, fresh), None, "ramp to the second stage");
        assert_eq!(h.crush_load(0.15, fresh), Some(3000.0));
        assert_eq!(h.crush_load(0.201, fresh), None, "bottoming is elastic");
        let mut crushed = CrushMemory::default();
        h.commit(0.06, &mut crushed);
        assert_eq!(h.crush_load(0.05, crushed), None, "rebound line");
        assert_eq!(
            h.crush_load(0.06, crushed),
            Some(1000.0),
            "back at the front"
        );
    }

    #[test]
    fn load_unload_reload_keeps_permanent_set() {
        let h = primary();
        let mut m = CrushMemory::default();
        // Load to 0.05 m on the first plateau and commit.
        for i in 0..=50 {
            let x = 0.001 * i as f64;
            h.commit(x, &mut m);
        }
        assert_eq!(m.max_stroke, 0.05);
        // Unload: linear at K_B, reaches zero at G = 0.05 − 1000/1e6 = 0.049.
        assert!((h.force(0.0495, m) - 500.0).abs() < 1e-6);
        assert!((h.permanent_set(m) - 0.049).abs() < 1e-12);
        assert_eq!(h.force(0.03, m), 0.0, "no tension in a crushed cartridge");
        // Reload: zero load until G, then back up the backoff line to the virgin curve.
        assert_eq!(h.force(0.0489, m), 0.0);
        assert!((h.force(0.05, m) - 1000.0).abs() < 1e-9);
        assert!(
            (h.force(0.06, m) - 1000.0).abs() < 1e-9,
            "continues on the plateau"
        );
        // The memory never shrinks.
        h.commit(0.02, &mut m);
        assert_eq!(m.max_stroke, 0.05);
        // Stored energy on the rebound line is F²/(2 K_B).
        assert!((h.stored_energy(0.0495, m) - 500.0 * 500.0 / 2e6).abs() < 1e-12);
    }

    #[test]
    fn a_bottomed_strut_crushes_through_the_stop_depth() {
        let h = primary(); // e = 1
        let mut m = CrushMemory::default();
        h.commit(0.21, &mut m); // 0.01 m into stroke-out: 3000 + 1e7·0.01 N
        assert_eq!((m.max_stroke, m.stop_depth), (0.21, 0.21 - 0.2));
        assert!((h.force(0.21, m) - 103_000.0).abs() < 1e-6);
        // Unloading: the honeycomb's 3000 N rebounds along K_B from 0.21 m (gone by 0.207 m),
        // the lossless stop retraces its line to the capacity.
        assert!((h.crush_force(0.209, m) - 2000.0).abs() < 1e-6);
        assert!((h.force(0.209, m) - 92_000.0).abs() < 1e-6);
        assert!((h.force(0.205, m) - 50_000.0).abs() < 1e-6);
        assert_eq!(h.force(0.2, m), 0.0);
        assert_eq!(h.force(0.199, m), 0.0);
        // The stop pushes the strut back to the capacity; no force below it.
        assert_eq!(h.permanent_set(m), 0.2);
        // Stored: the honeycomb's rebound triangle and the stop's own K_so·d²/2, not F_c·d.
        let e = 3000.0f64.powi(2) / 2e6 + 0.5 * 1e7 * 0.01f64.powi(2);
        assert!((h.stored_energy(0.21, m) - e).abs() < 1e-9);
    }

    /// Work done on the strut along strokes `path` (committing each), by the trapezoid rule on
    /// fine steps, J.
    fn work_along(h: &Honeycomb, m: &mut CrushMemory, path: &[f64]) -> f64 {
        let mut w = 0.0;
        for pair in path.windows(2) {
            let n = 20_000;
            for i in 0..n {
                let a = pair[0] + (pair[1] - pair[0]) * i as f64 / n as f64;
                let b = pair[0] + (pair[1] - pair[0]) * (i + 1) as f64 / n as f64;
                w += 0.5 * (h.force(a, *m) + h.force(b, *m)) * (b - a);
                h.commit(b, m);
            }
        }
        w
    }

    /// A bottomed strut with restitution e returns, at every hit, the honeycomb's rebound
    /// triangle and e² of what the stop's own spring took; the plateau load carried through
    /// the stop's depth is crushed; the stored energy is what unloading returns.
    #[test]
    fn a_stop_returns_the_square_of_its_restitution_at_every_hit() {
        for e in [0.0, 0.5, 0.8, 1.0] {
            let stages = [Stage {
                crush_load: 3000.0,
                stroke_end: 0.2,
            }];
            let h = Honeycomb::new(LoadStroke::new(1e5, &stages, 1e7).unwrap(), 1e6, e).unwrap();
            let mut m = CrushMemory::default();
            h.commit(0.2, &mut m);
            let triangle = 3000.0f64.powi(2) / 2e6;
            let own = 0.5 * 1e7 * 0.01f64.powi(2);
            // First hit: 10 mm deep from the capacity, F_c·d crushed plus the stop's own.
            let taken = work_along(&h, &mut m, &[0.2, 0.21]);
            assert!((taken - (3000.0 * 0.01 + own)).abs() < 1e-6);
            let expected = triangle + e * e * own;
            let stored = h.stored_energy(0.21, m);
            assert!((stored - expected).abs() < 1e-9 * taken, "e = {e}");
            // Unloading to below the capacity gives back what is stored, continuously from
            // the deepest point unless the stop is plastic.
            if e > 0.0 {
                let drop = 103_000.0 - h.force(0.21 - 1e-9, m);
                let rate = h.stop.unloading_rate() + h.backoff_rate;
                assert!(drop > 0.0 && drop < 2e-9 * rate, "{drop}");
            }
            let returned = -work_along(&h, &mut m, &[0.21, 0.199]);
            assert!(
                (returned - expected).abs() < 2e-3 * taken,
                "e = {e}: {returned} vs {expected}"
            );
            assert_eq!(m.stop_depth, 0.0, "the engagement ended at the capacity");
            // Second, shallower hit (6 mm): the stop loads afresh from its start, and gives
            // back e² of its own spring's energy again (not lossless below the first depth).
            let taken2 = work_along(&h, &mut m, &[0.199, 0.206]);
            let own2 = 0.5 * 1e7 * 0.006f64.powi(2);
            let returned2 = -work_along(&h, &mut m, &[0.206, 0.199]);
            assert!((taken2 - own2).abs() < 2e-3 * own2, "e = {e}: {taken2}");
            assert!(
                (returned2 - e * e * own2).abs() < 2e-3 * own2,
                "e = {e}: {returned2} vs {}",
                e * e * own2
            );
            // The stop alone is the force beyond the honeycomb's own, on every branch.
            for x in [0.15, 0.2, 0.205, 0.21, 0.211] {
                let beyond = h.force(x, m) - h.crush_force(x, m);
                assert!(
                    (h.stop_force(x, m) - beyond).abs() < 1e-6,
                    "e = {e}, x = {x}"
                );
            }
        }
        assert!(Stop::new(1e7, 1.2).is_err() && Stop::new(1e7, -0.1).is_err());
        assert!(Stop::new(1e7, f64::NAN).is_err());
    }

    /// The closed form of restitution: a mass that strikes a stop at speed v leaves it at
    /// e·v, at every hit (its flight between hits is ballistic and gives it back the speed it
    /// left with, so the hits are taken one after the other; velocity Verlet, each accepted
    /// depth committed, as an engine does). A plastic stop keeps it.
    #[test]
    fn a_mass_striking_a_stop_leaves_at_e_times_its_speed_at_every_hit() {
        for e in [0.0, 0.3, 0.5, 0.8, 1.0] {
            let stop = Stop::new(1e6, e).unwrap();
            let mass = 2.0;
            let dt = 1e-3 * (mass / stop.stiffest_rate()).sqrt();
            let mut deepest = 0.0;
            let mut speed: f64 = 1.5;
            for hit in 0..4 {
                let (mut d, mut v) = (0.0, speed);
                let accel = |d: f64, deepest: f64| -stop.force(d, deepest) / mass;
                let mut steps = 0;
                while d >= 0.0 && steps < 10_000_000 {
                    let a0 = accel(d, deepest);
                    d += v * dt + 0.5 * a0 * dt * dt;
                    let a1 = accel(d, deepest);
                    v += 0.5 * (a0 + a1) * dt;
                    Stop::commit(d, &mut deepest);
                    steps += 1;
                    if e == 0.0 && v <= 0.0 {
                        break;
                    }
                }
                if e == 0.0 {
                    assert!(v.abs() < 1e-3 * speed, "a plastic stop keeps it: {v}");
                    break;
                }
                assert_eq!(deepest, 0.0, "the engagement ended as it left");
                assert!(
                    (-v / speed - e).abs() < 2e-3 * e,
                    "e = {e}, hit {hit}: {} after {speed}",
                    -v
                );
                speed = -v;
            }
        }
    }

    /// The plastic stop's force, stored energy and rates are the limits of those of small
    /// restitutions: below the deepest point the force and the energy returned vanish as e → 0,
    /// and the steep start of the unloading curve narrows to nothing.
    #[test]
    fn a_plastic_stop_is_the_limit_of_small_restitutions() {
        let stop = |e: f64| Stop::new(1e7, e).unwrap();
        let (d_max, d) = (0.01, 0.0099);
        // The force 1 % below the deepest point, K_so·d_max·0.99^(2/e² − 1): 1.35e4 N at
        // e = 0.1, 1e-82 N at 0.01, nothing at 0.
        assert!((stop(0.1).force(d, d_max) - 1e5 * 0.99f64.powi(199)).abs() < 1.0);
        assert!(stop(1e-2).force(d, d_max) < 1e-80);
        assert_eq!(stop(0.0).force(d, d_max), 0.0);
        // Loading is the same line whatever e.
        assert_eq!(stop(0.0).force(0.011, d_max), stop(0.5).force(0.011, d_max));
        // What unloading returns: e²·f·d/2, to nothing.
        let f = 1e5;
        assert_eq!(stop(0.0).returned_energy(d_max, f), 0.0);
        assert!(stop(1e-3).returned_energy(d_max, f) < 1e-3);
        // No unloading stiffness at e = 0; the stiffest rate is the loading rate there and the
        // unloading one, n·K_so, above.
        assert_eq!(stop(0.0).unloading_rate(), 0.0);
        assert_eq!(stop(0.0).stiffest_rate(), 1e7);
        assert!((stop(0.5).stiffest_rate() - 7e7).abs() < 1e-3);
        assert_eq!(stop(1.0).stiffest_rate(), 1e7);
    }

    #[test]
    fn each_stroke_names_its_branch() {
        let h = primary();
        let mut m = CrushMemory::default();
        assert_eq!(h.branch(0.005, m), (Branch::Onset, 1e5));
        assert_eq!(h.branch(0.05, m), (Branch::Plateau, 0.0));
        let (b, k) = h.branch(0.105, m);
        assert_eq!(b, Branch::Onset, "onset to the second stage");
        assert!((k - 1e5).abs() < 1e-6, "{k}");
        assert_eq!(h.branch(0.21, m), (Branch::StrokeOut, 1e7));
        h.commit(0.15, &mut m);
        assert_eq!(h.branch(0.149, m), (Branch::Rebound, 1e6));
        assert_eq!(h.branch(0.15, m), (Branch::Plateau, 0.0));
        assert_eq!(
            Branch::StrokeOut.to_string(),
            "its stroke-out (bottoming) stop"
        );
    }

    #[test]
    fn tension_and_compression_are_independent() {
        let side = |f: f64| {
            Honeycomb::new(
                LoadStroke::new(
                    2e5,
                    &[Stage {
                        crush_load: f,
                        stroke_end: 0.05,
                    }],
                    1e7,
                )
                .unwrap(),
                1e6,
                1.0,
            )
            .unwrap()
        };
        let s = DoubleActingHoneycomb {
            tension: side(400.0),
            compression: side(600.0),
        };
        let mut m = DoubleActingMemory::default();
        // Tension to 0.02 m.
        assert!((s.force(0.02, m) - 400.0).abs() < 1e-9);
        s.commit(0.02, &mut m);
        // Back through zero into compression: no force between the permanent sets.
        assert_eq!(s.force(0.0, m), 0.0);
        assert!(
            (s.force(-0.001, m) + 200.0).abs() < 1e-9,
            "compression onset from the original zero"
        );
        assert!((s.force(-0.01, m) + 600.0).abs() < 1e-9);
        s.commit(-0.01, &mut m);
        // Back to tension: the tension memory is intact (reload from its permanent set).
        let g_t = s.tension.permanent_set(m.tension);
        assert!((g_t - (0.02 - 400.0 / 1e6)).abs() < 1e-12);
        assert_eq!(s.force(g_t - 1e-6, m), 0.0);
        assert!((s.force(0.02, m) - 400.0).abs() < 1e-9);
        assert_eq!(m.compression.max_stroke, 0.01);
    }

    #[test]
    fn trunnion_spring_gives_series_rates_and_shifts_every_stage() {
        let h = primary();
        let kt = 4e5;
        let t = h.with_trunnion(kt).unwrap();
        // eq. (35): onset slope K' = K_T K / (K_T + K).
        let k_onset = series_rate(1e5, kt);
        assert!((t.curve.force(0.001) - k_onset * 0.001).abs() < 1e-6);
        // eq. (36): backoff.
        assert!((t.backoff_rate - series_rate(1e6, kt)).abs() < 1e-6);
        // eq. (37) for stage 1, and its generalisation F_i/K_T for stage 2.
        let v: Vec<_> = t.curve.vertices().collect();
        assert!((v[1].0 - (0.01 + 1000.0 / kt)).abs() < 1e-12);
        assert!((v[4].0 - (0.2 + 3000.0 / kt)).abs() < 1e-12);
        // Permanent set is unchanged by the trunnion spring: x_max − F/K_B.
        let mut m = CrushMemory::default();
        t.commit(0.05 + 1000.0 / kt, &mut m);
        assert!((t.permanent_set(m) - (0.05 - 1000.0 / 1e6)).abs() < 1e-12);
    }

    #[test]
    fn stage_tables_out_of_order_are_rejected() {
        let bad_load = [
            Stage {
                crush_load: 1000.0,
                stroke_end: 0.1,
            },
            Stage {
                crush_load: 900.0,
                stroke_end: 0.2,
            },
        ];
        assert!(matches!(
            LoadStroke::new(1e5, &bad_load, 1e7),
            Err(LawError::StageTable(_))
        ));
        let bad_end = [Stage {
            crush_load: 1000.0,
            stroke_end: 0.005,
        }];
        assert!(matches!(
            LoadStroke::new(1e5, &bad_end, 1e7),
            Err(LawError::StageTable(_))
        ));
        assert!(matches!(
            LoadStroke::new(-1.0, &bad_end, 1e7),
            Err(LawError::NotPositive { .. })
        ));
        assert!(matches!(
            LoadStroke::new(1e5, &[], 1e7),
            Err(LawError::StageTable(_))
        ));
    }
}
