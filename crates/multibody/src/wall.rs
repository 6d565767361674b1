//! The obstacle wall of a locked footpad (OBST > 0, fig. 17), as the report defines it: "a
//! vertical cylindrical wall with its height equal to OBST"; "the footpad is not completely
//! free until [its] Z-position coordinate ... indicates that the footpad is above the
//! constraining obstacle". The wall alone holds the footpad laterally, from each landing until
//! it rises above the wall, bearing or not, as the core's footpad with inertia is held
//! (docs/errata.md, "Footpads with inertia"); the engines' contact friction is the surface's.
//!
//! The wall is a lateral spring-damper between the footpad and the point where it landed,
//! applied as an explicit force like the curbs': stiffness four times the primary strut's
//! stiffest rate (so the footpad's mode on the wall is twice as fast as its stiffest mode on
//! its strut, and the wall is rigid beside the gear), but no stiffer than the engine's step
//! resolves (ω·Δt ≤ 0.5 on PMASS, half of what the engines allow a strut law: on a gear too
//! stiff for that the wall is as stiff as the step allows, and never the mode that refuses a
//! step), critically damped on the footpad mass PMASS. Its work is booked with the contact's
//! (the contact-event account), as a locked footpad's lateral impulses are.

use nalgebra::{Vector2, Vector3};

/// The wall's stiffness as a multiple of the primary strut's stiffest rate.
const WALL_STIFFNESS_RATIO: f64 = 4.0;

/// The largest ω·Δt of the wall's mode on the footpad mass.
const WALL_OMEGA_DT: f64 = 0.5;

/// One footpad's obstacle wall.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ObstacleWall {
    /// The wall's height above the footpad's plane, OBST, m.
    height: f64,
    /// Lateral stiffness, N/m.
    stiffness: f64,
    /// Lateral damping, N·s/m.
    damping: f64,
    /// Where the footpad landed last (X, Y), m, while the wall holds it.
    anchor: Option<Vector2<f64>>,
}

impl ObstacleWall {
    /// The wall of a footpad of mass `mass` (kg) on a gear whose primary strut's stiffest rate
    /// is `primary_rate` (N/m), `height` (m) high, in an engine stepping `dt` (s).
    pub fn new(height: f64, mass: f64, primary_rate: f64, dt: f64) -> ObstacleWall {
        let resolved = mass * (WALL_OMEGA_DT / dt).powi(2);
        let stiffness = (WALL_STIFFNESS_RATIO * primary_rate).min(resolved);
        ObstacleWall {
            height,
            stiffness,
            damping: 2.0 * (stiffness * mass).sqrt(),
            anchor: None,
        }
    }

    /// Updates the wall after a step at whose end the footpad stands at `xy` (m) and
    /// `clearance` (m) above its plane, having received a pushing normal impulse over the step
    /// (`pushed`): a landing footpad is held where it landed; one above the wall is free.
    pub fn update(&mut self, pushed: bool, xy: Vector2<f64>, clearance: f64) {
        if clearance > self.height {
            self.anchor = None;
        } else if pushed && self.anchor.is_none() {
            self.anchor = Some(xy);
        }
    }

    /// The wall's force on the footpad at `xy` (m) moving at `velocity` (m/s, inertial), N
    /// (lateral; zero while it does not hold the footpad).
    pub fn force(&self, xy: Vector2<f64>, velocity: &Vector3<f64>) -> Vector3<f64> {
        match self.anchor {
            Some(a) => {
                let f = -(xy - a) * self.stiffness - velocity.xy() * self.damping;
                Vector3::new(f.x, f.y, 0.0)
            }
            None => Vector3::zeros(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The wall's angular frequency on the footpad mass `mass` (kg), rad/s.
    fn omega(w: &ObstacleWall, mass: f64) -> f64 {
        (w.stiffness / mass).sqrt()
    }

    fn wall() -> ObstacleWall {
        ObstacleWall::new(0.3, 0.2, 1.0e6, 2.0e-5)
    }

    #[test]
    fn the_wall_is_no_stiffer_than_the_step_resolves() {
        // 4 × 1e6 N/m on 0.2 kg: ω = 4472 rad/s, 0.09 of a 20 µs step; ×100 it would be 0.89.
        let (m, dt) = (0.2, 2.0e-5);
        assert!(
            (omega(&ObstacleWall::new(0.3, m, 1.0e6, dt), m) - (4.0e6 / m).sqrt()).abs() < 1e-9
        );
        let stiff = omega(&ObstacleWall::new(0.3, m, 1.0e8, dt), m) * dt;
        assert!((stiff - WALL_OMEGA_DT).abs() < 1e-12, "{stiff}");
    }

    #[test]
    fn a_footpad_is_held_from_its_landing_until_it_clears_the_wall() {
        let mut w = wall();
        let v = Vector3::zeros();
        w.update(false, Vector2::new(1.0, 2.0), 0.0);
        assert!(w.anchor.is_none(), "not before it lands");
        w.update(true, Vector2::new(1.0, 2.0), 0.0);
        // Lifted 0.2 m and pulled 1 mm aside: the wall pulls it back.
        w.update(false, Vector2::new(1.001, 2.0), 0.2);
        let f = w.force(Vector2::new(1.001, 2.0), &v);
        assert!(
            (f.x + 4.0e3).abs() < 1e-6 && f.y == 0.0 && f.z == 0.0,
            "{f:?}"
        );
        // Above the wall: free, and not held again until it lands.
        w.update(false, Vector2::new(1.5, 2.0), 0.31);
        assert_eq!(w.force(Vector2::new(1.5, 2.0), &v), Vector3::zeros());
        w.update(false, Vector2::new(1.5, 2.0), 0.1);
        assert!(w.anchor.is_none());
        w.update(true, Vector2::new(1.5, 2.0), 0.0);
        assert_eq!(w.force(Vector2::new(1.5, 2.0), &v), Vector3::zeros());
    }

    #[test]
    fn the_wall_is_critically_damped_on_the_footpad() {
        let w = wall();
        let (k, m) = (4.0e6, 0.2);
        assert!((omega(&w, m) - (k / m).sqrt()).abs() < 1e-9);
        let mut w = w;
        w.update(true, Vector2::zeros(), 0.0);
        let f = w.force(Vector2::zeros(), &Vector3::new(1.0, 0.0, 5.0));
        assert!((f.x + 2.0 * (k * m).sqrt()).abs() < 1e-9 && f.z == 0.0);
    }
}
