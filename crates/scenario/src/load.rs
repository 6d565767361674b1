//! Loading a scenario: the entry points ([`Scenario::load`], [`Scenario::load_with`],
//! [`ScenarioBase`] for many landings of one file) and the resolved scenario's queries. Each
//! stage has its module: `read` (the file and its `extends` chain), `overrides` (values set at
//! field paths), `check` (which file sets a field; numbers in SI within their range) and
//! `resolve` (the schema-checked file into SI). Every error names the file and the field.

use crate::check::{owner_of, Check, OVERRIDES};
use crate::dimension::{Dimension, Powers};
use crate::error::ScenarioError;
use crate::model::{self, Scenario};
use crate::overrides::{field_at, set_path, set_path_creating};
use crate::ranges;
use crate::read::{load_merged, parse, Merged};
use crate::resolve::{
    resolve_integrator, resolve_layers, resolve_mujoco, resolve_rapier, resolve_touchdown,
};
use crate::schema::{self};
use crate::units::Units;
use crate::Warning;
use std::path::Path;

impl Scenario {
    /// Reads, merges, checks and resolves the scenario at `path`.
    pub fn load(path: impl AsRef<Path>) -> Result<Scenario, ScenarioError> {
        let path = path.as_ref();
        resolve_layers(path.display().to_string(), load_merged(path, 0)?)
    }

    /// Reads the scenario at `path` with some values replaced: each override is a field path
    /// such as `primary_strut.compression.stages[0].crush_load` and a value in the file's own
    /// units ([`ScenarioBase::with`]).
    pub fn load_with(
        path: impl AsRef<Path>,
        overrides: &[(&str, f64)],
    ) -> Result<Scenario, ScenarioError> {
        let values: Vec<(&str, toml::Value)> = overrides
            .iter()
            .map(|(field, v)| (*field, toml::Value::Float(*v)))
            .collect();
        ScenarioBase::load(path)?.with(&values)
    }

    /// The values at field paths (`touchdown.attitude[2]`) of the resolved scenario, in the
    /// file's units, every default filled in: what a landing ran with (a campaign reads back the
    /// values it applied). `None` for a path with no field.
    pub fn values_of<'a>(
        &self,
        fields: impl IntoIterator<Item = &'a str>,
    ) -> Vec<Option<toml::Value>> {
        let file = toml::Value::try_from(&self.file).ok();
        fields
            .into_iter()
            .map(|field| file.as_ref().and_then(|f| field_at(f, field)).cloned())
            .collect()
    }

    /// The dimension of the number at `field` (`gear.legs[1].primary_strut.viscous.coefficient`),
    /// from its row of [`ranges::RANGES`]: a viscous coefficient's follows the exponent beside
    /// it in this scenario, a polynomial coefficient's its index. `None` for a field with no
    /// row (a count, a flag, or no field at all).
    pub fn dimension_of(&self, field: &str) -> Option<Result<Dimension, String>> {
        let row = ranges::lookup(field)?;
        let gamma = field
            .strip_suffix("viscous.coefficient")
            .map(|strut| format!("{strut}viscous.exponent"))
            .and_then(|exponent| self.values_of([exponent.as_str()]).pop().flatten())
            .and_then(|v| v.as_float().or(v.as_integer().map(|i| i as f64)));
        let index = field
            .strip_suffix(']')
            .and_then(|f| f.rsplit_once('['))
            .and_then(|(_, i)| i.parse::<u32>().ok())
            .map(f64::from);
        Some(Dimension::parse(row.unit, Powers { gamma, index }))
    }

    /// Checks that `unit` (written beside numbers meant for `field`, as a campaign does:
    /// `"ft/s"`, `"1"`; already checked to name this file's own units by
    /// [`Units::suffix_of`]) is of the field's dimension ([`Scenario::dimension_of`]), so that a
    /// length given to a velocity is refused rather than read as one. The error says what is
    /// wrong and the unit to write.
    pub fn check_unit_dimension(&self, field: &str, unit: &str) -> Result<(), String> {
        let given = Dimension::parse(unit, Powers::default())?;
        let wanted = match self.dimension_of(field) {
            Some(d) => d?,
            None => Dimension::NONE,
        };
        if given == wanted {
            return Ok(());
        }
        let write = match wanted.written_in(&self.units()) {
            Some(w) => format!("write its numbers in {w}"),
            None => "no unit with whole powers names it".into(),
        };
        Err(format!(
            "{unit:?} is {}, but `{field}` is {}: {write}",
            article(&given.words()),
            article(&wanted.words())
        ))
    }

    /// A number of the merged file at a field path (file units), as [`Scenario::load_with`]
    /// takes it; `None` if there is no number there.
    pub fn value_at(path: impl AsRef<Path>, field: &str) -> Result<Option<f64>, ScenarioError> {
        let merged = toml::Value::Table(load_merged(path.as_ref(), 0)?.table);
        Ok(
            field_at(&merged, field)
                .and_then(|v| v.as_float().or(v.as_integer().map(|i| i as f64))),
        )
    }

    /// Parses a scenario from TOML text (no `extends`); `source` names it in messages.
    pub fn from_toml(source: &str, text: &str) -> Result<Scenario, ScenarioError> {
        let base = ScenarioBase::from_toml(source, text)?;
        resolve_layers(base.source, base.merged)
    }

    /// The resolved scenario as TOML (every default written out, the file's units).
    pub fn to_toml(&self) -> String {
        toml::to_string(&self.file).expect("a scenario always serialises")
    }

    /// The units the file's numbers were read in ([`schema::ScenarioFile::read_units`]).
    pub fn units(&self) -> Units {
        self.file.read_units()
    }

    /// SHA-256 of the resolved scenario ([`Scenario::to_toml`]), hex: what identifies a
    /// scenario in exported models and comparison snapshots.
    pub fn sha256(&self) -> String {
        use sha2::{Digest, Sha256};
        format!("{:x}", Sha256::digest(self.to_toml().as_bytes()))
    }

    /// The file of the `extends` chain that sets `field` (a path such as
    /// `primary_strut.compression.stages[1]`), to name it in messages about that field.
    pub fn file_of(&self, field: &str) -> &str {
        owner_of(&self.layers, field)
    }

    /// Refuses `engine` unless the scenario lists it in `engines.applicable` and the engine
    /// models every mechanism the scene declares: `unsupported` is the engine's own declaration
    /// (why it does not model a mechanism, or `None` if it does). Every engine calls this with
    /// its declaration before it builds anything.
    pub fn require_engine(
        &self,
        engine: schema::Engine,
        unsupported: impl Fn(model::Mechanism) -> Option<&'static str>,
    ) -> Result<(), ScenarioError> {
        if let Some((m, why)) = self
            .mechanisms()
            .into_iter()
            .find_map(|m| unsupported(m).map(|why| (m, why)))
        {
            return Err(ScenarioError::field(
                self.file_of(m.field()),
                m.field(),
                format!(
                    "the {engine} engine does not model {}: {why} (docs/engines.md lists what each engine supports); run this scene on the core",
                    m.name()
                ),
            ));
        }
        if self.applicable_engines.contains(&engine) {
            return Ok(());
        }
        let listed: Vec<&str> = self.applicable_engines.iter().map(|e| e.name()).collect();
        Err(ScenarioError::field(
            self.file_of("engines.applicable"),
            "engines.applicable",
            format!(
                "the scenario does not apply to the {engine} engine (it lists {})",
                listed.join(", ")
            ),
        ))
    }
}

/// A scenario file read and merged once (its `extends` chain followed), to be resolved many
/// times with different values: a campaign's landings, a sensitivity study.
#[derive(Debug, Clone)]
pub struct ScenarioBase {
    source: String,
    merged: Merged,
}

impl ScenarioBase {
    /// Reads and merges the scenario file at `path` (not yet checked against the schema).
    pub fn load(path: impl AsRef<Path>) -> Result<ScenarioBase, ScenarioError> {
        let path = path.as_ref();
        Ok(ScenarioBase {
            source: path.display().to_string(),
            merged: load_merged(path, 0)?,
        })
    }

    /// A scenario given as TOML text (no `extends`); `source` names it in messages.
    pub fn from_toml(source: &str, text: &str) -> Result<ScenarioBase, ScenarioError> {
        let table = parse(source, text)?;
        if table.contains_key("extends") {
            return Err(ScenarioError::field(
                source,
                "extends",
                "a scenario given as text cannot extend a file (its path would be relative to nothing): give the path of a file that extends it, or the whole scenario without `extends`",
            ));
        }
        Ok(ScenarioBase {
            source: source.to_string(),
            merged: Merged {
                layers: vec![(source.to_string(), table.clone())],
                table,
            },
        })
    }

    /// What names the scenario in messages: its file's path, or the name given with its text.
    pub fn source(&self) -> &str {
        &self.source
    }

    /// The merged file as TOML values, in the file's units.
    pub fn table(&self) -> &toml::Table {
        &self.merged.table
    }

    /// The scenario with some values replaced: each override is a field path such as
    /// `primary_strut.compression.stages[0].crush_load` or `touchdown.attitude[2]` and a value
    /// in the file's own units, of the kind the field holds (a number for a number, a string for
    /// a string, a boolean for a boolean, an array for an array, replaced whole, a table for a
    /// table, merged key by key; a number or an array where a field takes either). `extends`,
    /// `units` and `schema_version` cannot be overridden. The overrides form the top layer of the `extends`
    /// chain (named `overrides` in messages); a path that does not exist in the merged file is
    /// an error.
    pub fn with(&self, overrides: &[(&str, toml::Value)]) -> Result<Scenario, ScenarioError> {
        let mut merged = self.merged.clone();
        let mut layer = toml::Table::new();
        for (field, value) in overrides {
            set_path(&mut merged.table, field, value, false)
                .map_err(|m| ScenarioError::field(OVERRIDES, *field, m))?;
            set_path_creating(&mut layer, field, value);
        }
        merged.layers.insert(0, (OVERRIDES.to_string(), layer));
        resolve_layers(self.source.clone(), merged)
    }
}

impl Scenario {
    /// The scenario with its rapier settings changed by `change` (command-line flags), checked
    /// as the file's own would be; the resolved scenario written out shows the new values.
    pub fn with_rapier(
        mut self,
        change: impl FnOnce(&mut schema::Rapier),
    ) -> Result<Scenario, ScenarioError> {
        change(&mut self.file.engines.rapier);
        self.rechecked(
            "engines.rapier.",
            |c, f, u| resolve_rapier(c, &f.engines.rapier, u),
            |s, v| s.rapier = v,
        )
    }

    /// The scenario with its integrator settings changed by `change` (file units, as in the
    /// file), checked as the file's own would be; the resolved scenario written out shows the
    /// new values.
    pub fn with_integrator(
        mut self,
        change: impl FnOnce(&mut schema::Integrator),
    ) -> Result<Scenario, ScenarioError> {
        change(&mut self.file.integrator);
        let surface = self.surface.clone();
        self.rechecked(
            "integrator.",
            |c, f, u| resolve_integrator(c, &f.integrator, u, &surface),
            |s, v| s.integrator = v,
        )
    }

    /// The scenario with its touchdown conditions changed by `change` (file units, as in the
    /// file), checked as the file's own would be; the resolved scenario written out shows the
    /// new values.
    pub fn with_touchdown(
        mut self,
        change: impl FnOnce(&mut schema::Touchdown),
    ) -> Result<Scenario, ScenarioError> {
        change(&mut self.file.touchdown);
        self.rechecked(
            "touchdown.",
            |c, f, u| resolve_touchdown(c, &f.touchdown, u),
            |s, v| s.touchdown = v,
        )
    }

    /// The scenario with its MuJoCo settings changed by `change` (command-line flags), checked
    /// as the file's own would be; the resolved scenario written out shows the new values.
    pub fn with_mujoco(
        mut self,
        change: impl FnOnce(&mut schema::Mujoco),
    ) -> Result<Scenario, ScenarioError> {
        change(&mut self.file.engines.mujoco);
        self.rechecked(
            "engines.mujoco.",
            |c, f, u| resolve_mujoco(c, &f.engines.mujoco, u),
            |s, v| s.mujoco = v,
        )
    }

    /// The table under `prefix` resolved again from the file by `resolve` and stored by
    /// `store`, its warnings replacing the old ones.
    fn rechecked<T>(
        mut self,
        prefix: &str,
        resolve: impl FnOnce(&Check, &schema::ScenarioFile, &Units) -> Result<T, ScenarioError>,
        store: impl FnOnce(&mut Scenario, T),
    ) -> Result<Scenario, ScenarioError> {
        let c = Check::new(&self.layers);
        let value = resolve(&c, &self.file, &self.units())?;
        let warnings = c.into_warnings();
        store(&mut self, value);
        self.replace_warnings(prefix, warnings);
        Ok(self)
    }

    /// The warnings of the fields under `prefix` replaced by `warnings` (a table re-checked).
    fn replace_warnings(&mut self, prefix: &str, warnings: Vec<Warning>) {
        self.warnings.retain(|w| !w.field.starts_with(prefix));
        self.warnings.extend(warnings);
    }
}

/// A dimension's words with their article: `a length/time`, `a pure number`.
fn article(words: &str) -> String {
    if words.starts_with("a ") {
        words.to_string()
    } else if words.starts_with(['a', 'e', 'i', 'o', 'u']) {
        format!("an {words}")
    } else {
        format!("a {words}")
    }
}
