//! The loader against hostile but fair input: tables only as tables, the units of the file that
//! wrote a number, special files, clear messages, plausibility ranges and warnings. Each test
//! names what it guards; the catalogue in tests/data/malformed/ holds one file per case too.

use crate::check::{RANGE_CHECKED, SI_FACTORS};
use crate::dimension::{Dimension, Powers};
use crate::error::ScenarioError;
use crate::ranges::{self, RANGES};
use crate::Scenario;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use toml::Value;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn scenario(name: &str) -> PathBuf {
    root().join("scenarios").join(name)
}

/// The bundled landings (`scenarios/*.toml`, `scenarios/robustness/*.toml`).
fn bundled() -> Vec<PathBuf> {
    let mut files = Vec::new();
    for dir in ["scenarios", "scenarios/robustness"] {
        for entry in std::fs::read_dir(root().join(dir)).unwrap() {
            let path = entry.unwrap().path();
            if path.is_file() && path.extension().is_some_and(|x| x == "toml") {
                files.push(path);
            }
        }
    }
    files.sort();
    assert!(files.len() > 10, "{files:?}");
    files
}

/// A scratch folder of its own, removed with everything in it when the value is dropped.
fn scratch(name: &str) -> tempfile::TempDir {
    tempfile::Builder::new()
        .prefix(&format!("touchdown-scenario-tests-{name}-"))
        .tempdir()
        .unwrap()
}

/// Writes `dir/file` extending `base` with the TOML `extra`; returns its path.
fn extending(dir: &Path, file: &str, base: &Path, extra: &str) -> PathBuf {
    let path = dir.join(file);
    std::fs::write(
        &path,
        format!(
            "schema_version = 1\nextends = {:?}\nname = \"test\"\n{extra}",
            base.display().to_string()
        ),
    )
    .unwrap();
    path
}

/// The field and message of a field error (panics on any other result).
fn field_error(result: Result<Scenario, ScenarioError>) -> (String, String, String) {
    match result {
        Err(ScenarioError::Field {
            file,
            field,
            message,
        }) => (file, field, message),
        Err(e) => panic!("expected a field error, got {e}"),
        Ok(_) => panic!("expected a field error, the scenario loaded"),
    }
}

/// One step of a path into a TOML value.
#[derive(Debug, Clone)]
enum Seg {
    Key(String),
    Index(usize),
}

/// The path as the loader writes it: `gear.legs[0].b2[1]`.
fn display(path: &[Seg]) -> String {
    let mut out = String::new();
    for seg in path {
        match seg {
            Seg::Key(k) if out.is_empty() => out.push_str(k),
            Seg::Key(k) => {
                out.push('.');
                out.push_str(k);
            }
            Seg::Index(i) => out.push_str(&format!("[{i}]")),
        }
    }
    out
}

/// Every node below the root (tables, arrays and leaves) with its path.
fn nodes(value: &Value) -> Vec<(Vec<Seg>, Value)> {
    fn walk(v: &Value, path: &mut Vec<Seg>, out: &mut Vec<(Vec<Seg>, Value)>) {
        if !path.is_empty() {
            out.push((path.clone(), v.clone()));
        }
        match v {
            Value::Table(t) => {
                for (k, child) in t {
                    path.push(Seg::Key(k.clone()));
                    walk(child, path, out);
                    path.pop();
                }
            }
            Value::Array(a) => {
                for (i, child) in a.iter().enumerate() {
                    path.push(Seg::Index(i));
                    walk(child, path, out);
                    path.pop();
                }
            }
            _ => {}
        }
    }
    let mut out = Vec::new();
    walk(value, &mut Vec::new(), &mut out);
    out
}

/// `value` with the node at `path` replaced by `new`.
fn replaced(value: &Value, path: &[Seg], new: Value) -> Value {
    let mut out = value.clone();
    let mut node = &mut out;
    for seg in path {
        node = match seg {
            Seg::Key(k) => node.get_mut(k.as_str()).unwrap(),
            Seg::Index(i) => node.get_mut(*i).unwrap(),
        };
    }
    *node = new;
    out
}

/// The resolved scenario (every default written out) as a TOML value.
fn resolved(path: &Path) -> Value {
    let sc = Scenario::load(path).unwrap_or_else(|e| panic!("{e}"));
    toml::from_str(&sc.to_toml()).unwrap()
}

fn load_value(value: &Value) -> Result<Scenario, ScenarioError> {
    Scenario::from_toml("mutant", &toml::to_string(value).unwrap())
}

/// Longest run of digits in `text`: a number printed in short notation has at most 6.
fn longest_digit_run(text: &str) -> usize {
    text.split(|c: char| !c.is_ascii_digit())
        .map(str::len)
        .max()
        .unwrap_or(0)
}

// 1. A table is only ever a table.

#[test]
fn every_table_of_every_bundled_scenario_refuses_an_array_in_its_place() {
    let mut tried = 0;
    for path in bundled() {
        let value = resolved(&path);
        for (at, node) in nodes(&value) {
            if !node.is_table() {
                continue;
            }
            let field = display(&at);
            for stand_in in [
                Value::Array(vec![Value::Float(1.0)]),
                Value::Array(vec![]),
                Value::Float(1.0),
                Value::String("x".into()),
            ] {
                let (_, got, message) = field_error(load_value(&replaced(&value, &at, stand_in)));
                assert_eq!(got, field, "{}: {message}", path.display());
                assert!(
                    message.starts_with("expected a table, found "),
                    "{field}: {message}"
                );
                tried += 1;
            }
        }
    }
    assert!(tried > 500, "{tried}");
}

#[test]
fn the_array_readings_serde_would_accept_are_refused() {
    let folder = scratch("arrays");
    let dir = folder.path();
    let flat = scenario("flat-drop.toml");
    for (extra, field) in [
        ("stability = [1.0]\n", "stability"),
        ("[engines]\nrapier = [1.0]\n", "engines.rapier"),
        ("[vehicle]\ninertia = [1.0, 1.0, 1.0]\n", "vehicle.inertia"),
        ("footpad = [0.013, 0.257]\n", "footpad"),
        (
            "units = [\"ft\", \"slug\", \"lbf\", \"deg\", \"s\"]\n",
            "units",
        ),
        ("[gear]\nparametric = [1.0]\n", "gear.parametric"),
    ] {
        let file = extending(dir, "a.toml", &flat, extra);
        let (owner, got, message) = field_error(Scenario::load(&file));
        assert_eq!(got, field, "{message}");
        assert!(owner.ends_with("a.toml"), "{owner}");
        assert_eq!(message, "expected a table, found an array");
    }
}

// 2. Numbers are read in the units of the file that wrote them.

#[test]
fn an_extending_file_may_not_change_the_units_it_inherits() {
    let folder = scratch("units");
    let dir = folder.path();
    let vehicle = scenario("vehicles/lm-1-6.toml");
    let flat = scenario("flat-drop.toml");
    let file = extending(dir, "metres.toml", &flat, "[units]\nlength = \"m\"\n");
    let (owner, field, message) = field_error(Scenario::load(&file));
    assert!(owner.ends_with("metres.toml"), "{owner}");
    assert_eq!(field, "units.length");
    assert!(
        message.contains("\"m\" here but \"ft\" in") && message.contains("lm-1-6.toml"),
        "{message}"
    );
    // Two levels down: the file that set the inherited unit is named.
    let middle = extending(dir, "middle.toml", &flat, "");
    let file = extending(dir, "kilograms.toml", &middle, "[units]\nmass = \"kg\"\n");
    let (_, field, message) = field_error(Scenario::load(&file));
    assert_eq!(field, "units.mass");
    assert!(
        message.contains(&vehicle.display().to_string()),
        "{message}"
    );
    // Restating the same units is not a change.
    let same = "[units]\nlength = \"ft\"\nmass = \"slug\"\nforce = \"lbf\"\nangle = \"deg\"\ntime = \"s\"\n";
    let file = extending(dir, "same.toml", &flat, same);
    Scenario::load(&file).unwrap();
}

// 3. Special files are refused before they are read.

fn not_a_file(result: Result<Scenario, ScenarioError>, path: &Path, kind: &str) {
    match result {
        Err(ScenarioError::NotAFile { file, kind: k }) => {
            assert_eq!(file, path.display().to_string());
            assert!(k.contains(kind), "{k}");
        }
        Err(e) => panic!("expected NotAFile, got {e}"),
        Ok(_) => panic!("{} loaded", path.display()),
    }
}

#[test]
fn a_directory_or_a_device_is_refused_naming_it() {
    let folder = scratch("special");
    let dir = folder.path();
    not_a_file(Scenario::load(dir), dir, "directory");
    #[cfg(unix)]
    not_a_file(
        Scenario::load("/dev/null"),
        Path::new("/dev/null"),
        "character device",
    );
    let file = extending(dir, "dir.toml", dir, "");
    let (_, field, message) = field_error(Scenario::load(&file));
    assert_eq!(field, "extends");
    assert!(
        message.contains(&dir.display().to_string()) && message.contains("a directory"),
        "{message}"
    );
}

/// Runs `f` on a thread and fails if it has not returned within a minute (a FIFO read blocks).
fn within_a_minute<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(f());
    });
    rx.recv_timeout(std::time::Duration::from_secs(60))
        .expect("the loader blocked on a FIFO")
}

#[cfg(unix)]
#[test]
fn a_fifo_is_refused_without_blocking() {
    let folder = scratch("fifo");
    let dir = folder.path();
    let fifo = dir.join("pipe.toml");
    match std::process::Command::new("mkfifo").arg(&fifo).status() {
        Ok(s) if s.success() => {}
        other => {
            eprintln!("skipped: mkfifo is not available ({other:?})");
            return;
        }
    }
    let f = fifo.clone();
    not_a_file(within_a_minute(move || Scenario::load(f)), &fifo, "FIFO");
    let file = extending(dir, "pipe-base.toml", &fifo, "");
    let (owner, field, message) = field_error(within_a_minute(move || Scenario::load(file)));
    assert!(owner.ends_with("pipe-base.toml"), "{owner}");
    assert_eq!(field, "extends");
    assert!(
        message.contains(&fifo.display().to_string()) && message.contains("FIFO"),
        "{message}"
    );
    let f = fifo.clone();
    assert!(within_a_minute(move || Scenario::value_at(f, "vehicle.mass")).is_err());
}

// 4. Clear messages.

#[test]
fn empty_input_says_it_is_empty() {
    for text in ["", "\n\n", "# nothing but a comment\n"] {
        match Scenario::from_toml("empty.toml", text) {
            Err(e @ ScenarioError::Empty { .. }) => {
                let m = e.to_string();
                assert!(
                    m.starts_with("empty.toml: empty file: expected a scenario (schema_version"),
                    "{m}"
                );
            }
            other => panic!("{other:?}"),
        }
    }
    let folder = scratch("empty");
    let dir = folder.path();
    let empty = dir.join("empty.toml");
    std::fs::write(&empty, "").unwrap();
    match Scenario::load(&empty) {
        Err(ScenarioError::Empty { file }) => assert_eq!(file, empty.display().to_string()),
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_syntax_error_on_a_huge_line_quotes_it_short() {
    let text = format!("schema_version = 1\nname = [{}\n", "[".repeat(100_000));
    match Scenario::from_toml("huge.toml", &text) {
        Err(e @ ScenarioError::Syntax { .. }) => {
            let m = e.to_string();
            assert!(m.lines().all(|l| l.chars().count() <= 220), "{}", m.len());
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_vehicle_loaded_as_a_landing_says_so() {
    let vehicle = scenario("vehicles/lm-1-6.toml");
    match Scenario::load(&vehicle) {
        Err(e @ ScenarioError::NotALanding { .. }) => {
            let m = e.to_string();
            assert!(m.starts_with(&vehicle.display().to_string()), "{m}");
            assert!(
                m.contains("a vehicle description") && m.contains("extended by a landing"),
                "{m}"
            );
            assert!(!m.contains("missing field"), "{m}");
        }
        other => panic!("{other:?}"),
    }
}

/// Spikes (`surface.spike_depth`) hold a footpad as an obstacle does, up to their engagement
/// depth: one restraint a footpad, none on soil nor beside a curb, no negative depth; each
/// refusal names the spike field of the leg.
#[test]
fn spikes_are_one_restraint_a_footpad_on_a_rigid_surface() {
    let folder = scratch("spikes");
    let dir = folder.path();
    let spiked = extending(
        dir,
        "spiked.toml",
        &scenario("fig-25-26.toml"),
        "[surface]\nobstacle = 0.0\nspike_depth = 0.02\n",
    );
    let pad = Scenario::load(&spiked).unwrap().surface.pads[2];
    assert!(pad.locked() && pad.obstacle <= 0.0);
    assert!((pad.hold_height() - 0.02 * crate::units::FOOT).abs() < 1e-15);
    for (extra, field, says) in [
        // The file that adds the wall over a spiked base is told about its own line.
        (
            "[surface]\nobstacle = 1.0\n",
            "surface.obstacle[0]",
            "give one of the two (surface.spike_depth[0] is set in ",
        ),
        ("[surface]\nobstacle = 0.0\nspike_depth = -0.01\n", "surface.spike_depth[0]", "≥ 0"),
        (
            "[surface]\nspike_depth = [0.0, 0.0, 0.02, 0.0]\nobstacle = 0.0\n[[surface.curbs]]\nleg = 3\ndistance = 0.3\nangle = 0.0\nfriction = 0.0\n",
            "surface.spike_depth[2]",
            "curbs apply to sliding footpads",
        ),
    ] {
        let file = extending(dir, "refused.toml", &scenario("fig-25-26.toml"), extra);
        let (owner, f, message) = field_error(Scenario::load(&file));
        assert_eq!(owner, file.display().to_string(), "{extra}: {message}");
        assert_eq!(f, field, "{extra}: {message}");
        assert!(message.contains(says), "{extra}: {message}");
    }
    let soil = extending(
        dir,
        "soil.toml",
        &scenario("soil-drop.toml"),
        "[surface]\nspike_depth = 0.01\n",
    );
    let (_, f, message) = field_error(Scenario::load(&soil));
    assert_eq!(f, "surface.spike_depth[0]", "{message}");
    // A landing with neither slides.
    let free = extending(
        dir,
        "free.toml",
        &scenario("fig-25-26.toml"),
        "[surface]\nspike_depth = 0.0\n",
    );
    assert!(Scenario::load(&free)
        .unwrap()
        .surface
        .pads
        .iter()
        .all(|p| !p.locked()));
}

#[test]
fn a_missing_field_is_named_by_its_own_path() {
    let value = resolved(&scenario("flat-drop.toml"));
    let mut t = value.as_table().unwrap().clone();
    t.remove("name");
    let (_, field, message) = field_error(load_value(&Value::Table(t)));
    assert_eq!(field, "name");
    assert_eq!(message, "missing field `name`");
    let mut t = value.as_table().unwrap().clone();
    t["touchdown"].as_table_mut().unwrap().remove("attitude");
    let (_, field, _) = field_error(load_value(&Value::Table(t)));
    assert_eq!(field, "touchdown.attitude");
}

#[test]
fn integers_and_floats_out_of_place_print_short() {
    let value = resolved(&scenario("curb-slide.toml"));
    for (at, new) in [
        ("schema_version", Value::Float(1e300)),
        ("schema_version", Value::Integer(i64::MAX)),
        ("name", Value::Float(-1e-300)),
        ("surface.curbs[0].leg", Value::Float(5e-324)),
        ("surface.curbs[0].leg", Value::Integer(i64::MIN)),
        ("stability.terminate_on_decision", Value::Float(1e300)),
        ("surface.kind", Value::Float(1e300)),
    ] {
        let path: Vec<Seg> = at
            .split('.')
            .flat_map(|k| match k.split_once('[') {
                Some((key, i)) => vec![
                    Seg::Key(key.into()),
                    Seg::Index(i.trim_end_matches(']').parse().unwrap()),
                ],
                None => vec![Seg::Key(k.into())],
            })
            .collect();
        let (_, field, message) = field_error(load_value(&replaced(&value, &path, new)));
        assert_eq!(field, at, "{message}");
        assert!(longest_digit_run(&message) <= 6, "{at}: {message}");
    }
}

// 5. Plausibility ranges.

/// The hostile numbers of the mutation runs: each must be refused, unless the field's range
/// holds 0 (then a tiny value is a legal 0) or the value is accepted with a warning.
const HOSTILE: [f64; 6] = [1e300, -1e300, 1e-300, -1e-300, 5e-324, f64::MAX];

#[test]
fn hostile_numbers_in_every_field_are_refused_with_short_messages() {
    let mut refused = 0;
    for path in bundled() {
        let value = resolved(&path);
        for (at, node) in nodes(&value) {
            let field = display(&at);
            if !(node.is_float() || node.is_integer()) {
                continue;
            }
            for x in HOSTILE {
                let result = load_value(&replaced(&value, &at, Value::Float(x)));
                match result {
                    Err(e) => {
                        let m = e.to_string();
                        assert!(longest_digit_run(&m) <= 6, "{field} = {x:e}: {m}");
                        refused += 1;
                    }
                    Ok(sc) => {
                        let range = ranges::lookup(&field)
                            .unwrap_or_else(|| panic!("{field} = {x:e} accepted, no range"));
                        let holds_zero = range.lower.value() <= 0.0 && range.upper.value() >= 0.0;
                        let warned = sc.warnings().iter().any(|w| w.field == field);
                        assert!(
                            x.abs() < 1e-200 && (holds_zero || warned),
                            "{}: {field} = {x:e} was accepted",
                            path.display()
                        );
                    }
                }
            }
        }
    }
    assert!(refused > 3000, "{refused}");
}

#[test]
fn ranges_are_checked_in_si_whatever_the_file_units() {
    let folder = scratch("si");
    let dir = folder.path();
    let flat = scenario("flat-drop.toml");
    // 1e7 kg is 685 218 slug.
    let heavy = extending(dir, "heavy.toml", &flat, "[vehicle]\nmass = 6.9e5\n");
    let (_, field, message) = field_error(Scenario::load(&heavy));
    assert_eq!(field, "vehicle.mass");
    assert!(
        message.contains("6.9e+05 in the file's units (1.00698e+07 kg)")
            && message.contains("[0.001, 1e+07] kg"),
        "{message}"
    );
    let ok = extending(dir, "ok.toml", &flat, "[vehicle]\nmass = 6.8e5\n");
    let sc = Scenario::load(&ok).unwrap();
    // Legal but heavier than the usual range: a warning, naming the file and the field.
    let w = &sc.warnings()[0];
    assert_eq!(w.field, "vehicle.mass");
    assert!(w.file.ends_with("ok.toml"));
    assert!(
        w.to_string()
            .contains("outside the usual range [1, 1e+06] kg"),
        "{w}"
    );
}

#[test]
fn unusual_values_are_accepted_with_a_warning() {
    let folder = scratch("warnings");
    let dir = folder.path();
    let flat = scenario("flat-drop.toml");
    let file = extending(
        dir,
        "fast.toml",
        &flat,
        "[touchdown]\nvertical_velocity = -150.0\n",
    );
    let sc = Scenario::load(&file).unwrap();
    assert_eq!(sc.warnings().len(), 1, "{:?}", sc.warnings());
    let w = &sc.warnings()[0];
    assert_eq!(w.field, "touchdown.vertical_velocity");
    assert!(
        w.to_string()
            .contains("-150 in the file's units (-45.72 m/s)"),
        "{w}"
    );
    // A changed setting re-checks its table's warnings.
    let sc = Scenario::load(&flat).unwrap();
    let sc = sc.with_rapier(|r| r.timestep = Some(1e-300)).unwrap();
    assert_eq!(sc.warnings().len(), 1);
    assert_eq!(sc.warnings()[0].field, "engines.rapier.timestep");
    let sc = sc.with_rapier(|r| r.timestep = Some(2e-5)).unwrap();
    assert!(sc.warnings().is_empty());
    assert!(sc.with_integrator(|i| i.t_end = 1e300).is_err());
}

#[test]
fn bundled_scenarios_load_without_warnings() {
    for path in bundled() {
        let sc = Scenario::load(&path).unwrap();
        assert!(
            sc.warnings().is_empty(),
            "{}: {:?}",
            path.display(),
            sc.warnings()
        );
    }
}

#[test]
fn legs_closer_than_the_least_separation_are_refused() {
    let value = resolved(&scenario("flat-drop.toml"));
    let at = vec![
        Seg::Key("gear".into()),
        Seg::Key("parametric".into()),
        Seg::Key("leg_azimuths".into()),
    ];
    let azimuths = |a: [f64; 4]| Value::Array(a.iter().map(|x| Value::Float(*x)).collect());
    for (a, field) in [
        (
            [0.0, 1e-300, 180.0, 270.0],
            "gear.parametric.leg_azimuths[1]",
        ),
        (
            [0.0, 90.0, 180.0, -1e-300],
            "gear.parametric.leg_azimuths[0]",
        ),
        ([0.0, 90.0, 90.5, 270.0], "gear.parametric.leg_azimuths[2]"),
        ([0.0, 90.0, 180.0, 359.5], "gear.parametric.leg_azimuths[0]"),
    ] {
        let (_, got, message) = field_error(load_value(&replaced(&value, &at, azimuths(a))));
        assert_eq!(got, field, "{a:?}: {message}");
        assert!(message.contains("at least 1 deg apart"), "{message}");
    }
    // Not increasing but counter-clockwise once around (wrapping through 0) is a gear.
    load_value(&replaced(&value, &at, azimuths([270.0, 0.0, 90.0, 180.0]))).unwrap();
    let many = Value::Array((0..40).map(|i| Value::Float(i as f64 * 9.0)).collect());
    let (_, field, message) = field_error(load_value(&replaced(&value, &at, many)));
    assert_eq!(field, "gear.parametric.leg_azimuths");
    assert!(message.contains("at most 32 legs"), "{message}");
}

/// A similar vehicle (`[similarity]`) written into `dir`: the figure 25-26 landing at full scale
/// on the Moon. Returns its path.
fn similar_vehicle(dir: &Path) -> PathBuf {
    fig_25_26_with(
        dir,
        "similar",
        "[similarity]\nlength = 6.0\nmass = 216.0\ntime = 6.0\n",
    )
}

/// The figure 25-26 landing with the TOML `tables` added, written into `dir` as `name`.toml.
/// Returns its path.
fn fig_25_26_with(dir: &Path, name: &str, tables: &str) -> PathBuf {
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(
        &path,
        format!(
            "schema_version = 1\nextends = {:?}\nname = {name:?}\n{tables}",
            root()
                .join("scenarios/fig-25-26.toml")
                .display()
                .to_string()
        ),
    )
    .unwrap();
    path
}

/// Every number of every bundled scenario (and of explicit cantilever legs) has a range and is
/// checked against it on load; every range is of a field some scenario has.
#[test]
fn every_numeric_field_has_a_range_checked_on_load() {
    let mut files = bundled();
    // Explicit cantilever legs (with l21): the catalogue's standalone file, its third leg fixed.
    let folder = scratch("coverage");
    let dir = folder.path();
    let text = std::fs::read_to_string(
        root().join("tests/data/malformed/strut-cannot-reach-footpad.toml"),
    )
    .unwrap()
    .replace("l21 = 1.6", "l21 = 0.9375");
    let explicit = dir.join("explicit.toml");
    std::fs::write(&explicit, text).unwrap();
    files.push(explicit);
    let similar = similar_vehicle(dir);
    files.push(similar);
    // The strides scheme's own settings.
    files.push(fig_25_26_with(
        dir,
        "strides",
        "[integrator]\nscheme = \"strides\"\nstride = 8.0\nmode_step = 1.0\n",
    ));
    // A landing's own comparison tolerances.
    files.push(fig_25_26_with(
        dir,
        "comparison",
        "[comparison]\nprimary_stroke = 0.1\nsecondary_stroke = 0.1\npeak_pitch_rate = 0.1\npeak_pitch_rate_time = 0.1\npitch_rate_history_rms_difference = 0.1\npitch_rate_history_largest_difference = 0.1\npeak_vertical_acceleration = 0.1\nmin_stability_distance = 0.1\noverturn_velocity = 0.1\npast_capacity = 0.1\nenergy = 0.1\n",
    ));
    let mut leaves = BTreeSet::new();
    RANGE_CHECKED.with(|c| c.borrow_mut().clear());
    for path in &files {
        let value = resolved(path);
        for (at, node) in nodes(&value) {
            if node.is_float() {
                leaves.insert(ranges::normalize(&display(&at)));
            }
        }
    }
    let checked = RANGE_CHECKED.with(|c| c.borrow().clone());
    let unranged: Vec<_> = leaves
        .iter()
        .filter(|f| ranges::lookup(f).is_none())
        .collect();
    assert!(
        unranged.is_empty(),
        "numeric fields without a range: {unranged:?}"
    );
    let unchecked: Vec<_> = leaves.difference(&checked).collect();
    assert!(
        unchecked.is_empty(),
        "fields not range-checked on load: {unchecked:?}"
    );
    let unused: Vec<_> = RANGES
        .iter()
        .filter(|r| !leaves.iter().any(|f| ranges::lookup(f) == Some(*r)))
        .map(|r| r.field)
        .collect();
    assert!(unused.is_empty(), "ranges of no field: {unused:?}");
}

/// The Ranges table's units are the dimensions the loader reads: every number of every bundled
/// scenario (and of a similar vehicle) is brought to SI by its dimension's factor in the file's
/// units, the one a campaign's unit is checked against.
#[test]
fn every_fields_dimension_is_the_one_it_is_read_with() {
    let folder = scratch("dimensions");
    let dir = folder.path();
    let similar = similar_vehicle(dir);
    let mut files = bundled();
    files.push(similar);
    let mut checked = 0;
    for path in &files {
        SI_FACTORS.with(|c| c.borrow_mut().clear());
        let scenario = Scenario::load(path).unwrap();
        let units = scenario.units();
        for (field, factor) in SI_FACTORS.with(|c| c.borrow().clone()) {
            let dimension = scenario
                .dimension_of(&field)
                .unwrap_or_else(|| panic!("{}: `{field}` has no row", path.display()))
                .unwrap_or_else(|e| panic!("{}: `{field}`: {e}", path.display()));
            let expected = dimension.si_factor(&units);
            assert!(
                (factor - expected).abs() <= 1e-12 * expected.abs(),
                "{}: `{field}` is read with {factor}, its dimension ({}) gives {expected}",
                path.display(),
                dimension.words()
            );
            checked += 1;
        }
    }
    assert!(checked > 1000, "{checked} numbers checked");
}

/// docs/scenario-format.md's fields table gives each field the dimension its range has.
#[test]
fn the_fields_table_states_each_fields_dimension() {
    let doc = std::fs::read_to_string(root().join("docs/scenario-format.md")).unwrap();
    let table = doc
        .split("## Fields")
        .nth(1)
        .and_then(|t| t.split("\n## ").next())
        .unwrap();
    let mut checked = 0;
    for line in table.lines().filter(|l| l.starts_with("| `")) {
        let cells: Vec<&str> = line.split(" | ").collect();
        let (names, words) = (cells[0].trim_start_matches("| "), cells[1].trim());
        if words == "as above" || words.contains(',') || names.contains("...") {
            continue;
        }
        // "—": a pure number (or no number at all: such fields have no range).
        let words = if words.starts_with('—') { "1" } else { words };
        for name in names.split(", ") {
            let field = name.trim_matches('`');
            let Some(row) = ranges::lookup(field) else {
                continue;
            };
            let powers = Powers {
                gamma: Some(1.0),
                index: Some(2.0),
            };
            let table = Dimension::parse(row.unit, powers).unwrap();
            let stated = Dimension::parse(words, powers)
                .unwrap_or_else(|e| panic!("`{field}`: its dimension {words:?}: {e}"));
            assert_eq!(stated, table, "`{field}`: {words:?} against {:?}", row.unit);
            checked += 1;
        }
    }
    assert!(checked >= 40, "{checked} fields checked");
}

/// docs/scenario-format.md lists every range as the code has it.
#[test]
fn the_format_page_documents_every_range() {
    let doc = std::fs::read_to_string(root().join("docs/scenario-format.md")).unwrap();
    let mut missing = Vec::new();
    for r in RANGES {
        let usual = r.usual_interval().unwrap_or_else(|| "—".into());
        let row = format!(
            "| `{}` | {} | {} | {} |",
            r.field,
            r.interval(),
            usual,
            r.reason
        );
        if !doc.lines().any(|l| l == row) {
            missing.push(row);
        }
    }
    assert!(
        missing.is_empty(),
        "rows missing from docs/scenario-format.md (\"Ranges\"):\n{}",
        missing.join("\n")
    );
    assert!(doc.contains(&format!(
        "at least {} deg apart",
        crate::units::short(ranges::MIN_LEG_SEPARATION_DEG)
    )));
}

/// An override of a field no file of the chain writes adds it, as a file extending the
/// scenario would (the resolved scenarios are the same); a field the format does not have is
/// refused by name.
#[test]
fn an_override_adds_a_field_no_file_writes_as_an_extending_file_would() {
    let base = crate::ScenarioBase::load(scenario("flat-drop.toml")).unwrap();
    let overridden = base
        .with(&[
            (
                "touchdown.body_rates",
                Value::try_from([0.5, 0.0, 0.0]).unwrap(),
            ),
            ("stability.terminate_on_decision", Value::Boolean(false)),
            ("name", Value::String("test".into())),
        ])
        .unwrap();
    let folder = scratch("override-adds");
    let dir = folder.path();
    let file = extending(
        dir,
        "adds.toml",
        &scenario("flat-drop.toml"),
        "[touchdown]\nbody_rates = [0.5, 0.0, 0.0]\n\n[stability]\nterminate_on_decision = false\n",
    );
    let extended = Scenario::load(&file).unwrap();
    assert_eq!(overridden.sha256(), extended.sha256());
    let (_, field, message) = field_error(base.with(&[("touchdown.body_rate", Value::Float(1.0))]));
    assert_eq!(field, "touchdown.body_rate");
    assert!(message.contains("unknown field"), "{message}");
}

/// An override takes any value the field's type takes, as an extending file would write it: an
/// array replaced whole, a per-leg array where the file has one number (and back), a table
/// merged key by key; the resolved scenario is the extending file's. What decides how the file
/// is read (`extends`, `units`, `schema_version`) is refused by name, and so is a value of
/// another kind.
#[test]
fn an_override_takes_arrays_tables_and_per_leg_values_as_an_extending_file_would() {
    let base = crate::ScenarioBase::load(scenario("flat-drop.toml")).unwrap();
    let table: toml::Table =
        toml::from_str("stroke_out_rate = 700000.0\nonset_rate = 9000").unwrap();
    let overridden = base
        .with(&[
            (
                "touchdown.horizontal_velocity",
                Value::try_from([0.0, 1.0]).unwrap(),
            ),
            (
                "surface.hole",
                Value::try_from([0.1, 0.0, 0.0, 0.0]).unwrap(),
            ),
            ("secondary_strut.tension", Value::Table(table)),
            ("name", Value::String("test".into())),
        ])
        .unwrap();
    let folder = scratch("override-arrays");
    let dir = folder.path();
    let file = extending(
        dir,
        "arrays.toml",
        &scenario("flat-drop.toml"),
        "[touchdown]\nhorizontal_velocity = [0.0, 1.0]\n\n[surface]\nhole = [0.1, 0.0, 0.0, 0.0]\n\n[secondary_strut.tension]\nstroke_out_rate = 700000.0\nonset_rate = 9000\n",
    );
    assert_eq!(overridden.sha256(), Scenario::load(&file).unwrap().sha256());
    assert_eq!(overridden.surface.pads[0].hole, 0.1 * crate::units::FOOT);
    // And back: one number for the per-leg array of fig-25-26.
    let fig = crate::ScenarioBase::load(scenario("fig-25-26.toml")).unwrap();
    let level = fig.with(&[("surface.hole", Value::Float(0.0))]).unwrap();
    assert!(level.surface.pads.iter().all(|p| p.hole == 0.0));
    for (field, value, says) in [
        (
            "extends",
            Value::String("stroke-out.toml".into()),
            "merged when the file is read",
        ),
        (
            "units.length",
            Value::String("m".into()),
            "every number of the file",
        ),
        ("schema_version", Value::Integer(2), "schema version"),
        (
            "surface.kind",
            Value::Float(3.0),
            "the field holds a string",
        ),
        (
            "touchdown.vertical_velocity",
            Value::String("fast".into()),
            "holds a number",
        ),
    ] {
        let (_, got, message) = field_error(base.with(&[(field, value)]));
        assert_eq!(got, field);
        assert!(message.contains(says), "{field}: {message}");
    }
    // Paths that are not field paths: refused by what is wrong with them, never nested (a
    // 60,000-part path used to overflow the stack).
    let deep = vec!["a"; 60_000].join(".");
    for (field, says) in [
        (deep.as_str(), "60000 parts"),
        ("touchdown..vertical_velocity", "empty key"),
        ("surface.hole[x]", "whole number in brackets"),
        ("surface.hole[1", "whole number in brackets"),
    ] {
        let (_, got, message) = field_error(base.with(&[(field, Value::Float(1.0))]));
        assert_eq!(got, field);
        assert!(message.contains(says), "{message}");
    }
}

/// A lander file no body could be is refused naming the field, or landed with a warning where a
/// test may mean it.
#[test]
fn a_lander_no_body_could_be_is_refused_or_warned_of() {
    // Principal moments past the triangle inequality: no distribution of mass has them.
    let flat = scenario("flat-drop.toml");
    let base = Scenario::load(&flat).unwrap();
    let j = base.vehicle.inertia;
    let past = (j[(0, 0)] + j[(2, 2)]) * 1.01 / base.file.read_units().inertia();
    let (_, field, message) =
        field_error(Scenario::load_with(&flat, &[("vehicle.inertia.yy", past)]));
    assert_eq!(field, "vehicle.inertia");
    assert!(message.contains("triangle inequality"), "{message}");
    // A flat plate's moments are on the limit, and it loads.
    let plate = (j[(0, 0)] + j[(2, 2)]) / base.file.read_units().inertia();
    assert!(Scenario::load_with(&flat, &[("vehicle.inertia.yy", plate)]).is_ok());
    // A footpad above its primary trunnion.
    let tripod = scenario("tripod-drop.toml");
    let (_, field, message) =
        field_error(Scenario::load_with(&tripod, &[("gear.legs[1].bp[2]", 0.5)]));
    assert_eq!(field, "gear.legs[1]");
    assert!(message.contains("below its primary trunnion"), "{message}");
    // An upward touchdown velocity, and crush loads that would not hold the landed weight:
    // legal, each with a warning naming its field.
    let up = Scenario::load_with(&flat, &[("touchdown.vertical_velocity", 1.0)]).unwrap();
    let fields: Vec<&str> = up.warnings().iter().map(|w| w.field.as_str()).collect();
    assert_eq!(fields, ["touchdown.vertical_velocity"]);
    let weak = Scenario::load_with(
        &flat,
        &[("primary_strut.compression.stages[0].crush_load", 10.0)],
    )
    .unwrap();
    let fields: Vec<&str> = weak.warnings().iter().map(|w| w.field.as_str()).collect();
    assert_eq!(fields, ["primary_strut.compression.stages[0].crush_load"]);
    assert!(
        weak.warnings()[0].message.contains("weight"),
        "{:?}",
        weak.warnings()
    );
}

/// A file past the size limit is refused with both sizes in whole bytes, never in floating
/// notation.
#[test]
fn a_file_past_the_size_limit_is_refused_in_whole_bytes() {
    let folder = scratch("huge");
    let path = folder.path().join("huge.toml");
    let file = std::fs::File::create(&path).unwrap();
    file.set_len(17_000_000).unwrap();
    let message = Scenario::load(&path).unwrap_err().to_string();
    assert!(
        message.contains("the file is 17000000 bytes")
            && message.contains("at most 16777216 bytes (16 MiB)")
            && !message.contains("e+"),
        "{message}"
    );
}

/// The tripod takes the parametric form without Z1 (its point 1 is the footpad): the 1/6-scale
/// model's fig. 23 parameters give the points `tripod-drop.toml` lists, to the six decimals it
/// writes them with; Z1 on a tripod, or none on a cantilever, is refused by name.
#[test]
fn the_tripod_takes_the_parametric_form_without_point_1() {
    let explicit = scenario("tripod-drop.toml");
    let text = std::fs::read_to_string(&explicit).unwrap();
    let start = text.find("[[gear.legs]]").unwrap();
    let end = text.find("[primary_strut]").unwrap();
    let parametric = "[gear.parametric]\nr1 = 1.639\nr2 = 1.562\nr3 = 2.221\nz2 = 0.806\nz3 = 1.351\nzc = 0.952\nbeta = 19.72\nbeta_convention = \"trunnion_azimuth\"\nleg_azimuths = [0.0, 90.0, 180.0, 270.0]\n\n";
    let folder = scratch("tripod-parametric");
    let path = folder.path().join("tripod.toml");
    std::fs::write(
        &path,
        format!("{}{parametric}{}", &text[..start], &text[end..]),
    )
    .unwrap();
    let (a, b) = (
        Scenario::load(&explicit).unwrap(),
        Scenario::load(&path).unwrap(),
    );
    let foot = 0.3048;
    for (x, y) in a.legs.iter().zip(&b.legs) {
        for (p, q) in [(x.b2, y.b2), (x.b3, y.b3), (x.b4, y.b4), (x.bp, y.bp)] {
            assert!((p - q).norm() < 1e-6 * foot, "{p} against {q}");
        }
        // Point 1 is the footpad: L21 is the whole primary.
        assert!((y.l21 - y.l2p).abs() < 1e-12 && (y.b1() - y.bp).norm() < 1e-12);
    }
    let (_, field, message) =
        field_error(Scenario::load_with(&path, &[("gear.parametric.z1", 0.49)]));
    assert_eq!(field, "gear.parametric.z1");
    assert!(message.contains("leaves Z1 out"), "{message}");
    let cantilever = folder.path().join("cantilever.toml");
    std::fs::write(
        &cantilever,
        std::fs::read_to_string(&path)
            .unwrap()
            .replace("arrangement = \"tripod\"", "arrangement = \"cantilever\""),
    )
    .unwrap();
    let (_, field, message) = field_error(Scenario::load(&cantilever));
    assert_eq!(field, "gear.parametric.z1");
    assert!(message.contains("expected Z1"), "{message}");
}
