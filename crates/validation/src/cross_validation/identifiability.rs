//! What the rows of a fit determine: the Jacobian, its singular values and each parameter's spread.

use super::protocol::CvProtocol;
use super::uncertainty::{covariance, scaled, unscaled};
use crate::calibrate::{infeasible, relative_errors, Predict};
use crate::reference::{FitParameter, Row};
use crate::ValidationError;
use nalgebra::DMatrix;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// How well the rows of a fit determine one parameter.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Determination {
    /// The parameter.
    pub name: String,
    /// Its fitted value, file units.
    pub value: f64,
    /// Its standard deviation from the linearised covariance, file units.
    pub sd: f64,
    /// The standard deviation of its bounds read as a uniform prior, (upper − lower)/√12,
    /// file units.
    pub prior_sd: f64,
    /// `sd / prior_sd`: 1 when the rows say nothing about it, near 0 when they fix it.
    pub ratio: f64,
    /// Whether the rows determine it (`ratio` at most the protocol's `determined_ratio`).
    pub determined: bool,
}

/// What the rows of a fit determine.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Identifiability {
    /// Singular values of the Jacobian of the relative stroke errors to the scaled parameters,
    /// largest first (dimensionless).
    pub singular_values: Vec<f64>,
    /// Residual variance s² of the relative errors: sum of squares / max(rows − parameters, 1).
    pub residual_variance: f64,
    /// Each parameter.
    pub parameters: Vec<Determination>,
    /// Correlations of the parameters in the linearised covariance (prior included).
    pub correlation: Vec<Vec<f64>>,
    /// The Jacobian, one row per Table I row of the fit, one column per parameter
    /// (relative stroke error per unit of scaled parameter).
    pub jacobian: Vec<Vec<f64>>,
}

/// The Jacobian of the relative stroke errors of `rows` to the scaled parameters at `x` (where
/// they are `centre`), by central differences of `step` (one-sided against a bound).
fn jacobian(
    rows: &[Row],
    parameters: &[FitParameter],
    x: &[f64],
    step: f64,
    centre: &[f64],
    predict: &Predict,
) -> Result<DMatrix<f64>, ValidationError> {
    let u = scaled(parameters, x);
    let columns: Vec<Vec<f64>> = (0..parameters.len())
        .into_par_iter()
        .map(|j| {
            let (lo, hi) = ((u[j] - step).max(0.0), (u[j] + step).min(1.0));
            let (mut a, mut b) = (u.clone(), u.clone());
            a[j] = lo;
            b[j] = hi;
            let (a, b) = (unscaled(parameters, &a), unscaled(parameters, &b));
            // A side whose diagram the loader refuses (outside the feasible set) gives way to a
            // one-sided difference from the fit.
            let side = |x: &[f64], at: f64| match relative_errors(rows, x, predict) {
                Ok(r) => Ok(Some((r, at))),
                Err(e) if infeasible(&e) => Ok(None),
                Err(e) => Err(e),
            };
            let here = (centre.to_vec(), u[j]);
            let ((ra, ua), (rb, ub)) = match (side(&a, lo)?, side(&b, hi)?) {
                (Some(a), Some(b)) => (a, b),
                (Some(a), None) => (a, here),
                (None, Some(b)) => (here, b),
                (None, None) => {
                    return Err(ValidationError::Calibration(format!(
                        "{}: no feasible parameter set within {step} of its range around the fit",
                        parameters[j].name
                    )))
                }
            };
            Ok(ra
                .iter()
                .zip(&rb)
                .map(|(ea, eb)| (eb - ea) / (ub - ua))
                .collect())
        })
        .collect::<Result<_, ValidationError>>()?;
    Ok(DMatrix::from_fn(rows.len(), parameters.len(), |i, j| {
        columns[j][i]
    }))
}

/// What `rows` determine of `parameters` at the fit `x`, by the criterion of `protocol` (its
/// Jacobian step and determined ratio), and the covariance (scaled units) behind it.
pub(super) fn identifiability(
    rows: &[Row],
    parameters: &[FitParameter],
    protocol: &CvProtocol,
    x: &[f64],
    predict: &Predict,
) -> Result<(Identifiability, DMatrix<f64>), ValidationError> {
    let residuals = relative_errors(rows, x, predict)?;
    let j = jacobian(
        rows,
        parameters,
        x,
        protocol.jacobian_step,
        &residuals,
        predict,
    )?;
    let ssr: f64 = residuals.iter().map(|r| r * r).sum();
    let dof = rows.len().saturating_sub(parameters.len()).max(1);
    let residual_variance = ssr / dof as f64;
    let c = covariance(&j, residual_variance)?;
    let mut singular_values: Vec<f64> = j
        .clone()
        .svd(false, false)
        .singular_values
        .iter()
        .copied()
        .collect();
    singular_values.sort_by(|a, b| b.total_cmp(a));
    let prior = 1.0 / 12f64.sqrt();
    let determinations = parameters
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let ratio = c[(k, k)].sqrt() / prior;
            Determination {
                name: p.name.clone(),
                value: x[k],
                sd: c[(k, k)].sqrt() * (p.upper - p.lower),
                prior_sd: prior * (p.upper - p.lower),
                ratio,
                determined: ratio <= protocol.determined_ratio,
            }
        })
        .collect();
    let n = parameters.len();
    let correlation = (0..n)
        .map(|a| {
            (0..n)
                .map(|b| c[(a, b)] / (c[(a, a)] * c[(b, b)]).sqrt())
                .collect()
        })
        .collect();
    let jacobian = (0..j.nrows())
        .map(|i| j.row(i).iter().copied().collect())
        .collect();
    Ok((
        Identifiability {
            singular_values,
            residual_variance,
            parameters: determinations,
            correlation,
            jacobian,
        },
        c,
    ))
}
