//! Overrides of a field: taken as an extending file would write them, refused by name.

use super::{extending, field_error, scenario, scratch};
use crate::Scenario;
use toml::Value;

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
