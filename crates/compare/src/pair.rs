//! Two engines' runs of a landing compared, each with its rounding ensemble
//! ([`crate::rounding`]): every channel of [`crate::metrics`] judged over every pair of members,
//! and the pair's verdict.

use crate::metrics::{channels, Channel, PairComparison, Verdict};
use crate::rounding::{own_spreads, Spread};
use crate::EngineRun;

/// Compares two engines' runs of the same landing, each with its rounding ensemble
/// ([`EngineRun::perturbed`]): a channel's verdict holds over every pair of members.
pub fn compare(a: &EngineRun, b: &EngineRun) -> PairComparison {
    let mut channels = channels(a, b);
    let own = [own_spreads(a), own_spreads(b)];
    let mut spreads: Vec<Spread> = channels
        .iter()
        .map(|c| Spread::of(c, [&own[0], &own[1]]))
        .collect();
    for (i, x) in a.members().iter().enumerate() {
        for (j, y) in b.members().iter().enumerate() {
            if i + j > 0 {
                let set = self::channels(x, y);
                for (c, s) in channels.iter().zip(&mut spreads) {
                    s.between(set.iter().find(|d| d.key() == c.key()));
                }
            }
        }
    }
    for (c, s) in channels.iter_mut().zip(&spreads) {
        c.ensemble_difference = s.between;
        [c.a_range, c.b_range] = s.values;
        c.rounding_spread = s.within;
        c.verdict = s.verdict(c.tolerance);
    }
    let (sa, sb) = (&a.summary, &b.summary);
    let outcome_agrees = sa.outcome == sb.outcome;
    let outcome_determined = a.outcome_determined() && b.outcome_determined();
    let worst_channel = if outcome_agrees {
        channels
            .iter()
            .enumerate()
            .max_by(|(_, x), (_, y)| {
                let failing = |c: &Channel| c.verdict == Verdict::Fail;
                (failing(x).cmp(&failing(y)))
                    .then((x.difference / x.tolerance).total_cmp(&(y.difference / y.tolerance)))
            })
            .map(|(i, _)| i)
    } else {
        None
    };
    let verdicts = channels.iter().map(|c| c.verdict);
    let verdict = if (outcome_determined && !outcome_agrees)
        || verdicts.clone().any(|v| v == Verdict::Fail)
    {
        Verdict::Fail
    } else if !outcome_determined || verdicts.clone().any(|v| v == Verdict::NotDetermined) {
        Verdict::NotDetermined
    } else {
        Verdict::Pass
    };
    PairComparison {
        a: a.engine,
        b: b.engine,
        outcome_a: sa.outcome,
        outcome_b: sb.outcome,
        outcome_agrees,
        outcome_determined,
        channels,
        worst_channel,
        verdict,
    }
}
