//! What every Touchdown engine reports of a landing, so that the engines are compared field by
//! field with the same signs and the same stability decision:
//!
//! | module | content |
//! |---|---|
//! | [`stability`] | stability distance, overturning velocity and the stable-landing conditions, eqs. (105)-(107) |
//! | [`capacity`] | the struts' capacities, and the struts a landing stroked past them onto their end stops |
//! | [`summary`] | the landing summary and the running extremes behind it |
//! | [`energy`] | the energy ledger: the accounts since touchdown, the work per mechanism, the imbalance that stops a run |
//! | [`sample`] | one row of the time history |
//! | [`history`] | the time-history file `history.csv` |
//! | [`document`] | the envelope of every JSON document: which document, the scenario, the settings |
//! | [`landing`] | the run loop every stepping engine shares, and its observers |
//!
//! An engine feeds a [`stability::StabilityTracker`] and an [`summary::Extremes`] after every
//! accepted step, fills a [`sample::Sample`] when asked, and builds its [`summary::Summary`] with
//! [`summary::Summary::new`].

pub mod capacity;
pub mod document;
pub mod energy;
pub mod history;
pub mod landing;
pub mod outcome;
pub mod sample;
pub mod stability;
pub mod summary;

pub use capacity::{Capacity, PastCapacity, StrutCapacities};
pub use document::{Document, ScenarioId};
pub use energy::{EnergyLedger, EnergyReport, Imbalance};
pub use history::History;
pub use landing::{Landing, Observer};
pub use outcome::{Divergence, Law, RunError, SetupFailure, StateAtStop};
pub use sample::{LegSample, Sample};
pub use stability::{Outcome, PadView, StabilityTracker};
pub use summary::{Extremes, Progress, Summary};

/// Force evaluations a run may make per step of its budget (a multibody engine evaluates once
/// a step; the core's adaptive scheme up to about seven times, more when it rejects steps).
pub const EVALUATIONS_PER_STEP: u64 = 10;

/// A run budget exhausted (docs/robustness.md, "Budgets").
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum BudgetExhausted {
    /// As many accepted steps as `integrator.max_steps`.
    #[error("step budget exhausted: {steps} accepted steps (integrator.max_steps = {max_steps}); the time step is too small for integrator.t_end")]
    Steps {
        /// Accepted steps.
        steps: u64,
        /// `integrator.max_steps`.
        max_steps: u64,
    },
    /// As many force evaluations as [`EVALUATIONS_PER_STEP`] × `integrator.max_steps`.
    #[error("force-evaluation budget exhausted: {evaluations} evaluations (at most {most}, {EVALUATIONS_PER_STEP} × integrator.max_steps) after {steps} accepted steps; the error control rejects too many steps")]
    Evaluations {
        /// Force evaluations.
        evaluations: u64,
        /// The evaluation budget.
        most: u64,
        /// Accepted steps.
        steps: u64,
    },
}

/// Checks a run's accepted `steps` and force `evaluations` against its budget,
/// `integrator.max_steps` = `max_steps` steps and [`EVALUATIONS_PER_STEP`] times as many
/// evaluations (docs/robustness.md, "Budgets").
pub fn check_budget(steps: u64, evaluations: u64, max_steps: u64) -> Result<(), BudgetExhausted> {
    if steps >= max_steps {
        return Err(BudgetExhausted::Steps { steps, max_steps });
    }
    let most = max_steps.saturating_mul(EVALUATIONS_PER_STEP);
    if evaluations >= most {
        return Err(BudgetExhausted::Evaluations {
            evaluations,
            most,
            steps,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_run_stops_at_its_step_or_evaluation_budget() {
        assert!(check_budget(999, 9_999, 1000).is_ok());
        assert_eq!(
            check_budget(1000, 0, 1000),
            Err(BudgetExhausted::Steps {
                steps: 1000,
                max_steps: 1000
            })
        );
        let evaluations = check_budget(10, 10_000, 1000).unwrap_err();
        assert!(
            evaluations.to_string().contains("force-evaluation budget"),
            "{evaluations}"
        );
    }
}
