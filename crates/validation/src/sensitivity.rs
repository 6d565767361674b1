//! How each estimated parameter moves each Table I stroke: every estimate is scaled by
//! 1 ± fraction (all its fields together) and every row is rerun.

use crate::calibrate::infeasible;
use crate::reference::{self, Estimates, Paths, TableI};
use crate::table::{run_row, stroke_in};
use crate::ValidationError;
use rayon::prelude::*;
use serde::Serialize;
use touchdown_scenario::Scenario;

/// Response of one row's stroke to one parameter.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Response {
    /// Table I row.
    pub id: u32,
    /// Stroke with the parameter at its value, in (`base_m` in the JSON).
    #[serde(rename = "base_m", serialize_with = "crate::si::inches")]
    pub base_in: f64,
    /// Relative stroke change with the parameter scaled by 1 − fraction, %; absent where the
    /// scaled value is refused (the parameter's `refused`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub minus_pct: Option<f64>,
    /// Relative stroke change with the parameter scaled by 1 + fraction, %; absent where the
    /// scaled value is refused.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub plus_pct: Option<f64>,
}

/// A scaled value the scenario loader refuses (a load-stroke table whose stages no longer crush
/// at rising loads: FP1 scaled past the second stage's load), so no stroke is reported for it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Refusal {
    /// The scale factor, 1 − fraction or 1 + fraction.
    pub factor: f64,
    /// What the loader said.
    pub reason: String,
}

/// One estimated parameter's row of the sensitivity table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ParameterSensitivity {
    /// The estimate.
    pub parameter: String,
    /// Its current value in the scenarios (calibrated if calibrated), file units.
    pub value: f64,
    /// The unit of `value`: the scenario file's own (`lbf`, `slug`, `lbf/ft`, ...).
    pub unit: String,
    /// One response per Table I row.
    pub rows: Vec<Response>,
    /// The scaled values refused, each once (empty when both are landed).
    pub refused: Vec<Refusal>,
}

/// The sensitivity table for a relative change `fraction` (0.2 for ±20 %).
pub fn sensitivity(
    paths: &Paths,
    fraction: f64,
) -> Result<Vec<ParameterSensitivity>, ValidationError> {
    let table: TableI = reference::read(&paths.reference("table-i.toml"))?;
    let estimates: Estimates = reference::read(&paths.reference("lm-1-6-estimates.toml"))?;
    let base: Vec<f64> = table
        .row
        .par_iter()
        .map(|r| run_row(paths, r, &[]).map(|s| stroke_in(&s, r.strut)))
        .collect::<Result<_, _>>()?;
    let mut out = Vec::with_capacity(estimates.parameter.len());
    let first = paths.scenario(&table.row[0].scenario);
    let units = Scenario::load(&first)?.file.units;
    for p in &estimates.parameter {
        let value = Scenario::value_at(&first, &p.fields[0])?.ok_or_else(|| {
            ValidationError::Reference(format!("{}: no number at {}", first.display(), p.fields[0]))
        })?;
        let mut refused = Vec::new();
        let jobs: Vec<(usize, f64)> = (0..table.row.len())
            .flat_map(|i| [(i, 1.0 - fraction), (i, 1.0 + fraction)])
            .collect();
        let strokes: Vec<Option<f64>> = jobs
            .par_iter()
            .map(|(i, factor)| {
                let overrides: Vec<(&str, f64)> = p
                    .fields
                    .iter()
                    .map(|f| (f.as_str(), value * factor))
                    .collect();
                let row = &table.row[*i];
                match run_row(paths, row, &overrides) {
                    Ok(s) => Ok(Ok(stroke_in(&s, row.strut))),
                    Err(e) if infeasible(&e) => Ok(Err(
                        innermost(&e).replace(&format!("{}/", paths.root.display()), "")
                    )),
                    Err(e) => Err(e),
                }
            })
            .collect::<Result<Vec<_>, _>>()?
            .into_iter()
            .zip(&jobs)
            .map(|(stroke, (_, factor))| {
                stroke
                    .map_err(|reason| {
                        if !refused.iter().any(|r: &Refusal| r.factor == *factor) {
                            refused.push(Refusal {
                                factor: *factor,
                                reason,
                            });
                        }
                    })
                    .ok()
            })
            .collect();
        let change = |stroke: Option<f64>, base: f64| stroke.map(|s| 100.0 * (s - base) / base);
        let rows = table
            .row
            .iter()
            .enumerate()
            .map(|(i, r)| Response {
                id: r.id,
                base_in: base[i],
                minus_pct: change(strokes[2 * i], base[i]),
                plus_pct: change(strokes[2 * i + 1], base[i]),
            })
            .collect();
        out.push(ParameterSensitivity {
            parameter: p.name.clone(),
            value,
            unit: touchdown_scenario::ranges::lookup(&p.fields[0])
                .map_or_else(String::new, |r| units.file_unit_of(r.unit)),
            rows,
            refused,
        });
    }
    Ok(out)
}

/// The innermost cause of `e`: what the loader refused.
fn innermost(e: &(dyn std::error::Error + 'static)) -> String {
    let mut cause = e;
    while let Some(next) = cause.source() {
        cause = next;
    }
    cause.to_string()
}
