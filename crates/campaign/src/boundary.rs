//! The stability boundary of a campaign's base configuration, drawn on its outcomes plot
//! (`boundary.json`): searched by `touchdown_validation::boundary` over the campaign's range of
//! descent and horizontal speeds when those two are the campaign's most influential inputs and
//! the base scenario moves along the dispersed horizontal axis. It holds every other input at
//! its base value: beside a campaign that disperses them, a reference, not a dividing line.

use crate::record::Cell;
use crate::statistics::Statistics;
use crate::store::{read_column, Manifest};
use crate::{Campaign, CampaignError};
use std::path::Path;
use touchdown_validation::boundary::{Asked, Request};

/// The file the boundary is written to in a campaign's folder.
pub const FILE: &str = "boundary.json";

/// Grid intervals across the campaign's range of horizontal speeds.
const GRID_INTERVALS: f64 = 16.0;

/// The bisection tolerance: that range divided by this.
const TOLERANCE_PARTS: f64 = 400.0;

/// Descent speeds searched, evenly over the campaign's range.
const DESCENT_SPEEDS: usize = 7;

/// Writes the boundary of the base configuration of `campaign` (on its first engine) into
/// `dir/boundary.json` when the campaign's `statistics` rank the vertical velocity and the
/// base's horizontal axis its two most influential inputs (read from the records of `dir`,
/// described by `manifest`), and removes an older one otherwise; `searching` is called before
/// the search starts (it lands seven descent speeds). Returns whether it wrote one.
pub fn write(
    campaign: &Campaign,
    dir: &Path,
    manifest: &Manifest,
    statistics: &Statistics,
    searching: impl FnOnce(),
) -> Result<bool, CampaignError> {
    let path = dir.join(FILE);
    if path.exists() {
        std::fs::remove_file(&path).map_err(|e| CampaignError::store(&path, e))?;
    }
    let top: Vec<&str> = (statistics.influence.iter())
        .take(2)
        .map(|i| i.column.as_str())
        .collect();
    let column = |field: &str| {
        (campaign.dispersions.iter())
            .find(|d| d.field == field)
            .map(|d| format!("applied.{}", d.column))
    };
    let [hx, hy] = campaign.base_scenario.file.touchdown.horizontal_velocity;
    let (axis, along) = match (hx == 0.0, hy == 0.0) {
        (true, false) => ("touchdown.horizontal_velocity[1]", hy.signum()),
        (false, true) => ("touchdown.horizontal_velocity[0]", hx.signum()),
        _ => return Ok(false),
    };
    let (Some(vv_col), Some(vh_col)) = (column("touchdown.vertical_velocity"), column(axis)) else {
        return Ok(false);
    };
    if !(top.contains(&vv_col.as_str()) && top.contains(&vh_col.as_str())) {
        return Ok(false);
    }
    // The two columns, read from the campaign's Parquet file one at a time.
    let values = |name: &str| -> Result<Vec<f64>, CampaignError> {
        let Some(i) = manifest.columns.iter().position(|c| c.name == name) else {
            return Ok(Vec::new());
        };
        let cells = read_column(&dir.join("landings.parquet"), &manifest.columns, i)?;
        Ok((cells.into_iter())
            .filter_map(|c| match c {
                Cell::Float(x) => Some(x),
                _ => None,
            })
            .collect())
    };
    let (vv, vh) = (values(&vv_col)?, values(&vh_col)?);
    let span = |v: &[f64]| {
        (v.iter()).fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(*x), b.max(*x))
        })
    };
    // Along the base's horizontal direction: the search's Vh is the dispersed component times
    // that direction's sign; descent speeds positive down, every one a descent.
    let (h0, h1) = span(&vh.iter().map(|x| x * along).collect::<Vec<_>>());
    let (v0, v1) = span(&vv.iter().map(|x| -x).collect::<Vec<_>>());
    if !(h1 > h0 && v1 > v0 && v0 > 0.0) {
        return Ok(false);
    }
    let last = (DESCENT_SPEEDS - 1) as f64;
    let vertical: Vec<f64> = (0..DESCENT_SPEEDS)
        .map(|k| -(v0 + (v1 - v0) * k as f64 / last))
        .collect();
    let engine = [campaign.engines[0]];
    let study = Request {
        base: &campaign.base,
        overrides: &[],
        vv: &vertical,
        vv_argument: "the campaign's vertical velocities",
        asked: Asked {
            vh_start: Some(h0),
            vh_step: Some((h1 - h0) / GRID_INTERVALS),
            vh_max: Some(h1),
            tolerance: Some((h1 - h0) / TOLERANCE_PARTS),
            scan_step: Some(0.0),
        },
        engines: &engine,
        restitutions: &[],
    }
    .resolve()?;
    searching();
    let points = study.run(&|| (), &|_| ())?;
    let line: Vec<serde_json::Value> = (points.iter())
        .filter_map(|p| {
            p.point.vh.map(|vh| {
                serde_json::json!({ vh_col.as_str(): vh * along, vv_col.as_str(): -p.point.vv })
            })
        })
        .collect();
    let document = serde_json::json!({
        "engine": engine[0].name(),
        "base_scenario": campaign.scenario_path.display().to_string(),
        "note": "the stability boundary of the base configuration (every other input at its base value), found by touchdown boundary's search",
        "points": line,
    });
    let text =
        serde_json::to_string_pretty(&document).map_err(|e| CampaignError::store(&path, e))?;
    std::fs::write(&path, text).map_err(|e| CampaignError::store(&path, e))?;
    Ok(true)
}
