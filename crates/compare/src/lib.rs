//! Shared scenarios through every engine, and how far apart the engines land (docs/engines.md):
//!
//! | module | content |
//! |---|---|
//! | [`trace`] | the time series a comparison needs (vertical velocity, pitch rate), from any engine |
//! | [`metrics`] | divergence of two engines, channel by channel, against written tolerances |
//! | [`report`] | a scenario's comparison as text (rounded for snapshot review) and JSON |
//! | [`plot`] | the traces behind the metrics, as CSV for `python/plot_compare.py` |
//! | [`robustness`] | the stiff and extreme catalogue: every case on every engine, classified; the largest stable steps |
//! | [`precision`] | work-precision: every engine and scheme over a ladder of steps or tolerances against a converged reference |
//!
//! An engine's run is its summary plus its trace; every pair of the engines asked for is
//! compared, the first engine of the pair being the reference of its relative channels.

pub mod metrics;
pub mod plot;
pub mod precision;
pub mod report;
pub mod robustness;
pub mod trace;

use serde::Serialize;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use touchdown_record::{Landing, Observer, Sample, Summary};
pub use touchdown_scenario::schema::Engine;
use touchdown_scenario::Scenario;
pub use trace::Trace;

/// Errors of a comparison: an engine that failed on a scenario.
#[derive(Debug, thiserror::Error)]
pub enum CompareError {
    /// The scenario does not load.
    #[error(transparent)]
    Scenario(#[from] touchdown_scenario::ScenarioError),
    /// An engine failed or diverged on the scenario.
    #[error("{engine} engine on {scenario}: {message}")]
    Engine {
        /// The engine.
        engine: &'static str,
        /// The scenario file.
        scenario: String,
        /// Its error.
        message: String,
    },
}

impl CompareError {
    fn engine(engine: Engine, path: &Path, message: String) -> CompareError {
        CompareError::Engine {
            engine: engine.name(),
            scenario: path.display().to_string(),
            message,
        }
    }
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
}

/// Collects a trace from any stepping engine.
struct Tracer(Sample, Trace);

impl<L: Landing> Observer<L> for Tracer {
    fn observe(&mut self, landing: &L) {
        landing.sample(&mut self.0);
        self.1.push(&self.0);
    }
}

/// A scratch folder for a run's files, removed when dropped; unique within the process.
#[derive(Debug)]
pub struct ScratchDir(PathBuf);

impl ScratchDir {
    /// Creates a fresh folder under the system's temporary folder.
    pub fn new() -> std::io::Result<ScratchDir> {
        static DIRS: AtomicUsize = AtomicUsize::new(0);
        let dir = std::env::temp_dir().join(format!(
            "touchdown-{}-{}",
            std::process::id(),
            DIRS.fetch_add(1, Ordering::Relaxed)
        ));
        std::fs::create_dir_all(&dir)?;
        Ok(ScratchDir(dir))
    }

    /// The folder.
    pub fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for ScratchDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Lands the scenario `sc` (read from `path`, named in errors; changes made to it after loading
/// apply on every engine) on `engine`. The stepping engines report every accepted state to
/// `observer`; MuJoCo's runner is given the resolved scenario in `out` and writes its
/// `summary.json` and `history.csv` there (with no `out`, it works in a scratch folder and
/// writes no history).
pub fn land<O>(
    engine: Engine,
    path: &Path,
    sc: &Scenario,
    observer: &mut O,
    out: Option<&Path>,
) -> Result<Summary, CompareError>
where
    O: Observer<touchdown_core::Simulation> + Observer<touchdown_rapier::RapierSimulation>,
{
    let fail = |message| CompareError::engine(engine, path, message);
    match engine {
        Engine::Core => touchdown_core::Simulation::new(sc)
            .and_then(|mut s| s.run(observer))
            .map_err(|e| fail(e.to_string())),
        Engine::Rapier => touchdown_rapier::RapierSimulation::new(sc)
            .and_then(|mut s| s.run(observer))
            .map_err(|e| fail(e.to_string())),
        Engine::Mujoco => {
            let launch = touchdown_mujoco::Launch::locate().map_err(|e| fail(e.to_string()))?;
            let scratch;
            let dir = match out {
                Some(dir) => dir,
                None => {
                    scratch = ScratchDir::new()
                        .map_err(|e| fail(format!("cannot create a scratch folder: {e}")))?;
                    scratch.path()
                }
            };
            let resolved = dir.join("scenario.resolved.toml");
            std::fs::write(&resolved, sc.to_toml())
                .map_err(|e| fail(format!("cannot write {}: {e}", resolved.display())))?;
            launch.run(&resolved, dir, out.is_some()).map_err(|e| {
                // A scratch folder's name changes from run to run: the error names what the
                // file holds instead, so that the same failure reads the same.
                let message = e.to_string();
                fail(message.replace(&resolved.display().to_string(), "the scenario as resolved"))
            })
        }
    }
}

/// Runs the scenario `sc` (read from `path`, named in errors) on `engine`, with its trace.
pub fn run(engine: Engine, path: &Path, sc: &Scenario) -> Result<EngineRun, CompareError> {
    let fail = |message| CompareError::engine(engine, path, message);
    let scratch =
        ScratchDir::new().map_err(|e| fail(format!("cannot create a scratch folder: {e}")))?;
    let mut tracer = Tracer(Sample::new(sc.legs.len()), Trace::default());
    let summary = land(engine, path, sc, &mut tracer, Some(scratch.path()))?;
    if engine == Engine::Mujoco {
        tracer.1 = Trace::from_history(&scratch.path().join("history.csv")).map_err(fail)?;
    }
    Ok(EngineRun {
        engine,
        summary,
        trace: tracer.1,
    })
}

/// The version of what computed a run (for the snapshot metadata).
pub fn engine_version(run: &EngineRun) -> String {
    let setting = |key: &str| {
        run.summary
            .engine_settings
            .get(key)
            .and_then(|v| v.as_str())
            .unwrap_or("?")
            .to_string()
    };
    match run.engine {
        Engine::Core => format!("touchdown-core {}", env!("CARGO_PKG_VERSION")),
        Engine::Rapier => format!("rapier3d-f64 {}", setting("rapier3d_f64")),
        Engine::Mujoco => format!("mujoco {}", setting("mujoco")),
    }
}

/// A scenario through several engines, every pair compared.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ScenarioComparison {
    /// Scenario name.
    pub scenario: String,
    /// Scenario file.
    pub file: String,
    /// SHA-256 of the resolved scenario.
    pub scenario_sha256: String,
    /// Each engine run and what computed it.
    pub engines: Vec<(Engine, String)>,
    /// Engines asked for that the scenario's `engines.applicable` leaves out (not run).
    pub not_applicable: Vec<Engine>,
    /// Each engine's summary.
    #[serde(skip)]
    pub runs: Vec<EngineRun>,
    /// Every pair, in engine order.
    pub pairs: Vec<metrics::PairComparison>,
}

/// Runs the scenario at `path` on those of `engines` that apply to it (`engines.applicable`)
/// and compares every pair.
pub fn compare_scenario(
    path: &Path,
    engines: &[Engine],
) -> Result<ScenarioComparison, CompareError> {
    let sc = Scenario::load(path)?;
    let (applicable, not_applicable): (Vec<Engine>, Vec<Engine>) = engines
        .iter()
        .partition(|e| sc.applicable_engines.contains(e));
    let runs = applicable
        .iter()
        .map(|e| run(*e, path, &sc))
        .collect::<Result<Vec<_>, _>>()?;
    let mut pairs = Vec::new();
    for (i, a) in runs.iter().enumerate() {
        for b in &runs[i + 1..] {
            pairs.push(metrics::compare(a, b));
        }
    }
    Ok(ScenarioComparison {
        scenario: sc.file.name.clone(),
        file: path.display().to_string(),
        scenario_sha256: sc.sha256(),
        engines: runs.iter().map(|r| (r.engine, engine_version(r))).collect(),
        not_applicable,
        runs,
        pairs,
    })
}
