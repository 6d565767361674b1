//! The `touchdown` command as a user runs it.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .unwrap()
}

fn touchdown(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_touchdown"))
        .args(args)
        .current_dir(root())
        .output()
        .expect("the touchdown binary runs")
}

/// A path in a folder of its own that is removed, with everything in it, when the value goes
/// out of scope: no test leaves files behind.
struct Scratch {
    _folder: tempfile::TempDir,
    path: PathBuf,
}

impl std::ops::Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.path
    }
}

impl AsRef<Path> for Scratch {
    fn as_ref(&self) -> &Path {
        &self.path
    }
}

impl AsRef<std::ffi::OsStr> for Scratch {
    fn as_ref(&self) -> &std::ffi::OsStr {
        self.path.as_os_str()
    }
}

/// A folder path `name` that does not exist yet (the command under test may create it).
fn temp(name: &str) -> Scratch {
    let folder = tempfile::Builder::new()
        .prefix("touchdown-cli-")
        .tempdir()
        .unwrap();
    let path = folder.path().join(name);
    Scratch {
        _folder: folder,
        path,
    }
}

/// Writes `dir/file`, a scenario named `name` that extends the bundled `base` (a path under
/// scenarios/) with the TOML `extra`; returns its path.
fn extending(dir: &str, file: &str, base: &str, name: &str, extra: &str) -> Scratch {
    let d = temp(dir);
    std::fs::create_dir_all(&*d).unwrap();
    let f = d.join(file);
    let base = root().join("scenarios").join(base);
    std::fs::write(
        &f,
        format!(
            "schema_version = 1\nextends = {:?}\nname = {name:?}\n{extra}",
            base.display().to_string()
        ),
    )
    .unwrap();
    Scratch {
        _folder: d._folder,
        path: f,
    }
}

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

/// `touchdown run --engine mujoco` with `python` as the interpreter.
fn run_mujoco_with(python: &Path) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_touchdown"))
        .args(["run", "scenarios/flat-drop.toml", "--engine", "mujoco"])
        .env("TOUCHDOWN_PYTHON", python)
        .current_dir(root())
        .output()
        .expect("the touchdown binary runs")
}

#[test]
fn mujoco_without_the_python_environment_fails_with_the_setup_command() {
    let out = run_mujoco_with(Path::new("/nonexistent/.venv/bin/python"));
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("not set up") && err.contains("scripts/setup-python"),
        "{err}"
    );
}

#[test]
fn mujoco_without_the_mujoco_package_fails_with_the_setup_command() {
    // An interpreter that cannot see any installed package (python3 -S: no site-packages).
    let d = temp("no-mujoco");
    std::fs::create_dir_all(&d).unwrap();
    let python = d.join("python");
    std::fs::write(&python, "#!/bin/sh\nexec python3 -S \"$@\"\n").unwrap();
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(&python, std::fs::Permissions::from_mode(0o755)).unwrap();
    let out = run_mujoco_with(&python);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("cannot be imported") && err.contains("scripts/setup-python"),
        "{err}"
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

/// `--set FIELD VALUE` (a space for the `=`) is named for what it is, not met with clap's advice
/// to write `-- -3`.
#[test]
fn a_set_split_in_two_is_told_how_to_join_it() {
    let out = touchdown(&[
        "run",
        "scenarios/flat-drop.toml",
        "--set",
        "touchdown.vertical_velocity",
        "-3",
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("--set touchdown.vertical_velocity -3: the field and its value are one argument joined by '=': --set touchdown.vertical_velocity=-3")
            && !err.contains("-- -3"),
        "{err}"
    );
}

/// `touchdown new` drafts a vehicle and a landing from a handful of numbers, reviews them, and a
/// first landing runs from them; it never writes over a file, and a number that makes no
/// vehicle is named by its flag.
#[test]
fn new_drafts_a_vehicle_a_first_landing_runs_from() {
    let dir = temp("new");
    let args = |out: &str, mass: &str| -> Vec<String> {
        [
            "new",
            "--out",
            out,
            "--name",
            "Team tripod",
            "--units",
            "si",
            "--arrangement",
            "tripod",
            "--mass",
            mass,
            "--gravity",
            "1.62",
            "--inertia",
            "300,300,380",
            "--footprint-radius",
            "1.6",
            "--centre-of-mass-height",
            "1.1",
            "--crush-load",
            "4000",
            "--stroke",
            "0.35",
            "--vertical-velocity",
            "-2.5",
            "--horizontal-velocity",
            "0.5",
        ]
        .map(String::from)
        .to_vec()
    };
    let run = |args: &[String]| touchdown(&args.iter().map(String::as_str).collect::<Vec<_>>());
    let out = run(&args(dir.to_str().unwrap(), "650"));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        text.contains("static tip-over angle") && text.contains("no findings"),
        "{text}"
    );
    let landing = dir.join("landing.toml");
    let ran = touchdown(&["run", landing.to_str().unwrap(), "--format", "json"]);
    assert!(
        ran.status.success(),
        "{}",
        String::from_utf8_lossy(&ran.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&ran.stdout).unwrap();
    assert_eq!(v["outcome"], "stable");
    assert!(v["past_capacity"].as_array().unwrap().is_empty());
    // Past the capacity it still lands: the drafted step resolves a footpad on a bottomed
    // stop; four times coarser, the energy guard stops it and names the setting to change.
    let hard = touchdown(&[
        "run",
        landing.to_str().unwrap(),
        "--set",
        "touchdown.vertical_velocity=-7.0",
    ]);
    let text = String::from_utf8_lossy(&hard.stdout);
    assert!(
        hard.status.success(),
        "{}",
        String::from_utf8_lossy(&hard.stderr)
    );
    assert!(text.contains("PAST THEIR CAPACITY"), "{text}");
    let coarse = touchdown(&[
        "run",
        landing.to_str().unwrap(),
        "--set",
        "touchdown.vertical_velocity=-5.0",
        "--set",
        "integrator.dt_max=2.5e-4",
    ]);
    let err = String::from_utf8_lossy(&coarse.stderr);
    assert!(
        err.contains("energy balance") && err.contains("try --set integrator.dt_max=6.25e-05"),
        "{err}"
    );
    // Never over a file.
    let again = run(&args(dir.to_str().unwrap(), "650"));
    assert_eq!(again.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&again.stderr)
        .contains("exists: touchdown new never writes over a file"));
    // A number that makes no vehicle, by its flag; nothing written.
    let other = dir.join("other");
    let bad = run(&args(other.to_str().unwrap(), "-3"));
    assert_eq!(
        String::from_utf8_lossy(&bad.stderr).trim(),
        "error: --mass: expected a positive number, got -3"
    );
    assert!(!other.exists());
    // A finding (a crush load typed in kN): the files are written, and the exit says so.
    let mut weak = args(dir.join("weak").to_str().unwrap(), "650");
    let at = weak.iter().position(|a| a == "--crush-load").unwrap();
    weak[at + 1] = "4".into();
    let out = run(&weak);
    assert_eq!(out.status.code(), Some(3));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("next: the findings above first"), "{text}");
}

/// A `--set` value with a unit after it is told that the file's units are implied.
#[test]
fn a_set_value_with_a_unit_is_told_to_drop_it() {
    for (value, number) in [("-3 m/s", "-3"), ("5deg", "5")] {
        let out = touchdown(&[
            "run",
            "scenarios/flat-drop.toml",
            "--set",
            &format!("touchdown.vertical_velocity={value}"),
        ]);
        assert_eq!(out.status.code(), Some(2));
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains(&format!(
                "a value is in the scenario file's own units, written as the number alone: touchdown.vertical_velocity={number}"
            )),
            "{err}"
        );
    }
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

/// `touchdown check` reviews a vehicle and its landing before it lands: exit 0 with no finding,
/// 3 with one, each naming the file that set the value; `run` prints the same as warnings.
#[test]
fn check_reviews_a_landing_before_it_runs() {
    let out = touchdown(&["check", "scenarios/robotic-lander-slope.toml"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{text}");
    for needle in [
        "gear crush load",
        "stroke energy",
        "static tip-over angle",
        "no findings",
    ] {
        assert!(text.contains(needle), "missing {needle:?} in\n{text}");
    }
    let f = extending(
        "check",
        "steep.toml",
        "flat-drop.toml",
        "steep",
        "[surface]\nslope = 70.0\n",
    );
    let out = touchdown(&["check", f.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(3));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains(&format!(
            "{}: field `surface.slope`: the slope, 70.00 deg, is at or past the static tip-over angle, 58.78 deg",
            f.display()
        )),
        "{text}"
    );
    let out = touchdown(&[
        "run",
        "scenarios/flat-drop.toml",
        "--set",
        "touchdown.vertical_velocity=-40.0",
        "--set",
        "integrator.t_end=0.02",
    ]);
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains(
            "warning: overrides: field `touchdown.vertical_velocity`: the touchdown energy"
        ),
        "{err}"
    );
}

#[test]
fn bad_input_fails_with_the_file_and_field() {
    let f = extending(
        "bad",
        "bad.toml",
        "flat-drop.toml",
        "bad",
        "[vehicle]\nmass = -2.0\n",
    );
    let out = touchdown(&["run", f.to_str().unwrap()]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("bad.toml") && err.contains("vehicle.mass") && err.contains("positive"),
        "{err}"
    );
    assert!(out.stdout.is_empty(), "nothing is written on failure");
    // A missing file: its path and the cause, once.
    let out = touchdown(&["run", "scenarios/nope.toml"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(
        err.trim(),
        "error: scenarios/nope.toml: cannot read the scenario file: No such file or directory (os error 2)"
    );
}

#[test]
fn validate_json_carries_every_row_and_the_targets() {
    let out = touchdown(&["validate", "--format", "json", "--report-only"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 8);
    for key in [
        "id",
        "landing",
        "vv_m_s",
        "vh_m_s",
        "strut",
        "experiment_m",
        "analysis_m",
        "ours_m",
        "error_vs_experiment_pct",
        "error_vs_analysis_pct",
        "role",
    ] {
        assert!(rows[0].get(key).is_some(), "row field {key}");
    }
    assert!(v["held_out_ours"]["mean_abs_error_pct"].is_number());
    assert!(v["held_out_report"]["mean_abs_error_pct"].is_number());
    assert!(v["targets"]["held_out_within_10_pct"].is_boolean());
    assert_eq!(v["facts"].as_array().unwrap().len(), 7);
}

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
            "engine,stop_restitution,vv_m_s,direction,stable_at_vh_m_s,unstable_at_vh_m_s,vh_m_s,resolved,undecided,past_capacity_vh_m_s,safe_to_vh_m_s,safe_until"
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
}

#[test]
fn export_mjcf_writes_a_standalone_model() {
    let dir = temp("mjcf");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("flat-drop.xml");
    let out = touchdown(&[
        "export-mjcf",
        "scenarios/flat-drop.toml",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let xml = std::fs::read_to_string(&file).unwrap();
    assert!(
        xml.starts_with("<!-- Touchdown MJCF export"),
        "{}",
        &xml[..80]
    );
    assert!(xml.trim_end().ends_with("</mujoco>"));
    for name in [
        "vehicle",
        "leg4_footpad",
        "leg4_stroke",
        "leg4_s41",
        "touchdown",
    ] {
        assert!(xml.contains(&format!("name=\"{name}\"")), "{name} missing");
    }
}

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

/// A PNG of some substance at `path`.
fn assert_png(path: &Path) {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert!(
        bytes.starts_with(b"\x89PNG\r\n\x1a\n") && bytes.len() > 10_000,
        "{} is not a plot ({} bytes)",
        path.display(),
        bytes.len()
    );
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

/// A failing verdict exits with its own status (3), distinct from an input error (1) and a usage
/// error (2), unless the user asks for the report only.
#[test]
fn a_failing_verdict_exits_3_unless_only_the_report_is_asked_for() {
    // The slow 2-2 landing with the report's massless footpad: the core and rapier part on its
    // secondary strokes (a FAIL).
    let args = [
        "compare",
        "scenarios/table-i-2-2-vv4.toml",
        "--engines",
        "core,rapier",
        "--set",
        "footpad.detached=rigid",
    ];
    let out = touchdown(&args);
    assert_eq!(
        out.status.code(),
        Some(3),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(String::from_utf8_lossy(&out.stdout).contains("core vs rapier: FAIL"));
    let out = touchdown(&[&args[..], &["--report-only"]].concat());
    assert_eq!(out.status.code(), Some(0));
    assert_eq!(
        touchdown(&["compare", "no-such.toml"]).status.code(),
        Some(1)
    );
    assert_eq!(
        touchdown(&["compare", "--no-such-flag"]).status.code(),
        Some(2)
    );
}

/// Output to a closed pipe ends the process quietly, killed by SIGPIPE as other tools are, not
/// with a panic message.
#[cfg(unix)]
#[test]
fn output_to_a_closed_pipe_ends_quietly() {
    use std::io::Read;
    use std::os::unix::process::ExitStatusExt;
    use std::process::Stdio;
    let mut child = Command::new(env!("CARGO_BIN_EXE_touchdown"))
        .args([
            "compare",
            "scenarios/flat-drop.toml",
            "scenarios/flat-drop.toml",
        ])
        .args(["--engines", "core,rapier", "--report-only"])
        .current_dir(root())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = [0u8; 16];
    child
        .stdout
        .as_mut()
        .unwrap()
        .read_exact(&mut first)
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.signal(), Some(libc::SIGPIPE), "{:?}", out.status);
    assert!(
        out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Output to a full disk is an error naming standard output (exit 1), not a panic (exit 101),
/// for every command that writes results on standard output.
#[cfg(unix)]
#[test]
fn output_to_a_full_disk_is_an_error_naming_standard_output() {
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    for args in [
        &["run", "scenarios/flat-drop.toml"][..],
        &["completions", "bash"],
        &[
            "campaign",
            "scenarios/campaigns/small.toml",
            "--format",
            "json",
        ],
        &[
            "boundary",
            "scenarios/table-i-2-2-vv8.toml",
            "--vv=-8:-8:2",
            "--vh-step",
            "8",
            "--vh-max",
            "8",
            "--format",
            "json",
        ],
    ] {
        let out = Command::new(env!("CARGO_BIN_EXE_touchdown"))
            .args(args)
            .current_dir(root())
            .stdout(full.try_clone().unwrap())
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
        assert!(
            err.contains("error: cannot write to standard output: No space left on device"),
            "{args:?}: {err}"
        );
    }
}

/// A time step the engine refuses is blamed on the argument that set it.
#[test]
fn a_refused_timestep_names_the_argument() {
    for t in ["1e-300", "nan"] {
        let out = touchdown(&[
            "run",
            "scenarios/flat-drop.toml",
            "--engine",
            "rapier",
            "--timestep",
            t,
        ]);
        assert_eq!(out.status.code(), Some(1));
        let err = String::from_utf8_lossy(&out.stderr);
        let line = err.lines().find(|l| l.starts_with("error:")).unwrap_or("");
        assert!(line.starts_with("error: --timestep"), "{err}");
    }
}

#[test]
fn a_campaign_streams_json_lines_then_its_statistics_and_draws_its_plots() {
    let dir = temp("campaign");
    let plots = dir.to_path_buf();
    let out = touchdown(&[
        "campaign",
        "scenarios/campaigns/small.toml",
        "--format",
        "json",
        "--threads",
        "2",
        "--out",
        dir.to_str().unwrap(),
        "--plot",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<serde_json::Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 25);
    for (i, l) in lines[..24].iter().enumerate() {
        assert_eq!(l["landing"], i, "in landing order");
        assert!(l["outcome"].is_string() && l["failure"].is_string());
    }
    let stats = &lines[24]["statistics"];
    assert_eq!(stats["landings"], 24);
    let lower = stats["stable"]["lower_bound"].as_f64().unwrap();
    assert!(lower > 0.0 && lower < stats["stable"]["fraction"].as_f64().unwrap());
    assert!(!text.contains("null") && !text.contains("NaN"));
    // The lines on standard output are the file's.
    let file = std::fs::read_to_string(dir.join("landings.jsonl")).unwrap();
    assert!(text.starts_with(&file));
    assert_png(&plots.join("outcomes.png"));
    assert_png(&plots.join("strokes.png"));
    // The text report says what its numbers are.
    let out = touchdown(&["campaign", "scenarios/campaigns/small.toml"]);
    let report = String::from_utf8_lossy(&out.stdout);
    assert!(
        report.contains("P(stable landing) = ") && report.contains("one-sided Clopper-Pearson")
    );
}

/// Long commands draw their progress on a terminal's standard error, with the rate and the
/// time left, and nothing when standard error is not a terminal or with `--quiet`. The terminal
/// is a pseudo-terminal from `script` (util-linux, in every Debian).
#[test]
fn a_campaign_shows_its_progress_on_a_terminal_only() {
    let on_terminal = |extra: &str| {
        let command = format!(
            "{} campaign scenarios/campaigns/small.toml{extra} > /dev/null",
            env!("CARGO_BIN_EXE_touchdown")
        );
        let out = Command::new("script")
            .args(["-qec", &command, "/dev/null"])
            .current_dir(root())
            .output()
            .expect("`script` runs (Debian package bsdutils)");
        assert!(out.status.success(), "{out:?}");
        String::from_utf8_lossy(&out.stdout).replace('\r', "\n")
    };
    let shown = on_terminal("");
    let bar = shown
        .lines()
        .find(|l| l.contains("/24 landings · "))
        .unwrap_or_else(|| panic!("no progress bar in {shown:?}"));
    assert!(bar.ends_with(" left") || bar.contains(" left "), "{bar:?}");
    assert!(!on_terminal(" --quiet").contains("landings"));
    let piped = touchdown(&["campaign", "scenarios/campaigns/small.toml"]);
    assert!(piped.status.success());
    assert!(
        piped.stderr.is_empty(),
        "{:?}",
        String::from_utf8_lossy(&piped.stderr)
    );
}

#[test]
fn campaign_arguments_are_checked_by_name() {
    let expect = |args: &[&str], says: &str| {
        let out = touchdown(args);
        assert!(!out.status.success(), "{args:?} succeeded");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains(says), "{args:?}: {stderr}");
    };
    let small = "scenarios/campaigns/small.toml";
    let cases: [(&[&str], &str); 8] = [
        (&["--shard", "5/4"], "expected K/N with 1 ≤ K ≤ N"),
        (
            &["--engines", "core,core"],
            "scenarios/campaigns/small.toml: field `--engines`: core is named twice",
        ),
        (
            &["--engines", "core,bullet"],
            "invalid value 'bullet' for '--engines",
        ),
        (
            &["--view", "2", "--out", "x"],
            "--view: a campaign on one engine has no disagreements to watch",
        ),
        (
            &["--plot"],
            "the following required arguments were not provided:\n  --out <DIR>",
        ),
        (
            &["--add", "3"],
            "--add: name the finished campaign's folder with --out",
        ),
        (&["--threads", "0"], "--threads: expected at least 1 thread"),
        (&["--format", "yaml"], "invalid value 'yaml' for '--format"),
    ];
    for (extra, says) in cases {
        let args: Vec<&str> = ["campaign", small].iter().chain(extra).copied().collect();
        expect(&args, says);
    }
    expect(
        &["campaign", "scenarios/campaigns/nothing.toml"],
        "scenarios/campaigns/nothing.toml: cannot read the campaign file",
    );
    let empty = temp("merge-empty");
    std::fs::create_dir_all(&empty).unwrap();
    let e = empty.to_str().unwrap();
    expect(
        &["campaign", "estimate", "--paired", e, "--low", e],
        "manifest.json: No such file or directory",
    );
    expect(
        &[
            "campaign",
            "estimate",
            "--paired",
            e,
            "--low",
            e,
            "--cost-ratio=0",
        ],
        "--cost-ratio: expected a positive number, got 0",
    );
    expect(
        &["campaign", "merge", empty.to_str().unwrap(), "--out", "x"],
        "expected a campaign folder written by `touchdown campaign --out`",
    );
}

#[test]
fn a_campaign_of_descent_and_horizontal_speeds_plots_the_engines_boundary() {
    let dir = temp("speeds");
    let plots = dir.join("out");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("speeds.toml");
    std::fs::write(
        &file,
        format!(
            "schema_version = 1\nname = \"speeds\"\nscenario = {:?}\nlandings = 40\nseed = 3\n\n[[dispersion]]\nfield = \"touchdown.vertical_velocity\"\nunit = \"ft/s\"\ndistribution = \"uniform\"\nmin = -12.0\nmax = -4.0\n\n[[dispersion]]\nfield = \"touchdown.horizontal_velocity[1]\"\nunit = \"ft/s\"\ndistribution = \"uniform\"\nmin = 0.0\nmax = 30.0\n",
            root().join("scenarios/table-i-2-2-vv8.toml").display().to_string()
        ),
    )
    .unwrap();
    let out = touchdown(&[
        "campaign",
        file.to_str().unwrap(),
        "--out",
        dir.join("out").to_str().unwrap(),
        "--plot",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let b: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(plots.join("boundary.json")).unwrap())
            .unwrap();
    let points = b["points"].as_array().unwrap();
    // The base configuration overturns within 30 ft/s up to about 8 ft/s of descent (four of
    // the search's descent speeds; docs/python.md has the same landing's boundary): each is a
    // point of the plot.
    assert!(points.len() >= 4, "{b}");
    for p in points {
        let vh = p["applied.touchdown.horizontal_velocity[1]_ft_s"]
            .as_f64()
            .unwrap();
        let vv = p["applied.touchdown.vertical_velocity_ft_s"]
            .as_f64()
            .unwrap();
        assert!(
            (0.0..=30.0).contains(&vh) && (-12.0..=-4.0).contains(&vv),
            "{p}"
        );
    }
    assert_png(&plots.join("outcomes.png"));
}

/// `touchdown calibrate` writes where it is told: one row for two parameters is refused before
/// any landing, and without `--out DIR` or `--update-tracked` nothing is written (a usage
/// error), so the tracked calibrated vehicle changes only when asked.
#[test]
fn calibrate_refuses_what_its_rows_cannot_determine_and_writes_only_where_told() {
    let out = temp("calibrate-one-row");
    let o = touchdown(&["calibrate", "--rows", "3", "--out", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("1 row(s) cannot determine 2 parameters"),
        "{err}"
    );
    assert!(!out.exists(), "nothing is written on refusal");
    let o = touchdown(&["calibrate"]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("--out"), "{err}");
}

/// `--set FIELD=VALUE` changes a value as a file that extends the scenario would, on `run`
/// and `boundary`, and is refused as a file would be: an unknown field names the field
/// (exit 1), a malformed setting is a usage error (exit 2).
#[test]
fn set_changes_a_value_as_an_extending_file_would() {
    let base = "table-i-2-2-vv8.toml";
    let name = "Table I 2-2, Vv = -8.0 ft/s, Vh = 6.0 ft/s";
    let file = extending(
        "set",
        "faster.toml",
        base,
        name,
        "[touchdown]\nvertical_velocity = -10.0\n",
    );
    let scenario = format!("scenarios/{base}");
    let json = |args: &[&str]| -> serde_json::Value {
        let o = touchdown(args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        serde_json::from_slice(&o.stdout).unwrap()
    };
    let set = json(&[
        "run",
        &scenario,
        "--set",
        "touchdown.vertical_velocity=-10.0",
        "--format",
        "json",
    ]);
    let extended = json(&["run", file.to_str().unwrap(), "--format", "json"]);
    let unchanged = json(&["run", &scenario, "--format", "json"]);
    // The same landing (the same resolved scenario): the documents differ in the file and the
    // settings they name.
    assert_eq!(set["scenario"]["sha256"], extended["scenario"]["sha256"]);
    assert_eq!(
        set["settings"]["set"][0]["field"],
        "touchdown.vertical_velocity"
    );
    let landing = |v: &serde_json::Value| {
        let mut v = v.clone();
        v["scenario"] = serde_json::Value::Null;
        v["settings"] = serde_json::Value::Null;
        v
    };
    assert_eq!(landing(&set), landing(&extended));
    assert_ne!(
        set["max_primary_stroke_m"],
        unchanged["max_primary_stroke_m"]
    );
    let boundary = |path: &str, extra: &[&str]| {
        let mut args = vec![
            "boundary",
            path,
            "--vv=-8:-8:1",
            "--vh-step",
            "6",
            "--vh-max",
            "18",
            "--format",
            "json",
        ];
        args.extend_from_slice(extra);
        json(&args)
    };
    let heavier = extending("set", "heavier.toml", base, name, "[vehicle]\nmass = 2.2\n");
    assert_eq!(
        landing(&boundary(&scenario, &["--set", "vehicle.mass=2.2"])),
        landing(&boundary(heavier.to_str().unwrap(), &[]))
    );

    let o = touchdown(&["run", &scenario, "--set", "touchdown.vertical_speed=-10.0"]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("touchdown.vertical_speed") && err.contains("--set"),
        "{err}"
    );
    let o = touchdown(&["run", &scenario, "--set", "vertical_velocity"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("FIELD=VALUE"));
    // A bare word is a string; a value that is not TOML otherwise is a typo, refused with
    // TOML's reason, never taken as a string.
    let named = json(&[
        "run",
        &scenario,
        "--set",
        "name=lander-2.b",
        "--format",
        "json",
    ]);
    assert_eq!(named["scenario_name"], "lander-2.b");
    for (value, reason) in [
        ("name=\"abc", "invalid basic string"),
        ("touchdown.attitude=[1, 2", "unclosed array"),
        ("touchdown.vertical_velocity=", "got \"\""),
        ("name=a b", "got \"a b\""),
    ] {
        let o = touchdown(&["run", &scenario, "--set", value]);
        assert_eq!(o.status.code(), Some(2), "{value}");
        let err = String::from_utf8_lossy(&o.stderr);
        let field = value.split('=').next().unwrap();
        assert!(
            err.contains(&format!("{field}: expected a TOML value")) && err.contains(reason),
            "{value}: {err}"
        );
    }
}

/// `precision` whose reference refinements run past the scenario's budget says which one, how
/// far the ladder got and how to give it more, rather than the engine's stop; `robustness`
/// refuses a case named twice.
#[test]
fn a_reference_past_its_budget_and_a_case_named_twice_are_said_as_such() {
    let o = touchdown(&[
        "precision",
        "scenarios/flat-drop.toml",
        "--engines",
        "core",
        "--set",
        "integrator.max_steps=3000",
        "-q",
    ]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("no converged reference within the run budget: refinement 1")
            && err.contains("--set integrator.max_steps=N (now 3000)"),
        "{err}"
    );
    let o = touchdown(&["robustness", "--cases", "onset-x10,onset-x10"]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("--cases: \"onset-x10\" is named twice"),
        "{err}"
    );
}

/// The command line helps itself: a typo gets clap's suggestion, every help text wraps at 100
/// columns, and the shell completions and manual pages are generated from the same definition.
#[test]
fn typos_get_suggestions_help_wraps_and_completions_and_man_pages_are_generated() {
    let o = touchdown(&["campain"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("'campaign'"));
    let o = touchdown(&["run", "scenarios/flat-drop.toml", "--formt", "json"]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("a similar argument exists: '--format'"));

    let commands = [
        "run",
        "compare",
        "precision",
        "robustness",
        "export-mjcf",
        "validate",
        "calibrate",
        "estimate",
        "sensitivity",
        "campaign",
        "boundary",
        "completions",
        "man",
    ];
    let every = commands.iter().map(|c| vec![*c, "--help"]);
    for c in every.chain([vec!["--help"], vec!["campaign", "merge", "--help"]]) {
        let o = touchdown(&c);
        assert!(o.status.success(), "{c:?}");
        let text = String::from_utf8_lossy(&o.stdout);
        for line in text.lines() {
            assert!(
                line.chars().count() <= 100,
                "{c:?}: a help line of {} columns: {line}",
                line.chars().count()
            );
        }
    }

    let o = touchdown(&["completions", "bash"]);
    assert!(o.status.success());
    let script = String::from_utf8_lossy(&o.stdout);
    assert!(
        script.contains("_touchdown()") && script.contains("campaign") && script.contains("--set")
    );
    let dir = temp("man");
    let o = touchdown(&["man", "--out", dir.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let page = std::fs::read_to_string(dir.join("touchdown.1")).unwrap();
    assert!(page.contains(".TH touchdown 1"), "{page}");
    for c in commands {
        let page = std::fs::read_to_string(dir.join(format!("touchdown-{c}.1"))).unwrap();
        assert!(page.contains(&format!(".TH touchdown-{c} 1")), "{c}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The project's data is found wherever the command runs from: above the executable when the
/// current directory is elsewhere, at `$TOUCHDOWN_HOME` when set; a wrong `$TOUCHDOWN_HOME` or
/// `--root` is an error saying what was expected.
#[test]
fn the_project_is_found_from_any_directory() {
    let elsewhere = std::env::temp_dir();
    let run = |envs: &[(&str, &str)], args: &[&str]| {
        let mut c = Command::new(env!("CARGO_BIN_EXE_touchdown"));
        c.args(args)
            .current_dir(&elsewhere)
            .env_remove("TOUCHDOWN_HOME");
        for (k, v) in envs {
            c.env(k, v);
        }
        c.output().unwrap()
    };
    let o = run(&[], &["validate", "--report-only", "--format", "json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let home = root();
    let o = run(
        &[("TOUCHDOWN_HOME", home.to_str().unwrap())],
        &["sensitivity", "--fraction", "0.1", "--format", "json"],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // Each parameter's value carries the unit of the scenario file it is written in.
    let table: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(table["schema"], "touchdown.sensitivity/1");
    let units: Vec<(&str, &str)> = table["parameters"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            (
                p["parameter"].as_str().unwrap(),
                p["unit"].as_str().unwrap(),
            )
        })
        .collect();
    assert!(units.contains(&("vehicle mass M", "slug")), "{units:?}");
    assert!(
        units.contains(&("primary onset rate", "lbf/ft")),
        "{units:?}"
    );
    assert!(units.iter().all(|(_, u)| !u.is_empty()), "{units:?}");
    let o = run(&[("TOUCHDOWN_HOME", "/nonexistent")], &["validate"]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("$TOUCHDOWN_HOME is /nonexistent") && err.contains("python/mujoco/run.py"),
        "{err}"
    );
    let o = run(&[], &["validate", "--root", elsewhere.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("expected the project's folder"));
}

/// A copied binary (nothing beside it) runs MuJoCo with `$TOUCHDOWN_HOME` alone: the library
/// is found in the project's build folders.
#[test]
fn a_copied_binary_runs_mujoco_with_touchdown_home_alone() {
    let dir = temp("copied-binary");
    std::fs::create_dir_all(&dir).unwrap();
    let copy = dir.join("touchdown");
    std::fs::copy(env!("CARGO_BIN_EXE_touchdown"), &copy).unwrap();
    let o = Command::new(&copy)
        .args([
            "run",
            "scenarios/flat-drop.toml",
            "--engine",
            "mujoco",
            "--format",
            "json",
        ])
        .current_dir(root())
        .env("TOUCHDOWN_HOME", root())
        .env_remove("TOUCHDOWN_MUJOCO_LIBRARY")
        .env_remove("TOUCHDOWN_PYTHON")
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let summary: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(summary["engine"], "mujoco");
    let _ = std::fs::remove_dir_all(&dir);
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

/// `touchdown view` writes the trajectory file and its page, byte for byte the same on a second
/// run (MuJoCo's frames read back from its history included), with every engine's frames;
/// `compare --view` writes the same page; bad arguments name themselves.
#[test]
fn view_writes_the_same_page_twice_and_refuses_bad_arguments() {
    let (a, b) = (temp("view-a"), temp("view-b"));
    for d in [&a, &b] {
        let out = touchdown(&[
            "view",
            "scenarios/fig-25-26.toml",
            "--out",
            d.to_str().unwrap(),
        ]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(text.contains("mujoco: stable (decided at "), "{text}");
    }
    for f in ["fig-25-26.trajectory.json", "fig-25-26.html"] {
        let (x, y) = (
            std::fs::read(a.join(f)).unwrap(),
            std::fs::read(b.join(f)).unwrap(),
        );
        assert!(x.len() > 10_000, "{f} is too small");
        assert!(x == y, "{f} differs between two runs");
    }
    let document: serde_json::Value =
        serde_json::from_slice(&std::fs::read(a.join("fig-25-26.trajectory.json")).unwrap())
            .unwrap();
    let engines = document["engines"].as_array().unwrap();
    let names: Vec<&str> = engines
        .iter()
        .map(|e| e["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["core", "rapier", "mujoco"]);
    for e in engines {
        let frames = e["frames"]["t_s"].as_array().unwrap().len();
        // A thousand frames a second of landing (the steps decimated): the stable landing
        // runs its 1.5 s.
        assert!(
            frames > 1000 && frames < 1600,
            "{}: {frames} frames",
            e["name"]
        );
        assert!(!e["events"].as_array().unwrap().is_empty());
    }
    // The comparison's page of the same landings is the same page.
    let c = temp("view-compare");
    let out = touchdown(&[
        "compare",
        "scenarios/fig-25-26.toml",
        "--report-only",
        "--view",
        c.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        std::fs::read(c.join("fig-25-26.html")).unwrap()
            == std::fs::read(a.join("fig-25-26.html")).unwrap(),
        "compare --view and view write the same page"
    );
    let only_core = extending(
        "view-applicable",
        "core-only.toml",
        "flat-drop.toml",
        "one engine",
        "[engines]\napplicable = [\"core\"]\n",
    );
    for (args, expected) in [
        (
            vec![
                "view",
                "scenarios/flat-drop.toml",
                "--frame-interval",
                "0",
                "--out",
                "x",
            ],
            "--frame-interval: expected a time between frames > 0 s, got 0",
        ),
        (
            vec!["view", "scenarios/flat-drop.toml"],
            "the following required arguments were not provided",
        ),
        (
            vec![
                "view",
                only_core.to_str().unwrap(),
                "--engines",
                "rapier",
                "--out",
                "x",
            ],
            "none of the engines asked for (rapier) applies to",
        ),
        (
            vec![
                "compare",
                "scenarios/flat-drop.toml",
                "--frame-interval",
                "0.01",
            ],
            "--view <DIR>",
        ),
    ] {
        let out = touchdown(&args);
        assert!(!out.status.success(), "{args:?} should fail");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(expected), "{args:?}: {err}");
    }
    assert!(
        !root().join("x").exists(),
        "nothing is written on a refusal"
    );
}

/// Every file under `dir` with its bytes, by path relative to `dir`.
fn files_of(dir: &Path) -> std::collections::BTreeMap<PathBuf, Vec<u8>> {
    let mut files = std::collections::BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else {
                let bytes = std::fs::read(&path).unwrap();
                files.insert(path.strip_prefix(dir).unwrap().to_path_buf(), bytes);
            }
        }
    }
    files
}

/// A copy of the TN D-3117-style campaign with `landings` landings, its base scenario named by
/// its full path, written into `dir`.
fn d3117_with(dir: &Path, landings: u64) -> PathBuf {
    let text = std::fs::read_to_string(root().join("scenarios/campaigns/lm-1-6-d3117.toml"))
        .unwrap()
        .replace("landings = 3000", &format!("landings = {landings}"))
        .replace(
            "scenario = \"../table-i-2-2-vv8.toml\"",
            &format!(
                "scenario = {:?}",
                root().join("scenarios/table-i-2-2-vv8.toml")
            ),
        );
    std::fs::create_dir_all(dir).unwrap();
    let file = dir.join("campaign.toml");
    std::fs::write(&file, text).unwrap();
    file
}

/// A campaign killed (SIGKILL) at any moment and continued with `--resume` into the same
/// folder ends byte for byte as an uninterrupted run, and a killed run never leaves a folder
/// that looks complete. Ten kill points spread over the run (its start-up, its landings, the
/// writing of its Parquet file and statistics) by a fixed low-discrepancy sequence.
#[test]
fn a_campaign_killed_at_any_moment_resumes_to_the_same_bytes() {
    let dir = temp("resume");
    let file = d3117_with(&dir, 120);
    let file = file.to_str().unwrap();
    let whole = dir.join("whole");
    let started = std::time::Instant::now();
    let out = touchdown(&["campaign", file, "--out", whole.to_str().unwrap()]);
    assert!(out.status.success(), "{out:?}");
    let span = started.elapsed();
    let expected = files_of(&whole);
    for k in 0..10 {
        let killed = dir.join(format!("killed-{k}"));
        // Fractions 0.05 to 1.15 of the uninterrupted run's time, in a scrambled order.
        let fraction = 0.05 + 1.1 * ((k as f64 * 0.618_034) % 1.0);
        let mut child = Command::new(env!("CARGO_BIN_EXE_touchdown"))
            .args(["campaign", file, "--out", killed.to_str().unwrap()])
            .current_dir(root())
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(span.mul_f64(fraction));
        let _ = child.kill(); // SIGKILL
        child.wait().unwrap();
        // Either nothing is there yet, or the run had finished: a complete folder.
        if killed.exists() {
            assert_eq!(
                files_of(&killed),
                expected,
                "kill {k} left a folder that differs"
            );
        }
        let out = touchdown(&[
            "campaign",
            file,
            "--out",
            killed.to_str().unwrap(),
            "--resume",
        ]);
        assert!(out.status.success(), "kill {k}: {out:?}");
        assert!(
            files_of(&killed) == expected,
            "kill {k} at {fraction:.2} of the run: the resumed folder differs"
        );
        assert!(!dir.join(format!("killed-{k}.partial")).exists());
    }
}

/// A campaign ended by SIGINT, SIGTERM or SIGHUP says what it keeps and the command that goes
/// on from it, ends with the status a shell gives a process the signal ended, and that command
/// completes the campaign.
#[cfg(unix)]
#[test]
fn a_campaign_ended_by_a_signal_says_what_it_keeps_and_how_to_go_on() {
    let dir = temp("signals");
    let file = d3117_with(&dir, 400);
    for signal in [libc::SIGINT, libc::SIGTERM, libc::SIGHUP] {
        let out = dir.join(format!("out-{signal}"));
        let records = dir.join(format!("out-{signal}.partial/landings.jsonl"));
        let child = Command::new(env!("CARGO_BIN_EXE_touchdown"))
            .args([
                "campaign",
                file.to_str().unwrap(),
                "--out",
                out.to_str().unwrap(),
            ])
            .current_dir(root())
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        let deadline = std::time::Instant::now() + std::time::Duration::from_secs(120);
        while std::fs::metadata(&records).map_or(true, |m| m.len() == 0) {
            assert!(
                std::time::Instant::now() < deadline,
                "no record within 120 s"
            );
            std::thread::sleep(std::time::Duration::from_millis(10));
        }
        // SAFETY: sending a signal to the child this test started and has not waited for.
        unsafe {
            libc::kill(child.id() as libc::pid_t, signal);
        }
        let ended = child.wait_with_output().unwrap();
        assert_eq!(ended.status.code(), Some(128 + signal), "{ended:?}");
        let err = String::from_utf8_lossy(&ended.stderr);
        let kept = format!("kept in {}", records.parent().unwrap().display());
        assert!(
            err.contains("stopped by a signal") && err.contains(&kept),
            "{err}"
        );
        let command = err.lines().last().unwrap().trim();
        assert!(command.ends_with("--resume"), "{err}");
        if signal == libc::SIGINT {
            let args: Vec<String> = shlex::split(command).unwrap();
            assert_eq!(args[0], "touchdown");
            let args: Vec<&str> = args[1..].iter().map(String::as_str).collect();
            let resumed = touchdown(&args);
            assert!(resumed.status.success(), "{resumed:?}");
            assert!(out.join("manifest.json").is_file());
        }
    }
}

/// A campaign that cannot write its records (here a file-size limit, as a full disk would)
/// ends with an error naming the file and a non-zero status, and leaves no folder that looks
/// complete; a single landing's `--out` names the file it could not write.
#[test]
fn a_campaign_that_cannot_write_ends_with_the_path_and_claims_nothing() {
    let dir = temp("full");
    let file = d3117_with(&dir, 120);
    let out_dir = dir.join("out");
    // `ulimit -f` in 512-byte blocks: 64 blocks, 32 kB, about ten records. SIGXFSZ ignored (as
    // `trap` leaves it for the program), so that a write past the limit fails with EFBIG.
    let past_the_limit = |args: String| {
        let command = format!(
            "trap '' XFSZ; ulimit -f 64; exec {} {args}",
            env!("CARGO_BIN_EXE_touchdown")
        );
        let out = Command::new("sh")
            .args(["-c", &command])
            .current_dir(root())
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr).to_string();
        assert_eq!(out.status.code(), Some(1), "{stderr}");
        stderr
    };
    let stderr = past_the_limit(format!(
        "campaign {} --out {}",
        file.display(),
        out_dir.display()
    ));
    // The first file past the limit (a history or the records), in the folder being built.
    assert!(
        stderr.contains("out.partial/") && stderr.contains("File too large"),
        "the error names the file: {stderr}"
    );
    assert!(!out_dir.exists(), "nothing claimed complete");
    // One landing's files past the same limit: the error names the file that failed.
    let run_dir = dir.join("run");
    let stderr = past_the_limit(format!(
        "run scenarios/fig-25-26.toml --out {}",
        run_dir.display()
    ));
    assert!(
        stderr.contains("cannot write") && stderr.contains("run/history.csv"),
        "the error names the file: {stderr}"
    );
}

#[test]
fn a_paired_campaign_draws_where_its_engines_disagree_and_writes_pages_of_the_worst() {
    let dir = temp("paired-plots");
    std::fs::create_dir_all(&*dir).unwrap();
    let file = dir.join("paired.toml");
    let small = std::fs::read_to_string(root().join("scenarios/campaigns/small.toml")).unwrap();
    let t_end = "\n[[dispersion]]\nfield = \"integrator.t_end\"\nunit = \"s\"\ndistribution = \"list\"\nvalues = [0.2]\n\n[[correlation]]";
    let text = small
        .replace(
            "scenario = \"../",
            &format!("scenario = \"{}/scenarios/", root().display()),
        )
        .replace("engine = \"core\"", "engines = [\"core\", \"rapier\"]")
        .replace("landings = 24", "landings = 4")
        .replace("histories = [3]", "histories = []")
        .replacen("\n[[correlation]]", t_end, 1);
    std::fs::write(&file, text).unwrap();
    let out = dir.join("out");
    let run = touchdown(&[
        "campaign",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--plot",
        "--view",
        "2",
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    for f in [
        "disagreement.png",
        "disagreement.csv",
        "differences.png",
        "differences.csv",
    ] {
        assert!(out.join(f).is_file(), "{f} missing");
    }
    // One row a landing, each with both engines' outcomes as the records hold them.
    let csv = std::fs::read_to_string(out.join("disagreement.csv")).unwrap();
    let records = std::fs::read_to_string(out.join("landings.jsonl")).unwrap();
    assert_eq!(csv.lines().count(), 1 + records.lines().count());
    for (row, record) in csv.lines().skip(1).zip(records.lines()) {
        let r: serde_json::Value = serde_json::from_str(record).unwrap();
        let expected = format!(
            ",{},{}",
            r["core.outcome"].as_str().unwrap(),
            r["rapier.outcome"].as_str().unwrap()
        );
        assert!(row.ends_with(&expected), "{row} against {expected}");
    }
    // The pages of the first two landings the pair lists.
    let stats: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("statistics.json")).unwrap())
            .unwrap();
    for w in stats["pairs"][0]["worst"]
        .as_array()
        .unwrap()
        .iter()
        .take(2)
    {
        let page = out.join(format!("views/landing-{}.html", w["landing"]));
        assert!(page.is_file(), "{} missing", page.display());
    }
}
