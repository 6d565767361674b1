//! Footpads on the rigid surface, eqs. (16)-(19), (85), (96)-(100) and the contact logic of
//! the text (docs/errata.md, "Contact and release (text before eq. 85, after eq. 100) —
//! reinterpreted" and "Modelling choices the report leaves open").
//!
//! Each footpad n is a point mass PMASS at the ball joint of its gear (eqs. 16-18) and sees its
//! own plane Z = −HOLE_n. States: `Free` (never touched), `Contact` (on its plane: Z held by the
//! surface's reaction, X-Y locked if OBST_n > 0 or sliding with Coulomb friction), `Detached`
//! (left the surface after contact). Off the surface the report's footpad is attached rigidly to
//! the vehicle by its massless gear (`footpad.detached = "rigid"`: the undeformed gear before
//! touchdown, the relaxed one after); a footpad with inertia (`"inertial"`) moves under its
//! gear's force and its weight alone, integrated with the vehicle by the scheme's own stages
//! (docs/errata.md, "Footpads with inertia (eqs. 16-19, 85-100) — extended").

use nalgebra::{Vector2, Vector3};
use serde::Serialize;
use touchdown_laws::sliding::VELOCITY_ROUNDING;
use touchdown_scenario::model::PadSurface;

/// Contact state of a footpad.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum ContactState {
    /// Never touched the surface.
    #[default]
    Free,
    /// On its surface plane.
    Contact,
    /// Left the surface after contact: attached by its relaxed gear (rigid), or moving under
    /// its gear's force and its weight (inertial).
    Detached,
}

impl ContactState {
    /// Short code for tables: 0 free, 1 contact, 2 detached.
    pub fn code(self) -> u8 {
        match self {
            ContactState::Free => 0,
            ContactState::Contact => 1,
            ContactState::Detached => 2,
        }
    }
}

/// One footpad (effective point mass PMASS at the footpad ball joint).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Footpad {
    /// Contact state.
    pub state: ContactState,
    /// Inertial position (XP, YP, ZP), m.
    pub position: Vector3<f64>,
    /// Inertial velocity, m/s.
    pub velocity: Vector3<f64>,
    /// Body-frame position BP while attached rigidly (the report's detached footpad,
    /// `footpad.detached = "rigid"`: the frozen, possibly deformed geometry), m.
    pub bp_attached: Vector3<f64>,
    /// Inertial acceleration off the surface at the accepted state (eqs. 16-18: the gear's
    /// force over PMASS plus gravity), m/s²; zero in contact.
    pub acceleration: Vector3<f64>,
    /// (XPI, YPI), inertial X-Y at the first touchdown, m (recorded the first time only:
    /// docs/errata.md, "Modelling choices the report leaves open"; curbs (eq. 86) and the soil's lateral displacement SP (eq. 102) refer to it).
    pub touchdown_xy: Vector2<f64>,
    /// The in-plane force of its curbs on a footpad with inertia off the surface, frozen over
    /// a step as on the surface (eq. 96 corrected), N.
    pub curb_xy: Vector2<f64>,
    /// Held laterally by its obstacle's wall (OBST_n > 0): from its landing until it rises above
    /// the wall, on the surface or off it (text after fig. 17: "it cannot move laterally until
    /// it rises above the wall").
    pub walled: bool,
    /// Sliding footpad at rest, held by static friction (docs/errata.md, "Sliding stop within a
    /// step — implementation of the text before eq. (100)").
    pub stuck: bool,
    /// Time of first contact, s.
    pub first_contact: Option<f64>,
}

/// Frozen footpad forces for one integration step (eq. 97: FXP, FYP, FDRAGP constant over it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlidingForces {
    /// (FXP, FYP): gear force on the footpad in the surface plane, N (eqs. 98-99, corrected).
    pub gear_xy: Vector2<f64>,
    /// Σ PFRC + Σ FWF: the curbs' force on the footpad, N (eqs. 94-96; zero without curbs).
    pub curb_xy: Vector2<f64>,
    /// FDRAGP, sliding-friction magnitude, N (eq. 85, corrected); on soil FGRND = FDRAG +
    /// FDRAGP (eq. 104).
    pub drag: f64,
    /// (g_x, g_y), m/s².
    pub gravity_xy: Vector2<f64>,
    /// FZI, the gear force pressing the footpad into the surface, N (eq. 67; the soil's
    /// vertical load, eq. 103).
    pub fzi: f64,
    /// PMASS, kg.
    pub mass: f64,
    /// Forces within this of each other count as equal, N (the simulation's force rounding:
    /// a stuck footpad under rounding-level loads does not break away).
    pub rounding: f64,
}

impl SlidingForces {
    /// In-plane acceleration at velocity `v`, eq. (97): (FXP, FYP)/PMASS − (FDRAGP/PMASS)·v̂ + g.
    fn acceleration(&self, v: &Vector2<f64>) -> Vector2<f64> {
        let speed = v.norm();
        let drag = if speed > 0.0 {
            v * (self.drag / (self.mass * speed))
        } else {
            Vector2::zeros()
        };
        (self.gear_xy + self.curb_xy) / self.mass - drag + self.gravity_xy // eq. (97)
    }

    /// Applied in-plane force FXYP including the footpad's weight component, N (eq. 100; the
    /// weight term is an addition: docs/errata.md, "Eq. (100): breakaway test — the pad's
    /// weight added").
    pub fn applied(&self) -> Vector2<f64> {
        self.gear_xy + self.curb_xy + self.gravity_xy * self.mass
    }
}

/// Advances a sliding footpad over `dt` s: fourth-order Runge-Kutta with the force magnitudes
/// frozen and only the drag direction updated (eq. 97 and the text after it), then the
/// sign-reversal logic (text before eq. 100): a velocity component that reverses is integrated
/// to zero and the position uses its average velocity up to the reversal; if both reverse the
/// footpad stops and stays stuck. A stuck footpad breaks away when |FXYP| > FDRAGP, taking one
/// step with the drag opposite FXYP.
pub fn advance_sliding(pad: &mut Footpad, f: &SlidingForces, dt: f64) {
    let p0 = Vector2::new(pad.position.x, pad.position.y);
    let v0 = Vector2::new(pad.velocity.x, pad.velocity.y);
    if pad.stuck {
        let applied = f.applied();
        let mag = applied.norm();
        if mag > f.drag + f.rounding {
            // Breakaway step: drag along −F̂XYP (text after eq. 100).
            let a = (applied - applied * (f.drag / mag)) / f.mass;
            let v1 = a * dt;
            let p1 = p0 + a * (0.5 * dt * dt);
            set_xy(pad, p1, v1);
            pad.stuck = false;
        }
        return;
    }
    // A footpad that friction brings to rest within the step stops there and is held (the
    // report's reversal logic: RK4 with a direction-switching drag would chatter about zero
    // instead of reversing). Deceleration along the motion with the forces frozen:
    let speed = v0.norm();
    if speed > 0.0 {
        let along = v0 / speed;
        let decel = (f.drag - f.applied().dot(&along)) / f.mass;
        if decel > 0.0 && speed <= decel * dt {
            let t_stop = speed / decel;
            set_xy(pad, p0 + v0 * (0.5 * t_stop), Vector2::zeros());
            pad.stuck = true;
            return;
        }
    }
    // RK4 on (p, v) with a(v) only.
    let k1v = f.acceleration(&v0);
    let k1p = v0;
    let v_a = v0 + k1v * (0.5 * dt);
    let k2v = f.acceleration(&v_a);
    let k2p = v_a;
    let v_b = v0 + k2v * (0.5 * dt);
    let k3v = f.acceleration(&v_b);
    let k3p = v_b;
    let v_c = v0 + k3v * dt;
    let k4v = f.acceleration(&v_c);
    let k4p = v_c;
    let mut v1 = v0 + (k1v + k2v * 2.0 + k3v * 2.0 + k4v) * (dt / 6.0);
    let mut p1 = p0 + (k1p + k2p * 2.0 + k3p * 2.0 + k4p) * (dt / 6.0);
    // Sign-reversal (stick) logic, per component. A component within rounding of zero counts
    // as zero (it neither reverses nor moves), so mirror-image footpads decide alike
    // (docs/errata.md, "Decisions at rounding level").
    let noise = VELOCITY_ROUNDING * (speed + f.applied().norm().max(f.drag) / f.mass * dt);
    let mut reversed = [false; 2];
    for i in 0..2 {
        if v1[i].abs() <= noise {
            v1[i] = 0.0;
        } else if v0[i].abs() > noise && v0[i] * v1[i] < 0.0 {
            reversed[i] = true;
            let t_star = dt * v0[i] / (v0[i] - v1[i]);
            p1[i] = p0[i] + 0.5 * v0[i] * t_star;
            v1[i] = 0.0;
        }
    }
    let at_rest = |i: usize| reversed[i] || v1[i] == 0.0;
    if (reversed[0] || reversed[1]) && at_rest(0) && at_rest(1) {
        pad.stuck = true;
        v1 = Vector2::zeros();
    }
    set_xy(pad, p1, v1);
}

fn set_xy(pad: &mut Footpad, p: Vector2<f64>, v: Vector2<f64>) {
    pad.position.x = p.x;
    pad.position.y = p.y;
    pad.velocity.x = v.x;
    pad.velocity.y = v.y;
}

/// Puts a footpad into contact at inertial X-Y `xy` on its plane (text before eq. 86;
/// docs/errata.md, "Modelling choices the report leaves open"):
/// records (XPI, YPI), keeps its in-plane velocity `v_xy` unless it is locked (OBST > 0), and
/// sets its normal velocity to `v_normal` (m/s): 0 on the rigid surface (a plastic impact of its
/// own mass), its own on soil, where it penetrates (eq. 103).
pub fn touch_down(
    pad: &mut Footpad,
    surface: &PadSurface,
    xy: Vector2<f64>,
    v_xy: Vector2<f64>,
    v_normal: f64,
    t: f64,
) {
    pad.state = ContactState::Contact;
    pad.position = Vector3::new(xy.x, xy.y, surface.plane());
    if pad.first_contact.is_none() {
        pad.touchdown_xy = xy;
    }
    let v = if surface.locked() {
        Vector2::zeros()
    } else {
        v_xy
    };
    pad.velocity = Vector3::new(v.x, v.y, v_normal);
    pad.acceleration = Vector3::zeros();
    pad.walled = surface.locked();
    pad.stuck = !surface.locked() && v == Vector2::zeros();
    pad.first_contact.get_or_insert(t);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pad(v: Vector2<f64>) -> Footpad {
        Footpad {
            state: ContactState::Contact,
            velocity: Vector3::new(v.x, v.y, 0.0),
            ..Default::default()
        }
    }

    #[test]
    fn friction_stops_a_sliding_pad_and_holds_it() {
        let f = SlidingForces {
            gear_xy: Vector2::zeros(),
            curb_xy: Vector2::zeros(),
            drag: 10.0,
            gravity_xy: Vector2::zeros(),
            fzi: 0.0,
            mass: 1.0,
            rounding: 0.0,
        };
        let mut p = pad(Vector2::new(1.0, 0.5));
        for _ in 0..20 {
            advance_sliding(&mut p, &f, 0.01);
        }
        assert!(p.stuck);
        assert_eq!(p.velocity, Vector3::zeros());
        // Stopping distance v²/(2a) along the initial direction = 1.25/20.
        let d = Vector2::new(p.position.x, p.position.y).norm();
        assert!((d - 1.25 / 20.0).abs() < 2e-3, "{d}");
        // Held while the applied force is below the drag; breaks away above it.
        let weak = SlidingForces {
            gear_xy: Vector2::new(5.0, 0.0),
            ..f
        };
        advance_sliding(&mut p, &weak, 0.01);
        assert!(p.stuck);
        let strong = SlidingForces {
            gear_xy: Vector2::new(15.0, 0.0),
            ..f
        };
        advance_sliding(&mut p, &strong, 0.01);
        assert!(!p.stuck && p.velocity.x > 0.0);
        assert!((p.velocity.x - 0.05).abs() < 1e-12, "(15 − 10)/1 · 0.01");
    }

    #[test]
    fn a_stuck_pad_under_rounding_level_loads_stays_stuck() {
        // At touchdown a footpad carries no drag yet (FZI = 0) and its gear force is zero up to
        // rounding: it does not break away, whatever that rounding's sign.
        let f = SlidingForces {
            gear_xy: Vector2::new(9.8e-14, -6.3e-14),
            curb_xy: Vector2::zeros(),
            drag: 0.0,
            gravity_xy: Vector2::zeros(),
            fzi: 0.0,
            mass: 0.2,
            rounding: 1e-6,
        };
        let mut p = pad(Vector2::zeros());
        p.stuck = true;
        advance_sliding(&mut p, &f, 1e-4);
        assert!(p.stuck);
        assert_eq!(p.velocity, Vector3::zeros());
        let pulled = SlidingForces {
            gear_xy: Vector2::new(1e-3, 0.0),
            ..f
        };
        advance_sliding(&mut p, &pulled, 1e-4);
        assert!(!p.stuck, "a load above rounding breaks it away");
    }

    #[test]
    fn frictionless_pad_follows_constant_force_exactly() {
        let f = SlidingForces {
            gear_xy: Vector2::new(2.0, -1.0),
            curb_xy: Vector2::zeros(),
            drag: 0.0,
            gravity_xy: Vector2::new(0.0, 0.5),
            fzi: 0.0,
            mass: 2.0,
            rounding: 0.0,
        };
        let mut p = pad(Vector2::new(0.3, 0.0));
        advance_sliding(&mut p, &f, 0.1);
        // a = (1, 0): x = 0.3·0.1 + 0.5·1·0.01, v = 0.4; y: a = 0, v stays 0 (not a reversal)
        assert!((p.position.x - 0.035).abs() < 1e-12);
        assert!((p.velocity.x - 0.4).abs() < 1e-12);
        assert_eq!(p.velocity.y, 0.0);
        assert!(!p.stuck);
    }
}
