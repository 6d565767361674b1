//! The dispersions' distributions and each landing's draws.
//!
//! Every landing has its own random stream: ChaCha8 keyed by the campaign's seed, on the stream
//! numbered by the landing's index (a counter-based generator: landing i's numbers depend on
//! (seed, i) only, never on which thread, shard or order ran it). Landing i draws one uniform
//! number per dispersion, in the file's order, turns each into a standard normal score
//! z = Φ⁻¹(u), correlates the scores through the Cholesky factor of the correlation matrix (a
//! Gaussian copula: the coefficients are those of the scores, which for two normal dispersions
//! is their correlation), and maps each score through its distribution's quantile function.

use nalgebra::{DMatrix, DVector};
use rand_chacha::rand_core::SeedableRng;
use rand_chacha::ChaCha8Rng;
use statrs::distribution::{ContinuousCDF, Normal};
use touchdown_sampling::open_unit;

/// A value applied to a scenario field.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// A number, in the scenario file's units.
    Number(f64),
    /// A string (a surface kind, a mode).
    Text(String),
    /// A boolean.
    Flag(bool),
}

impl Value {
    /// The value as TOML, to override a scenario field with.
    pub fn to_toml(&self) -> toml::Value {
        match self {
            Value::Number(x) => toml::Value::Float(*x),
            Value::Text(s) => toml::Value::String(s.clone()),
            Value::Flag(b) => toml::Value::Boolean(*b),
        }
    }

    /// A TOML value read back from a resolved scenario; `None` if it is not a scalar.
    pub fn from_toml(v: &toml::Value) -> Option<Value> {
        match v {
            toml::Value::Float(x) => Some(Value::Number(*x)),
            toml::Value::Integer(i) => Some(Value::Number(*i as f64)),
            toml::Value::String(s) => Some(Value::Text(s.clone())),
            toml::Value::Boolean(b) => Some(Value::Flag(*b)),
            _ => None,
        }
    }
}

/// A distribution of a dispersed field, in the scenario file's units.
#[derive(Debug, Clone, PartialEq)]
pub enum Distribution {
    /// Normal, N(mean, std_dev²).
    Normal {
        /// Mean.
        mean: f64,
        /// Standard deviation, > 0.
        std_dev: f64,
    },
    /// Normal N(mean, std_dev²) restricted to [min, max].
    TruncatedNormal {
        /// Mean of the untruncated normal.
        mean: f64,
        /// Standard deviation of the untruncated normal.
        std_dev: f64,
        /// Lower bound.
        min: f64,
        /// Upper bound.
        max: f64,
        /// Φ((min − mean)/std_dev).
        p_min: f64,
        /// Φ((max − mean)/std_dev).
        p_max: f64,
    },
    /// Uniform on [min, max].
    Uniform {
        /// Lower bound.
        min: f64,
        /// Upper bound.
        max: f64,
    },
    /// Log-normal: ln x is normal with mean ln(median) and standard deviation log_std_dev.
    LogNormal {
        /// Median, > 0.
        median: f64,
        /// Standard deviation of ln x, > 0.
        log_std_dev: f64,
    },
    /// One of `values`, value k with probability weight k over the sum of the weights.
    Choice {
        /// The values.
        values: Vec<Value>,
        /// Cumulative probabilities, the last 1.
        cumulative: Vec<f64>,
    },
    /// A fixed list: landing i takes `values[i mod len]` (no draw).
    List {
        /// The values.
        values: Vec<Value>,
    },
}

/// The standard normal distribution.
fn standard() -> Normal {
    Normal::standard()
}

impl Distribution {
    /// The truncated normal, refused when [min, max] holds less than 10⁻¹² of the normal's
    /// probability (its quantiles would be rounding noise).
    pub fn truncated_normal(
        mean: f64,
        std_dev: f64,
        min: f64,
        max: f64,
    ) -> Result<Distribution, String> {
        let p_min = standard().cdf((min - mean) / std_dev);
        let p_max = standard().cdf((max - mean) / std_dev);
        if p_max - p_min < 1e-12 {
            return Err(format!(
                "[{min}, {max}] lies too far in the tail of N({mean}, {std_dev}²) to draw from"
            ));
        }
        Ok(Distribution::TruncatedNormal {
            mean,
            std_dev,
            min,
            max,
            p_min,
            p_max,
        })
    }

    /// A choice among `values` with `weights` (≥ 0, not all zero, one per value).
    pub fn choice(values: Vec<Value>, weights: &[f64]) -> Distribution {
        let total: f64 = weights.iter().sum();
        let mut sum = 0.0;
        let mut cumulative: Vec<f64> = weights
            .iter()
            .map(|w| {
                sum += w;
                sum / total
            })
            .collect();
        if let Some(last) = cumulative.last_mut() {
            *last = 1.0;
        }
        Distribution::Choice { values, cumulative }
    }

    /// The value at normal score `z` (landing `landing`, for a list).
    pub fn quantile(&self, z: f64, landing: u64) -> Value {
        let p = || standard().cdf(z);
        match self {
            Distribution::Normal { mean, std_dev } => Value::Number(mean + std_dev * z),
            Distribution::TruncatedNormal {
                mean,
                std_dev,
                min,
                max,
                p_min,
                p_max,
            } => {
                let q =
                    (p_min + p() * (p_max - p_min)).clamp(f64::MIN_POSITIVE, 1.0 - f64::EPSILON);
                Value::Number((mean + std_dev * standard().inverse_cdf(q)).clamp(*min, *max))
            }
            Distribution::Uniform { min, max } => Value::Number(min + (max - min) * p()),
            Distribution::LogNormal {
                median,
                log_std_dev,
            } => Value::Number(median * (log_std_dev * z).exp()),
            Distribution::Choice { values, cumulative } => {
                let p = p();
                let k = cumulative
                    .iter()
                    .position(|c| p < *c)
                    .unwrap_or(values.len() - 1);
                values[k].clone()
            }
            Distribution::List { values } => {
                values[(landing % values.len() as u64) as usize].clone()
            }
        }
    }

    /// Whether every value the distribution can give is a finite number (and, log-normal, a
    /// positive one): checked at its centre and at ±9 (the normal scores of the open-unit
    /// uniforms reach ±8.3), where the quantile functions are monotone.
    pub fn draws_are_finite(&self) -> bool {
        [-9.0, 0.0, 9.0].iter().all(|z| match self.quantile(*z, 0) {
            Value::Number(x) => {
                x.is_finite() && !(matches!(self, Distribution::LogNormal { .. }) && x <= 0.0)
            }
            _ => true,
        })
    }

    /// A central value (the median or the first of a list), for the campaign's dry run.
    pub fn central(&self) -> Value {
        match self {
            Distribution::List { values } => values[0].clone(),
            d => d.quantile(0.0, 0),
        }
    }

    /// The distribution's name, as in campaign files.
    pub fn name(&self) -> &'static str {
        match self {
            Distribution::Normal { .. } => "normal",
            Distribution::TruncatedNormal { .. } => "truncated_normal",
            Distribution::Uniform { .. } => "uniform",
            Distribution::LogNormal { .. } => "log_normal",
            Distribution::Choice { .. } => "choice",
            Distribution::List { .. } => "list",
        }
    }
}

/// The random stream of landing `landing` of a campaign seeded `seed`.
pub fn stream(seed: u64, landing: u64) -> ChaCha8Rng {
    let mut key = [0u8; 32];
    key[..8].copy_from_slice(&seed.to_le_bytes());
    let mut rng = ChaCha8Rng::from_seed(key);
    rng.set_stream(landing);
    rng
}

/// The normal scores of landing `landing`: one per dispersion, correlated by `copula`.
pub fn scores(seed: u64, landing: u64, count: usize, copula: Option<&DMatrix<f64>>) -> Vec<f64> {
    let mut rng = stream(seed, landing);
    let z = DVector::from_iterator(
        count,
        (0..count).map(|_| standard().inverse_cdf(open_unit(&mut rng))),
    );
    match copula {
        Some(l) => (l * z).iter().copied().collect(),
        None => z.iter().copied().collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streams_depend_on_the_seed_and_the_landing_only() {
        let a = scores(7, 12, 3, None);
        assert_eq!(a, scores(7, 12, 3, None));
        assert_ne!(a, scores(7, 13, 3, None));
        assert_ne!(a, scores(8, 12, 3, None));
        // Drawing more numbers does not change the first ones.
        assert_eq!(a[..2], scores(7, 12, 2, None)[..]);
    }

    /// The generator's test, as TN D-3117 tested its own: 20,000 scores over 20 equiprobable
    /// bins of the normal (χ² with 19 degrees of freedom, 0.1 % critical value 43.82), no
    /// correlation between consecutive landings, and uniform numbers strictly inside (0, 1).
    #[test]
    fn scores_are_standard_normal_and_independent_across_landings() {
        let n = 20_000u64;
        let z: Vec<f64> = (0..n).map(|i| scores(1965, i, 1, None)[0]).collect();
        let mut bins = [0u32; 20];
        for x in &z {
            let p = standard().cdf(*x);
            bins[((p * 20.0) as usize).min(19)] += 1;
        }
        let expected = n as f64 / 20.0;
        let chi2: f64 = bins
            .iter()
            .map(|b| (*b as f64 - expected).powi(2) / expected)
            .sum();
        assert!(chi2 < 43.82, "χ² = {chi2}, bins {bins:?}");
        let lag1: f64 = z.windows(2).map(|w| w[0] * w[1]).sum::<f64>() / (n - 1) as f64;
        assert!(
            lag1.abs() < 4.0 / (n as f64).sqrt(),
            "lag-1 correlation {lag1}"
        );
        let mut rng = stream(0, 0);
        assert!((0..10_000).all(|_| {
            let u = open_unit(&mut rng);
            u > 0.0 && u < 1.0
        }));
    }

    #[test]
    fn quantiles_map_scores_to_each_distribution() {
        let n = Distribution::Normal {
            mean: -8.0,
            std_dev: 2.0,
        };
        assert_eq!(n.quantile(1.5, 0), Value::Number(-5.0));
        let u = Distribution::Uniform {
            min: 0.0,
            max: 10.0,
        };
        assert!(matches!(u.quantile(0.0, 0), Value::Number(x) if (x - 5.0).abs() < 1e-12));
        let l = Distribution::LogNormal {
            median: 3.0,
            log_std_dev: 0.5,
        };
        assert!(
            matches!(l.quantile(2.0, 0), Value::Number(x) if (x - 3.0 * 1f64.exp()).abs() < 1e-12)
        );
        let t = Distribution::truncated_normal(0.0, 1.0, -1.0, 2.0).unwrap();
        for z in [-9.0, -1.0, 0.0, 1.0, 9.0] {
            let Value::Number(x) = t.quantile(z, 0) else {
                panic!()
            };
            assert!((-1.0..=2.0).contains(&x), "{x}");
        }
        // The median of the truncated normal: Φ(x) = (Φ(-1) + Φ(2))/2.
        let Value::Number(m) = t.quantile(0.0, 0) else {
            panic!()
        };
        let target = 0.5 * (standard().cdf(-1.0) + standard().cdf(2.0));
        assert!((standard().cdf(m) - target).abs() < 1e-12);
        assert!(Distribution::truncated_normal(0.0, 1.0, 40.0, 41.0).is_err());
        assert!(t.draws_are_finite() && n.draws_are_finite() && l.draws_are_finite());
        let wide = Distribution::Uniform {
            min: -1e308,
            max: 1e308,
        };
        let steep = Distribution::LogNormal {
            median: 1.0,
            log_std_dev: 1e3,
        };
        assert!(!wide.draws_are_finite() && !steep.draws_are_finite());
        let c = Distribution::choice(
            vec![Value::Text("a".into()), Value::Text("b".into())],
            &[1.0, 3.0],
        );
        // P(a) = 1/4: scores below Φ⁻¹(1/4) = -0.6745 pick a.
        assert_eq!(c.quantile(-0.7, 0), Value::Text("a".into()));
        assert_eq!(c.quantile(-0.6, 0), Value::Text("b".into()));
        let list = Distribution::List {
            values: vec![Value::Number(1.0), Value::Number(2.0)],
        };
        assert_eq!(list.quantile(0.0, 5), Value::Number(2.0));
    }

    #[test]
    fn a_copula_correlates_the_scores_as_asked() {
        let rho: f64 = 0.6;
        let l = DMatrix::from_row_slice(2, 2, &[1.0, 0.0, rho, (1.0 - rho * rho).sqrt()]);
        let n = 20_000;
        let pairs: Vec<Vec<f64>> = (0..n).map(|i| scores(3, i, 2, Some(&l))).collect();
        let r: f64 = pairs.iter().map(|p| p[0] * p[1]).sum::<f64>() / n as f64;
        // The sample correlation's standard error is (1 − ρ²)/√n ≈ 0.0045.
        assert!((r - rho).abs() < 0.02, "{r}");
    }
}
