//! `touchdown compare`: the engines a scenario applies to, and its plot of the traces.

use super::{assert_png, extending, temp, touchdown};

#[test]
fn an_engine_the_scenario_leaves_out_is_refused_by_run_and_left_out_by_compare() {
    let f = extending(
        "applicable",
        "core-and-rapier.toml",
        "flat-drop.toml",
        "two engines",
        "[engines]\napplicable = [\"rapier\", \"core\"]\n",
    );
    let path = f.to_str().unwrap();
    let xml = f.with_file_name("model");
    for args in [
        &["run", path, "--engine", "mujoco"][..],
        &["export-mjcf", path, "--out", xml.to_str().unwrap()],
    ] {
        let out = touchdown(args);
        assert!(!out.status.success(), "{args:?} should fail");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains("core-and-rapier.toml")
                && err.contains("engines.applicable")
                && err.contains("does not apply to the mujoco engine (it lists core, rapier)"),
            "{args:?}: {err}"
        );
        assert!(out.stdout.is_empty(), "nothing is written on failure");
    }
    assert!(!xml.exists(), "no model is exported");
    let out = touchdown(&["compare", path]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("core vs rapier:"), "{text}");
    assert!(!text.contains("vs mujoco"), "{text}");
    assert!(
        text.contains("mujoco  not run: the scenario does not apply to it"),
        "{text}"
    );
    let out = touchdown(&["compare", path, "--engines", "core,mujoco"]);
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).contains("no pair of engines to compare"));
}

#[test]
fn compare_plot_overlays_the_traces_behind_the_metrics() {
    let d = temp("compare-plot");
    let out = touchdown(&[
        "compare",
        "scenarios/flat-drop.toml",
        "--engines",
        "core,rapier",
        "--out",
        d.to_str().unwrap(),
        "--plot",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_png(&d.join("flat-drop.png"));
    for engine in ["core", "rapier"] {
        let text = std::fs::read_to_string(d.join(format!("flat-drop.{engine}.csv"))).unwrap();
        let mut lines = text.lines();
        assert_eq!(
            lines.next(),
            Some("t_s,pitch_rate_rad_s,leg1_primary_stroke_m,leg2_primary_stroke_m,leg3_primary_stroke_m,leg4_primary_stroke_m,vertical_acceleration_m_s2")
        );
        let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
        assert!(rows.len() > 100, "{engine}: {} rows", rows.len());
        // The largest stroke plotted is the stroke the comparison measured (0.0622 m analytic).
        let max = rows
            .iter()
            .map(|r| r[2].parse::<f64>().unwrap())
            .fold(0.0, f64::max);
        assert!((max - 0.0622).abs() < 0.001, "{engine}: {max}");
        // The acceleration over the 2 ms window centred on each time: none within 1 ms of
        // either end; never a NaN.
        assert!(rows.first().unwrap()[6].is_empty() && rows.last().unwrap()[6].is_empty());
        assert!(rows.iter().any(|r| !r[6].is_empty()));
        assert!(!text.contains("NaN") && !text.contains("inf"));
    }
    // The comparison's document beside the traces, with every channel's verdict.
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("flat-drop.json")).unwrap()).unwrap();
    assert_eq!(doc["schema"], "touchdown.compare/1");
    let verdict = doc["pairs"][0]["channels"][0]["verdict"].as_str().unwrap();
    assert!(
        ["pass", "fail", "not_determined"].contains(&verdict),
        "{verdict}"
    );
}
