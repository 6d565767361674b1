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

/// A landing an engine steps (the core, the rapier rebuild).
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
