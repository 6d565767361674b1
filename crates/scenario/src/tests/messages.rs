//! Clear messages: empty and huge input, a vehicle read as a landing, restraints, field paths.

use super::{
    extending, field_error, load_value, longest_digit_run, replaced, resolved, scenario, scratch,
    Seg,
};
use crate::error::ScenarioError;
use crate::Scenario;
use toml::Value;

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
