//! The leave-one-out folds: each fit without its row, and its prediction of it with an interval.

use super::identifiability::{identifiability, Identifiability};
use super::protocol::CvProtocol;
use super::uncertainty::draws;
use crate::calibrate::{fit, infeasible, Fit, Predict};
use crate::reference::{FitAccuracy, Row, RowAccuracy, INCH};
use crate::ValidationError;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use touchdown_sampling::percentile;

/// Candidate parameter sets drawn per sample kept, of which the feasible ones are kept in draw
/// order.
const FEASIBLE_CANDIDATES: usize = 2;

/// One leave-one-out fold: the fit on every row but one, and its prediction of that row.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Fold {
    /// The Table I row held out and predicted.
    pub held_out: u32,
    /// The fit on the other rows.
    pub fit: Fit,
    /// What those rows determine.
    pub identifiability: Identifiability,
    /// Our predicted stroke of the held-out row, in (`predicted_m` in the JSON).
    #[serde(rename = "predicted_m", serialize_with = "crate::si::inches")]
    pub predicted_in: f64,
    /// The 2.5 and 97.5 percentiles of the prediction over the calibration's uncertainty, in.
    #[serde(rename = "interval_m", serialize_with = "crate::si::inches_pair")]
    pub interval_in: [f64; 2],
    /// The experiment's stroke, in (`experiment_m` in the JSON).
    #[serde(rename = "experiment_m", serialize_with = "crate::si::inches")]
    pub experiment_in: f64,
    /// The report's analytical stroke, in (`report_m` in the JSON).
    #[serde(rename = "report_m", serialize_with = "crate::si::inches")]
    pub report_in: f64,
    /// (ours − experiment) / experiment, %.
    pub error_pct: f64,
    /// (report − experiment) / experiment, %.
    pub report_error_pct: f64,
    /// |error| ≤ 10 %.
    pub within_10_pct: bool,
    /// The experiment lies within `interval_in`.
    pub within_interval: bool,
}

/// What a fold computes: the fit on every row but the held-out one, what they determine, and
/// the prediction of the held-out row with its interval, in.
#[derive(Serialize, Deserialize)]
pub(super) struct FoldParts {
    fit: Fit,
    identifiability: Identifiability,
    predicted_in: f64,
    interval_in: [f64; 2],
}

/// One fold: fit on every row of `table` but `held_out`, predict it with its interval.
pub(super) fn fold(
    table: &[Row],
    held_out: usize,
    protocol: &CvProtocol,
    predict: &Predict,
) -> Result<FoldParts, ValidationError> {
    let row = &table[held_out];
    let rows: Vec<Row> = table
        .iter()
        .enumerate()
        .filter(|(i, _)| *i != held_out)
        .map(|(_, r)| r.clone())
        .collect();
    let fitted = fit(
        &rows,
        &protocol.parameter,
        protocol.max_iterations,
        Some(protocol.restarts()),
        predict,
    )?;
    let (identifiability, c) =
        identifiability(&rows, &protocol.parameter, protocol, &fitted.value, predict)?;
    let predicted_in = predict(row, &fitted.value)?;
    // Candidates in the bounds, in draw order; those whose diagram the loader refuses (outside
    // the feasible set) are dropped, as draws outside the bounds are.
    let sets = draws(
        &protocol.parameter,
        &fitted.value,
        &c,
        FEASIBLE_CANDIDATES * protocol.samples,
        protocol.seed,
        u64::from(row.id),
    )?;
    let predicted: Vec<Option<f64>> = sets
        .par_iter()
        .map(|x| match predict(row, x) {
            Ok(s) => Ok(Some(s)),
            Err(e) if infeasible(&e) => Ok(None),
            Err(e) => Err(e),
        })
        .collect::<Result<_, _>>()?;
    let mut spread: Vec<f64> = predicted
        .into_iter()
        .flatten()
        .take(protocol.samples)
        .collect();
    if spread.len() < protocol.samples {
        return Err(ValidationError::Calibration(format!(
            "row {}: fewer than {} of {} draws of the fit's covariance are feasible diagrams",
            row.id,
            protocol.samples,
            sets.len()
        )));
    }
    Ok(FoldParts {
        fit: fitted,
        identifiability,
        predicted_in,
        interval_in: {
            spread.sort_by(f64::total_cmp);
            [percentile(&spread, 0.025), percentile(&spread, 0.975)]
        },
    })
}

/// The fold of `row` from what it computed.
pub(super) fn fold_of(row: &Row, parts: FoldParts) -> Fold {
    let FoldParts {
        fit,
        identifiability,
        predicted_in,
        interval_in,
    } = parts;
    let error_pct = 100.0 * (predicted_in - row.experiment) / row.experiment;
    Fold {
        held_out: row.id,
        fit,
        identifiability,
        predicted_in,
        interval_in,
        experiment_in: row.experiment,
        report_in: row.analysis,
        error_pct,
        report_error_pct: 100.0 * (row.analysis - row.experiment) / row.experiment,
        within_10_pct: error_pct.abs() <= 10.0,
        within_interval: interval_in[0] <= row.experiment && row.experiment <= interval_in[1],
    }
}

/// The accuracy the step settings give at the folds' fits: each fold's held-out row, which it
/// predicted at its fit with the settings, landed there again with every step limit
/// `refinement` times finer (`refined`). The landings are made in parallel and the first error
/// in row order is returned, so that the same rows are landed whatever the threads' timing.
pub(super) fn accuracy(
    table: &[Row],
    folds: &[Fold],
    refined: &Predict,
    refinement: f64,
) -> Result<FitAccuracy, ValidationError> {
    let each: Vec<Result<RowAccuracy, ValidationError>> = table
        .par_iter()
        .zip(folds)
        .map(|(row, f)| {
            Ok(RowAccuracy {
                id: row.id,
                stroke_m: f.predicted_in * INCH,
                refined_stroke_m: refined(row, &f.fit.value)? * INCH,
            })
        })
        .collect();
    Ok(FitAccuracy {
        refinement,
        row: each.into_iter().collect::<Result<_, _>>()?,
    })
}
