//! The vehicle-level mechanisms a multibody engine applies to its vehicle body as an external
//! force and torque: the descent engine with its nozzle (eqs. 69-74) and the RCS (eqs. 75-82),
//! the same laws the core applies (`touchdown_laws::scene::Propulsion`). The loads are
//! evaluated at the state before a step and held over it (the engines' user forces are
//! explicit), their work is booked on the step's displacement and rotation, and the nozzle
//! crush is committed at each state once the loads there are evaluated (as the core commits
//! after evaluating its accepted state: the rim pushes with the crush of the state before).

use crate::motion::{BodyMotion, Fault};
use nalgebra::Vector3;
use touchdown_laws::scene::{Attitude, Propulsion};
use touchdown_record::Law;
use touchdown_scenario::model::Mechanism;
use touchdown_scenario::{Scenario, ScenarioError};

/// The propulsion of a multibody landing and the loads it applies over the current step.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct VehicleLoads {
    /// The scene's engine and RCS.
    pub propulsion: Propulsion,
    /// The committed nozzle crush (shortening along Z_B), m.
    pub nozzle_crush: f64,
    /// Force on the vehicle's centre of mass over the current step, N, inertial axes.
    pub force: Vector3<f64>,
    /// Torque on the vehicle over the current step, N·m, inertial axes.
    pub torque: Vector3<f64>,
    /// The driving mechanisms' part (thrust and RCS) of `force` and `torque`, N and N·m,
    /// inertial axes: their positive work is energy put in (the balance's scale).
    pub driving: (Vector3<f64>, Vector3<f64>),
    /// Evaluations so far (one per step).
    evaluations: u64,
}

impl VehicleLoads {
    /// What `sc` declares of the engine and the RCS (nothing evaluated without them), for an
    /// engine stepping `dt` (s): the loads are held over a step, so the nozzle's rim is arrested
    /// within one.
    pub fn new(sc: &Scenario, dt: f64) -> Result<VehicleLoads, ScenarioError> {
        Ok(VehicleLoads {
            propulsion: Propulsion::from_scenario(sc, dt)?,
            ..Default::default()
        })
    }

    /// Whether the scene declares neither an engine nor an RCS.
    pub fn is_empty(&self) -> bool {
        self.propulsion.is_empty()
    }

    /// Evaluates the loads at time `t` (s) with the vehicle in state `v`, `first_contact`
    /// giving its first footpad contact (s; asked only by a translating RCS), for the coming
    /// step, then commits the nozzle crush at `v`; a non-finite load is a fault of the
    /// mechanism that produced it.
    pub fn evaluate(
        &mut self,
        t: f64,
        v: &BodyMotion,
        first_contact: impl Fn() -> Option<f64>,
    ) -> Result<(), Fault> {
        if self.is_empty() {
            return Ok(());
        }
        self.evaluations += 1;
        let r = &v.rotation;
        let omega = r.transpose() * v.angular_velocity;
        let velocity = r.transpose() * v.velocity;
        let theta = touchdown_frames::euler_from_t_bi(r);
        let attitude = Attitude {
            position: &v.position,
            velocity: &velocity,
            t_bi: r,
            theta: &theta,
            omega: &omega,
        };
        let body = (self.propulsion).loads(t, first_contact, &attitude, self.nozzle_crush);
        (self.propulsion).commit(&v.position, r, &mut self.nozzle_crush);
        self.force = r * body.force; // eqs. (74), (82)
        self.torque = r * body.torque;
        self.driving = (r * body.driving.0, r * body.driving.1);
        if (self.force.norm() + self.torque.norm()).is_finite() {
            Ok(())
        } else {
            Err(Fault {
                law: if self.propulsion.engine.is_some() {
                    Law::Thrust
                } else {
                    Law::Rcs
                },
                leg: None,
                message: format!(
                    "non-finite applied load: force {:?} N, torque {:?} N·m",
                    self.force, self.torque
                ),
            })
        }
    }

    /// Work of the loads held over the step from `before` to `after` (`dt` s long) on the
    /// vehicle, J: the force on the centre of mass's displacement, the torque on the mean
    /// angular velocity; all the loads, and their driving part.
    pub fn step_work(&self, before: &BodyMotion, after: &BodyMotion, dt: f64) -> StepWork {
        if self.is_empty() {
            return StepWork::default();
        }
        let displacement = after.position - before.position;
        let turn = 0.5 * (before.angular_velocity + after.angular_velocity) * dt;
        StepWork {
            applied: self.force.dot(&displacement) + self.torque.dot(&turn),
            driving: self.driving.0.dot(&displacement) + self.driving.1.dot(&turn),
        }
    }

    /// Evaluations of each declared engine or RCS mechanism so far.
    pub fn evaluations(&self) -> impl Iterator<Item = (Mechanism, u64)> + '_ {
        self.propulsion.mechanisms().map(|m| (m, self.evaluations))
    }
}

/// Work of the vehicle-level loads over one step, J: all of them, and their driving part.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StepWork {
    /// Work of every vehicle-level load, J.
    pub applied: f64,
    /// Work of the thrust and the RCS, J.
    pub driving: f64,
}
