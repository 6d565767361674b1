//! A campaign's files (docs/campaigns.md, "Output"): `manifest.json` (what computed the
//! landings and which), `landings.jsonl` (a record per line, in landing order),
//! `landings.parquet` (the same records in columns) and `statistics.json`.

use crate::record::{Cell, Column, Kind, Row};
use crate::spec::Campaign;
use crate::statistics::Statistics;
use crate::CampaignError;
use parquet::data_type::{BoolType, ByteArray, ByteArrayType, DoubleType, Int64Type};
use parquet::file::properties::WriterProperties;
use parquet::file::writer::SerializedFileWriter;
use parquet::schema::types::Type;
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::sync::Arc;

/// The manifest's format name.
pub const FORMAT: &str = "touchdown-campaign/1";

/// Landings per Parquet row group.
const ROW_GROUP: usize = 65_536;

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
    /// The engine.
    pub engine: String,
    /// The seed.
    pub seed: u64,
    /// The confidence of the statistics' lower bounds.
    pub confidence: f64,
    /// Landings of the whole campaign.
    pub landings: u64,
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
}

impl Manifest {
    /// The manifest of `campaign` (`landings` in all) for the part `part`.
    pub fn new(campaign: &Campaign, landings: u64, part: Part, columns: &[Column]) -> Manifest {
        Manifest {
            format: FORMAT.into(),
            touchdown_version: env!("CARGO_PKG_VERSION").into(),
            source_revision: env!("TOUCHDOWN_REVISION").into(),
            campaign_file: campaign.file.clone(),
            campaign_name: campaign.name.clone(),
            campaign_sha256: campaign.identity.clone(),
            engine: campaign.engine.name().into(),
            seed: campaign.seed,
            confidence: campaign.confidence,
            landings,
            base_scenario_file: campaign.scenario_path.display().to_string(),
            base_scenario_sha256: campaign.base_scenario.sha256(),
            base_scenario: campaign.base_scenario.to_toml(),
            part,
            columns: columns.to_vec(),
        }
    }

    /// Whether `other` is a part of the same campaign run by the same code: everything but the
    /// part, the campaign file's path and the landing count (which `--add` changes) agree.
    /// `Err` names what differs.
    pub fn same_campaign(&self, other: &Manifest) -> Result<(), String> {
        let checks = [
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
            (
                "campaign (its SHA-256)",
                &self.campaign_sha256,
                &other.campaign_sha256,
            ),
            ("engine", &self.engine, &other.engine),
            (
                "base scenario (its SHA-256)",
                &self.base_scenario_sha256,
                &other.base_scenario_sha256,
            ),
        ];
        for (what, a, b) in checks {
            if a != b {
                return Err(format!("{what}: {a} against {b}"));
            }
        }
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

/// Reads the records of `landings.jsonl` back (`file` names it in errors).
pub fn read_json_lines(
    file: &str,
    text: &str,
    columns: &[Column],
) -> Result<Vec<Row>, CampaignError> {
    text.lines()
        .enumerate()
        .map(|(n, line)| {
            let err = |message: String| CampaignError::Store {
                path: format!("{file}:{}", n + 1),
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
        })
        .collect()
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
            let repetition = if c.name == "landing" {
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

/// Writes the records as Parquet at `path`: uncompressed, row groups of 65,536 landings,
/// deterministic (same records, same bytes).
pub fn write_parquet(path: &Path, columns: &[Column], rows: &[Row]) -> Result<(), CampaignError> {
    let err = |e: &dyn std::fmt::Display| CampaignError::Store {
        path: path.display().to_string(),
        message: e.to_string(),
    };
    let file = std::fs::File::create(path).map_err(|e| err(&e))?;
    let props = Arc::new(
        WriterProperties::builder()
            .set_created_by(format!("touchdown {}", env!("CARGO_PKG_VERSION")))
            .build(),
    );
    let schema = Arc::new(schema(columns).map_err(|e| err(&e))?);
    let mut writer = SerializedFileWriter::new(file, schema, props).map_err(|e| err(&e))?;
    for group in rows.chunks(ROW_GROUP) {
        let mut rg = writer.next_row_group().map_err(|e| err(&e))?;
        let mut i = 0;
        while let Some(mut col) = rg.next_column().map_err(|e| err(&e))? {
            let cells = group.iter().map(|r| &r[i]);
            let required = columns[i].name == "landing";
            let levels: Vec<i16> = cells
                .clone()
                .map(|c| i16::from(!matches!(c, Cell::Missing)))
                .collect();
            let defs = (!required).then_some(levels.as_slice());
            match columns[i].kind {
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
    }
    writer.close().map_err(|e| err(&e))?;
    Ok(())
}

/// Writes a campaign's files into `dir`: the manifest, the records (JSON Lines and Parquet)
/// and their statistics.
pub fn write_all(
    dir: &Path,
    manifest: &Manifest,
    rows: &[Row],
    statistics: &Statistics,
) -> Result<(), CampaignError> {
    let write = |name: &str, text: String| {
        let path = dir.join(name);
        std::fs::write(&path, text).map_err(|e| CampaignError::Store {
            path: path.display().to_string(),
            message: e.to_string(),
        })
    };
    std::fs::create_dir_all(dir).map_err(|e| CampaignError::Store {
        path: dir.display().to_string(),
        message: e.to_string(),
    })?;
    write("manifest.json", pretty(manifest) + "\n")?;
    let mut lines = String::new();
    for r in rows {
        lines.push_str(&json_line(&manifest.columns, r));
        lines.push('\n');
    }
    write("landings.jsonl", lines)?;
    write_parquet(&dir.join("landings.parquet"), &manifest.columns, rows)?;
    write("statistics.json", pretty(statistics) + "\n")
}

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

/// Reads the manifest of a campaign folder.
pub fn read_manifest(dir: &Path) -> Result<Manifest, CampaignError> {
    let manifest: Manifest =
        serde_json::from_str(&read_file(dir, "manifest.json")?).map_err(|e| {
            CampaignError::Store {
                path: dir.join("manifest.json").display().to_string(),
                message: format!("not a campaign manifest: {e}"),
            }
        })?;
    if manifest.format != FORMAT {
        return Err(CampaignError::Store {
            path: dir.join("manifest.json").display().to_string(),
            message: format!("format {:?}, expected {FORMAT:?}", manifest.format),
        });
    }
    Ok(manifest)
}

/// Reads the manifest and records of a campaign folder.
pub fn read_dir(dir: &Path) -> Result<(Manifest, Vec<Row>), CampaignError> {
    let manifest = read_manifest(dir)?;
    let file = dir.join("landings.jsonl").display().to_string();
    let rows = read_json_lines(&file, &read_file(dir, "landings.jsonl")?, &manifest.columns)?;
    let span = manifest.part.end_landing - manifest.part.first_landing;
    let indices_ok = rows.len() as u64 == span
        && rows
            .iter()
            .zip(manifest.part.first_landing..)
            .all(|(r, i)| r[0] == Cell::Integer(i as i64));
    if !indices_ok {
        return Err(CampaignError::Store {
            path: file,
            message: format!(
                "expected landings {} to {} in order, one per line",
                manifest.part.first_landing,
                manifest.part.end_landing.saturating_sub(1)
            ),
        });
    }
    Ok((manifest, rows))
}
