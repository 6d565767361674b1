//! The rigid vehicle's state and its kinematics: position, velocity and acceleration of the
//! centre of mass (eqs. 10-12), the attitude as Euler angles (eqs. 5-9, `touchdown_frames`) or
//! a unit quaternion, the body rates (eqs. 13-15) and the slosh amplitude (eq. 109); and its
//! packing into the integrated part [`Ode`] a Runge–Kutta stage advances.

use crate::integrator::{self, Ode};
use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector2, Vector3};
use touchdown_frames::{EulerTrig, GIMBAL_LOCK_COS};
use touchdown_scenario::schema::AttitudeForm;

/// Rigid-vehicle state (inertial frame; Euler angles relative to the surface frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VehicleState {
    /// Centre-of-mass position, m.
    pub position: Vector3<f64>,
    /// Centre-of-mass velocity, m/s.
    pub velocity: Vector3<f64>,
    /// Centre-of-mass acceleration, m/s² (including gravity).
    pub acceleration: Vector3<f64>,
    /// Euler angles θ, rad, with their sines and cosines (set with T_BI, used by eqs. 5-9).
    pub euler: EulerTrig,
    /// Euler rates θ̇, rad/s.
    pub theta_dot: Vector3<f64>,
    /// Euler accelerations θ̈, rad/s².
    pub theta_ddot: Vector3<f64>,
    /// Body rates ω, rad/s.
    pub omega: Vector3<f64>,
    /// Body angular acceleration ω̇, rad/s² (eqs. 13-15).
    pub omega_dot: Vector3<f64>,
    /// T_BI (eq. 3) at θ (or from the quaternion).
    pub t_bi: Matrix3<f64>,
    /// Body → inertial unit quaternion (with `integrator.attitude = "quaternion"`; else the
    /// quaternion of the touchdown attitude, unused).
    pub quaternion: Quaternion<f64>,
    /// Slosh amplitude q (X_B, Y_B), m (eq. 109; zero without sloshing).
    pub slosh_q: Vector2<f64>,
    /// Slosh rate q̇, m/s.
    pub slosh_q_dot: Vector2<f64>,
    /// Slosh acceleration q̈, m/s².
    pub slosh_q_ddot: Vector2<f64>,
}

impl VehicleState {
    /// Sets θ (and T_BI, ω = T_EB·θ̇, eq. 6).
    pub(crate) fn set_attitude(&mut self, theta: Vector3<f64>, theta_dot: Vector3<f64>) {
        self.euler = EulerTrig::new(&theta);
        self.theta_dot = theta_dot;
        self.t_bi = self.euler.t_bi();
        self.omega = self.euler.t_eb() * theta_dot; // eq. (6)
    }

    /// Sets θ and ω (rad, rad/s), with θ̇ = T_BE·ω (eq. 7) and T_BI.
    fn set_euler(&mut self, theta: Vector3<f64>, omega: Vector3<f64>) {
        self.euler = EulerTrig::new(&theta);
        self.omega = omega;
        self.t_bi = self.euler.t_bi();
        self.theta_dot = self.euler.t_be() * omega; // eq. (7)
    }

    /// Sets the attitude from a quaternion `q` (normalised here) and ω (rad/s); θ is read from
    /// T_BI for the output, θ̇ by eq. (7) where it is defined.
    fn set_quaternion(&mut self, q: Quaternion<f64>, omega: Vector3<f64>) {
        let q = UnitQuaternion::from_quaternion(q);
        self.quaternion = q.into_inner();
        self.omega = omega;
        self.t_bi = q.to_rotation_matrix().into_inner();
        self.euler = EulerTrig::new(&touchdown_frames::euler_from_t_bi(&self.t_bi));
        self.theta_dot = if self.euler.cos.y.abs() < GIMBAL_LOCK_COS {
            Vector3::zeros()
        } else {
            self.euler.t_be() * omega
        };
    }

    /// The integrated part of the state.
    pub(crate) fn ode(&self) -> Ode {
        Ode {
            position: self.position,
            velocity: self.velocity,
            theta: self.euler.theta,
            quaternion: self.quaternion,
            omega: self.omega,
            slosh_q: self.slosh_q,
            slosh_q_dot: self.slosh_q_dot,
        }
    }

    /// Its time derivative (the accelerations set), the attitude in the form `form` (the other
    /// form's rate is zero).
    pub(crate) fn rate(&self, form: AttitudeForm) -> Ode {
        let (theta, quaternion) = match form {
            AttitudeForm::Euler => (self.theta_dot, Quaternion::new(0.0, 0.0, 0.0, 0.0)),
            AttitudeForm::Quaternion => (
                Vector3::zeros(),
                integrator::quaternion_rate(&self.quaternion, &self.omega),
            ),
        };
        Ode {
            position: self.velocity,
            velocity: self.acceleration,
            theta,
            quaternion,
            omega: self.omega_dot,
            slosh_q: self.slosh_q_dot,
            slosh_q_dot: self.slosh_q_ddot,
        }
    }

    /// Sets the integrated part of the state from `y`, the attitude in the form `form`.
    pub(crate) fn set_ode(&mut self, y: &Ode, form: AttitudeForm) {
        self.position = y.position;
        self.velocity = y.velocity;
        self.slosh_q = y.slosh_q;
        self.slosh_q_dot = y.slosh_q_dot;
        match form {
            AttitudeForm::Euler => self.set_euler(y.theta, y.omega),
            AttitudeForm::Quaternion => self.set_quaternion(y.quaternion, y.omega),
        }
    }

    /// Inertial position of a body-fixed point `b` (body axes), m.
    pub fn point(&self, b: &Vector3<f64>) -> Vector3<f64> {
        self.position + self.t_bi * b
    }

    /// Inertial velocity of a body-fixed point `b`, m/s.
    pub fn point_velocity(&self, b: &Vector3<f64>) -> Vector3<f64> {
        self.velocity + self.t_bi * self.omega.cross(b)
    }

    /// Angular velocity in inertial axes, rad/s.
    pub fn omega_inertial(&self) -> Vector3<f64> {
        self.t_bi * self.omega
    }
}
