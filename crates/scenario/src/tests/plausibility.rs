//! Plausibility ranges: hostile numbers refused, ranges in SI, unusual values warned of.

use super::{
    bundled, display, extending, field_error, load_value, longest_digit_run, nodes, replaced,
    resolved, scenario, scratch, Seg,
};
use crate::ranges;
use crate::Scenario;
use toml::Value;

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
