//! The protocol file, `reference/cross-validation-protocol.toml`: its settings and their check.

use crate::reference::FitParameter;
use crate::reference::Restarts;
use crate::ValidationError;
use serde::{Deserialize, Serialize};
use touchdown_scenario::schema::Scheme;

/// How the rows are split into folds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Folds {
    /// One fold per row: fit on every other row, predict it.
    LeaveOneOut,
}

/// `reference/cross-validation-protocol.toml`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CvProtocol {
    /// How the rows are split into folds.
    pub folds: Folds,
    /// Most optimiser iterations of each Nelder-Mead run.
    pub max_iterations: u64,
    /// Each restart's simplex, as a fraction of each parameter's range.
    pub restart_simplex: f64,
    /// Most restarts of each fit.
    pub max_restarts: u32,
    /// A restart that improves the objective by less than this fraction of it ends the fit.
    pub restart_improvement: f64,
    /// Step of the central differences, as a fraction of each parameter's range.
    pub jacobian_step: f64,
    /// A parameter whose standard deviation exceeds this fraction of its prior's is not
    /// determined by the rows.
    pub determined_ratio: f64,
    /// Parameter sets drawn for each prediction's interval.
    pub samples: usize,
    /// Seed of the draws.
    pub seed: u64,
    /// The integration scheme every landing of the protocol takes, fits, draws and profiles
    /// alike, and its refined runs (`None`: each Table I scenario's own, the report's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scheme: Option<Scheme>,
    /// The parameters fitted, with their initial values and bounds (file units).
    pub parameter: Vec<FitParameter>,
}

impl CvProtocol {
    /// The restarts of every fit.
    pub fn restarts(&self) -> Restarts {
        Restarts {
            simplex: self.restart_simplex,
            most: self.max_restarts,
            improvement: self.restart_improvement,
            grid: 0,
        }
    }

    /// Checks the settings: every error names the field.
    pub fn check(&self) -> Result<(), ValidationError> {
        let refuse = |field: &str, expected: &str| {
            Err(ValidationError::Reference(format!(
                "cross-validation-protocol.toml: {field}: expected {expected}"
            )))
        };
        if self.parameter.is_empty() {
            return refuse("parameter", "at least one parameter");
        }
        if !(self.jacobian_step > 0.0 && self.jacobian_step <= 0.5) {
            return refuse("jacobian_step", "a fraction in (0, 0.5]");
        }
        if !(self.determined_ratio > 0.0 && self.determined_ratio < 1.0) {
            return refuse("determined_ratio", "a fraction in (0, 1)");
        }
        self.restarts()
            .check("cross-validation-protocol.toml", "restart_")?;
        if self.samples < 2 {
            return refuse("samples", "at least 2");
        }
        for p in &self.parameter {
            if !(p.lower.is_finite() && p.upper.is_finite() && p.lower < p.initial)
                || p.initial >= p.upper
            {
                return refuse(&p.name, "finite bounds with lower < initial < upper");
            }
        }
        Ok(())
    }
}
