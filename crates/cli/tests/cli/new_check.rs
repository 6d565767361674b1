//! `touchdown new` drafts a vehicle and a landing; `touchdown check` reviews one first.

use super::{extending, temp, touchdown};

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
    // stop. At 8 ms (500 times the drafted step; the sliding footpads, corrected with the
    // vehicle, land it to 2 ms) the energy guard stops it and names the setting to change,
    // and that setting lands it.
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
    let coarse = |dt_max: &str| {
        touchdown(&[
            "run",
            landing.to_str().unwrap(),
            "--set",
            "touchdown.vertical_velocity=-5.0",
            "--set",
            &format!("integrator.dt_max={dt_max}"),
        ])
    };
    let stopped = coarse("8e-3");
    let err = String::from_utf8_lossy(&stopped.stderr);
    assert!(
        err.contains("energy balance") && err.contains("try --set integrator.dt_max=0.002"),
        "{err}"
    );
    let advised = coarse("0.002");
    assert!(
        advised.status.success(),
        "{}",
        String::from_utf8_lossy(&advised.stderr)
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
