//! Landers no body could be, and the tripod's parametric gear.

use super::{field_error, scenario, scratch};
use crate::Scenario;

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
