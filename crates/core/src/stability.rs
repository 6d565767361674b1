//! Stability distance, overturning velocity and the stable-landing conditions, eqs. (105)-(107)
//! and the text after them (review A16).
//!
//! Walls are vertical planes (parallel to G) through adjacent footpads, in leg order, which the
//! scenario guarantees is counter-clockwise seen from above. With ACM = r_A − r_CM and
//! n̂ = G×AB/|G×AB| (the outward normal), SD = ACM·n̂ is positive while the centre of mass is
//! inside the wall.

use nalgebra::Vector3;
use serde::Serialize;

/// Landing outcome.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Outcome {
    /// All four conditions of a stable landing held at one instant.
    Stable,
    /// The centre of mass crossed a stability wall.
    Unstable,
    /// Neither before the end time.
    Undecided,
}

/// Stability distance of the centre of mass `cm` to the wall through footpads `a` → `b`, m,
/// and the wall's outward unit normal, eq. (105). `None` if the wall is parallel to G.
pub fn stability_distance(
    gravity: &Vector3<f64>,
    cm: &Vector3<f64>,
    a: &Vector3<f64>,
    b: &Vector3<f64>,
) -> Option<(f64, Vector3<f64>)> {
    let ab = b - a;
    let n = gravity.cross(&ab);
    let len = n.norm();
    if len <= 1e-12 * gravity.norm() * ab.norm() {
        return None;
    }
    let n = n / len;
    Some(((a - cm).dot(&n), n)) // eq. (105); eq. (106): SD_vec = SD·n̂
}

/// Overturning velocity, m/s, eq. (107) with n̂ in place of the 0/0 direction ŜD at the
/// crossing: V_o = V·n̂_out (positive: moving out of the footprint).
pub fn overturn_velocity(v: &Vector3<f64>, n_out: &Vector3<f64>) -> f64 {
    v.dot(n_out) // eq. (107)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inside_is_positive_for_counter_clockwise_pads() {
        let g = Vector3::new(0.0, 0.0, -9.81);
        let pads = [
            Vector3::new(1.0, 0.0, 0.0),
            Vector3::new(0.0, 1.0, 0.0),
            Vector3::new(-1.0, 0.0, 0.0),
            Vector3::new(0.0, -1.0, 0.0),
        ];
        let cm = Vector3::new(0.1, 0.2, 1.0);
        for i in 0..4 {
            let (sd, n) = stability_distance(&g, &cm, &pads[i], &pads[(i + 1) % 4]).unwrap();
            assert!(sd > 0.0);
            // n points away from the footprint centre.
            assert!(n.dot(&((pads[i] + pads[(i + 1) % 4]) * 0.5)) > 0.0);
        }
        // Moving the CM outside wall 0-1 makes its SD negative, by the distance outside.
        let out = Vector3::new(1.0, 1.0, 0.5);
        let (sd, n) = stability_distance(&g, &out, &pads[0], &pads[1]).unwrap();
        assert!((sd + (2.0f64).sqrt() / 2.0).abs() < 1e-12);
        assert!(overturn_velocity(&Vector3::new(1.0, 1.0, 0.0), &n) > 0.0);
    }
}
