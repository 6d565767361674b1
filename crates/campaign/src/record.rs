//! One landing of a campaign as a record: the values applied (read back from the scenario that
//! ran), what became of the landing (its outcome, and its failure mode as data), and what it
//! measured (strokes against capacities, peak loads and accelerations, stability distance,
//! energy residual). A record is a row of named cells; its columns are the same for every
//! landing of a campaign (docs/campaigns.md, "Records").

use crate::distribution::Value;
use crate::spec::Campaign;
use serde::{Deserialize, Serialize};
use touchdown_record::capacity::SECONDARY_NAMES;
use touchdown_record::{Outcome, RunError, Summary};

/// What a column holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Kind {
    /// A 64-bit integer.
    Integer,
    /// A 64-bit float.
    Float,
    /// A UTF-8 string.
    Text,
    /// A boolean.
    Flag,
}

/// A column of the records.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Column {
    /// Its name, with the unit as a suffix (`_m`, `_n`, `_s`, `_m_s2`; `_of_capacity` for a
    /// fraction of a strut's capacity).
    pub name: String,
    /// What it holds.
    pub kind: Kind,
}

/// One cell of a record.
#[derive(Debug, Clone, PartialEq)]
pub enum Cell {
    /// An integer.
    Integer(i64),
    /// A float (always finite).
    Float(f64),
    /// A string.
    Text(String),
    /// A boolean.
    Flag(bool),
    /// No value: a measurement of a landing that did not complete, or that does not apply
    /// (a decision time of an undecided landing). Left out of the JSON, null in Parquet.
    Missing,
}

impl From<Option<f64>> for Cell {
    fn from(x: Option<f64>) -> Cell {
        match x {
            Some(x) if x.is_finite() => Cell::Float(x),
            _ => Cell::Missing,
        }
    }
}

impl From<&Value> for Cell {
    fn from(v: &Value) -> Cell {
        match v {
            Value::Number(x) => Cell::Float(*x),
            Value::Text(s) => Cell::Text(s.clone()),
            Value::Flag(b) => Cell::Flag(*b),
        }
    }
}

/// What became of a landing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// A stable landing (the report's four conditions held).
    Stable,
    /// The vehicle overturned (its centre of mass crossed a stability wall).
    Unstable,
    /// Neither before the end time.
    Undecided,
    /// The engine stopped the run (a law left its domain, a divergence, the budget).
    Stopped,
    /// The engine refused the dispersed scenario (a value out of its domain).
    Refused,
}

impl Status {
    /// Every status, in report order.
    pub const ALL: [Status; 5] = [
        Status::Stable,
        Status::Unstable,
        Status::Undecided,
        Status::Stopped,
        Status::Refused,
    ];

    /// What became of a landing that ended with `result`.
    pub fn of(result: Result<&Summary, &RunError>) -> Status {
        match result {
            Ok(s) => match s.outcome {
                Outcome::Stable => Status::Stable,
                Outcome::Unstable => Status::Unstable,
                Outcome::Undecided => Status::Undecided,
            },
            Err(RunError::Refused(_)) => Status::Refused,
            Err(_) => Status::Stopped,
        }
    }

    /// Its name, as in records.
    pub fn name(self) -> &'static str {
        match self {
            Status::Stable => "stable",
            Status::Unstable => "unstable",
            Status::Undecided => "undecided",
            Status::Stopped => "stopped",
            Status::Refused => "refused",
        }
    }
}

/// A landing's failure mode, the first that applies in this order: refused, stopped,
/// overturned, stroke-out (a strut reached the end of its last crush stage), undecided; `none`
/// for a stable landing within every strut's capacity.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Failure {
    /// A stable landing within every strut's capacity.
    None,
    /// The engine refused the scenario.
    Refused,
    /// The engine stopped the run.
    Stopped,
    /// The vehicle overturned.
    Overturned,
    /// A strut stroked out (named in `stroke_outs`).
    StrokeOut,
    /// No stability decision before the end time.
    Undecided,
}

impl Failure {
    /// Every failure mode, in report order.
    pub const ALL: [Failure; 6] = [
        Failure::None,
        Failure::Overturned,
        Failure::StrokeOut,
        Failure::Undecided,
        Failure::Stopped,
        Failure::Refused,
    ];

    /// Its name, as in records.
    pub fn name(self) -> &'static str {
        match self {
            Failure::None => "none",
            Failure::Refused => "refused",
            Failure::Stopped => "stopped",
            Failure::Overturned => "overturned",
            Failure::StrokeOut => "stroke_out",
            Failure::Undecided => "undecided",
        }
    }
}

/// The columns of a campaign's records, in order: the landing, the values applied, then what
/// each engine measured ([`prefix`]).
pub fn columns(campaign: &Campaign) -> Vec<Column> {
    let col = |name: String, kind| Column { name, kind };
    let mut c = vec![col("landing".into(), Kind::Integer)];
    for d in &campaign.dispersions {
        let kind = match d.distribution.central() {
            Value::Number(_) => Kind::Float,
            Value::Text(_) => Kind::Text,
            Value::Flag(_) => Kind::Flag,
        };
        c.push(col(format!("applied.{}", d.column), kind));
    }
    for engine in &campaign.engines {
        engine_columns(
            &prefix(engine.name(), campaign.engines.len()),
            campaign.base_scenario.legs.len(),
            &mut c,
        );
    }
    c
}

/// What starts the names of the columns of `engine` (its name) in a campaign on `engines`
/// engines: nothing on one (`outcome`), the engine's name and a dot on several, a paired
/// campaign (`core.outcome`, `rapier.outcome`).
pub fn prefix(engine: &str, engines: usize) -> String {
    if engines > 1 {
        format!("{engine}.")
    } else {
        String::new()
    }
}

/// The columns of one engine's measurements of a landing of a vehicle with `legs` legs, their
/// names after `prefix`, appended to `c`.
fn engine_columns(prefix: &str, legs: usize, c: &mut Vec<Column>) {
    let mut col = |name: String, kind| {
        c.push(Column {
            name: format!("{prefix}{name}"),
            kind,
        })
    };
    for name in ["outcome", "failure", "stroke_outs"] {
        col(name.into(), Kind::Text);
    }
    for name in [
        "decision_time_s",
        "t_end_s",
        "overturn_velocity_m_s",
        "min_stability_distance_m",
        "peak_specific_force_m_s2",
        "peak_pitch_rate_rad_s",
        "energy_residual_j",
        "energy_scale_j",
    ] {
        col(name.into(), Kind::Float);
    }
    for leg in 1..=legs {
        for name in ["stroke_m", "stroke_of_capacity", "force_n"] {
            col(format!("leg{leg}.primary.{name}"), Kind::Float);
        }
        // Each leg's primary, then each secondary (3-1, 4-1) in compression and in tension.
        for s in SECONDARY_NAMES {
            for side in ["compression", "tension"] {
                for name in ["stroke_m", "stroke_of_capacity", "force_n"] {
                    col(format!("leg{leg}.secondary_{s}.{side}.{name}"), Kind::Float);
                }
            }
        }
    }
    col("stop.time_s".into(), Kind::Float);
    col("stop.law".into(), Kind::Text);
    col("stop.leg".into(), Kind::Integer);
    col("stop.message".into(), Kind::Text);
    col("refusal.file".into(), Kind::Text);
    col("refusal.field".into(), Kind::Text);
    col("refusal.message".into(), Kind::Text);
}

/// A landing's record: one cell per column of [`columns`].
pub type Row = Vec<Cell>;

/// Whether a record read back from a file is one a landing could have written: each engine's
/// `outcome` one of [`Status`]'s names and its `failure` one of [`Failure`]'s, both present
/// (the statistics count every landing once by each). `Err` says which column holds what.
pub fn check(columns: &[Column], row: &Row) -> Result<(), String> {
    // Each engine's block: `outcome` itself, or `<engine>.outcome`.
    let prefixes: Vec<&str> = columns
        .iter()
        .filter(|c| !c.name.starts_with("applied."))
        .filter_map(|c| c.name.strip_suffix("outcome"))
        .filter(|p| p.is_empty() || p.ends_with('.'))
        .collect();
    if prefixes.is_empty() {
        return Err("no `outcome` column: every record has one per engine".into());
    }
    for p in prefixes {
        check_block(columns, row, p)?;
    }
    Ok(())
}

/// [`check`] of the block of columns named after `prefix`.
fn check_block(columns: &[Column], row: &Row, prefix: &str) -> Result<(), String> {
    let named = |column: &str, names: &[&str]| {
        let column = format!("{prefix}{column}");
        let cell = columns
            .iter()
            .position(|c| c.name == column)
            .and_then(|i| row.get(i));
        match cell {
            Some(Cell::Text(t)) if names.contains(&t.as_str()) => Ok(()),
            Some(Cell::Text(t)) => Err(format!(
                "column {column:?}: {t:?} is not one of {}",
                names.join(", ")
            )),
            _ => Err(format!(
                "column {column:?} is missing: every record has one of {}",
                names.join(", ")
            )),
        }
    };
    named("outcome", &Status::ALL.map(Status::name))?;
    named("failure", &Failure::ALL.map(Failure::name))
}

/// The record of landing `landing` that ran with the values `applied` and ended on each of the
/// campaign's engines with `results` (in the campaign's order): the summary of a landing that
/// completed, or why it did not.
pub fn row(
    campaign: &Campaign,
    landing: u64,
    applied: &[Value],
    results: &[Result<&Summary, &RunError>],
) -> Row {
    let legs = campaign.base_scenario.legs.len();
    let mut r: Row = Vec::with_capacity(1 + applied.len() + results.len() * (18 + legs * 15));
    r.push(Cell::Integer(landing as i64));
    r.extend(applied.iter().map(Cell::from));
    for result in results {
        block(&mut r, legs, *result);
    }
    r
}

/// One engine's cells of a record ([`engine_columns`]), appended to `r`.
fn block(r: &mut Row, legs: usize, result: Result<&Summary, &RunError>) {
    let measured = result.ok();
    let status = Status::of(result);
    let (failure, stroke_outs) = match result {
        Ok(s) => {
            // The struts past their capacity, named `leg2.primary`, `leg1.secondary_3_1.tension`.
            let outs: Vec<&str> = s.past_capacity.iter().map(|p| p.strut.as_str()).collect();
            let failure = match (s.outcome, outs.is_empty()) {
                (Outcome::Unstable, _) => Failure::Overturned,
                (_, false) => Failure::StrokeOut,
                (Outcome::Undecided, true) => Failure::Undecided,
                (Outcome::Stable, true) => Failure::None,
            };
            (failure, outs)
        }
        Err(RunError::Refused(_)) => (Failure::Refused, Vec::new()),
        Err(_) => (Failure::Stopped, Vec::new()),
    };
    r.push(Cell::Text(status.name().into()));
    r.push(Cell::Text(failure.name().into()));
    r.push(Cell::Text(stroke_outs.join(",")));
    match measured {
        Some(s) => {
            r.push(s.decision_time_s.into());
            r.push(Some(s.t_end_s).into());
            r.push(s.overturn_velocity_m_s.into());
            r.push(Some(s.min_stability_distance_m).into());
            r.push(Some(s.peak_specific_force_m_s2).into());
            r.push(Some(s.peak_pitch_rate_rad_s).into());
            r.push(Some(s.energy_residual_j).into());
            r.push(Some(s.energy.scale()).into());
            let caps = &s.strut_capacity;
            for leg in 0..legs {
                let strut = |stroke: f64, cap: f64, force: f64, r: &mut Row| {
                    r.push(Some(stroke).into());
                    r.push(Some(stroke / cap).into());
                    r.push(Some(force).into());
                };
                strut(
                    s.max_primary_stroke_m[leg],
                    caps.primary.stroke_m,
                    s.peak_primary_force_n[leg],
                    r,
                );
                for j in 0..2 {
                    strut(
                        s.max_secondary_compression_m[leg][j],
                        caps.secondary_compression.stroke_m,
                        s.peak_secondary_compression_force_n[leg][j],
                        r,
                    );
                    strut(
                        s.max_secondary_tension_m[leg][j],
                        caps.secondary_tension.stroke_m,
                        s.peak_secondary_tension_force_n[leg][j],
                        r,
                    );
                }
            }
        }
        None => r.extend(std::iter::repeat_n(Cell::Missing, 8 + legs * 15)),
    }
    match result {
        Err(RunError::Stopped(d)) => {
            r.push(Some(d.time_s).into());
            r.push(Cell::Text(law_name(d.law)));
            r.push(d.leg.map_or(Cell::Missing, |l| Cell::Integer(l as i64)));
            r.push(Cell::Text(d.message.clone()));
        }
        _ => r.extend(std::iter::repeat_n(Cell::Missing, 4)),
    }
    match result {
        Err(RunError::Refused(touchdown_scenario::ScenarioError::Field {
            file,
            field,
            message,
        })) => {
            r.push(Cell::Text(file.clone()));
            r.push(Cell::Text(field.clone()));
            r.push(Cell::Text(message.clone()));
        }
        Err(RunError::Refused(e)) => {
            r.push(Cell::Missing);
            r.push(Cell::Missing);
            r.push(Cell::Text(e.to_string()));
        }
        _ => r.extend(std::iter::repeat_n(Cell::Missing, 3)),
    }
}

/// The law's name as its serde name (`primary_honeycomb`).
fn law_name(law: touchdown_record::Law) -> String {
    serde_json::to_value(law)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default()
}
