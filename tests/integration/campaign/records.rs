//! The records: the values drawn reach the model, MuJoCo's are single runs', Parquet reads back.

use super::{small, small_with};
use touchdown_campaign::distribution::Value;
use touchdown_campaign::landing::draws;
use touchdown_campaign::record::Cell;
use touchdown_campaign::run::run;
use touchdown_campaign::Campaign;
use touchdown_tests::{python, root};

#[test]
fn the_values_applied_are_the_values_drawn_and_reach_the_model() {
    let campaign = Campaign::load(small()).unwrap();
    let mut rows = Vec::new();
    run(&campaign, None, None, None, false, |r| rows.push(r.clone())).unwrap();
    let n = campaign.dispersions.len();
    let mut references = std::collections::BTreeSet::new();
    for (i, row) in rows.iter().enumerate() {
        let drawn = draws(&campaign, i as u64);
        let applied: Vec<Cell> = drawn.iter().map(Cell::from).collect();
        assert_eq!(row[1..=n], applied[..], "landing {i}");
        if let Value::Text(t) = &drawn[4] {
            references.insert(t.clone());
        }
        // In SI in the model: the vertical velocity (ft/s in the file) and the heading (deg).
        let sc = campaign.base.with(&campaign.overrides(&drawn)).unwrap();
        let (Value::Number(vv), Value::Number(heading)) = (&drawn[0], &drawn[2]) else {
            panic!("numbers expected")
        };
        assert!((sc.touchdown.velocity_g.z - vv * 0.3048).abs() < 1e-12);
        assert!((sc.touchdown.attitude.z - heading.to_radians()).abs() < 1e-12);
    }
    // 24 landings of a 3:1 choice draw both values; the list cycles through its three slopes.
    assert_eq!(references.len(), 2);
    let slopes: Vec<&Cell> = rows.iter().take(3).map(|r| &r[6]).collect();
    assert_eq!(
        slopes,
        [&Cell::Float(0.0), &Cell::Float(5.0), &Cell::Float(10.0)]
    );
}

#[test]
fn the_parquet_records_read_back_in_pandas_polars_and_duckdb() {
    let tmp = tempfile::tempdir().unwrap();
    let campaign = Campaign::load(small()).unwrap();
    run(&campaign, None, None, Some(tmp.path()), false, |_| ()).unwrap();
    let out = std::process::Command::new(python())
        .arg(root().join("python/tests/campaign_read.py"))
        .arg(tmp.path())
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let report: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(report["rows"], 24);
    assert_eq!(
        report["readers"],
        serde_json::json!(["duckdb", "pandas", "polars"])
    );
}

/// A MuJoCo campaign lands through runners that serve many landings (one per thread): each
/// landing's record is that of a runner started for it alone.
#[test]
fn a_mujoco_campaign_lands_as_single_runs_do() {
    python();
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("mujoco.toml");
    small_with(&file, 4);
    let text = std::fs::read_to_string(&file).unwrap();
    std::fs::write(
        &file,
        text.replace("engine = \"core\"", "engine = \"mujoco\""),
    )
    .unwrap();
    let campaign = Campaign::load(&file).unwrap();
    let mut rows = Vec::new();
    let (manifest, _) = run(&campaign, None, Some(2), None, false, |r| {
        rows.push(r.clone())
    })
    .unwrap();
    let strokes: Vec<usize> = (0..4)
        .map(|leg| {
            let name = format!("leg{}.primary.stroke_m", leg + 1);
            manifest
                .columns
                .iter()
                .position(|c| c.name == name)
                .unwrap()
        })
        .collect();
    for (i, row) in rows.iter().enumerate() {
        let sc = campaign
            .base
            .with(&campaign.overrides(&draws(&campaign, i as u64)))
            .unwrap();
        let alone =
            touchdown_registry::land(campaign.engines[0], &file, &sc, &mut (), None).unwrap();
        for (leg, col) in strokes.iter().enumerate() {
            assert_eq!(
                row[*col],
                Cell::Float(alone.max_primary_stroke_m[leg]),
                "landing {i} leg {}",
                leg + 1
            );
        }
    }
}
