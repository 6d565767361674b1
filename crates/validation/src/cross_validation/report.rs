//! The cross-validation's result: the folds, the errors over sets of rows and the target.

use super::folds::Fold;
use super::identifiability::Identifiability;
use super::profile::Profile;
use super::protocol::CvProtocol;
use crate::calibrate::Fit;
use crate::facts::FactCheck;
use crate::reference::FitAccuracy;
use serde::Serialize;

/// Mean and largest |error| over a set of rows, ours (out of fold) and the report's.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Errors {
    /// The rows, Table I ids.
    pub rows: Vec<u32>,
    /// Mean |out-of-fold error|, %.
    pub mean_pct: f64,
    /// Largest |out-of-fold error|, %.
    pub max_pct: f64,
    /// The report's analysis on the same rows: mean |error|, %.
    pub report_mean_pct: f64,
    /// The report's analysis on the same rows: largest |error|, %.
    pub report_max_pct: f64,
}

/// The cross-validation.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CrossValidation {
    /// The protocol run.
    pub protocol: CvProtocol,
    /// One fold per row, in row order.
    pub folds: Vec<Fold>,
    /// Errors over every row.
    pub all_rows: Errors,
    /// Errors over the rows the two-row protocol holds out (its target's rows).
    pub two_row_held_out: Errors,
    /// Rows within 10 % of the experiment.
    pub rows_within_10_pct: usize,
    /// Rows whose experiment lies within the prediction's interval.
    pub rows_within_interval: usize,
    /// The accuracy the step settings give at the folds' fits: each fold's prediction of its
    /// held-out row, and the same landing with every step limit refined (one fold after
    /// another, in row order).
    pub accuracy: FitAccuracy,
    /// The fit to every row.
    pub full_fit: Fit,
    /// What every row together determines.
    pub identifiability: Identifiability,
    /// The objective along each parameter at the fit to every row.
    pub profiles: Vec<Profile>,
    /// The figure 25-26 facts (a second data set, never fitted) at the fit to every row, each
    /// against its own tolerance; empty for a model other than the core's.
    pub facts: Vec<FactCheck>,
    /// Landings run.
    pub landings: usize,
}

impl CrossValidation {
    /// The target: out-of-fold mean below the report's on the two-row protocol's
    /// held-out rows, and every row within 10 %.
    pub fn target_met(&self) -> bool {
        self.two_row_held_out.mean_pct < self.two_row_held_out.report_mean_pct
            && self.rows_within_10_pct == self.folds.len()
    }
}

/// Mean and largest |error| of `folds` restricted to `rows`.
pub(super) fn errors(folds: &[Fold], rows: &[u32]) -> Errors {
    let chosen: Vec<&Fold> = folds
        .iter()
        .filter(|f| rows.contains(&f.held_out))
        .collect();
    let n = chosen.len().max(1) as f64;
    let stat = |e: &dyn Fn(&Fold) -> f64| {
        let v: Vec<f64> = chosen.iter().map(|f| e(f).abs()).collect();
        (
            v.iter().sum::<f64>() / n,
            v.iter().copied().fold(0.0, f64::max),
        )
    };
    let (mean_pct, max_pct) = stat(&|f| f.error_pct);
    let (report_mean_pct, report_max_pct) = stat(&|f| f.report_error_pct);
    Errors {
        rows: chosen.iter().map(|f| f.held_out).collect(),
        mean_pct,
        max_pct,
        report_mean_pct,
        report_max_pct,
    }
}
