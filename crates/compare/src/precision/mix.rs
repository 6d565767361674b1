//! Work-precision on a mix of landings (a campaign's first landings; docs/performance.md,
//! "Work-precision on the campaign mix"): each landing's reference, the report's scheme refined
//! ([`super::refine`]) with how far its last two refinements part (its resolution: the maxima
//! a rocking stance makes do not converge), then each method's ladder over every landing that
//! has one, its errors gathered over the mix: the median and the worst error on every maximum
//! stroke and on the largest primary stroke, the outcomes that differ from the references',
//! and the mean cost of a landing. A single landing's study shows how a method converges; the
//! mix shows what its settings give on the landings a campaign is made of, where the chaotic
//! ones (an outcome or a maximum that the step's path decides) weigh in.

use super::{
    duration, measure, median, percent, reference_divisor, refine, setting_label, Method,
    FIXED_ERROR, REFERENCE_STROKE_AGREEMENT,
};
use crate::EngineRun;
use rayon::prelude::*;
use serde::Serialize;
use std::path::Path;
use touchdown_record::{Outcome, Summary};
use touchdown_scenario::Scenario;

/// One landing of a mix: its label (e.g. `landing 3`) and its resolved scenario.
#[derive(Debug, Clone)]
pub struct MixLanding {
    /// How the study names it.
    pub label: String,
    /// The scenario, resolved.
    pub scenario: Scenario,
}

/// Refinements of a mix landing's reference: the report's scheme with DIST and dt_max ÷ 64 to
/// ÷ 512 ([`super::reference_level`]), fewer if two agree within
/// [`REFERENCE_STROKE_AGREEMENT`] on every maximum stroke.
pub const MIX_REFERENCE_LEVELS: usize = 4;

/// A landing's reference, or why it has none (left out of the errors, counted).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MixReference {
    /// The landing's label.
    pub landing: String,
    /// Its reference, if it has one.
    #[serde(flatten)]
    pub found: Option<LandingReference>,
    /// Why it has none (a refinement failed or ran out of the scenario's budget).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub failure: Option<String>,
}

/// A landing's reference: its finest refinement, and how far that lands from the one before it
/// (the reference's resolution: where a landing's maxima are decided by the step's path, as a
/// rocking stance decides the secondaries', the refinements do not converge and the errors
/// below this are not resolved).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LandingReference {
    /// The finest refinement's step divisor.
    pub divisor: f64,
    /// Whether its last two refinements agree within [`REFERENCE_STROKE_AGREEMENT`] on every
    /// maximum stroke.
    pub converged: bool,
    /// How far the finest refinement lands from the one before it on every maximum stroke, a
    /// fraction of its largest primary stroke.
    #[serde(rename = "resolution_max_stroke_fraction")]
    pub resolution_max_stroke: f64,
    /// The same on the largest primary stroke, a fraction of it.
    #[serde(rename = "resolution_largest_primary_fraction")]
    pub resolution_largest_primary: f64,
    /// The finest refinement's outcome.
    pub outcome: Outcome,
    /// Whether the last two refinements have the same outcome: if not, the step decides it
    /// even there, and the landing is left out of the outcome counts.
    pub outcome_determined: bool,
    /// Accepted steps of the finest refinement.
    pub steps: u64,
    /// The finest refinement's run.
    #[serde(skip)]
    pub run: EngineRun,
}

/// The largest of a summary's maximum primary strokes, m.
fn largest_primary(s: &Summary) -> f64 {
    s.max_primary_stroke_m.iter().fold(0.0f64, |m, x| m.max(*x))
}

/// How far `run`'s largest primary stroke lands from `reference`'s, a fraction of it.
fn largest_primary_error(reference: &Summary, run: &Summary) -> f64 {
    let r = largest_primary(reference);
    (largest_primary(run) - r).abs() / r.max(f64::MIN_POSITIVE)
}

/// The reference of `landing` (its runs' diagnostics naming `path`).
fn mix_reference(path: &Path, landing: &MixLanding) -> MixReference {
    let found = refine(path, &landing.scenario, MIX_REFERENCE_LEVELS)
        .map_err(|e| e.to_string())
        .and_then(|r| {
            let Some((previous, agreement)) = &r.previous else {
                return Err(
                    "a single refinement: nothing to measure its resolution against".into(),
                );
            };
            let s = &r.run.summary;
            Ok(LandingReference {
                divisor: reference_divisor(r.level),
                converged: r.converged(),
                resolution_max_stroke: agreement.max_stroke,
                resolution_largest_primary: largest_primary_error(s, &previous.summary),
                outcome: s.outcome,
                outcome_determined: s.outcome == previous.summary.outcome,
                steps: s.steps,
                run: r.run,
            })
        });
    MixReference {
        landing: landing.label.clone(),
        failure: found.as_ref().err().cloned(),
        found: found.ok(),
    }
}

/// One rung of a method over the mix: its errors over the landings that have a reference.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MixRung {
    /// The method.
    pub method: Method,
    /// Its setting ([`Method::setting`]).
    pub value: f64,
    /// Landings measured: with a reference and a completed run.
    pub landings: usize,
    /// Landings whose run failed.
    pub failed: usize,
    /// The first failed landing and its engine's diagnostic.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub first_failure: Option<String>,
    /// Landings whose outcome differs from their reference's, among those whose reference's
    /// outcome the step does not decide ([`LandingReference::outcome_determined`]).
    pub outcomes_differing: usize,
    /// Every maximum stroke's error ([`super::Errors::max_stroke`], a fraction of each
    /// reference's largest primary stroke) over the landings; `None` with none measured.
    #[serde(
        rename = "max_stroke_fraction",
        skip_serializing_if = "Option::is_none"
    )]
    pub max_stroke: Option<Spread>,
    /// The largest primary stroke's error, a fraction of the reference's.
    #[serde(
        rename = "largest_primary_fraction",
        skip_serializing_if = "Option::is_none"
    )]
    pub largest_primary: Option<Spread>,
    /// Mean accepted steps of a landing.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mean_steps: Option<f64>,
    /// Mean wall time of a landing (each its median of the timed runs), s.
    #[serde(rename = "mean_wall_time_s", skip_serializing_if = "Option::is_none")]
    pub mean_wall_time: Option<f64>,
    /// Why the rung stopped before its last landing (its landings took longer than the
    /// study's time budget), which ends its method's ladder: its figures are of the landings
    /// before, not of the mix.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stopped: Option<String>,
}

/// An error over the landings of a mix: its median and its largest, with the landing that made
/// it (fractions).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Spread {
    /// The median over the landings.
    pub median: f64,
    /// The largest.
    pub worst: f64,
    /// The landing it was made on.
    pub worst_landing: String,
}

impl Spread {
    /// The spread of `errors`, each with its landing's label; `None` if there are none.
    fn of(errors: &[(f64, &str)]) -> Option<Spread> {
        let (worst, landing) =
            (errors.iter()).fold(None, |w: Option<(f64, &str)>, &(e, l)| match w {
                Some((x, _)) if x >= e => w,
                _ => Some((e, l)),
            })?;
        let mut values: Vec<f64> = errors.iter().map(|e| e.0).collect();
        Some(Spread {
            median: median(&mut values),
            worst,
            worst_landing: landing.to_string(),
        })
    }
}

/// The cheapest rungs of a method within the stroke error on the largest primary stroke: on
/// its median over the landings, and on every landing with every outcome its reference's and
/// no run failed. (Not on every maximum stroke: the maxima a rocking stance makes are decided
/// by the step's path, and the references resolve them only to about a per cent; the study
/// states that resolution.)
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MixAtError {
    /// The method.
    pub method: Method,
    /// The cheapest rung whose median error on the largest primary stroke is within it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub median_value: Option<f64>,
    /// Its mean wall time of a landing, s.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub median_wall_time_s: Option<f64>,
    /// The cheapest rung whose every landing's largest primary stroke is within it, every
    /// outcome its reference's and no run failed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub worst_value: Option<f64>,
    /// Its mean wall time of a landing, s.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub worst_wall_time_s: Option<f64>,
}

/// The work-precision study of a mix of landings.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WorkPrecisionMix {
    /// The mix's name (a campaign's name).
    #[serde(rename = "mix_name")]
    pub name: String,
    /// Landings in the mix.
    pub landings: usize,
    /// Landings with a reference.
    pub referenced: usize,
    /// Timed runs per rung and landing whose median is its wall time.
    pub repeats: usize,
    /// The most a rung's landings may take on average, s: the first rung past it ends its
    /// method's ladder ([`MixRung::stopped`]).
    #[serde(rename = "max_landing_time_s")]
    pub max_landing_time: f64,
    /// Whether this binary was built with optimisations.
    pub optimised_build: bool,
    /// Every landing's reference.
    pub references: Vec<MixReference>,
    /// The references' resolution of every maximum stroke over the landings
    /// ([`LandingReference::resolution_max_stroke`]); `None` without a reference.
    #[serde(
        rename = "resolution_max_stroke_fraction",
        skip_serializing_if = "Option::is_none"
    )]
    pub resolution_max_stroke: Option<Spread>,
    /// The same on the largest primary stroke.
    #[serde(
        rename = "resolution_largest_primary_fraction",
        skip_serializing_if = "Option::is_none"
    )]
    pub resolution_largest_primary: Option<Spread>,
    /// Every rung, method by method, coarsest first.
    pub rungs: Vec<MixRung>,
    /// Stroke error at which [`WorkPrecisionMix::at_error`] is read, a fraction.
    #[serde(rename = "fixed_error_fraction")]
    pub fixed_error: f64,
    /// For each method, the cheapest rungs within [`WorkPrecisionMix::fixed_error`].
    pub at_error: Vec<MixAtError>,
}

/// What [`work_precision_mix`] reports as it goes.
#[derive(Debug, Clone, Copy)]
pub enum Progress<'a> {
    /// A landing's reference is done.
    Reference(&'a MixReference),
    /// A rung is done over the whole mix.
    Rung(&'a MixRung),
}

/// The work-precision study of the mix `landings` (named `name`; `path` is the file they come
/// from, which names the runs' diagnostics) for `methods` (on each landing whose
/// `engines.applicable` lists the method's engine), over each method's default ladder or its
/// first `rungs`, with `repeats` timed runs per rung and landing; a method's ladder ends at
/// the first rung whose landings take longer than `max_landing_time` (s) on average (its
/// finer rungs cost more). The references are computed in parallel on the current thread
/// pool, the rungs one landing after another (their wall times are measured); `progress`
/// hears of each reference and each rung when it is done.
#[allow(clippy::too_many_arguments)]
pub fn work_precision_mix(
    path: &Path,
    name: &str,
    landings: &[MixLanding],
    methods: &[Method],
    rungs: Option<usize>,
    repeats: usize,
    max_landing_time: f64,
    progress: impl Fn(Progress<'_>) + Sync,
) -> WorkPrecisionMix {
    let references: Vec<MixReference> = landings
        .par_iter()
        .map(|l| {
            let r = mix_reference(path, l);
            progress(Progress::Reference(&r));
            r
        })
        .collect();
    let referenced: Vec<(&MixLanding, &LandingReference)> = landings
        .iter()
        .zip(&references)
        .filter_map(|(l, r)| r.found.as_ref().map(|f| (l, f)))
        .collect();
    let mut all = Vec::new();
    for &method in methods {
        for &value in method.rungs(rungs) {
            let rung = mix_rung(path, &referenced, method, value, repeats, max_landing_time);
            progress(Progress::Rung(&rung));
            let stopped = rung.stopped.is_some();
            all.push(rung);
            if stopped {
                break;
            }
        }
    }
    let resolution = |pick: &dyn Fn(&LandingReference) -> f64| {
        let errors: Vec<(f64, &str)> = (references.iter())
            .filter_map(|r| r.found.as_ref().map(|f| (pick(f), r.landing.as_str())))
            .collect();
        Spread::of(&errors)
    };
    WorkPrecisionMix {
        name: name.to_string(),
        landings: landings.len(),
        referenced: referenced.len(),
        repeats,
        max_landing_time,
        optimised_build: !cfg!(debug_assertions),
        resolution_max_stroke: resolution(&|f| f.resolution_max_stroke),
        resolution_largest_primary: resolution(&|f| f.resolution_largest_primary),
        references,
        at_error: methods.iter().map(|&m| at_error(&all, m)).collect(),
        rungs: all,
        fixed_error: FIXED_ERROR,
    }
}

/// One rung of `method` at `value` over the landings with a reference, stopped after the
/// landing that takes the mean wall time past `max_landing_time` (s).
fn mix_rung(
    path: &Path,
    referenced: &[(&MixLanding, &LandingReference)],
    method: Method,
    value: f64,
    repeats: usize,
    max_landing_time: f64,
) -> MixRung {
    let (mut strokes, mut primaries) = (Vec::new(), Vec::new());
    let (mut steps, mut wall) = (0.0, 0.0);
    let (mut failed, mut first_failure, mut differing) = (0, None, 0);
    let mut stopped = None;
    for (k, &(landing, reference)) in referenced.iter().enumerate() {
        let reference_run = &reference.run;
        let sc = &landing.scenario;
        if !sc.applicable_engines.contains(&method.engine()) {
            continue;
        }
        let rung = measure(path, sc, reference_run, method, value, repeats);
        match (rung.measured, rung.summary) {
            (Some(m), Some(summary)) => {
                let label = landing.label.as_str();
                strokes.push((m.errors.max_stroke, label));
                let primary = largest_primary_error(&reference_run.summary, &summary);
                primaries.push((primary, label));
                steps += m.steps as f64;
                wall += m.wall_time_s;
                differing +=
                    usize::from(reference.outcome_determined && reference.outcome != m.outcome);
                let mean = wall / strokes.len() as f64;
                if mean > max_landing_time && k + 1 < referenced.len() {
                    stopped = Some(format!(
                        "after {} of {} landings: {} a landing, past the budget of {}; the ladder ends here",
                        k + 1,
                        referenced.len(),
                        duration(mean),
                        duration(max_landing_time)
                    ));
                    break;
                }
            }
            _ => {
                failed += 1;
                if first_failure.is_none() {
                    let why = rung.failure.unwrap_or_default();
                    first_failure = Some(format!("{}: {why}", landing.label));
                }
            }
        }
    }
    let n = strokes.len();
    let mean = |total: f64| (n > 0).then(|| total / n as f64);
    MixRung {
        method,
        value,
        landings: n,
        failed,
        first_failure,
        outcomes_differing: differing,
        max_stroke: Spread::of(&strokes),
        largest_primary: Spread::of(&primaries),
        mean_steps: mean(steps),
        mean_wall_time: mean(wall),
        stopped,
    }
}

/// The cheapest rungs of `method` within [`FIXED_ERROR`] ([`MixAtError`]).
fn at_error(rungs: &[MixRung], method: Method) -> MixAtError {
    let cheapest = |within: &dyn Fn(&MixRung) -> bool| {
        rungs
            .iter()
            .filter(|r| r.method == method && r.landings > 0 && r.stopped.is_none() && within(r))
            .filter_map(|r| r.mean_wall_time.map(|t| (r.value, t)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
    };
    let median =
        cheapest(&|r| (r.largest_primary.as_ref()).is_some_and(|e| e.median <= FIXED_ERROR));
    let worst = cheapest(&|r| {
        (r.largest_primary.as_ref()).is_some_and(|e| e.worst <= FIXED_ERROR)
            && r.outcomes_differing == 0
            && r.failed == 0
    });
    MixAtError {
        method,
        median_value: median.map(|x| x.0),
        median_wall_time_s: median.map(|x| x.1),
        worst_value: worst.map(|x| x.0),
        worst_wall_time_s: worst.map(|x| x.1),
    }
}

/// A spread as the text prints it: median, worst (landing).
fn spread_text(s: &Option<Spread>) -> [String; 2] {
    match s {
        Some(s) => [
            percent(s.median),
            format!("{} ({})", percent(s.worst), s.worst_landing),
        ],
        None => [String::new(), String::new()],
    }
}

/// The study as text: the references, then a table of the rungs, then the cheapest rungs.
pub fn text(w: &WorkPrecisionMix) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "work-precision on a mix: {} ({} landings)",
        w.name, w.landings
    );
    let found = || w.references.iter().filter_map(|r| r.found.as_ref());
    let converged = found().filter(|f| f.converged).count();
    let undetermined = found().filter(|f| !f.outcome_determined).count();
    let _ = writeln!(
        s,
        "references: {} of {} landings (core report, DIST and dt_max ÷{} to ÷{}; {converged} converged within {:.0e} on every maximum stroke; {undetermined} whose outcome the last two refinements decide otherwise, left out of the outcome counts)",
        w.referenced,
        w.landings,
        reference_divisor(0),
        reference_divisor(MIX_REFERENCE_LEVELS - 1),
        REFERENCE_STROKE_AGREEMENT,
    );
    let [m, x] = spread_text(&w.resolution_max_stroke);
    let [pm, px] = spread_text(&w.resolution_largest_primary);
    let _ = writeln!(
        s,
        "their resolution (the finest refinement against the one before it): every maximum stroke median {m}, worst {x}; the largest primary stroke median {pm}, worst {px}"
    );
    for r in &w.references {
        if let Some(failure) = &r.failure {
            let _ = writeln!(s, "  {}: no reference ({failure})", r.landing);
        }
    }
    let _ = writeln!(
        s,
        "errors: every maximum stroke as a fraction of each reference's largest primary stroke, and the largest primary stroke, median and worst over the landings; outcomes that differ from the references'; wall time: mean of a landing, each the median of {} runs; a ladder ends at the first rung past {} a landing{}",
        w.repeats,
        duration(w.max_landing_time),
        super::build_note(w.optimised_build)
    );
    let rows = w.rungs.iter().map(|r| {
        let opt = |x: Option<f64>, f: &dyn Fn(f64) -> String| x.map_or(String::new(), f);
        let [sm, sw] = spread_text(&r.max_stroke);
        let [pm, pw] = spread_text(&r.largest_primary);
        vec![
            r.method.name().to_string(),
            setting_label(r.method, r.value),
            r.landings.to_string(),
            opt(r.mean_steps, &|x| format!("{x:.0}")),
            opt(r.mean_wall_time, &duration),
            sm,
            sw,
            pm,
            pw,
            r.outcomes_differing.to_string(),
            match (&r.first_failure, &r.stopped) {
                (Some(f), _) => format!("{} ({f})", r.failed),
                (None, Some(stop)) => format!("{}; stopped {stop}", r.failed),
                (None, None) => r.failed.to_string(),
            },
        ]
    });
    s.push('\n');
    s.push_str(&crate::report::text_table(
        &[
            "method",
            "setting",
            "landings",
            "steps",
            "wall time",
            "strokes median",
            "worst",
            "primary median",
            "worst",
            "outcomes differ",
            "failed",
        ],
        &[2, 3, 4, 5, 7, 9],
        rows,
    ));
    let _ = writeln!(
        s,
        "\nat {} error on the largest primary stroke, the cheapest rung within it: on the median | on every landing, with every outcome the reference's",
        percent(w.fixed_error)
    );
    let cell = |v: Option<f64>, t: Option<f64>, m: Method| match (v, t) {
        (Some(v), Some(t)) => format!("{:>14} {:>11}", setting_label(m, v), duration(t)),
        _ => format!("{:>26}", "no rung within it"),
    };
    for a in &w.at_error {
        let _ = writeln!(
            s,
            "{:<12} {} | {}",
            a.method.name(),
            cell(a.median_value, a.median_wall_time_s, a.method),
            cell(a.worst_value, a.worst_wall_time_s, a.method),
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_spread_is_the_median_and_the_worst_with_its_landing() {
        assert_eq!(Spread::of(&[]), None);
        let s = Spread::of(&[(0.02, "a"), (0.05, "b"), (0.01, "c"), (0.05, "d")]).unwrap();
        assert_eq!((s.median, s.worst), (0.035, 0.05));
        assert_eq!(
            s.worst_landing, "b",
            "the first landing that made the worst"
        );
    }

    /// The cheapest rung on the median needs only the median within the error; on every landing
    /// it needs the worst within it, no outcome changed and no failure; a stopped rung (not of
    /// the whole mix) is neither.
    #[test]
    fn the_cheapest_rungs_within_the_error_are_read_on_the_largest_primary() {
        let rung = |value: f64, median: f64, worst: f64, time: f64| MixRung {
            method: Method::Report,
            value,
            landings: 3,
            failed: 0,
            first_failure: None,
            outcomes_differing: 0,
            max_stroke: Spread::of(&[(0.5, "x")]),
            largest_primary: Some(Spread {
                median,
                worst,
                worst_landing: "landing 2".into(),
            }),
            mean_steps: Some(100.0 * value),
            mean_wall_time: Some(time),
            stopped: None,
        };
        let rungs = [
            rung(1.0, 0.005, 0.07, 0.01),
            MixRung {
                outcomes_differing: 1,
                ..rung(2.0, 0.001, 0.009, 0.02)
            },
            MixRung {
                stopped: Some("after 1 of 3 landings".into()),
                ..rung(4.0, 0.0, 0.0, 0.04)
            },
            rung(8.0, 0.0005, 0.008, 0.08),
        ];
        let a = at_error(&rungs, Method::Report);
        assert_eq!(
            (a.median_value, a.median_wall_time_s),
            (Some(1.0), Some(0.01))
        );
        assert_eq!(
            (a.worst_value, a.worst_wall_time_s),
            (Some(8.0), Some(0.08))
        );
        assert_eq!(at_error(&rungs, Method::Strides).median_value, None);
    }
}
