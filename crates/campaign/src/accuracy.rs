//! The accuracy a campaign's integrator settings give, measured and stated (docs/campaigns.md,
//! "Accuracy"): the first landings of the campaign landed again on each of its engines with
//! its settings and with its step refined: on the core every step limit [`REFINEMENT`]/2 and
//! [`REFINEMENT`] times (`touchdown_scenario::schema::Integrator::refine`), on a multibody
//! engine its fixed step [`MULTIBODY_REFINEMENT`]/2 and [`MULTIBODY_REFINEMENT`] times
//! (`touchdown_registry::refined`); their outcomes and maxima compared: the settings' error
//! against the finest, and the finest two against each other (how far the reference itself is
//! from converged). The manifest of the whole campaign (and of the part that holds landing 0)
//! carries the result.
//!
//! It measures the error of the steps, not of the model: both runs are of the same laws.

use crate::distribution::Value;
use crate::landing::{draws, outcome, pool, scenario};
use crate::record::Status;
use crate::spec::Campaign;
use crate::statistics::clopper_pearson_lower;
use crate::CampaignError;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use touchdown_record::{Outcome, RunError, Summary};
use touchdown_registry::Engine;
use touchdown_scenario::{Scenario, ScenarioError};

/// How many times finer the core's reference runs' step limits are than the campaign's.
pub const REFINEMENT: f64 = touchdown_scenario::schema::ACCURACY_REFINEMENT;

/// How many times finer a multibody engine's reference runs' step is than the campaign's. Less
/// than the core's: a multibody landing costs seconds at its own step (rapier about 5 s of a
/// core for the 1/6-scale model's 1.5 s, docs/performance.md), and its sample lands each
/// landing 1 + 2 + 4 times the steps again, about 7 % more on a paired campaign of 1,000.
pub const MULTIBODY_REFINEMENT: f64 = 4.0;

/// How many times finer `engine`'s reference runs' step is than the campaign's.
pub fn refinement(engine: Engine) -> f64 {
    match engine {
        Engine::Core => REFINEMENT,
        Engine::Rapier | Engine::Mujoco => MULTIBODY_REFINEMENT,
    }
}

/// A campaign's landings per landing of its accuracy sample.
pub const LANDINGS_PER_SAMPLE: u64 = 100;

/// The most landings an accuracy sample holds.
pub const MAX_SAMPLE: u64 = 20;

/// The landings whose accuracy a campaign of `landings` measures unless its file says how
/// many (`[accuracy] landings`, [`sample`]): landings `0..n`, one in
/// [`LANDINGS_PER_SAMPLE`] rounded up, at least one and at most [`MAX_SAMPLE`]. Each is landed
/// three times more: at the campaign's settings, with its step limits [`REFINEMENT`]/2 and
/// [`REFINEMENT`] times finer (about 1 + 4 + 8 times the steps): about 13 % more work on 1,000
/// landings, 2.6 % on 10,000, 0.3 % on 100,000, and 54 % on 24.
pub fn sample_size(landings: u64) -> u64 {
    landings
        .div_ceil(LANDINGS_PER_SAMPLE)
        .clamp(1, MAX_SAMPLE)
        .min(landings)
}

/// The landings of `campaign`'s accuracy sample when it has `landings` in all: the file's
/// `[accuracy] landings` (at most `landings`), or [`sample_size`]. Its landings are draws of
/// the campaign's distributions like any other, so that what the sample shows of them bounds
/// the whole campaign ([`OutcomeBound`]).
pub fn sample(campaign: &Campaign, landings: u64) -> u64 {
    campaign
        .accuracy_landings
        .map_or_else(|| sample_size(landings), |n| n.min(landings))
}

/// An upper confidence bound on the fraction of a campaign's landings whose outcome its
/// settings decide otherwise than the refined runs would: the one-sided Clopper-Pearson bound
/// from the landings of the sample that differ among those measured. The sample's landings are
/// independent draws of the campaign's distributions, so the bound is on the campaign's
/// landings, not on the sample's (but for a `list` dispersion, a sequence rather than a draw,
/// of which the sample holds the first values). Twenty landings that all agree bound it by
/// 13.9 % at 95 % confidence: a sample says "identical" of a fraction it cannot resolve
/// (docs/campaigns.md, "Accuracy").
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct OutcomeBound {
    /// The bound, a fraction (dimensionless).
    pub fraction: f64,
    /// Its one-sided confidence, the campaign's (dimensionless, in (0, 1)).
    pub confidence: f64,
}

impl OutcomeBound {
    /// The bound from `differ` of `measured` landings at `confidence`: 1 when none was
    /// measured.
    pub fn new(differ: u64, measured: u64, confidence: f64) -> OutcomeBound {
        let agree = measured.saturating_sub(differ);
        OutcomeBound {
            fraction: 1.0 - clopper_pearson_lower(agree, measured, confidence),
            confidence,
        }
    }
}

/// The largest of one error over the sample and the landing it was found on.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Worst {
    /// The error, a fraction (dimensionless).
    pub fraction: f64,
    /// The landing.
    pub landing: u64,
}

/// The errors of the maxima over the landings both runs completed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Maxima {
    /// The landing's largest primary stroke against the refined run's:
    /// |max − max_ref| / max_ref.
    pub largest_primary_stroke: Worst,
    /// Every maximum stroke (each strut's primary, secondary compression and tension) against
    /// the refined run's, as a fraction of that strut's capacity.
    pub stroke_of_capacity: Worst,
    /// The pitch rate's extreme in each sense against the refined run's (the larger of the
    /// two differences: a rocking landing's two swings, not the signed peak, which jumps from
    /// one swing to the other as they change places), as a fraction of the largest peak pitch
    /// rate of the refined runs of the sample.
    pub peak_pitch_rate_of_largest: Worst,
}

/// The errors of the maxima over a set of landings: of the campaign's settings, and of the
/// runs half as refined, each against the refined runs.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Comparison {
    /// The campaign's settings against the refined runs: their error.
    pub settings: Maxima,
    /// The runs [`REFINEMENT`]/2 times finer against the refined runs: how far the reference is
    /// from converged. A channel whose error here is about its error in `settings` is decided by
    /// the landing's sensitivity (a late rocking, an overturn), not by the step.
    pub reference: Maxima,
}

/// The accuracy of a campaign's settings on one engine, on its first landings
/// ([`sample_size`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Accuracy {
    /// The engine measured.
    pub engine: String,
    /// The landings measured: `0..sample_landings`.
    pub sample_landings: u64,
    /// How many times finer the reference runs' step limits are ([`refinement`]).
    pub refinement: f64,
    /// Landings whose outcome (stable, unstable, undecided, stopped, refused) is the refined
    /// run's.
    pub outcomes_identical: u64,
    /// The landings not measured: their settings refined leave their ranges (a `max_steps` or
    /// `rtol` near its bound; docs/scenario-format.md, "Ranges").
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub not_refined: Vec<u64>,
    /// The landings whose outcome differs from the refined run's.
    pub outcomes_differ: Vec<u64>,
    /// The landings whose outcome differs between the refined runs and those half as refined.
    pub reference_outcomes_differ: Vec<u64>,
    /// What `outcomes_differ` bounds of the whole campaign: the fraction of its landings whose
    /// outcome its settings decide otherwise than the refined runs, at most, at the campaign's
    /// confidence. Absent from manifests written before it was stated.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub outcomes_differ_bound: Option<OutcomeBound>,
    /// Landings the three runs completed, whose maxima are compared.
    pub compared: u64,
    /// The largest errors of the maxima over them; absent when there are none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub maxima: Option<Comparison>,
    /// Landings the three runs found stable: the landings whose maxima a design reads (an
    /// overturn's are up to its crossing, where the runs part).
    pub stable: u64,
    /// The largest errors of the maxima over them; absent when there are none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stable_maxima: Option<Comparison>,
}

/// One landing of the sample at the campaign's settings, half refined and refined.
struct Runs {
    landing: u64,
    run: Result<Summary, RunError>,
    half: Result<Summary, RunError>,
    refined: Result<Summary, RunError>,
}

/// The accuracy of a campaign's settings on each of its engines: the core's and each multibody
/// engine's, in the campaign's order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Measured {
    /// The core's, `None` when the campaign does not land on it.
    pub core: Option<Accuracy>,
    /// Each multibody engine's.
    pub multibody: Vec<Accuracy>,
}

/// The accuracy of `campaign`'s settings on each of its engines, on the first [`sample`]
/// landings of the campaign planned with `landings` in all, landed on `threads` threads (all
/// the machine's with `None`). An engine that cannot be set up is an error, as in the
/// campaign.
pub fn measure(
    campaign: &Campaign,
    landings: u64,
    threads: Option<usize>,
) -> Result<Measured, CampaignError> {
    let n = sample(campaign, landings);
    let pool = pool(threads)?;
    let mut measured = Measured::default();
    for &engine in &campaign.engines {
        let runs: Vec<Option<Runs>> = pool.install(|| {
            (0..n)
                .into_par_iter()
                .map(|i| land_runs(campaign, engine, i, &draws(campaign, i)))
                .collect::<Result<_, _>>()
        })?;
        let not_refined = (0..n).filter(|i| runs[*i as usize].is_none()).collect();
        let runs: Vec<Runs> = runs.into_iter().flatten().collect();
        let accuracy = compare(&runs, n, not_refined, campaign.confidence, engine);
        match engine {
            Engine::Core => measured.core = Some(accuracy),
            Engine::Rapier | Engine::Mujoco => measured.multibody.push(accuracy),
        }
    }
    Ok(measured)
}

/// Landing `landing` (its draws `drawn`) on `engine` at the campaign's settings, half refined
/// and refined ([`refinement`]); `Ok(None)` when its settings refined leave their ranges (a
/// `max_steps` or `rtol` near its bound): not measured.
fn land_runs(
    campaign: &Campaign,
    engine: Engine,
    landing: u64,
    drawn: &[Value],
) -> Result<Option<Runs>, CampaignError> {
    let at = |factor: f64| {
        scenario(campaign, drawn).and_then(|sc| match factor > 1.0 {
            true => touchdown_registry::refined(engine, &sc, factor),
            false => Ok(sc),
        })
    };
    let fine = refinement(engine);
    let (run, half, refined) = (at(1.0), at(fine / 2.0), at(fine));
    if run.is_ok() && (half.is_err() || refined.is_err()) {
        return Ok(None);
    }
    let land = |sc: Result<Scenario, ScenarioError>| {
        let sc = match sc {
            Ok(sc) => sc,
            Err(e) => return Ok(Err(RunError::Refused(e))),
        };
        outcome(touchdown_registry::land_reusing_runner(
            engine,
            &campaign.scenario_path,
            &sc,
            &mut (),
            None,
        ))
    };
    let (run, half, refined) = (land(run)?, land(half)?, land(refined)?);
    Ok(Some(Runs {
        landing,
        run,
        half,
        refined,
    }))
}

/// Every maximum stroke of `s` with its strut's capacity, m, in a fixed order.
fn strokes(s: &Summary) -> impl Iterator<Item = (f64, f64)> + '_ {
    let c = &s.strut_capacity;
    let primary = s
        .max_primary_stroke_m
        .iter()
        .map(|x| (*x, c.primary.stroke_m));
    let compression = (s.max_secondary_compression_m.iter().flatten())
        .map(|x| (*x, c.secondary_compression.stroke_m));
    let tension =
        (s.max_secondary_tension_m.iter().flatten()).map(|x| (*x, c.secondary_tension.stroke_m));
    primary.chain(compression).chain(tension)
}

/// The largest primary stroke of `s`, m.
fn largest_primary(s: &Summary) -> f64 {
    s.max_primary_stroke_m.iter().fold(0.0, |m, x| m.max(*x))
}

/// The larger of `worst` and `fraction` on `landing` (the first landing keeps a tie).
fn keep(worst: &mut Worst, fraction: f64, landing: u64) {
    if fraction > worst.fraction {
        *worst = Worst { fraction, landing };
    }
}

/// The largest errors of the maxima over `completed` (each landing with its run and refined
/// run); `None` when it is empty.
fn maxima(completed: &[(u64, &Summary, &Summary)]) -> Option<Maxima> {
    let (first, _, _) = completed.first()?;
    let zero = Worst {
        fraction: 0.0,
        landing: *first,
    };
    let mut m = Maxima {
        largest_primary_stroke: zero,
        stroke_of_capacity: zero,
        peak_pitch_rate_of_largest: zero,
    };
    let largest_pitch_rate = completed
        .iter()
        .fold(0.0f64, |a, (_, _, r)| a.max(r.peak_pitch_rate_rad_s.abs()));
    for &(landing, run, refined) in completed {
        let (a, b) = (largest_primary(run), largest_primary(refined));
        if b > 0.0 {
            keep(&mut m.largest_primary_stroke, (a - b).abs() / b, landing);
        }
        for ((x, capacity), (x_ref, _)) in strokes(run).zip(strokes(refined)) {
            keep(
                &mut m.stroke_of_capacity,
                (x - x_ref).abs() / capacity,
                landing,
            );
        }
        if largest_pitch_rate > 0.0 {
            let d = (run.min_pitch_rate_rad_s - refined.min_pitch_rate_rad_s)
                .abs()
                .max((run.max_pitch_rate_rad_s - refined.max_pitch_rate_rad_s).abs());
            keep(
                &mut m.peak_pitch_rate_of_largest,
                d / largest_pitch_rate,
                landing,
            );
        }
    }
    Some(m)
}

/// The landings of `runs` the three runs completed, each with its summaries (the campaign's
/// settings, half refined, refined), and the errors of their maxima; the errors `None` when
/// there are none.
fn comparison<'a>(
    runs: impl Iterator<Item = (u64, &'a Summary, &'a Summary, &'a Summary)>,
) -> (u64, Option<Comparison>) {
    let (settings, reference): (Vec<_>, Vec<_>) = runs
        .map(|(i, run, half, refined)| ((i, run, refined), (i, half, refined)))
        .unzip();
    let comparison = maxima(&settings).zip(maxima(&reference));
    let comparison = comparison.map(|(settings, reference)| Comparison {
        settings,
        reference,
    });
    (settings.len() as u64, comparison)
}

/// The sample's outcomes and maxima on `engine` compared (`n` landings, of which
/// `not_refined` could not be refined and are not in `runs`), the outcomes' bound at
/// `confidence`.
fn compare(
    runs: &[Runs],
    n: u64,
    not_refined: Vec<u64>,
    confidence: f64,
    engine: Engine,
) -> Accuracy {
    let differ = |a: &Result<Summary, RunError>, b: &Result<Summary, RunError>| {
        Status::of(a.as_ref()) != Status::of(b.as_ref())
    };
    let outcomes_differ: Vec<u64> = (runs.iter())
        .filter(|r| differ(&r.run, &r.refined))
        .map(|r| r.landing)
        .collect();
    let reference_outcomes_differ = (runs.iter())
        .filter(|r| differ(&r.half, &r.refined))
        .map(|r| r.landing)
        .collect();
    let completed: Vec<_> = (runs.iter())
        .filter_map(|r| {
            let (a, b, c) = (r.run.as_ref(), r.half.as_ref(), r.refined.as_ref());
            Some((r.landing, a.ok()?, b.ok()?, c.ok()?))
        })
        .collect();
    let is_stable = |s: &Summary| s.outcome == Outcome::Stable;
    let (compared, maxima) = comparison(completed.iter().copied());
    let (stable, stable_maxima) = comparison(
        (completed.iter().copied())
            .filter(|(_, a, b, c)| is_stable(a) && is_stable(b) && is_stable(c)),
    );
    let measured = runs.len() as u64;
    let outcomes_differ_bound = Some(OutcomeBound::new(
        outcomes_differ.len() as u64,
        measured,
        confidence,
    ));
    Accuracy {
        engine: engine.name().into(),
        sample_landings: n,
        refinement: refinement(engine),
        outcomes_identical: measured - outcomes_differ.len() as u64,
        not_refined,
        outcomes_differ,
        outcomes_differ_bound,
        reference_outcomes_differ,
        compared,
        maxima,
        stable,
        stable_maxima,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sample_is_one_landing_in_a_hundred_between_one_and_twenty() {
        assert_eq!(sample_size(1), 1);
        assert_eq!(sample_size(24), 1);
        assert_eq!(sample_size(101), 2);
        assert_eq!(sample_size(1000), 10);
        assert_eq!(sample_size(2001), 20);
        assert_eq!(sample_size(100_000), 20);
    }

    /// The bound on the outcomes a sample cannot tell apart: none of 20 differing bounds the
    /// fraction by 1 − 0.05^(1/20) = 13.9 % at 95 % (the rule of three's exact form), and it
    /// narrows as the sample grows and widens with every landing that differs.
    #[test]
    fn a_sample_that_agrees_bounds_the_campaigns_differing_outcomes() {
        let none_of_20 = OutcomeBound::new(0, 20, 0.95).fraction;
        assert!((none_of_20 - (1.0 - 0.05f64.powf(1.0 / 20.0))).abs() < 1e-12);
        assert!((none_of_20 - 0.139).abs() < 5e-4, "{none_of_20}");
        let none_of_1000 = OutcomeBound::new(0, 1000, 0.95).fraction;
        assert!(
            none_of_1000 < 0.003 && none_of_1000 > 0.0029,
            "{none_of_1000}"
        );
        let some_of_1000 = OutcomeBound::new(37, 1000, 0.95).fraction;
        assert!(
            some_of_1000 > 0.037 && some_of_1000 < 0.05,
            "{some_of_1000}"
        );
        assert_eq!(OutcomeBound::new(0, 0, 0.95).fraction, 1.0);
        assert_eq!(OutcomeBound::new(3, 3, 0.95).fraction, 1.0);
    }
}
