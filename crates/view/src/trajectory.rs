//! The trajectory file (`touchdown.trajectory/1`, docs/outputs.md, "The trajectory file"): what
//! a viewer needs to draw a landing of one or more engines, from the same [`Sample`]s every
//! engine records into `history.csv`.
//!
//! - **Frames** are kept at most every `frame_interval_s` of landing time, plus the first and
//!   the last state and the states on both sides of each footpad's first touchdown: a landing
//!   of 10 000 steps becomes about a thousand frames whatever its footpads do.
//! - **Events** list every change of a footpad's contact state exactly (time, new state, the
//!   footpad's position), however fast they come: a footpad that chatters on the surface (a
//!   multibody's contact at its 20 µs step, the core's pads re-touching) changes state every
//!   few steps, and a frame at each change would keep nearly every step. A viewer takes a
//!   footpad's contact state at time t from the last event at or before t, so that no change is
//!   lost between frames.
//! - **Geometry** the drawing needs beyond the history: the trunnions B2, B3, B4 in body axes
//!   (a viewer moves them with the body's attitude), point 1 per frame (where the secondaries
//!   meet the primary: L21 from B2 along B2 → footpad in the cantilever gear, eqs. 27-30 at the
//!   current footpad; the footpad itself in the tripod), the
//!   centre of mass's projection along gravity onto the surface (the foot of the stability
//!   walls' construction, eqs. 105-107), and the rotation from the surface frame to the gravity
//!   frame (eq. 1), so that a viewer draws with gravity down.
//! - **Numbers** are rounded to what a drawing resolves: lengths to 1 µm, times to 0.1 µs,
//!   attitude quaternions to 1e-7, rates to 1e-6 rad/s, forces and stability distances to five
//!   significant digits.

use nalgebra::{Rotation3, UnitQuaternion, Vector2, Vector3};
use serde::Serialize;
use touchdown_frames::{t_bi, t_gi};
use touchdown_laws::curb::Curb;
use touchdown_record::{Landing, Observer, Sample};
use touchdown_scenario::schema::Arrangement;
use touchdown_scenario::Scenario;

/// Default landing time between kept frames, s: a thousand frames a second of landing.
pub const DEFAULT_FRAME_INTERVAL: f64 = 1.0e-3;

/// The scenario's lander and ground as a viewer draws them.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Scene {
    /// The scenario's name.
    pub scenario_name: String,
    /// The vehicle's gear, leg by leg.
    pub vehicle: VehicleView,
    /// The ground.
    pub surface: SurfaceView,
}

/// The vehicle as drawn.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct VehicleView {
    /// Legs in the scenario's order (counter-clockwise seen from above).
    pub legs: Vec<LegView>,
}

/// One leg's body-fixed points, body axes from the centre of mass, m.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LegView {
    /// B2, the primary strut's trunnion, m.
    pub primary_trunnion_m: [f64; 3],
    /// B3, the first secondary's trunnion, m.
    pub sec31_trunnion_m: [f64; 3],
    /// B4, the second secondary's trunnion, m.
    pub sec41_trunnion_m: [f64; 3],
    /// PR, the footpad's radius, m.
    pub pad_radius_m: f64,
}

/// The ground as drawn.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SurfaceView {
    /// Slope α, rad.
    pub slope_rad: f64,
    /// T_GI of eq. (1), by rows: a vector in the surface frame (X-Y on the surface, Z up its
    /// normal: every position of the file) times this matrix is in the gravity frame (Z up
    /// against gravity).
    pub surface_to_gravity: [[f64; 3]; 3],
    /// Whether the ground is soil (eqs. 101-104) rather than rigid.
    pub soil: bool,
    /// The ground under each footpad, leg by leg.
    pub pads: Vec<PadGround>,
}

/// The ground under one footpad.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PadGround {
    /// HOLE: the local ground is the plane Z = −hole_m of the surface frame, m.
    pub hole_m: f64,
    /// OBST: > 0, the footpad is locked laterally by an obstacle this high once it touches, m.
    pub obstacle_m: f64,
    /// > 0: spikes hold the footpad laterally while it is within this depth of its plane, m.
    pub spike_depth_m: f64,
    /// U, the sliding friction coefficient.
    pub friction: f64,
}

impl Scene {
    /// The scene of `sc`.
    pub fn new(sc: &Scenario) -> Scene {
        let t = t_gi(sc.surface.slope);
        Scene {
            scenario_name: sc.file.name.clone(),
            vehicle: VehicleView {
                legs: sc
                    .legs
                    .iter()
                    .map(|leg| LegView {
                        primary_trunnion_m: point(&leg.b2),
                        sec31_trunnion_m: point(&leg.b3),
                        sec41_trunnion_m: point(&leg.b4),
                        pad_radius_m: length(sc.footpad.radius),
                    })
                    .collect(),
            },
            surface: SurfaceView {
                slope_rad: sc.surface.slope,
                surface_to_gravity: [0, 1, 2].map(|r| [0, 1, 2].map(|c| t[(r, c)])),
                soil: sc.surface.soil.is_some(),
                pads: sc
                    .surface
                    .pads
                    .iter()
                    .map(|p| PadGround {
                        hole_m: p.hole,
                        obstacle_m: p.obstacle,
                        spike_depth_m: p.spike_depth,
                        friction: p.friction,
                    })
                    .collect(),
            },
        }
    }
}

/// A change of one footpad's contact state.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ContactEvent {
    /// The first recorded state with the new contact state, s.
    pub t_s: f64,
    /// The leg, 1-based.
    pub leg: usize,
    /// The new state: 0 never touched, 1 in contact, 2 left the surface (as `history.csv`).
    pub contact: u8,
    /// The footpad (ball joint) then, surface frame, m.
    pub pad_m: [f64; 3],
}

/// A curb as drawn: a line of the surface plane, fixed where its footpad first touched (eqs.
/// 86-90).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CurbView {
    /// The leg, 1-based.
    pub leg: usize,
    /// A point of the curb line, surface frame (Z = 0), m.
    pub point_m: [f64; 2],
    /// B̂ of eq. (90), along the curb.
    pub along: [f64; 2],
    /// Â of eq. (89), from the footpad toward the curb.
    pub toward: [f64; 2],
}

/// One leg's frames.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct LegFrames {
    /// Footpad (ball joint), surface frame, m.
    pub pad_m: Vec<[f64; 3]>,
    /// Point 1, where the secondaries meet the primary strut (the footpad in the tripod gear),
    /// surface frame, m.
    pub point1_m: Vec<[f64; 3]>,
    /// Contact state: 0 never touched, 1 in contact, 2 left the surface.
    pub contact: Vec<u8>,
    /// Primary stroke, m (compression positive).
    pub primary_stroke_m: Vec<f64>,
    /// Primary axial force, N (compression positive).
    pub primary_force_n: Vec<f64>,
    /// First secondary's stroke, m (tension positive).
    pub sec31_stroke_m: Vec<f64>,
    /// First secondary's axial force, N (tension positive).
    pub sec31_force_n: Vec<f64>,
    /// Second secondary's stroke, m (tension positive).
    pub sec41_stroke_m: Vec<f64>,
    /// Second secondary's axial force, N (tension positive).
    pub sec41_force_n: Vec<f64>,
}

/// One stability wall's frames.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WallFrames {
    /// The legs whose footpads the wall joins, 1-based.
    pub legs: [usize; 2],
    /// Stability distance (eq. 105), m, positive while the centre of mass is inside; left out
    /// when the wall is undefined at some frame (parallel to gravity).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stability_distance_m: Option<Vec<f64>>,
}

/// The kept states of one landing, column by column.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct Frames {
    /// Time, s.
    pub t_s: Vec<f64>,
    /// Centre of mass, surface frame, m.
    pub position_m: Vec<[f64; 3]>,
    /// Unit quaternion (w, x, y, z) turning body axes into the surface frame (T_BI of eq. 3).
    pub attitude: Vec<[f64; 4]>,
    /// Pitch rate, about the surface frame's X axis, rad/s.
    pub pitch_rate_rad_s: Vec<f64>,
    /// The centre of mass projected along gravity onto the surface plane Z = 0, m.
    pub com_projection_m: Vec<[f64; 3]>,
    /// Leg by leg.
    pub legs: Vec<LegFrames>,
    /// Wall by wall: wall k joins the footpads of legs k and k + 1 (the last, of the last leg
    /// and the first).
    pub walls: Vec<WallFrames>,
}

/// What a [`Recorder`] keeps of a landing (serialised as the fields of its engine's entry in the
/// trajectory file).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Recording {
    /// Every change of a footpad's contact state, in time order.
    pub events: Vec<ContactEvent>,
    /// The curbs of the footpads that touched.
    pub curbs: Vec<CurbView>,
    /// The kept states.
    pub frames: Frames,
}

/// Keeps the frames of a landing as it runs (an [`Observer`] of any stepping engine, or fed
/// [`Sample`]s read back from a history with [`Recorder::push`]).
pub struct Recorder {
    interval: f64,
    geometry: Geometry,
    /// Curbs of the scenario: leg (0-based), DWALLI (m), the curb.
    curbs: Vec<(usize, f64, Curb)>,
    /// Where each footpad first touched, surface plane, m.
    touchdown: Vec<Option<Vector2<f64>>>,
    /// The state being recorded, and the one before it.
    current: Sample,
    previous: Sample,
    previous_kept: bool,
    last_kept: f64,
    recording: Recording,
}

impl Recorder {
    /// A recorder for landings of `sc`, keeping a frame at most every `interval` s of landing
    /// time besides the contact events (a non-positive interval keeps every state).
    pub fn new(sc: &Scenario, interval: f64) -> Recorder {
        let n = sc.legs.len();
        let frames = Frames {
            legs: vec![LegFrames::default(); n],
            walls: (0..n)
                .map(|k| WallFrames {
                    legs: [k + 1, (k + 1) % n + 1],
                    stability_distance_m: Some(Vec::new()),
                })
                .collect(),
            ..Frames::default()
        };
        Recorder {
            interval,
            geometry: Geometry {
                gravity: touchdown_frames::gravity_inertial(1.0, sc.surface.slope),
                // The tripod's secondaries meet the primary at the footpad (B1 = BP).
                legs: sc
                    .legs
                    .iter()
                    .map(|l| {
                        (
                            l.b2,
                            (sc.arrangement == Arrangement::Cantilever).then_some(l.l21),
                        )
                    })
                    .collect(),
            },
            curbs: sc
                .surface
                .curbs
                .iter()
                .filter_map(|c| {
                    let curb = Curb::new(c.distance, c.angle, c.friction).ok()?;
                    Some((c.leg, c.distance, curb))
                })
                .collect(),
            touchdown: vec![None; n],
            current: Sample::new(n),
            previous: Sample::new(n),
            previous_kept: false,
            last_kept: f64::NEG_INFINITY,
            recording: Recording {
                events: Vec::new(),
                curbs: Vec::new(),
                frames,
            },
        }
    }

    /// Records the state `s` (the next accepted state of the landing).
    pub fn push(&mut self, s: &Sample) {
        self.current.clone_from(s);
        self.accept();
    }

    /// Decides whether the state in `current` is kept, and whether the one before it must be.
    fn accept(&mut self) {
        // The first state is always kept.
        let first = self.recording.frames.t_s.is_empty();
        let mut first_touchdown = false;
        for (i, (now, before)) in self
            .current
            .legs
            .iter()
            .zip(&self.previous.legs)
            .enumerate()
        {
            if !first && now.contact != before.contact {
                self.recording.events.push(ContactEvent {
                    t_s: time(self.current.t),
                    leg: i + 1,
                    contact: now.contact,
                    pad_m: point(&now.pad_position),
                });
            }
            if now.contact != 0 && self.touchdown[i].is_none() {
                self.touchdown[i] = Some(now.pad_position.xy());
                first_touchdown = !first;
            }
        }
        let frames = &mut self.recording.frames;
        if first_touchdown && !self.previous_kept {
            self.geometry.keep(frames, &self.previous);
        }
        // A frame due when the interval has passed, within rounding of the time sum.
        let due = self.current.t - self.last_kept >= self.interval * (1.0 - 1.0e-9);
        let kept = first || first_touchdown || due;
        if kept {
            self.geometry.keep(frames, &self.current);
            self.last_kept = self.current.t;
        }
        std::mem::swap(&mut self.current, &mut self.previous);
        self.previous_kept = kept;
    }

    /// The recording, the last state kept.
    pub fn finish(mut self) -> Recording {
        if !self.recording.frames.t_s.is_empty() && !self.previous_kept {
            self.geometry
                .keep(&mut self.recording.frames, &self.previous);
        }
        self.recording.curbs = self
            .curbs
            .iter()
            .filter_map(|(leg, dwalli, curb)| {
                let at = self.touchdown[*leg]?;
                // eqs. (87)-(88): the curb's line passes DWALLI from the first contact along Â.
                let point = at + curb.normal() * *dwalli;
                let pair = |v: Vector2<f64>| [v.x, v.y].map(|c| round_to(c, 1.0e6));
                Some(CurbView {
                    leg: leg + 1,
                    point_m: pair(point),
                    along: pair(curb.along()),
                    toward: pair(curb.normal()),
                })
            })
            .collect();
        self.recording
    }
}

/// What turns a state into a frame beyond the history's columns.
struct Geometry {
    /// Unit vector along gravity, surface frame.
    gravity: Vector3<f64>,
    /// B2 (body axes, m) and L21 (m) per leg: point 1 is L21 from B2 toward the footpad in the
    /// cantilever gear, the footpad itself in the tripod (no L21).
    legs: Vec<(Vector3<f64>, Option<f64>)>,
}

impl Geometry {
    /// Appends the state `s` to the frames `f`.
    fn keep(&self, f: &mut Frames, s: &Sample) {
        f.t_s.push(time(s.t));
        f.position_m.push(point(&s.position));
        let rotation = Rotation3::from_matrix_unchecked(t_bi(&s.theta)); // eq. (3)
        let q = UnitQuaternion::from_rotation_matrix(&rotation);
        // The hemisphere with w ≥ 0, so that the same attitude has the same numbers.
        let q = if q.w < 0.0 {
            -q.into_inner()
        } else {
            q.into_inner()
        };
        f.attitude
            .push([q.w, q.i, q.j, q.k].map(|c| round_to(c, 1.0e7)));
        f.pitch_rate_rad_s.push(round_to(s.pitch_rate, 1.0e6));
        // Along gravity from the centre of mass to the plane Z = 0.
        let projection = s.position - self.gravity * (s.position.z / self.gravity.z);
        f.com_projection_m.push(point(&projection));
        for ((out, leg), (b2, l21)) in f.legs.iter_mut().zip(&s.legs).zip(&self.legs) {
            let point1 = match l21 {
                // Point 1: L21 from B2 along the primary strut (eqs. 27-30).
                Some(l21) => {
                    let b2 = s.position + rotation * b2;
                    let axis = leg.pad_position - b2;
                    b2 + axis * (l21 / axis.norm())
                }
                None => leg.pad_position,
            };
            out.pad_m.push(point(&leg.pad_position));
            out.point1_m.push(point(&point1));
            out.contact.push(leg.contact);
            out.primary_stroke_m.push(length(leg.primary_stroke));
            out.primary_force_n.push(significant(leg.primary_force));
            out.sec31_stroke_m.push(length(leg.secondary_stroke[0]));
            out.sec31_force_n.push(significant(leg.secondary_force[0]));
            out.sec41_stroke_m.push(length(leg.secondary_stroke[1]));
            out.sec41_force_n.push(significant(leg.secondary_force[1]));
        }
        for (wall, sd) in f.walls.iter_mut().zip(&s.stability_distance) {
            if !sd.is_finite() {
                wall.stability_distance_m = None;
            }
            if let Some(series) = &mut wall.stability_distance_m {
                series.push(significant(*sd));
            }
        }
    }
}

/// A recorder watches any stepping engine.
impl<L: Landing> Observer<L> for Recorder {
    fn observe(&mut self, landing: &L) {
        landing.sample(&mut self.current);
        self.accept();
    }
}

/// `x` rounded to the nearest multiple of 1/`per`, written as its shortest decimal (`per` a
/// power of ten); −0 written 0.
fn round_to(x: f64, per: f64) -> f64 {
    (x * per).round() / per + 0.0
}

/// A length rounded to 1 µm.
fn length(x: f64) -> f64 {
    round_to(x, 1.0e6)
}

/// A time rounded to 0.1 µs.
pub(crate) fn time(x: f64) -> f64 {
    round_to(x, 1.0e7)
}

/// A point rounded to 1 µm.
fn point(v: &Vector3<f64>) -> [f64; 3] {
    [length(v.x), length(v.y), length(v.z)]
}

/// `x` rounded to five significant digits.
fn significant(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x + 0.0;
    }
    let p = 4 - x.abs().log10().floor() as i32;
    if p >= 0 {
        round_to(x, 10f64.powi(p))
    } else {
        let unit = 10f64.powi(-p);
        (x / unit).round() * unit + 0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounding_writes_short_decimals() {
        assert_eq!(significant(123456.7).to_string(), "123460");
        assert_eq!(significant(-0.000123456).to_string(), "-0.00012346");
        assert_eq!(significant(0.0), 0.0);
        assert_eq!(length(0.1234567).to_string(), "0.123457");
        assert_eq!(length(-1.0e-9).to_string(), "0");
        assert_eq!(time(0.01234567891).to_string(), "0.0123457");
    }
}
