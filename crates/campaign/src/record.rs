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

/// What a column is to the analysis. The statistics, the pairing of engines and the records'
/// checks select their columns by role ([`Column::role`]), read here from the tables the
/// columns are made from ([`columns`]), never by a reading of names of their own.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// The landing's index (`landing`).
    Landing,
    /// A value applied to the landing (`applied.<column>`).
    Applied,
    /// An engine's outcome (`outcome`: a [`Status`] name).
    Outcome,
    /// An engine's failure mode (`failure`: a [`Failure`] name).
    Failure,
    /// The struts an engine's landing stroked out (`stroke_outs`).
    StrokeOuts,
    /// One of an engine's measurements of the landing.
    Measure(Measure),
    /// Why an engine did not complete the landing (`stop.*`, `refusal.*`).
    Diagnostic,
}

/// An engine's measurement of a landing: of the landing as a whole, or of one strut (a column
/// `leg<N>.<strut>.<quantity>`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Measure {
    /// When the outcome was decided, s.
    DecisionTime,
    /// When the run ended, s.
    EndTime,
    /// The centre of mass's speed across a stability wall, m/s.
    OverturnVelocity,
    /// The least stability distance, m.
    MinStabilityDistance,
    /// The largest specific force at the centre of mass, m/s².
    PeakSpecificForce,
    /// The peak pitch rate, rad/s.
    PeakPitchRate,
    /// The energy balance's residual, J.
    EnergyResidual,
    /// The energy balance's scale, J.
    EnergyScale,
    /// The energy balance's residual, in magnitude, as a fraction of its scale: how closely the
    /// engine's integration kept the landing's energy.
    EnergyImbalance,
    /// A strut's largest stroke, m.
    Stroke,
    /// A strut's largest stroke as a fraction of its capacity.
    StrokeOfCapacity,
    /// A strut's largest force, N.
    Force,
}

impl Measure {
    /// Whether the statistics give its percentiles over the landings (`statistics.json`,
    /// `percentiles`).
    pub fn has_percentiles(self) -> bool {
        matches!(
            self,
            Measure::StrokeOfCapacity
                | Measure::Force
                | Measure::PeakSpecificForce
                | Measure::MinStabilityDistance
                | Measure::EnergyImbalance
        )
    }

    /// Whether a paired campaign reports its paired differences between engines.
    pub fn paired(self) -> bool {
        matches!(self, Measure::Stroke | Measure::MinStabilityDistance)
    }
}

/// Each engine's account of a landing: the columns after its prefix, in order.
const ACCOUNT: [(&str, Role); 3] = [
    ("outcome", Role::Outcome),
    ("failure", Role::Failure),
    ("stroke_outs", Role::StrokeOuts),
];

/// Each engine's measurements of the landing as a whole, in order.
const LANDING_MEASURES: [(&str, Measure); 9] = [
    ("decision_time_s", Measure::DecisionTime),
    ("t_end_s", Measure::EndTime),
    ("overturn_velocity_m_s", Measure::OverturnVelocity),
    ("min_stability_distance_m", Measure::MinStabilityDistance),
    ("peak_specific_force_m_s2", Measure::PeakSpecificForce),
    ("peak_pitch_rate_rad_s", Measure::PeakPitchRate),
    ("energy_residual_j", Measure::EnergyResidual),
    ("energy_scale_j", Measure::EnergyScale),
    ("energy_imbalance_of_scale", Measure::EnergyImbalance),
];

/// Each strut's measurements (`leg<N>.<strut>.<quantity>`), in order.
const STRUT_MEASURES: [(&str, Measure); 3] = [
    ("stroke_m", Measure::Stroke),
    ("stroke_of_capacity", Measure::StrokeOfCapacity),
    ("force_n", Measure::Force),
];

/// Each engine's diagnostics of a landing it did not complete, in order.
const DIAGNOSTICS: [(&str, Kind); 7] = [
    ("stop.time_s", Kind::Float),
    ("stop.law", Kind::Text),
    ("stop.leg", Kind::Integer),
    ("stop.message", Kind::Text),
    ("refusal.file", Kind::Text),
    ("refusal.field", Kind::Text),
    ("refusal.message", Kind::Text),
];

impl Column {
    /// Its role, read from its name against the tables the columns are made from: `landing`,
    /// `applied.*`, and an engine's columns after its prefix ([`prefix`]). `None` for a name no
    /// campaign writes.
    pub fn role(&self) -> Option<Role> {
        let name = self.name.as_str();
        if name == "landing" {
            return Some(Role::Landing);
        }
        if name.starts_with("applied.") {
            return Some(Role::Applied);
        }
        let own = unprefixed(name);
        let find = |table: &[(&str, Role)]| table.iter().find(|(n, _)| *n == own).map(|r| r.1);
        if let Some(role) = find(&ACCOUNT) {
            return Some(role);
        }
        if let Some((_, m)) = LANDING_MEASURES.iter().find(|(n, _)| *n == own) {
            return Some(Role::Measure(*m));
        }
        if let Some((_, quantity)) = strut_parts(own) {
            let m = STRUT_MEASURES.iter().find(|(n, _)| *n == quantity)?;
            return Some(Role::Measure(m.1));
        }
        DIAGNOSTICS
            .iter()
            .any(|(n, _)| *n == own)
            .then_some(Role::Diagnostic)
    }

    /// Its measurement, if it is one.
    pub fn measure(&self) -> Option<Measure> {
        match self.role() {
            Some(Role::Measure(m)) => Some(m),
            _ => None,
        }
    }
}

/// A column's name without its engine's prefix (`core.outcome` → `outcome`; unchanged on a
/// single engine's columns, which have none).
fn unprefixed(name: &str) -> &str {
    match name.split_once('.') {
        Some((engine, rest)) if engine.parse::<touchdown_scenario::schema::Engine>().is_ok() => {
            rest
        }
        _ => name,
    }
}

/// A strut measurement's strut and quantity: `leg2.primary.force_n` → (`leg2.primary.`,
/// `force_n`); `None` for a name that is not `leg<N>.<...>.<quantity>`.
fn strut_parts(own: &str) -> Option<(&str, &str)> {
    let digits = own.strip_prefix("leg")?;
    if !digits.starts_with(|c: char| c.is_ascii_digit()) {
        return None;
    }
    let dot = own.rfind('.')?;
    Some((&own[..=dot], &own[dot + 1..]))
}

/// The strut a strut measurement's name (after the engine's prefix) is of, with its dot:
/// `leg2.secondary_3_1.tension.stroke_of_capacity` → `leg2.secondary_3_1.tension.`.
pub fn strut_of(name: &str) -> Option<&str> {
    strut_parts(unprefixed(name)).map(|(strut, _)| strut)
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
    for (name, _) in ACCOUNT {
        col(name.into(), Kind::Text);
    }
    for (name, _) in LANDING_MEASURES {
        col(name.into(), Kind::Float);
    }
    for leg in 1..=legs {
        for (name, _) in STRUT_MEASURES {
            col(format!("leg{leg}.primary.{name}"), Kind::Float);
        }
        // Each leg's primary, then each secondary (3-1, 4-1) in compression and in tension.
        for s in SECONDARY_NAMES {
            for side in ["compression", "tension"] {
                for (name, _) in STRUT_MEASURES {
                    col(format!("leg{leg}.secondary_{s}.{side}.{name}"), Kind::Float);
                }
            }
        }
    }
    for (name, kind) in DIAGNOSTICS {
        col(name.into(), kind);
    }
}

/// A landing's record: one cell per column of [`columns`].
pub type Row = Vec<Cell>;

/// Whether a record read back from a file is one a landing could have written: each engine's
/// `outcome` one of [`Status`]'s names and its `failure` one of [`Failure`]'s, both present
/// (the statistics count every landing once by each). `Err` says which column holds what.
pub fn check(columns: &[Column], row: &Row) -> Result<(), String> {
    // Each engine's block: `outcome` itself, or `<engine>.outcome`. This runs for every record
    // read back, so a column's role is read only where its name can be an outcome's.
    let prefixes: Vec<&str> = columns
        .iter()
        .filter_map(|c| Some((c.name.strip_suffix("outcome")?, c)))
        .filter(|(_, c)| c.role() == Some(Role::Outcome))
        .map(|(p, _)| p)
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
    let per_engine = ACCOUNT.len()
        + LANDING_MEASURES.len()
        + legs * 5 * STRUT_MEASURES.len()
        + DIAGNOSTICS.len();
    let mut r: Row = Vec::with_capacity(1 + applied.len() + results.len() * per_engine);
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
            r.push(Some(s.energy_residual_j.abs() / s.energy.scale()).into());
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
        None => r.extend(std::iter::repeat_n(
            Cell::Missing,
            LANDING_MEASURES.len() + legs * 5 * STRUT_MEASURES.len(),
        )),
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Every column a campaign on one engine or on two writes has the role of the table it is
    /// made from, whatever the engine's prefix; a name no campaign writes has none.
    #[test]
    fn every_column_has_the_role_of_its_table() {
        for prefix in ["", "core.", "mujoco."] {
            let mut c = Vec::new();
            engine_columns(prefix, 4, &mut c);
            let role = |name: &str| {
                let full = format!("{prefix}{name}");
                let column = c.iter().find(|c| c.name == full).expect("a column");
                column.role()
            };
            assert_eq!(role("outcome"), Some(Role::Outcome));
            assert_eq!(role("failure"), Some(Role::Failure));
            assert_eq!(role("stroke_outs"), Some(Role::StrokeOuts));
            assert_eq!(
                role("min_stability_distance_m"),
                Some(Role::Measure(Measure::MinStabilityDistance))
            );
            assert_eq!(
                role("leg4.secondary_4_1.tension.stroke_of_capacity"),
                Some(Role::Measure(Measure::StrokeOfCapacity))
            );
            assert_eq!(
                role("leg1.primary.stroke_m"),
                Some(Role::Measure(Measure::Stroke))
            );
            assert_eq!(role("stop.leg"), Some(Role::Diagnostic));
            assert!(c.iter().all(|c| c.role().is_some()), "{c:?}");
            // 3 accounts, 9 landing measures, 4 legs of 5 struts of 3, 7 diagnostics.
            assert_eq!(c.len(), 3 + 9 + 4 * 5 * 3 + 7);
            let strut = c.iter().find(|c| c.name.ends_with("leg2.primary.force_n"));
            assert_eq!(strut.and_then(|c| strut_of(&c.name)), Some("leg2.primary."));
        }
        let named = |name: &str| Column {
            name: name.into(),
            kind: Kind::Float,
        };
        assert_eq!(named("landing").role(), Some(Role::Landing));
        assert_eq!(named("applied.vv_ft_s").role(), Some(Role::Applied));
        assert_eq!(named("core.leg2.primary.colour").role(), None);
        assert_eq!(named("speed_m_s").role(), None);
    }
}
