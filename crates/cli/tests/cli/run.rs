//! `touchdown run`: the same bytes twice, its summaries, report page, energy lines and history.

use super::{temp, touchdown};
use std::path::Path;

#[test]
fn same_scenario_same_binary_byte_identical_outputs() {
    let mut headers = Vec::new();
    for engine in ["core", "rapier", "mujoco"] {
        let (a, b) = (temp(&format!("{engine}-a")), temp(&format!("{engine}-b")));
        for d in [&a, &b] {
            let out = touchdown(&[
                "run",
                "scenarios/fig-25-26.toml",
                "--engine",
                engine,
                "--format",
                "json",
                "--out",
                d.to_str().unwrap(),
            ]);
            assert!(
                out.status.success(),
                "{engine}: {}",
                String::from_utf8_lossy(&out.stderr)
            );
        }
        for f in ["summary.json", "history.csv", "scenario.resolved.toml"] {
            let (x, y) = (
                std::fs::read(a.join(f)).unwrap(),
                std::fs::read(b.join(f)).unwrap(),
            );
            assert!(!x.is_empty(), "{engine}: {f} is empty");
            assert!(x == y, "{engine}: {f} differs between two runs");
        }
        let history = std::fs::read_to_string(a.join("history.csv")).unwrap();
        assert!(
            !history.contains("NaN") && !history.contains("inf"),
            "{engine}: no NaN or infinity in the history"
        );
        assert!(history.lines().count() > 500);
        headers.push(history.lines().next().unwrap().to_string());
    }
    assert!(
        headers.iter().all(|h| *h == headers[0]),
        "every engine writes the same history columns"
    );
}

#[test]
fn json_summary_has_the_documented_fields() {
    let out = touchdown(&["run", "scenarios/table-i-2-2-vv8.toml", "--format", "json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for key in [
        "engine",
        "outcome",
        "t_end_s",
        "steps",
        "max_primary_stroke_m",
        "max_secondary_compression_m",
        "max_secondary_tension_m",
        "peak_primary_force_n",
        "peak_secondary_compression_force_n",
        "peak_secondary_tension_force_n",
        "peak_specific_force_m_s2",
        "peak_pitch_rate_rad_s",
        "min_stability_distance_m",
        "first_contact_s",
        "energy_residual_j",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    assert_eq!(v["engine"], "core");
    assert!(["stable", "unstable", "undecided"].contains(&v["outcome"].as_str().unwrap()));
    assert_eq!(v["max_primary_stroke_m"].as_array().unwrap().len(), 4);
    assert_eq!(
        v["max_secondary_compression_m"][0]
            .as_array()
            .unwrap()
            .len(),
        2
    );
    // Present only when it has a value: never a null.
    assert_eq!(
        v.get("overturn_velocity_m_s").is_some(),
        v["outcome"] == "unstable"
    );
    assert_eq!(
        v.get("decision_time_s").is_some(),
        v["outcome"] != "undecided"
    );
    assert!(!String::from_utf8_lossy(&out.stdout).contains("null"));
    let touched = v["first_contact_s"].as_object().unwrap();
    assert!(touched.keys().all(|k| k.starts_with("leg")) && !touched.is_empty());
}

#[test]
fn resolved_scenario_reloads_to_the_same_result() {
    let d = temp("resolved");
    let out = touchdown(&[
        "run",
        "scenarios/table-i-1-2-1-vv7.toml",
        "--format",
        "json",
        "--out",
        d.to_str().unwrap(),
    ]);
    assert!(out.status.success());
    let resolved = d.join("scenario.resolved.toml");
    let text = std::fs::read_to_string(&resolved).unwrap();
    assert!(
        !text.contains("extends"),
        "the resolved scenario stands alone"
    );
    assert!(
        text.contains("release = \"gear_force\"") && text.contains("stop_restitution = 0.5"),
        "defaults are written out"
    );
    let again = touchdown(&["run", resolved.to_str().unwrap(), "--format", "json"]);
    assert!(
        again.status.success(),
        "{}",
        String::from_utf8_lossy(&again.stderr)
    );
    // The same landing (the same resolved scenario's hash), but for the file's path.
    let without_path = |bytes: &[u8]| {
        let mut v: serde_json::Value = serde_json::from_slice(bytes).unwrap();
        v["scenario"]["path"] = serde_json::Value::Null;
        v
    };
    assert_eq!(without_path(&out.stdout), without_path(&again.stdout));
}

#[test]
fn text_summary_reads_well() {
    let out = touchdown(&["run", "scenarios/flat-drop.toml"]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    for needle in [
        "outcome:  STABLE",
        "primary",
        "minimum stability distance",
        "balance residual",
        " ft",
    ] {
        assert!(text.contains(needle), "missing {needle:?} in\n{text}");
    }
}

/// The summary gives each maximum stroke's time (a touchdown peak told from a late rock), and an
/// undecided landing says why and how to decide it, in the file's time unit.
#[test]
fn the_summary_times_its_maxima_and_an_undecided_landing_says_what_to_do() {
    let out = touchdown(&[
        "run",
        "scenarios/flat-drop.toml",
        "--set",
        "integrator.t_end=0.01",
        "--format",
        "json",
    ]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let times = v["max_primary_stroke_time_s"].as_array().unwrap();
    assert_eq!(times.len(), 4);
    for t in times {
        let t = t.as_f64().unwrap();
        assert!(t > 0.0 && t <= 0.01, "{t}");
    }
    let text = touchdown(&[
        "run",
        "scenarios/flat-drop.toml",
        "--set",
        "integrator.t_end=0.01",
    ]);
    let text = String::from_utf8(text.stdout).unwrap();
    assert!(text.contains("time of each maximum stroke, s"), "{text}");
    assert!(
        text.contains("UNDECIDED (no stability decision before the end time, 0.0100 s")
            && text.contains("a longer run may decide it: --set integrator.t_end=0.02"),
        "{text}"
    );
}

/// `run --out DIR --report` writes one self-contained page of the landing, the same bytes
/// twice: its outcome and why, each strut against its capacity with the time, the energy
/// ledger, the histories; no script, nothing undefined.
#[test]
fn report_writes_one_page_per_landing() {
    let pages: Vec<String> = ["report-1", "report-2"]
        .iter()
        .map(|name| {
            let dir = temp(name);
            let out = touchdown(&[
                "run",
                "scenarios/fig-25-26.toml",
                "--set",
                "integrator.t_end=0.3",
                "--out",
                dir.to_str().unwrap(),
                "--report",
            ]);
            assert!(
                out.status.success(),
                "{}",
                String::from_utf8_lossy(&out.stderr)
            );
            std::fs::read_to_string(dir.join("report.html")).unwrap()
        })
        .collect();
    assert_eq!(pages[0], pages[1]);
    let page = &pages[0];
    for needle in [
        "Stable, with 2 struts past their capacity",
        "leg1.secondary_4_1.compression",
        "Strokes against capacity",
        "Energy since touchdown",
        "Primary strokes, m",
        "Pitch rate, rad/s",
        "<polyline",
    ] {
        assert!(page.contains(needle), "missing {needle:?}");
    }
    assert!(!page.contains("<script") && !page.contains("NaN"));
    assert!(!page.contains(",inf") && !page.contains("inf,") && !page.contains("\"inf"));
    let o = touchdown(&["run", "scenarios/flat-drop.toml", "--report"]);
    assert_eq!(o.status.code(), Some(2), "--report needs --out");
}

/// `run`'s energy lines say which side of the balance each is on: the initial kinetic energy
/// plus the residual equals the sum of the lines marked + (or −), as printed (to their rounding),
/// on a sliding landing and on one with thrust (a mechanism that puts energy in).
#[test]
fn the_energy_lines_of_run_add_up_with_their_signs() {
    for scenario in [
        "scenarios/level-sliding.toml",
        "scenarios/thrust-tailoff.toml",
    ] {
        let o = touchdown(&["run", scenario]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let text = String::from_utf8_lossy(&o.stdout);
        let section = text.split("energy since touchdown, J").nth(1).unwrap();
        let value = |line: &str| -> f64 {
            line.split_whitespace()
                .find_map(|w| w.parse::<f64>().ok())
                .unwrap_or_else(|| panic!("no number in {line:?}"))
        };
        let (mut sum, mut initial, mut residual, mut signed) = (0.0, None, None, 0);
        for line in section.lines().skip(1).take_while(|l| l.starts_with("  ")) {
            let body = line.trim_start();
            if let Some(rest) = body.strip_prefix("+ ") {
                sum += value(rest);
                signed += 1;
            } else if let Some(rest) = body.strip_prefix("− ") {
                sum -= value(rest);
                signed += 1;
            } else if body.starts_with("initial kinetic energy") {
                initial = Some(value(body));
            } else if body.starts_with("balance residual") {
                residual = Some(value(body));
            }
        }
        assert_eq!(signed, 10, "{section}");
        let (initial, residual) = (initial.unwrap(), residual.unwrap());
        assert!(
            (initial + residual - sum).abs() < 1e-3,
            "{scenario}: {initial} + {residual} vs {sum}\n{section}"
        );
    }
}

/// `history.csv` carries every account of the energy balance, so the balance rebuilds from
/// each row on every engine: the residual column equals the sum of the accounts (each with its
/// sign) minus the initial kinetic energy, to the 10 digits the file writes.
#[test]
fn the_energy_balance_rebuilds_from_every_row_of_the_history() {
    for (scenario, engine) in [
        ("scenarios/level-sliding.toml", "core"),
        ("scenarios/thrust-tailoff.toml", "core"),
        ("scenarios/level-sliding.toml", "rapier"),
        ("scenarios/level-sliding.toml", "mujoco"),
    ] {
        let dir = temp(&format!("history-{engine}"));
        let o = touchdown(&[
            "run",
            scenario,
            "--engine",
            engine,
            "--out",
            dir.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let mut csv = csv::Reader::from_path(dir.join("history.csv")).unwrap();
        let header = csv.headers().unwrap().clone();
        let col = |name: &str| {
            header
                .iter()
                .position(|h| h == name)
                .unwrap_or_else(|| panic!("{engine}: no column {name}"))
        };
        let plus: Vec<usize> = [
            "kinetic_j",
            "potential_change_j",
            "footpad_j",
            "honeycomb_stored_j",
            "honeycomb_dissipated_j",
            "viscous_j",
            "bearing_friction_j",
            "sliding_friction_j",
            "mechanisms_j",
        ]
        .map(col)
        .to_vec();
        let (events, initial, residual) = (
            col("contact_events_j"),
            col("kinetic_initial_j"),
            col("residual_j"),
        );
        let mut rows = 0;
        for record in csv.records() {
            let r = record.unwrap();
            let v = |i: usize| r[i].parse::<f64>().unwrap();
            let sum: f64 = plus.iter().map(|&i| v(i)).sum::<f64>() - v(events) - v(initial);
            assert!(
                (sum - v(residual)).abs() <= 1e-7 * v(initial).abs().max(1.0),
                "{engine} {scenario} at t = {}: {sum} vs {}",
                &r[0],
                v(residual)
            );
            rows += 1;
        }
        assert!(rows > 10, "{engine}: {rows} rows");
        let _ = std::fs::remove_dir_all(&dir);
    }
}

/// `run --out DIR --every N` keeps every Nth step's row of history.csv and the last, on every
/// engine (each writes the same file, thinned in one place).
#[test]
fn every_thins_the_history_on_every_engine() {
    let rows = |dir: &Path| -> Vec<String> {
        std::fs::read_to_string(dir.join("history.csv"))
            .unwrap()
            .lines()
            .map(String::from)
            .collect()
    };
    for engine in ["core", "mujoco"] {
        let (all, thinned) = (
            temp(&format!("every-all-{engine}")),
            temp(&format!("every-7-{engine}")),
        );
        for (dir, every) in [(&all, "1"), (&thinned, "7")] {
            let o = touchdown(&[
                "run",
                "scenarios/flat-drop.toml",
                "--engine",
                engine,
                "--out",
                dir.to_str().unwrap(),
                "--every",
                every,
            ]);
            assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        }
        let (all, thinned) = (rows(&all), rows(&thinned));
        assert!(all.len() > 100, "{engine}: {} rows", all.len());
        let mut expected: Vec<String> = std::iter::once(all[0].clone())
            .chain(all[1..].iter().step_by(7).cloned())
            .collect();
        if (all.len() - 2) % 7 != 0 {
            expected.push(all.last().unwrap().clone());
        }
        assert_eq!(thinned, expected, "{engine}");
    }
    // Without --every, rows no closer than the core's largest step: every step on the core,
    // every ⌊dt_max / step⌋-th on rapier (0.2 ms / 20 µs on the 1/6-scale model).
    for (engine, n) in [("core", 1), ("rapier", 10)] {
        let (all, default) = (
            temp(&format!("every-1-{engine}")),
            temp(&format!("every-default-{engine}")),
        );
        for (dir, every) in [(&all, Some("1")), (&default, None)] {
            let mut args = vec![
                "run",
                "scenarios/flat-drop.toml",
                "--engine",
                engine,
                "--set",
                "integrator.t_end=0.1",
                "--out",
                dir.to_str().unwrap(),
            ];
            args.extend(every.iter().flat_map(|e| ["--every", e]));
            let o = touchdown(&args);
            assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        }
        let (all, default) = (rows(&all), rows(&default));
        let mut expected: Vec<String> = std::iter::once(all[0].clone())
            .chain(all[1..].iter().step_by(n).cloned())
            .collect();
        if (all.len() - 2) % n != 0 {
            expected.push(all.last().unwrap().clone());
        }
        assert_eq!(
            default, expected,
            "{engine}: the default thinning is every {n}"
        );
    }
    let o = touchdown(&["run", "scenarios/flat-drop.toml", "--every", "2"]);
    assert_eq!(o.status.code(), Some(2), "--every needs --out");
    let o = touchdown(&[
        "run",
        "scenarios/flat-drop.toml",
        "--out",
        "x",
        "--every",
        "0",
    ]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("--every: expected at least 1"));
}
