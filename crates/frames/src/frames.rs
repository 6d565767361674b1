//! Coordinate frames of TN D-7045, eqs. (1)-(4): the rotations between the inertial, gravity
//! and body frames, and gravity in the inertial frame.
//!
//! Frames: I (inertial) has its X-Y plane on the sloped surface and Z up its normal; G (gravity)
//! shares X with I and has Z_G up along −g; B (body) has its origin at the rigid-vehicle centre
//! of mass and Z_B up the vehicle centre line. `v_I = T_BI·v_B`.

use nalgebra::{Matrix3, Vector3};

/// Rotation about X by `a` rad (active).
pub fn rot_x(a: f64) -> Matrix3<f64> {
    rot_x_of(a.sin_cos())
}

/// Rotation about X by the angle of sine and cosine `(s, c)`.
fn rot_x_of((s, c): (f64, f64)) -> Matrix3<f64> {
    Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c)
}

/// Rotation about Y by `a` rad (active).
pub fn rot_y(a: f64) -> Matrix3<f64> {
    rot_y_of(a.sin_cos())
}

/// Rotation about Y by the angle of sine and cosine `(s, c)`.
fn rot_y_of((s, c): (f64, f64)) -> Matrix3<f64> {
    Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c)
}

/// Rotation about Z by `a` rad (active), by the sine and cosine of `turn_sin_cos`: whole
/// quarter turns exact, eighth turns with equal sine and cosine. So a leg at 180° lies on the
/// mirror plane of the leg at 0° bit for bit (sin π is 1.2e-16 in floating point), and the
/// report's 1-2-1 and 2-2 gears are their own mirror images exactly (docs/errata.md,
/// "Decisions at rounding level").
pub fn rot_z(a: f64) -> Matrix3<f64> {
    let (s, c) = turn_sin_cos(a);
    Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)
}

/// The sine and cosine of `a` rad, computed so that the mirror images of an angle about the
/// axes and the diagonals of a quarter turn get the mirror images of its sine and cosine, bit
/// for bit: `a` is reduced by its nearest multiple k·π/2, the rest turned by k quarters with
/// exact sign changes; a rest nearer an eighth turn than zero, ±(π/4 + d), is turned from the
/// eighth, sin = (cos d + sin d)/√2 and cos = (cos d − sin d)/√2, so that at 45° (d = 0)
/// sine and cosine are one number (the library's sin 45° and cos 45° differ by one unit in the
/// last place) and 45° ± d have each other's sine and cosine. A rest, or a d, within rounding
/// of zero (4 ulp of `a`) counts as zero. Within an ulp or two of the library's sin and cos;
/// docs/errata.md, "Decisions at rounding level".
pub(crate) fn turn_sin_cos(a: f64) -> (f64, f64) {
    use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, FRAC_PI_4, FRAC_PI_8};
    let quarters = (a / FRAC_PI_2).round();
    let mut rest = a - quarters * FRAC_PI_2;
    let rounding = 4.0 * f64::EPSILON * a.abs();
    if rest.abs() <= rounding {
        rest = 0.0;
    }
    let (s0, c0) = if rest.abs() > FRAC_PI_8 {
        let mut d = rest.abs() - FRAC_PI_4;
        if d.abs() <= rounding {
            d = 0.0;
        }
        let (sd, cd) = d.sin_cos();
        (
            ((cd + sd) * FRAC_1_SQRT_2).copysign(rest),
            (cd - sd) * FRAC_1_SQRT_2,
        )
    } else {
        rest.sin_cos()
    };
    // (the quarter turns as an integer: a float's remainder is a library call; an angle past
    // 2⁶³ quarter turns has no meaningful sine anyway)
    match (quarters as i64).rem_euclid(4) {
        0 => (s0, c0),
        1 => (c0, -s0),
        2 => (-s0, -c0),
        _ => (-c0, s0),
    }
}

/// T_IG, inertial → gravity components, eq. (1), for slope `alpha` rad.
pub fn t_ig(alpha: f64) -> Matrix3<f64> {
    let (s, c) = alpha.sin_cos();
    Matrix3::new(1.0, 0.0, 0.0, 0.0, c, s, 0.0, -s, c) // eq. (1)
}

/// T_GI = T_IGᵀ, gravity → inertial components, eq. (2).
pub fn t_gi(alpha: f64) -> Matrix3<f64> {
    t_ig(alpha).transpose() // eq. (2)
}

/// T_BI, body → inertial components, eq. (3): the intrinsic sequence θx, then θy about Y_B',
/// then θz about Z_B'', i.e. Rx(θx)·Ry(θy)·Rz(θz) (equal to the printed GO** matrix; coded
/// as the product to avoid transcription sign errors). Angles in rad.
pub fn t_bi(theta: &Vector3<f64>) -> Matrix3<f64> {
    EulerTrig::new(theta).t_bi()
}

/// The Euler angles θ (rad) with their sines and cosines, computed once for every matrix of
/// eqs. (3), (5), (6) and (9) at that attitude: each matrix is the one its own function
/// computes, bit for bit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EulerTrig {
    /// θ, rad.
    pub theta: Vector3<f64>,
    /// sin θx, sin θy, sin θz.
    pub sin: Vector3<f64>,
    /// cos θx, cos θy, cos θz.
    pub cos: Vector3<f64>,
}

impl EulerTrig {
    /// The sines and cosines of `theta` (rad); θz's by `turn_sin_cos`, so that a gear turned
    /// by whole quarter or eighth turns is its own mirror image in eq. (3) bit for bit.
    pub fn new(theta: &Vector3<f64>) -> EulerTrig {
        let [x, y] = [theta.x, theta.y].map(f64::sin_cos);
        let z = turn_sin_cos(theta.z);
        EulerTrig {
            theta: *theta,
            sin: Vector3::new(x.0, y.0, z.0),
            cos: Vector3::new(x.1, y.1, z.1),
        }
    }

    /// T_BI, eq. (3): [`t_bi`] at θ.
    pub fn t_bi(&self) -> Matrix3<f64> {
        let (s, c) = (&self.sin, &self.cos);
        let (sz, cz) = (s.z, c.z);
        // eq. (3): Rx·Ry written out, then times Rz, each entry the product's without its
        // terms in the rotations' zeros (`rot_x`·`rot_y`·`rot_z`, the test below, bit for bit)
        let p = Matrix3::new(
            c.y,
            0.0,
            s.y,
            s.x * s.y,
            c.x,
            -(s.x * c.y),
            -(c.x * s.y),
            s.x,
            c.x * c.y,
        );
        Matrix3::from_fn(|r, k| match k {
            0 => p[(r, 0)] * cz + p[(r, 1)] * sz,
            1 => p[(r, 1)] * cz - p[(r, 0)] * sz,
            _ => p[(r, 2)],
        })
    }
}

/// Euler angles (θx, θy, θz), rad, of a body → inertial rotation matrix: the inverse of
/// [`t_bi`], with θy in [−π/2, π/2].
pub fn euler_from_t_bi(t: &Matrix3<f64>) -> Vector3<f64> {
    // T = Rx Ry Rz: T[0,2] = sin θy, T[0,0] = cθy·cθz, T[0,1] = −cθy·sθz,
    // T[1,2] = −sθx·cθy, T[2,2] = cθx·cθy.
    let ty = t[(0, 2)].clamp(-1.0, 1.0).asin();
    let tx = (-t[(1, 2)]).atan2(t[(2, 2)]);
    let tz = (-t[(0, 1)]).atan2(t[(0, 0)]);
    Vector3::new(tx, ty, tz)
}

/// Gravity in the inertial frame, G_I = T_GI·(0, 0, −g) = (0, g·sin α, −g·cos α): +Y is
/// downhill for α > 0 (docs/errata.md, "Conventions fixed first").
pub fn gravity_inertial(g: f64, alpha: f64) -> Vector3<f64> {
    t_gi(alpha) * Vector3::new(0.0, 0.0, -g)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, PI};

    #[test]
    fn an_attitude_s_matrices_are_those_of_their_own_functions_bit_for_bit() {
        // Quarter turns, their neighbours, signed zeros and large angles: EulerTrig computes
        // every sine once, and must give the very matrices eqs. (3), (5), (6) give alone.
        let q = std::f64::consts::FRAC_PI_2;
        let angles = [
            0.0,
            -0.0,
            1e-300,
            0.3,
            -1.2,
            q,
            -q,
            2.0 * q,
            3.0 * q,
            q * (1.0 + 1e-15),
            0.5 * q,
            0.5 * q + 1e-16,
            7.0,
            -40.0,
        ];
        for &x in &angles {
            for &y in &angles[..6] {
                for &z in &angles {
                    let theta = Vector3::new(x, y, z);
                    let e = EulerTrig::new(&theta);
                    let bits = |m: Matrix3<f64>| m.map(f64::to_bits);
                    assert_product_of_rotations(&e.t_bi(), &theta);
                    assert_eq!(bits(e.t_be()), bits(crate::t_be(&theta)), "{theta}");
                    assert_eq!(bits(e.t_eb()), bits(crate::t_eb(&theta)), "{theta}");
                }
            }
        }
    }

    #[test]
    fn quarter_turns_about_z_are_exact() {
        let x = Vector3::new(0.5, 0.0, 0.1);
        for (deg, expected) in [
            (90.0, Vector3::new(0.0, 0.5, 0.1)),
            (180.0, Vector3::new(-0.5, 0.0, 0.1)),
            (270.0, Vector3::new(0.0, -0.5, 0.1)),
            (-90.0, Vector3::new(0.0, -0.5, 0.1)),
            (360.0, x),
        ] {
            assert_eq!(rot_z(f64::to_radians(deg)) * x, expected, "{deg}°");
        }
        // Other angles as sin and cos give them, to rounding.
        for a in [0.3, 1.9, -2.5, 4.0, 100.0] {
            let (s, c) = f64::sin_cos(a);
            let r = rot_z(a);
            assert!(
                (r[(0, 0)] - c).abs() < 1e-14 && (r[(1, 0)] - s).abs() < 1e-14,
                "{a}"
            );
        }
    }

    #[test]
    fn eighth_turns_have_one_sine_and_cosine_and_mirror_bit_for_bit() {
        // 45°, 135°, −45°, 225° as the scenario's degrees give them: |sin| and |cos| one number.
        for deg in [45.0_f64, 135.0, -45.0, 225.0, 315.0] {
            let (s, c) = turn_sin_cos(deg.to_radians());
            assert_eq!(s.abs(), c.abs(), "{deg}°");
            assert_eq!(s.abs(), std::f64::consts::FRAC_1_SQRT_2, "{deg}°");
        }
        // 45° + d and 45° − d, which the diagonal mirror maps into each other, have each
        // other's sine and cosine.
        let eighth = std::f64::consts::FRAC_PI_4;
        for d in [1e-12, 1e-6, 0.01, 0.3] {
            let (s1, c1) = turn_sin_cos(eighth + d);
            let (s2, c2) = turn_sin_cos(eighth - d);
            assert_eq!((s1, c1), (c2, s2), "d = {d}");
        }
        // Within two units in the last place of the library's sine and cosine.
        let mut a = -7.0;
        while a < 7.0 {
            let (s, c) = turn_sin_cos(a);
            let (s0, c0) = a.sin_cos();
            let ulps = |x: f64, y: f64| (x - y).abs() / f64::EPSILON;
            assert!(
                ulps(s, s0) <= 2.0 && ulps(c, c0) <= 2.0,
                "{a}: {s} {s0} {c} {c0}"
            );
            a += 0.001;
        }
    }

    /// `t` is the product of the three rotations of `theta` (eq. 3) entry by entry, bit for bit
    /// (a zero entry's sign aside: the product adds the rotations' zero terms).
    fn assert_product_of_rotations(t: &Matrix3<f64>, theta: &Vector3<f64>) {
        let product = rot_x(theta.x) * rot_y(theta.y) * rot_z(theta.z);
        for (a, b) in t.iter().zip(product.iter()) {
            let same = if *b == 0.0 {
                *a == 0.0
            } else {
                a.to_bits() == b.to_bits()
            };
            assert!(same, "θ = {theta:?}: {t} vs {product}");
        }
    }

    /// The closed form of T_BI is the product of its three rotations, over quarter turns, zeros
    /// of either sign, small and large angles on every axis.
    #[test]
    fn t_bi_is_the_product_of_its_rotations_bit_for_bit() {
        let angles = [
            0.0, -0.0, 1e-300, -3e-17, 0.1, -0.7, 1.0, FRAC_PI_2, -FRAC_PI_2, PI, 2.5, -3.0, 7.0,
            100.0,
        ];
        for x in angles {
            for y in angles {
                for z in angles {
                    let theta = Vector3::new(x, y, z);
                    assert_product_of_rotations(&t_bi(&theta), &theta);
                }
            }
        }
    }

    #[test]
    fn t_bi_matches_the_printed_go_terms() {
        let th = Vector3::new(0.3, -0.4, 1.1);
        let t = t_bi(&th);
        let (sx, cx) = th.x.sin_cos();
        let (sy, cy) = th.y.sin_cos();
        let (sz, cz) = th.z.sin_cos();
        let goxx = cy * cz;
        let goxy = cy * sz;
        let goxz = sy;
        let goyx = sx * sy * cz + cx * sz;
        let goyy = sx * sy * sz - cx * cz;
        let goyz = sx * cy;
        let gozx = cx * sy * cz - sx * sz;
        let gozy = cx * sy * sz + sx * cz;
        let gozz = cx * cy;
        let printed = Matrix3::new(goxx, -goxy, goxz, goyx, -goyy, -goyz, -gozx, gozy, gozz);
        assert!((t - printed).abs().max() < 1e-14);
    }

    #[test]
    fn transformations_are_orthogonal_and_mutually_inverse() {
        let i = Matrix3::identity();
        for th in [Vector3::new(0.3, -0.4, 1.1), Vector3::new(-2.0, 1.2, 0.4)] {
            let t = t_bi(&th);
            assert!(
                (t * t.transpose() - i).abs().max() < 1e-14,
                "T_BI orthogonal"
            );
            assert!((t.determinant() - 1.0).abs() < 1e-14, "a proper rotation");
            // eq. (4): T_IB = T_BIᵀ takes inertial components back to body components.
            let v = Vector3::new(0.2, -1.0, 3.0);
            assert!((t.transpose() * (t * v) - v).norm() < 1e-14);
        }
        for alpha in [0.0, 0.087, -0.3] {
            // eqs. (1)-(2): T_GI = T_IG⁻¹ = T_IGᵀ.
            assert!((t_gi(alpha) * t_ig(alpha) - i).abs().max() < 1e-15);
            assert!((t_ig(alpha).determinant() - 1.0).abs() < 1e-15);
        }
    }

    #[test]
    fn euler_angles_round_trip() {
        let th = Vector3::new(0.2, -0.7, 2.5);
        assert!((euler_from_t_bi(&t_bi(&th)) - th).abs().max() < 1e-12);
    }

    #[test]
    fn gravity_points_downhill_along_plus_y() {
        let g = gravity_inertial(9.81, 0.1);
        assert!(g.y > 0.0 && g.z < 0.0 && g.x == 0.0);
        assert!((g.norm() - 9.81).abs() < 1e-12);
        // An upright vehicle on slope α has θx = α relative to the surface.
        let up_g = Vector3::z();
        assert!((t_gi(0.1) * up_g - t_bi(&Vector3::new(0.1, 0.0, 0.0)) * up_g).norm() < 1e-15);
    }
}
