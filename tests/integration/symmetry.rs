//! Results that must not depend on the side a landing is seen from, nor on how the legs are
//! numbered: every bundled scenario against its mirror image and against its legs renumbered,
//! and every mirror-symmetric scenario against itself (docs/errata.md, "Decisions at rounding
//! level").

use nalgebra::Vector3;
use touchdown_record::Summary;
use touchdown_scenario::mirror::{matrix, pseudovector};
use touchdown_scenario::model::Leg;
use touchdown_scenario::schema::Scheme;
use touchdown_scenario::Scenario;
use touchdown_tests::{bundled_landings, scenario};

/// Relative agreement required between a landing and its mirror image.
const TOLERANCE: f64 = 1e-9;

/// The bundled scenarios that part from their mirror images at more than rounding level: a
/// mirrored curb's angle 180° − a is rounded, and a landing whose motion is itself unstable to
/// asymmetric disturbances grows that rounding-level asymmetry; it parts from itself at least as
/// far when a 1e-15 rad roll, a few units in the last place, is put in on purpose
/// ([`instability_is_physical`]). Every other landing and its mirror image are exact images
/// (the start is placed by the centre of mass, docs/errata.md, "Eq. (19)"; the legs' loads are
/// summed in an order every turn and mirror of the gear leaves the same, and an eighth turn's
/// sine and cosine are one number, docs/errata.md, "Decisions at rounding level"), however
/// unstable the motion: the 2-2 landings, whose plane of symmetry is a diagonal of the body
/// axes, among them (they parted from their mirror images by up to 2.4e-2 when sin 45° and
/// cos 45° differed by one unit in the last place). The gap at the end time, the widest to the
/// mirror image or the renumbered legs against the 1e-15 rad rolled copy (`cargo test --test
/// integration symmetry::mirror -- --nocapture` prints them):
///
/// - `curb-slide`: 2.0e-8 (the curbs' angles rounded) against 2.2e-7; the footpads strike
///   their curbs again and again as the vehicle rocks.
const UNSTABLE_TO_ASYMMETRY: &[&str] = &["curb-slide.toml"];

/// What a renumbering or mirroring does to the legs: new leg k is old leg `legs[k]`, with its
/// secondaries swapped (3-1 ↔ 4-1) when `swap`.
#[derive(Debug, Clone)]
struct Map {
    legs: Vec<usize>,
    swap: bool,
}

/// The leg map under which a scenario is its own mirror image
/// (`touchdown_scenario::mirror::self_mirror`), secondaries swapped.
fn self_mirror(sc: &Scenario) -> Option<Map> {
    touchdown_scenario::mirror::self_mirror(sc).map(|legs| Map { legs, swap: true })
}

/// The scenario seen in a mirror (x → −x), its legs renumbered counter-clockwise: new leg k is
/// the mirror image of old leg (n − k) mod n, with its secondary trunnions B3 and B4 exchanged
/// (a mirror reverses the sense of rotation). Per-footpad surface values follow their legs; the
/// touchdown attitude becomes (θx, −θy, −θz), the velocity (−vx, vy, vz), the body rates
/// (ωx, −ωy, −ωz); the products of inertia Ixy and Ixz change sign; a curb follows its leg and
/// its normal's angle a from the X axis becomes 180° − a; the RCS's commanded attitude and rates
/// mirror like the touchdown's.
fn mirrored(sc: &Scenario) -> (Scenario, Map) {
    let n = sc.legs.len();
    let map = Map {
        legs: (0..n).map(|k| (n - k) % n).collect(),
        swap: true,
    };
    let m = matrix();
    let mut out = sc.clone();
    out.legs = map
        .legs
        .iter()
        .map(|&i| {
            let l = sc.legs[i];
            Leg {
                b2: m * l.b2,
                b3: m * l.b4,
                b4: m * l.b3,
                bp: m * l.bp,
                l31: l.l41,
                l41: l.l31,
                ..l
            }
        })
        .collect();
    out.surface.pads = map.legs.iter().map(|&i| sc.surface.pads[i]).collect();
    out.vehicle.inertia = m * sc.vehicle.inertia * m;
    let td = &mut out.touchdown;
    td.attitude = Vector3::new(td.attitude.x, -td.attitude.y, -td.attitude.z);
    td.velocity_g = m * td.velocity_g;
    td.body_rates = pseudovector(&td.body_rates);
    if let Some(t) = &mut out.thrust {
        t.nozzle_exit = m * t.nozzle_exit;
    }
    if let Some(s) = &mut out.slosh {
        s.initial_amplitude[0] = -s.initial_amplitude[0];
    }
    let new_index = inverse(&map).legs;
    for c in &mut out.surface.curbs {
        c.leg = new_index[c.leg];
        c.angle = std::f64::consts::PI - c.angle;
    }
    if let Some(r) = &mut out.rcs {
        let a = r.commanded_attitude;
        r.commanded_attitude = Vector3::new(a.x, -a.y, -a.z);
        r.commanded_rates = pseudovector(&r.commanded_rates);
    }
    (out, map)
}

/// The scenario with its legs renumbered one place on (new leg k is old leg k + 1).
fn renumbered(sc: &Scenario) -> (Scenario, Map) {
    let n = sc.legs.len();
    let map = Map {
        legs: (0..n).map(|k| (k + 1) % n).collect(),
        swap: false,
    };
    let mut out = sc.clone();
    out.legs = map.legs.iter().map(|&i| sc.legs[i]).collect();
    out.surface.pads = map.legs.iter().map(|&i| sc.surface.pads[i]).collect();
    (out, map)
}

/// Every per-leg and global figure of a summary, named, in the numbering of `map` applied to
/// `s` (so that a run of the mapped scenario gives the same list).
fn figures(s: &Summary, map: Option<&Map>) -> Vec<(String, f64)> {
    let n = s.max_primary_stroke_m.len();
    let identity = Map {
        legs: (0..n).collect(),
        swap: false,
    };
    let map = map.unwrap_or(&identity);
    let pair = |p: [f64; 2]| if map.swap { [p[1], p[0]] } else { p };
    let mut out = vec![];
    for (k, &i) in map.legs.iter().enumerate() {
        out.push((
            format!("leg {} primary stroke", k + 1),
            s.max_primary_stroke_m[i],
        ));
        let c = pair(s.max_secondary_compression_m[i]);
        let t = pair(s.max_secondary_tension_m[i]);
        for j in 0..2 {
            out.push((format!("leg {} secondary {j} compression", k + 1), c[j]));
            out.push((format!("leg {} secondary {j} tension", k + 1), t[j]));
        }
    }
    let e = &s.energy;
    out.extend([
        ("end time".to_string(), s.t_end_s),
        ("peak pitch rate".to_string(), s.peak_pitch_rate_rad_s),
        (
            "peak pitch rate, negative".to_string(),
            s.min_pitch_rate_rad_s,
        ),
        (
            "peak pitch rate, positive".to_string(),
            s.max_pitch_rate_rad_s,
        ),
        (
            "minimum stability distance".to_string(),
            s.min_stability_distance_m,
        ),
        ("kinetic energy".to_string(), e.kinetic_j),
        ("honeycomb dissipated".to_string(), e.honeycomb_dissipated_j),
        ("honeycomb stored".to_string(), e.honeycomb_stored_j),
        ("bearing friction".to_string(), e.bearing_friction_j),
        ("sliding friction".to_string(), e.sliding_friction_j),
        ("mechanisms".to_string(), e.mechanisms_j),
    ]);
    out
}

/// Each figure of `a` beside the same figure of `b` (`b` in the numbering `map` gives), with
/// their difference as a fraction of its scale (the larger magnitude of that kind of figure in
/// `a`: the largest stroke for strokes, the touchdown kinetic energy for energies,
/// `scales` for the pitch rate and the minimum stability distance).
fn scaled_differences(
    a: &Summary,
    b: &Summary,
    map: &Map,
    scales: Scales,
) -> Vec<(String, f64, f64, f64)> {
    let fa = figures(a, None);
    let fb = figures(b, Some(&inverse(map)));
    let stroke_scale = fa
        .iter()
        .filter(|(n, _)| n.starts_with("leg"))
        .fold(0.0f64, |m, (_, x)| m.max(x.abs()));
    let energy_scale = a.energy.kinetic_initial_j;
    fa.iter()
        .zip(&fb)
        .map(|((name, x), (_, y))| {
            let scale = if name.starts_with("leg") {
                stroke_scale
            } else if name.contains("energy")
                || name.contains("dissipated")
                || name.contains("friction")
                || name.contains("stored")
                || name == "mechanisms"
            {
                energy_scale
            } else if name.starts_with("peak pitch rate") {
                scales.rate_rad_s
            } else if name == "minimum stability distance" {
                // A signed distance that is near zero on a grazing overturn: measured against
                // the lander's size, not against itself.
                scales.length_m
            } else {
                x.abs().max(y.abs())
            };
            let d = (x - y).abs() / scale.max(f64::MIN_POSITIVE);
            (name.clone(), d, *x, *y)
        })
        .collect()
}

/// What a difference of a rate or a length is measured against.
#[derive(Debug, Clone, Copy)]
struct Scales {
    /// The pitch rate's scale: the touchdown speed over the primary strut's length, rad/s.
    rate_rad_s: f64,
    /// A length's scale: the primary strut's length L2P, m.
    length_m: f64,
}

/// The largest scaled difference between two landings' figures ([`scaled_differences`]).
fn gap(a: &Summary, b: &Summary, map: &Map, scales: Scales) -> f64 {
    scaled_differences(a, b, map, scales)
        .iter()
        .fold(0.0, |m, d| m.max(d.1))
}

/// The figures of `a` and `b` that differ by more than [`TOLERANCE`] of their scale, and
/// whether the outcomes differ.
fn differences(a: &Summary, b: &Summary, map: &Map, scales: Scales) -> Vec<String> {
    let mut out = vec![];
    if a.outcome != b.outcome {
        out.push(format!("outcome {:?} vs {:?}", a.outcome, b.outcome));
    }
    for (name, d, x, y) in scaled_differences(a, b, map, scales) {
        if d > TOLERANCE {
            out.push(format!("{name}: {x:.12e} vs {y:.12e}"));
        }
    }
    out
}

/// The inverse of a leg map (old leg i is new leg inverse[i]).
fn inverse(map: &Map) -> Map {
    let mut legs = vec![0; map.legs.len()];
    for (k, &i) in map.legs.iter().enumerate() {
        legs[i] = k;
    }
    Map {
        legs,
        swap: map.swap,
    }
}

fn core(sc: &Scenario) -> Summary {
    touchdown_core::run(sc).unwrap_or_else(|e| panic!("{}: {e}", sc.source))
}

/// A scenario listed in [`UNSTABLE_TO_ASYMMETRY`] must part from its mirror image because a
/// rounding-level asymmetry grows, not by an abrupt decision: a deliberate 1e-15 rad roll of the
/// touchdown attitude must move its figures at least a tenth as far as the mirror does, where a
/// decision flipped by rounding alone would leave the nudged landing within rounding of the
/// original. (It may move them much further: the roll can be a far larger asymmetry than the
/// mirror's rounding, and grows as that does.)
fn instability_is_physical(sc: &Scenario, mirror_gap: f64, scales: Scales) -> bool {
    let mut nudged = sc.clone();
    nudged.touchdown.attitude.x += 1e-15;
    let identity = Map {
        legs: (0..sc.legs.len()).collect(),
        swap: false,
    };
    let nudge_gap = gap(&core(sc), &core(&nudged), &identity, scales);
    eprintln!(
        "{}: mirror gap {mirror_gap:.2e}, 1e-15 nudge gap {nudge_gap:.2e}",
        sc.source
    );
    nudge_gap > 0.1 * mirror_gap
}

/// The figures' scales of landing `sc`: its touchdown speed over its primary's length for
/// rates, that length for lengths.
fn scales(sc: &Scenario) -> Scales {
    let speed = sc
        .touchdown
        .velocity_g
        .norm()
        .max(1e-3 * sc.vehicle.gravity.sqrt());
    Scales {
        rate_rad_s: speed / sc.legs[0].l2p,
        length_m: sc.legs[0].l2p,
    }
}

/// Landing `sc` on the core as `scheme` makes it (the scenario, or one built from it), with the
/// landings it must match: its legs renumbered, its mirror image and, for a mirror-symmetric
/// landing, itself (what was compared, the other landing, the leg map between them).
fn with_images(
    sc: &Scenario,
    scheme: impl Fn(Scenario) -> Scenario,
) -> (Summary, Vec<(&'static str, Summary, Map)>) {
    let original = core(&scheme(sc.clone()));
    let mut pairs = vec![];
    let (renamed, map) = renumbered(sc);
    pairs.push(("legs renumbered", core(&scheme(renamed)), map));
    let (image, map) = mirrored(sc);
    pairs.push(("mirrored", core(&scheme(image)), map));
    if let Some(own) = self_mirror(sc) {
        pairs.push(("its own mirror image", original.clone(), own));
    }
    (original, pairs)
}

/// Every bundled landing run on the core: its mirror image gives the mirrored result and its
/// renumbered legs the renumbered result, to 1e-9 relative; a mirror-symmetric landing is its
/// own mirror image, so it comes out symmetric.
#[test]
fn mirror_symmetric_landings_come_out_symmetric() {
    let mut failures = vec![];
    let mut symmetric = vec![];
    for name in bundled_landings() {
        let sc = Scenario::load(scenario(&name)).unwrap_or_else(|e| panic!("{e}"));
        let scales = scales(&sc);
        let (original, pairs) = with_images(&sc, |s| s);
        if self_mirror(&sc).is_some() {
            symmetric.push(name.clone());
        }
        if UNSTABLE_TO_ASYMMETRY.contains(&name.as_str()) {
            let widest = pairs
                .iter()
                .map(|(_, other, map)| gap(&original, other, map, scales))
                .fold(0.0, f64::max);
            assert!(
                instability_is_physical(&sc, widest, scales),
                "{name} is listed as unstable to asymmetry, but a 1e-15 nudge moves it less than a tenth as far as its mirror image and renumbering do"
            );
            continue;
        }
        for (what, other, map) in &pairs {
            for d in differences(&original, other, map, scales) {
                failures.push(format!("{name}, {what}: {d}"));
            }
        }
    }
    assert!(
        symmetric.len() >= 5,
        "expected the symmetric drops and the 2-2 landings to be their own mirror images: {symmetric:?}"
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The `strides` scheme's step and its footpads' corrector are built of the legs' own
/// quantities summed over the legs (docs/errata.md, "Long strides where the gear is soft"):
/// every bundled landing it applies to (not on soil nor beside curbs) and that is not
/// [`UNSTABLE_TO_ASYMMETRY`] on the report's scheme comes out mirrored and renumbered to 1e-9,
/// and symmetric where it is its own mirror image, as on the report's scheme.
#[test]
fn the_strides_scheme_lands_mirror_images_and_renumbered_legs_alike() {
    let strides = |s: Scenario| {
        s.with_integrator(|it| it.scheme = Scheme::Strides)
            .unwrap_or_else(|e| panic!("{e}"))
    };
    let mut failures = vec![];
    let mut landed = vec![];
    for name in bundled_landings() {
        let sc = Scenario::load(scenario(&name)).unwrap_or_else(|e| panic!("{e}"));
        let applies = sc.surface.soil.is_none() && sc.surface.curbs.is_empty();
        if !applies || UNSTABLE_TO_ASYMMETRY.contains(&name.as_str()) {
            continue;
        }
        landed.push(name.clone());
        let (original, pairs) = with_images(&sc, strides);
        for (what, other, map) in &pairs {
            for d in differences(&original, other, map, scales(&sc)) {
                failures.push(format!("{name}, {what}: {d}"));
            }
        }
    }
    assert!(landed.len() >= 10, "{landed:?}");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A landing that is its own mirror image lands as its own mirror image on the core bit for
/// bit, the 2-2 landings (whose plane of symmetry is a diagonal of the body axes) as the 1-2-1
/// landings (a plane of the body axes), and the rounding ensemble's perturbed copies
/// ([`touchdown_compare::rounding`]), the touchdown velocity moved by one unit in the last
/// place across one way and the other, land as mirror images of each other to 1e-9 of each
/// figure's scale, however far either lands from the landing as given: the perturbation
/// carries no asymmetry of its own.
#[test]
fn the_rounding_ensembles_copies_of_a_symmetric_landing_are_mirror_images() {
    let mut checked = vec![];
    let mut failures = vec![];
    for name in bundled_landings() {
        if UNSTABLE_TO_ASYMMETRY.contains(&name.as_str()) {
            continue;
        }
        let sc = Scenario::load(scenario(&name)).unwrap_or_else(|e| panic!("{e}"));
        let Some(own) = self_mirror(&sc) else {
            continue;
        };
        let [plus, minus] = touchdown_compare::rounding::CROSSWISE_ULPS
            .map(|u| core(&touchdown_compare::rounding::crosswise(&sc, u).unwrap()));
        let scales = Scales {
            rate_rad_s: sc.touchdown.velocity_g.norm().max(1e-3) / sc.legs[0].l2p,
            length_m: sc.legs[0].l2p,
        };
        let given = core(&sc);
        let asymmetry = gap(&given, &given, &own, scales);
        if asymmetry != 0.0 {
            failures.push(format!(
                "{name}: not its own mirror image, by {asymmetry:e}"
            ));
        }
        for d in differences(&plus, &minus, &own, scales) {
            failures.push(format!("{name}, copies: {d}"));
        }
        checked.push(name);
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert!(checked.len() >= 15, "{checked:?}");
}

/// A channel rounding decides, named: on the Table I 2-2 landing at 4 ft/s, standing on
/// spikes, the core's copies moved by one unit in the last place across land the uphill legs'
/// primaries more than the comparison's primary-stroke tolerance (5 %) apart, though the
/// landing is its own mirror image bit for bit and the copies each other's: the vehicle rocks
/// back onto its uphill legs 3 and 4 after the touchdown, their footpads lifted out of their
/// spikes or held by them, and which of the two it comes down on harder is decided by the last
/// bit of the touchdown velocity.
/// `touchdown compare` reports such a channel as not determined at this precision
/// (docs/engines.md, "Rounding-decided channels").
#[test]
fn the_last_bit_of_the_touchdown_velocity_decides_a_rocking_landings_primaries() {
    let sc = Scenario::load(scenario("table-i-2-2-vv4.toml")).unwrap();
    let [plus, minus] = touchdown_compare::rounding::CROSSWISE_ULPS
        .map(|u| core(&touchdown_compare::rounding::crosswise(&sc, u).unwrap()));
    let given = core(&sc);
    let leg = |s: &Summary, i: usize| s.max_primary_stroke_m[i];
    let strokes = [leg(&given, 3), leg(&plus, 3), leg(&minus, 3)];
    let (lo, hi) = strokes
        .iter()
        .fold((f64::MAX, 0.0_f64), |(lo, hi), &x| (lo.min(x), hi.max(x)));
    let moved = (hi - lo) / hi;
    eprintln!(
        "leg 4 primary strokes {strokes:.5?} m as given and on the copies: {:.1} %",
        100.0 * moved
    );
    assert!(
        moved > touchdown_compare::metrics::PRIMARY_STROKE.limit,
        "moved {moved}"
    );
}
