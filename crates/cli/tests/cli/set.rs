//! `--set FIELD=VALUE`: a value changed as an extending file would, and bad settings told.

use super::{extending, touchdown};

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
