//! Rigid-vehicle equations of motion, eqs. (10)-(15).

use nalgebra::{Matrix3, Vector3};

/// The rigid vehicle's mass properties.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassProperties {
    /// M, kg (excluding the effective footpad masses).
    pub mass: f64,
    /// J, kg·m², body axes, with −Ixy, −Ixz, −Iyz off the diagonal.
    pub inertia: Matrix3<f64>,
    /// J⁻¹, 1/(kg·m²).
    pub inertia_inv: Matrix3<f64>,
}

impl MassProperties {
    /// From mass (kg) and a positive-definite inertia tensor (kg·m²).
    pub fn new(mass: f64, inertia: Matrix3<f64>) -> Self {
        let inertia_inv = inertia
            .try_inverse()
            .expect("the scenario checks the inertia is positive definite");
        MassProperties {
            mass,
            inertia,
            inertia_inv,
        }
    }

    /// Centre-of-mass acceleration, m/s², eqs. (10)-(12): `F/M + g` (F excludes gravity).
    pub fn linear_acceleration(
        &self,
        force: &Vector3<f64>,
        gravity: &Vector3<f64>,
    ) -> Vector3<f64> {
        force / self.mass + gravity // eqs. (10)-(12)
    }

    /// Body angular acceleration ω̇, rad/s², from the body torque T (N·m) and rates ω (rad/s):
    /// eqs. (13)-(15) solved as the 3×3 system J·ω̇ = T − ω×(J·ω).
    pub fn angular_acceleration(
        &self,
        torque: &Vector3<f64>,
        omega: &Vector3<f64>,
    ) -> Vector3<f64> {
        self.inertia_inv * (torque - omega.cross(&(self.inertia * omega))) // eqs. (13)-(15)
    }

    /// Kinetic energy ½·M·V² + ½·ωᵀ·J·ω, J.
    pub fn kinetic_energy(&self, v: &Vector3<f64>, omega: &Vector3<f64>) -> f64 {
        0.5 * self.mass * v.norm_squared() + 0.5 * omega.dot(&(self.inertia * omega))
    }
}

/// Body torque, N·m, written component by component as eqs. (13)-(15) with the corrections
/// of docs/errata.md (eq. 13: first bracket −Ixz·ωx; eq. 14: −Ixz·ωz, Iyz·ωy, trailing ωx).
/// `i` = (Ixx, Iyy, Izz, Ixy, Ixz, Iyz) with the report's product convention Ixy = ∫xy dm.
/// The tests' oracle for the vector form the core integrates (docs/errata.md, eqs. 13-15).
#[cfg(test)]
pub fn euler_torque(i: [f64; 6], omega: &Vector3<f64>, omega_dot: &Vector3<f64>) -> Vector3<f64> {
    let [ixx, iyy, izz, ixy, ixz, iyz] = i;
    let (wx, wy, wz) = (omega.x, omega.y, omega.z);
    let (ax, ay, az) = (omega_dot.x, omega_dot.y, omega_dot.z);
    // eq. (13), corrected
    let tx = ixx * ax - ixy * ay - ixz * az + (-ixz * wx - iyz * wy + izz * wz) * wy
        - (-ixy * wx + iyy * wy - iyz * wz) * wz;
    // eq. (14), corrected
    let ty = -ixy * ax + iyy * ay - iyz * az
        + (ixx * wx - ixy * wy - ixz * wz) * wz
        + (ixz * wx + iyz * wy - izz * wz) * wx;
    // eq. (15), as printed
    let tz = -ixz * ax - iyz * ay
        + izz * az
        + (-ixy * wx + iyy * wy - iyz * wz) * wx
        + (-ixx * wx + ixy * wy + ixz * wz) * wy;
    Vector3::new(tx, ty, tz)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> ([f64; 6], Matrix3<f64>) {
        let i = [3.0, 4.0, 5.0, 0.4, -0.3, 0.2];
        let [ixx, iyy, izz, ixy, ixz, iyz] = i;
        (
            i,
            Matrix3::new(ixx, -ixy, -ixz, -ixy, iyy, -iyz, -ixz, -iyz, izz),
        )
    }

    #[test]
    fn corrected_euler_equations_equal_the_vector_form() {
        let (i, j) = sample();
        let w = Vector3::new(0.7, -1.3, 2.1);
        let wd = Vector3::new(-0.4, 0.9, 0.25);
        let vector_form = j * wd + w.cross(&(j * w));
        assert!((euler_torque(i, &w, &wd) - vector_form).norm() < 1e-12);
    }

    #[test]
    fn angular_acceleration_solves_the_euler_equations() {
        let (i, j) = sample();
        let m = MassProperties::new(10.0, j);
        let w = Vector3::new(0.7, -1.3, 2.1);
        let t = Vector3::new(5.0, -2.0, 1.0);
        let wd = m.angular_acceleration(&t, &w);
        assert!((euler_torque(i, &w, &wd) - t).norm() < 1e-12);
    }

    #[test]
    fn printed_eq14_is_wrong_even_for_principal_axes() {
        // Printed: Iyy·ω̇y + Ixx·ωx·ωz − Izz·ωy·ωz; correct: Iyy·ω̇y + (Ixx − Izz)·ωz·ωx.
        let (ixx, iyy, izz) = (3.0, 4.0, 5.0);
        let w = Vector3::new(0.7, -1.3, 2.1);
        let printed = ixx * w.x * w.z - izz * w.y * w.z;
        let t = euler_torque([ixx, iyy, izz, 0.0, 0.0, 0.0], &w, &Vector3::zeros());
        assert!((t.y - (ixx - izz) * w.z * w.x).abs() < 1e-12);
        assert!((t.y - printed).abs() > 1.0);
    }
}
