//! A campaign's files (docs/campaigns.md, "Output"): `manifest.json` (what computed the
//! landings and which), `landings.jsonl` (a record per line, in landing order),
//! `landings.parquet` (the same records in columns) and `statistics.json`.
//!
//! Nothing holds the records: `landings.jsonl` is written a line at a time as the landings
//! finish (the [`Journal`], which a stopped run resumes from), the Parquet file is written from
//! it a row group at a time ([`write_parquet`]), and read back a column at a time
//! ([`visit_column`]) by the analysis (`crate::analysis`); the statistics it computes and the
//! manifest are written last ([`seal`]). This module reads and writes; it computes nothing.

use crate::accuracy::{Accuracy, Measured};
use crate::record::{Cell, Column, Kind, Role, Row};
use crate::spec::Campaign;
use crate::CampaignError;
use parquet::data_type::{BoolType, ByteArray, ByteArrayType, DoubleType, Int64Type};
use parquet::file::properties::WriterProperties;
use parquet::file::writer::SerializedFileWriter;
use parquet::schema::types::Type;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::io::{BufRead, Write};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The manifest's format name.
pub const FORMAT: &str = "touchdown-campaign/2";

/// Landings per Parquet row group: the records held while the Parquet file is written (about
/// 3 kB each, so about 25 MB).
const ROW_GROUP: usize = 8_192;

/// The landings a part of a campaign holds: `first..end`, and the shard that ran them.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Part {
    /// First landing.
    pub first_landing: u64,
    /// One past the last landing.
    pub end_landing: u64,
    /// The shard `K/N` that ran them, when run as a shard.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shard: Option<String>,
}

/// What computed a campaign's landings, and which: written beside every part and every merge.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    /// [`FORMAT`].
    pub format: String,
    /// The version of the `touchdown` that ran the landings.
    pub touchdown_version: String,
    /// The source revision it was built from (`git rev-parse HEAD` at build time), or
    /// `unknown`.
    pub source_revision: String,
    /// The campaign file, as given.
    pub campaign_file: String,
    /// The campaign's name.
    pub campaign_name: String,
    /// SHA-256 of the campaign without its landing count.
    pub campaign_sha256: String,
    /// SHA-256 of what decides each landing's values and scenario
    /// ([`Campaign::draws_identity`]): campaigns sharing it land the same scenarios.
    pub draws_sha256: String,
    /// The engines, in the campaign's order (several for a paired campaign).
    pub engines: Vec<String>,
    /// The seed.
    pub seed: u64,
    /// The confidence of the statistics' lower bounds.
    pub confidence: f64,
    /// Landings of the whole campaign.
    pub landings: u64,
    /// The scenario field each `applied.*` column holds, in the columns' order.
    #[serde(default)]
    pub dispersed_fields: Vec<String>,
    /// The landings whose histories the campaign keeps (in `histories/`).
    pub histories: Vec<u64>,
    /// The base scenario file, as the campaign names it.
    pub base_scenario_file: String,
    /// SHA-256 of the resolved base scenario.
    pub base_scenario_sha256: String,
    /// The resolved base scenario (TOML, its file's units, every default written out).
    pub base_scenario: String,
    /// The landings of this part.
    pub part: Part,
    /// The records' columns.
    pub columns: Vec<Column>,
    /// The accuracy of the campaign's settings on the core, measured on its first landings
    /// ([`crate::accuracy`]): in the manifest of a part that holds landing 0 and of the whole
    /// campaign; absent from the other parts and when the campaign does not land on the core.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub accuracy: Option<Accuracy>,
    /// The same on each multibody engine the campaign lands on, in its order; empty where
    /// `accuracy` is absent (and in manifests written before it was stated).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub multibody_accuracy: Vec<Accuracy>,
    /// SHA-256 of each file the folder holds beside the manifest ([`SEALED`]), as written.
    pub files_sha256: BTreeMap<String, String>,
    /// SHA-256 of this manifest written with this field empty: a manifest edited after it was
    /// written does not read.
    pub seal_sha256: String,
}

/// The files of a campaign folder its manifest holds the SHA-256 of.
pub const SEALED: [&str; 3] = ["landings.jsonl", "landings.parquet", "statistics.json"];

impl Manifest {
    /// States the accuracy `measured` on each engine (`accuracy`, `multibody_accuracy`).
    pub fn state(&mut self, measured: Measured) {
        self.accuracy = measured.core;
        self.multibody_accuracy = measured.multibody;
    }

    /// The manifest of `campaign` (`landings` in all) for the part `part`.
    pub fn new(campaign: &Campaign, landings: u64, part: Part, columns: &[Column]) -> Manifest {
        Manifest {
            format: FORMAT.into(),
            touchdown_version: env!("CARGO_PKG_VERSION").into(),
            source_revision: env!("TOUCHDOWN_REVISION").into(),
            campaign_file: campaign.file.clone(),
            campaign_name: campaign.name.clone(),
            campaign_sha256: campaign.identity.clone(),
            draws_sha256: campaign.draws_identity.clone(),
            engines: campaign.engines.iter().map(|e| e.name().into()).collect(),
            seed: campaign.seed,
            confidence: campaign.confidence,
            landings,
            dispersed_fields: campaign
                .dispersions
                .iter()
                .map(|d| d.field.clone())
                .collect(),
            histories: campaign.histories.clone(),
            base_scenario_file: campaign.scenario_path.display().to_string(),
            base_scenario_sha256: campaign.base_scenario.sha256(),
            base_scenario: campaign.base_scenario.to_toml(),
            part,
            columns: columns.to_vec(),
            accuracy: None,
            multibody_accuracy: Vec::new(),
            files_sha256: BTreeMap::new(),
            seal_sha256: String::new(),
        }
    }

    /// Whether `path`, relative to the folder's `histories/`, is (in) the history of a landing
    /// of this part that the campaign keeps: `landing-N.csv`, or the MuJoCo runner's folder
    /// `landing-N/` or a file in it, under a folder named after its engine when the campaign is
    /// paired.
    pub fn keeps_history(&self, path: &Path) -> bool {
        let mut parts = path.iter().map(|c| c.to_string_lossy());
        if self.engines.len() > 1 {
            let engine = parts.next().unwrap_or_default();
            if !self.engines.iter().any(|e| *e == engine) {
                return false;
            }
        }
        let Some(first) = parts.next() else {
            return false;
        };
        let rest = parts.count();
        let name = match rest {
            0 => first.strip_suffix(".csv").unwrap_or(&first),
            _ => first.as_ref(),
        };
        name.strip_prefix("landing-")
            .and_then(|n| n.parse::<u64>().ok())
            .is_some_and(|l| {
                (self.part.first_landing..self.part.end_landing).contains(&l)
                    && self.histories.contains(&l)
            })
    }

    /// The SHA-256 of this manifest written with an empty seal.
    fn seal(&self) -> String {
        let unsealed = Manifest {
            seal_sha256: String::new(),
            ..self.clone()
        };
        crate::sha256_hex(pretty(&unsealed).as_bytes())
    }

    /// Checks that the files of the campaign folder `dir` are those this manifest sealed:
    /// `Err` names the first that differs (edited, damaged or replaced since it was written).
    pub fn check_files(&self, dir: &Path) -> Result<(), CampaignError> {
        for name in SEALED {
            let path = dir.join(name);
            let held = file_sha256(&path)?;
            if self.files_sha256.get(name) != Some(&held) {
                return Err(CampaignError::Store {
                    path: path.display().to_string(),
                    message: format!(
                        "is not the file its manifest sealed (SHA-256 {held}, sealed {}): it was edited or damaged after touchdown wrote it; run this part again",
                        self.files_sha256.get(name).map_or("none", String::as_str)
                    ),
                });
            }
        }
        Ok(())
    }

    /// Whether `other` is a part of the same campaign run by the same code: everything but the
    /// part, the campaign file's path and the landing count (which `--add` changes) agree.
    /// `Err` names what differs.
    pub fn same_campaign(&self, other: &Manifest) -> Result<(), String> {
        let build = [
            ("format", &self.format, &other.format),
            (
                "touchdown version",
                &self.touchdown_version,
                &other.touchdown_version,
            ),
            (
                "source revision",
                &self.source_revision,
                &other.source_revision,
            ),
        ];
        let differ = |checks: &[(&str, &String, &String)]| {
            checks
                .iter()
                .find(|(_, a, b)| a != b)
                .map_or(Ok(()), |(what, a, b)| {
                    Err(format!("{what}: {a} against {b}"))
                })
        };
        differ(&build)?;
        // The engines before the campaign's hash, which names them: say what differs.
        if self.engines != other.engines {
            return Err(format!(
                "engines: {} against {}",
                self.engines.join(", "),
                other.engines.join(", ")
            ));
        }
        differ(&[
            (
                "campaign (its SHA-256)",
                &self.campaign_sha256,
                &other.campaign_sha256,
            ),
            (
                "base scenario (its SHA-256)",
                &self.base_scenario_sha256,
                &other.base_scenario_sha256,
            ),
        ])?;
        if self.columns != other.columns {
            return Err("the records' columns differ".into());
        }
        Ok(())
    }
}

/// A cell as JSON text; `None` when missing.
fn cell_json(c: &Cell) -> Option<String> {
    match c {
        Cell::Integer(i) => Some(i.to_string()),
        Cell::Float(x) => serde_json::to_string(x).ok(),
        Cell::Text(s) => serde_json::to_string(s).ok(),
        Cell::Flag(b) => Some(b.to_string()),
        Cell::Missing => None,
    }
}

/// A record as one line of JSON (no newline): its cells in column order, the missing left out.
pub fn json_line(columns: &[Column], row: &Row) -> String {
    let mut s = String::with_capacity(64 * columns.len());
    s.push('{');
    for (c, cell) in columns.iter().zip(row) {
        if let Some(v) = cell_json(cell) {
            if s.len() > 1 {
                s.push(',');
            }
            s.push_str(&serde_json::to_string(&c.name).unwrap_or_default());
            s.push(':');
            s.push_str(&v);
        }
    }
    s.push('}');
    s
}

/// The record of one line of `landings.jsonl` (`at` names the file and line in errors).
fn parse_line(
    at: &dyn Fn() -> String,
    line: &str,
    columns: &[Column],
) -> Result<Row, CampaignError> {
    let err = |message: String| CampaignError::Store {
        path: at(),
        message,
    };
    let object: serde_json::Map<String, serde_json::Value> =
        serde_json::from_str(line).map_err(|e| err(format!("not a record: {e}")))?;
    if let Some(key) = object
        .keys()
        .find(|k| !columns.iter().any(|c| &c.name == *k))
    {
        return Err(err(format!("unknown column {key:?}")));
    }
    let row: Row = columns
        .iter()
        .map(|c| {
            let v = object.get(&c.name);
            Ok(match (c.kind, v) {
                (_, None) => Cell::Missing,
                (Kind::Integer, Some(v)) if v.is_i64() => {
                    Cell::Integer(v.as_i64().unwrap_or_default())
                }
                (Kind::Float, Some(v)) if v.is_number() => {
                    Cell::Float(v.as_f64().unwrap_or_default())
                }
                (Kind::Text, Some(serde_json::Value::String(s))) => Cell::Text(s.clone()),
                (Kind::Flag, Some(serde_json::Value::Bool(b))) => Cell::Flag(*b),
                (kind, Some(v)) => {
                    return Err(err(format!(
                        "column {:?}: expected {kind:?}, got {v}",
                        c.name
                    )))
                }
            })
        })
        .collect::<Result<_, _>>()?;
    crate::record::check(columns, &row).map_err(err)?;
    Ok(row)
}

/// Hands each record of the `landings.jsonl` at `path` to `f`, in order, reading a line at a
/// time; the records must be landings `first`, `first + 1`, ... Returns how many there were.
pub fn for_each_record(
    path: &Path,
    columns: &[Column],
    first: u64,
    mut f: impl FnMut(Row) -> Result<(), CampaignError>,
) -> Result<u64, CampaignError> {
    let file = std::fs::File::open(path).map_err(|e| {
        CampaignError::store(
            path,
            format!("{e} (expected a campaign folder written by `touchdown campaign --out`)"),
        )
    })?;
    let mut reader = std::io::BufReader::new(file);
    let mut line = String::new();
    let mut n = 0u64;
    loop {
        line.clear();
        if reader
            .read_line(&mut line)
            .map_err(|e| CampaignError::store(path, e))?
            == 0
        {
            return Ok(n);
        }
        let at = || format!("{}:{}", path.display(), n + 1);
        let row = parse_line(&at, line.trim_end_matches('\n'), columns)?;
        if row[0] != Cell::Integer((first + n) as i64) {
            return Err(CampaignError::Store {
                path: at(),
                message: format!("expected landing {}, one per line in order", first + n),
            });
        }
        f(row)?;
        n += 1;
    }
}

/// The length of `file` up to and including its last newline (0 without one), read back from
/// its end a block at a time.
fn end_of_last_line(file: &std::fs::File) -> std::io::Result<u64> {
    use std::io::{Read, Seek, SeekFrom};
    let mut file = file;
    let mut end = file.metadata()?.len();
    let mut block = vec![0u8; 65_536];
    while end > 0 {
        let start = end.saturating_sub(block.len() as u64);
        let part = &mut block[..(end - start) as usize];
        file.seek(SeekFrom::Start(start))?;
        file.read_exact(part)?;
        if let Some(i) = part.iter().rposition(|b| *b == b'\n') {
            return Ok(start + i as u64 + 1);
        }
        end = start;
    }
    Ok(0)
}

/// `landings.jsonl` being written, a record per line as the landings finish, each line handed
/// to the system as soon as it is written: a run killed at any moment leaves every finished
/// line but the one being written, which [`Journal::resume`] drops.
pub struct Journal {
    path: PathBuf,
    file: std::fs::File,
    columns: Vec<Column>,
    line: String,
}

impl Journal {
    /// A new, empty `landings.jsonl` in `dir` for records with `columns`.
    pub fn create(dir: &Path, columns: &[Column]) -> Result<Journal, CampaignError> {
        let path = dir.join("landings.jsonl");
        let file = std::fs::File::create(&path).map_err(|e| CampaignError::store(&path, e))?;
        Ok(Journal {
            path,
            file,
            columns: columns.to_vec(),
            line: String::new(),
        })
    }

    /// The `landings.jsonl` a stopped run left in `dir`, its records those of landings `first`
    /// on, each handed to `kept`: the complete lines are kept and a last line cut short by the
    /// stop is dropped. Returns it, ready for the next landing, and the records it holds.
    pub fn resume(
        dir: &Path,
        columns: &[Column],
        first: u64,
        mut kept: impl FnMut(&Row),
    ) -> Result<(Journal, u64), CampaignError> {
        let path = dir.join("landings.jsonl");
        let file = std::fs::OpenOptions::new()
            .read(true)
            .write(true)
            .open(&path)
            .map_err(|e| CampaignError::store(&path, e))?;
        // Only whole lines count: a run stopped mid-line wrote no newline after its last one.
        let whole = end_of_last_line(&file).map_err(|e| CampaignError::store(&path, e))?;
        file.set_len(whole)
            .map_err(|e| CampaignError::store(&path, e))?;
        let n = for_each_record(&path, columns, first, |row| {
            kept(&row);
            Ok(())
        })?;
        let file = std::fs::OpenOptions::new()
            .append(true)
            .open(&path)
            .map_err(|e| CampaignError::store(&path, e))?;
        Ok((
            Journal {
                path,
                file,
                columns: columns.to_vec(),
                line: String::new(),
            },
            n,
        ))
    }

    /// Writes one record's line.
    pub fn append(&mut self, row: &Row) -> Result<(), CampaignError> {
        self.line.clear();
        self.line.push_str(&json_line(&self.columns, row));
        self.line.push('\n');
        self.file
            .write_all(self.line.as_bytes())
            .map_err(|e| CampaignError::store(&self.path, e))
    }

    /// Ends the writing: everything written reaches the disk.
    pub fn close(self) -> Result<(), CampaignError> {
        self.file
            .sync_all()
            .map_err(|e| CampaignError::store(&self.path, e))
    }
}

/// The Parquet schema of the records: every column optional but `landing`.
fn schema(columns: &[Column]) -> Result<Type, parquet::errors::ParquetError> {
    use parquet::basic::{LogicalType, Repetition, Type as Physical};
    let fields = columns
        .iter()
        .map(|c| {
            let (physical, logical) = match c.kind {
                Kind::Integer => (Physical::INT64, None),
                Kind::Float => (Physical::DOUBLE, None),
                Kind::Text => (Physical::BYTE_ARRAY, Some(LogicalType::String)),
                Kind::Flag => (Physical::BOOLEAN, None),
            };
            let repetition = if c.role() == Some(Role::Landing) {
                Repetition::REQUIRED
            } else {
                Repetition::OPTIONAL
            };
            Type::primitive_type_builder(&c.name, physical)
                .with_repetition(repetition)
                .with_logical_type(logical)
                .build()
                .map(Arc::new)
        })
        .collect::<Result<Vec<_>, _>>()?;
    Type::group_type_builder("landing_record")
        .with_fields(fields)
        .build()
}

/// The Parquet file of the records being written, a row group at a time: uncompressed, row
/// groups of [`ROW_GROUP`] landings counted from the part's first, deterministic (same records,
/// same bytes).
struct Parquet {
    path: PathBuf,
    writer: SerializedFileWriter<std::fs::File>,
    columns: Vec<Column>,
    group: Vec<Row>,
}

impl Parquet {
    /// A new Parquet file at `path` for records with `columns`.
    fn create(path: &Path, columns: &[Column]) -> Result<Parquet, CampaignError> {
        let file = std::fs::File::create(path).map_err(|e| CampaignError::store(path, e))?;
        let props = Arc::new(
            WriterProperties::builder()
                .set_created_by(format!("touchdown {}", env!("CARGO_PKG_VERSION")))
                .build(),
        );
        let schema = Arc::new(schema(columns).map_err(|e| CampaignError::store(path, e))?);
        let writer = SerializedFileWriter::new(file, schema, props)
            .map_err(|e| CampaignError::store(path, e))?;
        Ok(Parquet {
            path: path.to_path_buf(),
            writer,
            columns: columns.to_vec(),
            group: Vec::with_capacity(ROW_GROUP),
        })
    }

    /// Adds a record, writing the row group when it is full.
    fn push(&mut self, row: Row) -> Result<(), CampaignError> {
        self.group.push(row);
        if self.group.len() == ROW_GROUP {
            self.write_group()?;
        }
        Ok(())
    }

    /// Writes the records held as a row group.
    fn write_group(&mut self) -> Result<(), CampaignError> {
        let path = self.path.clone();
        let err = |e: &dyn std::fmt::Display| CampaignError::store(&path, e);
        let mut rg = self.writer.next_row_group().map_err(|e| err(&e))?;
        let mut i = 0;
        while let Some(mut col) = rg.next_column().map_err(|e| err(&e))? {
            let cells = self.group.iter().map(|r| &r[i]);
            let required = self.columns[i].role() == Some(Role::Landing);
            let levels: Vec<i16> = cells
                .clone()
                .map(|c| i16::from(!matches!(c, Cell::Missing)))
                .collect();
            let defs = (!required).then_some(levels.as_slice());
            match self.columns[i].kind {
                Kind::Integer => {
                    let v: Vec<i64> = cells
                        .filter_map(|c| match c {
                            Cell::Integer(x) => Some(*x),
                            _ => None,
                        })
                        .collect();
                    col.typed::<Int64Type>().write_batch(&v, defs, None)
                }
                Kind::Float => {
                    let v: Vec<f64> = cells
                        .filter_map(|c| match c {
                            Cell::Float(x) => Some(*x),
                            _ => None,
                        })
                        .collect();
                    col.typed::<DoubleType>().write_batch(&v, defs, None)
                }
                Kind::Text => {
                    let v: Vec<ByteArray> = cells
                        .filter_map(|c| match c {
                            Cell::Text(s) => Some(ByteArray::from(s.as_str())),
                            _ => None,
                        })
                        .collect();
                    col.typed::<ByteArrayType>().write_batch(&v, defs, None)
                }
                Kind::Flag => {
                    let v: Vec<bool> = cells
                        .filter_map(|c| match c {
                            Cell::Flag(b) => Some(*b),
                            _ => None,
                        })
                        .collect();
                    col.typed::<BoolType>().write_batch(&v, defs, None)
                }
            }
            .map_err(|e| err(&e))?;
            col.close().map_err(|e| err(&e))?;
            i += 1;
        }
        rg.close().map_err(|e| err(&e))?;
        self.group.clear();
        Ok(())
    }

    /// Writes the last row group and the file's footer.
    fn close(mut self) -> Result<(), CampaignError> {
        if !self.group.is_empty() {
            self.write_group()?;
        }
        self.writer
            .close()
            .map_err(|e| CampaignError::store(&self.path, e))?;
        Ok(())
    }
}

/// The cells of column `i` (of `columns`) of every record of the Parquet file at `path`, in
/// order: one column held at a time.
pub fn read_column(path: &Path, columns: &[Column], i: usize) -> Result<Vec<Cell>, CampaignError> {
    let mut cells = Vec::new();
    visit_column(path, columns, i, &mut |c| cells.push(c))?;
    Ok(cells)
}

/// Calls `visit` with the cell of column `i` (of `columns`) of every record of the Parquet
/// file at `path`, in order, reading a row group at a time: what the caller keeps is all that
/// is held of the column.
pub fn visit_column(
    path: &Path,
    columns: &[Column],
    i: usize,
    visit: &mut dyn FnMut(Cell),
) -> Result<(), CampaignError> {
    use parquet::column::reader::get_typed_column_reader;
    use parquet::file::reader::{FileReader, SerializedFileReader};
    let err = |e: &dyn std::fmt::Display| CampaignError::store(path, e);
    let file = std::fs::File::open(path).map_err(|e| err(&e))?;
    let reader = SerializedFileReader::new(file).map_err(|e| err(&e))?;
    for g in 0..reader.num_row_groups() {
        let group = reader.get_row_group(g).map_err(|e| err(&e))?;
        let n = group.metadata().num_rows() as usize;
        let column = group.get_column_reader(i).map_err(|e| err(&e))?;
        let mut defs: Vec<i16> = Vec::with_capacity(n);
        // Present where the definition level is 1 (the required `landing` has none: all are).
        macro_rules! read {
            ($type:ty, $cell:expr) => {{
                let mut values = Vec::with_capacity(n);
                get_typed_column_reader::<$type>(column)
                    .read_records(n, Some(&mut defs), None, &mut values)
                    .map_err(|e| err(&e))?;
                let mut values = values.into_iter();
                for k in 0..n {
                    let present = defs.get(k).is_none_or(|d| *d == 1);
                    let value = if present { values.next() } else { None };
                    visit(value.map_or(Cell::Missing, $cell));
                }
            }};
        }
        match columns[i].kind {
            Kind::Integer => read!(Int64Type, Cell::Integer),
            Kind::Float => read!(DoubleType, Cell::Float),
            Kind::Text => read!(ByteArrayType, |v: ByteArray| Cell::Text(
                v.as_utf8().unwrap_or_default().to_string()
            )),
            Kind::Flag => read!(BoolType, Cell::Flag),
        }
    }
    Ok(())
}

/// Writes the Parquet file of the campaign folder `dir` whose `landings.jsonl` is written (and
/// closed), from its records a row group at a time; returns how many landings it holds.
pub fn write_parquet(dir: &Path, manifest: &Manifest) -> Result<u64, CampaignError> {
    let columns = &manifest.columns;
    let mut parquet = Parquet::create(&dir.join(PARQUET), columns)?;
    let landings = for_each_record(
        &dir.join("landings.jsonl"),
        columns,
        manifest.part.first_landing,
        |row| parquet.push(row),
    )?;
    parquet.close()?;
    Ok(landings)
}

/// Writes `statistics` (`statistics.json`, any serialisable document) into the folder `dir`
/// whose records and Parquet file are written and, last, its manifest sealed with the digests
/// of its files.
pub fn seal<T: Serialize>(
    dir: &Path,
    manifest: &mut Manifest,
    statistics: &T,
) -> Result<(), CampaignError> {
    let write = |name: &str, text: String| {
        let path = dir.join(name);
        let file = std::fs::File::create(&path).map_err(|e| CampaignError::store(&path, e))?;
        let mut file = std::io::BufWriter::new(file);
        file.write_all(text.as_bytes())
            .and_then(|()| file.flush())
            .and_then(|()| file.get_ref().sync_all())
            .map_err(|e| CampaignError::store(&path, e))
    };
    write("statistics.json", pretty(statistics) + "\n")?;
    manifest.files_sha256 = SEALED
        .iter()
        .map(|name| Ok((name.to_string(), file_sha256(&dir.join(name))?)))
        .collect::<Result<_, CampaignError>>()?;
    manifest.seal_sha256 = manifest.seal();
    write("manifest.json", pretty(manifest) + "\n")?;
    Ok(())
}

/// The campaign's Parquet file in its folder.
pub const PARQUET: &str = "landings.parquet";

/// Pretty JSON of a value made of plain numbers and strings.
pub fn pretty<T: Serialize>(value: &T) -> String {
    serde_json::to_string_pretty(value).unwrap_or_default()
}

/// The text of the file `name` of the campaign folder `dir`.
fn read_file(dir: &Path, name: &str) -> Result<String, CampaignError> {
    let path = dir.join(name);
    std::fs::read_to_string(&path).map_err(|e| CampaignError::Store {
        path: path.display().to_string(),
        message: format!("{e} (expected a campaign folder written by `touchdown campaign --out`)"),
    })
}

/// The SHA-256 (hex) of the file at `path`, read a block at a time.
fn file_sha256(path: &Path) -> Result<String, CampaignError> {
    use sha2::{Digest, Sha256};
    use std::io::Read;
    let mut file = std::fs::File::open(path).map_err(|e| CampaignError::store(path, e))?;
    let mut hasher = Sha256::new();
    let mut block = vec![0u8; 65_536];
    loop {
        let n = file
            .read(&mut block)
            .map_err(|e| CampaignError::store(path, e))?;
        if n == 0 {
            return Ok(format!("{:x}", hasher.finalize()));
        }
        hasher.update(&block[..n]);
    }
}

/// Reads the manifest of a campaign folder, refused if it was edited after it was written (its
/// seal).
pub fn read_manifest(dir: &Path) -> Result<Manifest, CampaignError> {
    let path = dir.join("manifest.json");
    let refuse = |message: String| CampaignError::Store {
        path: path.display().to_string(),
        message,
    };
    let value: serde_json::Value = serde_json::from_str(&read_file(dir, "manifest.json")?)
        .map_err(|e| refuse(format!("not a campaign manifest: {e}")))?;
    let format = value.get("format").and_then(|f| f.as_str()).unwrap_or("");
    if format != FORMAT {
        return Err(refuse(format!(
            "format {format:?}, expected {FORMAT:?}: written by another version of touchdown; run the campaign again with this one"
        )));
    }
    let manifest: Manifest = serde_json::from_value(value)
        .map_err(|e| refuse(format!("not a campaign manifest: {e}")))?;
    if manifest.seal_sha256 != manifest.seal() {
        return Err(CampaignError::Store {
            path: dir.join("manifest.json").display().to_string(),
            message: "was edited after touchdown wrote it (its fields do not match its seal_sha256): restore it or run this part again".into(),
        });
    }
    Ok(manifest)
}
