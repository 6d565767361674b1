//! The field checker of a file and the chain it extends: which file sets a field, errors that
//! name it, numbers brought to SI and checked against their plausible range (`crate::ranges`),
//! and the warnings of values outside their usual range.

use crate::error::ScenarioError;
use crate::model::{self};
use crate::ranges;
use crate::schema::{self, PerPad, Trunnion};
use crate::units::{short, Units};
use crate::Warning;
use nalgebra::Vector3;

/// Name of the layer [`Scenario::load_with`] puts its overrides in.
pub(crate) const OVERRIDES: &str = "overrides";

/// The file (of an `extends` chain) that sets the value at a serde path such as
/// `primary_strut.compression.stages[1].crush_load`: the first layer that has it, or, for a
/// field no layer has (a missing field), the first that has its closest enclosing table, or the
/// top file.
pub(crate) fn owner_of<'a>(layers: &'a [(String, toml::Table)], path: &str) -> &'a str {
    let keys: Vec<&str> = path
        .split('.')
        .map(|k| k.split('[').next().unwrap_or(k))
        .filter(|k| !k.is_empty())
        .collect();
    for n in (1..=keys.len()).rev() {
        if let Some(file) = first_layer_with(layers, &keys[..n]) {
            return file;
        }
    }
    layers
        .iter()
        .find(|(file, _)| file != OVERRIDES)
        .unwrap_or(&layers[0])
        .0
        .as_str()
}

/// The first layer that sets the value at `keys` (or a non-table value on the way to it).
pub(crate) fn first_layer_with<'a>(
    layers: &'a [(String, toml::Table)],
    keys: &[&str],
) -> Option<&'a str> {
    for (file, table) in layers {
        let mut node = Some(table);
        let mut found = !keys.is_empty();
        for (i, k) in keys.iter().enumerate() {
            match node.and_then(|t| t.get(*k)) {
                Some(toml::Value::Table(t)) if i + 1 < keys.len() => node = Some(t),
                Some(_) => break,
                None => {
                    found = false;
                    break;
                }
            }
        }
        if found {
            return Some(file);
        }
    }
    None
}

/// Field checker bound to one file and the chain it extends: an error names the file that
/// sets the field. It also collects the warnings of values outside their usual range.
pub(crate) struct Check<'a> {
    pub(crate) layers: &'a [(String, toml::Table)],
    warnings: std::cell::RefCell<Vec<Warning>>,
}

#[cfg(test)]
thread_local! {
    /// Fields range-checked on this thread (tests: every field of a scenario is checked).
    pub(crate) static RANGE_CHECKED: std::cell::RefCell<std::collections::BTreeSet<String>> =
        const { std::cell::RefCell::new(std::collections::BTreeSet::new()) };
    /// Each range-checked field and the factor its value was brought to SI with (tests: the
    /// factor is its dimension's in the file's units).
    pub(crate) static SI_FACTORS: std::cell::RefCell<Vec<(String, f64)>> =
        const { std::cell::RefCell::new(Vec::new()) };
}

impl<'a> Check<'a> {
    pub(crate) fn new(layers: &'a [(String, toml::Table)]) -> Self {
        Check {
            layers,
            warnings: std::cell::RefCell::new(Vec::new()),
        }
    }
    /// The warnings collected.
    pub(crate) fn into_warnings(self) -> Vec<Warning> {
        self.warnings.into_inner()
    }
}

impl Check<'_> {
    pub(crate) fn err(&self, field: &str, message: impl Into<String>) -> ScenarioError {
        ScenarioError::field(owner_of(self.layers, field), field, message)
    }
    /// An error for two fields that exclude each other, `field` and `other`: it names the one
    /// set nearest the top of the chain (the file being written, or the command line's
    /// overrides; `field` when one layer sets both) and says which file sets the other, so
    /// that a file adding one over a base that has the other is told about its own line.
    pub(crate) fn conflict(&self, field: &str, other: &str, message: &str) -> ScenarioError {
        let layer = |f: &str| {
            let owner = owner_of(self.layers, f);
            self.layers.iter().position(|(file, _)| file == owner)
        };
        let (near, far) = if layer(other) < layer(field) {
            (other, field)
        } else {
            (field, other)
        };
        let far_file = owner_of(self.layers, far);
        self.err(near, format!("{message} ({far} is set in {far_file})"))
    }
    pub(crate) fn warn(&self, field: &str, message: impl Into<String>) {
        self.warnings.borrow_mut().push(Warning {
            file: owner_of(self.layers, field).to_string(),
            field: field.to_string(),
            message: message.into(),
        });
    }
    pub(crate) fn finite(&self, field: &str, v: f64) -> Result<f64, ScenarioError> {
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.err(field, format!("expected a finite number, got {}", short(v))))
        }
    }
    pub(crate) fn positive(&self, field: &str, v: f64) -> Result<f64, ScenarioError> {
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(self.err(
                field,
                format!("expected a positive number, got {}", short(v)),
            ))
        }
    }
    pub(crate) fn non_negative(&self, field: &str, v: f64) -> Result<f64, ScenarioError> {
        if v.is_finite() && v >= 0.0 {
            Ok(v)
        } else {
            Err(self.err(field, format!("expected a number ≥ 0, got {}", short(v))))
        }
    }
    /// `v` (file units) in SI, `v·scale`, checked against the field's plausible range
    /// ([`ranges::RANGES`]): outside it an error, outside its usual range a warning.
    pub(crate) fn si(&self, field: &str, v: f64, scale: f64) -> Result<f64, ScenarioError> {
        let x = v * scale;
        let Some(r) = ranges::lookup(field) else {
            return Ok(x);
        };
        #[cfg(test)]
        RANGE_CHECKED.with(|c| c.borrow_mut().insert(ranges::normalize(field)));
        #[cfg(test)]
        SI_FACTORS.with(|c| c.borrow_mut().push((field.to_string(), scale)));
        let shown = x / r.si;
        let unit = if r.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", r.unit)
        };
        let value = if (shown - v).abs() <= 1e-9 * v.abs() {
            format!("{}{unit}", short(v))
        } else {
            format!("{} in the file's units ({}{unit})", short(v), short(shown))
        };
        if !r.contains(x) {
            return Err(self.err(
                field,
                format!(
                    "{value} is outside the plausible range {}: {}",
                    r.interval(),
                    r.reason
                ),
            ));
        }
        if !r.is_usual(x) {
            self.warn(
                field,
                format!(
                    "{value} is outside the usual range {} but within the plausible range {}, so it is accepted: {}",
                    r.usual_interval().unwrap_or_default(),
                    r.interval(),
                    r.reason
                ),
            );
        }
        Ok(x)
    }
    /// [`Check::positive`], then [`Check::si`].
    pub(crate) fn positive_si(
        &self,
        field: &str,
        v: f64,
        scale: f64,
    ) -> Result<f64, ScenarioError> {
        self.si(field, self.positive(field, v)?, scale)
    }
    /// [`Check::non_negative`], then [`Check::si`].
    pub(crate) fn non_negative_si(
        &self,
        field: &str,
        v: f64,
        scale: f64,
    ) -> Result<f64, ScenarioError> {
        self.si(field, self.non_negative(field, v)?, scale)
    }
    /// A whole number ≥ 1 (a count), checked against its range like [`Check::si`].
    pub(crate) fn whole(&self, field: &str, v: f64) -> Result<u32, ScenarioError> {
        let x = self.si(field, self.positive(field, v)?, 1.0)?;
        if x.fract() != 0.0 {
            return Err(self.err(field, format!("expected a whole number, got {v}")));
        }
        Ok(x as u32)
    }
    /// [`Check::finite`], then [`Check::si`].
    pub(crate) fn finite_si(&self, field: &str, v: f64, scale: f64) -> Result<f64, ScenarioError> {
        self.si(field, self.finite(field, v)?, scale)
    }
    pub(crate) fn vec3(
        &self,
        field: &str,
        v: [f64; 3],
        scale: f64,
    ) -> Result<Vector3<f64>, ScenarioError> {
        let mut out = Vector3::zeros();
        for (i, x) in v.iter().enumerate() {
            out[i] = self.finite_si(&format!("{field}[{i}]"), *x, scale)?;
        }
        Ok(out)
    }
    pub(crate) fn per_pad(
        &self,
        field: &str,
        v: &PerPad,
        n: usize,
    ) -> Result<Vec<f64>, ScenarioError> {
        let values = match v {
            PerPad::All(x) => vec![*x; n],
            PerPad::Each(xs) if xs.len() == n => xs.clone(),
            PerPad::Each(xs) => {
                return Err(self.err(
                    field,
                    format!(
                        "expected one value or {n} values (one per leg), got {}",
                        xs.len()
                    ),
                ))
            }
        };
        for (i, x) in values.iter().enumerate() {
            self.finite(&format!("{field}[{i}]"), *x)?;
        }
        Ok(values)
    }
    /// Each of `values` (file units), as `field[i]`, through [`Check::si`]; SI.
    pub(crate) fn each_si(
        &self,
        field: &str,
        values: &[f64],
        scale: f64,
    ) -> Result<Vec<f64>, ScenarioError> {
        values
            .iter()
            .enumerate()
            .map(|(i, x)| self.si(&format!("{field}[{i}]"), *x, scale))
            .collect()
    }
    pub(crate) fn load_stroke(
        &self,
        field: &str,
        ls: &schema::LoadStroke,
        max_stages: usize,
        u: &Units,
    ) -> Result<model::LoadStroke, ScenarioError> {
        let k = u.stiffness();
        let onset_rate = self.positive_si(&format!("{field}.onset_rate"), ls.onset_rate, k)?;
        let backoff_rate =
            self.positive_si(&format!("{field}.backoff_rate"), ls.backoff_rate, k)?;
        let stroke_out_rate =
            self.positive_si(&format!("{field}.stroke_out_rate"), ls.stroke_out_rate, k)?;
        if ls.stages.is_empty() || ls.stages.len() > max_stages {
            return Err(self.err(
                &format!("{field}.stages"),
                format!("expected 1 to {max_stages} stages, got {}", ls.stages.len()),
            ));
        }
        let mut stages = Vec::with_capacity(ls.stages.len());
        for (i, s) in ls.stages.iter().enumerate() {
            let f = format!("{field}.stages[{i}]");
            let load = self.positive_si(&format!("{f}.crush_load"), s.crush_load, u.force())?;
            let end = self.positive_si(&format!("{f}.stroke_end"), s.stroke_end, u.length())?;
            stages.push((load, end));
        }
        let field = format!("{field}.stop_restitution");
        let e = self.non_negative(&field, ls.stop_restitution)?;
        if e > 1.0 {
            return Err(self.err(
                &field,
                format!("expected a number in [0, 1], got {}", short(e)),
            ));
        }
        let e = self.si(&field, e, 1.0)?;
        Ok(model::LoadStroke {
            onset_rate,
            backoff_rate,
            stroke_out_rate,
            stages,
            stop_restitution: e,
        })
    }
    pub(crate) fn trunnion(
        &self,
        field: &str,
        t: Trunnion,
        u: &Units,
    ) -> Result<Option<f64>, ScenarioError> {
        match t {
            Trunnion::Rigid(_) => Ok(None),
            Trunnion::Rate(k) => Ok(Some(self.positive_si(field, k, u.stiffness())?)),
        }
    }
    pub(crate) fn viscous(
        &self,
        field: &str,
        v: schema::Viscous,
        u: &Units,
    ) -> Result<model::Viscous, ScenarioError> {
        let exponent = self.positive_si(&format!("{field}.exponent"), v.exponent, 1.0)?;
        let coefficient = self.non_negative_si(
            &format!("{field}.coefficient"),
            v.coefficient,
            u.viscous_coefficient(exponent),
        )?;
        Ok(model::Viscous {
            coefficient,
            exponent,
        })
    }
}
