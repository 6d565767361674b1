//! Runge–Kutta integration of the vehicle's equations of motion, beside the report's own
//! predictor-corrector (eqs. 20-25, in [`crate::stepper::report`]): the classical fourth-order method
//! at a fixed step and the Dormand–Prince 5(4) embedded pair with error control.
//!
//! What a Runge–Kutta stage advances is [`Ode`]: the centre of mass (eqs. 10-12), the attitude
//! (Euler angles by eq. 7, or a unit quaternion), the body rates (eqs. 13-15) and the slosh
//! amplitude (eq. 109). The footpads' sliding (eq. 97) and the honeycombs' memories stay outside:
//! the footpads advance over the step with their forces frozen, as in the report, and the
//! memories are committed only at accepted states, so a stage or a rejected step changes
//! nothing but the trial it evaluates.

use nalgebra::{Quaternion, Vector2, Vector3};

/// A Runge–Kutta method as a Butcher tableau of at most [`MAX_STAGES`] stages.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tableau {
    /// Stages.
    pub stages: usize,
    /// Nodes c_i (fractions of the step).
    pub c: [f64; MAX_STAGES],
    /// Coupling coefficients a_ij (j < i).
    pub a: [[f64; MAX_STAGES]; MAX_STAGES],
    /// Weights b_i of the solution.
    pub b: [f64; MAX_STAGES],
    /// Weights of the error estimate, b_i − b̂_i (embedded pairs only).
    pub e: Option<[f64; MAX_STAGES]>,
    /// Order of the lower-order solution of an embedded pair (the error's exponent is
    /// 1/(order + 1)).
    pub error_order: u32,
    /// Whether the last stage is evaluated at the new state (first-same-as-last): its
    /// evaluation is then the accepted state's.
    pub fsal: bool,
}

/// Most stages of a tableau here.
pub const MAX_STAGES: usize = 7;

/// The classical fourth-order Runge–Kutta method.
pub const RK4: Tableau = Tableau {
    stages: 4,
    c: [0.0, 0.5, 0.5, 1.0, 0.0, 0.0, 0.0],
    a: [
        [0.0; 7],
        [0.5, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.0, 0.5, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0],
        [0.0; 7],
        [0.0; 7],
        [0.0; 7],
    ],
    b: [1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0, 0.0, 0.0, 0.0],
    e: None,
    error_order: 0,
    fsal: false,
};

/// The fifth-order weights of the Dormand–Prince pair, also its last stage's coupling
/// (first-same-as-last).
const DOPRI5_B: [f64; MAX_STAGES] = [
    35.0 / 384.0,
    0.0,
    500.0 / 1113.0,
    125.0 / 192.0,
    -2187.0 / 6784.0,
    11.0 / 84.0,
    0.0,
];

/// The Dormand–Prince 5(4) pair (Dormand & Prince 1980; Hairer, Nørsett & Wanner, table 5.2):
/// fifth-order solution, fourth-order error estimate, first-same-as-last.
pub const DOPRI5: Tableau = Tableau {
    stages: 7,
    c: [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0],
    a: [
        [0.0; 7],
        [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0, 0.0],
        [
            19372.0 / 6561.0,
            -25360.0 / 2187.0,
            64448.0 / 6561.0,
            -212.0 / 729.0,
            0.0,
            0.0,
            0.0,
        ],
        [
            9017.0 / 3168.0,
            -355.0 / 33.0,
            46732.0 / 5247.0,
            49.0 / 176.0,
            -5103.0 / 18656.0,
            0.0,
            0.0,
        ],
        DOPRI5_B,
    ],
    b: DOPRI5_B,
    e: Some([
        DOPRI5_B[0] - 5179.0 / 57600.0,
        0.0,
        500.0 / 1113.0 - 7571.0 / 16695.0,
        125.0 / 192.0 - 393.0 / 640.0,
        -2187.0 / 6784.0 + 92097.0 / 339200.0,
        11.0 / 84.0 - 187.0 / 2100.0,
        -1.0 / 40.0,
    ]),
    error_order: 4,
    fsal: true,
};

/// The vehicle state a Runge–Kutta stage advances, or its time derivative (SI, inertial frame
/// for the centre of mass, body axes for the rates).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ode {
    /// Centre of mass R, m (derivative: m/s).
    pub position: Vector3<f64>,
    /// Velocity Ṙ, m/s (derivative: m/s²).
    pub velocity: Vector3<f64>,
    /// Euler angles θ, rad (derivative θ̇ = T_BE·ω, eq. 7); unused with a quaternion.
    pub theta: Vector3<f64>,
    /// Body → inertial unit quaternion (derivative ½·q⊗(0, ω)); unused with Euler angles.
    pub quaternion: Quaternion<f64>,
    /// Body rates ω, rad/s (derivative ω̇, eqs. 13-15).
    pub omega: Vector3<f64>,
    /// Slosh amplitude q, m (eq. 109).
    pub slosh_q: Vector2<f64>,
    /// Slosh rate q̇, m/s.
    pub slosh_q_dot: Vector2<f64>,
}

impl Ode {
    /// All zero.
    pub fn zeros() -> Ode {
        Ode {
            position: Vector3::zeros(),
            velocity: Vector3::zeros(),
            theta: Vector3::zeros(),
            quaternion: Quaternion::new(0.0, 0.0, 0.0, 0.0),
            omega: Vector3::zeros(),
            slosh_q: Vector2::zeros(),
            slosh_q_dot: Vector2::zeros(),
        }
    }

    /// self + h·k.
    #[inline]
    pub fn add_scaled(&mut self, h: f64, k: &Ode) {
        self.position += k.position * h;
        self.velocity += k.velocity * h;
        self.theta += k.theta * h;
        self.quaternion += k.quaternion * h;
        self.omega += k.omega * h;
        self.slosh_q += k.slosh_q * h;
        self.slosh_q_dot += k.slosh_q_dot * h;
    }

    /// The components as one sequence (for the error norm).
    fn components(&self) -> impl Iterator<Item = f64> + '_ {
        self.position
            .iter()
            .chain(self.velocity.iter())
            .chain(self.theta.iter())
            .chain(self.quaternion.coords.iter())
            .chain(self.omega.iter())
            .chain(self.slosh_q.iter())
            .chain(self.slosh_q_dot.iter())
            .copied()
    }
}

/// The quaternion's rate for body rates ω (rad/s): q̇ = ½·q⊗(0, ω).
#[inline]
pub fn quaternion_rate(q: &Quaternion<f64>, omega: &Vector3<f64>) -> Quaternion<f64> {
    q * Quaternion::from_imag(*omega) * 0.5
}

/// The error of a step relative to the tolerances: the largest |error_i| / (atol + rtol ·
/// max(|y0_i|, |y1_i|)) over the components (≤ 1: accept).
pub fn error_ratio(y0: &Ode, y1: &Ode, error: &Ode, rtol: f64, atol: f64) -> f64 {
    y0.components()
        .zip(y1.components())
        .zip(error.components())
        .map(|((a, b), e)| e.abs() / (atol + rtol * a.abs().max(b.abs())))
        .fold(0.0, f64::max)
}

/// The next step after a step of `dt` (s) with error ratio `ratio` from a pair whose lower
/// order is `order`: dt·0.9·ratio^(−1/(order+1)), its change limited to [0.2, 5].
pub fn next_step(dt: f64, ratio: f64, order: u32) -> f64 {
    let factor = if ratio > 0.0 {
        0.9 * ratio.powf(-1.0 / f64::from(order + 1))
    } else {
        5.0
    };
    dt * factor.clamp(0.2, 5.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Integrates ẏ = λy over [0, 1] with `tab` in `n` steps; returns y(1).
    fn decay(tab: &Tableau, n: usize) -> (f64, f64) {
        let lambda = -2.0;
        let h = 1.0 / n as f64;
        let (mut y, mut err) = (1.0, 0.0f64);
        for _ in 0..n {
            let mut k = [0.0; MAX_STAGES];
            for i in 0..tab.stages {
                let yi = y + h * (0..i).map(|j| tab.a[i][j] * k[j]).sum::<f64>();
                k[i] = lambda * yi;
            }
            if let Some(e) = tab.e {
                err = err.max((h * (0..tab.stages).map(|i| e[i] * k[i]).sum::<f64>()).abs());
            }
            y += h * (0..tab.stages).map(|i| tab.b[i] * k[i]).sum::<f64>();
        }
        ((y - lambda.exp()).abs(), err)
    }

    #[test]
    fn tableaux_are_consistent() {
        for tab in [RK4, DOPRI5] {
            assert!((tab.b.iter().sum::<f64>() - 1.0).abs() < 1e-15);
            for i in 0..tab.stages {
                let row: f64 = tab.a[i].iter().sum();
                assert!(
                    (row - tab.c[i]).abs() < 1e-14,
                    "row {i}: {row} vs {}",
                    tab.c[i]
                );
            }
        }
        assert!(DOPRI5.e.unwrap().iter().sum::<f64>().abs() < 1e-15);
        // First-same-as-last: the last stage is the solution.
        assert!((0..7).all(|j| DOPRI5.a[6][j] == DOPRI5.b[j]));
    }

    #[test]
    fn methods_converge_at_their_order() {
        for (tab, order) in [(RK4, 4.0), (DOPRI5, 5.0)] {
            let (e1, _) = decay(&tab, 10);
            let (e2, _) = decay(&tab, 20);
            let observed = (e1 / e2).log2();
            assert!(
                (observed - order).abs() < 0.3,
                "order {observed} vs {order}"
            );
        }
        // The embedded estimate is of the fourth-order solution's local error: it falls by
        // about 2^5 when the step halves.
        let (_, a) = decay(&DOPRI5, 10);
        let (_, b) = decay(&DOPRI5, 20);
        assert!(((a / b).log2() - 5.0).abs() < 0.5);
    }

    #[test]
    fn quaternion_rate_keeps_the_unit_norm_and_turns_about_omega() {
        let q = Quaternion::new(0.8, 0.0, 0.6, 0.0);
        let w = Vector3::new(0.3, -1.0, 2.0);
        let qd = quaternion_rate(&q, &w);
        assert!(q.coords.dot(&qd.coords).abs() < 1e-15);
        // A turn about z at 2 rad/s from the identity: q̇ = (0, 0, 0, 1).
        let qd = quaternion_rate(&Quaternion::identity(), &Vector3::new(0.0, 0.0, 2.0));
        assert!((qd.coords - Quaternion::new(0.0, 0.0, 0.0, 1.0).coords).norm() < 1e-15);
    }

    #[test]
    fn the_step_controller_shrinks_on_error_and_grows_within_limits() {
        assert!(next_step(1.0, 2.0, 4) < 1.0);
        assert!(next_step(1.0, 0.5, 4) > 1.0);
        assert_eq!(next_step(1.0, 0.0, 4), 5.0);
        assert_eq!(next_step(1.0, 1e9, 4), 0.2);
        let y = Ode::zeros();
        let mut e = Ode::zeros();
        e.velocity.y = 2e-9;
        assert!((error_ratio(&y, &y, &e, 1e-6, 1e-9) - 2.0).abs() < 1e-12);
    }
}
