//! The virgin load-stroke curve: stages, onset ramps, plateaus, stroke-out, trunnion spring.

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
    /// x[n − 1], the stroke at the end of the last stage (m), kept beside the vertices: the
    /// laws read it at every evaluation.
    capacity: f64,
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
            capacity: x[n - 1],
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
            None => self.f[self.n - 1] + self.stroke_out_rate * (x - self.capacity),
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

    /// The least slope of the virgin curve over the strokes `from` to `to` (m, 0 ≤ from ≤ to),
    /// N/m: the least of the segments' slopes that span part of it, the stroke-out rate past
    /// the capacity.
    pub fn least_slope(&self, from: f64, to: f64) -> f64 {
        let mut least = if to > self.capacity() {
            self.stroke_out_rate
        } else {
            f64::INFINITY
        };
        for i in 1..self.n {
            if self.x[i] > from && self.x[i - 1] < to {
                least = least.min((self.f[i] - self.f[i - 1]) / (self.x[i] - self.x[i - 1]));
            }
        }
        if least.is_finite() {
            least
        } else {
            self.slope(from)
        }
    }

    /// Stroke at which the last stage is exhausted (bottoming begins), m.
    #[inline]
    pub fn capacity(&self) -> f64 {
        self.capacity
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
        out.capacity = out.x[self.n - 1];
        out.stroke_out_rate = series_rate(self.stroke_out_rate, k_t);
        Ok(out)
    }
}
