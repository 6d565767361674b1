//! Shared scenarios through every engine, and how far apart the engines land (docs/engines.md):
//!
//! | module | content |
//! |---|---|
//! | [`trace`] | the time series a comparison needs (vertical velocity, pitch rate), from any engine |
//! | [`metrics`] | divergence of two engines, channel by channel, against written tolerances |
//! | [`pair`] | two engines' runs of a landing compared over their rounding ensembles: each channel's verdict and the pair's |
//! | [`report`] | a scenario's comparison as text (rounded for snapshot review) and JSON |
//! | [`rounding`] | each landing again with its touchdown velocity moved by a unit in the last place: the verdicts rounding decides |
//! | [`plot`] | the traces behind the metrics, as CSV for `python/figures/plot_compare.py` |
//! | [`robustness`] | the stiff and extreme catalogue: every case on every engine, classified; the largest stable steps |
//! | [`precision`] | work-precision: every engine and scheme over a ladder of steps or tolerances against a converged reference |
//!
//! An engine's run is its summary plus its trace; every pair of the engines asked for is
//! compared, the first engine of the pair being the reference of its relative channels.

pub mod metrics;
pub mod pair;
pub mod plot;
pub mod precision;
pub mod report;
pub mod robustness;
pub mod rounding;
pub mod trace;

use rayon::prelude::*;
use serde::Serialize;
use std::path::Path;
use touchdown_record::{Landing, Observer, Sample, Summary};
use touchdown_registry::land;
pub use touchdown_registry::{Engine, EngineFailure};
use touchdown_scenario::Scenario;
use touchdown_view::{EngineTrajectory, Recorder, Recording, Scene, Trajectory};
pub use trace::Trace;

/// Errors of a comparison: a scenario that does not load, an engine that did not complete it.
#[derive(Debug, thiserror::Error)]
pub enum CompareError {
    /// The scenario does not load.
    #[error(transparent)]
    Scenario(#[from] touchdown_scenario::ScenarioError),
    /// An engine did not complete the scenario (refused, stopped, not set up).
    #[error(transparent)]
    Engine(#[from] EngineFailure),
    /// The precision study found no converged reference on the core.
    #[error("core engine on {scenario}: {message}")]
    Unconverged {
        /// The scenario file.
        scenario: String,
        /// How far apart the last refinements landed.
        message: String,
    },
    /// Fewer than two distinct engines asked for.
    #[error("name at least two engines to compare (got {})", if .0.is_empty() { "none".to_string() } else { names(.0) })]
    TooFewEngines(Vec<Engine>),
    /// A setting out of its range, named as the command line names it (`--frame-interval`).
    #[error("{argument}: expected {expected}, got {got}")]
    Setting {
        /// The command line's argument.
        argument: &'static str,
        /// What it takes.
        expected: &'static str,
        /// The value given.
        got: f64,
    },
    /// None of the engines asked for applies to the scenario.
    #[error("none of the engines asked for ({}) applies to {scenario} (its engines.applicable: {})", names(.asked), names(.applicable))]
    NoneApplicable {
        /// The scenario file.
        scenario: String,
        /// The engines asked for.
        asked: Vec<Engine>,
        /// The scenario's `engines.applicable`.
        applicable: Vec<Engine>,
    },
    /// An engine's trace could not be read back.
    #[error("{engine} engine on {scenario}: {message}")]
    Trace {
        /// The engine.
        engine: Engine,
        /// The scenario file.
        scenario: String,
        /// What is wrong with the trace.
        message: String,
    },
}

/// One engine's run of a landing.
#[derive(Debug, Clone, PartialEq)]
pub struct EngineRun {
    /// The engine.
    pub engine: Engine,
    /// Its summary.
    pub summary: Summary,
    /// Its trace.
    pub trace: Trace,
    /// What its channels are judged against: the vehicle's scales and the tolerances.
    pub basis: metrics::Basis,
    /// Its frames for a viewer, when asked for ([`run_recorded`]).
    pub recording: Option<Recording>,
    /// The same engine's runs of the landing's perturbed copies ([`rounding::perturbed`]): the
    /// rest of its rounding ensemble (empty for a run alone).
    pub perturbed: Vec<EngineRun>,
}

impl EngineRun {
    /// The run itself, then its perturbed copies.
    pub fn members(&self) -> Vec<&EngineRun> {
        std::iter::once(self).chain(&self.perturbed).collect()
    }

    /// Whether the run and its perturbed copies have one outcome.
    pub fn outcome_determined(&self) -> bool {
        self.perturbed
            .iter()
            .all(|r| r.summary.outcome == self.summary.outcome)
    }
}

/// Collects a trace, and the frames for a viewer if asked, from any stepping engine.
struct Tracer {
    sample: Sample,
    sink: Sink,
}

/// Where a run's samples go: the trace, and the recorder when asked for.
struct Sink {
    trace: Trace,
    recorder: Option<Recorder>,
}

impl Sink {
    fn push(&mut self, s: &Sample) {
        self.trace.push(s);
        if let Some(r) = &mut self.recorder {
            r.push(s);
        }
    }
}

impl<L: Landing> Observer<L> for Tracer {
    fn observe(&mut self, landing: &L) {
        landing.sample(&mut self.sample);
        self.sink.push(&self.sample);
    }
}

/// Runs the scenario `sc` (read from `path`, named in errors) on `engine`, with its trace.
pub fn run(engine: Engine, path: &Path, sc: &Scenario) -> Result<EngineRun, CompareError> {
    run_recorded(engine, path, sc, None)
}

/// [`run`], also recording the frames of a trajectory file when `frame_interval` (s between
/// kept frames, [`touchdown_view::Recorder`]) is given.
pub fn run_recorded(
    engine: Engine,
    path: &Path,
    sc: &Scenario,
    frame_interval: Option<f64>,
) -> Result<EngineRun, CompareError> {
    let failure = |error| EngineFailure {
        engine,
        scenario: path.display().to_string(),
        error,
    };
    let basis = metrics::Basis::of(sc)?;
    let scratch = touchdown_registry::scratch_folder(engine).map_err(failure)?;
    let mut tracer = Tracer {
        sample: Sample::new(sc.legs.len()),
        sink: Sink {
            trace: Trace::new(basis.acceleration_window_s()),
            recorder: frame_interval.map(|dt| Recorder::new(sc, dt)),
        },
    };
    let summary = land(engine, path, sc, &mut tracer, Some(scratch.path()))?;
    if engine == Engine::Mujoco {
        // The runner wrote its history outside this process: its rows are the samples.
        touchdown_record::history::read(&scratch.path().join("history.csv"), |s| {
            tracer.sink.push(s)
        })
        .map_err(|e| CompareError::Trace {
            engine,
            scenario: path.display().to_string(),
            message: e.to_string(),
        })?;
    }
    Ok(EngineRun {
        engine,
        summary,
        trace: tracer.sink.trace,
        basis,
        recording: tracer.sink.recorder.map(Recorder::finish),
        perturbed: Vec::new(),
    })
}

/// [`run_recorded`], with the rounding ensemble: the scenario's perturbed copies
/// ([`rounding::perturbed`]) land on the same engine too, in parallel (collected in order: the
/// same result whatever the thread count), into [`EngineRun::perturbed`]; only the landing as
/// given records frames.
pub fn run_ensemble(
    engine: Engine,
    path: &Path,
    sc: &Scenario,
    frame_interval: Option<f64>,
) -> Result<EngineRun, CompareError> {
    let copies = rounding::perturbed(sc)?;
    let landings: Vec<(&Scenario, Option<f64>)> = std::iter::once((sc, frame_interval))
        .chain(copies.iter().map(|c| (c, None)))
        .collect();
    let mut runs = first_error_in_order(
        landings
            .par_iter()
            .map(|(s, frames)| run_recorded(engine, path, s, *frames))
            .collect(),
    )?;
    let mut run = runs.remove(0);
    run.perturbed = runs;
    Ok(run)
}

/// The results of runs made in parallel, in their order, or the error of the first that
/// failed in that order (not whichever thread failed first): the same error whatever the thread
/// count.
fn first_error_in_order<T>(results: Vec<Result<T, CompareError>>) -> Result<Vec<T>, CompareError> {
    results.into_iter().collect()
}

/// Checks the time between a trajectory's frames, s.
fn check_frame_interval(frame_interval: f64) -> Result<(), CompareError> {
    if frame_interval.is_finite() && frame_interval > 0.0 {
        return Ok(());
    }
    Err(CompareError::Setting {
        argument: "--frame-interval",
        expected: "a time between frames > 0 s",
        got: frame_interval,
    })
}

/// `engines` split into those the scenario's `engines.applicable` lists and the others, in the
/// order given.
fn split_applicable(sc: &Scenario, engines: &[Engine]) -> (Vec<Engine>, Vec<Engine>) {
    engines
        .iter()
        .partition(|e| sc.applicable_engines.contains(e))
}

/// Engine names, comma-separated.
fn names(engines: &[Engine]) -> String {
    engines
        .iter()
        .map(|e| e.name())
        .collect::<Vec<_>>()
        .join(",")
}

/// A landing to watch (`touchdown view`): `sc` on each of `engines` it applies to, in engine
/// order, each run recording its frames every `frame_interval` s; with the engines left out
/// because the scenario's `engines.applicable` does not list them.
pub fn watch(
    path: &Path,
    sc: &Scenario,
    engines: &[Engine],
    frame_interval: f64,
) -> Result<(Vec<EngineRun>, Vec<Engine>), CompareError> {
    check_frame_interval(frame_interval)?;
    let mut asked = engines.to_vec();
    asked.sort();
    asked.dedup();
    let (run, skipped) = split_applicable(sc, &asked);
    if run.is_empty() {
        return Err(CompareError::NoneApplicable {
            scenario: path.display().to_string(),
            asked: skipped,
            applicable: sc.applicable_engines.clone(),
        });
    }
    let runs = run
        .iter()
        .map(|&e| run_recorded(e, path, sc, Some(frame_interval)))
        .collect::<Result<Vec<_>, _>>()?;
    Ok((runs, skipped))
}

/// The trajectory file of the runs of the scenario at `path`, which recorded their frames every
/// `frame_interval` s (`touchdown.trajectory/1`, on one line; its settings: the `overrides`
/// that resolved `sc`, the engines that ran and the frame interval), and the page that plays
/// it.
pub fn trajectory_files<'v>(
    path: &Path,
    sc: &Scenario,
    runs: &[EngineRun],
    overrides: impl IntoIterator<Item = (&'v str, &'v toml::Value)>,
    frame_interval: f64,
) -> (String, String) {
    let engines: Vec<Engine> = runs.iter().map(|r| r.engine).collect();
    let options = serde_json::json!({ "engines": engines, "frame_interval_s": frame_interval });
    let settings = touchdown_record::document::settings(overrides, options);
    let body = trajectory(sc, runs);
    let id = touchdown_record::ScenarioId::new(path.display(), sc);
    let json = touchdown_record::Document::new("trajectory", Some(&id), &settings, &body).line();
    let title = format!("{}: touchdown view", sc.file.name);
    let html = touchdown_view::page(&title, &json);
    (json, html)
}

/// The trajectory document's body of the runs of `sc` that recorded their frames
/// ([`run_recorded`]), in the order given.
pub fn trajectory<'a>(sc: &Scenario, runs: &'a [EngineRun]) -> Trajectory<'a> {
    Trajectory {
        scene: Scene::new(sc),
        engines: runs
            .iter()
            .filter_map(|r| {
                Some(EngineTrajectory::new(
                    r.engine,
                    engine_version(r),
                    &r.summary,
                    r.recording.as_ref()?,
                ))
            })
            .collect(),
    }
}

/// The version of what computed a run (for the snapshot metadata).
pub fn engine_version(run: &EngineRun) -> String {
    touchdown_registry::version(run.engine, &run.summary)
}

/// A scenario through several engines, every pair compared. Serialised as the fields of its
/// document after the envelope, which names the file and the hash ([`report::json_line`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ScenarioComparison {
    /// Scenario name.
    #[serde(rename = "scenario_name")]
    pub scenario: String,
    /// Scenario file.
    #[serde(skip)]
    pub file: String,
    /// SHA-256 of the resolved scenario.
    #[serde(skip)]
    pub scenario_sha256: String,
    /// Each engine run and what computed it (`{"name", "version"}` in the JSON).
    #[serde(serialize_with = "engine_versions")]
    pub engines: Vec<(Engine, String)>,
    /// Engines asked for that the scenario's `engines.applicable` leaves out (not run).
    pub not_applicable: Vec<Engine>,
    /// The vehicle's scales, which the tolerances not of a channel's own value are ratios of.
    pub scales: touchdown_scenario::scales::Scales,
    /// The window the vertical accelerations are averaged over
    /// ([`metrics::Basis::acceleration_window_s`]), s.
    pub acceleration_window_s: f64,
    /// Each engine's summary.
    #[serde(skip)]
    pub runs: Vec<EngineRun>,
    /// Every pair, in engine order.
    pub pairs: Vec<metrics::PairComparison>,
}

/// The engines that ran as `[{"name": "core", "version": ...}]`.
fn engine_versions<S: serde::Serializer>(
    engines: &[(Engine, String)],
    s: S,
) -> Result<S::Ok, S::Error> {
    use serde::ser::SerializeSeq;
    let mut seq = s.serialize_seq(Some(engines.len()))?;
    for (name, version) in engines {
        seq.serialize_element(&serde_json::json!({ "name": name, "version": version }))?;
    }
    seq.end()
}

/// The engines of a comparison: `engines` in engine order, each once; at least two.
pub fn engine_set(engines: &[Engine]) -> Result<Vec<Engine>, CompareError> {
    let mut set = engines.to_vec();
    set.sort();
    set.dedup();
    if set.len() < 2 {
        return Err(CompareError::TooFewEngines(set));
    }
    Ok(set)
}

/// Runs the scenario at `path` on those of `engines` that apply to it (`engines.applicable`)
/// and compares every pair.
pub fn compare_scenario(
    path: &Path,
    engines: &[Engine],
) -> Result<ScenarioComparison, CompareError> {
    compare_resolved(path, &Scenario::load(path)?, engines)
}

/// [`compare_scenario`] of a scenario already resolved (with overrides, or read from text);
/// `path` names it in the report and in errors.
pub fn compare_resolved(
    path: &Path,
    sc: &Scenario,
    engines: &[Engine],
) -> Result<ScenarioComparison, CompareError> {
    compare_recorded(path, sc, engines, None)
}

/// [`compare_resolved`], each run also recording the frames of a trajectory file when
/// `frame_interval` is given ([`run_recorded`], [`trajectory`]).
pub fn compare_recorded(
    path: &Path,
    sc: &Scenario,
    engines: &[Engine],
    frame_interval: Option<f64>,
) -> Result<ScenarioComparison, CompareError> {
    if let Some(f) = frame_interval {
        check_frame_interval(f)?;
    }
    let basis = metrics::Basis::of(sc)?;
    let (applicable, not_applicable) = split_applicable(sc, engines);
    // The engines land side by side (each with its ensemble in parallel too), collected in
    // the order given: the same comparison, and the same error, whatever the thread count.
    let runs = first_error_in_order(
        applicable
            .par_iter()
            .map(|e| run_ensemble(*e, path, sc, frame_interval))
            .collect(),
    )?;
    let mut pairs = Vec::new();
    for (i, a) in runs.iter().enumerate() {
        for b in &runs[i + 1..] {
            pairs.push(pair::compare(a, b));
        }
    }
    Ok(ScenarioComparison {
        scenario: sc.file.name.clone(),
        file: path.display().to_string(),
        scenario_sha256: sc.sha256(),
        engines: runs.iter().map(|r| (r.engine, engine_version(r))).collect(),
        not_applicable,
        scales: basis.scales,
        acceleration_window_s: basis.acceleration_window_s(),
        runs,
        pairs,
    })
}
