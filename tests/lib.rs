//! Shared helpers for the workspace-level tests.

use nalgebra::Vector3;
use std::path::PathBuf;
use touchdown_laws::{GearLaws, LoadStroke};
use touchdown_record::{Outcome, Sample, Summary};
use touchdown_scenario::model::Leg;
use touchdown_scenario::schema::Arrangement;
use touchdown_scenario::Scenario;

/// The workspace root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("tests/ sits in the workspace root")
        .to_path_buf()
}

/// The interpreter of the project's pinned Python environment (`.venv`, made by
/// `scripts/setup-python`, which `scripts/test` runs). Panics, with the command that creates
/// it, if it is missing: a test that needs it fails, it is never skipped.
pub fn python() -> PathBuf {
    let python = root().join(".venv/bin/python");
    assert!(
        python.exists(),
        "the project's Python environment is missing ({}): run `scripts/setup-python` (scripts/test runs it)",
        python.display()
    );
    python
}

/// A landing of the scenario file `path` on the MuJoCo engine, end to end through the Python
/// runner, its output written under a temporary folder named by `tag` and removed after.
pub fn mujoco(path: &std::path::Path, tag: &str) -> touchdown_record::Summary {
    let out = std::env::temp_dir().join(format!(
        "touchdown-mujoco-{}-{tag}-{}",
        std::process::id(),
        path.file_stem().unwrap().to_string_lossy()
    ));
    let launch = touchdown_mujoco::Launch::locate().unwrap_or_else(|e| panic!("{e}"));
    let summary = launch
        .run(path, &out, false)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let _ = std::fs::remove_dir_all(&out);
    summary
}

/// A scenario file under `scenarios/`.
pub fn scenario(name: &str) -> PathBuf {
    root().join("scenarios").join(name)
}

/// The `[similarity]` table of the Froude twin: the 1/6-scale model six times as large under a
/// sixth of the gravity (length 6, mass 216, time 6), TOML for [`variant`]'s `extra`.
pub const FROUDE_TWIN: &str = "[similarity]\nlength = 6.0\nmass = 216.0\ntime = 6.0\n";

/// A variant of scenario `base` (under `scenarios/`) named `name`, with `extra` TOML on top,
/// written to a temporary file (the MuJoCo runner and the CLI read files).
pub fn variant(base: &str, name: &str, extra: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("touchdown-variants-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("the temporary folder is writable");
    let path = dir.join(format!("{name}.toml"));
    let text = format!(
        "schema_version = 1\nextends = {:?}\nname = {name:?}\n{extra}",
        scenario(base).display().to_string()
    );
    std::fs::write(&path, text).expect("the variant is written");
    path
}

/// The slope of [`set_down_on_a_slope`], deg.
pub const SLOPE_DEG: f64 = 10.0;

/// A variant of scenario `base` named `name`, set down on a [`SLOPE_DEG`] slope in the slope's
/// attitude, its first footpad on the surface at t = 0, at 1 ft/s into it and `along_x` ft/s
/// along the slope's level line (+X), on ground of friction `friction`, run to 1.5 s: the
/// settled lander of the sliding, curb-friction and rocking oracles.
pub fn set_down_on_a_slope(base: &str, name: &str, friction: f64, along_x: f64) -> PathBuf {
    variant(
        base,
        name,
        &format!(
            "[surface]\nslope = {SLOPE_DEG:?}\nfriction = {friction:?}\n[touchdown]\n\
             attitude_reference = \"surface\"\nclearance = 0.0\nvertical_velocity = -1.0\n\
             horizontal_velocity = [{along_x:?}, 0.0]\n[integrator]\nt_end = 1.5\n"
        ),
    )
}

/// Every bundled landing (scenarios/*.toml; the vehicle files are not landings), sorted.
pub fn bundled_landings() -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(root().join("scenarios"))
        .expect("scenarios/ is readable")
        .filter_map(|e| {
            let name = e.ok()?.file_name().into_string().ok()?;
            name.ends_with(".toml").then_some(name)
        })
        .collect();
    names.sort();
    names
}

/// The file names of the nine validation landings under `scenarios/` (the eight Table I
/// landings and the figure 25-26 landing), sorted.
pub fn validation_landings() -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(scenario(""))
        .expect("scenarios/ is readable")
        .map(|e| {
            e.expect("a directory entry")
                .file_name()
                .to_string_lossy()
                .into_owned()
        })
        .filter(|n| n.starts_with("table-i-") || n.starts_with("fig-25-26"))
        .collect();
    names.sort();
    assert_eq!(names.len(), 9, "{names:?}");
    names
}

/// Area under a virgin load-stroke curve from 0 to x (J): work of monotonic loading.
fn area(curve: &LoadStroke, x: f64) -> f64 {
    if x <= 0.0 {
        return 0.0;
    }
    let mut a = 0.0;
    let mut prev = (0.0, 0.0);
    for (xi, fi) in curve.vertices().skip(1) {
        if x <= xi {
            let f = prev.1 + (fi - prev.1) * (x - prev.0) / (xi - prev.0);
            return a + 0.5 * (prev.1 + f) * (x - prev.0);
        }
        a += 0.5 * (prev.1 + fi) * (xi - prev.0);
        prev = (xi, fi);
    }
    let f = curve.force(x);
    a + 0.5 * (prev.1 + f) * (x - prev.0)
}

/// Maximum strokes of leg 1, m, of a symmetric vertical drop on flat ground with locked
/// footpads, without viscous forces, computed independently of any engine: the primary's
/// compression c and the secondaries' S31, S41 (tension positive). At maximum stroke the
/// vehicle is at rest, so its initial kinetic energy plus the potential energy released by the
/// drop h equals the work of monotonic loading of every strut and of the primary's bearing
/// friction. The balance is solved for h (pure translation: the footpad fixed in space moves up
/// by h in body axes), and the strokes are the gear's at h: point 1 at L21 along the primary for
/// the cantilever, the footpad itself for the tripod (eqs. 27-34). Gear masses are left out (the
/// report's gear is massless).
///
/// The bearing friction's work is derived here from statics, not from the laws' code: the
/// secondaries pull point 1 with their virgin-curve forces along their own axes; the primary,
/// pinned at its trunnion B2, balances their part normal to it at L21 with a side load FM at the
/// footpad, |FM|·|V2P| = |F⊥|·L21; the inner cylinder, a beam on its two bearings (bearing 1 at
/// D1 from the footpad, bearing 2 at D1 − D2, D2 = D2₀ + c), carries FM with
/// F2 − F1 = FM and F2·(D1 − D2) = F1·D1 (moments about the footpad), and the friction
/// μB·(F1 + F2) opposes the compression along the whole monotonic stroke. A tripod's primary is
/// a two-force member (FM = 0).
pub fn analytic_drop_strokes(sc: &Scenario) -> [f64; 3] {
    assert_eq!(sc.primary.viscous.coefficient, 0.0);
    let laws = GearLaws::from_scenario(sc).unwrap();
    let m = sc.vehicle.mass;
    let g = sc.vehicle.gravity;
    let v = sc.touchdown.velocity_g.norm();
    let tripod = sc.arrangement == Arrangement::Tripod;
    let strokes = |h: f64| -> Vec<[f64; 3]> {
        sc.legs
            .iter()
            .map(|leg| {
                let bp = leg.bp + Vector3::new(0.0, 0.0, h);
                let v2p = bp - leg.b2;
                let b1 = if tripod {
                    bp
                } else {
                    leg.b2 + v2p.normalize() * leg.l21
                };
                [
                    leg.l2p - v2p.norm(),
                    (b1 - leg.b3).norm() - leg.l31,
                    (b1 - leg.b4).norm() - leg.l41,
                ]
            })
            .collect()
    };
    let secondary_area = |s: f64| {
        if s >= 0.0 {
            area(&laws.secondary.honeycomb.tension.curve, s)
        } else {
            area(&laws.secondary.honeycomb.compression.curve, -s)
        }
    };
    let secondary_force = |s: f64| {
        if s >= 0.0 {
            laws.secondary.honeycomb.tension.curve.force(s)
        } else {
            -laws.secondary.honeycomb.compression.curve.force(-s)
        }
    };
    // The bearing friction on `leg`'s primary at the drop h, its strokes `[c, s3, s4]`, N.
    let (mu, d1) = (
        sc.primary.bearing_friction,
        sc.primary.inner_cylinder_length,
    );
    let friction = |leg: &Leg, h: f64, [c, s3, s4]: [f64; 3]| -> f64 {
        let v2p = leg.bp + Vector3::new(0.0, 0.0, h) - leg.b2;
        let axis = v2p.normalize();
        let b1 = leg.b2 + axis * leg.l21;
        let pull = (leg.b3 - b1).normalize() * secondary_force(s3)
            + (leg.b4 - b1).normalize() * secondary_force(s4);
        let fm = (pull - axis * pull.dot(&axis)).norm() * leg.l21 / v2p.norm();
        let d2 = sc.primary.initial_overlap + c;
        let f1 = fm * (d1 - d2) / d2;
        let f2 = f1 + fm;
        mu * (f1 + f2)
    };
    // Its work from 0 to h over every leg, J: the trapezoid over 2,000 steps of the drop.
    let friction_work = |h: f64| -> f64 {
        if mu == 0.0 || tripod {
            return 0.0;
        }
        let at = |hk: f64| -> Vec<(f64, f64)> {
            let s = strokes(hk);
            sc.legs
                .iter()
                .zip(s)
                .map(|(leg, st)| (friction(leg, hk, st), st[0]))
                .collect()
        };
        let n = 2000;
        let (mut w, mut prev) = (0.0, at(0.0));
        for k in 1..=n {
            let now = at(h * k as f64 / n as f64);
            for ((f, c), (f0, c0)) in now.iter().zip(&prev) {
                w += 0.5 * (f + f0) * (c - c0);
            }
            prev = now;
        }
        w
    };
    let work = |h: f64| -> f64 {
        let struts: f64 = strokes(h)
            .iter()
            .map(|[c, s3, s4]| {
                area(&laws.primary.honeycomb.curve, *c) + secondary_area(*s3) + secondary_area(*s4)
            })
            .sum();
        struts + friction_work(h)
    };
    let balance = |h: f64| 0.5 * m * v * v + m * g * h - work(h);
    let (mut lo, mut hi) = (0.0, 0.3);
    assert!(balance(lo) > 0.0 && balance(hi) < 0.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if balance(mid) > 0.0 {
            lo = mid
        } else {
            hi = mid
        }
    }
    strokes(lo)[0]
}

/// Asserts that a symmetric vertical drop's `summary` strokes as [`analytic_drop_strokes`]
/// of its scenario `sc`: every leg's primary within 1 % of the analytic stroke, each secondary
/// within 1 % of the primary's; the energy balance closed to 0.2 % of the initial kinetic
/// energy, and the landing stable.
pub fn assert_drop_strokes_to_the_energy_balance(sc: &Scenario, summary: &Summary) {
    let [c, s3, s4] = analytic_drop_strokes(sc);
    let engine = &summary.engine;
    let name = &sc.file.name;
    for i in 0..sc.legs.len() {
        let stroke = summary.max_primary_stroke_m[i];
        let err = (stroke - c).abs() / c;
        assert!(
            err < 0.01,
            "{name}, {engine}, leg {}: primary stroke {stroke:.6} m vs analytic {c:.6} m ({:.3} %)",
            i + 1,
            100.0 * err
        );
        for (j, s) in [s3, s4].into_iter().enumerate() {
            let got = if s < 0.0 {
                -summary.max_secondary_compression_m[i][j]
            } else {
                summary.max_secondary_tension_m[i][j]
            };
            assert!(
                (got - s).abs() < 0.01 * c,
                "{name}, {engine}, leg {}: secondary {} stroke {got:.6} m vs analytic {s:.6} m",
                i + 1,
                j + 3
            );
        }
    }
    let e = &summary.energy;
    assert!(
        e.residual_j.abs() < 2e-3 * e.kinetic_initial_j,
        "{name}, {engine}: residual {} J",
        e.residual_j
    );
    assert_eq!(summary.outcome, Outcome::Stable, "{name}, {engine}");
}

/// The seeded proptest runner of the fuzz harnesses (`tests/integration/fuzz.rs`,
/// `crates/cli/tests/fuzz.rs`): `TOUCHDOWN_FUZZ_CASES` cases (else `default_cases`) drawn from
/// `TOUCHDOWN_FUZZ_SEED` (else 7), so the suite tries the same cases every run; no failure
/// files (a case found is kept as a regression case in the harness). Returns the runner, the
/// cases and the seed.
pub fn fuzz_runner(default_cases: u32) -> (proptest::test_runner::TestRunner, u32, u64) {
    use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
    let env = |name: &str| std::env::var(name).ok().and_then(|s| s.parse::<u64>().ok());
    let cases = env("TOUCHDOWN_FUZZ_CASES").map_or(default_cases, |n| n as u32);
    let seed = env("TOUCHDOWN_FUZZ_SEED").unwrap_or(7);
    let mut seed_bytes = [0u8; 32];
    seed_bytes[..8].copy_from_slice(&seed.to_le_bytes());
    let config = Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    };
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &seed_bytes);
    (TestRunner::new_with_rng(config, rng), cases, seed)
}

/// Checks that each of the first `count` rebounds' `rises` (m, heights of the apexes above the
/// rest height, in order) after the first is at most `bound(before, first)` (m) and that the
/// fourth is below 5 % of the first: the bouncing of a landing on end stops dies out.
pub fn assert_rebounds_fall(
    label: &str,
    rises: &[f64],
    count: usize,
    bound: impl Fn(f64, f64) -> f64,
) {
    assert!(rises.len() >= count.max(4), "{label}: rises {rises:?} m");
    for k in 1..count {
        let most = bound(rises[k - 1], rises[0]);
        assert!(
            rises[k] <= most,
            "{label}: rebound {k} rose {} m after {} m (at most {most} m)",
            rises[k],
            rises[k - 1]
        );
    }
    assert!(
        rises[3] < 0.05 * rises[0],
        "{label}: still bouncing {rises:?}"
    );
}

/// `fig-25-26` with spikes 0.02 ft deep in place of its wall (docs/errata.md, "Spikes, not a
/// wall"), written by [`variant`] as `name` (one name per test: tests run side by side).
pub fn spiked_fig_25_26(name: &str) -> PathBuf {
    variant(
        "fig-25-26.toml",
        name,
        "[surface]\nobstacle = 0.0\nspike_depth = 0.02\n",
    )
}

/// Spikes, not a wall (docs/errata.md, "Spikes, not a wall"): along the `samples` of a landing
/// of the spiked `fig-25-26` ([`spiked_fig_25_26`], scenario `sc`) on `engine`, a footpad more
/// than its engagement depth above its plane at two samples running feels no lateral restraint
/// (its `restraint_force` is 0 N), and the uphill footpads 3 and 4, which leave the ground,
/// move sideways with their gear while they fly; the spikes do hold the footpads in the ground
/// (a restraint force somewhere), so that a restraint never built does not pass.
pub fn assert_spikes_let_go_of_flying_footpads(engine: &str, sc: &Scenario, samples: &[Sample]) {
    let held = samples
        .iter()
        .flat_map(|s| s.legs.iter().map(|g| g.restraint_force.abs()))
        .fold(0.0, f64::max);
    assert!(
        held > 1.0,
        "{engine}: the spikes never held a footpad ({held} N)"
    );
    let mut flew = [0.0f64; 4];
    for pair in samples.windows(2) {
        for (i, p) in sc.surface.pads.iter().enumerate() {
            let depth = p.spike_depth;
            assert!(depth > 0.0, "fig-25-26 has spikes");
            let out = |s: &Sample| s.legs[i].pad_position.z > p.plane() + depth;
            if out(&pair[0]) && out(&pair[1]) {
                let f = pair[1].legs[i].restraint_force;
                assert!(
                    f == 0.0,
                    "{engine}: leg {} held by {f} N at t = {} s, out of the ground",
                    i + 1,
                    pair[1].t
                );
                let moved = pair[1].legs[i].pad_position.xy() - pair[0].legs[i].pad_position.xy();
                flew[i] += moved.norm();
            }
        }
    }
    assert!(
        flew[2] > 0.01 && flew[3] > 0.01,
        "{engine}: the flying footpads moved {flew:?} m sideways"
    );
}
