//! The vehicle body's motion as both multibody engines read it after a step, and what stops a
//! run before it is placed in time and state: the types the bookkeeping (`crate::book`) and the
//! vehicle-level mechanisms (`crate::applied`) share.

use nalgebra::{Matrix3, Vector3};
use touchdown_record::{Divergence, Law, StateAtStop};

/// The vehicle body's pose and velocity as the bookkeeping reads them (inertial frame = the
/// surface frame); named apart from the core's `VehicleState`, which also holds Euler angles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyMotion {
    /// Centre of mass, m.
    pub position: Vector3<f64>,
    /// Body → inertial rotation.
    pub rotation: Matrix3<f64>,
    /// Centre-of-mass velocity, m/s.
    pub velocity: Vector3<f64>,
    /// Angular velocity, rad/s, inertial axes.
    pub angular_velocity: Vector3<f64>,
}

impl BodyMotion {
    /// The pitch rate: angular velocity about the inertial X axis, rad/s.
    pub fn pitch_rate(&self) -> f64 {
        self.angular_velocity.x
    }

    /// The state as a diagnostic's numbers.
    pub fn at_stop(&self) -> StateAtStop {
        StateAtStop {
            position_m: self.position.into(),
            velocity_m_s: self.velocity.into(),
            euler_angles_rad: None,
            angular_velocity_rad_s: self.angular_velocity.into(),
        }
    }

    /// Whether every component is finite.
    pub fn is_finite(&self) -> bool {
        (self.position.norm() + self.velocity.norm() + self.angular_velocity.norm()).is_finite()
    }
}

/// What stopped a run, before it is placed in time and state ([`Fault::at`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Fault {
    /// The law or mechanism involved.
    pub law: Law,
    /// The leg's index, where one is involved.
    pub leg: Option<usize>,
    /// What happened.
    pub message: String,
}

impl Fault {
    /// The divergence at time `time` (s) with the vehicle in state `vehicle`.
    pub fn at(self, time: f64, vehicle: &BodyMotion) -> Divergence {
        Divergence::new(time, self.law, self.leg, self.message, vehicle.at_stop())
    }
}
