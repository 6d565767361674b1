//! What every Touchdown engine reports of a landing, so that the engines are compared field by
//! field with the same signs and the same stability decision:
//!
//! | module | content |
//! |---|---|
//! | [`stability`] | stability distance, overturning velocity and the stable-landing conditions, eqs. (105)-(107) |
//! | [`summary`] | the landing summary, the energy report and the running extremes behind them |
//! | [`sample`] | one row of the time history (`history.csv`) |
//!
//! An engine feeds a [`stability::StabilityTracker`] and an [`summary::Extremes`] after every
//! accepted step, fills a [`sample::Sample`] when asked, and builds its [`summary::Summary`] with
//! [`summary::Summary::new`].

pub mod sample;
pub mod stability;
pub mod summary;

pub use sample::{LegSample, Sample};
pub use stability::{Outcome, PadView, StabilityTracker};
pub use summary::{EnergyReport, Extremes, Progress, Summary};
