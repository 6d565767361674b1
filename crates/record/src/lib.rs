//! What every Touchdown engine reports of a landing, so that the engines are compared field by
//! field with the same signs and the same stability decision:
//!
//! | module | content |
//! |---|---|
//! | [`stability`] | stability distance, overturning velocity and the stable-landing conditions, eqs. (105)-(107) |
//! | [`summary`] | the landing summary, the energy report and the running extremes behind them |
//! | [`sample`] | one row of the time history |
//! | [`history`] | the time-history file `history.csv` |
//! | [`landing`] | the run loop every stepping engine shares, and its observers |
//!
//! An engine feeds a [`stability::StabilityTracker`] and an [`summary::Extremes`] after every
//! accepted step, fills a [`sample::Sample`] when asked, and builds its [`summary::Summary`] with
//! [`summary::Summary::new`].

pub mod history;
pub mod landing;
pub mod sample;
pub mod stability;
pub mod summary;

pub use history::History;
pub use landing::{Landing, Observer};
pub use sample::{LegSample, Sample};
pub use stability::{Outcome, PadView, StabilityTracker};
pub use summary::{EnergyLedger, EnergyReport, Extremes, Progress, Summary};

/// Most accepted steps any engine takes in one landing; a run that reaches it stops with a
/// diagnostic. A Table I landing takes about a thousand steps on the core and a hundred
/// thousand on a multibody engine at 20 µs; ten million is about 10 s of the core and a few
/// minutes of a multibody engine (docs/robustness.md, "Budgets").
pub const STEP_BUDGET: u64 = 10_000_000;

/// Most gear-force evaluations in one landing (a multibody engine evaluates once a step; the
/// core's adaptive scheme up to about seven times, more when it rejects steps).
pub const EVALUATION_BUDGET: u64 = 100_000_000;

/// Checks a run's accepted `steps` and force `evaluations` against [`STEP_BUDGET`] and
/// [`EVALUATION_BUDGET`]: the message of the budget exhausted, if one is.
pub fn check_budget(steps: u64, evaluations: u64) -> Result<(), String> {
    if steps >= STEP_BUDGET {
        return Err(format!(
            "step budget exhausted: {steps} accepted steps (at most {STEP_BUDGET}); the time step is too small for integrator.t_end"
        ));
    }
    if evaluations >= EVALUATION_BUDGET {
        return Err(format!(
            "force-evaluation budget exhausted: {evaluations} evaluations (at most {EVALUATION_BUDGET}) after {steps} accepted steps; the error control rejects too many steps"
        ));
    }
    Ok(())
}

/// A run stopped because it diverged or left the domain of a law: where and why, so that the
/// user can tell which law or mechanism failed (every engine reports it the same way).
#[derive(Debug, Clone, PartialEq)]
pub struct Divergence {
    /// Time of the failure, s.
    pub time: f64,
    /// The law or mechanism involved (with the leg, where one is).
    pub law: String,
    /// What happened.
    pub message: String,
    /// Vehicle state at the failure.
    pub state: String,
}

impl std::fmt::Display for Divergence {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "simulation stopped at t = {:.6} s in {}: {}; state: {}",
            self.time, self.law, self.message, self.state
        )
    }
}

impl std::error::Error for Divergence {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_run_stops_at_its_step_or_evaluation_budget() {
        assert!(check_budget(STEP_BUDGET - 1, EVALUATION_BUDGET - 1).is_ok());
        let steps = check_budget(STEP_BUDGET, 0).unwrap_err();
        assert!(
            steps.contains("step budget") && steps.contains("10000000"),
            "{steps}"
        );
        let evaluations = check_budget(10, EVALUATION_BUDGET).unwrap_err();
        assert!(
            evaluations.contains("force-evaluation budget"),
            "{evaluations}"
        );
    }
}
