//! Reading a scenario file: the file itself (regular files only, size-capped), its TOML, and
//! the chain of files it `extends`, merged key by key with the layers kept for messages.

use crate::check::owner_of;
use crate::error::ScenarioError;
use std::path::{Path, PathBuf};

/// Deepest chain of `extends` followed (guards against cycles).
pub(crate) const MAX_EXTENDS_DEPTH: usize = 8;

/// A parsed file with the chain of files it was merged from (the file itself first).
#[derive(Debug, Clone)]
pub(crate) struct Merged {
    pub(crate) table: toml::Table,
    /// (path, its own table before merging), child first.
    pub(crate) layers: Vec<(String, toml::Table)>,
}

/// Largest scenario file read, bytes: a scenario is a few kilobytes; this keeps a hostile path
/// (a huge log, a disk image) from being read into memory.
pub(crate) const MAX_FILE_BYTES: u64 = 16 << 20;

/// What a path is when it is not a regular file, for [`ScenarioError::NotAFile`].
pub(crate) fn special_kind(t: &std::fs::FileType) -> Option<&'static str> {
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

/// Reads a TOML file of the project (a scenario, a campaign): refused unless it is a regular
/// file (checked with `stat` before it is opened, so a FIFO cannot block, and again on the open
/// handle), at most `MAX_FILE_BYTES` (16 MiB), valid UTF-8 TOML, and not empty.
pub fn read_toml(path: impl AsRef<Path>) -> Result<toml::Table, ScenarioError> {
    read_table(path.as_ref())
}

/// [`read_toml`] on a path: the one reader of every scenario and campaign file.
pub(crate) fn read_table(path: &Path) -> Result<toml::Table, ScenarioError> {
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
pub(crate) fn parse(file: &str, text: &str) -> Result<toml::Table, ScenarioError> {
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
pub(crate) const MAX_MESSAGE_LINE: usize = 200;

/// `message` with every line cut to [`MAX_MESSAGE_LINE`] characters.
pub(crate) fn clipped_lines(message: &str) -> String {
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
pub(crate) fn merge(base: &mut toml::Table, over: toml::Table) {
    for (k, v) in over {
        match (base.get_mut(&k), v) {
            (Some(toml::Value::Table(b)), toml::Value::Table(o)) => merge(b, o),
            (_, v) => {
                base.insert(k, v);
            }
        }
    }
}

pub(crate) fn load_merged(path: &Path, depth: usize) -> Result<Merged, ScenarioError> {
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
pub(crate) fn check_same_units(
    file: &str,
    own: &toml::Table,
    base: &Merged,
) -> Result<(), ScenarioError> {
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
pub(crate) fn is_unit(key: &str, value: &toml::Value) -> bool {
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

/// The merged table of a scenario file (its `extends` chain resolved), as TOML values in the
/// file's units, without the schema check.
pub fn merged_table(path: impl AsRef<Path>) -> Result<toml::Table, ScenarioError> {
    load_merged(path.as_ref(), 0).map(|m| m.table)
}
