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
    /// Index of the leg whose footpad touches first.
    pub first_leg: usize,
}

/// Initial state of a scenario, eq. (19) corrected for holes (docs/errata.md, "Eq. (19): initial position with holes — corrected"): the footpad
/// k that is lowest relative to its own plane, k = argmin_n [(T_BI·BP_n)_z + HOLE_n], touches
/// its plane at inertial X = Y = 0, so R_cm = (0, 0, −HOLE_k) − T_BI·BP_k. An attitude given
/// relative to the horizontal is composed with the slope: T_BI = T_GI·T_BG (docs/errata.md, "Eq. (19): initial position with holes — corrected"). A
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
    let height = |i: usize| (t * s.legs[i].bp).z + s.surface.pads[i].hole;
    let first_leg = (0..s.legs.len()).fold(0, |k, i| if height(i) < height(k) { i } else { k });
    let position = Vector3::new(0.0, 0.0, s.surface.pads[first_leg].plane() + td.clearance)
        - t * s.legs[first_leg].bp; // eq. (19)
    InitialState {
        t_bi: t,
        theta,
        position,
        velocity: t_gi(alpha) * td.velocity_g,
        omega: td.body_rates,
        first_leg,
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
        assert!(
            gap(init.first_leg).abs() < 1e-12,
            "the first pad sits on its own plane"
        );
        assert_eq!(
            (init.position + init.t_bi * s.legs[init.first_leg].bp).xy(),
            nalgebra::Vector2::zeros()
        );
        for i in 0..s.legs.len() {
            assert!(gap(i) >= -1e-12, "pad {} starts below its plane", i + 1);
        }
        // Attitude relative to the horizontal: the body Z axis is tilted 5° from Z_G, and the
        // velocity is given in the gravity frame.
        let z_b_in_g = t_ig(s.surface.slope) * init.t_bi * Vector3::z();
        assert!((z_b_in_g.z - (5.0f64).to_radians().cos()).abs() < 1e-12);
        assert!((t_ig(s.surface.slope) * init.velocity - s.touchdown.velocity_g).norm() < 1e-12);
    }
}
