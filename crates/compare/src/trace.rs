//! The time series a comparison needs of a landing, the same for every engine: time, vertical
//! velocity, pitch rate, attitude and primary strokes at every accepted state.

use touchdown_record::Sample;

/// Window of the vertical-acceleration average, as a fraction of the vehicle's time scale
/// ([`touchdown_scenario::scales::Scales::time_s`]): the velocity change over 1.97 ms on the
/// 1/6-scale model (time scale 0.263 s), like an accelerometer filtered at a few hundred hertz.
/// A multibody's contact impulses make the step-to-step acceleration of its vehicle spiky at
/// the 20 µs step; the report's is smooth.
pub const ACCELERATION_WINDOW: f64 = 0.0075;

/// A landing's trace (SI, inertial frame = the surface frame).
#[derive(Debug, Clone, PartialEq)]
pub struct Trace {
    /// Times, s, increasing.
    pub t: Vec<f64>,
    /// Vertical (surface-normal) velocity of the centre of mass, m/s.
    pub vz: Vec<f64>,
    /// Pitch rate, angular velocity about the inertial X axis, rad/s.
    pub pitch_rate: Vec<f64>,
    /// Euler angles θ relative to the surface frame (eq. 3 order), rad.
    pub attitude: Vec<[f64; 3]>,
    /// Primary strokes, m (compression positive): `legs` values per time, leg by leg.
    pub primary_stroke: Vec<f64>,
    /// Legs per time in `primary_stroke`.
    pub legs: usize,
    /// Window of the vertical-acceleration average, s ([`ACCELERATION_WINDOW`] of the
    /// vehicle's time scale).
    pub acceleration_window_s: f64,
}

impl Trace {
    /// An empty trace whose vertical acceleration is averaged over `acceleration_window_s`
    /// (s, > 0).
    pub fn new(acceleration_window_s: f64) -> Trace {
        Trace {
            t: Vec::new(),
            vz: Vec::new(),
            pitch_rate: Vec::new(),
            attitude: Vec::new(),
            primary_stroke: Vec::new(),
            legs: 0,
            acceleration_window_s,
        }
    }

    /// Appends a sample.
    pub fn push(&mut self, s: &Sample) {
        self.t.push(s.t);
        self.vz.push(s.velocity.z);
        self.pitch_rate.push(s.pitch_rate);
        self.attitude.push(s.theta.into());
        self.legs = s.legs.len();
        self.primary_stroke
            .extend(s.legs.iter().map(|l| l.primary_stroke));
    }

    /// `values` (one per time of this trace) linearly interpolated at time `t`, s, within the
    /// trace's span.
    pub fn at(&self, values: &[f64], t: f64) -> f64 {
        let (i, j, w) = self.bracket(t);
        values[i] + w * (values[j] - values[i])
    }

    /// The Euler angles (as [`Trace::attitude`]) linearly interpolated at time `t`, s, within
    /// the trace's span.
    pub fn attitude_at(&self, t: f64) -> [f64; 3] {
        let (i, j, w) = self.bracket(t);
        let (a, b) = (self.attitude[i], self.attitude[j]);
        [0, 1, 2].map(|k| a[k] + w * (b[k] - a[k]))
    }

    /// The samples around time `t`, s, and the weight of the later one (the first or last
    /// sample alone outside the span).
    fn bracket(&self, t: f64) -> (usize, usize, f64) {
        let i = self.t.partition_point(|x| *x < t);
        if i == 0 {
            return (0, 0, 0.0);
        }
        if i >= self.t.len() {
            let last = self.t.len() - 1;
            return (last, last, 0.0);
        }
        let (t0, t1) = (self.t[i - 1], self.t[i]);
        let w = if t1 > t0 { (t - t0) / (t1 - t0) } else { 1.0 };
        (i - 1, i, w)
    }

    /// End of the trace, s.
    pub fn end(&self) -> f64 {
        self.t.last().copied().unwrap_or(0.0)
    }

    /// Every leg's primary stroke at the `i`-th time, m.
    pub fn primary_strokes_at(&self, i: usize) -> &[f64] {
        &self.primary_stroke[i * self.legs..(i + 1) * self.legs]
    }

    /// The vertical acceleration averaged over the trace's window from each time of the trace
    /// whose window ends within it: (the window's middle, s; m/s², positive up).
    pub fn vertical_acceleration(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        let w = self.acceleration_window_s;
        let end = self.end() - w;
        self.t
            .iter()
            .zip(&self.vz)
            .take_while(move |(t, _)| **t <= end)
            .map(move |(&t, &vz)| {
                let a = (self.at(&self.vz, t + w) - vz) / w;
                (t + 0.5 * w, a)
            })
    }

    /// The vertical acceleration averaged over the trace's window centred on `t` (m/s²,
    /// positive up): the function whose values at the windows' middles
    /// [`Trace::vertical_acceleration`] gives; `None` where the window leaves the trace.
    pub fn vertical_acceleration_at(&self, t: f64) -> Option<f64> {
        let w = self.acceleration_window_s;
        let (from, to) = (t - 0.5 * w, t + 0.5 * w);
        let start = *self.t.first()?;
        (from >= start && to <= self.end())
            .then(|| (self.at(&self.vz, to) - self.at(&self.vz, from)) / w)
    }

    /// The vertical acceleration of largest magnitude, averaged over the trace's window (m/s²,
    /// signed; positive up), and its time (the window's middle, s).
    pub fn peak_vertical_acceleration(&self) -> (f64, f64) {
        self.vertical_acceleration()
            .fold((0.0, 0.0), |peak: (f64, f64), (t, a)| {
                if a.abs() > peak.0.abs() {
                    (a, t)
                } else {
                    peak
                }
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interpolation_and_windowed_acceleration() {
        // Decelerating at 10 m/s², then at 50 m/s² from 4 to 8 ms, sampled every 0.5 ms.
        let t: Vec<f64> = (0..=24).map(|k| k as f64 * 5e-4).collect();
        let v = |t: f64| -3.0 + 10.0 * t.min(0.004) + 50.0 * (t.clamp(0.004, 0.008) - 0.004);
        let trace = Trace {
            vz: t.iter().map(|t| v(*t)).collect(),
            pitch_rate: vec![0.0; t.len()],
            attitude: vec![[0.0; 3]; t.len()],
            primary_stroke: t.iter().flat_map(|t| [*t, 2.0 * t]).collect(),
            legs: 2,
            t,
            acceleration_window_s: 2.0e-3,
        };
        assert_eq!(trace.primary_strokes_at(3)[1], 2.0 * 1.5e-3);
        assert_eq!(trace.primary_stroke.len() / trace.legs, 25);
        assert!((trace.at(&trace.vz, 0.00325) - v(0.00325)).abs() < 1e-12);
        assert_eq!(trace.at(&trace.vz, 1.0), trace.vz[24]);
        let (a, at) = trace.peak_vertical_acceleration();
        assert!((a - 50.0).abs() < 1e-6, "{a}");
        assert!((0.005 - 1e-9..=0.007 + 1e-9).contains(&at), "{at}");
    }
}
