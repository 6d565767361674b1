//! The trajectory file's recorder (`touchdown_view::Recorder`) against the full history of a
//! landing: every contact change listed exactly, frames bounded by the interval, point 1 where
//! the engine's strokes put it (eqs. 27-34), the centre of mass projected along gravity.

use nalgebra::Vector3;
use touchdown_core::Simulation;
use touchdown_frames::{gravity_inertial, t_bi};
use touchdown_record::{Landing, Observer, Sample};
use touchdown_scenario::schema::Arrangement;
use touchdown_scenario::Scenario;
use touchdown_tests::scenario;
use touchdown_view::{Recorder, Recording};

/// Every accepted state of a landing, and what a recorder kept of it.
struct Both {
    all: Vec<Sample>,
    recorder: Recorder,
}

impl<L: Landing> Observer<L> for Both {
    fn observe(&mut self, landing: &L) {
        let mut s = Sample::new(self.all.first().map_or(4, |s| s.legs.len()));
        landing.sample(&mut s);
        self.recorder.push(&s);
        self.all.push(s);
    }
}

fn land(name: &str, interval: f64) -> (Scenario, Vec<Sample>, Recording) {
    let sc = Scenario::load(scenario(name)).unwrap();
    let mut both = Both {
        all: Vec::new(),
        recorder: Recorder::new(&sc, interval),
    };
    Simulation::new(&sc).unwrap().run(&mut both).unwrap();
    (sc, both.all, both.recorder.finish())
}

/// Every change of a footpad's contact state in the full history is an event, at its time,
/// and nothing else is; the frames are the first state, the last, one per interval at most and
/// the two states around each footpad's first touchdown.
#[test]
fn events_are_exact_and_frames_are_bounded() {
    for name in [
        "fig-25-26.toml",
        "level-sliding.toml",
        "near-boundary-overturn.toml",
    ] {
        let interval = 2.0e-3;
        let (sc, all, rec) = land(name, interval);
        let mut expected = Vec::new();
        for w in all.windows(2) {
            for (leg, (a, b)) in w[0].legs.iter().zip(&w[1].legs).enumerate() {
                if a.contact != b.contact {
                    expected.push((w[1].t, leg + 1, b.contact));
                }
            }
        }
        assert!(!expected.is_empty(), "{name}: no contact change to check");
        assert_eq!(rec.events.len(), expected.len(), "{name}");
        for (e, (t, leg, contact)) in rec.events.iter().zip(&expected) {
            assert!(
                (e.t_s - t).abs() <= 0.5e-7,
                "{name}: event at {} for {t}",
                e.t_s
            );
            assert_eq!((e.leg, e.contact), (*leg, *contact), "{name}");
        }
        let f = &rec.frames;
        let (first, last) = (all[0].t, all[all.len() - 1].t);
        assert_eq!(f.t_s[0], first);
        assert!(
            (f.t_s[f.t_s.len() - 1] - last).abs() <= 0.5e-7,
            "{name}: last state kept"
        );
        assert!(
            f.t_s.windows(2).all(|w| w[0] < w[1]),
            "{name}: times increase"
        );
        let bound = ((last - first) / interval).ceil() as usize + 2 + 2 * sc.legs.len();
        assert!(
            f.t_s.len() <= bound,
            "{name}: {} frames > {bound}",
            f.t_s.len()
        );
        assert!(
            f.t_s.len() * 4 < all.len(),
            "{name}: {} of {} states",
            f.t_s.len(),
            all.len()
        );
        // No state between two frames was due: each came before the interval had passed (the
        // frames' times are rounded to 1e-7 s, half of which either way).
        for w in f.t_s.windows(2) {
            let inside = all
                .iter()
                .filter(|s| s.t > w[0] + 1e-7 && s.t < w[1] - 1e-7);
            for s in inside {
                assert!(
                    s.t - w[0] < interval + 0.5e-7,
                    "{name}: the state at {} s was due after the frame at {} s",
                    s.t,
                    w[0]
                );
            }
        }
        // Each footpad's first touchdown: the last state before it and the first in contact.
        for leg in 0..sc.legs.len() {
            let Some(k) = all.iter().position(|s| s.legs[leg].contact != 0) else {
                continue;
            };
            for s in &all[k.saturating_sub(1)..=k] {
                assert!(
                    f.t_s.iter().any(|t| (t - s.t).abs() <= 0.5e-7),
                    "{name}: leg {} touchdown state at {} not kept",
                    leg + 1,
                    s.t
                );
            }
        }
    }
}

/// Point 1 lies L21 from B2 along B2 → footpad (the footpad itself in the tripod gear), and the
/// secondaries drawn from their trunnions
/// to it are as long as the engine's strokes make them (L31 + S31, L41 + S41: eqs. 27-34); the
/// centre of mass's projection lies on the surface, straight below it along gravity.
#[test]
fn frames_draw_the_gear_the_engine_computed() {
    for name in ["table-i-2-2-vv8.toml", "tripod-drop.toml"] {
        gear_as_computed(name);
    }
}

fn gear_as_computed(name: &str) {
    let (sc, all, rec) = land(name, 1.0e-3);
    let tripod = sc.arrangement == Arrangement::Tripod;
    let f = &rec.frames;
    let g = gravity_inertial(1.0, sc.surface.slope);
    let v = |p: &[f64; 3]| Vector3::new(p[0], p[1], p[2]);
    let mut checked = 0;
    for k in 0..f.t_s.len() {
        let q = f.attitude[k];
        let q = nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
            q[0], q[1], q[2], q[3],
        ));
        let x = v(&f.position_m[k]);
        for (leg, (geometry, frames)) in sc.legs.iter().zip(&f.legs).enumerate() {
            let b = |p: &Vector3<f64>| x + q * p;
            let (b2, p1, pad) = (b(&geometry.b2), v(&frames.point1_m[k]), v(&frames.pad_m[k]));
            if tripod {
                assert_eq!(
                    p1, pad,
                    "{name}: the tripod's secondaries meet at the footpad"
                );
            } else {
                let along = (pad - b2).normalize();
                assert!(
                    ((p1 - b2) - along * geometry.l21).norm() < 5e-6,
                    "leg {}",
                    leg + 1
                );
            }
            for (trunnion, rest, stroke) in [
                (geometry.b3, geometry.l31, frames.sec31_stroke_m[k]),
                (geometry.b4, geometry.l41, frames.sec41_stroke_m[k]),
            ] {
                let length = (p1 - b(&trunnion)).norm();
                assert!(
                    (length - rest - stroke).abs() < 1e-5,
                    "{name}: leg {} at {} s: secondary {length} m, rest {rest} + stroke {stroke}",
                    leg + 1,
                    f.t_s[k]
                );
                checked += 1;
            }
        }
        let below = v(&f.com_projection_m[k]);
        assert!(below.z.abs() < 1e-6);
        assert!(
            (x - below).cross(&g).norm() < 1e-5,
            "projection along gravity"
        );
        // The quaternion is the Euler attitude of eq. (3).
        let state = all
            .iter()
            .find(|s| (s.t - f.t_s[k]).abs() <= 0.5e-7)
            .unwrap();
        let r = q.to_rotation_matrix();
        assert!((r.matrix() - t_bi(&state.theta)).abs().max() < 1e-6);
    }
    assert!(checked > 100);
}
