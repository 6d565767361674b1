//! Shared scenarios through every engine, and how far apart the engines land (docs/engines.md):
//!
//! | module | content |
//! |---|---|
//! | [`trace`] | the time series a comparison needs (vertical velocity, pitch rate), from any engine |
//! | [`metrics`] | divergence of two engines, channel by channel, against written tolerances |
//! | [`report`] | a scenario's comparison as text (rounded for snapshot review) and JSON |
//!
//! An engine's run is its summary plus its trace; every pair of the engines asked for is
//! compared, the first engine of the pair being the reference of its relative channels.

pub mod metrics;
pub mod report;
pub mod trace;

use serde::Serialize;
use std::path::Path;
use touchdown_record::{Landing, Observer, Sample, Summary};
use touchdown_scenario::Scenario;
pub use trace::Trace;

/// An engine of the testbench.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Engine {
    /// The report-faithful core.
    Core,
    /// The rapier multibody rebuild.
    Rapier,
    /// The MuJoCo model driven by the shared laws.
    Mujoco,
}

impl Engine {
    /// Every engine, in comparison order.
    pub const ALL: [Engine; 3] = [Engine::Core, Engine::Rapier, Engine::Mujoco];

    /// The engine's name as on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Engine::Core => "core",
            Engine::Rapier => "rapier",
            Engine::Mujoco => "mujoco",
        }
    }
}

impl std::str::FromStr for Engine {
    type Err = String;
    fn from_str(s: &str) -> Result<Engine, String> {
        Engine::ALL
            .into_iter()
            .find(|e| e.name() == s)
            .ok_or_else(|| format!("unknown engine {s:?}; expected core, rapier or mujoco"))
    }
}

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

/// Runs the scenario at `path` (loaded as `sc`) on `engine`.
pub fn run(engine: Engine, path: &Path, sc: &Scenario) -> Result<EngineRun, CompareError> {
    let fail = |message: String| CompareError::Engine {
        engine: engine.name(),
        scenario: path.display().to_string(),
        message,
    };
    let mut tracer = Tracer(Sample::new(sc.legs.len()), Trace::default());
    let summary = match engine {
        Engine::Core => touchdown_core::Simulation::new(sc)
            .and_then(|mut s| s.run(&mut tracer))
            .map_err(|e| fail(e.to_string()))?,
        Engine::Rapier => touchdown_rapier::RapierSimulation::new(sc)
            .and_then(|mut s| s.run(&mut tracer))
            .map_err(|e| fail(e.to_string()))?,
        Engine::Mujoco => {
            let launch = touchdown_mujoco::Launch::locate().map_err(|e| fail(e.to_string()))?;
            let dir = std::env::temp_dir().join(format!(
                "touchdown-compare-{}-{}",
                std::process::id(),
                path.file_stem().unwrap_or_default().to_string_lossy()
            ));
            let result = launch
                .run(path, None, &dir, true)
                .map_err(|e| fail(e.to_string()))
                .and_then(|summary| {
                    tracer.1 = Trace::from_history(&dir.join("history.csv")).map_err(fail)?;
                    Ok(summary)
                });
            let _ = std::fs::remove_dir_all(&dir);
            result?
        }
    };
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
    /// Each engine and what computed it.
    pub engines: Vec<(Engine, String)>,
    /// Each engine's summary.
    #[serde(skip)]
    pub runs: Vec<EngineRun>,
    /// Every pair, in engine order.
    pub pairs: Vec<metrics::PairComparison>,
}

/// Runs the scenario at `path` on `engines` and compares every pair.
pub fn compare_scenario(
    path: &Path,
    engines: &[Engine],
) -> Result<ScenarioComparison, CompareError> {
    let sc = Scenario::load(path)?;
    let runs = engines
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
        runs,
        pairs,
    })
}
