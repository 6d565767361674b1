//! The statistics of a paired campaign (docs/campaigns.md, "Paired campaigns"): every landing's
//! draws landed on several engines, each engine's statistics, and between each pair of engines
//! what a reviewer needs: how often their outcomes disagree (with its exact binomial interval),
//! McNemar's exact test of the difference in P(stable), the paired differences of every strut's
//! maximum stroke and of the minimum stability distance, which inputs go with disagreement, and
//! the landings that disagree most.

use crate::record::{Cell, Column, Measure, Status};
use crate::statistics::{correlations, Interval, Statistics};
use serde::Serialize;
use statrs::distribution::{Binomial, DiscreteCDF};
use touchdown_sampling::percentile;

/// How many of the landings that disagree most each pair lists.
pub const WORST: usize = 10;

/// A campaign's statistics: of its one engine, or of each engine of a paired campaign and of
/// each pair.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Report {
    /// A campaign on one engine.
    One(Box<Statistics>),
    /// A paired campaign.
    Paired(Paired),
}

impl Report {
    /// The statistics of the first engine (the only one of a campaign on one engine).
    pub fn first(&self) -> &Statistics {
        match self {
            Report::One(s) => s,
            Report::Paired(p) => &p.engines[0].statistics,
        }
    }
}

/// The statistics of a paired campaign.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Paired {
    /// Landings (each landed on every engine).
    pub landings: u64,
    /// Confidence of the bounds and intervals, in (0, 1).
    pub confidence: f64,
    /// Each engine's statistics, in the campaign's order.
    pub engines: Vec<EngineStatistics>,
    /// Each pair of engines, in the campaign's order (first with second, first with third, ...).
    pub pairs: Vec<Pair>,
}

/// One engine's statistics in a paired campaign (its percentiles name its own columns).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EngineStatistics {
    /// The engine.
    pub engine: String,
    /// Its statistics.
    #[serde(flatten)]
    pub statistics: Statistics,
}

/// What two engines' landings of the same draws say of each other.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Pair {
    /// The two engines, A then B.
    pub engines: [String; 2],
    /// Landings whose outcomes differ (`stable` against `unstable`, a run stopped on one
    /// engine only, ...).
    pub disagreement: Interval,
    /// Landings stable on A and not on B.
    pub stable_on_a_only: u64,
    /// Landings stable on B and not on A.
    pub stable_on_b_only: u64,
    /// McNemar's exact two-sided p-value of P(stable) being the same on both engines: the
    /// probability, with each discordant landing equally likely to be stable on either, of a
    /// split at least as uneven as the one seen (1 with no discordant landing).
    pub mcnemar_p_value: f64,
    /// Percentiles of the differences B − A of each strut's maximum stroke and of the minimum
    /// stability distance, over the landings both engines measured.
    pub differences: Vec<Difference>,
    /// Each numeric input's correlation with disagreement (the indicator of differing
    /// outcomes), the strongest first.
    pub influence: Vec<DisagreementInfluence>,
    /// The landings that disagree most: those whose outcomes differ first, then the largest
    /// difference of a strut's maximum stroke ([`WORST`] at most).
    pub worst: Vec<Disagreement>,
}

/// Percentiles of a paired difference B − A.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Difference {
    /// The measurement (its column's name without the engine, its unit in its name).
    pub column: String,
    /// Landings both engines measured.
    pub landings: u64,
    /// 5th percentile.
    pub p05: f64,
    /// Median.
    pub p50: f64,
    /// 95th percentile.
    pub p95: f64,
    /// Largest |B − A|.
    pub max_abs: f64,
}

/// How strongly an input goes with the engines disagreeing.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DisagreementInfluence {
    /// The applied value's column.
    pub column: String,
    /// Its correlation with disagreement (point-biserial), in [−1, 1]; absent when it is not
    /// defined (the agreement the same on every landing; an input the same on every landing is
    /// not listed).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub correlation_with_disagreement: Option<f64>,
}

/// A landing on which two engines disagree.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Disagreement {
    /// The landing.
    pub landing: u64,
    /// Its outcome on A and on B.
    pub outcomes: [String; 2],
    /// The largest |B − A| of a strut's maximum stroke, m (0 when neither measured one).
    pub largest_stroke_difference_m: f64,
    /// That strut's column (without the engine), empty when none.
    pub strut: String,
    /// The values applied, by column.
    pub applied: serde_json::Map<String, serde_json::Value>,
    /// The landing as a standalone scenario file in the campaign's folder.
    pub scenario_file: String,
}

/// McNemar's exact two-sided p-value from the discordant counts `b` and `c`:
/// min(1, 2·P(X ≤ min(b, c))) for X ~ Binomial(b + c, ½); 1 when b + c = 0.
pub fn mcnemar_exact(b: u64, c: u64) -> f64 {
    let m = b + c;
    match Binomial::new(0.5, m) {
        Ok(x) if m > 0 => (2.0 * x.cdf(b.min(c))).min(1.0),
        _ => 1.0,
    }
}

/// The statistics of the pair of engines whose columns start with `prefixes` (A, B) among
/// `columns` of `n` landings, `column(i, visit)` calling `visit` with each cell of column `i`
/// in landing order (what is kept: two columns of numbers at a time and a few numbers a
/// landing, about 50 bytes a landing); `scenario_file(landing)` names where a listed landing's
/// scenario is written.
pub fn pair<E>(
    columns: &[Column],
    n: u64,
    confidence: f64,
    engines: [&str; 2],
    prefixes: [&str; 2],
    column: &mut impl FnMut(usize, &mut dyn FnMut(Cell)) -> Result<(), E>,
    scenario_file: &dyn Fn(u64) -> String,
) -> Result<Pair, E> {
    let index = |prefix: &str, name: &str| {
        let name = format!("{prefix}{name}");
        columns.iter().position(|c| c.name == name)
    };
    // Each landing's outcome on each engine, as its place in `Status::ALL` (`NONE`: no outcome).
    const NONE: u8 = u8::MAX;
    let name = |code: u8| Status::ALL.get(usize::from(code)).map_or("", |s| s.name());
    let mut outcomes = [Vec::new(), Vec::new()];
    for (o, prefix) in outcomes.iter_mut().zip(prefixes) {
        match index(prefix, "outcome") {
            Some(i) => column(i, &mut |c| {
                o.push(match c {
                    Cell::Text(t) => Status::ALL
                        .iter()
                        .position(|s| s.name() == t)
                        .map_or(NONE, |k| k as u8),
                    _ => NONE,
                })
            })?,
            None => *o = vec![NONE; n as usize],
        }
    }
    let stable = |code: u8| name(code) == Status::Stable.name();
    let (mut a_only, mut b_only) = (0, 0);
    let disagree: Vec<bool> = (0..n as usize)
        .map(|i| {
            let (a, b) = (outcomes[0][i], outcomes[1][i]);
            match (stable(a), stable(b)) {
                (true, false) => a_only += 1,
                (false, true) => b_only += 1,
                _ => {}
            }
            a != b
        })
        .collect();
    let k = disagree.iter().filter(|d| **d).count() as u64;
    // Each landing's largest stroke difference and its strut, for the worst landings.
    let mut largest = vec![(0.0f64, usize::MAX); n as usize];
    let mut differences = Vec::new();
    for (i, c) in columns.iter().enumerate() {
        let Some(name) = c.name.strip_prefix(prefixes[0]) else {
            continue;
        };
        let Some(measure) = c.measure().filter(|m| m.paired()) else {
            continue;
        };
        let Some(j) = index(prefixes[1], name) else {
            continue;
        };
        let mut a: Vec<Option<f64>> = Vec::with_capacity(n as usize);
        column(i, &mut |c| {
            a.push(match c {
                Cell::Float(x) => Some(x),
                _ => None,
            })
        })?;
        let mut d: Vec<f64> = Vec::with_capacity(n as usize);
        let mut landing = 0;
        column(j, &mut |b| {
            if let (Some(Some(a)), Cell::Float(b)) = (a.get(landing), b) {
                d.push(b - a);
                let slot = &mut largest[landing];
                if measure == Measure::Stroke && (b - a).abs() > slot.0 {
                    *slot = ((b - a).abs(), i);
                }
            }
            landing += 1;
        })?;
        if d.is_empty() {
            continue;
        }
        let max_abs = d.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        d.sort_unstable_by(f64::total_cmp); // in place; equal values have equal bits
        differences.push(Difference {
            column: name.to_string(),
            landings: d.len() as u64,
            p05: percentile(&d, 0.05),
            p50: percentile(&d, 0.5),
            p95: percentile(&d, 0.95),
            max_abs,
        });
    }
    let indicator: Vec<f64> = disagree.iter().map(|d| f64::from(u8::from(*d))).collect();
    let influence = correlations(columns, &indicator, column)?
        .into_iter()
        .map(
            |(column, correlation_with_disagreement)| DisagreementInfluence {
                column,
                correlation_with_disagreement,
            },
        )
        .collect();
    // The worst: differing outcomes first, then the largest stroke difference, then in order.
    let mut order: Vec<usize> = (0..n as usize)
        .filter(|i| disagree[*i] || largest[*i].0 > 0.0)
        .collect();
    order.sort_by(|x, y| {
        (disagree[*y].cmp(&disagree[*x]))
            .then_with(|| largest[*y].0.total_cmp(&largest[*x].0))
            .then_with(|| x.cmp(y))
    });
    order.truncate(WORST);
    let mut worst: Vec<Disagreement> = order
        .iter()
        .map(|&i| Disagreement {
            landing: i as u64,
            outcomes: [name(outcomes[0][i]).into(), name(outcomes[1][i]).into()],
            largest_stroke_difference_m: largest[i].0,
            strut: columns
                .get(largest[i].1)
                .and_then(|c| c.name.strip_prefix(prefixes[0]))
                .unwrap_or_default()
                .to_string(),
            applied: serde_json::Map::new(),
            scenario_file: scenario_file(i as u64),
        })
        .collect();
    crate::statistics::read_applied(
        columns,
        worst.iter_mut().map(|w| (w.landing, &mut w.applied)),
        column,
    )?;
    Ok(Pair {
        engines: engines.map(str::to_string),
        disagreement: Interval::of(k, n, confidence),
        stable_on_a_only: a_only,
        stable_on_b_only: b_only,
        mcnemar_p_value: mcnemar_exact(a_only, b_only),
        differences,
        influence,
        worst,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::record::Kind;

    /// C(n, i)/2ⁿ summed term by term.
    fn binomial_half_cdf(k: u64, n: u64) -> f64 {
        let mut term = 0.5f64.powi(n as i32);
        let mut sum = term;
        for i in 1..=k {
            term *= (n - i + 1) as f64 / i as f64;
            sum += term;
        }
        sum
    }

    #[test]
    fn mcnemar_is_the_exact_sign_test_of_the_discordant_landings() {
        // 2 against 9: 2·P(X ≤ 2), X ~ B(11, ½) = 2·67/2048.
        assert!((mcnemar_exact(2, 9) - 2.0 * 67.0 / 2048.0).abs() < 1e-12);
        assert!((mcnemar_exact(9, 2) - mcnemar_exact(2, 9)).abs() < 1e-15);
        for (b, c) in [(0u64, 7u64), (3, 3), (10, 25), (40, 31)] {
            let exact = (2.0 * binomial_half_cdf(b.min(c), b + c)).min(1.0);
            assert!((mcnemar_exact(b, c) - exact).abs() < 1e-9, "{b} {c}");
        }
        assert_eq!(mcnemar_exact(0, 0), 1.0);
        assert_eq!(mcnemar_exact(5, 5), 1.0);
    }

    fn col(name: &str, kind: Kind) -> Column {
        Column {
            name: name.into(),
            kind,
        }
    }

    #[test]
    fn a_pair_counts_its_disagreements_and_lists_the_worst_first() {
        let columns = vec![
            col("landing", Kind::Integer),
            col("applied.v_m_s", Kind::Float),
            col("core.outcome", Kind::Text),
            col("core.leg1.primary.stroke_m", Kind::Float),
            col("rapier.outcome", Kind::Text),
            col("rapier.leg1.primary.stroke_m", Kind::Float),
        ];
        let t = |s: &str| Cell::Text(s.into());
        let cells: Vec<Vec<Cell>> = vec![
            (0..4).map(Cell::Integer).collect(),
            [1.0, 2.0, 3.0, 4.0].map(Cell::Float).to_vec(),
            vec![t("stable"), t("stable"), t("unstable"), t("stable")],
            [0.10, 0.20, 0.30, 0.40].map(Cell::Float).to_vec(),
            vec![t("stable"), t("unstable"), t("unstable"), t("stable")],
            vec![
                Cell::Float(0.10),
                Cell::Float(0.25),
                Cell::Missing,
                Cell::Float(0.50),
            ],
        ];
        let p = pair(
            &columns,
            4,
            0.95,
            ["core", "rapier"],
            ["core.", "rapier."],
            &mut |i, visit: &mut dyn FnMut(Cell)| {
                cells[i].iter().cloned().for_each(visit);
                Ok::<_, ()>(())
            },
            &|l| format!("disagreements/landing-{l}.toml"),
        )
        .unwrap();
        assert_eq!(p.disagreement.landings, 1);
        assert_eq!((p.stable_on_a_only, p.stable_on_b_only), (1, 0));
        assert!((p.mcnemar_p_value - 1.0).abs() < 1e-12);
        let d = &p.differences[0];
        assert_eq!(
            (d.column.as_str(), d.landings),
            ("leg1.primary.stroke_m", 3)
        );
        assert!((d.max_abs - 0.10).abs() < 1e-12);
        // Landing 1 disagrees on its outcome; then landing 3 (0.10 m) before landing 0 (0 m,
        // not listed).
        let listed: Vec<u64> = p.worst.iter().map(|w| w.landing).collect();
        assert_eq!(listed, [1, 3]);
        assert_eq!(
            p.worst[0].outcomes,
            ["stable".to_string(), "unstable".into()]
        );
        assert_eq!(p.worst[0].strut, "leg1.primary.stroke_m");
        assert_eq!(p.worst[0].applied["applied.v_m_s"], serde_json::json!(2.0));
        assert_eq!(p.worst[1].scenario_file, "disagreements/landing-3.toml");
        assert!(p.influence[0].correlation_with_disagreement.unwrap().abs() > 0.0);
    }
}
