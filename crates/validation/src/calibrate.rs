//! Calibration of the estimated parameters to a chosen subset of Table I rows (the protocol in
//! `reference/calibration-protocol.toml`), with argmin's Nelder-Mead. The result is written back
//! as `scenarios/vehicles/lm-1-6-calibrated.toml` (which extends the estimates and overrides
//! only the fitted fields) and recorded, with the rows used, in
//! `reference/calibration-result.toml`. Held-out rows never enter the objective.

use crate::reference::{
    self, CalibrationRecord, Estimates, FitAccuracy, FitParameter, Fitted, Paths, Protocol,
    Restarts, Row, RowAccuracy, TableI, INCH,
};
use crate::table::{land, stroke_in};
use crate::ValidationError;
use argmin::core::{CostFunction, Executor, State};
use argmin::solver::neldermead::NelderMead;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use touchdown_scenario::schema::{Scheme, ACCURACY_REFINEMENT};
use touchdown_scenario::ScenarioBase;

/// Most iterations of the optimiser.
const MAX_ITERATIONS: u64 = 200;
/// The objective of a parameter set the scenario loader refuses (far above any real fit's).
pub const INFEASIBLE: f64 = 1e3;
/// Relative size of the initial simplex around the initial values.
const SIMPLEX: f64 = 0.1;

/// A row's predicted stroke, in, with the fitted parameters at the values given (file units,
/// in the protocol's order): the model a fit calibrates.
pub type Predict<'a> = dyn Fn(&Row, &[f64]) -> Result<f64, ValidationError> + Sync + 'a;

/// The core's stroke for a Table I row of `rows` with each parameter's value written to its
/// scenario `fields` (file units): the model every fit of the 1/6-scale model calibrates,
/// landed with `scheme` (`None`: the row's scenario's own) and every step limit of the row's
/// scenario refined `refinement` times (1: its own settings; `Integrator::refine`, for the
/// scheme landed). Each row's scenario file is read and merged once, here, and resolved with
/// the values at each call.
pub fn table_model<'a>(
    paths: &Paths,
    rows: &[Row],
    fields: &'a [Vec<String>],
    scheme: Option<Scheme>,
    refinement: f64,
) -> Result<impl Fn(&Row, &[f64]) -> Result<f64, ValidationError> + Sync + 'a, ValidationError> {
    let mut bases: HashMap<String, (PathBuf, ScenarioBase)> = HashMap::new();
    for row in rows {
        let path = paths.scenario(&row.scenario);
        let base = ScenarioBase::load(&path)?;
        bases.insert(row.scenario.clone(), (path, base));
    }
    Ok(move |row: &Row, x: &[f64]| {
        let (path, base) = bases.get(&row.scenario).ok_or_else(|| {
            ValidationError::Calibration(format!("row {} is not one of the model's rows", row.id))
        })?;
        let values: Vec<(&str, toml::Value)> = overrides(fields, x)
            .into_iter()
            .map(|(f, v)| (f, toml::Value::Float(v)))
            .collect();
        let mut sc = base.with(&values)?;
        if scheme.is_some() || refinement > 1.0 {
            sc = sc.with_integrator(|it| {
                if let Some(scheme) = scheme {
                    it.scheme = scheme;
                }
                if refinement > 1.0 {
                    it.refine(refinement);
                }
            })?;
        }
        land(path, &sc).map(|s| stroke_in(&s, row.strut))
    })
}

/// The overrides that set each parameter's scenario `fields` to its value in `x` (file units).
pub fn overrides<'a>(fields: &'a [Vec<String>], x: &[f64]) -> Vec<(&'a str, f64)> {
    fields
        .iter()
        .zip(x)
        .flat_map(|(f, v)| f.iter().map(move |f| (f.as_str(), *v)))
        .collect()
}

/// The relative stroke errors (ours − experiment) / experiment of `rows` at `x`, in row order.
/// Every row is landed even when one fails (a parameter set whose diagram the loader refuses),
/// the first error in row order winning: a parallel collect that stopped at the first error
/// would land a number of rows that depends on the threads' timing, and the landings the
/// cross-validation reports with it.
pub fn relative_errors(
    rows: &[Row],
    x: &[f64],
    predict: &Predict,
) -> Result<Vec<f64>, ValidationError> {
    let each: Vec<Result<f64, ValidationError>> = rows
        .par_iter()
        .map(|row| predict(row, x).map(|s| (s - row.experiment) / row.experiment))
        .collect();
    each.into_iter().collect()
}

/// The objective: sum over the fitted rows of the squared relative stroke error.
struct Objective<'a> {
    rows: &'a [Row],
    parameters: &'a [FitParameter],
    predict: &'a Predict<'a>,
}

impl Objective<'_> {
    /// The objective at `x` (file units, in the parameters' order).
    fn at(&self, x: &[f64]) -> Result<f64, ValidationError> {
        // Outside the bounds: a penalty growing with the distance (Nelder-Mead is unconstrained).
        let outside: f64 = self
            .parameters
            .iter()
            .zip(x)
            .map(|(p, v)| ((p.lower - v).max(0.0) + (v - p.upper).max(0.0)) / (p.upper - p.lower))
            .sum();
        if outside > 0.0 {
            return Ok(1e3 * (1.0 + outside));
        }
        match relative_errors(self.rows, x, self.predict) {
            Ok(errors) => Ok(errors.iter().fold(0.0, |sum, r| sum + r * r)),
            // A parameter set whose load-stroke diagram the loader refuses (stages at rising
            // loads, each long enough for its onset ramp) lies outside the feasible set, as a
            // value outside the bounds does.
            Err(e) if infeasible(&e) => Ok(INFEASIBLE),
            Err(e) => Err(e),
        }
    }
}

impl CostFunction for Objective<'_> {
    type Param = Vec<f64>;
    type Output = f64;

    fn cost(&self, x: &Self::Param) -> Result<f64, argmin::core::Error> {
        self.at(x)
            .map_err(|e| argmin::core::Error::msg(e.to_string()))
    }
}

/// Whether `e` refuses the parameter set itself (the scenario loader or an engine refusing its
/// load-stroke diagram: stages at rising loads, each long enough for its onset ramp), rather
/// than reporting a landing that failed: such a set lies outside the feasible set of a fit.
pub fn infeasible(e: &ValidationError) -> bool {
    matches!(
        e,
        ValidationError::Scenario(_)
            | ValidationError::Run {
                source: touchdown_record::RunError::Refused(_),
                ..
            }
    )
}

/// A fit of parameters to rows.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Fit {
    /// The fitted values, file units, in the parameters' order.
    pub value: Vec<f64>,
    /// The objective there: sum of squared relative stroke errors on the rows.
    pub objective: f64,
    /// Iterations the optimiser ran.
    pub iterations: u64,
}

/// Fits `parameters` to `rows` (sum of squared relative stroke errors of `predict`) with
/// argmin's Nelder-Mead from the initial values, an initial simplex of 10 % steps, bounds by
/// penalty and at most `max_iterations` iterations a run; with `restarts`, run again from the
/// end point (a collapsed simplex is not a minimum), and with their `grid`, the same again from
/// the grid's best point, the better fit kept. Every caller (the two-row calibration, each
/// cross-validation fold) fits with this one function.
pub fn fit(
    rows: &[Row],
    parameters: &[FitParameter],
    max_iterations: u64,
    restarts: Option<Restarts>,
    predict: &Predict,
) -> Result<Fit, ValidationError> {
    if rows.is_empty() || parameters.is_empty() {
        return Err(ValidationError::Calibration(
            "at least one row and one parameter are needed".into(),
        ));
    }
    for p in parameters {
        if !(p.lower < p.initial && p.initial < p.upper) {
            return Err(ValidationError::Calibration(format!(
                "{}: expected lower < initial < upper",
                p.name
            )));
        }
    }
    let x0: Vec<f64> = parameters.iter().map(|p| p.initial).collect();
    let from_initial = descend(rows, parameters, &x0, max_iterations, restarts, predict)?;
    let grid = restarts.map_or(0, |r| r.grid);
    if grid == 0 {
        return Ok(from_initial);
    }
    let start = grid_start(rows, parameters, grid, predict)?;
    let from_grid = descend(rows, parameters, &start, max_iterations, restarts, predict)?;
    let iterations = from_initial.iterations + from_grid.iterations;
    let best = if from_grid.objective < from_initial.objective {
        from_grid
    } else {
        from_initial
    };
    Ok(Fit { iterations, ..best })
}

/// The best point of a grid of `n` points per parameter over its bounds, the cells' centres
/// (the first in the grid's order on a tie).
fn grid_start(
    rows: &[Row],
    parameters: &[FitParameter],
    n: u32,
    predict: &Predict,
) -> Result<Vec<f64>, ValidationError> {
    let n = n as usize;
    let points = u32::try_from(parameters.len())
        .ok()
        .and_then(|p| n.checked_pow(p))
        .ok_or_else(|| {
            ValidationError::Calibration(format!(
                "a grid of {n} points per parameter over {} parameters is too large",
                parameters.len()
            ))
        })?;
    let point = |k: usize| -> Vec<f64> {
        let mut rest = k;
        parameters
            .iter()
            .map(|p| {
                let i = rest % n;
                rest /= n;
                p.lower + (i as f64 + 0.5) / n as f64 * (p.upper - p.lower)
            })
            .collect()
    };
    let objective = Objective {
        rows,
        parameters,
        predict,
    };
    let costs = (0..points)
        .into_par_iter()
        .map(|k| objective.at(&point(k)))
        .collect::<Result<Vec<f64>, ValidationError>>()?;
    let best = (0..points).fold(0, |b, k| if costs[k] < costs[b] { k } else { b });
    Ok(point(best))
}

/// Nelder-Mead from `x0` with an initial simplex of 10 % steps, then its `restarts`.
fn descend(
    rows: &[Row],
    parameters: &[FitParameter],
    x0: &[f64],
    max_iterations: u64,
    restarts: Option<Restarts>,
    predict: &Predict,
) -> Result<Fit, ValidationError> {
    let mut simplex = vec![x0.to_vec()];
    for i in 0..x0.len() {
        let mut v = x0.to_vec();
        v[i] *= 1.0 + SIMPLEX;
        simplex.push(v);
    }
    let mut best = nelder_mead(rows, parameters, simplex, max_iterations, predict)?;
    let Some(r) = restarts else {
        return Ok(best);
    };
    for _ in 0..r.most {
        let mut simplex = vec![best.value.clone()];
        for (i, p) in parameters.iter().enumerate() {
            let mut v = best.value.clone();
            let step = r.simplex * (p.upper - p.lower);
            v[i] += if v[i] + step <= p.upper { step } else { -step };
            simplex.push(v);
        }
        let next = nelder_mead(rows, parameters, simplex, max_iterations, predict)?;
        let gain = best.objective - next.objective;
        let iterations = best.iterations + next.iterations;
        let done = gain <= r.improvement * best.objective;
        if gain > 0.0 {
            best = Fit { iterations, ..next };
        } else {
            best.iterations = iterations;
        }
        if done {
            break;
        }
    }
    Ok(best)
}

/// One Nelder-Mead run from `simplex`.
fn nelder_mead(
    rows: &[Row],
    parameters: &[FitParameter],
    simplex: Vec<Vec<f64>>,
    max_iterations: u64,
    predict: &Predict,
) -> Result<Fit, ValidationError> {
    let objective = Objective {
        rows,
        parameters,
        predict,
    };
    let solver = NelderMead::new(simplex)
        .with_sd_tolerance(1e-10)
        .map_err(|e| ValidationError::Calibration(e.to_string()))?;
    let result = Executor::new(objective, solver)
        .configure(|state| state.max_iters(max_iterations))
        .run()
        .map_err(|e| ValidationError::Calibration(e.to_string()))?;
    let state = result.state();
    let value = state.get_best_param().cloned().ok_or_else(|| {
        ValidationError::Calibration("the optimiser returned no parameters".into())
    })?;
    Ok(Fit {
        value,
        objective: state.get_best_cost(),
        iterations: state.get_iter(),
    })
}

/// The Table I rows `ids`, in that order.
pub fn rows_of(table: &TableI, ids: &[u32]) -> Result<Vec<Row>, ValidationError> {
    ids.iter()
        .map(|id| {
            table
                .row
                .iter()
                .find(|r| r.id == *id)
                .cloned()
                .ok_or_else(|| ValidationError::Calibration(format!("Table I has no row {id}")))
        })
        .collect()
}

/// The scenario fields of each parameter, from the estimates.
pub fn fields_of(
    estimates: &Estimates,
    parameters: &[FitParameter],
) -> Result<Vec<Vec<String>>, ValidationError> {
    parameters
        .iter()
        .map(|p| Ok(estimates.get(&p.name)?.fields.clone()))
        .collect()
}

/// Fits the protocol's parameters to its rows (or to `rows`, if given). Refused when the rows
/// are fewer than the parameters: the data could not determine them.
pub fn calibrate(
    paths: &Paths,
    protocol: &Protocol,
    rows: Option<&[u32]>,
) -> Result<CalibrationRecord, ValidationError> {
    let table: TableI = reference::read(&paths.reference("table-i.toml"))?;
    let estimates: Estimates = reference::read(&paths.reference("lm-1-6-estimates.toml"))?;
    let ids = rows.unwrap_or(&protocol.rows).to_vec();
    if ids.len() < protocol.parameter.len() {
        return Err(ValidationError::Calibration(format!(
            "{} row(s) cannot determine {} parameters: name at least as many rows as parameters",
            ids.len(),
            protocol.parameter.len()
        )));
    }
    let chosen = rows_of(&table, &ids)?;
    let fields = fields_of(&estimates, &protocol.parameter)?;
    let model = table_model(paths, &chosen, &fields, None, 1.0)?;
    protocol
        .restarts
        .check("calibration-protocol.toml", "restarts.")?;
    let fitted = fit(
        &chosen,
        &protocol.parameter,
        MAX_ITERATIONS,
        Some(protocol.restarts),
        &model,
    )?;
    let parameter = protocol
        .parameter
        .iter()
        .zip(&fitted.value)
        .zip(&fields)
        .map(|((p, v), fields)| Fitted {
            name: p.name.clone(),
            fields: fields.clone(),
            initial: p.initial,
            value: *v,
        })
        .collect();
    let refined = table_model(paths, &chosen, &fields, None, ACCURACY_REFINEMENT)?;
    let row = chosen
        .par_iter()
        .map(|r| {
            Ok(RowAccuracy {
                id: r.id,
                stroke_m: model(r, &fitted.value)? * INCH,
                refined_stroke_m: refined(r, &fitted.value)? * INCH,
            })
        })
        .collect::<Result<_, ValidationError>>()?;
    Ok(CalibrationRecord {
        rows: ids,
        optimiser: "argmin Nelder-Mead".into(),
        iterations: fitted.iterations,
        objective: fitted.objective,
        parameter,
        accuracy: Some(FitAccuracy {
            refinement: ACCURACY_REFINEMENT,
            row,
        }),
    })
}

/// Writes the calibrated vehicle file and the record: into the folder `dir`, or, with `None`,
/// over the tracked files (`scenarios/vehicles/<vehicle>-calibrated.toml`, which the Table I
/// scenarios extend, and `reference/calibration-result.toml`). The vehicle file extends the
/// estimates and sets only the fitted fields; an array holding a fitted field is written whole
/// (arrays are replaced whole by `extends`). In a folder of its own it extends the estimates by
/// their absolute path. Returns the two files written.
pub fn write(
    paths: &Paths,
    record: &CalibrationRecord,
    dir: Option<&Path>,
) -> Result<[PathBuf; 2], ValidationError> {
    let estimates: Estimates = reference::read(&paths.reference("lm-1-6-estimates.toml"))?;
    let vehicle = paths.scenario(&estimates.vehicle);
    let mut fitted = touchdown_scenario::merged_table(&vehicle)?;
    for p in &record.parameter {
        for f in &p.fields {
            touchdown_scenario::set_field(&mut fitted, f, p.value)
                .map_err(|m| ValidationError::Calibration(format!("{f}: {m}")))?;
        }
    }
    let failed = |path: &Path, e: std::io::Error| {
        ValidationError::Calibration(format!("{}: {e}", path.display()))
    };
    let base_name = match dir {
        None => vehicle
            .file_name()
            .map(|n| n.to_string_lossy().to_string())
            .unwrap_or_default(),
        Some(_) => std::fs::canonicalize(&vehicle)
            .map_err(|e| failed(&vehicle, e))?
            .display()
            .to_string(),
    };
    let mut out = toml::Table::new();
    out.insert("schema_version".into(), toml::Value::Integer(1));
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
    let name = format!(
        "{}-calibrated.toml",
        vehicle
            .file_stem()
            .map(|s| s.to_string_lossy().to_string())
            .unwrap_or_default()
    );
    let (calibrated, path) = match dir {
        None => (
            vehicle.with_file_name(name),
            paths.reference("calibration-result.toml"),
        ),
        Some(d) => {
            std::fs::create_dir_all(d).map_err(|e| failed(d, e))?;
            (d.join(name), d.join("calibration-result.toml"))
        }
    };
    std::fs::write(&calibrated, text).map_err(|e| failed(&calibrated, e))?;
    let record_text = format!(
        "# Written by `touchdown calibrate` from reference/calibration-protocol.toml; the rows used are\n# the calibration rows of `touchdown validate`, every other row is held out.\n{}",
        toml::to_string(record).map_err(|e| ValidationError::Calibration(e.to_string()))?
    );
    std::fs::write(&path, record_text).map_err(|e| failed(&path, e))?;
    Ok([calibrated, path])
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::Strut;

    fn row(id: u32, strut: Strut) -> Row {
        Row {
            id,
            landing: "1-2-1".into(),
            vv: -10.0,
            vh: 4.0,
            strut,
            experiment: 4.0,
            analysis: 4.0,
            scenario: "none.toml".into(),
        }
    }

    /// A fit whose first row's stroke has a side basin near its initial value (a 5 %
    /// error at 150) and its deep one at 255 (no error) across a flat stretch, as row 3's
    /// stroke against FP1 has: started from the estimate, Nelder-Mead and its restarts stop in
    /// the side basin, since no restart's simplex reaches past the flat; started as well from
    /// the best point of a 5 × 5 grid over the bounds, the fit reaches the deep basin.
    #[test]
    fn a_grid_start_reaches_the_basin_a_restart_from_a_side_basin_does_not() {
        let parameters = [
            FitParameter {
                name: "FP1".into(),
                initial: 130.0,
                lower: 40.0,
                upper: 290.0,
            },
            FitParameter {
                name: "FS1".into(),
                initial: 60.0,
                lower: 20.0,
                upper: 140.0,
            },
        ];
        let rows = [row(3, Strut::Primary), row(7, Strut::Secondary)];
        let bump = |x: f64, at: f64, width: f64| (-((x - at) / width).powi(2)).exp();
        let predict = |row: &Row, x: &[f64]| -> Result<f64, ValidationError> {
            let error = match row.strut {
                Strut::Primary => {
                    0.1 * (1.0 - bump(x[0], 255.0, 12.0)) - 0.05 * bump(x[0], 150.0, 30.0)
                }
                Strut::Secondary => (x[1] - 75.0) / 75.0,
            };
            Ok(row.experiment * (1.0 + error))
        };
        let restarts = Restarts {
            simplex: 0.25,
            most: 6,
            improvement: 1e-4,
            grid: 0,
        };
        let side = fit(&rows, &parameters, 200, Some(restarts), &predict).unwrap();
        assert!((side.value[0] - 150.0).abs() < 5.0, "{side:?}");
        assert!(side.objective > 2e-3, "{side:?}");
        let grid = Restarts {
            grid: 5,
            ..restarts
        };
        let deep = fit(&rows, &parameters, 200, Some(grid), &predict).unwrap();
        assert!((deep.value[0] - 255.0).abs() < 0.5, "{deep:?}");
        assert!((deep.value[1] - 75.0).abs() < 0.05, "{deep:?}");
        assert!(deep.objective < 1e-9, "{deep:?}");
        assert!(deep.iterations > side.iterations);
    }
}
