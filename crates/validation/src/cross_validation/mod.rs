//! Cross-validation of the 1/6-scale model's calibration against Table I
//! (`reference/cross-validation-protocol.toml`; docs/validation.md, "Cross-validation"): each
//! row is predicted by a fit that never saw it (leave-one-out), what the rows can determine is
//! measured rather than assumed (the Jacobian's singular values, each parameter's spread against
//! its bounds, a profile of the objective along each parameter), and every prediction carries
//! the calibration's uncertainty (parameter sets drawn from the fold's linearised covariance).
//!
//! Parameters are handled scaled to their bounds, u = (x − lower) / (upper − lower), so that the
//! Jacobian, the covariance and the singular values do not depend on the parameters' units.

mod checkpointing;
mod folds;
mod identifiability;
mod profile;
mod protocol;
mod report;
#[cfg(test)]
mod tests;
mod uncertainty;

pub use folds::Fold;
pub use identifiability::{Determination, Identifiability};
pub use profile::{Profile, PROFILE_POINTS};
pub use protocol::{CvProtocol, Folds};
pub use report::{CrossValidation, Errors};

use crate::calibrate::{fields_of, fit, overrides, rows_of, table_model, Predict};
use crate::checkpoint::Checkpoint;
use crate::facts;
use crate::reference::{
    self, CalibrationRecord, Estimates, FitParameter, Paths, Protocol, Row, TableI,
};
use crate::ValidationError;
use checkpointing::unit;
use folds::{fold, fold_of, FoldParts};
use identifiability::identifiability;
use profile::profile;
use rayon::prelude::*;
use report::errors;
use touchdown_scenario::schema::ACCURACY_REFINEMENT;

/// Cross-validates `protocol` over the rows of `table` with the model `predict`;
/// `two_row_held_out` are the rows the two-row protocol holds out (its target's rows);
/// `refined` is the same model with every step limit `refinement` times finer, which states
/// the accuracy of the folds' predictions ([`CrossValidation::accuracy`]). With a
/// `checkpoint`, every fold, the fit to every row and every profile point is kept there as it
/// ends, and what it already holds is not computed again (the result is the same).
pub fn cross_validate_with(
    table: &[Row],
    protocol: &CvProtocol,
    two_row_held_out: &[u32],
    predict: &Predict,
    (refined, refinement): (&Predict, f64),
    checkpoint: Option<&Checkpoint>,
) -> Result<CrossValidation, ValidationError> {
    protocol.check()?;
    if table.len() <= protocol.parameter.len() {
        return Err(ValidationError::Calibration(format!(
            "{} rows leave {} per fold, fewer than the {} parameters",
            table.len(),
            table.len().saturating_sub(1),
            protocol.parameter.len()
        )));
    }
    let folds: Vec<(FoldParts, usize)> = (0..table.len())
        .into_par_iter()
        .map(|i| {
            unit(checkpoint, &format!("fold-{i}"), predict, |predict| {
                fold(table, i, protocol, predict)
            })
        })
        .collect::<Result<_, _>>()?;
    let mut landings: usize = folds.iter().map(|(_, n)| n).sum();
    let folds: Vec<Fold> = (table.iter().zip(folds))
        .map(|(row, (parts, _))| fold_of(row, parts))
        .collect();
    let accuracy = folds::accuracy(table, &folds, refined, refinement)?;
    landings += folds.len();
    let ((full_fit, identifiability), full_landings) =
        unit(checkpoint, "full", predict, |predict| {
            let full_fit = fit(
                table,
                &protocol.parameter,
                protocol.max_iterations,
                Some(protocol.restarts()),
                predict,
            )?;
            let (identifiability, _) = identifiability(
                table,
                &protocol.parameter,
                protocol,
                &full_fit.value,
                predict,
            )?;
            Ok((full_fit, identifiability))
        })?;
    landings += full_landings;
    let mut profiles = Vec::with_capacity(protocol.parameter.len());
    for k in 0..protocol.parameter.len() {
        let (p, n) = profile(table, protocol, k, &full_fit, predict, checkpoint)?;
        profiles.push(p);
        landings += n;
    }
    let all: Vec<u32> = table.iter().map(|r| r.id).collect();
    Ok(CrossValidation {
        all_rows: errors(&folds, &all),
        two_row_held_out: errors(&folds, two_row_held_out),
        rows_within_10_pct: folds.iter().filter(|f| f.within_10_pct).count(),
        rows_within_interval: folds.iter().filter(|f| f.within_interval).count(),
        accuracy,
        protocol: protocol.clone(),
        folds,
        full_fit,
        identifiability,
        profiles,
        facts: Vec::new(),
        landings,
    })
}

/// How many landings a whole cross-validation lands, about: 2,704,378 in the run of
/// `docs/validation/cross-validation.json` (its `landings`); the fits' iterations vary with the
/// model, so a run lands about as many, not exactly.
pub const LANDINGS_ABOUT: u64 = 2_700_000;

/// Cross-validates the 1/6-scale model on the core over Table I
/// (`reference/cross-validation-protocol.toml`), its finished work kept in `checkpoint` if
/// one is given ([`cross_validate_with`]); `landed` is called after each landing (for a
/// progress bar: about [`LANDINGS_ABOUT`] in all).
pub fn cross_validate(
    paths: &Paths,
    checkpoint: Option<&Checkpoint>,
    landed: &(dyn Fn() + Sync),
) -> Result<CrossValidation, ValidationError> {
    let protocol: CvProtocol = reference::read(&paths.reference("cross-validation-protocol.toml"))?;
    let two_row: Protocol = reference::read(&paths.reference("calibration-protocol.toml"))?;
    let table: TableI = reference::read(&paths.reference("table-i.toml"))?;
    let estimates: Estimates = reference::read(&paths.reference("lm-1-6-estimates.toml"))?;
    let fields = fields_of(&estimates, &protocol.parameter)?;
    let model = table_model(paths, &table.row, &fields, protocol.scheme, 1.0)?;
    let refined = table_model(
        paths,
        &table.row,
        &fields,
        protocol.scheme,
        ACCURACY_REFINEMENT,
    )?;
    let held_out: Vec<u32> = table
        .row
        .iter()
        .map(|r| r.id)
        .filter(|id| !two_row.rows.contains(id))
        .collect();
    let mut cv = cross_validate_with(
        &table.row,
        &protocol,
        &held_out,
        &counted(&model, landed),
        (&counted(&refined, landed), ACCURACY_REFINEMENT),
        checkpoint,
    )?;
    cv.facts = facts::check(paths, &overrides(&fields, &cv.full_fit.value))?.checks;
    cv.landings += 1;
    Ok(cv)
}

/// The model `model`, calling `landed` after each of its landings.
fn counted<'a>(
    model: &'a Predict<'a>,
    landed: &'a (dyn Fn() + Sync),
) -> impl Fn(&Row, &[f64]) -> Result<f64, ValidationError> + Sync + 'a {
    move |row, x| {
        let stroke = model(row, x);
        landed();
        stroke
    }
}

/// What the rows of a calibration `record` (the two-row protocol's, or any rows asked for)
/// determine of its `parameters` at its fit, by the cross-validation protocol's criterion: a
/// calibration of parameters its rows cannot determine is refused or flagged, never reported
/// as fitted.
pub fn determination(
    paths: &Paths,
    record: &CalibrationRecord,
    parameters: &[FitParameter],
) -> Result<Identifiability, ValidationError> {
    let protocol: CvProtocol = reference::read(&paths.reference("cross-validation-protocol.toml"))?;
    let table: TableI = reference::read(&paths.reference("table-i.toml"))?;
    let rows = rows_of(&table, &record.rows)?;
    let fields: Vec<Vec<String>> = record.parameter.iter().map(|p| p.fields.clone()).collect();
    let x: Vec<f64> = record.parameter.iter().map(|p| p.value).collect();
    let model = table_model(paths, &rows, &fields, None, 1.0)?;
    identifiability(&rows, parameters, &protocol, &x, &model).map(|(i, _)| i)
}
