//! Work-precision: each engine and integration scheme run over a ladder of step sizes or
//! tolerances, its error against a converged reference set against what it cost (steps, force
//! evaluations, wall time). `touchdown precision` prints it; docs/performance.md records it.
//!
//! The reference is the core with the report's scheme at steps far below any rung's, refined
//! ([`reference_level`]) until two successive refinements agree on the strokes within
//! [`REFERENCE_STROKE_AGREEMENT`]: the scheme that lands every footpad on its plane within a
//! step (eq. 25 and its contact limit), so that it converges where footpads rattle in their free
//! play on spikes, which the Dormand–Prince pair's error control rejects step after step. The
//! multibody engines are measured against the same reference, so their error holds the model's difference (a gear with masses and a contact solver against the
//! report's massless gear) besides the numerical one; [`Errors::self_max_stroke`] separates the
//! two by measuring each rung against the finest rung of its own ladder. [`mix`] gathers the
//! study over the landings of a campaign.

use crate::metrics::pitch_rate_differences;
use crate::{run, CompareError, Engine, EngineRun, Trace};
use nalgebra::{Matrix3, Vector3};
use serde::Serialize;
use std::path::Path;
use std::time::Instant;
use touchdown_frames::t_bi;
use touchdown_record::{Outcome, Summary};
use touchdown_registry::land;
use touchdown_scenario::schema::Scheme;
use touchdown_scenario::Scenario;

pub mod mix;

/// An integration method whose accuracy one number sets: a core scheme or a multibody engine.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Method {
    /// The core with the report's predictor-corrector (eqs. 20-25); the rung divides DIST and
    /// dt_max by its value.
    Report,
    /// The core with the report's predictor-corrector in long strides (`strides`, docs/errata.md,
    /// "Long strides where the gear is soft"); the rung divides DIST, dt_max and mode_step by
    /// its value.
    Strides,
    /// The core with the classical fourth-order Runge–Kutta method; the rung is its step, s.
    Rk4,
    /// The core with the Dormand–Prince 5(4) pair; the rung is `rtol` (`atol` = 1e-3 `rtol`, in
    /// SI units of the state), within the scenario's dt_min and dt_max.
    Dopri5,
    /// The rapier rebuild; the rung is its fixed step, s.
    Rapier,
    /// The MuJoCo engine; the rung is its fixed step, s.
    Mujoco,
}

/// `atol` of a [`Method::Dopri5`] rung as a fraction of its `rtol` (state components are of
/// order 0.001 to 1 in SI: strokes in m, rates in rad/s).
pub const DOPRI5_ATOL_PER_RTOL: f64 = 1.0e-3;

impl Method {
    /// Every method, in table order.
    pub const ALL: [Method; 6] = [
        Method::Report,
        Method::Strides,
        Method::Rk4,
        Method::Dopri5,
        Method::Rapier,
        Method::Mujoco,
    ];

    /// The engine that runs the method.
    pub fn engine(self) -> Engine {
        match self {
            Method::Report | Method::Strides | Method::Rk4 | Method::Dopri5 => Engine::Core,
            Method::Rapier => Engine::Rapier,
            Method::Mujoco => Engine::Mujoco,
        }
    }

    /// Name in tables and plots.
    pub fn name(self) -> &'static str {
        match self {
            Method::Report => "core report",
            Method::Strides => "core strides",
            Method::Rk4 => "core rk4",
            Method::Dopri5 => "core dopri5",
            Method::Rapier => "rapier",
            Method::Mujoco => "mujoco",
        }
    }

    /// What a rung's value is.
    pub fn setting(self) -> &'static str {
        match self {
            Method::Report => "DIST and dt_max divided by",
            Method::Strides => "DIST, dt_max and mode_step divided by",
            Method::Rk4 | Method::Rapier | Method::Mujoco => "step, s",
            Method::Dopri5 => "rtol",
        }
    }

    /// The default ladder, coarsest rung first.
    pub fn ladder(self) -> &'static [f64] {
        match self {
            Method::Report | Method::Strides => &[1.0, 2.0, 4.0, 8.0, 16.0, 32.0],
            Method::Rk4 => &[2.0e-4, 1.0e-4, 5.0e-5, 2.0e-5, 1.0e-5, 5.0e-6],
            Method::Dopri5 => &[1.0e-2, 1.0e-3, 1.0e-4, 1.0e-5, 1.0e-6, 1.0e-7, 1.0e-8],
            Method::Rapier | Method::Mujoco => &[1.0e-4, 5.0e-5, 2.0e-5, 1.0e-5, 5.0e-6],
        }
    }

    /// The rungs a study measures: the ladder's first `rungs` (all of them with `None`).
    pub fn rungs(self, rungs: Option<usize>) -> &'static [f64] {
        let ladder = self.ladder();
        &ladder[..rungs.unwrap_or(ladder.len()).min(ladder.len())]
    }

    /// The scenario `sc` set to the rung `value` of this method.
    pub fn apply(
        self,
        sc: &Scenario,
        value: f64,
    ) -> Result<Scenario, touchdown_scenario::ScenarioError> {
        let time = sc.units().time();
        let sc = sc.clone();
        match self {
            Method::Report => sc.with_integrator(|it| {
                it.scheme = Scheme::Report;
                it.refine(value);
            }),
            Method::Strides => sc.with_integrator(|it| {
                it.scheme = Scheme::Strides;
                it.refine(value);
            }),
            Method::Rk4 => sc.with_integrator(|it| {
                it.scheme = Scheme::Rk4;
                it.dt_max = value / time;
                it.dt_min = it.dt_min.min(it.dt_max);
            }),
            Method::Dopri5 => sc.with_integrator(|it| {
                it.scheme = Scheme::Dopri5;
                it.rtol = value;
                it.atol = value * DOPRI5_ATOL_PER_RTOL;
            }),
            Method::Rapier => sc.with_rapier(|r| r.timestep = Some(value / time)),
            Method::Mujoco => sc.with_mujoco(|m| m.timestep = Some(value / time)),
        }
    }
}

/// How far a run lands from another (the reference), on the channels of the work-precision study (docs/performance.md, "Work-precision: error against run time").
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Errors {
    /// Largest difference of any maximum stroke (primary; secondary compression and tension),
    /// as a fraction of the reference's largest primary stroke.
    #[serde(rename = "max_stroke_fraction")]
    pub max_stroke: f64,
    /// RMS difference of the pitch-rate history over the common span (interpolated at the
    /// reference's times), as a fraction of the reference's peak pitch-rate magnitude (at least
    /// 0.1 rad/s).
    #[serde(rename = "pitch_rate_rms_fraction")]
    pub pitch_rate_rms: f64,
    /// Angle of the rotation between the two attitudes at the common end time, rad.
    pub final_attitude_rad: f64,
    /// [`Errors::max_stroke`] against the finest rung of the run's own ladder instead of the
    /// reference (the ladder's own convergence; `None` outside a ladder, and for the finest
    /// rung itself; left out of the JSON then).
    #[serde(
        rename = "self_max_stroke_fraction",
        skip_serializing_if = "Option::is_none"
    )]
    pub self_max_stroke: Option<f64>,
}

/// Every maximum stroke of a summary, m, in a fixed order.
pub(crate) fn max_strokes(s: &Summary) -> impl Iterator<Item = f64> + '_ {
    s.max_primary_stroke_m.iter().copied().chain(
        s.max_secondary_compression_m
            .iter()
            .chain(&s.max_secondary_tension_m)
            .flatten()
            .copied(),
    )
}

/// Largest maximum-stroke difference of `run` from `reference`, as a fraction of the reference's
/// largest primary stroke.
fn stroke_error(reference: &Summary, run: &Summary) -> f64 {
    let scale = reference
        .max_primary_stroke_m
        .iter()
        .fold(0.0f64, |m, s| m.max(*s))
        .max(f64::MIN_POSITIVE);
    max_strokes(reference)
        .zip(max_strokes(run))
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
        / scale
}

/// The attitude of `trace` at time `t`, as the rotation body ← surface.
fn attitude_at(trace: &Trace, t: f64) -> Matrix3<f64> {
    t_bi(&Vector3::from(trace.attitude_at(t)))
}

/// The errors of `run` against `reference` (the self-convergence left unset).
pub fn errors(reference: &EngineRun, run: &EngineRun) -> Errors {
    let (rms, _) = pitch_rate_differences(&reference.trace, &run.trace);
    // As the comparison's pitch-rate channels: a peak under 0.1 rad/s counts as 0.1 rad/s (a
    // symmetric drop does not pitch).
    let peak = reference.summary.peak_pitch_rate_rad_s.abs().max(0.1);
    let end = reference.trace.end().min(run.trace.end());
    let gap = attitude_at(&reference.trace, end) - attitude_at(&run.trace, end);
    // ‖R_a − R_b‖_F = 2√2 sin(φ/2) for the angle φ between the rotations (precise when small).
    let final_attitude_rad = 2.0 * (gap.norm() / 8f64.sqrt()).min(1.0).asin();
    Errors {
        max_stroke: stroke_error(&reference.summary, &run.summary),
        pitch_rate_rms: rms / peak,
        final_attitude_rad,
        self_max_stroke: None,
    }
}

/// How closely two successive refinements of the reference must agree on every maximum stroke,
/// as a fraction of the largest primary stroke: a hundredth of the 1 % stroke error the
/// work-precision tables are read at ([`FIXED_ERROR`]). The pitch-rate history and the final
/// attitude are not asked to agree: where a landing is still rocking at its end time they wander
/// with the step (the Table I 2-2 landing at 8 ft/s: 1.0e-4 rad between the report's scheme ÷512
/// and ÷1024); their agreement is stated as the reference's resolution of those columns.
pub const REFERENCE_STROKE_AGREEMENT: f64 = 1.0e-4;

/// Refinements tried for the reference before giving up.
pub const REFERENCE_LEVELS: usize = 5;

/// The step divisor of the reference's first refinement: twice the finest rung of the report's
/// default ladder ([`Method::ladder`]).
pub const REFERENCE_FIRST_DIVISOR: f64 = 64.0;

/// The step divisor of the reference's `level`-th refinement (from 0):
/// [`REFERENCE_FIRST_DIVISOR`] · 2^level.
pub fn reference_divisor(level: usize) -> f64 {
    REFERENCE_FIRST_DIVISOR * 2f64.powi(level as i32)
}

/// The reference's `level`-th refinement (from 0): the report's scheme with DIST and dt_max
/// divided by [`reference_divisor`], dt_min no larger than dt_max; the run budget stays the
/// scenario's (`integrator.max_steps`), so a reference too fine for it is said as such.
pub fn reference_level(
    sc: &Scenario,
    level: usize,
) -> Result<Scenario, touchdown_scenario::ScenarioError> {
    let divisor = reference_divisor(level);
    sc.clone().with_integrator(|it| {
        let budget = it.max_steps;
        it.scheme = Scheme::Report;
        it.refine(divisor);
        it.max_steps = budget;
    })
}

/// The converged reference of a scenario.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Reference {
    /// The finest refinement's step divisor: the scenario's DIST and dt_max over it.
    pub divisor: f64,
    /// Its DIST (eq. 25), m.
    pub dist_m: f64,
    /// Its largest step, s.
    pub dt_max_s: f64,
    /// Refinements run.
    pub levels: usize,
    /// How far the finest refinement lands from the one before it: on the strokes within
    /// [`Reference::asked_max_stroke`]; on the pitch-rate history and the final
    /// attitude, the reference's resolution of those columns.
    pub agreement: Errors,
    /// The agreement asked on the strokes ([`REFERENCE_STROKE_AGREEMENT`]).
    #[serde(rename = "asked_max_stroke_fraction")]
    pub asked_max_stroke: f64,
    /// Steps and force evaluations of the finest refinement.
    pub steps: u64,
    /// Force evaluations of the finest refinement.
    pub force_evaluations: u64,
    /// The finest refinement's outcome.
    pub outcome: Outcome,
    /// The finest refinement's run.
    #[serde(skip)]
    pub run: EngineRun,
}

/// How far the refinements of a reference went ([`refine`]): the finest run and how it lands
/// from the one before it.
#[derive(Debug, Clone)]
pub struct Refinements {
    /// The finest refinement's level (from 0; its divisor is [`reference_divisor`] of it).
    pub level: usize,
    /// Its scenario.
    pub scenario: Scenario,
    /// Its run.
    pub run: EngineRun,
    /// The refinement before it, and how far the finest lands from it; `None` after one
    /// refinement.
    pub previous: Option<(EngineRun, Errors)>,
}

impl Refinements {
    /// Whether the last two refinements agree within [`REFERENCE_STROKE_AGREEMENT`] on every
    /// maximum stroke.
    pub fn converged(&self) -> bool {
        (self.previous.as_ref()).is_some_and(|(_, e)| e.max_stroke <= REFERENCE_STROKE_AGREEMENT)
    }

    /// The reference the finest refinement is, with how far it lands from the one before it;
    /// `None` after one refinement.
    fn reference(self) -> Option<Reference> {
        let scl = &self.scenario;
        let (_, agreement) = self.previous?;
        let current = self.run;
        Some(Reference {
            divisor: reference_divisor(self.level),
            dist_m: scl.integrator.dist,
            dt_max_s: scl.integrator.dt_max,
            levels: self.level + 1,
            agreement,
            asked_max_stroke: REFERENCE_STROKE_AGREEMENT,
            steps: current.summary.steps,
            force_evaluations: current.summary.force_evaluations,
            outcome: current.summary.outcome,
            run: current,
        })
    }
}

/// Refines `sc` (read from `path`) through at most `levels` refinements ([`reference_level`]),
/// until two successive ones agree within [`REFERENCE_STROKE_AGREEMENT`] on every maximum
/// stroke ([`Refinements::converged`]) or the levels run out; an error if a refinement fails,
/// or runs out of the scenario's budget (said as such, with what the refinements before it
/// showed).
pub fn refine(path: &Path, sc: &Scenario, levels: usize) -> Result<Refinements, CompareError> {
    let mut done: Option<Refinements> = None;
    for level in 0..levels {
        let scl = reference_level(sc, level)?;
        let current = match run(Engine::Core, path, &scl) {
            // A refinement past the scenario's budget: the ladder ends there, said as such.
            Err(CompareError::Engine(touchdown_registry::EngineFailure {
                error: touchdown_record::RunError::Stopped(d),
                ..
            })) if d.law == touchdown_record::Law::RunBudget => {
                let compared = done.as_ref().map_or_else(
                    || "no two refinements compared yet".to_string(),
                    disagreement,
                );
                return Err(CompareError::Unconverged {
                    scenario: path.display().to_string(),
                    message: format!(
                        "no converged reference within the run budget: refinement {level} (the report's scheme, DIST and dt_max ÷{}) ran out of it at t = {:.4} s ({}); {compared}; give the reference a larger budget with --set integrator.max_steps=N (now {})",
                        reference_divisor(level),
                        d.time_s,
                        d.message,
                        scl.integrator.max_steps
                    ),
                });
            }
            other => other?,
        };
        let previous = done.map(|d| {
            let e = errors(&current, &d.run);
            (d.run, e)
        });
        let r = Refinements {
            level,
            scenario: scl,
            run: current,
            previous,
        };
        if r.converged() {
            return Ok(r);
        }
        done = Some(r);
    }
    done.ok_or_else(|| CompareError::Unconverged {
        scenario: path.display().to_string(),
        message: "no refinement asked for".into(),
    })
}

/// How far the last two of `r` part on the strokes, as the messages say it.
fn disagreement(r: &Refinements) -> String {
    match &r.previous {
        Some((_, e)) => format!(
            "refinements {} and {} (÷{} and ÷{}) differ by {:.2e} on the strokes",
            r.level - 1,
            r.level,
            reference_divisor(r.level - 1),
            reference_divisor(r.level),
            e.max_stroke,
        ),
        None => "no two refinements compared yet".to_string(),
    }
}

/// Computes the converged reference of `sc` (read from `path`): refinements until two
/// successive ones agree within [`REFERENCE_STROKE_AGREEMENT`]; an error if none do within
/// [`REFERENCE_LEVELS`].
pub fn reference(path: &Path, sc: &Scenario) -> Result<Reference, CompareError> {
    let r = refine(path, sc, REFERENCE_LEVELS)?;
    let message = disagreement(&r);
    if let Some(reference) = r.converged().then(|| r.reference()).flatten() {
        return Ok(reference);
    }
    Err(CompareError::Unconverged {
        scenario: path.display().to_string(),
        message: format!(
            "no converged reference within {REFERENCE_LEVELS} refinements of the report's scheme (DIST and dt_max ÷{} to ÷{}): {} (asked: {:.0e})",
            reference_divisor(0),
            reference_divisor(REFERENCE_LEVELS - 1),
            message,
            REFERENCE_STROKE_AGREEMENT,
        ),
    })
}

/// What a rung cost and how far it landed from the reference.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Measured {
    /// Accepted steps.
    pub steps: u64,
    /// Gear-force evaluations.
    pub force_evaluations: u64,
    /// Wall time of a whole landing, median of the repeated runs, s (for MuJoCo with the
    /// runner's start-up: the Python interpreter, imports, model compilation).
    pub wall_time_s: f64,
    /// Outcome.
    pub outcome: Outcome,
    /// Errors against the reference.
    pub errors: Errors,
}

/// One rung of a ladder.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Rung {
    /// The method.
    pub method: Method,
    /// Its setting ([`Method::setting`]).
    pub value: f64,
    /// What it measured; `None` if the run failed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub measured: Option<Measured>,
    /// Why the run failed (the engine's diagnostic).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub failure: Option<String>,
    /// The run's summary.
    #[serde(skip)]
    pub summary: Option<Summary>,
}

/// The cheapest rung of a method within a stroke error.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AtError {
    /// The method.
    pub method: Method,
    /// The cheapest rung's setting, if any rung is within the error.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub value: Option<f64>,
    /// Its wall time, s.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wall_time_s: Option<f64>,
    /// Its wall time over the fastest method's.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ratio_to_fastest: Option<f64>,
    /// The same measured against the method's own finest rung instead of the reference (what
    /// the numerics alone cost): setting, wall time, ratio to the fastest on this measure.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub self_value: Option<f64>,
    /// Wall time of [`AtError::self_value`], s.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub self_wall_time_s: Option<f64>,
    /// Its ratio to the fastest on this measure.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub self_ratio_to_fastest: Option<f64>,
}

/// A scenario's work-precision study.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WorkPrecision {
    /// Scenario name.
    #[serde(rename = "scenario_name")]
    pub scenario: String,
    /// Scenario file (in the document's envelope).
    #[serde(skip)]
    pub file: String,
    /// SHA-256 of the resolved scenario (in the document's envelope).
    #[serde(skip)]
    pub scenario_sha256: String,
    /// Runs per rung whose median is the wall time.
    pub repeats: usize,
    /// Whether this binary was built with optimisations (wall times of a debug build are not
    /// representative).
    pub optimised_build: bool,
    /// The reference.
    pub reference: Reference,
    /// Every rung, method by method, coarsest first.
    pub rungs: Vec<Rung>,
    /// Stroke error at which [`WorkPrecision::at_error`] is read, a fraction.
    #[serde(rename = "fixed_error_fraction")]
    pub fixed_error: f64,
    /// For each method, the cheapest rung within [`WorkPrecision::fixed_error`].
    pub at_error: Vec<AtError>,
}

/// The stroke error at which the methods' costs are compared: 1 % of the largest primary stroke.
pub const FIXED_ERROR: f64 = 0.01;

/// Median of `values` (sorted in place).
pub(crate) fn median(values: &mut [f64]) -> f64 {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    if n % 2 == 1 {
        values[n / 2]
    } else {
        0.5 * (values[n / 2 - 1] + values[n / 2])
    }
}

/// Runs one rung: once with the trace for the errors, then `repeats` times untraced for the wall
/// time.
pub(crate) fn measure(
    path: &Path,
    sc: &Scenario,
    reference: &EngineRun,
    method: Method,
    value: f64,
    repeats: usize,
) -> Rung {
    let attempt = || -> Result<(Measured, EngineRun), CompareError> {
        let scr = method.apply(sc, value)?;
        let engine = method.engine();
        let traced = run(engine, path, &scr)?;
        let mut times = Vec::with_capacity(repeats);
        for _ in 0..repeats.max(1) {
            let start = Instant::now();
            land(engine, path, &scr, &mut (), None)?;
            times.push(start.elapsed().as_secs_f64());
        }
        let s = &traced.summary;
        Ok((
            Measured {
                steps: s.steps,
                force_evaluations: s.force_evaluations,
                wall_time_s: median(&mut times),
                outcome: s.outcome,
                errors: errors(reference, &traced),
            },
            traced,
        ))
    };
    match attempt() {
        Ok((measured, traced)) => Rung {
            method,
            value,
            measured: Some(measured),
            failure: None,
            summary: Some(traced.summary),
        },
        Err(e) => Rung {
            method,
            value,
            measured: None,
            failure: Some(e.to_string()),
            summary: None,
        },
    }
}

/// The cheapest rung of each method within `error`, on the reference's and on its own measure.
fn at_error(rungs: &[Rung], methods: &[Method], error: f64) -> Vec<AtError> {
    let cheapest = |method: Method, pick: &dyn Fn(&Measured) -> Option<f64>| {
        rungs
            .iter()
            .filter(|r| r.method == method)
            .filter_map(|r| r.measured.as_ref().map(|m| (r.value, m)))
            .filter(|(_, m)| pick(m).is_some_and(|e| e <= error))
            .min_by(|a, b| a.1.wall_time_s.total_cmp(&b.1.wall_time_s))
            .map(|(v, m)| (v, m.wall_time_s))
    };
    let reference: Vec<_> = methods
        .iter()
        .map(|m| cheapest(*m, &|x| Some(x.errors.max_stroke)))
        .collect();
    let own: Vec<_> = methods
        .iter()
        .map(|m| cheapest(*m, &|x| x.errors.self_max_stroke))
        .collect();
    let fastest = |found: &[Option<(f64, f64)>]| {
        found
            .iter()
            .flatten()
            .map(|(_, t)| *t)
            .fold(f64::INFINITY, f64::min)
    };
    let (f_ref, f_own) = (fastest(&reference), fastest(&own));
    methods
        .iter()
        .zip(reference.iter().zip(&own))
        .map(|(method, (r, o))| AtError {
            method: *method,
            value: r.map(|x| x.0),
            wall_time_s: r.map(|x| x.1),
            ratio_to_fastest: r.map(|x| x.1 / f_ref),
            self_value: o.map(|x| x.0),
            self_wall_time_s: o.map(|x| x.1),
            self_ratio_to_fastest: o.map(|x| x.1 / f_own),
        })
        .collect()
}

/// The work-precision study of the scenario at `path` for `methods` (those whose engine the
/// scenario's `engines.applicable` lists), each over its default ladder (or the first `rungs`
/// of it), with `repeats` timed runs per rung; `progress` hears of each rung when it is done.
pub fn work_precision(
    path: &Path,
    methods: &[Method],
    rungs: Option<usize>,
    repeats: usize,
    progress: impl FnMut(&Rung),
) -> Result<WorkPrecision, CompareError> {
    work_precision_resolved(
        path,
        &Scenario::load(path)?,
        methods,
        rungs,
        repeats,
        progress,
    )
}

/// [`work_precision`] of a scenario already resolved (with overrides); `path` names it in the
/// study and in errors.
pub fn work_precision_resolved(
    path: &Path,
    sc: &Scenario,
    methods: &[Method],
    rungs: Option<usize>,
    repeats: usize,
    mut progress: impl FnMut(&Rung),
) -> Result<WorkPrecision, CompareError> {
    let reference = reference(path, sc)?;
    let methods: Vec<Method> = methods
        .iter()
        .copied()
        .filter(|m| sc.applicable_engines.contains(&m.engine()))
        .collect();
    let mut all = Vec::new();
    for &method in &methods {
        let mut measured: Vec<Rung> = (method.rungs(rungs))
            .iter()
            .map(|&value| {
                let rung = measure(path, sc, &reference.run, method, value, repeats);
                progress(&rung);
                rung
            })
            .collect();
        // The ladder's own convergence: every rung against its finest completed rung.
        if let Some(finest) = measured.iter().rposition(|r| r.summary.is_some()) {
            let (coarser, rest) = measured.split_at_mut(finest);
            let best = rest[0].summary.as_ref();
            for rung in coarser {
                if let (Some(m), Some(run), Some(best)) =
                    (rung.measured.as_mut(), &rung.summary, best)
                {
                    m.errors.self_max_stroke = Some(stroke_error(best, run));
                }
            }
        }
        all.extend(measured);
    }
    Ok(WorkPrecision {
        scenario: sc.file.name.clone(),
        file: path.display().to_string(),
        scenario_sha256: sc.sha256(),
        repeats,
        optimised_build: !cfg!(debug_assertions),
        at_error: at_error(&all, &methods, FIXED_ERROR),
        fixed_error: FIXED_ERROR,
        reference,
        rungs: all,
    })
}

/// A rung's setting as the tables print it.
pub fn setting_label(method: Method, value: f64) -> String {
    match method {
        Method::Report | Method::Strides => format!("÷{value}"),
        Method::Rk4 | Method::Rapier | Method::Mujoco => {
            format!("{:.3} µs", value * 1e6).replace(".000", "")
        }
        Method::Dopri5 => format!("rtol {value:.0e}"),
    }
}

/// A duration, s, in a readable unit.
pub(crate) fn duration(t: f64) -> String {
    if t < 1.0e-3 {
        format!("{:.1} µs", t * 1e6)
    } else if t < 1.0 {
        format!("{:.2} ms", t * 1e3)
    } else {
        format!("{t:.2} s")
    }
}

pub(crate) fn percent(x: f64) -> String {
    format!("{:.3} %", 100.0 * x)
}

/// What the text says of a study's wall times after their description: nothing from an
/// optimised build, that they are not representative from a debug build.
pub(crate) fn build_note(optimised: bool) -> &'static str {
    if optimised {
        ""
    } else {
        " (DEBUG BUILD: not representative; run with `cargo run --release`)"
    }
}

/// The study as a text table.
pub fn text(w: &WorkPrecision) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let r = &w.reference;
    let _ = writeln!(s, "work-precision: {} ({})", w.scenario, w.file);
    let _ = writeln!(
        s,
        "reference: core report, DIST and dt_max ÷{} (DIST {:.3e} m, dt_max {:.3e} s; {} refinements from ÷{}; {} steps, {} force evaluations, {:?}); against the refinement before it: strokes {:.1e} (asked {:.0e}); its resolution of the pitch rate {:.1e}, of the final attitude {:.1e} rad",
        r.divisor,
        r.dist_m,
        r.dt_max_s,
        r.levels,
        REFERENCE_FIRST_DIVISOR,
        r.steps,
        r.force_evaluations,
        r.outcome,
        r.agreement.max_stroke,
        r.asked_max_stroke,
        r.agreement.pitch_rate_rms,
        r.agreement.final_attitude_rad,
    );
    let _ = writeln!(
        s,
        "errors: maximum strokes as a fraction of the reference's largest primary stroke (against the reference; against the method's own finest rung), pitch-rate history RMS as a fraction of its peak, angle between the final attitudes"
    );
    let _ = writeln!(
        s,
        "wall time: one whole landing, median of {} runs{}",
        w.repeats,
        build_note(w.optimised_build)
    );
    let rows = w.rungs.iter().map(|rung| {
        let mut row = vec![
            rung.method.name().to_string(),
            setting_label(rung.method, rung.value),
        ];
        match &rung.measured {
            Some(m) => row.extend([
                m.steps.to_string(),
                m.force_evaluations.to_string(),
                duration(m.wall_time_s),
                percent(m.errors.max_stroke),
                m.errors
                    .self_max_stroke
                    .map(percent)
                    .unwrap_or_else(|| "finest".into()),
                percent(m.errors.pitch_rate_rms),
                format!("{:.1e}", m.errors.final_attitude_rad),
                format!("{:?}", m.outcome),
            ]),
            None => {
                row.extend(std::iter::repeat_n(String::new(), 7));
                row.push(format!(
                    "failed: {}",
                    rung.failure.as_deref().unwrap_or("?")
                ));
            }
        }
        row
    });
    s.push('\n');
    s.push_str(&crate::report::text_table(
        &[
            "method",
            "setting",
            "steps",
            "evaluations",
            "wall time",
            "strokes",
            "own ladder",
            "pitch rate",
            "attitude",
            "outcome",
        ],
        &[1, 2, 3, 4, 5, 6, 7, 8],
        rows,
    ));
    let _ = writeln!(
        s,
        "\nat {} stroke error, the cheapest rung within it: against the reference | against the method's own finest rung",
        percent(w.fixed_error)
    );
    let cell = |v: Option<f64>, t: Option<f64>, ratio: Option<f64>, m: Method| match (v, t, ratio) {
        (Some(v), Some(t), Some(ratio)) => format!(
            "{:>14} {:>11} ×{:<7.1}",
            setting_label(m, v),
            duration(t),
            ratio
        ),
        _ => format!("{:>34}", "no rung within it"),
    };
    for a in &w.at_error {
        let _ = writeln!(
            s,
            "{:<12} {} | {}",
            a.method.name(),
            cell(a.value, a.wall_time_s, a.ratio_to_fastest, a.method),
            cell(
                a.self_value,
                a.self_wall_time_s,
                a.self_ratio_to_fastest,
                a.method
            ),
        );
    }
    s
}
