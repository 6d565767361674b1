//! The report's integration scheme: the linear-acceleration predictor-corrector of
//! eqs. (20)-(24), one update per degree of freedom (position, Euler angles, slosh amplitude),
//! and its step-size rule, eq. (25).

use super::{limit_step, Advance, Scratch, Stepper};
use crate::ledger::Quadrature;
use crate::simulation::Physics;
use crate::state::VehicleState;
use crate::surface::ContactState;
use std::ops::{Add, Div, Mul};
use touchdown_record::RunError;

/// The report's predictor-corrector with its own scratch space.
#[derive(Debug, Clone)]
pub(crate) struct PredictorCorrector {
    scratch: Scratch,
}

impl PredictorCorrector {
    /// The scheme working in `scratch`.
    pub(crate) fn new(scratch: Scratch) -> PredictorCorrector {
        PredictorCorrector { scratch }
    }
}

impl Stepper for PredictorCorrector {
    fn advance(&mut self, physics: &mut Physics, old: &VehicleState) -> Result<Advance, RunError> {
        let dt = limit_step(physics, step_size(physics));
        let pads = physics.advance_pads(dt, old);
        let trial_power = predict_correct(physics, &mut self.scratch, dt, old)?;
        Ok(Advance {
            dt,
            quadrature: Quadrature::Trapezoid { trial_power },
            pads,
        })
    }

    fn scratch(&mut self) -> &mut Scratch {
        &mut self.scratch
    }
}

/// Step size by eq. (25), Δt = DIST/VEL clamped to [Δt_min, Δt_max], s.
fn step_size(physics: &Physics) -> f64 {
    let it = &physics.integrator;
    let v = &physics.vehicle;
    let mut vel: f64 = 0.0;
    for p in &physics.pads {
        let rel = if physics.inertial || p.state == ContactState::Contact {
            p.velocity - v.velocity
        } else {
            v.t_bi * v.omega.cross(&p.bp_attached)
        };
        vel = vel.max(rel.norm());
    }
    let dt = if vel > 0.0 { it.dist / vel } else { it.dt_max }; // eq. (25)
    dt.clamp(it.dt_min, it.dt_max)
}

/// A degree of freedom the scheme updates (a vector of positions, angles or amplitudes).
trait Quantity: Copy + Add<Output = Self> + Mul<f64, Output = Self> + Div<f64, Output = Self> {}

impl<T> Quantity for T where T: Copy + Add<Output = T> + Mul<f64, Output = T> + Div<f64, Output = T> {}

/// The predictor, eqs. (22)-(23) with c = 0: from value `x`, rate `x_dot` and acceleration
/// `x_ddot` at t_k, the value and rate after `dt` (s).
fn predict<T: Quantity>(x: T, x_dot: T, x_ddot: T, dt: f64) -> (T, T) {
    (
        x + x_dot * dt + x_ddot * (0.5 * dt * dt),
        x_dot + x_ddot * dt,
    )
}

/// The corrector, eqs. (22)-(23) with c = (a* − a_k)/Δt (eq. 24): from value `x`, rate
/// `x_dot` and acceleration `x_ddot` at t_k and the acceleration `trial` at the prediction,
/// the value x_k + ẋ_k·Δt + (a_k/3 + a*/6)·Δt² and the rate ẋ_k + (a_k + a*)·Δt/2 after `dt`
/// (s).
fn correct<T: Quantity>(x: T, x_dot: T, x_ddot: T, trial: T, dt: f64) -> (T, T) {
    (
        x + x_dot * dt + (x_ddot / 3.0 + trial / 6.0) * (dt * dt),
        x_dot + (x_ddot + trial) * (0.5 * dt),
    )
}

/// Steps 3-5 of the report's scheme from the accepted state `old` over `dt` (s), the trial
/// evaluated into `scratch.trial`, the corrected state written into `scratch.new`: returns the
/// vehicle-level mechanisms' power at the trial, W.
fn predict_correct(
    physics: &mut Physics,
    scratch: &mut Scratch,
    dt: f64,
    old: &VehicleState,
) -> Result<f64, RunError> {
    let slosh = physics.mechanisms.slosh.is_some();
    // 3. predictor, c = 0 (eqs. 22-23); the footpads off the surface too (eqs. 16-18)
    let inertial = physics.inertial;
    for p in physics.pads.iter_mut() {
        if inertial && p.state != ContactState::Contact {
            (p.position, p.velocity) = predict(p.position, p.velocity, p.acceleration, dt);
        }
    }
    let mut pred = *old;
    (pred.position, pred.velocity) = predict(old.position, old.velocity, old.acceleration, dt);
    let (theta, theta_dot) = predict(old.theta, old.theta_dot, old.theta_ddot, dt);
    pred.set_attitude(theta, theta_dot);
    if slosh {
        (pred.slosh_q, pred.slosh_q_dot) =
            predict(old.slosh_q, old.slosh_q_dot, old.slosh_q_ddot, dt);
    }
    // 4. trial evaluation
    let loads = physics.loads(physics.t + dt, &pred, &mut scratch.trial)?;
    physics.evaluations += 1;
    physics.accelerate(&mut pred, &loads)?;
    // 5. corrector: c = (a* − a_k)/Δt (eq. 24) in eqs. (22)-(23), the footpads off the surface
    // from their start with their accelerations at t_k and at the prediction
    for i in 0..physics.pads.len() {
        if inertial && physics.pads[i].state != ContactState::Contact {
            let trial = physics.pad_acceleration(i, &pred, &scratch.trial[i]);
            let (p0, v0) = physics.pad_start[i];
            let pad = &mut physics.pads[i];
            (pad.position, pad.velocity) = correct(p0, v0, pad.acceleration, trial, dt);
        }
    }
    let new = &mut scratch.new;
    *new = *old;
    (new.position, new.velocity) = correct(
        old.position,
        old.velocity,
        old.acceleration,
        pred.acceleration,
        dt,
    );
    let (theta, theta_dot) = correct(
        old.theta,
        old.theta_dot,
        old.theta_ddot,
        pred.theta_ddot,
        dt,
    );
    new.set_attitude(theta, theta_dot);
    if slosh {
        (new.slosh_q, new.slosh_q_dot) = correct(
            old.slosh_q,
            old.slosh_q_dot,
            old.slosh_q_ddot,
            pred.slosh_q_ddot,
            dt,
        );
    }
    Ok(loads.applied_power.applied)
}
