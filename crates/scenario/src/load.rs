//! Reading a scenario file: TOML parsing, `extends` merging, schema checking and resolution
//! into SI with validation. Every error names the file and the field.

use crate::dimension::{Dimension, Powers};
use crate::error::ScenarioError;
use crate::mechanisms;
use crate::model::{self, Scenario};
use crate::ranges;
use crate::schema::{self, PerPad, ScenarioFile, Trunnion, SCHEMA_VERSION};
use crate::strict::Strict;
use crate::units::{short, Units};
use crate::Warning;
use nalgebra::{Matrix3, Vector3};
use std::path::{Path, PathBuf};

/// Deepest chain of `extends` followed (guards against cycles).
const MAX_EXTENDS_DEPTH: usize = 8;

/// A parsed file with the chain of files it was merged from (the file itself first).
#[derive(Debug, Clone)]
struct Merged {
    table: toml::Table,
    /// (path, its own table before merging), child first.
    layers: Vec<(String, toml::Table)>,
}

/// Largest scenario file read, bytes: a scenario is a few kilobytes; this keeps a hostile path
/// (a huge log, a disk image) from being read into memory.
const MAX_FILE_BYTES: u64 = 16 << 20;

/// What a path is when it is not a regular file, for [`ScenarioError::NotAFile`].
fn special_kind(t: &std::fs::FileType) -> Option<&'static str> {
    if t.is_file() {
        return None;
    }
    if t.is_dir() {
        return Some("a directory");
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return Some("a FIFO (named pipe)");
        }
        if t.is_char_device() {
            return Some("a character device");
        }
        if t.is_block_device() {
            return Some("a block device");
        }
        if t.is_socket() {
            return Some("a socket");
        }
    }
    Some("neither a file nor a directory")
}

/// Reads a TOML file of the project (a scenario, a campaign) as [`read_table`] does.
pub fn read_toml(path: impl AsRef<Path>) -> Result<toml::Table, ScenarioError> {
    read_table(path.as_ref())
}

/// Reads a scenario file: refused unless it is a regular file (checked with `stat` before it is
/// opened, so a FIFO cannot block, and again on the open handle), at most [`MAX_FILE_BYTES`],
/// valid UTF-8 TOML, and not empty.
fn read_table(path: &Path) -> Result<toml::Table, ScenarioError> {
    use std::io::Read;
    let file = path.display().to_string();
    let io = |cause: std::io::Error| ScenarioError::Io {
        file: file.clone(),
        cause,
    };
    let not_a_file = |kind: &str| ScenarioError::NotAFile {
        file: file.clone(),
        kind: kind.to_string(),
    };
    let too_large = |bytes: u64| ScenarioError::TooLarge {
        file: file.clone(),
        bytes,
        most: MAX_FILE_BYTES,
    };
    let meta = std::fs::metadata(path).map_err(io)?;
    if let Some(kind) = special_kind(&meta.file_type()) {
        return Err(not_a_file(kind));
    }
    let handle = std::fs::File::open(path).map_err(io)?;
    let meta = handle.metadata().map_err(io)?;
    if let Some(kind) = special_kind(&meta.file_type()) {
        return Err(not_a_file(kind));
    }
    if meta.len() > MAX_FILE_BYTES {
        return Err(too_large(meta.len()));
    }
    let mut text = String::new();
    handle
        .take(MAX_FILE_BYTES + 1)
        .read_to_string(&mut text)
        .map_err(io)?;
    if text.len() as u64 > MAX_FILE_BYTES {
        return Err(too_large(text.len() as u64));
    }
    parse(&file, &text)
}

/// Parses TOML text; `file` names it in messages. An empty table (no key at all) is refused.
fn parse(file: &str, text: &str) -> Result<toml::Table, ScenarioError> {
    let table = toml::from_str::<toml::Table>(text).map_err(|e| ScenarioError::Syntax {
        file: file.to_string(),
        message: clipped_lines(&e.to_string()),
    })?;
    if table.is_empty() {
        return Err(ScenarioError::Empty {
            file: file.to_string(),
        });
    }
    Ok(table)
}

/// Longest line of a TOML parser message kept (the parser quotes the offending line, which a
/// hostile file makes a megabyte long).
const MAX_MESSAGE_LINE: usize = 200;

/// `message` with every line cut to [`MAX_MESSAGE_LINE`] characters.
fn clipped_lines(message: &str) -> String {
    message
        .lines()
        .map(|line| match line.char_indices().nth(MAX_MESSAGE_LINE) {
            Some((cut, _)) => format!("{}…", &line[..cut]),
            None => line.to_string(),
        })
        .collect::<Vec<_>>()
        .join("\n")
        + if message.ends_with('\n') { "\n" } else { "" }
}

/// Deep-merges `over` onto `base`: tables merge key by key, anything else is replaced.
fn merge(base: &mut toml::Table, over: toml::Table) {
    for (k, v) in over {
        match (base.get_mut(&k), v) {
            (Some(toml::Value::Table(b)), toml::Value::Table(o)) => merge(b, o),
            (_, v) => {
                base.insert(k, v);
            }
        }
    }
}

fn load_merged(path: &Path, depth: usize) -> Result<Merged, ScenarioError> {
    let file = path.display().to_string();
    let own = read_table(path)?;
    let Some(parent) = own.get("extends") else {
        return Ok(Merged {
            table: own.clone(),
            layers: vec![(file, own)],
        });
    };
    let Some(parent) = parent.as_str() else {
        return Err(ScenarioError::field(
            &file,
            "extends",
            "expected a file name (string)",
        ));
    };
    if depth >= MAX_EXTENDS_DEPTH {
        return Err(ScenarioError::field(
            &file,
            "extends",
            format!("more than {MAX_EXTENDS_DEPTH} levels of `extends` (a cycle?)"),
        ));
    }
    let parent_path: PathBuf = path.parent().unwrap_or(Path::new(".")).join(parent);
    let mut base = load_merged(&parent_path, depth + 1).map_err(|e| match e {
        ScenarioError::Io {
            file: missing,
            cause,
        } => ScenarioError::field(&file, "extends", format!("cannot read {missing}: {cause}")),
        ScenarioError::NotAFile { file: target, kind } => ScenarioError::field(
            &file,
            "extends",
            format!("{target} is not a regular file ({kind}): expected a scenario file"),
        ),
        other => other,
    })?;
    check_same_units(&file, &own, &base)?;
    let mut over = own.clone();
    over.remove("extends");
    base.table.remove("extends");
    merge(&mut base.table, over);
    base.layers.insert(0, (file, own));
    Ok(base)
}

/// Refuses a file whose `[units]` differ from those of the file it extends: every number is
/// read in the units of the file that wrote it, and the merged file has one unit system, so a
/// changed unit would silently reinterpret every inherited number.
fn check_same_units(file: &str, own: &toml::Table, base: &Merged) -> Result<(), ScenarioError> {
    let (Some(toml::Value::Table(mine)), Some(toml::Value::Table(inherited))) =
        (own.get("units"), base.table.get("units"))
    else {
        return Ok(());
    };
    for (key, value) in mine {
        let Some(theirs) = inherited.get(key) else {
            continue;
        };
        // An unknown unit is the schema's to report ("unknown variant"), not a change.
        if theirs != value && is_unit(key, value) {
            let field = format!("units.{key}");
            let base_file = owner_of(&base.layers, &field);
            return Err(ScenarioError::field(
                file,
                &field,
                format!(
                    "{value} here but {theirs} in {base_file}, which this file extends: a file's numbers are in the units of the file that wrote them, so a file may not change the units of the file it extends (leave [units] out, or write the file standalone)"
                ),
            ));
        }
    }
    Ok(())
}

/// Whether `value` is a unit the format knows for the `[units]` key `key`.
fn is_unit(key: &str, value: &toml::Value) -> bool {
    use crate::units::{AngleUnit, ForceUnit, LengthUnit, MassUnit, TimeUnit};
    let v = value.clone();
    match key {
        "length" => v.try_into::<LengthUnit>().is_ok(),
        "mass" => v.try_into::<MassUnit>().is_ok(),
        "force" => v.try_into::<ForceUnit>().is_ok(),
        "angle" => v.try_into::<AngleUnit>().is_ok(),
        "time" => v.try_into::<TimeUnit>().is_ok(),
        _ => false,
    }
}

/// Name of the layer [`Scenario::load_with`] puts its overrides in.
const OVERRIDES: &str = "overrides";

/// The file (of an `extends` chain) that sets the value at a serde path such as
/// `primary_strut.compression.stages[1].crush_load`: the first layer that has it, or, for a
/// field no layer has (a missing field), the first that has its closest enclosing table, or the
/// top file.
fn owner_of<'a>(layers: &'a [(String, toml::Table)], path: &str) -> &'a str {
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
fn first_layer_with<'a>(layers: &'a [(String, toml::Table)], keys: &[&str]) -> Option<&'a str> {
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
    /// `"ft/s"`, `"1"`) names this file's own units ([`Units::suffix_of`]) and the field's
    /// dimension ([`Scenario::dimension_of`]), so that a length given to a velocity is refused
    /// rather than read as one. Returns the unit as a name suffix (`ft_s`), or what is wrong and
    /// the unit to write.
    pub fn check_unit(&self, field: &str, unit: &str) -> Result<String, String> {
        let units = self.units();
        let suffix = units.suffix_of(unit)?;
        let given = Dimension::parse(unit, Powers::default())?;
        let wanted = match self.dimension_of(field) {
            Some(d) => d?,
            None => Dimension::NONE,
        };
        if given == wanted {
            return Ok(suffix);
        }
        let write = match wanted.written_in(&units) {
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

    /// The units the file's numbers were read in ([`ScenarioFile::read_units`]).
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

/// The value at the field path `field` (`a.b[2].c`) of `root`, if there is one.
fn field_at<'a>(root: &'a toml::Value, field: &str) -> Option<&'a toml::Value> {
    let mut node = root;
    for (key, index) in path_keys(field).ok()? {
        node = node.get(key)?;
        if let Some(i) = index {
            node = node.get(i)?;
        }
    }
    Some(node)
}

/// Parts a field path may have: the schema's deepest fields have 4
/// (`primary_strut.compression.stages[0].crush_load`); a longer path names no field, and
/// refusing it here keeps a hostile one (tens of thousands of parts) from nesting tables
/// deeper than the reader's stack.
const MAX_PATH_PARTS: usize = 16;

/// The keys of a field path `a.b[2].c`: (key, optional array index) pairs; `Err` says why the
/// text is not a field path (an empty key, an index that is not a whole number in brackets,
/// more than [`MAX_PATH_PARTS`] parts).
fn path_keys(field: &str) -> Result<Vec<(&str, Option<usize>)>, String> {
    let parts = field.split('.').count();
    if parts > MAX_PATH_PARTS {
        return Err(format!(
            "a field path of {parts} parts: no field is deeper than {MAX_PATH_PARTS}"
        ));
    }
    field
        .split('.')
        .map(|k| {
            let (key, index) = match k.split_once('[') {
                Some((key, rest)) => {
                    let index = rest
                        .strip_suffix(']')
                        .and_then(|i| i.parse::<usize>().ok())
                        .ok_or_else(|| {
                            format!("`{k}`: expected an index as a whole number in brackets, such as `legs[0]`")
                        })?;
                    (key, Some(index))
                }
                None => (k, None),
            };
            if key.is_empty() {
                return Err(format!(
                    "`{field}` has an empty key: expected keys joined by dots, such as `touchdown.vertical_velocity`"
                ));
            }
            Ok((key, index))
        })
        .collect()
}

/// The merged table of a scenario file (its `extends` chain resolved), as TOML values in the
/// file's units, without the schema check.
pub fn merged_table(path: impl AsRef<Path>) -> Result<toml::Table, ScenarioError> {
    load_merged(path.as_ref(), 0).map(|m| m.table)
}

/// Replaces the number at `field` (e.g. `primary_strut.compression.stages[0].crush_load`) in a
/// scenario table; the path must exist and hold a number.
pub fn set_field(table: &mut toml::Table, field: &str, value: f64) -> Result<(), String> {
    set_path(table, field, &toml::Value::Float(value), true)
}

/// Why `field` cannot be overridden, if it cannot: what decides how the file is read, not a
/// value of the landing.
fn not_overridable(field: &str) -> Option<String> {
    let head = field.split(['.', '[']).next().unwrap_or("");
    match head {
        "extends" => Some("`extends` is merged when the file is read; an override cannot change which file is extended (write a file that extends the other)".into()),
        "units" => Some("the units decide how every number of the file is read; an override cannot change them (write the file in the other units)".into()),
        "schema_version" => Some("the schema version is the file's, not a value of the landing".into()),
        _ => None,
    }
}

/// The kind of value a field holds, in messages.
fn kind_of(v: &toml::Value) -> &'static str {
    match v {
        toml::Value::Float(_) | toml::Value::Integer(_) => "a number",
        toml::Value::String(_) => "a string",
        toml::Value::Boolean(_) => "a boolean",
        toml::Value::Datetime(_) => "a date",
        toml::Value::Array(_) => "an array",
        toml::Value::Table(_) => "a table",
    }
}

/// Replaces the value at `field` in `table` with `value`, as a file extending the scenario
/// would: a number (written as a float), string or boolean for one of its kind, an array whole
/// (a number for an array and an array for a number where a field takes either, such as a
/// per-leg `surface.hole`: the schema then checks it), a table merged key by key. With
/// `number_only`, only a number for a number. A field no file of the chain writes is added,
/// with the tables that lead to it: the scenario's strict schema then refuses a field that
/// does not exist, naming it. An array element must exist. `extends`, `units` and
/// `schema_version` are refused ([`not_overridable`]).
fn set_path(
    table: &mut toml::Table,
    field: &str,
    value: &toml::Value,
    number_only: bool,
) -> Result<(), String> {
    if let Some(why) = not_overridable(field) {
        return Err(why);
    }
    if number_only && !matches!(value, toml::Value::Float(_) | toml::Value::Integer(_)) {
        return Err(format!("expected a number, got {}", kind_of(value)));
    }
    let keys = path_keys(field)?;
    let mut node = table;
    for (n, (key, index)) in keys.iter().enumerate() {
        let last = n + 1 == keys.len();
        if !node.contains_key(*key) && index.is_none() {
            let added = if last {
                value.clone()
            } else {
                toml::Value::Table(toml::Table::new())
            };
            node.insert((*key).to_string(), added);
            if last {
                return Ok(());
            }
        }
        let entry = node
            .get_mut(*key)
            .ok_or_else(|| format!("no field `{key}` to override"))?;
        let entry = match index {
            Some(i) => entry
                .get_mut(*i)
                .ok_or_else(|| format!("no element {i} in `{key}`"))?,
            None => entry,
        };
        if last {
            let (have, given) = (kind_of(entry), kind_of(value));
            let either = matches!(
                (have, given),
                ("a number", "an array") | ("an array", "a number")
            );
            if have != given && (number_only || !either) {
                return Err(format!("the field holds {have}; the override is {given}"));
            }
            match (entry, value) {
                (toml::Value::Table(t), toml::Value::Table(o)) => merge(t, o.clone()),
                (entry, toml::Value::Integer(i)) => *entry = toml::Value::Float(*i as f64),
                (entry, v) => *entry = v.clone(),
            }
            return Ok(());
        }
        node = entry
            .as_table_mut()
            .ok_or_else(|| format!("`{key}` is not a table"))?;
    }
    Err("empty field path".into())
}

/// Records an override in its own layer table (for naming the overrides in messages).
fn set_path_creating(table: &mut toml::Table, field: &str, value: &toml::Value) {
    let Ok(keys) = path_keys(field) else {
        return;
    };
    let mut node = table;
    for (key, _) in &keys[..keys.len() - 1] {
        node = node
            .entry(key.to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()))
            .as_table_mut()
            .expect("created as a table");
    }
    node.insert(keys[keys.len() - 1].0.to_string(), value.clone());
}

/// Schema check (types, required and unknown fields, tables only as tables), then resolution.
fn resolve_layers(source: String, merged: Merged) -> Result<Scenario, ScenarioError> {
    let t = &merged.table;
    if !t.contains_key("surface")
        && !t.contains_key("touchdown")
        && (t.contains_key("vehicle") || t.contains_key("gear"))
    {
        return Err(ScenarioError::NotALanding { file: source });
    }
    let file: ScenarioFile =
        read_strict(toml::Value::Table(merged.table)).map_err(|m| ScenarioError::Field {
            file: owner_of(&merged.layers, &m.field).to_string(),
            field: m.field,
            message: m.message,
        })?;
    resolve(&source, merged.layers, file)
}

/// Where a TOML document does not fit a schema: the field (a path such as
/// `dispersion[2].mean`) and what is wrong with it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SchemaMismatch {
    /// The field path.
    pub field: String,
    /// What is wrong (the first line of the deserializer's message).
    pub message: String,
}

/// Reads `value` as a `T` through the strict reader of the scenario schema (tables only as
/// tables, numbers in short notation): the reader of scenario files, and of other project files
/// in TOML (campaigns). A missing field is reported at its own path, not at its table's.
pub fn read_strict<T: serde::de::DeserializeOwned>(
    value: toml::Value,
) -> Result<T, SchemaMismatch> {
    serde_path_to_error::deserialize(Strict(value)).map_err(|e| {
        let mut field = e.path().to_string();
        let message = e.inner().to_string();
        let message = message.lines().next().unwrap_or_default().to_string();
        // "missing field `x`" is about the field x, not about the table that lacks it.
        if let Some(name) = message
            .strip_prefix("missing field `")
            .and_then(|rest| rest.split('`').next())
        {
            field = if field == "." || field.is_empty() {
                name.to_string()
            } else {
                format!("{field}.{name}")
            };
        }
        SchemaMismatch { field, message }
    })
}

/// The applicable engines in comparison order: at least one, none named twice.
fn resolve_applicable(
    c: &Check,
    engines: &[schema::Engine],
) -> Result<Vec<schema::Engine>, ScenarioError> {
    let field = "engines.applicable";
    if engines.is_empty() {
        return Err(c.err(
            field,
            "expected at least one of \"core\", \"rapier\", \"mujoco\"",
        ));
    }
    let mut sorted = engines.to_vec();
    sorted.sort();
    if let Some(w) = sorted.windows(2).find(|w| w[0] == w[1]) {
        return Err(c.err(
            field,
            format!("expected each engine once, {} is named twice", w[0]),
        ));
    }
    Ok(sorted)
}

/// The rapier engine's settings in SI.
fn resolve_rapier(
    c: &Check,
    r: &schema::Rapier,
    u: &Units,
) -> Result<model::Rapier, ScenarioError> {
    Ok(model::Rapier {
        timestep: r
            .timestep
            .map(|v| c.positive_si("engines.rapier.timestep", v, u.time()))
            .transpose()?,
        contact_frequency: r
            .contact_frequency
            .map(|v| c.positive_si("engines.rapier.contact_frequency", v, 1.0 / u.time()))
            .transpose()?,
        contact_damping_ratio: c.non_negative_si(
            "engines.rapier.contact_damping_ratio",
            r.contact_damping_ratio,
            1.0,
        )?,
    })
}

/// The MuJoCo export's settings in SI.
fn resolve_mujoco(
    c: &Check,
    m: &schema::Mujoco,
    u: &Units,
) -> Result<model::Mujoco, ScenarioError> {
    let timestep = m
        .timestep
        .map(|v| c.positive_si("engines.mujoco.timestep", v, u.time()))
        .transpose()?;
    let contact_timeconst = m
        .contact_timeconst
        .map(|v| c.positive_si("engines.mujoco.contact_timeconst", v, u.time()))
        .transpose()?;
    if let (Some(step), Some(timeconst)) = (timestep, contact_timeconst) {
        let least = model::Mujoco::MIN_TIMECONST_PER_STEP * step;
        if timeconst < least {
            return Err(c.err(
                "engines.mujoco.contact_timeconst",
                format!(
                    "expected at least twice engines.mujoco.timestep, {} in the file's time unit (MuJoCo would silently raise it)",
                    short(least / u.time())
                ),
            ));
        }
    }
    Ok(model::Mujoco {
        timestep,
        contact_timeconst,
        contact_damping_ratio: c.non_negative_si(
            "engines.mujoco.contact_damping_ratio",
            m.contact_damping_ratio,
            1.0,
        )?,
        contact_width: m
            .contact_width
            .map(|v| c.positive_si("engines.mujoco.contact_width", v, u.length()))
            .transpose()?,
    })
}

/// The integrator settings, SI, checked.
fn resolve_integrator(
    c: &Check,
    it: &schema::Integrator,
    u: &Units,
) -> Result<model::Integrator, ScenarioError> {
    let integrator = model::Integrator {
        scheme: it.scheme,
        dist: c.positive_si("integrator.dist", it.dist, u.length())?,
        dt_min: c.positive_si("integrator.dt_min", it.dt_min, u.time())?,
        dt_max: c.positive_si("integrator.dt_max", it.dt_max, u.time())?,
        t_end: c.positive_si("integrator.t_end", it.t_end, u.time())?,
        contact_step_limit: it.contact_step_limit,
        energy_tolerance: c.positive_si("integrator.energy_tolerance", it.energy_tolerance, 1.0)?,
        max_steps: c
            .positive_si("integrator.max_steps", it.max_steps, 1.0)?
            .round() as u64,
        attitude: it.attitude,
        rtol: c.positive_si("integrator.rtol", it.rtol, 1.0)?,
        atol: c.positive_si("integrator.atol", it.atol, 1.0)?,
    };
    if integrator.dt_min > integrator.dt_max {
        return Err(c.err("integrator.dt_min", "expected dt_min ≤ dt_max"));
    }
    if it.attitude == schema::AttitudeForm::Quaternion && it.scheme == schema::Scheme::Report {
        return Err(c.err(
            "integrator.attitude",
            "expected \"euler\" with scheme \"report\" (the report's predictor-corrector integrates Euler angles, eqs. 20-25); \"quaternion\" needs scheme \"rk4\" or \"dopri5\"",
        ));
    }
    Ok(integrator)
}

/// The multibody engines' gear links.
fn resolve_links(c: &Check, l: &schema::GearLinks) -> Result<model::GearLinks, ScenarioError> {
    Ok(model::GearLinks {
        outer_cylinder_mass_ratio: c.positive_si(
            "engines.links.outer_cylinder_mass_ratio",
            l.outer_cylinder_mass_ratio,
            1.0,
        )?,
        link_radius_ratio: c.positive_si(
            "engines.links.link_radius_ratio",
            l.link_radius_ratio,
            1.0,
        )?,
    })
}

impl Scenario {
    /// The scenario with its rapier settings changed by `change` (command-line flags), checked
    /// as the file's own would be; the resolved scenario written out shows the new values.
    pub fn with_rapier(
        mut self,
        change: impl FnOnce(&mut schema::Rapier),
    ) -> Result<Scenario, ScenarioError> {
        change(&mut self.file.engines.rapier);
        let c = Check::new(&self.layers);
        let rapier = resolve_rapier(&c, &self.file.engines.rapier, &self.units())?;
        let warnings = c.into_warnings();
        self.rapier = rapier;
        self.replace_warnings("engines.rapier.", warnings);
        Ok(self)
    }

    /// The scenario with its integrator settings changed by `change` (file units, as in the
    /// file), checked as the file's own would be; the resolved scenario written out shows the
    /// new values.
    pub fn with_integrator(
        mut self,
        change: impl FnOnce(&mut schema::Integrator),
    ) -> Result<Scenario, ScenarioError> {
        change(&mut self.file.integrator);
        let c = Check::new(&self.layers);
        let integrator = resolve_integrator(&c, &self.file.integrator, &self.units())?;
        let warnings = c.into_warnings();
        self.integrator = integrator;
        self.replace_warnings("integrator.", warnings);
        Ok(self)
    }

    /// The scenario with its MuJoCo settings changed by `change` (command-line flags), checked
    /// as the file's own would be; the resolved scenario written out shows the new values.
    pub fn with_mujoco(
        mut self,
        change: impl FnOnce(&mut schema::Mujoco),
    ) -> Result<Scenario, ScenarioError> {
        change(&mut self.file.engines.mujoco);
        let c = Check::new(&self.layers);
        let mujoco = resolve_mujoco(&c, &self.file.engines.mujoco, &self.units())?;
        let warnings = c.into_warnings();
        self.mujoco = mujoco;
        self.replace_warnings("engines.mujoco.", warnings);
        Ok(self)
    }

    /// The warnings of the fields under `prefix` replaced by `warnings` (a table re-checked).
    fn replace_warnings(&mut self, prefix: &str, warnings: Vec<Warning>) {
        self.warnings.retain(|w| !w.field.starts_with(prefix));
        self.warnings.extend(warnings);
    }
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
    fn trunnion(&self, field: &str, t: Trunnion, u: &Units) -> Result<Option<f64>, ScenarioError> {
        match t {
            Trunnion::Rigid(_) => Ok(None),
            Trunnion::Rate(k) => Ok(Some(self.positive_si(field, k, u.stiffness())?)),
        }
    }
    fn viscous(
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

/// Legs from the report's parameterisation (see [`schema::Parametric`]), body axes, m.
fn parametric_legs(
    c: &Check,
    p: &schema::Parametric,
    u: &Units,
) -> Result<Vec<model::Leg>, ScenarioError> {
    let l = u.length();
    let f = |name: &str, v: f64| c.positive_si(&format!("gear.parametric.{name}"), v, l);
    let (r1, r2, r3) = (f("r1", p.r1)?, f("r2", p.r2)?, f("r3", p.r3)?);
    let (z1, z2, z3, zc) = (
        f("z1", p.z1)?,
        f("z2", p.z2)?,
        f("z3", p.z3)?,
        f("zc", p.zc)?,
    );
    let beta = c.finite_si("gear.parametric.beta", p.beta, u.angle())?;
    if z1 >= z3 {
        return Err(c.err(
            "gear.parametric.z1",
            format!(
                "expected Z1 below the primary trunnion height Z3 = {}, got {}",
                short(p.z3),
                short(p.z1)
            ),
        ));
    }
    // Point 1: on the primary axis from B2 = (R1, Z3) to BP = (R3, 0), at height Z1.
    let t1 = (z3 - z1) / z3;
    let x1 = r1 + (r3 - r1) * t1;
    let (b3, b4) = match p.beta_convention {
        schema::BetaConvention::TrunnionAzimuth => (
            Vector3::new(r2 * beta.cos(), r2 * beta.sin(), z2),
            Vector3::new(r2 * beta.cos(), -r2 * beta.sin(), z2),
        ),
        schema::BetaConvention::StrutAngle => {
            let y = (x1 - r2) * beta.tan();
            (Vector3::new(r2, y, z2), Vector3::new(r2, -y, z2))
        }
    };
    let b2 = Vector3::new(r1, 0.0, z3);
    let bp = Vector3::new(r3, 0.0, 0.0);
    let l21 = t1 * (bp - b2).norm();
    let shift = Vector3::new(0.0, 0.0, zc);
    check_leg_count(c, "gear.parametric.leg_azimuths", p.leg_azimuths.len())?;
    let mut legs = Vec::with_capacity(p.leg_azimuths.len());
    for (i, az) in p.leg_azimuths.iter().enumerate() {
        let a = c.finite_si(
            &format!("gear.parametric.leg_azimuths[{i}]"),
            *az,
            u.angle(),
        )?;
        let r = touchdown_frames::rot_z(a);
        legs.push(model::Leg::from_points(
            r * b2 - shift,
            r * b3 - shift,
            r * b4 - shift,
            r * bp - shift,
            l21,
        ));
    }
    Ok(legs)
}

fn explicit_legs(
    c: &Check,
    legs: &[schema::Leg],
    arrangement: schema::Arrangement,
    u: &Units,
) -> Result<Vec<model::Leg>, ScenarioError> {
    check_leg_count(c, "gear.legs", legs.len())?;
    let l = u.length();
    legs.iter()
        .enumerate()
        .map(|(i, leg)| {
            let f = |n: &str| format!("gear.legs[{i}].{n}");
            let (b2, bp) = (c.vec3(&f("b2"), leg.b2, l)?, c.vec3(&f("bp"), leg.bp, l)?);
            // eqs. (29)-(30): point 1 at L21 along the primary; the tripod's is the footpad.
            let l21 = match (arrangement, leg.l21) {
                (schema::Arrangement::Cantilever, Some(x)) => c.positive_si(&f("l21"), x, l)?,
                (schema::Arrangement::Cantilever, None) => {
                    return Err(c.err(&f("l21"), "expected L21 (length) for the cantilever gear"))
                }
                (schema::Arrangement::Tripod, None) => (bp - b2).norm(),
                (schema::Arrangement::Tripod, Some(_)) => {
                    return Err(c.err(
                        &f("l21"),
                        "the tripod's secondaries meet the primary at the footpad: leave L21 out",
                    ))
                }
            };
            Ok(model::Leg::from_points(
                b2,
                c.vec3(&f("b3"), leg.b3, l)?,
                c.vec3(&f("b4"), leg.b4, l)?,
                bp,
                l21,
            ))
        })
        .collect()
}

/// From 3 to [`ranges::MAX_LEGS`] legs.
fn check_leg_count(c: &Check, field: &str, n: usize) -> Result<(), ScenarioError> {
    if n < 3 {
        return Err(c.err(field, format!("expected at least 3 legs, got {n}")));
    }
    if n > ranges::MAX_LEGS {
        return Err(c.err(
            field,
            format!("expected at most {} legs, got {n}", ranges::MAX_LEGS),
        ));
    }
    Ok(())
}

/// Geometric checks common to both ways of giving the legs.
fn check_legs(
    c: &Check,
    field: &str,
    legs: &[model::Leg],
    arrangement: schema::Arrangement,
    lengths: f64,
) -> Result<(), ScenarioError> {
    let tiny = 1e-9;
    for (i, leg) in legs.iter().enumerate() {
        let f = format!("{field}[{i}]");
        if leg.l2p < tiny {
            return Err(c.err(&f, "the footpad BP coincides with the primary trunnion B2"));
        }
        if arrangement == schema::Arrangement::Cantilever && leg.l21 >= leg.l2p {
            return Err(c.err(
                &f,
                format!(
                    "the strut cannot reach its footpad: L21 = {} must be shorter than the primary strut |BP − B2| = {} (file length units)",
                    short(leg.l21 / lengths),
                    short(leg.l2p / lengths)
                ),
            ));
        }
        if leg.l31 < tiny || leg.l41 < tiny {
            return Err(c.err(
                &f,
                "a secondary trunnion coincides with the attachment point 1",
            ));
        }
    }
    // Counter-clockwise order seen from above: footpad azimuths strictly increasing, one turn.
    let az: Vec<f64> = legs.iter().map(|l| l.bp.y.atan2(l.bp.x)).collect();
    let mut turn = 0.0;
    for i in 0..az.len() {
        let mut d = az[(i + 1) % az.len()] - az[i];
        while d <= 0.0 {
            d += std::f64::consts::TAU;
        }
        turn += d;
    }
    if (turn - std::f64::consts::TAU).abs() > 1e-6 {
        return Err(c.err(
            field,
            "legs must be listed counter-clockwise seen from above (+Z_B), once around",
        ));
    }
    // Consecutive footpads apart by a least angle: two legs at (nearly) one azimuth are one leg
    // listed twice, and their stability wall has no direction.
    let least = ranges::MIN_LEG_SEPARATION_DEG.to_radians();
    for i in 0..az.len() {
        let j = (i + 1) % az.len();
        let d = (az[j] - az[i]).rem_euclid(std::f64::consts::TAU);
        if d < least {
            let element = if field == "gear.parametric" {
                format!("gear.parametric.leg_azimuths[{j}]")
            } else {
                format!("{field}[{j}]")
            };
            return Err(c.err(
                &element,
                format!(
                    "leg {}'s footpad is {} deg counter-clockwise from leg {}'s seen from above; expected consecutive legs at least {} deg apart",
                    j + 1,
                    short(d.to_degrees()),
                    i + 1,
                    short(ranges::MIN_LEG_SEPARATION_DEG)
                ),
            ));
        }
    }
    Ok(())
}

fn inertia(c: &Check, i: &schema::Inertia, u: &Units) -> Result<Matrix3<f64>, ScenarioError> {
    let s = u.inertia();
    let g = |n: &str, v: f64| c.finite_si(&format!("vehicle.inertia.{n}"), v, s);
    let (xx, yy, zz) = (g("xx", i.xx)?, g("yy", i.yy)?, g("zz", i.zz)?);
    let (xy, xz, yz) = (g("xy", i.xy)?, g("xz", i.xz)?, g("yz", i.yz)?);
    let j = Matrix3::new(xx, -xy, -xz, -xy, yy, -yz, -xz, -yz, zz);
    if j.cholesky().is_none() {
        return Err(c.err("vehicle.inertia", "expected a positive-definite inertia tensor (check the moments and the products of inertia)"));
    }
    Ok(j)
}

fn resolve(
    source: &str,
    layers: Vec<(String, toml::Table)>,
    file: ScenarioFile,
) -> Result<Scenario, ScenarioError> {
    let c = Check::new(&layers);
    if file.schema_version != SCHEMA_VERSION {
        return Err(c.err(
            "schema_version",
            format!("expected {SCHEMA_VERSION}, got {}", file.schema_version),
        ));
    }
    if let Some(s) = &file.similarity {
        c.positive_si("similarity.length", s.length, 1.0)?;
        c.positive_si("similarity.mass", s.mass, 1.0)?;
        c.positive_si("similarity.time", s.time, 1.0)?;
    }
    let u = file.read_units();
    let vehicle = model::Vehicle {
        mass: c.positive_si("vehicle.mass", file.vehicle.mass, u.mass())?,
        inertia: inertia(&c, &file.vehicle.inertia, &u)?,
        gravity: c.non_negative_si("vehicle.gravity", file.vehicle.gravity, u.acceleration())?,
    };
    let arrangement = file.gear.arrangement;
    let (legs, legs_field) = match (&file.gear.legs, &file.gear.parametric) {
        (Some(l), None) => (explicit_legs(&c, l, arrangement, &u)?, "gear.legs"),
        (None, Some(_)) if arrangement == schema::Arrangement::Tripod => {
            return Err(c.err(
                "gear.arrangement",
                "the tripod is not supported by gear.parametric (the report's fig. 23 parameterisation is of the cantilever gear): give the tripod's points in gear.legs",
            ))
        }
        (None, Some(p)) => (parametric_legs(&c, p, &u)?, "gear.parametric"),
        _ => return Err(c.err("gear", "expected exactly one of `legs` or `parametric`")),
    };
    check_legs(&c, legs_field, &legs, arrangement, u.length())?;
    let n = legs.len();
    let ps = &file.primary_strut;
    let primary = model::PrimaryStrut {
        compression: c.load_stroke("primary_strut.compression", &ps.compression, 3, &u)?,
        trunnion_rate: c.trunnion("primary_strut.trunnion", ps.trunnion, &u)?,
        viscous: c.viscous("primary_strut.viscous", ps.viscous, &u)?,
        bearing_friction: c.non_negative_si(
            "primary_strut.bearing.friction",
            ps.bearing.friction,
            1.0,
        )?,
        inner_cylinder_length: c.positive_si(
            "primary_strut.bearing.inner_cylinder_length",
            ps.bearing.inner_cylinder_length,
            u.length(),
        )?,
        initial_overlap: c.positive_si(
            "primary_strut.bearing.initial_overlap",
            ps.bearing.initial_overlap,
            u.length(),
        )?,
        bending_stiffness: mechanisms::bending(&c, ps.bending, arrangement, &u)?,
    };
    if primary.initial_overlap >= primary.inner_cylinder_length {
        return Err(c.err(
            "primary_strut.bearing.initial_overlap",
            "expected the initial overlap D2 to be shorter than the inner cylinder D1",
        ));
    }
    let shortest = legs.iter().map(|l| l.l2p).fold(f64::INFINITY, f64::min);
    if primary.inner_cylinder_length >= shortest {
        return Err(c.err(
            "primary_strut.bearing.inner_cylinder_length",
            "expected the inner cylinder D1 to be shorter than the primary strut",
        ));
    }
    let ss = &file.secondary_strut;
    let secondary = model::SecondaryStrut {
        tension: c.load_stroke("secondary_strut.tension", &ss.tension, 4, &u)?,
        compression: c.load_stroke("secondary_strut.compression", &ss.compression, 4, &u)?,
        trunnion_rate: c.trunnion("secondary_strut.trunnion", ss.trunnion, &u)?,
        viscous: c.viscous("secondary_strut.viscous", ss.viscous, &u)?,
    };
    let footpad = model::Footpad {
        mass: c.positive_si("footpad.mass", file.footpad.mass, u.mass())?,
        radius: c.positive_si("footpad.radius", file.footpad.radius, u.length())?,
        height: match file.footpad.height {
            Some(h) => Some(c.positive_si("footpad.height", h, u.length())?),
            None => None,
        },
        crush: match &file.footpad.crush {
            Some(ls) => Some(c.load_stroke("footpad.crush", ls, 4, &u)?),
            None => None,
        },
        detached: file.footpad.detached,
    };
    let sf = &file.surface;
    let slope = c.finite("surface.slope", sf.slope)? * u.angle();
    if slope.abs() >= std::f64::consts::FRAC_PI_2 {
        return Err(c.err(
            "surface.slope",
            "expected a slope strictly between −90° and 90°",
        ));
    }
    let slope = c.si("surface.slope", sf.slope, u.angle())?;
    let hole = c.per_pad("surface.hole", &sf.hole, n)?;
    let obstacle = c.per_pad("surface.obstacle", &sf.obstacle, n)?;
    let friction = c.per_pad("surface.friction", &sf.friction, n)?;
    if let Some(i) = friction.iter().position(|f| *f < 0.0) {
        return Err(c.err(
            &format!("surface.friction[{i}]"),
            format!(
                "expected a friction coefficient ≥ 0, got {}",
                short(friction[i])
            ),
        ));
    }
    let hole_si = c.each_si("surface.hole", &hole, u.length())?;
    let obstacle_si = c.each_si("surface.obstacle", &obstacle, u.length())?;
    let friction = c.each_si("surface.friction", &friction, 1.0)?;
    let pads = (0..n)
        .map(|i| model::PadSurface {
            hole: hole_si[i],
            obstacle: obstacle_si[i],
            friction: friction[i],
        })
        .collect();
    // A footpad with inertia leaves when its surface would have to pull: the report's
    // stand-ins for the pressing force would make the surface pull or let go of a pressed
    // footpad (docs/errata.md, "Footpads with inertia").
    if footpad.detached == schema::Detached::Inertial
        && sf.release != schema::ReleaseRule::GearForce
    {
        return Err(c.err(
            "surface.release",
            "expected \"gear_force\" with footpad.detached = \"inertial\" (the default): a footpad with mass leaves when its surface would have to pull; the report's stand-ins \"strut_force\" and \"honeycomb_force\" go with its massless footpad, footpad.detached = \"rigid\"",
        ));
    }
    let surface = model::Surface {
        slope,
        soil: mechanisms::soil(&c, sf, &footpad, &obstacle, &u)?,
        curbs: mechanisms::curbs(&c, sf, &footpad, &obstacle, &u)?,
        pads,
        release: sf.release,
    };
    let td = &file.touchdown;
    let vh = td.horizontal_velocity;
    let mut velocity_g = Vector3::zeros();
    for (i, v) in vh.iter().enumerate() {
        velocity_g[i] = c.finite_si(
            &format!("touchdown.horizontal_velocity[{i}]"),
            *v,
            u.velocity(),
        )?;
    }
    velocity_g.z = c.finite_si(
        "touchdown.vertical_velocity",
        td.vertical_velocity,
        u.velocity(),
    )?;
    let touchdown = model::Touchdown {
        attitude: c.vec3("touchdown.attitude", td.attitude, u.angle())?,
        attitude_reference: td.attitude_reference,
        velocity_g,
        body_rates: c.vec3("touchdown.body_rates", td.body_rates, u.angular_rate())?,
        clearance: c.non_negative_si("touchdown.clearance", td.clearance, u.length())?,
    };
    let integrator = resolve_integrator(&c, &file.integrator, &u)?;
    let st = &file.stability;
    let frac = c.positive(
        "stability.kinetic_energy_fraction",
        st.kinetic_energy_fraction,
    )?;
    if frac > 1.0 {
        return Err(c.err(
            "stability.kinetic_energy_fraction",
            format!("expected a fraction in (0, 1], got {}", short(frac)),
        ));
    }
    let stability = model::Stability {
        kinetic_energy_fraction: c.si("stability.kinetic_energy_fraction", frac, 1.0)?,
        counted_energy: st.counted_energy,
        min_separation_velocity: c.non_negative_si(
            "stability.min_separation_velocity",
            st.min_separation_velocity,
            u.velocity(),
        )?,
        walls: st.walls,
        terminate_on_decision: st.terminate_on_decision,
    };
    let applicable_engines = resolve_applicable(&c, &file.engines.applicable)?;
    let rapier = resolve_rapier(&c, &file.engines.rapier, &u)?;
    let mujoco = resolve_mujoco(&c, &file.engines.mujoco, &u)?;
    let links = resolve_links(&c, &file.engines.links)?;
    let thrust = mechanisms::thrust(&c, file.thrust.as_ref(), &u)?;
    let rcs = mechanisms::rcs(&c, file.rcs.as_ref(), &u)?;
    let slosh = mechanisms::slosh(&c, file.slosh.as_ref(), vehicle.mass, &u)?;
    let warnings = c.into_warnings();
    Ok(Scenario {
        source: source.to_string(),
        layers,
        file,
        vehicle,
        arrangement,
        legs,
        primary,
        secondary,
        footpad,
        surface,
        touchdown,
        integrator,
        stability,
        applicable_engines,
        rapier,
        mujoco,
        links,
        thrust,
        rcs,
        slosh,
        warnings,
    })
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
