//! Calibration of the estimated parameters to a chosen subset of Table I rows (the protocol in
//! `reference/calibration-protocol.toml`), with argmin's Nelder-Mead. The result is written back
//! as `scenarios/vehicles/lm-1-6-calibrated.toml` (which extends the estimates and overrides
//! only the fitted fields) and recorded, with the rows used, in
//! `reference/calibration-result.toml`. Held-out rows never enter the objective.

use crate::reference::{self, CalibrationRecord, Estimates, Fitted, Paths, Protocol, Row, TableI};
use crate::table::{run_row, stroke_in};
use crate::ValidationError;
use argmin::core::{CostFunction, Executor, State};
use argmin::solver::neldermead::NelderMead;

/// Most iterations of the optimiser.
const MAX_ITERATIONS: u64 = 200;
/// Relative size of the initial simplex around the initial values.
const SIMPLEX: f64 = 0.1;

/// The objective: sum over the calibration rows of the squared relative stroke error.
struct Objective<'a> {
    paths: &'a Paths,
    rows: Vec<Row>,
    parameters: Vec<(reference::FitParameter, Vec<String>)>,
}

impl Objective<'_> {
    fn overrides<'p>(&'p self, x: &[f64]) -> Vec<(&'p str, f64)> {
        self.parameters
            .iter()
            .zip(x)
            .flat_map(|((_, fields), v)| fields.iter().map(move |f| (f.as_str(), *v)))
            .collect()
    }
}

impl CostFunction for Objective<'_> {
    type Param = Vec<f64>;
    type Output = f64;

    fn cost(&self, x: &Self::Param) -> Result<f64, argmin::core::Error> {
        // Outside the bounds: a penalty growing with the distance (Nelder-Mead is unconstrained).
        let outside: f64 = self
            .parameters
            .iter()
            .zip(x)
            .map(|((p, _), v)| {
                ((p.lower - v).max(0.0) + (v - p.upper).max(0.0)) / (p.upper - p.lower)
            })
            .sum();
        if outside > 0.0 {
            return Ok(1e3 * (1.0 + outside));
        }
        let overrides = self.overrides(x);
        let mut sum = 0.0;
        for row in &self.rows {
            let s = run_row(self.paths, row, &overrides)
                .map_err(|e| argmin::core::Error::msg(e.to_string()))?;
            let rel = (stroke_in(&s, row.strut) - row.experiment) / row.experiment;
            sum += rel * rel;
        }
        Ok(sum)
    }
}

/// Fits the protocol's parameters to its rows (or to `rows`, if given).
pub fn calibrate(
    paths: &Paths,
    protocol: &Protocol,
    rows: Option<&[u32]>,
) -> Result<CalibrationRecord, ValidationError> {
    let table: TableI = reference::read(&paths.reference("table-i.toml"))?;
    let estimates: Estimates = reference::read(&paths.reference("lm-1-6-estimates.toml"))?;
    let ids = rows.unwrap_or(&protocol.rows).to_vec();
    if ids.is_empty() || protocol.parameter.is_empty() {
        return Err(ValidationError::Calibration(
            "at least one row and one parameter are needed".into(),
        ));
    }
    let chosen: Vec<Row> = ids
        .iter()
        .map(|id| {
            table
                .row
                .iter()
                .find(|r| r.id == *id)
                .cloned()
                .ok_or_else(|| ValidationError::Calibration(format!("Table I has no row {id}")))
        })
        .collect::<Result<_, _>>()?;
    let parameters = protocol
        .parameter
        .iter()
        .map(|p| {
            if !(p.lower < p.initial && p.initial < p.upper) {
                return Err(ValidationError::Calibration(format!(
                    "{}: expected lower < initial < upper",
                    p.name
                )));
            }
            Ok((p.clone(), estimates.get(&p.name)?.fields.clone()))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let x0: Vec<f64> = protocol.parameter.iter().map(|p| p.initial).collect();
    let mut simplex = vec![x0.clone()];
    for i in 0..x0.len() {
        let mut v = x0.clone();
        v[i] *= 1.0 + SIMPLEX;
        simplex.push(v);
    }
    let objective = Objective {
        paths,
        rows: chosen,
        parameters,
    };
    let solver = NelderMead::new(simplex)
        .with_sd_tolerance(1e-10)
        .map_err(|e| ValidationError::Calibration(e.to_string()))?;
    let result = Executor::new(objective, solver)
        .configure(|state| state.max_iters(MAX_ITERATIONS))
        .run()
        .map_err(|e| ValidationError::Calibration(e.to_string()))?;
    let state = result.state();
    let best = state.get_best_param().cloned().ok_or_else(|| {
        ValidationError::Calibration("the optimiser returned no parameters".into())
    })?;
    let parameter = protocol
        .parameter
        .iter()
        .zip(&best)
        .map(|(p, v)| {
            Ok(Fitted {
                name: p.name.clone(),
                fields: estimates.get(&p.name)?.fields.clone(),
                initial: p.initial,
                value: *v,
            })
        })
        .collect::<Result<Vec<_>, ValidationError>>()?;
    Ok(CalibrationRecord {
        rows: ids,
        optimiser: "argmin Nelder-Mead".into(),
        iterations: state.get_iter(),
        objective: state.get_best_cost(),
        parameter,
    })
}

/// Writes the calibrated vehicle file and the record. The vehicle file extends the estimates
/// and sets only the fitted fields; an array holding a fitted field is written whole (arrays
/// are replaced whole by `extends`).
pub fn write(paths: &Paths, record: &CalibrationRecord) -> Result<(), ValidationError> {
    let estimates: Estimates = reference::read(&paths.reference("lm-1-6-estimates.toml"))?;
    let vehicle = paths.scenario(&estimates.vehicle);
    let mut fitted = touchdown_scenario::merged_table(&vehicle)?;
    for p in &record.parameter {
        for f in &p.fields {
            touchdown_scenario::set_field(&mut fitted, f, p.value)
                .map_err(|m| ValidationError::Calibration(format!("{f}: {m}")))?;
        }
    }
    let mut out = toml::Table::new();
    out.insert("schema_version".into(), toml::Value::Integer(1));
    let base_name = vehicle
        .file_name()
        .map(|n| n.to_string_lossy().to_string())
        .unwrap_or_default();
    out.insert("extends".into(), toml::Value::String(base_name));
    out.insert(
        "name".into(),
        toml::Value::String("LM 1/6-scale model, calibrated".into()),
    );
    for p in &record.parameter {
        for f in &p.fields {
            copy_field(&fitted, &mut out, f);
        }
    }
    let rows: Vec<String> = record.rows.iter().map(u32::to_string).collect();
    let mut text = String::new();
    text.push_str("# Calibrated values of the 1/6-scale LM model, written by `touchdown calibrate`; do not edit\n");
    text.push_str("# by hand. It extends the estimates and overrides only the fitted fields.\n");
    text.push_str(&format!(
        "# Calibration rows (Table I): {}; every other row is held out.\n",
        rows.join(", ")
    ));
    text.push_str(&format!(
        "# {} : {} iterations, objective (sum of squared relative errors) {:.3e}.\n",
        record.optimiser, record.iterations, record.objective
    ));
    for p in &record.parameter {
        text.push_str(&format!("# {}: {} -> {:.6}\n", p.name, p.initial, p.value));
    }
    text.push_str(&toml::to_string(&out).map_err(|e| ValidationError::Calibration(e.to_string()))?);
    let calibrated = vehicle.with_file_name(format!(
        "{}-calibrated.toml",
        vehicle
            .file_stem()
            .map(|s| s.to_string_lossy().to_string())
            .unwrap_or_default()
    ));
    std::fs::write(&calibrated, text)
        .map_err(|e| ValidationError::Calibration(format!("{}: {e}", calibrated.display())))?;
    let record_text = format!(
        "# Written by `touchdown calibrate` from reference/calibration-protocol.toml; the rows used are\n# the calibration rows of `touchdown validate`, every other row is held out.\n{}",
        toml::to_string(record).map_err(|e| ValidationError::Calibration(e.to_string()))?
    );
    let path = paths.reference("calibration-result.toml");
    std::fs::write(&path, record_text)
        .map_err(|e| ValidationError::Calibration(format!("{}: {e}", path.display())))
}

/// Copies into `out` the part of `from` that holds `field`: the leaf itself, or the whole
/// array on the way to it.
fn copy_field(from: &toml::Table, out: &mut toml::Table, field: &str) {
    let mut src = from;
    let mut dst = out;
    let keys: Vec<&str> = field.split('.').collect();
    for (n, key) in keys.iter().enumerate() {
        let (name, indexed) = match key.split_once('[') {
            Some((k, _)) => (k, true),
            None => (*key, false),
        };
        let Some(value) = src.get(name) else { return };
        if indexed || n + 1 == keys.len() {
            dst.insert(name.to_string(), value.clone());
            return;
        }
        let Some(next) = value.as_table() else { return };
        src = next;
        dst = dst
            .entry(name.to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()))
            .as_table_mut()
            .expect("created as a table");
    }
}
