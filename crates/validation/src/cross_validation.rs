//! Cross-validation of the 1/6-scale model's calibration against Table I
//! (`reference/cross-validation-protocol.toml`; docs/validation.md, "Cross-validation"): each
//! row is predicted by a fit that never saw it (leave-one-out), what the rows can determine is
//! measured rather than assumed (the Jacobian's singular values, each parameter's spread against
//! its bounds, a profile of the objective along each parameter), and every prediction carries
//! the calibration's uncertainty (parameter sets drawn from the fold's linearised covariance).
//!
//! Parameters are handled scaled to their bounds, u = (x − lower) / (upper − lower), so that the
//! Jacobian, the covariance and the singular values do not depend on the parameters' units.

use crate::calibrate::{
    fields_of, fit, infeasible, overrides, relative_errors, rows_of, table_model, Fit, Predict,
    Restarts, INFEASIBLE,
};
use crate::checkpoint::{counted, Checkpoint};
use crate::facts::{self, FactCheck};
use crate::reference::{
    self, CalibrationRecord, Estimates, FitParameter, Paths, Protocol, Row, TableI,
};
use crate::ValidationError;
use nalgebra::{DMatrix, DVector};
use rand_chacha::rand_core::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use statrs::distribution::{ContinuousCDF, Normal};
use touchdown_sampling::{open_unit, percentile};

/// Points of each parameter's profile, spread evenly over its bounds.
pub const PROFILE_POINTS: usize = 9;

/// Candidate parameter sets drawn per sample kept, of which the feasible ones are kept in draw
/// order.
const FEASIBLE_CANDIDATES: usize = 2;

/// Most draws tried per accepted sample (the rest fall outside the bounds) before the sampling
/// is refused.
const MAX_DRAWS_PER_SAMPLE: usize = 10_000;

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

/// The profile of the objective along one parameter: at each value, the other parameters
/// fitted again to every row. Values at which no feasible parameter set was found (every
/// diagram tried refused by the loader) are left out.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Profile {
    /// The parameter.
    pub name: String,
    /// Its values, file units, over its bounds.
    pub value: Vec<f64>,
    /// The lowest objective (sum of squared relative errors over every row) with the
    /// parameter at each value.
    pub objective: Vec<f64>,
    /// Every parameter at each value (file units, the protocol's order): how the others move
    /// to make up for it.
    pub fitted: Vec<Vec<f64>>,
}

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

/// Scaled coordinates of `x`.
fn scaled(parameters: &[FitParameter], x: &[f64]) -> Vec<f64> {
    parameters
        .iter()
        .zip(x)
        .map(|(p, v)| (v - p.lower) / (p.upper - p.lower))
        .collect()
}

/// File units of scaled coordinates `u`.
fn unscaled(parameters: &[FitParameter], u: &[f64]) -> Vec<f64> {
    parameters
        .iter()
        .zip(u)
        .map(|(p, v)| p.lower + v * (p.upper - p.lower))
        .collect()
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

/// The linearised covariance of the scaled parameters, s² (JᵀJ + 12 s² I)⁻¹: the fit's
/// curvature with the bounds read as a uniform prior of variance 1/12 (scaled units).
fn covariance(j: &DMatrix<f64>, residual_variance: f64) -> Result<DMatrix<f64>, ValidationError> {
    let s2 = residual_variance.max(f64::MIN_POSITIVE);
    let n = j.ncols();
    let precision = j.transpose() * j / s2 + DMatrix::identity(n, n) * 12.0;
    precision
        .try_inverse()
        .ok_or_else(|| ValidationError::Calibration("the fit's covariance is singular".into()))
}

/// What `rows` determine of `parameters` at the fit `x`, by the criterion of `protocol` (its
/// Jacobian step and determined ratio), and the covariance (scaled units) behind it.
fn identifiability(
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

/// `count` parameter sets (file units) drawn from the normal centred on the fit `x` with the
/// scaled covariance `c`, truncated to the bounds by rejection; stream `stream` of `seed`.
fn draws(
    parameters: &[FitParameter],
    x: &[f64],
    c: &DMatrix<f64>,
    count: usize,
    seed: u64,
    stream: u64,
) -> Result<Vec<Vec<f64>>, ValidationError> {
    let l = c.clone().cholesky().ok_or_else(|| {
        ValidationError::Calibration("the fit's covariance is not positive definite".into())
    })?;
    let l = l.l();
    let centre = DVector::from_vec(scaled(parameters, x));
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(stream);
    let normal = Normal::standard();
    let mut out = Vec::with_capacity(count);
    let mut tried = 0;
    while out.len() < count {
        tried += 1;
        if tried > MAX_DRAWS_PER_SAMPLE * count {
            return Err(ValidationError::Calibration(format!(
                "fewer than 1 in {MAX_DRAWS_PER_SAMPLE} draws of the fit's covariance fall within the bounds"
            )));
        }
        let z = DVector::from_fn(parameters.len(), |_, _| {
            normal.inverse_cdf(open_unit(&mut rng))
        });
        let u = &centre + &l * z;
        if u.iter().all(|v| (0.0..=1.0).contains(v)) {
            out.push(unscaled(parameters, u.as_slice()));
        }
    }
    Ok(out)
}

/// The profile of parameter `k` over its bounds ([`PROFILE_POINTS`] values): the others
/// fitted again at each, from their values in `full` (the fit to every row), with the
/// protocol's optimiser and restarts; each point a unit of `checkpoint`. Returns the profile
/// and the landings it ran.
fn profile(
    table: &[Row],
    protocol: &CvProtocol,
    k: usize,
    full: &Fit,
    predict: &Predict,
    checkpoint: Option<&Checkpoint>,
) -> Result<(Profile, usize), ValidationError> {
    let p = &protocol.parameter[k];
    let values: Vec<f64> = (0..PROFILE_POINTS)
        .map(|i| p.lower + (p.upper - p.lower) * i as f64 / (PROFILE_POINTS - 1) as f64)
        .collect();
    // The others start at the full fit, just inside their bounds (a fit starts strictly inside).
    let others: Vec<FitParameter> = protocol
        .parameter
        .iter()
        .zip(&full.value)
        .enumerate()
        .filter(|(i, _)| *i != k)
        .map(|(_, (q, v))| {
            let edge = 1e-6 * (q.upper - q.lower);
            FitParameter {
                initial: v.clamp(q.lower + edge, q.upper - edge),
                ..q.clone()
            }
        })
        .collect();
    let points: Vec<(ProfilePoint, usize)> = values
        .par_iter()
        .enumerate()
        .map(|(j, v)| {
            unit(
                checkpoint,
                &format!("profile-{k}-{j}"),
                predict,
                |predict| {
                    let with = |y: &[f64]| {
                        let mut x = y.to_vec();
                        x.insert(k, *v);
                        x
                    };
                    let fixed = |row: &Row, y: &[f64]| predict(row, &with(y));
                    let f = fit(
                        table,
                        &others,
                        protocol.max_iterations,
                        Some(protocol.restarts()),
                        &fixed,
                    )?;
                    Ok(ProfilePoint {
                        fit: (f.objective < INFEASIBLE).then(|| (f.objective, with(&f.value))),
                    })
                },
            )
        })
        .collect::<Result<_, ValidationError>>()?;
    let landings = points.iter().map(|(_, n)| n).sum();
    let mut profile = Profile {
        name: p.name.clone(),
        value: Vec::new(),
        objective: Vec::new(),
        fitted: Vec::new(),
    };
    for (v, (point, _)) in values.into_iter().zip(points) {
        if let Some((objective, x)) = point.fit {
            profile.value.push(v);
            profile.objective.push(objective);
            profile.fitted.push(x);
        }
    }
    Ok((profile, landings))
}

/// One point of a profile: the objective and every parameter of the fit there, or `None` if
/// no feasible parameter set was found.
#[derive(Serialize, Deserialize)]
struct ProfilePoint {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    fit: Option<(f64, Vec<f64>)>,
}

/// The unit of work `name`, kept in `checkpoint` if there is one (computed with `predict`
/// unless the checkpoint holds it), and the landings it ran.
fn unit<T: Serialize + DeserializeOwned>(
    checkpoint: Option<&Checkpoint>,
    name: &str,
    predict: &Predict,
    compute: impl FnOnce(&Predict) -> Result<T, ValidationError>,
) -> Result<(T, usize), ValidationError> {
    match checkpoint {
        Some(c) => c.unit(name, predict, compute),
        None => counted(predict, compute),
    }
}

/// Mean and largest |error| of `folds` restricted to `rows`.
fn errors(folds: &[Fold], rows: &[u32]) -> Errors {
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

/// What a fold computes: the fit on every row but the held-out one, what they determine, and
/// the prediction of the held-out row with its interval, in.
#[derive(Serialize, Deserialize)]
struct FoldParts {
    fit: Fit,
    identifiability: Identifiability,
    predicted_in: f64,
    interval_in: [f64; 2],
}

/// One fold: fit on every row of `table` but `held_out`, predict it with its interval.
fn fold(
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
fn fold_of(row: &Row, parts: FoldParts) -> Fold {
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

/// Cross-validates `protocol` over the rows of `table` with the model `predict`;
/// `two_row_held_out` are the rows the two-row protocol holds out (its target's rows). With a
/// `checkpoint`, every fold, the fit to every row and every profile point is kept there as it
/// ends, and what it already holds is not computed again (the result is the same).
pub fn cross_validate_with(
    table: &[Row],
    protocol: &CvProtocol,
    two_row_held_out: &[u32],
    predict: &Predict,
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
        protocol: protocol.clone(),
        folds,
        full_fit,
        identifiability,
        profiles,
        facts: Vec::new(),
        landings,
    })
}

/// How many landings a whole cross-validation lands, about: 2,356,323 in the run of
/// `docs/validation/cross-validation.json` (its `landings`); the fits' iterations vary with the
/// model, so a run lands about as many, not exactly.
pub const LANDINGS_ABOUT: u64 = 2_400_000;

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
    let model = table_model(paths, &table.row, &fields)?;
    let held_out: Vec<u32> = table
        .row
        .iter()
        .map(|r| r.id)
        .filter(|id| !two_row.rows.contains(id))
        .collect();
    let counted = |row: &Row, x: &[f64]| {
        let stroke = model(row, x);
        landed();
        stroke
    };
    let mut cv = cross_validate_with(&table.row, &protocol, &held_out, &counted, checkpoint)?;
    cv.facts = facts::check(paths, &overrides(&fields, &cv.full_fit.value))?.checks;
    cv.landings += 1;
    Ok(cv)
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
    let model = table_model(paths, &rows, &fields)?;
    identifiability(&rows, parameters, &protocol, &x, &model).map(|(i, _)| i)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::Strut;

    fn row(id: u32, vv: f64, experiment: f64) -> Row {
        Row {
            id,
            landing: "test".into(),
            vv,
            vh: 0.0,
            strut: Strut::Primary,
            experiment,
            analysis: experiment * 1.01,
            scenario: String::new(),
        }
    }

    fn parameter(name: &str, initial: f64) -> FitParameter {
        FitParameter {
            name: name.into(),
            initial,
            lower: 0.1,
            upper: 10.0,
        }
    }

    fn protocol(parameter: Vec<FitParameter>) -> CvProtocol {
        CvProtocol {
            folds: Folds::LeaveOneOut,
            max_iterations: 400,
            restart_simplex: 0.25,
            max_restarts: 4,
            restart_improvement: 1e-6,
            jacobian_step: 0.01,
            determined_ratio: 0.5,
            samples: 32,
            seed: 7,
            parameter,
        }
    }

    /// A stroke law known in closed form: s = a·|vv| + b, made exact by construction.
    fn linear(x: &[f64], vv: f64) -> f64 {
        x[0] * vv.abs() + x[1]
    }

    #[test]
    fn an_exact_model_is_predicted_out_of_fold_and_its_parameters_are_determined() {
        let truth = [1.5, 2.0];
        let table: Vec<Row> = (1..=6)
            .map(|i| row(i, -(i as f64) - 3.0, linear(&truth, -(i as f64) - 3.0)))
            .collect();
        let predict = |r: &Row, x: &[f64]| Ok(linear(x, r.vv));
        let p = protocol(vec![parameter("a", 1.0), parameter("b", 1.0)]);
        let cv = cross_validate_with(&table, &p, &[1, 2, 3], &predict, None).unwrap();
        assert_eq!(cv.folds.len(), 6);
        for f in &cv.folds {
            assert!(
                f.error_pct.abs() < 1e-3,
                "row {}: {}",
                f.held_out,
                f.error_pct
            );
        }
        assert!(cv.identifiability.parameters.iter().all(|d| d.determined));
        assert!(
            (cv.full_fit.value[0] - 1.5).abs() < 1e-3 && (cv.full_fit.value[1] - 2.0).abs() < 1e-3,
            "{:?}",
            cv.full_fit
        );
        assert_eq!(cv.two_row_held_out.rows, vec![1, 2, 3]);
        // The report's analysis is 1 % off on every row by construction.
        assert!((cv.all_rows.report_mean_pct - 1.0).abs() < 1e-9);
    }

    /// Two parameters that enter only through their product, and one that does not enter at
    /// all: the rows fix the product, the sum and nothing of the third, and the analysis must
    /// say so.
    #[test]
    fn parameters_the_rows_cannot_separate_are_not_determined() {
        let table: Vec<Row> = (1..=6)
            .map(|i| row(i, -(i as f64), 3.0 * i as f64 + 1.0))
            .collect();
        let predict = |r: &Row, x: &[f64]| Ok(x[0] * x[1] * r.vv.abs() + x[2]);
        let p = protocol(vec![
            parameter("m", 2.0),
            parameter("k", 2.0),
            parameter("c", 2.0),
            parameter("unused", 2.0),
        ]);
        let cv = cross_validate_with(&table, &p, &[1], &predict, None).unwrap();
        let id = &cv.identifiability;
        let d = &id.parameters;
        assert!(d[2].determined && d[2].ratio < 0.1, "{d:?}");
        assert!(!d[3].determined && d[3].ratio > 0.95, "{d:?}");
        assert!(!(d[0].determined && d[1].determined), "{d:?}");
        // Two directions of the scaled Jacobian are null: the unused parameter, and m against k.
        let s = &id.singular_values;
        assert!(s[2] < 1e-3 * s[0] && s[3] < 1e-3 * s[0], "{s:?}");
        assert!(id.correlation[0][1] < -0.5, "{:?}", id.correlation);
        // Out of fold, the product and the sum are still predicted.
        assert!(cv.all_rows.mean_pct < 1e-2, "{:?}", cv.all_rows);
    }

    #[test]
    fn the_held_out_row_never_enters_its_fold() {
        let table: Vec<Row> = (1..=5)
            .map(|i| row(i, -(i as f64), 2.0 * i as f64 + 0.3 * (i as f64).sin()))
            .collect();
        let predict = |r: &Row, x: &[f64]| Ok(x[0] * r.vv.abs() + x[1]);
        let p = protocol(vec![parameter("a", 1.0), parameter("b", 1.0)]);
        let cv = cross_validate_with(&table, &p, &[1], &predict, None).unwrap();
        let mut moved = table.clone();
        moved[2].experiment *= 2.0;
        let again = cross_validate_with(&moved, &p, &[1], &predict, None).unwrap();
        // Row 3's own fold is bit for bit the same fit; every other fold, which sees row 3, moves.
        assert_eq!(cv.folds[2].fit, again.folds[2].fit);
        assert_eq!(cv.folds[2].predicted_in, again.folds[2].predicted_in);
        for i in [0, 1, 3, 4] {
            assert_ne!(cv.folds[i].fit, again.folds[i].fit, "fold {i}");
        }
    }

    #[test]
    fn a_run_stopped_part_way_resumes_from_its_checkpoint_to_the_same_result() {
        let table: Vec<Row> = (1..=5)
            .map(|i| row(i, -(i as f64), 2.0 * i as f64 + 0.3 * (i as f64).sin()))
            .collect();
        let predict = |r: &Row, x: &[f64]| Ok(x[0] * r.vv.abs() + x[1]);
        let p = protocol(vec![parameter("a", 1.0), parameter("b", 1.0)]);
        let whole = cross_validate_with(&table, &p, &[1], &predict, None).unwrap();
        // A run that dies after a third of its landings (as a killed run would) ...
        let dir = tempfile::tempdir().unwrap();
        let checkpoint = Checkpoint::new(dir.path(), "this run").unwrap();
        let calls = std::sync::atomic::AtomicUsize::new(0);
        let dying = |r: &Row, x: &[f64]| {
            if calls.fetch_add(1, std::sync::atomic::Ordering::Relaxed) > whole.landings / 3 {
                Err(ValidationError::Calibration("killed".into()))
            } else {
                predict(r, x)
            }
        };
        assert!(cross_validate_with(&table, &p, &[1], &dying, Some(&checkpoint)).is_err());
        let (kept, kept_landings) = checkpoint.kept();
        assert!(kept > 0, "some units finished before the kill");
        // ... resumes from what it kept, landing fewer, to the same result and count.
        let resumed_calls = std::sync::atomic::AtomicUsize::new(0);
        let counting = |r: &Row, x: &[f64]| {
            resumed_calls.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            predict(r, x)
        };
        let resumed = cross_validate_with(&table, &p, &[1], &counting, Some(&checkpoint)).unwrap();
        assert_eq!(resumed, whole);
        let landed = resumed_calls.load(std::sync::atomic::Ordering::Relaxed);
        assert!(landed < whole.landings, "{landed} of {}", whole.landings);
        // The kept units' landings and the resumed run's make the whole run's (what a resumed
        // run's progress starts from).
        assert_eq!(kept_landings + landed, whole.landings);
        // Units of another run's key are not taken.
        let other = Checkpoint::new(dir.path(), "another program").unwrap();
        assert_eq!(other.kept(), (0, 0));
    }

    #[test]
    fn intervals_widen_with_the_misfit_and_cover_the_truth_of_a_noisy_law() {
        // A law with a ±5 % wobble the model cannot follow: the misfit sets s², so the
        // intervals are a few per cent wide, not zero.
        let table: Vec<Row> = (1..=8)
            .map(|i| {
                let vv = -(i as f64);
                let wobble = if i % 2 == 0 { 1.05 } else { 0.95 };
                row(i, vv, linear(&[1.5, 2.0], vv) * wobble)
            })
            .collect();
        let predict = |r: &Row, x: &[f64]| Ok(linear(x, r.vv));
        let p = protocol(vec![parameter("a", 1.0), parameter("b", 1.0)]);
        let cv = cross_validate_with(&table, &p, &[1], &predict, None).unwrap();
        for f in &cv.folds {
            let width = (f.interval_in[1] - f.interval_in[0]) / f.predicted_in;
            assert!(width > 0.01 && width < 0.5, "row {}: {width}", f.held_out);
            assert!(f.interval_in[0] <= f.predicted_in && f.predicted_in <= f.interval_in[1]);
        }
        assert!(cv.identifiability.residual_variance > 0.0);
    }

    #[test]
    fn a_bad_protocol_names_its_field() {
        let mut p = protocol(vec![parameter("a", 1.0)]);
        p.samples = 1;
        let e = p.check().unwrap_err().to_string();
        assert!(e.contains("samples"), "{e}");
        let mut p = protocol(vec![parameter("a", 1.0)]);
        p.parameter[0].initial = 20.0;
        let e = p.check().unwrap_err().to_string();
        assert!(e.contains(": a: expected finite bounds"), "{e}");
    }
}
