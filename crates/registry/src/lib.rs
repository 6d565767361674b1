//! The engines in one place, below everything that runs landings (the comparison, the
//! validation tools, the command line): what each engine declares it models (its own crate's
//! `unsupported`), and a scenario landed on the engine asked for, with a typed outcome
//! ([`RunError`]: refused, stopped, set-up failure).

use std::path::Path;
pub use touchdown_record::RunError;
use touchdown_record::{Landing, Observer, Summary};
use touchdown_scenario::model::Mechanism;
pub use touchdown_scenario::schema::Engine;
use touchdown_scenario::{Scenario, ScenarioError};

/// Why `engine` does not model `mechanism`, or `None` if it does: the engine's own declaration.
pub fn unsupported(engine: Engine, mechanism: Mechanism) -> Option<&'static str> {
    match engine {
        Engine::Core => touchdown_core::unsupported(mechanism),
        Engine::Rapier => touchdown_rapier::unsupported(mechanism),
        Engine::Mujoco => touchdown_mujoco::unsupported(mechanism),
    }
}

/// Refuses `engine` for `sc` unless the scenario lists it in `engines.applicable` and the
/// engine models every mechanism the scene declares.
pub fn require(engine: Engine, sc: &Scenario) -> Result<(), ScenarioError> {
    sc.require_engine(engine, |m| unsupported(engine, m))
}

/// The step `engine` lands `sc` with, s: the multibody engines' fixed step, stated or derived
/// from the scenario's scale (docs/engines.md, "Step and contact from the scenario's scale"),
/// or why they refuse it; the core's largest step `integrator.dt_max` (its step adapts below).
pub fn time_step(engine: Engine, sc: &Scenario) -> Result<f64, ScenarioError> {
    match engine {
        Engine::Core => Ok(sc.integrator.dt_max),
        Engine::Rapier => touchdown_multibody::RapierSettings::new(sc).map(|s| s.timestep),
        Engine::Mujoco => touchdown_multibody::MujocoSettings::new(sc).map(|s| s.timestep),
    }
}

/// `sc` landed by `engine` with its step `factor` times finer and nothing else changed: the
/// core's every step limit and its run budget (`Integrator::refine`); a multibody engine's
/// fixed step, with its contact settings stated as [`time_step`]'s derivation gives them at the
/// unrefined step (MuJoCo derives its contact's time constant from the step: a finer step must
/// not stiffen the contact it measures) and its run budget, `integrator.max_steps`, grown by
/// `factor`. What a campaign's accuracy sample lands (docs/campaigns.md, "Accuracy").
pub fn refined(engine: Engine, sc: &Scenario, factor: f64) -> Result<Scenario, ScenarioError> {
    let sc = sc.clone();
    // Settings are stated in the file's units, its [similarity] applied.
    let (time, length) = (sc.units().time(), sc.units().length());
    // A multibody run's budget grows with its steps.
    let budget = |sc: Scenario| sc.with_integrator(|it| it.max_steps *= factor);
    match engine {
        Engine::Core => sc.with_integrator(|it| it.refine(factor)),
        Engine::Rapier => {
            let s = touchdown_multibody::RapierSettings::new(&sc)?;
            budget(sc)?.with_rapier(|r| {
                r.timestep = Some(s.timestep / factor / time);
                r.contact_frequency = Some(s.contact_frequency * time);
            })
        }
        Engine::Mujoco => {
            let s = touchdown_multibody::MujocoSettings::new(&sc)?;
            budget(sc)?.with_mujoco(|m| {
                m.timestep = Some(s.timestep / factor / time);
                m.contact_timeconst = Some(s.contact_timeconst / time);
                m.contact_width = Some(s.contact_width / length);
            })
        }
    }
}

/// A landing that did not complete on an engine, with the scenario file it was read from.
#[derive(Debug, thiserror::Error)]
#[error("{engine} engine on {scenario}: {error}")]
pub struct EngineFailure {
    /// The engine.
    pub engine: Engine,
    /// The scenario file, as given.
    pub scenario: String,
    /// What became of the landing.
    pub error: RunError,
}

/// Lands the scenario `sc` (read from `path`, named in errors; changes made to it after loading
/// apply on every engine) on `engine`. The stepping engines report every accepted state to
/// `observer`; MuJoCo's runner is given the resolved scenario in `out` and writes its
/// `summary.json` and `history.csv` there (with no `out`, it works in a scratch folder removed
/// afterwards and writes no history).
pub fn land<O>(
    engine: Engine,
    path: &Path,
    sc: &Scenario,
    observer: &mut O,
    out: Option<&Path>,
) -> Result<Summary, EngineFailure>
where
    O: Observer<touchdown_core::Simulation> + Observer<touchdown_rapier::RapierSimulation>,
{
    let failure = |error| EngineFailure {
        engine,
        scenario: path.display().to_string(),
        error,
    };
    match engine {
        Engine::Core => touchdown_core::Simulation::new(sc).and_then(|mut s| s.run(observer)),
        Engine::Rapier => {
            touchdown_rapier::RapierSimulation::new(sc).and_then(|mut s| s.run(observer))
        }
        Engine::Mujoco => land_on_mujoco(sc, out, |resolved, dir, history| {
            touchdown_mujoco::Launch::locate()?.run(resolved, dir, history)
        }),
    }
    .map_err(failure)
}

/// A scratch folder for `engine`'s files, removed when dropped.
pub fn scratch_folder(engine: Engine) -> Result<tempfile::TempDir, RunError> {
    tempfile::Builder::new()
        .prefix("touchdown-")
        .tempdir()
        .map_err(|e| RunError::setup(engine, format!("cannot create a scratch folder: {e}")))
}

/// As [`land`], but a MuJoCo landing goes to a runner this thread keeps serving
/// ([`touchdown_mujoco::Worker`]): Python's and MuJoCo's start-up are paid once per
/// thread, not once per landing (a campaign's landings). Results are those of [`land`].
pub fn land_reusing_runner<O>(
    engine: Engine,
    path: &Path,
    sc: &Scenario,
    observer: &mut O,
    out: Option<&Path>,
) -> Result<Summary, EngineFailure>
where
    O: Observer<touchdown_core::Simulation> + Observer<touchdown_rapier::RapierSimulation>,
{
    if engine != Engine::Mujoco {
        return land(engine, path, sc, observer, out);
    }
    land_on_mujoco(sc, out, |resolved, dir, history| {
        MUJOCO_RUNNER.with(|cell| {
            let mut runner = cell.borrow_mut();
            let worker = match runner.as_mut() {
                Some(w) => w,
                None => runner.insert(touchdown_mujoco::Launch::locate()?.worker()?),
            };
            let result = worker.run(resolved, dir, history);
            // A runner that failed outside a landing, or ended on one (a MuJoCo error stops
            // the landing and ends its process), is replaced by the next landing.
            if matches!(result, Err(touchdown_mujoco::MujocoError::Runner(_))) || worker.ended() {
                *runner = None;
            }
            result
        })
    })
    .map_err(|error| EngineFailure {
        engine,
        scenario: path.display().to_string(),
        error,
    })
}

thread_local! {
    /// This thread's serving MuJoCo runner, started by its first MuJoCo landing.
    static MUJOCO_RUNNER: std::cell::RefCell<Option<touchdown_mujoco::Worker>> =
        const { std::cell::RefCell::new(None) };
}

/// Lands `sc` on MuJoCo with `runner` (the resolved scenario's file, the output folder, whether
/// to write the history), in `out` or a scratch folder.
fn land_on_mujoco(
    sc: &Scenario,
    out: Option<&Path>,
    runner: impl FnOnce(&Path, &Path, bool) -> Result<Summary, touchdown_mujoco::MujocoError>,
) -> Result<Summary, RunError> {
    touchdown_mujoco::refusal(sc)?;
    let scratch;
    let dir = match out {
        Some(dir) => dir,
        None => {
            scratch = scratch_folder(Engine::Mujoco)?;
            scratch.path()
        }
    };
    let resolved = dir.join("scenario.resolved.toml");
    std::fs::write(&resolved, sc.to_toml()).map_err(|e| {
        RunError::setup(
            Engine::Mujoco,
            format!("cannot write {}: {e}", resolved.display()),
        )
    })?;
    runner(&resolved, dir, out.is_some())
        .map_err(RunError::from)
        .map_err(|e| match e {
            // A scratch folder's name changes from run to run: a set-up failure names what the
            // file holds instead, so that the same failure reads the same.
            RunError::Setup(mut s) => {
                s.cause = s
                    .cause
                    .replace(&resolved.display().to_string(), "the scenario as resolved");
                RunError::Setup(s)
            }
            e => e,
        })
}

/// The version of what computed a run, from its summary (for the snapshot metadata).
pub fn version(engine: Engine, summary: &Summary) -> String {
    let setting = |key: &str| {
        summary
            .engine_settings
            .get(key)
            .and_then(|v| v.as_str())
            .unwrap_or("?")
            .to_string()
    };
    match engine {
        Engine::Core => format!("touchdown-core {}", env!("CARGO_PKG_VERSION")),
        Engine::Rapier => format!("rapier3d-f64 {}", setting("rapier3d_f64")),
        Engine::Mujoco => format!("mujoco {}", setting("mujoco")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use touchdown_record::Law;

    fn scenario(name: &str) -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../scenarios")
            .join(name)
    }

    #[test]
    fn each_engine_declares_what_it_models() {
        for m in Mechanism::ALL {
            assert_eq!(unsupported(Engine::Core, m), None, "{m:?}");
        }
        for engine in [Engine::Rapier, Engine::Mujoco] {
            for m in [Mechanism::Soil, Mechanism::Slosh, Mechanism::Bending] {
                assert!(unsupported(engine, m).is_some(), "{engine} {m:?}");
            }
            assert_eq!(unsupported(engine, Mechanism::Thrust), None);
        }
    }

    /// A refined multibody run changes the step and the budget, nothing else: the contact is
    /// the one derived at the unrefined step (MuJoCo's time constant is twice that step, not
    /// twice the refined one), in a file that states none of it and in a Froude twin of one
    /// that states all of it; the core's refinement is its integrator's.
    #[test]
    fn a_refined_multibody_run_has_its_step_finer_and_its_contact_unchanged() {
        use touchdown_multibody::{MujocoSettings, RapierSettings};
        let tmp = tempfile::tempdir().unwrap();
        let twin = tmp.path().join("twin.toml");
        let base = scenario("fig-25-26.toml").canonicalize().unwrap();
        std::fs::write(
            &twin,
            format!(
                "extends = {:?}\n[similarity]\nlength = 6.0\nmass = 216.0\ntime = 6.0\n",
                base.display().to_string()
            ),
        )
        .unwrap();
        let derived = Scenario::load(scenario("robotic-lander-nominal.toml")).unwrap();
        let twin = Scenario::load(&twin).unwrap();
        assert!(derived.mujoco.timestep.is_none() && derived.mujoco.contact_timeconst.is_none());
        assert!(twin.mujoco.timestep.is_some() && twin.rapier.contact_frequency.is_some());
        for sc in [derived, twin] {
            let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs();
            let r = RapierSettings::new(&sc).unwrap();
            let fine = refined(Engine::Rapier, &sc, 4.0).unwrap();
            let rf = RapierSettings::new(&fine).unwrap();
            assert!(close(rf.timestep, r.timestep / 4.0), "{rf:?} {r:?}");
            assert!(close(rf.contact_frequency, r.contact_frequency));
            assert_eq!(fine.integrator.max_steps, 4 * sc.integrator.max_steps);
            let m = MujocoSettings::new(&sc).unwrap();
            let mf = MujocoSettings::new(&refined(Engine::Mujoco, &sc, 4.0).unwrap()).unwrap();
            assert!(close(mf.timestep, m.timestep / 4.0), "{mf:?} {m:?}");
            assert!(close(mf.contact_timeconst, m.contact_timeconst));
            assert!(close(mf.contact_width, m.contact_width));
            let core = refined(Engine::Core, &sc, 4.0).unwrap();
            assert!(close(core.integrator.dt_max, sc.integrator.dt_max / 4.0));
            assert_eq!(core.integrator.max_steps, 4 * sc.integrator.max_steps);
        }
    }

    #[test]
    fn outcomes_come_back_as_data() {
        let path = scenario("soil-drop.toml");
        let sc = Scenario::load(&path).unwrap();
        let refused = land(Engine::Rapier, &path, &sc, &mut (), None).unwrap_err();
        match refused.error {
            RunError::Refused(ScenarioError::Field { field, .. }) => {
                assert_eq!(field, "surface.soil")
            }
            other => panic!("expected a refusal, got {other}"),
        }
        let path = scenario("flat-drop.toml");
        let mut sc = Scenario::load(&path).unwrap();
        sc.integrator.max_steps = 100;
        match land(Engine::Core, &path, &sc, &mut (), None).map_err(|f| f.error) {
            Err(RunError::Stopped(d)) => {
                assert_eq!((d.law, d.leg), (Law::RunBudget, None), "{d}");
                assert!(d.time_s > 0.0 && d.state.position_m[2] > 0.0, "{d}");
            }
            other => panic!("expected a stop at the run budget, got {other:?}"),
        }
    }
}
