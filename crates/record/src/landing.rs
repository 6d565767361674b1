//! What every stepping engine is to its callers: a landing stepped to its end, watched by
//! observers after every accepted step. The run loop is written once, here.

use crate::{History, Sample, Summary};

/// Something that watches a landing of type `L` at touchdown and after every accepted step.
pub trait Observer<L: ?Sized> {
    /// Called with the landing at an accepted state.
    fn observe(&mut self, landing: &L);
}

impl<L: ?Sized> Observer<L> for () {
    fn observe(&mut self, _: &L) {}
}

/// An observer that may be absent.
impl<L: ?Sized, O: Observer<L>> Observer<L> for Option<O> {
    fn observe(&mut self, landing: &L) {
        if let Some(o) = self {
            o.observe(landing);
        }
    }
}

/// A landing an engine steps (the core, the rapier rebuild). An engine implements the four
/// required methods; the run loop ([`Landing::run`]), the observers and the history file come
/// with the trait. The least such engine, a body falling from rest with no gear:
///
/// ```
/// use nalgebra::Vector3;
/// use touchdown_record::{
///     EnergyReport, Extremes, Landing, Outcome, Progress, Sample, StabilityTracker, Summary,
/// };
///
/// struct FreeFall {
///     t: f64,
///     dt: f64,
///     t_end: f64,
///     height: f64,
///     velocity: f64,
///     steps: u64,
///     stability: StabilityTracker,
///     extremes: Extremes,
/// }
///
/// impl Landing for FreeFall {
///     type Error = std::convert::Infallible;
///     fn step(&mut self) -> Result<(), Self::Error> {
///         self.velocity -= 9.81 * self.dt; // semi-implicit Euler
///         self.height += self.velocity * self.dt;
///         self.t += self.dt;
///         self.steps += 1;
///         Ok(())
///     }
///     fn finished(&self) -> bool {
///         self.steps as f64 * self.dt >= self.t_end
///     }
///     fn sample(&self, out: &mut Sample) {
///         out.t = self.t;
///         out.position = Vector3::new(0.0, 0.0, self.height);
///         out.velocity = Vector3::new(0.0, 0.0, self.velocity);
///     }
///     fn summary(&self) -> Summary {
///         let progress = Progress {
///             t: self.t,
///             steps: self.steps,
///             force_evaluations: self.steps,
///             first_contact_s: Vec::new(),
///         };
///         Summary::new(
///             "free-fall",
///             "example",
///             Default::default(),
///             progress,
///             &self.stability,
///             &self.extremes,
///             EnergyReport::default(),
///         )
///     }
/// }
///
/// let scenario = touchdown_scenario::Scenario::load(concat!(
///     env!("CARGO_MANIFEST_DIR"),
///     "/../../scenarios/flat-drop.toml"
/// ))
/// .unwrap();
/// let gravity = Vector3::new(0.0, 0.0, -9.81);
/// let mut fall = FreeFall {
///     t: 0.0,
///     dt: 1e-3,
///     t_end: 0.1,
///     height: 1.0,
///     velocity: 0.0,
///     steps: 0,
///     stability: StabilityTracker::new(&scenario.stability, gravity, 0, 0.0),
///     extremes: Extremes::new(0, Default::default()),
/// };
/// let mut heights = Vec::new();
/// let summary = fall.run(&mut ()).unwrap();
/// assert_eq!(summary.steps, 100);
/// assert_eq!(summary.outcome, Outcome::Undecided); // nothing fed the stability criteria
/// // An observer sees the start and every accepted step.
/// struct Heights<'a>(&'a mut Vec<f64>);
/// impl touchdown_record::Observer<FreeFall> for Heights<'_> {
///     fn observe(&mut self, landing: &FreeFall) {
///         self.0.push(landing.height);
///     }
/// }
/// let mut again = FreeFall { t: 0.0, height: 1.0, velocity: 0.0, steps: 0, ..fall };
/// again.run(&mut Heights(&mut heights)).unwrap();
/// assert_eq!(heights.len(), 101);
/// assert!((heights[100] - (1.0 - 0.5 * 9.81 * 0.1 * 0.1)).abs() < 5e-3);
/// ```
pub trait Landing: Sized {
    /// The engine's error (a divergence among them).
    type Error;

    /// One accepted step.
    fn step(&mut self) -> Result<(), Self::Error>;

    /// Whether the run has ended (an unstable decision, if the scenario terminates on one, or
    /// the end time; a stable landing runs to its end time).
    fn finished(&self) -> bool;

    /// Writes the current state into `out` (a sample made for as many legs).
    fn sample(&self, out: &mut Sample);

    /// The summary at the current state.
    fn summary(&self) -> Summary;

    /// Runs to an unstable decision (if the scenario terminates on one) or to the end time, with
    /// `observer` called at the start and after every step.
    fn run(&mut self, observer: &mut impl Observer<Self>) -> Result<Summary, Self::Error> {
        observer.observe(self);
        while !self.finished() {
            self.step()?;
            observer.observe(self);
        }
        Ok(self.summary())
    }
}

/// A history file records any landing: one row per observed state.
impl<L: Landing, W: std::io::Write> Observer<L> for History<W> {
    fn observe(&mut self, landing: &L) {
        landing.sample(self.sample_mut());
        self.write();
    }
}
