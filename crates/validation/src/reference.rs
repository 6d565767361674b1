//! The reference data files under `reference/` and the paths of the workspace.

use crate::ValidationError;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Inches per foot.
pub const INCH: f64 = 0.0254;

/// Where the workspace's data live.
#[derive(Debug, Clone)]
pub struct Paths {
    /// Workspace root (holds `reference/` and `scenarios/`).
    pub root: PathBuf,
}

impl Paths {
    /// Paths under `root`.
    pub fn new(root: impl Into<PathBuf>) -> Paths {
        Paths { root: root.into() }
    }
    /// A file under `reference/`.
    pub fn reference(&self, name: &str) -> PathBuf {
        self.root.join("reference").join(name)
    }
    /// A file under `scenarios/`.
    pub fn scenario(&self, name: &str) -> PathBuf {
        self.root.join("scenarios").join(name)
    }
}

/// Reads and parses a TOML reference file.
pub fn read<T: for<'de> Deserialize<'de>>(path: &Path) -> Result<T, ValidationError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| ValidationError::Reference(format!("{}: {e}", path.display())))?;
    toml::from_str(&text)
        .map_err(|e| ValidationError::Reference(format!("{}: {e}", path.display())))
}

/// Which strut a Table I row measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Strut {
    /// Maximum primary-strut compression stroke.
    Primary,
    /// Maximum secondary-strut compression stroke.
    Secondary,
}

/// One row of Table I (report units: ft/s, in).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Row {
    /// Row number, 1 to 8, in the table's order.
    pub id: u32,
    /// "1-2-1" or "2-2".
    pub landing: String,
    /// Vertical touchdown velocity, ft/s (negative, down, as printed).
    pub vv: f64,
    /// Horizontal touchdown velocity, ft/s.
    pub vh: f64,
    /// Strut measured.
    pub strut: Strut,
    /// Experimental stroke, in.
    pub experiment: f64,
    /// The report's analytical stroke, in.
    pub analysis: f64,
    /// Scenario file (under `scenarios/`) that sets up the row.
    pub scenario: String,
}

/// Table I.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct TableI {
    /// Provenance.
    pub provenance: String,
    /// The eight rows.
    pub row: Vec<Row>,
}

/// One estimated (tag E) parameter.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Estimate {
    /// Name (as the calibration protocol refers to it).
    pub name: String,
    /// Scenario fields it sets, all to the same value (file units).
    pub fields: Vec<String>,
    /// Why this value.
    pub reasoning: String,
}

/// `reference/lm-1-6-estimates.toml`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct Estimates {
    /// The vehicle file they live in (under `scenarios/`).
    pub vehicle: String,
    /// The parameters.
    pub parameter: Vec<Estimate>,
}

impl Estimates {
    /// The estimate called `name`.
    pub fn get(&self, name: &str) -> Result<&Estimate, ValidationError> {
        self.parameter
            .iter()
            .find(|p| p.name == name)
            .ok_or_else(|| {
                ValidationError::Reference(format!(
                    "no estimated parameter named {name:?} in reference/lm-1-6-estimates.toml"
                ))
            })
    }
}

/// A parameter to fit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FitParameter {
    /// Name of an estimate.
    pub name: String,
    /// Initial value (file units).
    pub initial: f64,
    /// Lower bound.
    pub lower: f64,
    /// Upper bound.
    pub upper: f64,
}

/// `reference/calibration-protocol.toml`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Protocol {
    /// Table I row ids used for calibration.
    pub rows: Vec<u32>,
    /// How the fit is restarted from its end point.
    pub restarts: Restarts,
    /// Parameters fitted.
    pub parameter: Vec<FitParameter>,
}

/// A fitted parameter in the calibration record.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Fitted {
    /// Name of the estimate.
    pub name: String,
    /// Scenario fields set.
    pub fields: Vec<String>,
    /// Initial value (file units).
    pub initial: f64,
    /// Fitted value (file units).
    pub value: f64,
}

/// `reference/calibration-result.toml`, written by `touchdown calibrate`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CalibrationRecord {
    /// Rows used (every other row is held out).
    pub rows: Vec<u32>,
    /// Optimiser.
    pub optimiser: String,
    /// Iterations run.
    pub iterations: u64,
    /// Objective at the optimum: sum of squared relative stroke errors on the rows.
    pub objective: f64,
    /// Fitted parameters.
    pub parameter: Vec<Fitted>,
    /// The accuracy the step settings give at the fit: each row landed again with every step
    /// limit refined; absent from records written before it was stated.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub accuracy: Option<FitAccuracy>,
}

/// The rows of a fit landed at the fitted values with the scenarios' step settings and with
/// every step limit `refinement` times finer (`Integrator::refine`): how far the settings'
/// strokes, which the fit matched, are from the refined runs'.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FitAccuracy {
    /// How many times finer the refined runs' step limits are (dimensionless).
    pub refinement: f64,
    /// Each row, in the fit's order.
    pub row: Vec<RowAccuracy>,
}

/// One row of a fit at its fitted values, at the step settings and refined.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RowAccuracy {
    /// Table I row.
    pub id: u32,
    /// Its stroke at the step settings, m.
    pub stroke_m: f64,
    /// Its stroke with every step limit refined, m.
    pub refined_stroke_m: f64,
}

/// Restarts of a fit: Nelder-Mead run again from its end point with a fresh simplex, until a
/// restart no longer improves the objective (a collapsed simplex is not a minimum: the strokes
/// respond to the crush loads through thresholds, a stage reached or a footpad let go).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Restarts {
    /// Each restart's simplex: a step of this fraction of each parameter's range (towards the
    /// middle of its bounds).
    pub simplex: f64,
    /// Most restarts.
    pub most: u32,
    /// A restart that improves the objective by less than this fraction of it ends the fit.
    pub improvement: f64,
    /// Also start the fit (with its restarts) from the best of a grid of this many points per
    /// parameter over its bounds (the cells' centres), and keep the better of the two fits: a
    /// restart from a side basin's end point does not reach a deeper basin the simplex never
    /// spans. 0 (the default): no grid.
    #[serde(default)]
    pub grid: u32,
}

impl Restarts {
    /// Checks the settings read from `file`: every error names the file and the field.
    pub fn check(&self, file: &str, prefix: &str) -> Result<(), ValidationError> {
        let refuse = |field: &str, expected: &str| {
            Err(ValidationError::Reference(format!(
                "{file}: {prefix}{field}: expected {expected}"
            )))
        };
        if !(self.simplex > 0.0 && self.simplex <= 0.5) {
            return refuse("simplex", "a fraction in (0, 0.5]");
        }
        if !(self.improvement >= 0.0 && self.improvement < 1.0) {
            return refuse("improvement", "a fraction in [0, 1)");
        }
        if self.grid > 20 {
            return refuse("grid", "at most 20 points per parameter");
        }
        Ok(())
    }
}
