//! The native half of the Python package `touchdown` (python/touchdown/): a landing on any
//! engine and a campaign's shard, on the Rust crates, with the interpreter's lock released
//! while they run. Errors arrive as Python exceptions carrying the file, field and cause the
//! command line prints.

use pyo3::exceptions::{PyException, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use serde_json::json;
use std::fmt::Display;
use std::path::Path;
use touchdown_campaign::{Campaign, CampaignError, Shard};
use touchdown_compare::CompareError;
use touchdown_record::{History, RunError};
use touchdown_registry::{Engine, EngineFailure};
use touchdown_scenario::{ScenarioBase, ScenarioError};
use touchdown_validation::boundary::{Asked, Request};
use touchdown_validation::ValidationError;

pyo3::create_exception!(
    _native,
    TouchdownError,
    PyException,
    "Every error of touchdown."
);
pyo3::create_exception!(
    _native,
    ScenarioInvalid,
    TouchdownError,
    "A scenario or campaign file (or text) refused: `file`, `field` and `message`."
);
pyo3::create_exception!(
    _native,
    LandingStopped,
    TouchdownError,
    "A landing the engine stopped: `time_s`, `law`, `leg` and `message`."
);
pyo3::create_exception!(
    _native,
    EngineUnavailable,
    TouchdownError,
    "An engine that cannot be set up (MuJoCo without the project's Python environment)."
);

/// The exception of a scenario error, with its file and field as attributes.
fn scenario_error(py: Python<'_>, e: &ScenarioError) -> PyErr {
    if let ScenarioError::Io { file, cause } = e {
        if cause.kind() == std::io::ErrorKind::NotFound {
            let cwd = std::env::current_dir()
                .map(|d| d.display().to_string())
                .unwrap_or_else(|_| "?".into());
            return pyo3::exceptions::PyFileNotFoundError::new_err((
                2,
                format!(
                    "no scenario file {file} (relative paths are from the working directory {cwd}); scenario text is TOML of several lines"
                ),
                file.clone(),
            ));
        }
    }
    let err = ScenarioInvalid::new_err(e.to_string());
    let (file, field, message) = match e {
        ScenarioError::Field {
            file,
            field,
            message,
        } => (file.clone(), Some(field.clone()), message.clone()),
        other => (String::new(), None, other.to_string()),
    };
    let v = err.value(py);
    let _ = v.setattr("file", file);
    let _ = v.setattr("field", field);
    let _ = v.setattr("message", message);
    err
}

/// The exception of an engine's failure.
fn engine_error(py: Python<'_>, f: &EngineFailure) -> PyErr {
    run_error(py, &f.error, f.to_string())
}

/// The exception of a landing that did not complete, with `said` as its text.
fn run_error(py: Python<'_>, e: &RunError, said: String) -> PyErr {
    match e {
        RunError::Refused(e) => scenario_error(py, e),
        RunError::Stopped(d) => {
            let err = LandingStopped::new_err(said);
            let v = err.value(py);
            let _ = v.setattr("time_s", d.time_s);
            let _ = v.setattr("law", d.law.name());
            let _ = v.setattr("leg", d.leg);
            let _ = v.setattr("message", d.message.clone());
            err
        }
        RunError::Setup(_) => EngineUnavailable::new_err(said),
    }
}

/// The exception of a comparison's error.
fn compare_error(py: Python<'_>, e: &CompareError) -> PyErr {
    match e {
        CompareError::Scenario(e) => scenario_error(py, e),
        CompareError::Engine(f) => engine_error(py, f),
        CompareError::Setting {
            argument,
            expected,
            got,
        } => setting_error(argument, expected, got),
        other => TouchdownError::new_err(other.to_string()),
    }
}

/// A setting out of its range as a `ValueError` named by its keyword argument (the command
/// line's `--vh-step` is `vh_step`).
fn setting_error(argument: &str, expected: impl Display, got: impl Display) -> PyErr {
    PyValueError::new_err(format!(
        "{}: expected {expected}, got {got}",
        argument.trim_start_matches("--").replace('-', "_")
    ))
}

/// The exception of a boundary search's error; a setting's is a `ValueError` named by its
/// keyword argument.
fn validation_error(py: Python<'_>, e: &ValidationError) -> PyErr {
    match e {
        ValidationError::Scenario(e) => scenario_error(py, e),
        ValidationError::Run { scenario, source } => {
            run_error(py, source, format!("{scenario}: {source}"))
        }
        ValidationError::Point { source, .. } => TouchdownError::new_err(format!("{e}: {source}")),
        ValidationError::Setting {
            argument,
            expected,
            got,
        } => setting_error(argument, expected, got),
        other => TouchdownError::new_err(other.to_string()),
    }
}

/// The exception of a campaign's error.
fn campaign_error(py: Python<'_>, e: &CampaignError) -> PyErr {
    match e {
        CampaignError::Field {
            file,
            field,
            message,
        } => scenario_error(
            py,
            &ScenarioError::field(file, field.clone(), message.clone()),
        ),
        CampaignError::Engine(f) => engine_error(py, f),
        other => TouchdownError::new_err(other.to_string()),
    }
}

/// What names a scenario given as text in messages.
const TEXT_SOURCE: &str = "<scenario text>";

/// A scenario file, or TOML text; with the name messages give it. A scenario's text spans
/// lines (every key and table starts one), so a string of one line is a path: a missing file
/// is `FileNotFoundError`, never TOML read from the path (docs/python.md).
fn base(scenario: &str) -> Result<(ScenarioBase, &str), ScenarioError> {
    if scenario.contains('\n') {
        Ok((ScenarioBase::from_toml(TEXT_SOURCE, scenario)?, TEXT_SOURCE))
    } else {
        Ok((ScenarioBase::load(scenario)?, scenario))
    }
}

/// A scenario (a path or TOML text) resolved with `values`, and the name messages give it.
fn resolved<'a>(
    scenario: &'a str,
    values: &[(String, toml::Value)],
) -> Result<(touchdown_scenario::Scenario, &'a str), Box<Failed>> {
    base(scenario)
        .and_then(|(b, source)| Ok((b.with(&as_refs(values))?, source)))
        .map_err(|e| Box::new(Failed::Scenario(e)))
}

/// The override of `key`'s value as TOML: a number, a string or a boolean; anything else is a
/// TypeError, a string that is not valid Unicode a ValueError, each naming the override.
fn toml_value(key: &str, v: &Bound<'_, PyAny>) -> PyResult<toml::Value> {
    if let Ok(b) = v.extract::<bool>() {
        return Ok(toml::Value::Boolean(b));
    }
    if let Ok(x) = v.extract::<f64>() {
        return Ok(toml::Value::Float(x));
    }
    if let Ok(s) = v.extract::<String>() {
        return Ok(toml::Value::String(s));
    }
    if v.is_instance_of::<PyString>() {
        return Err(PyValueError::new_err(format!(
            "overrides[{key:?}]: expected a string of valid Unicode, got {} (a lone surrogate)",
            v.repr()?
        )));
    }
    Err(PyTypeError::new_err(format!(
        "overrides[{key:?}]: expected a number, a string or a boolean, got {}",
        v.get_type().name()?
    )))
}

/// The overrides given as a dict, each field path with its value as TOML.
fn override_values(overrides: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<(String, toml::Value)>> {
    let mut values = Vec::new();
    if let Some(d) = overrides {
        for (k, v) in d.iter() {
            let key: String = k.extract().map_err(|_| {
                let repr = k.repr().map(|r| r.to_string()).unwrap_or_default();
                PyTypeError::new_err(format!(
                    "overrides: expected field paths as strings of valid Unicode, got {repr}"
                ))
            })?;
            let value = toml_value(&key, &v)?;
            values.push((key, value));
        }
    }
    Ok(values)
}

/// The overrides as [`ScenarioBase::with`] takes them.
fn as_refs(values: &[(String, toml::Value)]) -> Vec<(&str, toml::Value)> {
    values
        .iter()
        .map(|(k, v)| (k.as_str(), v.clone()))
        .collect()
}

/// The settings of a call's documents, as the command line's: the overrides, then `options`.
fn settings(values: &[(String, toml::Value)], options: serde_json::Value) -> serde_json::Value {
    touchdown_record::document::settings(values.iter().map(|(k, v)| (k.as_str(), v)), options)
}

/// Engines named by the caller.
fn engines(names: Vec<String>) -> PyResult<Vec<Engine>> {
    names
        .iter()
        .map(|n| {
            n.parse()
                .map_err(|e: String| PyValueError::new_err(format!("engines: {e}")))
        })
        .collect()
}

/// Lands `scenario` (a path or TOML text) on `engine` with `overrides` (field path → value in
/// the file's units): the summary as JSON and, with `history`, the history as CSV text; with
/// `rounding`, the summary says what the rounding ensemble found (`touchdown run --rounding`).
#[pyfunction]
#[pyo3(signature = (scenario, engine="core", overrides=None, history=true, rounding=false))]
fn run(
    py: Python<'_>,
    scenario: &str,
    engine: &str,
    overrides: Option<&Bound<'_, PyDict>>,
    history: bool,
    rounding: bool,
) -> PyResult<(String, Option<String>)> {
    let engine: Engine = engine
        .parse()
        .map_err(|e: String| TouchdownError::new_err(format!("engine: {e}")))?;
    let values = override_values(overrides)?;
    let result = py.detach(|| -> Result<(String, Option<String>), Box<Failed>> {
        let (sc, source) = resolved(scenario, &values)?;
        let path = Path::new(source);
        let mut recorder = if history && engine != Engine::Mujoco {
            Some(
                History::to_writer(Vec::new(), sc.legs.len())
                    .map_err(|e| Box::new(Failed::Other(e.to_string())))?,
            )
        } else {
            None
        };
        let summary = touchdown_registry::land(engine, path, &sc, &mut recorder, None)
            .map_err(|f| Box::new(Failed::Engine(f)))?;
        let csv = match recorder {
            Some(h) => Some(
                String::from_utf8(
                    h.into_inner()
                        .map_err(|e| Box::new(Failed::Other(e.to_string())))?,
                )
                .unwrap_or_default(),
            ),
            None => None,
        };
        let determinacy = if rounding {
            Some(
                touchdown_compare::rounding::determinacy(engine, path, &sc)
                    .map_err(|e| Box::new(Failed::Compare(e)))?,
            )
        } else {
            None
        };
        let options = if rounding {
            json!({ "rounding": true })
        } else {
            json!({})
        };
        let id = touchdown_record::ScenarioId::new(source, &sc);
        let document = touchdown_compare::rounding::run_document(
            &summary,
            &id,
            &settings(&values, options),
            determinacy.as_ref(),
        );
        Ok((document, csv))
    });
    result.map_err(|f| f.into_py_err(py))
}

/// Lands `scenario` (a path or TOML text) with `overrides` on each of `engines` and compares
/// every pair as `touchdown compare --format json` does: its line for the scenario.
#[pyfunction]
#[pyo3(signature = (scenario, engines, overrides=None))]
fn compare(
    py: Python<'_>,
    scenario: &str,
    engines: Vec<String>,
    overrides: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    let engines = self::engines(engines)?;
    let values = override_values(overrides)?;
    py.detach(|| -> Result<String, Box<Failed>> {
        let (sc, source) = resolved(scenario, &values)?;
        let set =
            touchdown_compare::engine_set(&engines).map_err(|e| Box::new(Failed::Compare(e)))?;
        let c = touchdown_compare::compare_resolved(Path::new(source), &sc, &set)
            .map_err(|e| Box::new(Failed::Compare(e)))?;
        // The engines as the command line records them: in engine order, each once.
        let settings = settings(&values, json!({ "engines": set }));
        Ok(touchdown_compare::report::json_line(&c, &settings))
    })
    .map_err(|f| f.into_py_err(py))
}

/// The review of `scenario` (a path or TOML text) with `overrides` before it lands, as
/// `touchdown check --format json` prints it (docs/schemas/check.schema.json).
#[pyfunction]
#[pyo3(signature = (scenario, overrides=None))]
fn check(
    py: Python<'_>,
    scenario: &str,
    overrides: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    let values = override_values(overrides)?;
    py.detach(|| -> Result<String, Box<Failed>> {
        let (sc, source) = resolved(scenario, &values)?;
        let review = touchdown_review::review(&sc).map_err(|e| Box::new(Failed::Scenario(e)))?;
        let id = touchdown_record::ScenarioId::new(source, &sc);
        Ok(review.document(&id, &settings(&values, json!({}))))
    })
    .map_err(|f| f.into_py_err(py))
}

/// A landing to watch, as `touchdown view` writes it: `scenario` (a path or TOML text) with
/// `overrides` on each of `engines` that its `engines.applicable` lists, a frame every
/// `frame_interval` s; the trajectory document (JSON) and the page that plays it (HTML).
#[pyfunction]
#[pyo3(signature = (scenario, engines, frame_interval, overrides=None))]
fn view(
    py: Python<'_>,
    scenario: &str,
    engines: Vec<String>,
    frame_interval: f64,
    overrides: Option<&Bound<'_, PyDict>>,
) -> PyResult<(String, String)> {
    let engines = self::engines(engines)?;
    let values = override_values(overrides)?;
    py.detach(|| -> Result<(String, String), Box<Failed>> {
        let (sc, source) = resolved(scenario, &values)?;
        let path = Path::new(source);
        let (runs, _) = touchdown_compare::watch(path, &sc, &engines, frame_interval)
            .map_err(|e| Box::new(Failed::Compare(e)))?;
        let overrides = values.iter().map(|(k, v)| (k.as_str(), v));
        Ok(touchdown_compare::trajectory_files(
            path,
            &sc,
            &runs,
            overrides,
            frame_interval,
        ))
    })
    .map_err(|f| f.into_py_err(py))
}

/// The stability-boundary search of `scenario` (a path or TOML text) with `overrides`, as
/// `touchdown boundary --format json` does: at each vertical velocity of `vv` (negative down,
/// as in the scenario files, the scenario's velocity unit), on each of `engines`, scanned
/// every `scan_step` around the changes (0: the grid only), once per end-stop restitution of
/// `stop_restitution` (empty: the scenario's own); a setting that is `None` takes the
/// command's default, a ratio of the vehicle's velocity scale; the points as the command's
/// JSON Lines.
#[pyfunction]
#[pyo3(signature = (scenario, vv, vh_start, vh_step, vh_max, tol, engines, overrides=None, scan_step=None, stop_restitution=Vec::new()))]
#[allow(clippy::too_many_arguments)]
fn boundary(
    py: Python<'_>,
    scenario: &str,
    vv: Vec<f64>,
    vh_start: Option<f64>,
    vh_step: Option<f64>,
    vh_max: Option<f64>,
    tol: Option<f64>,
    engines: Vec<String>,
    overrides: Option<&Bound<'_, PyDict>>,
    scan_step: Option<f64>,
    stop_restitution: Vec<f64>,
) -> PyResult<Vec<String>> {
    let engines = self::engines(engines)?;
    let values = override_values(overrides)?;
    let asked = Asked {
        vh_start,
        vh_step,
        vh_max,
        tolerance: tol,
        scan_step,
    };
    py.detach(|| -> Result<Vec<String>, Box<Failed>> {
        let (b, _) = base(scenario).map_err(|e| Box::new(Failed::Scenario(e)))?;
        let overrides = as_refs(&values);
        let boundary = |e| Box::new(Failed::Boundary(e));
        let study = Request {
            base: &b,
            overrides: &overrides,
            vv: &vv,
            vv_argument: "vv",
            asked,
            engines: &engines,
            restitutions: &stop_restitution,
        }
        .resolve()
        .map_err(boundary)?;
        let points = study.run(&|| (), &|_| ()).map_err(boundary)?;
        let (id, settings) = (study.scenario_id(), study.document_settings());
        Ok(points
            .iter()
            .map(|p| study.document_line(p, &id, &settings))
            .collect())
    })
    .map_err(|f| f.into_py_err(py))
}

/// Runs shard `k` of `n` of the campaign file `campaign` into `out_dir` exactly as
/// `touchdown campaign CAMPAIGN --shard K/N --out OUT_DIR [--resume]` does; returns `out_dir`.
#[pyfunction]
#[pyo3(signature = (campaign, k, n, out_dir, resume = false))]
fn run_shard(
    py: Python<'_>,
    campaign: &str,
    k: u64,
    n: u64,
    out_dir: &str,
    resume: bool,
) -> PyResult<String> {
    let shard = shard(k, n)?;
    py.detach(|| {
        let c = Campaign::load(campaign)?;
        let out = Some(Path::new(out_dir));
        touchdown_campaign::run::run(&c, Some(shard), None, out, resume, |_| ()).map(|_| ())
    })
    .map_err(|e| campaign_error(py, &e))?;
    Ok(out_dir.to_string())
}

/// Shard `k` of `n`, checked as `--shard K/N` is.
fn shard(k: u64, n: u64) -> PyResult<Shard> {
    format!("{k}/{n}")
        .parse()
        .map_err(|e: String| TouchdownError::new_err(format!("shard: {e}")))
}

/// Whether `dir` holds shard `k` of `n` of the campaign file `campaign`, finished by this build:
/// what a scheduler of shards counts as done (a folder of another campaign, or of the campaign
/// before an edit, is not).
#[pyfunction]
fn holds_shard(py: Python<'_>, campaign: &str, k: u64, n: u64, dir: &str) -> PyResult<bool> {
    let shard = shard(k, n)?;
    py.detach(|| {
        let c = Campaign::load(campaign)?;
        touchdown_campaign::run::holds_part(&c, Some(shard), Path::new(dir))
    })
    .map_err(|e| campaign_error(py, &e))
}

/// Merges the campaign folders `parts` into `out_dir` exactly as `touchdown campaign merge`
/// does (refusing parts of other campaigns, builds or base scenarios, gaps and overlaps);
/// returns `out_dir`.
#[pyfunction]
fn merge(py: Python<'_>, parts: Vec<String>, out_dir: &str) -> PyResult<String> {
    py.detach(|| {
        let parts: Vec<&Path> = parts.iter().map(Path::new).collect();
        touchdown_campaign::merge(&parts, Path::new(out_dir), |_| ()).map(|_| ())
    })
    .map_err(|e| campaign_error(py, &e))?;
    Ok(out_dir.to_string())
}

/// What failed inside a call that released the interpreter's lock.
enum Failed {
    Scenario(ScenarioError),
    Engine(EngineFailure),
    Compare(CompareError),
    Boundary(ValidationError),
    Other(String),
}

impl Failed {
    fn into_py_err(self, py: Python<'_>) -> PyErr {
        match self {
            Failed::Scenario(e) => scenario_error(py, &e),
            Failed::Engine(f) => engine_error(py, &f),
            Failed::Compare(e) => compare_error(py, &e),
            Failed::Boundary(e) => validation_error(py, &e),
            Failed::Other(m) => TouchdownError::new_err(m),
        }
    }
}

/// The native module `touchdown._native`.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add_function(wrap_pyfunction!(compare, m)?)?;
    m.add_function(wrap_pyfunction!(check, m)?)?;
    m.add_function(wrap_pyfunction!(view, m)?)?;
    m.add_function(wrap_pyfunction!(boundary, m)?)?;
    m.add_function(wrap_pyfunction!(run_shard, m)?)?;
    m.add_function(wrap_pyfunction!(holds_shard, m)?)?;
    m.add_function(wrap_pyfunction!(merge, m)?)?;
    m.add("TouchdownError", py.get_type::<TouchdownError>())?;
    m.add("ScenarioInvalid", py.get_type::<ScenarioInvalid>())?;
    m.add("LandingStopped", py.get_type::<LandingStopped>())?;
    m.add("EngineUnavailable", py.get_type::<EngineUnavailable>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
