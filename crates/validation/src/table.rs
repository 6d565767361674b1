//! Table I: our strokes beside the experiment and the report's analysis, row by row, with the
//! role of each row (calibration or held out) and the held-out error statistics.

use crate::facts::{self, FactCheck};
use crate::reference::{self, CalibrationRecord, Paths, Row, Strut, TableI, INCH};
use crate::ValidationError;
use serde::Serialize;
use std::path::Path;
use touchdown_core::{Outcome, Summary};
use touchdown_scenario::Scenario;

/// Role of a Table I row in the calibration protocol.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Role {
    /// Used to fit the estimated parameters.
    Calibration,
    /// Never used to choose parameters.
    HeldOut,
}

/// One Table I row with our result.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RowResult {
    /// Row number.
    pub id: u32,
    /// "1-2-1" or "2-2".
    pub landing: String,
    /// Vv, ft/s (negative down; `vv_m_s` in the JSON).
    #[serde(rename = "vv_m_s", serialize_with = "crate::si::feet_per_second")]
    pub vv_ft_s: f64,
    /// Vh, ft/s (`vh_m_s` in the JSON).
    #[serde(rename = "vh_m_s", serialize_with = "crate::si::feet_per_second")]
    pub vh_ft_s: f64,
    /// Strut measured.
    pub strut: Strut,
    /// Experimental stroke, in (`experiment_m` in the JSON).
    #[serde(rename = "experiment_m", serialize_with = "crate::si::inches")]
    pub experiment_in: f64,
    /// The report's analytical stroke, in (`analysis_m` in the JSON).
    #[serde(rename = "analysis_m", serialize_with = "crate::si::inches")]
    pub analysis_in: f64,
    /// Our stroke, in (`ours_m` in the JSON).
    #[serde(rename = "ours_m", serialize_with = "crate::si::inches")]
    pub ours_in: f64,
    /// (ours − experiment)/experiment, %.
    pub error_vs_experiment_pct: f64,
    /// (ours − analysis)/analysis, %.
    pub error_vs_analysis_pct: f64,
    /// The report's (analysis − experiment)/experiment, %.
    pub report_error_vs_experiment_pct: f64,
    /// Calibration or held out.
    pub role: Role,
    /// Our stability outcome.
    pub outcome: Outcome,
}

/// Absolute-error statistics over a set of rows, %.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Stats {
    /// Number of rows.
    pub rows: usize,
    /// Mean absolute error, %.
    pub mean_abs_error_pct: f64,
    /// Maximum absolute error, %.
    pub max_abs_error_pct: f64,
}

impl Stats {
    fn of(errors: impl Iterator<Item = f64>) -> Stats {
        let e: Vec<f64> = errors.map(f64::abs).collect();
        let rows = e.len();
        let mean = if rows > 0 {
            e.iter().sum::<f64>() / rows as f64
        } else {
            f64::NAN
        };
        Stats {
            rows,
            mean_abs_error_pct: mean,
            max_abs_error_pct: e.iter().copied().fold(0.0, f64::max),
        }
    }
}

/// The targets of the validation (the report's claim: strokes within 10 %).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Targets {
    /// Every held-out row within 10 % of the experiment.
    pub held_out_within_10_pct: bool,
    /// Mean held-out error no worse than the report's own analysis on the same rows.
    pub mean_no_worse_than_report: bool,
}

/// The whole validation.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Validation {
    /// Rows in Table I order.
    pub rows: Vec<RowResult>,
    /// Our errors on the held-out rows.
    pub held_out_ours: Stats,
    /// The report's errors on the same rows.
    pub held_out_report: Stats,
    /// Whether the targets are met.
    pub targets: Targets,
    /// The calibration the scenarios carry (none: every row is held out).
    pub calibration: Option<CalibrationRecord>,
    /// The figure 25-26 facts beside our run of that landing.
    pub facts: Vec<FactCheck>,
}

/// Our stroke for a Table I row, in: the largest compression stroke of the measured strut
/// kind over every leg.
pub fn stroke_in(summary: &Summary, strut: Strut) -> f64 {
    let m = match strut {
        Strut::Primary => summary
            .max_primary_stroke_m
            .iter()
            .copied()
            .fold(0.0, f64::max),
        Strut::Secondary => summary
            .max_secondary_compression_m
            .iter()
            .flatten()
            .copied()
            .fold(0.0, f64::max),
    };
    m / INCH
}

/// Runs the landing of a row with optional overrides (field path, value in file units).
pub fn run_row(
    paths: &Paths,
    row: &Row,
    overrides: &[(&str, f64)],
) -> Result<Summary, ValidationError> {
    let path = paths.scenario(&row.scenario);
    land(&path, &Scenario::load_with(&path, overrides)?)
}

/// The core's landing of `sc`, read from `path` (named in an error).
pub fn land(path: &Path, sc: &Scenario) -> Result<Summary, ValidationError> {
    touchdown_core::run(sc).map_err(|source| ValidationError::Run {
        scenario: path.display().to_string(),
        source,
    })
}

/// The calibration record, if `touchdown calibrate` has written one.
pub fn calibration_record(paths: &Paths) -> Result<Option<CalibrationRecord>, ValidationError> {
    let path = paths.reference("calibration-result.toml");
    if !path.exists() {
        return Ok(None);
    }
    reference::read(&path).map(Some)
}

/// Runs every Table I landing and the figure 25-26 landing.
pub fn validate(paths: &Paths) -> Result<Validation, ValidationError> {
    let table: TableI = reference::read(&paths.reference("table-i.toml"))?;
    let calibration = calibration_record(paths)?;
    let calibration_rows: Vec<u32> = calibration
        .as_ref()
        .map(|c| c.rows.clone())
        .unwrap_or_default();
    let mut rows = Vec::with_capacity(table.row.len());
    for row in &table.row {
        let s = run_row(paths, row, &[])?;
        let ours = stroke_in(&s, row.strut);
        rows.push(RowResult {
            id: row.id,
            landing: row.landing.clone(),
            vv_ft_s: row.vv,
            vh_ft_s: row.vh,
            strut: row.strut,
            experiment_in: row.experiment,
            analysis_in: row.analysis,
            ours_in: ours,
            error_vs_experiment_pct: 100.0 * (ours - row.experiment) / row.experiment,
            error_vs_analysis_pct: 100.0 * (ours - row.analysis) / row.analysis,
            report_error_vs_experiment_pct: 100.0 * (row.analysis - row.experiment)
                / row.experiment,
            role: if calibration_rows.contains(&row.id) {
                Role::Calibration
            } else {
                Role::HeldOut
            },
            outcome: s.outcome,
        });
    }
    let held: Vec<&RowResult> = rows.iter().filter(|r| r.role == Role::HeldOut).collect();
    let held_out_ours = Stats::of(held.iter().map(|r| r.error_vs_experiment_pct));
    let held_out_report = Stats::of(held.iter().map(|r| r.report_error_vs_experiment_pct));
    let targets = Targets {
        held_out_within_10_pct: held.iter().all(|r| r.error_vs_experiment_pct.abs() <= 10.0),
        mean_no_worse_than_report: held_out_ours.mean_abs_error_pct
            <= held_out_report.mean_abs_error_pct,
    };
    let facts = facts::check(paths, &[])?.checks;
    Ok(Validation {
        rows,
        held_out_ours,
        held_out_report,
        targets,
        calibration,
        facts,
    })
}
