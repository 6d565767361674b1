//! The uniform draw and the percentile shared by the campaigns (`touchdown-campaign`: dispersed
//! landings and their statistics) and the validation protocols (`touchdown-validation`: the
//! cross-validation's parameter draws and prediction intervals), so that both turn random bits
//! into numbers, and samples into intervals, by one rule.

use rand_chacha::rand_core::Rng;

/// A uniform number in the open interval (0, 1) from the top 53 bits of the next 64-bit word:
/// (k + ½)/2⁵³ for k in [0, 2⁵³), never 0 or 1, so that an inverse CDF of it is finite.
pub fn open_unit<R: Rng + ?Sized>(rng: &mut R) -> f64 {
    ((rng.next_u64() >> 11) as f64 + 0.5) * (1.0 / (1u64 << 53) as f64)
}

/// The `p` percentile (0 ≤ p ≤ 1) of `sorted` (ascending, not empty), linearly interpolated
/// between order statistics, as numpy's default (`numpy.percentile`, method "linear").
pub fn percentile(sorted: &[f64], p: f64) -> f64 {
    let h = (sorted.len() - 1) as f64 * p;
    let lo = h.floor() as usize;
    let hi = (lo + 1).min(sorted.len() - 1);
    sorted[lo] + (h - lo as f64) * (sorted[hi] - sorted[lo])
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand_chacha::rand_core::SeedableRng;

    #[test]
    fn percentiles_interpolate_as_numpy_does() {
        let v = [1.0, 2.0, 3.0, 4.0];
        // numpy.percentile([1, 2, 3, 4], [50, 90]) = [2.5, 3.7]
        assert_eq!(percentile(&v, 0.5), 2.5);
        assert!((percentile(&v, 0.9) - 3.7).abs() < 1e-12);
        assert_eq!(percentile(&v, 0.0), 1.0);
        assert_eq!(percentile(&v, 1.0), 4.0);
        assert_eq!(percentile(&[5.0], 0.99), 5.0);
    }

    #[test]
    fn uniform_draws_stay_inside_the_open_interval() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let draws: Vec<f64> = (0..10_000).map(|_| open_unit(&mut rng)).collect();
        assert!(draws.iter().all(|&u| u > 0.0 && u < 1.0));
        let mean = draws.iter().sum::<f64>() / draws.len() as f64;
        // The mean of 10,000 uniforms is within 4 standard errors (0.0029 each) of ½.
        assert!(
            (mean - 0.5).abs() < 4.0 * (1.0 / 12.0f64 / 1e4).sqrt(),
            "{mean}"
        );
    }
}
