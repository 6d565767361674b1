//! The settled end (`stability.settled_tolerance`, docs/errata.md, "Settled landings: an early
//! end with a proof"): dispersed landings of the bundled campaign, each run to its end time and
//! again with the settled end, must agree on every outcome and every maximum (the strokes and
//! the least stability distance within ε, every other maximum exactly). The CI runs the first
//! 60 draws; `TOUCHDOWN_SETTLED_LANDINGS=10000 cargo test --release -p touchdown-cli settled`
//! runs 10,000 (docs/errata.md gives its figures).

use super::{extending, root, touchdown};
use serde_json::Value;

/// ε, ft (the campaign's vehicle file is in feet): 0.1 mm.
const TOLERANCE_FT: f64 = 1.0e-4 / 0.3048;

/// The campaign `lm-1-6-d3117` on `scenario`, its first `landings` draws, written into `dir`
/// and run; its landing records in order.
fn landings(dir: &std::path::Path, name: &str, scenario: &str, landings: u64) -> Vec<Value> {
    let text = std::fs::read_to_string(root().join("scenarios/campaigns/lm-1-6-d3117.toml"))
        .unwrap()
        .replace(
            "scenario = \"../table-i-2-2-vv8.toml\"",
            &format!("scenario = {scenario:?}"),
        )
        .replace("landings = 3000", &format!("landings = {landings}"));
    let file = dir.join(format!("{name}.toml"));
    std::fs::write(&file, text).unwrap();
    let o = touchdown(&["campaign", file.to_str().unwrap(), "--format", "json", "-q"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8(o.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str::<Value>(l).unwrap())
        .filter(|v| v.get("landing").is_some())
        .collect()
}

#[test]
fn settled_landings_keep_every_outcome_and_maximum() {
    let n: u64 = std::env::var("TOUCHDOWN_SETTLED_LANDINGS")
        .map(|v| v.parse().expect("TOUCHDOWN_SETTLED_LANDINGS is a count"))
        .unwrap_or(60);
    let settled = extending(
        "settled",
        "settled.toml",
        "table-i-2-2-vv8.toml",
        "settled",
        &format!("\n[stability]\nsettled_tolerance = {TOLERANCE_FT}\n"),
    );
    let dir = settled.parent().unwrap();
    let base = root().join("scenarios/table-i-2-2-vv8.toml");
    let full = landings(dir, "full", base.to_str().unwrap(), n);
    let early = landings(dir, "early", settled.to_str().unwrap(), n);
    assert_eq!(full.len() as u64, n);
    let eps = TOLERANCE_FT * 0.3048;
    let mut ended = 0;
    for (a, b) in full.iter().zip(&early) {
        let landing = &a["landing"];
        assert_eq!(a["outcome"], b["outcome"], "landing {landing}");
        assert_eq!(a["failure"], b["failure"], "landing {landing}");
        let (ta, tb) = (
            a["t_end_s"].as_f64().unwrap(),
            b["t_end_s"].as_f64().unwrap(),
        );
        assert!(tb <= ta, "landing {landing}");
        if tb < ta {
            ended += 1;
        }
        for (key, value) in a.as_object().unwrap() {
            let (Some(x), Some(y)) = (value.as_f64(), b[key].as_f64()) else {
                continue;
            };
            let moved = (x - y).abs();
            if key.ends_with(".stroke_m") || key == "min_stability_distance_m" {
                assert!(moved <= eps, "landing {landing}: {key} {x} vs {y}");
            } else if key.ends_with("force_n") || key.starts_with("peak_") {
                assert_eq!(x, y, "landing {landing}: {key}");
            }
        }
    }
    // The comparison means something only where the settled end ended a landing early.
    assert!(ended > 0, "no landing of {n} ended settled");
    eprintln!("{ended} of {n} landings ended settled");
}

#[test]
fn the_summary_says_where_a_landing_was_proved_settled() {
    let o = touchdown(&[
        "run",
        "scenarios/table-i-2-2-vv10.toml",
        "--set",
        "stability.settled_tolerance=0.001",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.contains("proved settled at t = 0.70") && out.contains("run:      0.70"),
        "{out}"
    );
}

#[test]
fn a_settled_end_outside_its_derivation_is_refused() {
    let o = touchdown(&[
        "run",
        "scenarios/soil-drop.toml",
        "--set",
        "stability.settled_tolerance=0.001",
    ]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("stability.settled_tolerance") && err.contains("soil"),
        "{err}"
    );
    let o = touchdown(&[
        "run",
        "scenarios/table-i-2-2-vv8.toml",
        "--set",
        "stability.settled_tolerance=0",
    ]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("stability.settled_tolerance"), "{err}");
}
