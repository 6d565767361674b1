//! The state a landing starts from, eq. (19) corrected for holes: the same for every engine, so
//! that all of them start a landing from the same state.

use nalgebra::{Matrix3, Vector3};
use touchdown_frames::{euler_from_t_bi, t_bi, t_gi};

/// The state a landing starts from, in the inertial frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InitialState {
    /// T_BI at touchdown.
    pub t_bi: Matrix3<f64>,
    /// Euler angles relative to the surface (inertial) frame, rad.
    pub theta: Vector3<f64>,
    /// Centre-of-mass position, m.
    pub position: Vector3<f64>,
    /// Centre-of-mass velocity, m/s (eq. 2: V_I = T_GI·V_G).
    pub velocity: Vector3<f64>,
    /// Body rates, rad/s.
    pub omega: Vector3<f64>,
}

/// Initial state of a scenario, eq. (19) corrected for holes (docs/errata.md, "Eq. (19): initial position with holes — corrected"): the footpad
/// k that is lowest relative to its own plane, k = argmin_n [(T_BI·BP_n)_z + HOLE_n], touches
/// its plane, with the centre of mass above the inertial origin: R_cm = (0, 0, −HOLE_k −
/// (T_BI·BP_k)_z) (the report puts footpad k at X = Y = 0; a placement by the centre of mass
/// does not depend on which of two equally low footpads is k, so a landing and its mirror image
/// or renumbering start from positions that are exact images: docs/errata.md, "Decisions at
/// rounding level"). An attitude given relative to the horizontal is composed with the slope:
/// T_BI = T_GI·T_BG (docs/errata.md, "Eq. (19): initial position with holes — corrected"). A
/// `touchdown.clearance` lifts the whole vehicle by that height along the surface normal.
pub fn initial_state(s: &crate::Scenario) -> InitialState {
    let td = &s.touchdown;
    let alpha = s.surface.slope;
    let t_bi0 = match td.attitude_reference {
        crate::schema::AttitudeReference::Surface => t_bi(&td.attitude),
        crate::schema::AttitudeReference::Horizontal => t_gi(alpha) * t_bi(&td.attitude),
    };
    let theta = euler_from_t_bi(&t_bi0);
    let t = t_bi(&theta);
    // eq. (19): the height of the centre of mass that puts the lowest footpad on its plane
    let height = (0..s.legs.len())
        .map(|i| s.surface.pads[i].plane() - (t * s.legs[i].bp).z)
        .fold(f64::NEG_INFINITY, f64::max);
    InitialState {
        t_bi: t,
        theta,
        position: Vector3::new(0.0, 0.0, height + td.clearance),
        velocity: t_gi(alpha) * td.velocity_g,
        omega: td.body_rates,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use touchdown_frames::t_ig;

    #[test]
    fn initial_state_puts_the_lowest_pad_on_its_plane() {
        // Table I 2-2 (footnote reading): depressions under legs 1 and 2.
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../scenarios/table-i-2-2-vv8.toml");
        let s = crate::Scenario::load(path).unwrap();
        let init = initial_state(&s);
        let gap =
            |i: usize| (init.position + init.t_bi * s.legs[i].bp).z - s.surface.pads[i].plane();
        let lowest = (0..s.legs.len()).map(gap).fold(f64::INFINITY, f64::min);
        assert!(lowest.abs() < 1e-12, "the lowest pad sits on its own plane");
        assert_eq!(init.position.xy(), nalgebra::Vector2::zeros());
        // Attitude relative to the horizontal: the body Z axis is tilted 5° from Z_G, and the
        // velocity is given in the gravity frame.
        let z_b_in_g = t_ig(s.surface.slope) * init.t_bi * Vector3::z();
        assert!((z_b_in_g.z - (5.0f64).to_radians().cos()).abs() < 1e-12);
        assert!((t_ig(s.surface.slope) * init.velocity - s.touchdown.velocity_g).norm() < 1e-12);
    }
}
