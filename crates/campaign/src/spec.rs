//! The campaign file (TOML, docs/campaigns.md): a base scenario, the dispersed fields with
//! their distributions and units, correlations between named pairs, the number of landings,
//! the seed, the engine and what to record; read through the scenario schema's strict reader,
//! every error naming the file and the field.

use crate::distribution::{Distribution, Value};
use crate::CampaignError;
use nalgebra::DMatrix;
use serde::Deserialize;
use std::path::{Path, PathBuf};
use touchdown_scenario::schema::Engine;
use touchdown_scenario::{Scenario, ScenarioBase};

/// The campaign file format's version.
pub const SCHEMA_VERSION: u32 = 1;

/// Most landings a campaign may plan (a budget: 10⁹ landings is weeks of one machine).
pub const MAX_LANDINGS: u64 = 1_000_000_000;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct CampaignFile {
    schema_version: u32,
    name: String,
    #[serde(default)]
    description: String,
    scenario: String,
    #[serde(default)]
    engine: Option<Engine>,
    #[serde(default)]
    engines: Option<Vec<Engine>>,
    landings: u64,
    seed: u64,
    #[serde(default = "default_confidence")]
    confidence: f64,
    #[serde(default)]
    record: RecordFile,
    #[serde(default)]
    accuracy: AccuracyFile,
    #[serde(default, rename = "dispersion")]
    dispersions: Vec<DispersionFile>,
    #[serde(default, rename = "correlation")]
    correlations: Vec<CorrelationFile>,
}

fn default_confidence() -> f64 {
    0.95
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RecordFile {
    /// Landings whose time history is written (`histories/landing-N.csv`).
    #[serde(default)]
    histories: Vec<u64>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct AccuracyFile {
    /// Landings of the accuracy sample (docs/campaigns.md, "Accuracy").
    #[serde(default)]
    landings: Option<u64>,
}

#[derive(Debug, Deserialize)]
#[serde(tag = "distribution", rename_all = "snake_case", deny_unknown_fields)]
enum DispersionFile {
    Normal {
        field: String,
        unit: String,
        mean: f64,
        std_dev: f64,
    },
    TruncatedNormal {
        field: String,
        unit: String,
        mean: f64,
        std_dev: f64,
        min: f64,
        max: f64,
    },
    Uniform {
        field: String,
        unit: String,
        min: f64,
        max: f64,
    },
    LogNormal {
        field: String,
        unit: String,
        median: f64,
        log_std_dev: f64,
    },
    Choice {
        field: String,
        #[serde(default)]
        unit: Option<String>,
        values: Vec<toml::Value>,
        #[serde(default)]
        weights: Vec<f64>,
    },
    List {
        field: String,
        #[serde(default)]
        unit: Option<String>,
        values: Vec<toml::Value>,
    },
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct CorrelationFile {
    fields: [String; 2],
    coefficient: f64,
}

/// One dispersed field.
#[derive(Debug, Clone, PartialEq)]
pub struct Dispersion {
    /// The scenario field path, e.g. `touchdown.attitude[2]`.
    pub field: String,
    /// The unit its values are written in (the scenario's), as written; `None` for text.
    pub unit: Option<String>,
    /// The column name of its applied value: the field, then the unit as a suffix
    /// (`touchdown.vertical_velocity_ft_s`).
    pub column: String,
    /// Its distribution, in the scenario file's units.
    pub distribution: Distribution,
}

/// A campaign, read and checked.
#[derive(Debug, Clone)]
pub struct Campaign {
    /// The campaign file, as given.
    pub file: String,
    /// Its name.
    pub name: String,
    /// What it studies.
    pub description: String,
    /// The base scenario file (relative paths are read from the campaign file's folder).
    pub scenario_path: PathBuf,
    /// The base scenario, merged, to be resolved with each landing's values.
    pub base: ScenarioBase,
    /// The base scenario resolved with no dispersion.
    pub base_scenario: Scenario,
    /// The engines every landing runs on, in the file's order: one, or several for a paired
    /// campaign (each landing's draws landed on each; docs/campaigns.md, "Paired campaigns").
    pub engines: Vec<Engine>,
    /// Landings planned.
    pub landings: u64,
    /// The seed of every landing's stream.
    pub seed: u64,
    /// The confidence of the lower bounds, in (0, 1).
    pub confidence: f64,
    /// Landings whose history is written.
    pub histories: Vec<u64>,
    /// The landings of the accuracy sample the file asks for (`[accuracy] landings`, at least
    /// one), or `None` for the default, one in a hundred between 1 and 20
    /// ([`crate::accuracy::sample_size`]).
    pub accuracy_landings: Option<u64>,
    /// The dispersed fields, in the file's order (the order of the draws).
    pub dispersions: Vec<Dispersion>,
    /// The lower Cholesky factor of the correlation matrix of the dispersions' normal scores
    /// (a Gaussian copula); `None` when every dispersion is independent.
    pub copula: Option<DMatrix<f64>>,
    /// SHA-256 of the campaign without its landing count (hex): what a shard, a merge and an
    /// extension must share.
    pub identity: String,
    /// SHA-256 of what decides each landing's values and scenario (hex): the seed, the
    /// dispersions and correlations, and the resolved base scenario. Campaigns that share it
    /// land the same scenario at every landing number, whatever their engines, names or counts.
    pub draws_identity: String,
}

impl Campaign {
    /// Reads and checks the campaign file at `path`, and the base scenario it names.
    pub fn load(path: impl AsRef<Path>) -> Result<Campaign, CampaignError> {
        let path = path.as_ref();
        let file = path.display().to_string();
        let table = touchdown_scenario::read_toml(path).map_err(|e| CampaignError::file(&e))?;
        let identity = identity(&table);
        let draws_table = draws_table(&table);
        let spec: CampaignFile = touchdown_scenario::read_strict(toml::Value::Table(table))
            .map_err(|m| CampaignError::field(&file, m.field, m.message))?;
        let err = |field: &str, message: String| CampaignError::field(&file, field, message);
        if spec.schema_version != SCHEMA_VERSION {
            return Err(err(
                "schema_version",
                format!(
                    "{} is not a campaign format this build reads (expected {SCHEMA_VERSION})",
                    spec.schema_version
                ),
            ));
        }
        if spec.landings == 0 || spec.landings > MAX_LANDINGS {
            return Err(err(
                "landings",
                format!(
                    "expected between 1 and {MAX_LANDINGS} landings, got {}",
                    spec.landings
                ),
            ));
        }
        if !(spec.confidence > 0.0 && spec.confidence < 1.0) {
            return Err(err(
                "confidence",
                format!(
                    "expected a confidence strictly between 0 and 1 (0.95 for 95 %), got {}",
                    spec.confidence
                ),
            ));
        }
        if let Some(h) = spec.record.histories.iter().find(|h| **h >= spec.landings) {
            return Err(err(
                "record.histories",
                format!(
                    "landing {h} is not in the campaign (landings are numbered 0 to {})",
                    spec.landings - 1
                ),
            ));
        }
        if spec.accuracy.landings == Some(0) {
            return Err(err(
                "accuracy.landings",
                "expected at least 1 landing in the accuracy sample, got 0 (leave the field out \
                 for the default, one landing in a hundred between 1 and 20)"
                    .into(),
            ));
        }
        let scenario_path = path.parent().unwrap_or(Path::new(".")).join(&spec.scenario);
        let base = ScenarioBase::load(&scenario_path).map_err(|e| {
            err(
                "scenario",
                format!("the base scenario {}: {e}", scenario_path.display()),
            )
        })?;
        let base_scenario = base.with(&[]).map_err(|e| {
            err(
                "scenario",
                format!("the base scenario {}: {e}", scenario_path.display()),
            )
        })?;
        let (engines, engines_field) = match (spec.engine, spec.engines) {
            (Some(_), Some(_)) => return Err(err(
                "engines",
                "name the engines either with `engine` (one) or with `engines` (a list), not both"
                    .into(),
            )),
            (Some(e), None) => (vec![e], "engine"),
            (None, Some(list)) => (list, "engines"),
            (None, None) => (vec![Engine::Core], "engine"),
        };
        check_engines(&engines, &base_scenario).map_err(|m| err(engines_field, m))?;
        let mut dispersions = Vec::with_capacity(spec.dispersions.len());
        for (i, d) in spec.dispersions.into_iter().enumerate() {
            let d = dispersion(&format!("dispersion[{i}]"), d, &base_scenario)
                .map_err(|(field, message)| err(&field, message))?;
            if let Some(j) = dispersions
                .iter()
                .position(|o: &Dispersion| o.field == d.field)
            {
                return Err(err(
                    &format!("dispersion[{i}].field"),
                    format!("`{}` is already dispersed by dispersion[{j}]", d.field),
                ));
            }
            // A dry run at the distribution's central value: the field exists, holds this kind
            // of value, and the scenario resolves with it.
            base.with(&[(d.field.as_str(), d.distribution.central().to_toml())])
                .map_err(|e| {
                    err(
                        &format!("dispersion[{i}].field"),
                        format!("`{}` cannot be set in the base scenario: {e}", d.field),
                    )
                })?;
            // The field exists: its unit must be of its dimension (docs/scenario-format.md,
            // "Ranges"), not only in the scenario's units.
            if let Some(unit) = &d.unit {
                base_scenario
                    .check_unit_dimension(&d.field, unit)
                    .map_err(|m| err(&format!("dispersion[{i}].unit"), m))?;
            }
            dispersions.push(d);
        }
        let copula = copula(&spec.correlations, &dispersions)
            .map_err(|(field, message)| err(&field, message))?;
        Ok(Campaign {
            file,
            name: spec.name,
            description: spec.description,
            scenario_path,
            base,
            engines,
            landings: spec.landings,
            seed: spec.seed,
            confidence: spec.confidence,
            histories: spec.record.histories,
            accuracy_landings: spec.accuracy.landings,
            dispersions,
            copula,
            draws_identity: crate::sha256_hex(
                format!("{draws_table}\nbase scenario {}", base_scenario.sha256()).as_bytes(),
            ),
            base_scenario,
            identity,
        })
    }
}

impl Campaign {
    /// The same campaign landed on `engines` instead of the file's (`--engines`): refused,
    /// naming `argument`, unless they are distinct engines the base scenario lists as
    /// applicable. Its identity names the engines, so that its parts and merges are not taken
    /// for the file's.
    pub fn with_engines(
        mut self,
        engines: Vec<Engine>,
        argument: &str,
    ) -> Result<Campaign, CampaignError> {
        check_engines(&engines, &self.base_scenario)
            .map_err(|m| CampaignError::field(&self.file, argument, m))?;
        let names: Vec<&str> = engines.iter().map(|e| e.name()).collect();
        self.identity =
            crate::sha256_hex(format!("{} engines {}", self.identity, names.join(",")).as_bytes());
        self.engines = engines;
        Ok(self)
    }

    /// Whether the landings are paired across several engines (their records hold a block of
    /// columns per engine).
    pub fn paired(&self) -> bool {
        self.engines.len() > 1
    }

    /// The overrides that set each dispersed field to its value in `values` (one per
    /// dispersion, in order), for [`ScenarioBase::with`].
    pub fn overrides<'a>(&'a self, values: &[Value]) -> Vec<(&'a str, toml::Value)> {
        self.dispersions
            .iter()
            .zip(values)
            .map(|(d, v)| (d.field.as_str(), v.to_toml()))
            .collect()
    }
}

/// Checks a campaign's engines: at least one, none twice, each one the base scenario can run on.
fn check_engines(engines: &[Engine], base: &Scenario) -> Result<(), String> {
    if engines.is_empty() {
        return Err("expected at least one engine".into());
    }
    for (i, e) in engines.iter().enumerate() {
        if engines[..i].contains(e) {
            return Err(format!("{e} is named twice: expected distinct engines"));
        }
        touchdown_registry::require(*e, base).map_err(|m| m.to_string())?;
    }
    Ok(())
}

/// SHA-256 (hex) of the campaign table without `landings`, written back as TOML (keys in
/// order): two files that differ only in their landing count, or in layout and comments, are
/// one campaign.
fn identity(table: &toml::Table) -> String {
    let mut t = table.clone();
    t.remove("landings");
    crate::sha256_hex(toml::to_string(&t).unwrap_or_default().as_bytes())
}

/// The keys of the campaign table that decide the values drawn (`seed`, `dispersion`,
/// `correlation`), written back as TOML: with the resolved base scenario, what
/// [`Campaign::draws_identity`] hashes.
fn draws_table(table: &toml::Table) -> String {
    let t: toml::Table = ["seed", "dispersion", "correlation"]
        .into_iter()
        .filter_map(|k| Some((k.to_string(), table.get(k)?.clone())))
        .collect();
    toml::to_string(&t).unwrap_or_default()
}

/// A dispersion checked: its parameters, its unit against the base scenario's units, its values.
fn dispersion(
    at: &str,
    d: DispersionFile,
    base: &Scenario,
) -> Result<Dispersion, (String, String)> {
    let units = &base.file.units;
    let unit_suffix = |unit: &str| units.suffix_of(unit).map_err(|m| (format!("{at}.unit"), m));
    let positive = |name: &str, x: f64| {
        if x.is_finite() && x > 0.0 {
            Ok(x)
        } else {
            Err((
                format!("{at}.{name}"),
                format!("expected a positive number, got {x}"),
            ))
        }
    };
    let finite = |name: &str, x: f64| {
        if x.is_finite() {
            Ok(x)
        } else {
            Err((
                format!("{at}.{name}"),
                format!("expected a number, got {x}"),
            ))
        }
    };
    let interval = |min: f64, max: f64| {
        finite("min", min)?;
        finite("max", max)?;
        if min < max {
            Ok(())
        } else {
            Err((
                format!("{at}.max"),
                format!("expected max > min, got min {min}, max {max}"),
            ))
        }
    };
    let (field, unit, distribution) = match d {
        DispersionFile::Normal {
            field,
            unit,
            mean,
            std_dev,
        } => (
            field,
            Some(unit),
            Distribution::Normal {
                mean: finite("mean", mean)?,
                std_dev: positive("std_dev", std_dev)?,
            },
        ),
        DispersionFile::TruncatedNormal {
            field,
            unit,
            mean,
            std_dev,
            min,
            max,
        } => {
            interval(min, max)?;
            let d = Distribution::truncated_normal(
                finite("mean", mean)?,
                positive("std_dev", std_dev)?,
                min,
                max,
            )
            .map_err(|m| (format!("{at}.min"), m))?;
            (field, Some(unit), d)
        }
        DispersionFile::Uniform {
            field,
            unit,
            min,
            max,
        } => {
            interval(min, max)?;
            (field, Some(unit), Distribution::Uniform { min, max })
        }
        DispersionFile::LogNormal {
            field,
            unit,
            median,
            log_std_dev,
        } => (
            field,
            Some(unit),
            Distribution::LogNormal {
                median: positive("median", median)?,
                log_std_dev: positive("log_std_dev", log_std_dev)?,
            },
        ),
        DispersionFile::Choice {
            field,
            unit,
            values,
            weights,
        } => {
            let values = values_of(at, &values, unit.is_some())?;
            let weights = if weights.is_empty() {
                vec![1.0; values.len()]
            } else {
                weights
            };
            if weights.len() != values.len() {
                return Err((
                    format!("{at}.weights"),
                    format!(
                        "expected one weight per value ({}), got {}",
                        values.len(),
                        weights.len()
                    ),
                ));
            }
            // The sum is the normaliser of the draw: it must be finite (weights of 1e308 each
            // overflow it, and every probability would read as 0) and positive.
            let sum = weights.iter().sum::<f64>();
            if weights.iter().any(|w| !(w.is_finite() && *w >= 0.0))
                || !(sum.is_finite() && sum > 0.0)
            {
                return Err((
                    format!("{at}.weights"),
                    "expected weights ≥ 0, not all zero, with a finite sum (they are relative: scale them down)".into(),
                ));
            }
            (field, unit, Distribution::choice(values, &weights))
        }
        DispersionFile::List {
            field,
            unit,
            values,
        } => {
            let values = values_of(at, &values, unit.is_some())?;
            (field, unit, Distribution::List { values })
        }
    };
    if !distribution.draws_are_finite() {
        return Err((
            at.to_string(),
            format!(
                "its {} draws would overflow: its values out to ±9 standard scores must be finite numbers (and positive, log-normal)",
                distribution.name()
            ),
        ));
    }
    let column = match &unit {
        Some(u) => format!("{field}_{}", unit_suffix(u)?),
        None => field.clone(),
    };
    Ok(Dispersion {
        field,
        unit,
        column,
        distribution,
    })
}

/// The values of a choice or a list: numbers (with a unit) or strings or booleans (without),
/// all of one kind.
fn values_of(
    at: &str,
    values: &[toml::Value],
    has_unit: bool,
) -> Result<Vec<Value>, (String, String)> {
    let field = format!("{at}.values");
    if values.is_empty() {
        return Err((field, "expected at least one value".into()));
    }
    let values: Vec<Value> = values
        .iter()
        .map(|v| match v {
            toml::Value::Float(x) if x.is_finite() => Ok(Value::Number(*x)),
            toml::Value::Integer(i) => Ok(Value::Number(*i as f64)),
            toml::Value::String(s) => Ok(Value::Text(s.clone())),
            toml::Value::Boolean(b) => Ok(Value::Flag(*b)),
            other => Err((
                field.clone(),
                format!("expected numbers, strings or booleans, got {other}"),
            )),
        })
        .collect::<Result<_, _>>()?;
    let numbers = matches!(values[0], Value::Number(_));
    if values
        .iter()
        .any(|v| std::mem::discriminant(v) != std::mem::discriminant(&values[0]))
    {
        return Err((field, "expected values of one kind".into()));
    }
    match (numbers, has_unit) {
        (true, false) => Err((
            format!("{at}.unit"),
            "numbers need their unit (the scenario's, e.g. \"ft/s\"; \"1\" for a pure number)"
                .into(),
        )),
        (false, true) => Err((
            format!("{at}.unit"),
            "strings and booleans have no unit: leave `unit` out".into(),
        )),
        _ => Ok(values),
    }
}

/// The Cholesky factor of the correlation matrix the `[[correlation]]` tables describe.
fn copula(
    correlations: &[CorrelationFile],
    dispersions: &[Dispersion],
) -> Result<Option<DMatrix<f64>>, (String, String)> {
    if correlations.is_empty() {
        return Ok(None);
    }
    let n = dispersions.len();
    let mut r = DMatrix::<f64>::identity(n, n);
    for (k, c) in correlations.iter().enumerate() {
        let at = format!("correlation[{k}]");
        let index = |name: &str| {
            dispersions
                .iter()
                .position(|d| d.field == name)
                .ok_or_else(|| {
                    (
                        format!("{at}.fields"),
                        format!("`{name}` is not a dispersed field"),
                    )
                })
        };
        let (i, j) = (index(&c.fields[0])?, index(&c.fields[1])?);
        if i == j {
            return Err((
                format!("{at}.fields"),
                "expected two different fields".into(),
            ));
        }
        for m in [i, j] {
            if matches!(dispersions[m].distribution, Distribution::List { .. }) {
                return Err((
                    format!("{at}.fields"),
                    format!(
                        "`{}` is a fixed list, not drawn: it cannot be correlated",
                        dispersions[m].field
                    ),
                ));
            }
        }
        if !(c.coefficient.is_finite() && c.coefficient.abs() < 1.0) {
            return Err((
                format!("{at}.coefficient"),
                format!(
                    "expected a coefficient strictly between -1 and 1, got {}",
                    c.coefficient
                ),
            ));
        }
        if r[(i, j)] != 0.0 {
            return Err((
                format!("{at}.fields"),
                "this pair is already correlated".into(),
            ));
        }
        r[(i, j)] = c.coefficient;
        r[(j, i)] = c.coefficient;
    }
    match r.cholesky() {
        Some(c) => Ok(Some(c.l())),
        None => Err((
            "correlation".into(),
            "the coefficients together are not a correlation matrix (it is not positive definite): weaken them".into(),
        )),
    }
}
