//! `touchdown view` and `compare --view`: the trajectory file and its page, the same bytes twice.

use super::{extending, root, temp, touchdown};

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
