//! The calibration's uncertainty: scaled parameters, linearised covariance, draws from it.

use crate::reference::FitParameter;
use crate::ValidationError;
use nalgebra::{DMatrix, DVector};
use rand_chacha::rand_core::SeedableRng;
use rand_chacha::ChaCha8Rng;
use statrs::distribution::{ContinuousCDF, Normal};
use touchdown_sampling::open_unit;

/// Most draws tried per accepted sample (the rest fall outside the bounds) before the sampling
/// is refused.
const MAX_DRAWS_PER_SAMPLE: usize = 10_000;

/// Scaled coordinates of `x`.
pub(super) fn scaled(parameters: &[FitParameter], x: &[f64]) -> Vec<f64> {
    parameters
        .iter()
        .zip(x)
        .map(|(p, v)| (v - p.lower) / (p.upper - p.lower))
        .collect()
}

/// File units of scaled coordinates `u`.
pub(super) fn unscaled(parameters: &[FitParameter], u: &[f64]) -> Vec<f64> {
    parameters
        .iter()
        .zip(u)
        .map(|(p, v)| p.lower + v * (p.upper - p.lower))
        .collect()
}

/// The linearised covariance of the scaled parameters, s² (JᵀJ + 12 s² I)⁻¹: the fit's
/// curvature with the bounds read as a uniform prior of variance 1/12 (scaled units).
pub(super) fn covariance(
    j: &DMatrix<f64>,
    residual_variance: f64,
) -> Result<DMatrix<f64>, ValidationError> {
    let s2 = residual_variance.max(f64::MIN_POSITIVE);
    let n = j.ncols();
    let precision = j.transpose() * j / s2 + DMatrix::identity(n, n) * 12.0;
    precision
        .try_inverse()
        .ok_or_else(|| ValidationError::Calibration("the fit's covariance is singular".into()))
}

/// `count` parameter sets (file units) drawn from the normal centred on the fit `x` with the
/// scaled covariance `c`, truncated to the bounds by rejection; stream `stream` of `seed`.
pub(super) fn draws(
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
