//! The campaign's analysis, once its records are stored: the statistics from the Parquet file
//! a column at a time (each engine's, and a paired campaign's pairs), and the landings they name
//! (the closest to failing each margin, the disagreements) written as standalone scenario files.

use crate::paired::{self, Disagreement, EngineStatistics, Pair, Paired, Report};
use crate::record::{prefix, Cell, Role};
use crate::statistics::Statistics;
use crate::store::{visit_column, Manifest, PARQUET};
use crate::CampaignError;
use std::path::Path;

/// The statistics of the campaign folder `dir` whose Parquet file holds `landings` records,
/// read a column at a time (a paired campaign's also each pair's), and the landings they list
/// written as standalone scenario files (`closest/`, and `disagreements/` for a pair).
pub fn analyse(dir: &Path, manifest: &Manifest, landings: u64) -> Result<Report, CampaignError> {
    let columns = &manifest.columns;
    let parquet_path = dir.join(PARQUET);
    let mut read = |i, visit: &mut dyn FnMut(Cell)| visit_column(&parquet_path, columns, i, visit);
    let confidence = manifest.confidence;
    Ok(if manifest.engines.len() < 2 {
        let statistics =
            Statistics::from_columns(columns, landings, confidence, "", &mut read, &|by, l| {
                closest_file(None, by, l)
            })?;
        write_closest(dir, manifest, &statistics)?;
        Report::One(Box::new(statistics))
    } else {
        let names: Vec<&str> = manifest.engines.iter().map(String::as_str).collect();
        let prefixes: Vec<String> = names.iter().map(|e| prefix(e, names.len())).collect();
        let mut engines = Vec::with_capacity(names.len());
        for (engine, prefix) in names.iter().zip(&prefixes) {
            let statistics = Statistics::from_columns(
                columns,
                landings,
                confidence,
                prefix,
                &mut read,
                &|by, l| closest_file(Some(engine), by, l),
            )?;
            write_closest(dir, manifest, &statistics)?;
            engines.push(EngineStatistics {
                engine: engine.to_string(),
                statistics,
            });
        }
        let mut pairs = Vec::new();
        for a in 0..names.len() {
            for b in a + 1..names.len() {
                pairs.push(paired::pair(
                    columns,
                    landings,
                    confidence,
                    [names[a], names[b]],
                    [&prefixes[a], &prefixes[b]],
                    &mut read,
                    &|l| format!("{DISAGREEMENTS}/landing-{l}.toml"),
                )?);
            }
        }
        write_disagreements(dir, manifest, &pairs)?;
        Report::Paired(Paired {
            landings,
            confidence,
            engines,
            pairs,
        })
    })
}

/// The folder of a paired campaign's listed disagreements, as scenario files.
pub const DISAGREEMENTS: &str = "disagreements";

/// The folder of a campaign's closest landings (statistics.json's `margins.closest`), as
/// scenario files.
pub const CLOSEST: &str = "closest";

/// The file of the landing `landing` closest to failing `by` a margin (of `engine`'s, in a
/// paired campaign): `CLOSEST/[engine-]by-landing-N.toml`.
fn closest_file(engine: Option<&str>, by: &str, landing: u64) -> String {
    let by = by.replace('_', "-");
    match engine {
        Some(e) => format!("{CLOSEST}/{e}-{by}-landing-{landing}.toml"),
        None => format!("{CLOSEST}/{by}-landing-{landing}.toml"),
    }
}

/// Writes the closest landings of `statistics` as the standalone scenarios that ran them.
fn write_closest(
    dir: &Path,
    manifest: &Manifest,
    statistics: &Statistics,
) -> Result<(), CampaignError> {
    write_scenarios(
        dir,
        manifest,
        CLOSEST,
        statistics
            .margins
            .closest
            .iter()
            .map(|c| (c.landing, &c.applied, c.scenario_file.as_str())),
    )
}

/// Writes each landing `pairs` list as the standalone scenario that ran it:
/// `DISAGREEMENTS/landing-N.toml`.
fn write_disagreements(
    dir: &Path,
    manifest: &Manifest,
    pairs: &[Pair],
) -> Result<(), CampaignError> {
    let listed: std::collections::BTreeMap<u64, &Disagreement> = pairs
        .iter()
        .flat_map(|p| &p.worst)
        .map(|w| (w.landing, w))
        .collect();
    write_scenarios(
        dir,
        manifest,
        DISAGREEMENTS,
        listed
            .values()
            .map(|w| (w.landing, &w.applied, w.scenario_file.as_str())),
    )
}

/// Writes each landing of `landings` (its index, the values applied to it by column, its file
/// under `dir`) as the standalone scenario that ran it: the resolved base of the manifest with
/// the values applied. Nothing, not even `folder`, when there is none.
fn write_scenarios<'a>(
    dir: &Path,
    manifest: &Manifest,
    folder: &str,
    landings: impl Iterator<Item = (u64, &'a serde_json::Map<String, serde_json::Value>, &'a str)>,
) -> Result<(), CampaignError> {
    let mut landings = landings.peekable();
    if landings.peek().is_none() {
        return Ok(());
    }
    let base_file = &manifest.base_scenario_file;
    let base = touchdown_scenario::ScenarioBase::from_toml(base_file, &manifest.base_scenario)
        .map_err(|e| CampaignError::store(Path::new(base_file), e))?;
    let folder = dir.join(folder);
    std::fs::create_dir_all(&folder).map_err(|e| CampaignError::store(&folder, e))?;
    for (landing, applied_values, scenario_file) in landings {
        let applied = manifest
            .columns
            .iter()
            .filter(|c| c.role() == Some(Role::Applied))
            .map(|c| applied_values.get(&c.name));
        let mut overrides: Vec<(&str, toml::Value)> = manifest
            .dispersed_fields
            .iter()
            .zip(applied)
            .filter_map(|(field, v)| {
                let v = match v? {
                    serde_json::Value::Bool(b) => toml::Value::Boolean(*b),
                    serde_json::Value::String(s) => toml::Value::String(s.clone()),
                    serde_json::Value::Number(x) => toml::Value::Float(x.as_f64()?),
                    _ => return None,
                };
                Some((field.as_str(), v))
            })
            .collect();
        // Named for what it is, not for the base it was drawn from.
        let values: Vec<String> = overrides
            .iter()
            .map(|(field, v)| format!("{field} = {v}"))
            .collect();
        overrides.push((
            "name",
            toml::Value::String(format!("{}: landing {landing}", manifest.campaign_name)),
        ));
        overrides.push((
            "description",
            toml::Value::String(format!(
                "Landing {landing} of the campaign {:?} (seed {}), on {}: the base scenario {} with {} (the file's units).",
                manifest.campaign_name,
                manifest.seed,
                manifest.engines.join(" and "),
                manifest.base_scenario_file,
                values.join(", ")
            )),
        ));
        let path = dir.join(scenario_file);
        let sc = base
            .with(&overrides)
            .map_err(|e| CampaignError::store(&path, format!("landing {landing}: {e}")))?;
        std::fs::write(&path, sc.to_toml()).map_err(|e| CampaignError::store(&path, e))?;
    }
    Ok(())
}
