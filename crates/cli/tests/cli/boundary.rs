//! `touchdown boundary`: the stability boundary in CSV, JSON and text, its plot, its refusals.

use super::{assert_png, extending, root, temp, touchdown};

#[test]
fn boundary_prints_csv_and_json() {
    let f = extending(
        "boundary",
        "steep.toml",
        "fig-25-26.toml",
        "steep",
        "[surface]\nkind = \"rigid\"\nslope = 26.0\nhole = [0.3333, 0.3333, 0.0, 0.0]\nfriction = 0.0\n",
    );
    let args = |fmt: &'static str| {
        [
            "boundary",
            f.to_str().unwrap(),
            "--vv=-12:-12:1",
            "--vh-step",
            "2",
            "--vh-max",
            "12",
            "--tol",
            "0.1",
            "--format",
            fmt,
        ]
        .map(String::from)
    };
    let csv = touchdown(&args("csv").iter().map(String::as_str).collect::<Vec<_>>());
    assert!(
        csv.status.success(),
        "{}",
        String::from_utf8_lossy(&csv.stderr)
    );
    let text = String::from_utf8(csv.stdout).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some(
            "engine,stop_restitution,vv_m_s,direction,stable_at_vh_m_s,unstable_at_vh_m_s,vh_m_s,resolved,undecided,past_capacity_vh_m_s,safe_to_vh_m_s,safe_until,refined_holds"
        )
    );
    // One row per transition; the first is the boundary (the lowest stable -> unstable), in SI.
    let row: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!((row[0], row[1]), ("core", ""));
    assert_eq!(row[2].parse::<f64>().unwrap(), -12.0 * 0.3048);
    assert_eq!(row[3], "stable_to_unstable");
    let vh: f64 = row[6].parse().expect("a boundary was found");
    assert!(vh > 0.0 && vh < 12.0 * 0.3048);
    assert_eq!(row[7], "true");
    // The safe envelope ends at or below the overturn.
    let safe: f64 = row[10].parse().expect("a safe envelope");
    assert!(safe <= vh, "{row:?}");
    let (lo, hi): (f64, f64) = (row[4].parse().unwrap(), row[5].parse().unwrap());
    assert!(lo < vh && vh < hi && hi - lo <= 0.1 * 0.3048 + 1e-12);
    // JSON Lines: one document per point, with the scenario and the settings as given.
    let json = touchdown(&args("json").iter().map(String::as_str).collect::<Vec<_>>());
    let lines: Vec<serde_json::Value> = String::from_utf8(json.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 1);
    let v = &lines[0];
    assert_eq!(v["schema"], "touchdown.boundary/1");
    assert!(v["scenario"]["sha256"].as_str().unwrap().len() == 64);
    assert_eq!(v["settings"]["vv_ft_s"][0], -12.0);
    assert_eq!(v["settings"]["tolerance_ft_s"], 0.1);
    assert!(
        (v["vh_m_s"].as_f64().unwrap() - vh).abs() < 1e-12,
        "csv and json agree"
    );
    let transitions = v["transitions"].as_array().unwrap();
    assert_eq!(
        transitions.len(),
        text.lines().count() - 1,
        "a CSV row per transition"
    );
    for key in [
        "stable_at_vh_m_s",
        "unstable_at_vh_m_s",
        "vh_m_s",
        "direction",
        "resolved",
        "undecided_at_vh_m_s",
    ] {
        assert!(transitions[0].get(key).is_some(), "transition field {key}");
    }
    assert_eq!(transitions[0]["vh_m_s"], v["vh_m_s"]);
    // The core's transitions state the step's accuracy: their ends landed again ÷ 8.
    for t in transitions {
        let r = &t["refined"];
        assert_eq!(r["refinement"], 8.0, "{t}");
        let holds = r["stable_at_outcome"] == "stable" && r["unstable_at_outcome"] == "unstable";
        assert_eq!(r["holds"], holds, "{t}");
    }
    assert_eq!(
        v["undecided_at_vh_m_s"].as_array().unwrap().len() as u64,
        v["undecided"].as_u64().unwrap()
    );
    assert!(
        v["landings"].as_u64().unwrap() >= 7,
        "the whole grid 0, 2, ..., 12"
    );
    let table = touchdown(&args("text").iter().map(String::as_str).collect::<Vec<_>>());
    let table = String::from_utf8(table.stdout).unwrap();
    assert!(table.starts_with("stability boundary:"), "{table}");
    assert!(
        table.contains(&format!(
            "accuracy (core): each transition's bracket ends landed again with every step limit ÷ 8: {} of {} hold",
            transitions.iter().filter(|t| t["refined"]["holds"] == true).count(),
            transitions.len()
        )),
        "{table}"
    );
    assert!(
        table
            .lines()
            .any(|l| l.starts_with("  core") && l.contains(&format!("{:.3}", vh / 0.3048))),
        "{table}"
    );
    // The safe envelope is in every document; the search over end-stop laws reports each and
    // their spread.
    assert!(v["safe"].is_object(), "{v}");
    let mut spread: Vec<String> = args("text").to_vec();
    spread.extend(["--stop-restitution".to_string(), "0.2,1".to_string()]);
    let spread = touchdown(&spread.iter().map(String::as_str).collect::<Vec<_>>());
    assert!(
        spread.status.success(),
        "{}",
        String::from_utf8_lossy(&spread.stderr)
    );
    let spread = String::from_utf8(spread.stdout).unwrap();
    assert!(spread.contains("by end-stop restitution"), "{spread}");
    let last = spread.lines().last().unwrap();
    assert!(
        last.starts_with("  core") && last.split_whitespace().count() == 5,
        "{spread}"
    );
    // A restitution outside [0, 1] is refused, naming the argument.
    let mut bad_e: Vec<String> = args("text").to_vec();
    bad_e.extend(["--stop-restitution".to_string(), "1.5".to_string()]);
    let bad = touchdown(&bad_e.iter().map(String::as_str).collect::<Vec<_>>());
    assert!(!bad.status.success());
    let e = String::from_utf8_lossy(&bad.stderr);
    assert!(
        e.contains("--stop-restitution") && e.contains("[0, 1]"),
        "{e}"
    );
    // A bad range is a clear error.
    let bad = touchdown(&["boundary", f.to_str().unwrap(), "--vv", "12:4:1"]);
    assert!(!bad.status.success());
    let e = String::from_utf8_lossy(&bad.stderr);
    assert!(e.contains("negative down"), "{e}");
    // So are bad search settings, naming the argument.
    for (flag, value) in [("--vh-step", "0"), ("--tol", "1e-12"), ("--vh-max", "-1")] {
        let arg = format!("{flag}={value}");
        let bad = touchdown(&["boundary", f.to_str().unwrap(), "--vv=-12:-12:1", &arg]);
        assert!(!bad.status.success());
        let e = String::from_utf8_lossy(&bad.stderr);
        assert!(
            e.contains(flag) && e.contains("expected"),
            "{flag} {value}: {e}"
        );
    }
    // A speed the scenario cannot take names the scenario, the speed and the field.
    let bad = touchdown(&["boundary", f.to_str().unwrap(), "--vv=-1e308:-1e308:1"]);
    assert_eq!(bad.status.code(), Some(1));
    let e = String::from_utf8_lossy(&bad.stderr);
    assert!(
        e.contains(&format!("{} at vertical velocity -1e+308", f.display()))
            && e.contains("touchdown.vertical_velocity"),
        "{e}"
    );
    // A scenario with no horizontal velocity gives the search no direction: a field error
    // naming the file and the field, not a fault of the reference data.
    let drop = root().join("scenarios/tripod-drop.toml");
    let bad = touchdown(&["boundary", drop.to_str().unwrap(), "--vv=-8:-8:2"]);
    assert_eq!(bad.status.code(), Some(1));
    let e = String::from_utf8_lossy(&bad.stderr);
    assert!(
        e.contains(&format!(
            "{}: field `touchdown.horizontal_velocity`: expected a non-zero",
            drop.display()
        )) && !e.contains("reference data"),
        "{e}"
    );
}

#[test]
fn boundary_plot_overlays_the_engines() {
    let d = temp("boundary-plot");
    let png = d.join("boundary-near-boundary-overturn.png");
    let out = touchdown(&[
        "boundary",
        "scenarios/near-boundary-overturn.toml",
        "--vv=-8:-10:2",
        "--vh-step",
        "8",
        "--vh-max",
        "32",
        "--tol",
        "1",
        "--format",
        "csv",
        "--out",
        d.to_str().unwrap(),
        "--plot",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_png(&png);
    let points: Vec<serde_json::Value> = std::fs::read_to_string(png.with_extension("jsonl"))
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(points.len(), 2);
    assert!(points.iter().all(|p| p["engine"] == "core"));
    assert!(points
        .iter()
        .all(|p| p["transitions"].is_array() && p["undecided_at_vh_m_s"].is_array()));
    let csv = String::from_utf8(out.stdout).unwrap();
    assert!(
        csv.starts_with("engine,stop_restitution,vv_m_s,direction,"),
        "{csv}"
    );
    // Refused: an engine the scenario leaves out.
    let f = extending(
        "boundary-applicable",
        "core-only.toml",
        "near-boundary-overturn.toml",
        "core only",
        "[engines]\napplicable = [\"core\"]\n",
    );
    let out = touchdown(&[
        "boundary",
        f.to_str().unwrap(),
        "--vv=-8:-8:1",
        "--engines",
        "core,rapier",
    ]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("does not apply to the rapier engine"));
}
