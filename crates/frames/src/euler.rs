//! Euler-angle kinematics, eqs. (5)-(9): body rates and Euler-angle rates, and the Euler-angle
//! accelerations from the body angular acceleration.

use crate::frames::{turn_sin_cos, EulerTrig};
use nalgebra::{Matrix3, Vector3};

/// |cos θy| below which the Euler-angle kinematics are declared singular (θy → ±90°, eqs. 5
/// and 9a divide by cos θy; docs/errata.md, "Modelling choices the report leaves open", gimbal
/// lock).
pub const GIMBAL_LOCK_COS: f64 = 1e-6;

/// T_BE, body rates → Euler rates, eq. (5). Angles in rad.
pub fn t_be(theta: &Vector3<f64>) -> Matrix3<f64> {
    t_be_of(theta.y.sin_cos(), turn_sin_cos(theta.z))
}

/// T_BE (eq. 5) from the sine and cosine of θy and of θz.
fn t_be_of((sy, cy): (f64, f64), (sz, cz): (f64, f64)) -> Matrix3<f64> {
    Matrix3::new(
        cz / cy,
        -sz / cy,
        0.0,
        sz,
        cz,
        0.0,
        -sy * cz / cy,
        sy * sz / cy,
        1.0,
    ) // eq. (5)
}

/// T_EB = T_BE⁻¹, Euler rates → body rates, eq. (6); also maps the Euler-angle deviations
/// to body attitude errors in eq. (77). Angles in rad.
pub fn t_eb(theta: &Vector3<f64>) -> Matrix3<f64> {
    t_eb_of(theta.y.sin_cos(), turn_sin_cos(theta.z))
}

/// T_EB (eq. 6) from the sine and cosine of θy and of θz.
fn t_eb_of((sy, cy): (f64, f64), (sz, cz): (f64, f64)) -> Matrix3<f64> {
    Matrix3::new(cy * cz, sz, 0.0, -cy * sz, cz, 0.0, sy, 0.0, 1.0) // eq. (6)
}

impl EulerTrig {
    /// (sin θy, cos θy) and (sin θz, cos θz).
    fn yz(&self) -> ((f64, f64), (f64, f64)) {
        ((self.sin.y, self.cos.y), (self.sin.z, self.cos.z))
    }

    /// T_BE, eq. (5): [`t_be`] at θ.
    pub fn t_be(&self) -> Matrix3<f64> {
        let (y, z) = self.yz();
        t_be_of(y, z)
    }

    /// T_EB, eq. (6): [`t_eb`] at θ.
    pub fn t_eb(&self) -> Matrix3<f64> {
        let (y, z) = self.yz();
        t_eb_of(y, z)
    }

    /// Euler-angle accelerations θ̈ at θ from the body angular acceleration ω̇, eqs. (9a)-(9c),
    /// which expand the corrected eq. (8), θ̈ = T_BE·ω̇ + (dT_BE/dt)·ω (the printed eq. 8 lacks
    /// T_BE on ω̇; docs/errata.md). `theta_dot` = θ̇, `omega` = ω, `omega_dot` = ω̇ (rad/s,
    /// rad/s, rad/s²).
    pub fn euler_acceleration(
        &self,
        theta_dot: &Vector3<f64>,
        omega: &Vector3<f64>,
        omega_dot: &Vector3<f64>,
    ) -> Vector3<f64> {
        let ((sy, cy), (sz, cz)) = self.yz();
        let (td_x, td_y, td_z) = (theta_dot.x, theta_dot.y, theta_dot.z);
        // eq. (9a)
        let tdd_x = (omega_dot.x * cz - omega_dot.y * sz - 2.0 * td_z * td_y + td_y * omega.z) / cy;
        // eq. (9b), as reprinted in the equations-of-motion section (the first printing has ω̈y)
        let tdd_y = omega_dot.x * sz + omega_dot.y * cz + td_z * td_x * cy;
        // eq. (9c), uses θ̈x
        let tdd_z = -tdd_x * sy - td_x * td_y * cy + omega_dot.z;
        Vector3::new(tdd_x, tdd_y, tdd_z)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frames::t_bi;

    #[test]
    fn t_be_inverts_t_eb() {
        let th = Vector3::new(0.4, -0.9, 2.0);
        assert!((t_be(&th) * t_eb(&th) - Matrix3::identity()).abs().max() < 1e-12);
    }

    #[test]
    fn t_eb_maps_euler_rates_to_body_rates() {
        // ω in body axes from the time derivative of T_BI: [ω×] = T_BIᵀ·dT_BI/dt.
        let th = Vector3::new(0.3, 0.5, -1.2);
        let td = Vector3::new(0.7, -0.2, 1.1);
        let h = 1e-6;
        let dt = (t_bi(&(th + td * h)) - t_bi(&(th - td * h))) / (2.0 * h);
        let w = t_bi(&th).transpose() * dt;
        let omega = Vector3::new(w[(2, 1)], w[(0, 2)], w[(1, 0)]);
        assert!((omega - t_eb(&th) * td).norm() < 1e-8);
    }

    #[test]
    fn eq9_is_the_derivative_of_eq7() {
        // Along an arbitrary smooth attitude path θ(t), with ω = T_EB·θ̇ (eq. 6), eq. (9) must
        // give θ̈ from ω̇.
        let th = |t: f64| {
            Vector3::new(
                0.3 + 0.2 * t,
                -0.4 + 0.5 * t * t,
                1.0 - 0.3 * t + 0.1 * t * t * t,
            )
        };
        let h = 1e-4;
        let thd = |t: f64| (th(t + h) - th(t - h)) / (2.0 * h);
        let om = |t: f64| t_eb(&th(t)) * thd(t);
        let t0 = 0.37;
        let thdd = (th(t0 + h) - th(t0) * 2.0 + th(t0 - h)) / (h * h);
        let omega_dot = (om(t0 + h) - om(t0 - h)) / (2.0 * h);
        let analytic = EulerTrig::new(&th(t0)).euler_acceleration(&thd(t0), &om(t0), &omega_dot);
        assert!((thdd - analytic).norm() < 1e-5, "{thdd} vs {analytic}");
    }
}
