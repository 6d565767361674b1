//! The MuJoCo export (issue 5): every scenario in `scenarios/` exports to MJCF that the pinned
//! MuJoCo (`mujoco-core` in the project's venv) loads, and the model's keyframe is the shared
//! touchdown state. A missing venv fails with the command that creates it.

use std::process::Command;
use touchdown_scenario::{frames, Scenario};
use touchdown_tests::{python, root, scenario};

#[test]
fn every_scenario_exports_to_a_model_mujoco_loads_in_the_touchdown_state() {
    let dir = std::env::temp_dir().join(format!("touchdown-mjcf-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut cases = Vec::new();
    for entry in std::fs::read_dir(scenario("")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let sc = Scenario::load(&path).unwrap();
            let xml = touchdown_mujoco::export(&sc);
            let file = dir.join(path.file_stem().unwrap()).with_extension("xml");
            std::fs::write(&file, xml).unwrap();
            cases.push((file, sc));
        }
    }
    assert!(cases.len() >= 10, "{} scenarios", cases.len());
    let out = Command::new(python())
        .arg(root().join("python/mujoco/check_model.py"))
        .args(cases.iter().map(|(f, _)| f))
        .output()
        .expect("the venv's python runs");
    assert!(
        out.status.success(),
        "check_model.py failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let reports: Vec<serde_json::Value> = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(reports.len(), cases.len());
    for ((file, sc), r) in cases.iter().zip(&reports) {
        let name = file.display();
        let n = sc.legs.len();
        // A free joint (7 + 6) and per gear two trunnion hinges and the stroke.
        assert_eq!(r["nq"], 7 + 3 * n, "{name}");
        assert_eq!(r["nv"], 6 + 3 * n, "{name}");
        let actuators: Vec<&str> = r["actuators"]
            .as_array()
            .unwrap()
            .iter()
            .map(|a| a.as_str().unwrap())
            .collect();
        let expected: Vec<String> = (1..=n)
            .flat_map(|i| ["primary", "plateau", "s31", "s41"].map(|a| format!("leg{i}_{a}")))
            .collect();
        assert_eq!(actuators, expected, "{name}: stable actuator names");
        // The secondary tendons start at the struts' lengths L31, L41.
        let lengths = r["tendon_lengths_m"].as_array().unwrap();
        for (i, leg) in sc.legs.iter().enumerate() {
            for (j, l0) in [leg.l31, leg.l41].into_iter().enumerate() {
                let l = lengths[2 * i + j].as_f64().unwrap();
                assert!(
                    (l - l0).abs() < 1e-9,
                    "{name}: leg {} tendon {j}: {l} vs {l0}",
                    i + 1
                );
            }
        }
        // The first footpad is on its plane (its sphere's centre one radius above the plane,
        // BP on it), touching; the others are above theirs.
        let init = frames::initial_state(sc);
        let heights = r["footpad_heights_m"].as_array().unwrap();
        let k = init.first_leg;
        let z = heights[k].as_f64().unwrap();
        assert!(
            (z - sc.surface.pads[k].plane()).abs() < 1e-9,
            "{name}: first footpad at {z} m"
        );
        assert!(r["contacts"].as_u64().unwrap() >= 1, "{name}: no contact");
        // Only what the scene needs: a frictionless, unlocked footpad has a frictionless
        // contact.
        for (i, pad) in sc.surface.pads.iter().enumerate() {
            let want = if pad.locked() || pad.friction > 0.0 {
                3
            } else {
                1
            };
            assert_eq!(r["footpad_condim"][i], want, "{name}: leg {} condim", i + 1);
        }
        assert_eq!(r["timestep_s"], sc.mujoco.timestep, "{name}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_export_is_deterministic_and_names_its_scenario() {
    let sc = Scenario::load(scenario("fig-25-26.toml")).unwrap();
    let a = touchdown_mujoco::export(&sc);
    let b = touchdown_mujoco::export(&Scenario::load(scenario("fig-25-26.toml")).unwrap());
    assert_eq!(a, b);
    let hash = touchdown_mujoco::mjcf::scenario_hash(&sc);
    assert_eq!(hash.len(), 64);
    assert!(a.contains(&hash) && a.contains(touchdown_mujoco::mjcf::GENERATOR));
    let other = Scenario::load(scenario("table-i-2-2-vv8.toml")).unwrap();
    assert_ne!(touchdown_mujoco::mjcf::scenario_hash(&other), hash);
}
