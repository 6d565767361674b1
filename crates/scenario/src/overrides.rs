//! Field paths (`touchdown.attitude[2]`) into a merged scenario table: reading a value at a
//! path, and `--set`-style overrides written at a path, refused where a value cannot be set.

use crate::read::merge;

/// The value at the field path `field` (`a.b[2].c`) of `root`, if there is one.
pub(crate) fn field_at<'a>(root: &'a toml::Value, field: &str) -> Option<&'a toml::Value> {
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
pub(crate) const MAX_PATH_PARTS: usize = 16;

/// The keys of a field path `a.b[2].c`: (key, optional array index) pairs; `Err` says why the
/// text is not a field path (an empty key, an index that is not a whole number in brackets,
/// more than [`MAX_PATH_PARTS`] parts).
pub(crate) fn path_keys(field: &str) -> Result<Vec<(&str, Option<usize>)>, String> {
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

/// Replaces the number at `field` (e.g. `primary_strut.compression.stages[0].crush_load`) in a
/// scenario table; the path must exist and hold a number.
pub fn set_field(table: &mut toml::Table, field: &str, value: f64) -> Result<(), String> {
    set_path(table, field, &toml::Value::Float(value), true)
}

/// Why `field` cannot be overridden, if it cannot: what decides how the file is read, not a
/// value of the landing.
pub(crate) fn not_overridable(field: &str) -> Option<String> {
    let head = field.split(['.', '[']).next().unwrap_or("");
    match head {
        "extends" => Some("`extends` is merged when the file is read; an override cannot change which file is extended (write a file that extends the other)".into()),
        "units" => Some("the units decide how every number of the file is read; an override cannot change them (write the file in the other units)".into()),
        "schema_version" => Some("the schema version is the file's, not a value of the landing".into()),
        _ => None,
    }
}

/// The kind of value a field holds, in messages.
pub(crate) fn kind_of(v: &toml::Value) -> &'static str {
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
pub(crate) fn set_path(
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
pub(crate) fn set_path_creating(table: &mut toml::Table, field: &str, value: &toml::Value) {
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
