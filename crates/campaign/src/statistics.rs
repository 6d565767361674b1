//! A campaign's statistics: the probability of a stable landing with its one-sided
//! Clopper-Pearson lower bound (the "lower-limit probability of a stable landing" of TN D-3117),
//! the zero-failure sample sizes, counts per outcome, failure mode and stroked-out strut, and
//! percentiles of the strokes against their capacities and of the peak loads
//! (docs/campaigns.md, "Statistics").

use crate::record::{strut_of, Cell, Column, Failure, Kind, Measure, Role, Status};
use serde::Serialize;
use statrs::distribution::{Beta, ContinuousCDF};
use touchdown_sampling::percentile;

/// A count of landings under a name.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Count {
    /// The outcome, failure mode or strut.
    pub name: String,
    /// Landings.
    pub landings: u64,
}

/// A proportion of landings with its lower confidence bound.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Proportion {
    /// Landings counted.
    pub landings: u64,
    /// Their fraction of the campaign; absent (not defined) when it holds no landings.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fraction: Option<f64>,
    /// The one-sided Clopper-Pearson lower bound of the probability at the campaign's
    /// confidence; absent when the campaign holds no landings.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lower_bound: Option<f64>,
}

/// A proportion with its two-sided exact (Clopper-Pearson) interval.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Interval {
    /// Landings counted.
    pub landings: u64,
    /// Their fraction of the campaign; absent (not defined) when it holds no landings.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fraction: Option<f64>,
    /// The interval's lower end at the campaign's confidence; absent with no landings.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lower: Option<f64>,
    /// Its upper end; absent with no landings.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub upper: Option<f64>,
}

impl Interval {
    /// The fraction of `k` landings in `n` with its interval at `confidence`
    /// ([`clopper_pearson_interval`]).
    pub fn of(k: u64, n: u64, confidence: f64) -> Interval {
        let (lower, upper) = clopper_pearson_interval(k, n, confidence);
        let defined = |x: f64| (n > 0).then_some(x);
        Interval {
            landings: k,
            fraction: defined(k as f64 / n as f64),
            lower: defined(lower),
            upper: defined(upper),
        }
    }
}

/// Landings a campaign needs to show a reliability at the campaign's confidence with no
/// failure at all: n = ⌈ln(1 − C)/ln R⌉.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ZeroFailure {
    /// The reliability R to show.
    pub reliability: f64,
    /// Landings needed.
    pub landings: u64,
}

/// Percentiles of one column over the landings that measured it (linear interpolation between
/// order statistics, as numpy's default).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Percentiles {
    /// The column (its unit in its name).
    pub column: String,
    /// Landings that measured it.
    pub landings: u64,
    /// Median.
    pub p50: f64,
    /// 90th percentile.
    pub p90: f64,
    /// 99th percentile.
    pub p99: f64,
    /// Maximum.
    pub max: f64,
}

/// How close the landings came to failing by one measure, the smaller the closer: the lower
/// tail of a margin over the landings that measured it (linear interpolation between order
/// statistics, as [`Percentiles`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Margin {
    /// The margin: `min_stability_distance_m` (the closest approach to overturn, m), or a
    /// strut's stroke margin `legN.<strut>.stroke_margin`, 1 − its largest stroke over its
    /// capacity (negative past the capacity).
    pub margin: String,
    /// Landings that measured it.
    pub landings: u64,
    /// The least.
    pub min: f64,
    /// 1st percentile.
    pub p1: f64,
    /// 10th percentile.
    pub p10: f64,
    /// Median.
    pub p50: f64,
    /// The landing with the least (the first of equals).
    pub landing: u64,
}

/// A landing that came closest to failing by a kind of margin, written as the standalone
/// scenario that ran it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ClosestLanding {
    /// `stability_distance` (the closest approach to overturn) or `stroke` (the least stroke
    /// margin of any strut).
    pub by: String,
    /// The margin it has the least of (a [`Margin::margin`]) and its value.
    pub margin: String,
    /// Its value (m for the stability distance, a fraction of capacity for a stroke).
    pub value: f64,
    /// The landing.
    pub landing: u64,
    /// The values applied, by column.
    pub applied: serde_json::Map<String, serde_json::Value>,
    /// The landing as a standalone scenario file in the campaign's folder.
    pub scenario_file: String,
}

/// The margins of a campaign's landings: what a team reads when nothing fails.
#[derive(Debug, Clone, PartialEq, Serialize, Default)]
pub struct Margins {
    /// The closest approach to overturn: each landing's minimum stability distance (absent
    /// when no landing measured one).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stability_distance: Option<Margin>,
    /// Each strut's stroke margin, the least first (ties by name).
    pub strokes: Vec<Margin>,
    /// The landings closest to failing, by the stability distance and by the stroke margin.
    pub closest: Vec<ClosestLanding>,
}

/// How strongly a dispersed input goes with a stable landing: the correlation between its
/// applied value and the indicator of a stable landing (point-biserial), over every landing.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Influence {
    /// The applied value's column.
    pub column: String,
    /// The correlation, in [−1, 1]; absent when it is not defined (the outcome the same on
    /// every landing; an input the same on every landing is not listed).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub correlation_with_stable: Option<f64>,
}

/// A campaign's statistics.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Statistics {
    /// Landings.
    pub landings: u64,
    /// Confidence of the lower bounds, in (0, 1).
    pub confidence: f64,
    /// Landings per outcome (every outcome, zero counts included).
    pub outcomes: Vec<Count>,
    /// Landings per failure mode (each landing has one: docs/campaigns.md).
    pub failures: Vec<Count>,
    /// Landings in which each strut stroked out (only the struts that did).
    pub stroke_outs: Vec<Count>,
    /// Stable landings: the probability of a stable landing and its lower bound.
    pub stable: Proportion,
    /// Stable landings within every strut's capacity.
    pub stable_within_capacity: Proportion,
    /// The zero-failure sample sizes at the campaign's confidence.
    pub zero_failure: Vec<ZeroFailure>,
    /// Percentiles of the strokes (fractions of capacity), peak loads, the peak specific force
    /// and the minimum stability distance.
    pub percentiles: Vec<Percentiles>,
    /// The numeric dispersed inputs that vary over the landings, the most influential on
    /// stability first.
    pub influence: Vec<Influence>,
    /// How close the landings came to overturning and to each strut's capacity, with the
    /// closest landings as scenarios.
    pub margins: Margins,
}

/// Pearson's correlation of `x` and `y`; `None` where it is not defined (either constant, or
/// fewer than two pairs).
pub fn correlation(x: &[f64], y: &[f64]) -> Option<f64> {
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for (a, b) in x.iter().zip(y) {
        sxy += (a - mx) * (b - my);
        sxx += (a - mx) * (a - mx);
        syy += (b - my) * (b - my);
    }
    (sxx > 0.0 && syy > 0.0).then(|| sxy / (sxx * syy).sqrt())
}

/// The correlation of each numeric applied value that varies over the landings with `indicator`
/// (one per landing), the strongest first (ties by name), those not defined (the indicator
/// constant) last; `column(i, visit)` calls `visit` with each cell of column
/// `i`, in landing order.
pub fn correlations<E>(
    columns: &[Column],
    indicator: &[f64],
    column: &mut impl FnMut(usize, &mut dyn FnMut(Cell)) -> Result<(), E>,
) -> Result<Vec<(String, Option<f64>)>, E> {
    let mut out = Vec::new();
    for (i, c) in columns.iter().enumerate() {
        if !(c.role() == Some(Role::Applied) && c.kind == Kind::Float) {
            continue;
        }
        let mut x: Vec<f64> = Vec::with_capacity(indicator.len());
        column(i, &mut |c| {
            x.push(match c {
                Cell::Float(x) => x,
                _ => 0.0,
            })
        })?;
        // An input the same on every landing says nothing of the outcome: left out.
        if x.iter().all(|v| *v == x[0]) {
            continue;
        }
        out.push((c.name.clone(), correlation(&x, indicator)));
    }
    let strength = |r: Option<f64>| r.map_or(-1.0, f64::abs);
    out.sort_by(|a, b| {
        strength(b.1)
            .total_cmp(&strength(a.1))
            .then_with(|| a.0.cmp(&b.0))
    });
    Ok(out)
}

/// The one-sided Clopper-Pearson lower bound on a probability from `k` successes in `n`
/// trials at confidence `confidence`: the p with P(X ≥ k | p) = 1 − confidence, the
/// (1 − confidence) quantile of Beta(k, n − k + 1); 0 when k = 0.
pub fn clopper_pearson_lower(k: u64, n: u64, confidence: f64) -> f64 {
    if k == 0 || n == 0 {
        return 0.0;
    }
    match Beta::new(k as f64, (n - k + 1) as f64) {
        Ok(b) => b.inverse_cdf(1.0 - confidence),
        Err(_) => 0.0,
    }
}

/// The two-sided exact (Clopper-Pearson) interval of a probability from `k` successes in `n`
/// trials at confidence `confidence`: each end the one-sided bound at (1 + confidence)/2, the
/// upper one that of the failures, [L(k, n), 1 − L(n − k, n)] with L
/// [`clopper_pearson_lower`] (that is [B(α/2; k, n − k + 1), B(1 − α/2; k + 1, n − k)], α = 1
/// − confidence, with 0 and 1 at k = 0 and k = n).
pub fn clopper_pearson_interval(k: u64, n: u64, confidence: f64) -> (f64, f64) {
    let one_sided = 0.5 + confidence / 2.0;
    (
        clopper_pearson_lower(k, n, one_sided),
        1.0 - clopper_pearson_lower(n.saturating_sub(k), n, one_sided),
    )
}

/// Landings that show reliability `reliability` at confidence `confidence` with no failure:
/// the least n with Rⁿ ≤ 1 − C.
pub fn zero_failure_landings(reliability: f64, confidence: f64) -> u64 {
    ((1.0 - confidence).ln() / reliability.ln()).ceil() as u64
}

/// The reliabilities the zero-failure table lists.
const RELIABILITIES: [f64; 4] = [0.9, 0.95, 0.99, 0.999];

impl Statistics {
    /// The statistics of `n` records with `columns` at confidence `confidence`, of the engine
    /// whose columns' names start with `prefix` ([`crate::record::prefix`]); `column(i, visit)`
    /// calls `visit` with each cell of column `i`, in landing order; `scenario_file(by,
    /// landing)` names the file a closest landing is written to. What is kept of the records
    /// is counts, one number a landing (stable or not) and one column of numbers at a time
    /// (its percentiles, margins and correlations): 16 bytes a landing.
    pub fn from_columns<E>(
        columns: &[Column],
        n: u64,
        confidence: f64,
        prefix: &str,
        column: &mut impl FnMut(usize, &mut dyn FnMut(Cell)) -> Result<(), E>,
        scenario_file: &dyn Fn(&str, u64) -> String,
    ) -> Result<Statistics, E> {
        let index = |name: &str| {
            let name = format!("{prefix}{name}");
            columns.iter().position(|c| c.name == name)
        };
        // Calls `each` with the text of column `name` of every landing ("" where it is missing
        // or the column is absent).
        let mut texts = |name: &str, each: &mut dyn FnMut(&str)| -> Result<(), E> {
            match index(name) {
                Some(i) => column(i, &mut |c| match c {
                    Cell::Text(s) => each(&s),
                    _ => each(""),
                }),
                None => {
                    (0..n).for_each(|_| each(""));
                    Ok(())
                }
            }
        };
        // The landings whose column `name` holds each of `names`; `each` also sees every text.
        let mut counts = |name: &str,
                          names: &[&'static str],
                          each: &mut dyn FnMut(&str)|
         -> Result<Vec<Count>, E> {
            let mut landings = vec![0; names.len()];
            texts(name, &mut |t| {
                if let Some(k) = names.iter().position(|s| *s == t) {
                    landings[k] += 1;
                }
                each(t);
            })?;
            Ok(names
                .iter()
                .zip(landings)
                .map(|(name, landings)| Count {
                    name: (*name).into(),
                    landings,
                })
                .collect())
        };
        let mut stable_indicator: Vec<f64> = Vec::with_capacity(n as usize);
        let outcomes = counts("outcome", &Status::ALL.map(Status::name), &mut |t| {
            stable_indicator.push(f64::from(u8::from(t == Status::Stable.name())))
        })?;
        let failures = counts("failure", &Failure::ALL.map(Failure::name), &mut |_| {})?;
        let mut struts = std::collections::BTreeMap::<String, u64>::new();
        texts("stroke_outs", &mut |t| {
            for s in t.split(',').filter(|s| !s.is_empty()) {
                *struts.entry(s.to_string()).or_default() += 1;
            }
        })?;
        let proportion = |k: u64| Proportion {
            landings: k,
            fraction: (n > 0).then(|| k as f64 / n as f64),
            lower_bound: (n > 0).then(|| clopper_pearson_lower(k, n, confidence)),
        };
        let landings_of = |counts: &[Count], name: &str| {
            counts
                .iter()
                .find(|c| c.name == name)
                .map_or(0, |c| c.landings)
        };
        let stable = landings_of(&outcomes, Status::Stable.name());
        let within = landings_of(&failures, Failure::None.name());
        let mut percentiles = Vec::new();
        let mut margins = Margins::default();
        for (i, c) in columns.iter().enumerate() {
            let Some(name) = c.name.strip_prefix(prefix) else {
                continue;
            };
            let Some(measure) = c.measure().filter(|m| m.has_percentiles()) else {
                continue;
            };
            let mut v: Vec<f64> = Vec::with_capacity(n as usize);
            // The landings of the least and of the largest value (the first of equals).
            let (mut landing, mut least, mut largest) =
                (0u64, (f64::INFINITY, 0), (f64::NEG_INFINITY, 0));
            column(i, &mut |c| {
                if let Cell::Float(x) = c {
                    v.push(x);
                    if x < least.0 {
                        least = (x, landing);
                    }
                    if x > largest.0 {
                        largest = (x, landing);
                    }
                }
                landing += 1;
            })?;
            if v.is_empty() {
                continue;
            }
            // Unstable: values equal under total_cmp have the same bits, so the order is the same, and
            // it sorts in place.
            v.sort_unstable_by(f64::total_cmp);
            if measure == Measure::MinStabilityDistance {
                margins.stability_distance = Some(Margin {
                    margin: name.to_string(),
                    landings: v.len() as u64,
                    min: v[0],
                    p1: percentile(&v, 0.01),
                    p10: percentile(&v, 0.1),
                    p50: percentile(&v, 0.5),
                    landing: least.1,
                });
            }
            if let (Measure::StrokeOfCapacity, Some(strut)) = (measure, strut_of(name)) {
                // The margin 1 − x falls as x rises: its lower percentiles are the upper ones of x.
                margins.strokes.push(Margin {
                    margin: format!("{strut}stroke_margin"),
                    landings: v.len() as u64,
                    min: 1.0 - v[v.len() - 1],
                    p1: 1.0 - percentile(&v, 0.99),
                    p10: 1.0 - percentile(&v, 0.9),
                    p50: 1.0 - percentile(&v, 0.5),
                    landing: largest.1,
                });
            }
            percentiles.push(Percentiles {
                column: c.name.clone(),
                landings: v.len() as u64,
                p50: percentile(&v, 0.5),
                p90: percentile(&v, 0.9),
                p99: percentile(&v, 0.99),
                max: v[v.len() - 1],
            });
        }
        margins.strokes.sort_by(|a, b| {
            a.min
                .total_cmp(&b.min)
                .then_with(|| a.margin.cmp(&b.margin))
        });
        margins.closest = closest(columns, &margins, column, scenario_file)?;
        let influence = correlations(columns, &stable_indicator, column)?
            .into_iter()
            .map(|(column, correlation_with_stable)| Influence {
                column,
                correlation_with_stable,
            })
            .collect();
        Ok(Statistics {
            landings: n,
            confidence,
            outcomes,
            failures,
            stroke_outs: struts
                .into_iter()
                .map(|(name, landings)| Count { name, landings })
                .collect(),
            stable: proportion(stable),
            stable_within_capacity: proportion(within),
            zero_failure: RELIABILITIES
                .iter()
                .map(|r| ZeroFailure {
                    reliability: *r,
                    landings: zero_failure_landings(*r, confidence),
                })
                .collect(),
            percentiles,
            influence,
            margins,
        })
    }
}

/// The landings closest to failing by the stability distance and by the least stroke margin of
/// any strut (`margins.strokes` sorted, the least first), with the values applied to them.
fn closest<E>(
    columns: &[Column],
    margins: &Margins,
    column: &mut impl FnMut(usize, &mut dyn FnMut(Cell)) -> Result<(), E>,
    scenario_file: &dyn Fn(&str, u64) -> String,
) -> Result<Vec<ClosestLanding>, E> {
    let mut out: Vec<ClosestLanding> = [
        ("stability_distance", margins.stability_distance.as_ref()),
        ("stroke", margins.strokes.first()),
    ]
    .into_iter()
    .filter_map(|(by, m)| {
        m.map(|m| ClosestLanding {
            by: by.to_string(),
            margin: m.margin.clone(),
            value: m.min,
            landing: m.landing,
            applied: serde_json::Map::new(),
            scenario_file: scenario_file(by, m.landing),
        })
    })
    .collect();
    read_applied(
        columns,
        out.iter_mut().map(|c| (c.landing, &mut c.applied)),
        column,
    )?;
    Ok(out)
}

/// Fills each target's map with the values applied to its landing (the `landing`-th record),
/// by column: one pass over each `applied.*` column for all of them.
pub(crate) fn read_applied<'a, E>(
    columns: &[Column],
    targets: impl IntoIterator<Item = (u64, &'a mut serde_json::Map<String, serde_json::Value>)>,
    column: &mut impl FnMut(usize, &mut dyn FnMut(Cell)) -> Result<(), E>,
) -> Result<(), E> {
    let mut targets: Vec<_> = targets.into_iter().collect();
    if targets.is_empty() {
        return Ok(());
    }
    for (i, c) in columns.iter().enumerate() {
        if c.role() != Some(Role::Applied) {
            continue;
        }
        let mut landing = 0;
        column(i, &mut |cell| {
            for (_, applied) in targets.iter_mut().filter(|(l, _)| *l == landing) {
                let value = match &cell {
                    Cell::Float(x) => serde_json::json!(x),
                    Cell::Integer(x) => serde_json::json!(x),
                    Cell::Text(s) => serde_json::json!(s),
                    Cell::Flag(b) => serde_json::json!(b),
                    Cell::Missing => serde_json::Value::Null,
                };
                applied.insert(c.name.clone(), value);
            }
            landing += 1;
        })?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// P(X ≥ k) for X ~ Binomial(n, p), summed term by term.
    fn upper_tail(k: u64, n: u64, p: f64) -> f64 {
        let mut term = (1.0 - p).powi(n as i32); // P(X = 0)
        let mut sum = if k == 0 { term } else { 0.0 };
        for j in 1..=n {
            term *= (n - j + 1) as f64 / j as f64 * p / (1.0 - p);
            if j >= k {
                sum += term;
            }
        }
        sum
    }

    /// The bound against its definition, computed independently of the beta function: the p at
    /// which P(X ≥ k | p) = 1 − C, by bisection on the exact binomial tail; and the closed forms
    /// of k = n, (1 − C)^(1/n), and of k = 1, 1 − C^(1/n).
    #[test]
    fn clopper_pearson_is_the_exact_binomial_bound() {
        for (k, n, c) in [
            (8u64, 10u64, 0.95),
            (95, 100, 0.95),
            (1, 20, 0.9),
            (17, 24, 0.9),
            (50, 60, 0.99),
        ] {
            let (mut lo, mut hi) = (0.0f64, 1.0f64);
            for _ in 0..100 {
                let mid = 0.5 * (lo + hi);
                if upper_tail(k, n, mid) < 1.0 - c {
                    lo = mid
                } else {
                    hi = mid
                }
            }
            let got = clopper_pearson_lower(k, n, c);
            assert!(
                (got - lo).abs() < 1e-9,
                "k {k} n {n} C {c}: {got} against {lo}"
            );
        }
        for (n, c) in [(299u64, 0.95), (10, 0.9), (2995, 0.95)] {
            let exact = (1.0f64 - c).powf(1.0 / n as f64);
            assert!((clopper_pearson_lower(n, n, c) - exact).abs() < 1e-9);
        }
        assert!(
            (clopper_pearson_lower(1, 20, 0.9) - (1.0 - 0.9f64.powf(1.0 / 20.0))).abs() < 1e-12
        );
        assert_eq!(clopper_pearson_lower(0, 50, 0.95), 0.0);
    }

    #[test]
    fn the_exact_interval_has_its_textbook_ends() {
        // k = 0: upper end 1 − (α/2)^(1/n); k = n: lower end (α/2)^(1/n).
        let (lo, hi) = clopper_pearson_interval(0, 30, 0.95);
        assert_eq!(lo, 0.0);
        assert!((hi - (1.0 - 0.025f64.powf(1.0 / 30.0))).abs() < 1e-9);
        let (lo, hi) = clopper_pearson_interval(30, 30, 0.95);
        assert!((lo - 0.025f64.powf(1.0 / 30.0)).abs() < 1e-9);
        assert_eq!(hi, 1.0);
        // 5 of 20 at 95 %: the published interval 0.0866 to 0.4910.
        let (lo, hi) = clopper_pearson_interval(5, 20, 0.95);
        assert!(
            (lo - 0.0866).abs() < 5e-4 && (hi - 0.4910).abs() < 5e-4,
            "{lo} {hi}"
        );
    }

    #[test]
    fn the_zero_failure_rule_gives_the_textbook_sizes() {
        assert_eq!(zero_failure_landings(0.99, 0.95), 299);
        assert_eq!(zero_failure_landings(0.999, 0.95), 2995);
        assert_eq!(zero_failure_landings(0.9, 0.9), 22);
    }

    /// The margins' lower tails are those of the columns they come from (a stroke margin's the
    /// upper tail of its fraction of capacity, turned over), each names the landing of its
    /// least, and the closest landings carry their applied values and files.
    #[test]
    fn margins_are_the_lower_tails_with_their_landings() {
        let col = |name: &str, kind| Column {
            name: name.into(),
            kind,
        };
        let columns = [
            col("landing", Kind::Integer),
            col("applied.v_m_s", Kind::Float),
            col("outcome", Kind::Text),
            col("leg1.primary.stroke_of_capacity", Kind::Float),
            col("leg2.primary.stroke_of_capacity", Kind::Float),
            col("min_stability_distance_m", Kind::Float),
        ];
        let v = [1.0, 2.0, 3.0, 4.0, 5.0];
        let leg1 = [0.5, 0.9, 0.2, 0.9, 0.1];
        let leg2 = [0.3, 0.3, 0.3, 0.3, 0.3];
        let sd = [0.4, 0.1, 0.3, 0.05, 0.2];
        let mut read = |i: usize, visit: &mut dyn FnMut(Cell)| {
            for k in 0..5 {
                visit(match i {
                    0 => Cell::Integer(k as i64),
                    1 => Cell::Float(v[k]),
                    2 => Cell::Text("stable".into()),
                    3 => Cell::Float(leg1[k]),
                    4 => Cell::Float(leg2[k]),
                    _ => Cell::Float(sd[k]),
                });
            }
            Ok::<_, ()>(())
        };
        let s = Statistics::from_columns(&columns, 5, 0.95, "", &mut read, &|by, l| {
            format!("closest/{by}-{l}.toml")
        })
        .unwrap();
        let m = &s.margins;
        let d = m.stability_distance.as_ref().unwrap();
        assert_eq!((d.min, d.landing, d.landings), (0.05, 3, 5));
        assert!((d.p50 - 0.2).abs() < 1e-15 && (d.p10 - 0.07).abs() < 1e-12);
        // leg 1 reaches 0.9 of its capacity first on landing 1: margin 0.1 there.
        let names: Vec<&str> = m.strokes.iter().map(|x| x.margin.as_str()).collect();
        assert_eq!(
            names,
            ["leg1.primary.stroke_margin", "leg2.primary.stroke_margin"]
        );
        assert!((m.strokes[0].min - 0.1).abs() < 1e-15 && m.strokes[0].landing == 1);
        assert!((m.strokes[0].p50 - 0.5).abs() < 1e-15);
        assert_eq!(m.closest.len(), 2);
        assert_eq!(
            (m.closest[0].by.as_str(), m.closest[0].landing),
            ("stability_distance", 3)
        );
        assert_eq!(
            m.closest[0].applied["applied.v_m_s"],
            serde_json::json!(4.0)
        );
        assert_eq!(m.closest[1].scenario_file, "closest/stroke-1.toml");
        assert_eq!(
            m.closest[1].applied["applied.v_m_s"],
            serde_json::json!(2.0)
        );
    }

    #[test]
    fn correlation_is_pearsons() {
        assert!((correlation(&[1.0, 2.0, 3.0], &[2.0, 4.0, 6.0]).unwrap() - 1.0).abs() < 1e-12);
        assert!(
            (correlation(&[1.0, 2.0, 3.0], &[1.0, 0.0, 0.0]).unwrap() + 0.8660254037844387).abs()
                < 1e-12
        );
        assert_eq!(correlation(&[1.0, 1.0], &[0.0, 1.0]), None);
        assert_eq!(correlation(&[], &[]), None);
    }
}
