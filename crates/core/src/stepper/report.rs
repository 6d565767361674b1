//! The report's integration scheme: the linear-acceleration predictor-corrector of
//! eqs. (20)-(24), one update per degree of freedom (position, Euler angles, slosh amplitude),
//! and its step-size rule, eq. (25).

use super::{limit_step, Advance, Scratch, Stepper};
use crate::gear::GearState;
use crate::ledger::Quadrature;
use crate::loads::Loads;
use crate::model::Model;
use crate::state::State;
use crate::surface::ContactState;
use crate::vehicle::VehicleState;
use nalgebra::Vector3;
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
    fn advance(
        &mut self,
        model: &Model,
        state: &mut State,
        old: &VehicleState,
    ) -> Result<Advance, RunError> {
        let dt = limit_step(model, state, step_size(model, state));
        let pads = state.advance_pads(model, dt, old);
        let trial_power = predict_correct(model, state, &mut self.scratch, dt, old)?;
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
fn step_size(model: &Model, state: &State) -> f64 {
    let it = &model.integrator;
    let v = &state.vehicle;
    let mut vel: f64 = 0.0;
    for p in &state.pads {
        let rel = if model.inertial || p.state == ContactState::Contact {
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
    model: &Model,
    state: &mut State,
    scratch: &mut Scratch,
    dt: f64,
    old: &VehicleState,
) -> Result<f64, RunError> {
    let slosh = model.mechanisms.slosh.is_some();
    // 3. predictor, c = 0 (eqs. 22-23); the footpads off the surface too (eqs. 16-18)
    let inertial = model.inertial;
    for p in state.pads.iter_mut() {
        if inertial && p.state != ContactState::Contact {
            (p.position, p.velocity) = predict(p.position, p.velocity, p.acceleration, dt);
        }
    }
    let mut pred = *old;
    (pred.position, pred.velocity) = predict(old.position, old.velocity, old.acceleration, dt);
    let (theta, theta_dot) = predict(old.euler.theta, old.theta_dot, old.theta_ddot, dt);
    pred.set_attitude(theta, theta_dot);
    if slosh {
        (pred.slosh_q, pred.slosh_q_dot) =
            predict(old.slosh_q, old.slosh_q_dot, old.slosh_q_ddot, dt);
    }
    // 4. trial evaluation
    let mut loads = state.loads(model, state.t + dt, &pred, &mut scratch.trial)?;
    state.evaluations += 1;
    // 5. corrector. The footpads off the surface first (`correct_footpads`): the change of
    // their primary's force the implicit correction finds is the trial's, on the footpad, on
    // the vehicle and in the ledger alike.
    if inertial {
        correct_footpads(model, state, &pred, scratch, &mut loads, dt);
    }
    state.accelerate(model, &mut pred, &loads)?;
    // the vehicle: c = (a* − a_k)/Δt (eq. 24) in eqs. (22)-(23)
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
        old.euler.theta,
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

/// A footpad's corrected state and the change of its primary's force the correction found.
struct Corrected {
    /// Position, m, and velocity, m/s, inertial.
    position: Vector3<f64>,
    velocity: Vector3<f64>,
    /// The primary strut's axis V̂2P, body axes.
    axis: Vector3<f64>,
    /// The change of its force FCP over the trial's, N (compression positive).
    force: f64,
}

/// Step 5 of the report's scheme for the footpads off the surface: each corrected by
/// [`correct_footpad`], the change of its primary's force put into the trial's forces
/// (`scratch.trial`) and into `loads` on the vehicle, summed in the legs' order
/// (crate::summation), in the evaluation's per-leg buffers.
fn correct_footpads(
    model: &Model,
    state: &mut State,
    pred: &VehicleState,
    scratch: &mut Scratch,
    loads: &mut Loads,
    dt: f64,
) {
    let (mut leg_force, mut leg_torque) = std::mem::take(&mut state.leg_loads);
    leg_force.fill(Vector3::zeros());
    leg_torque.fill(Vector3::zeros());
    for i in 0..state.pads.len() {
        if state.pads[i].state != ContactState::Contact {
            let c = correct_footpad(
                model,
                state,
                i,
                pred,
                (&scratch.previous[i], &scratch.trial[i]),
                dt,
            );
            let bp = pred.t_bi.transpose() * (state.pads[i].position - pred.position);
            let on_pad = c.axis * c.force;
            let slot = &mut scratch.trial[i];
            slot.fcp += c.force;
            slot.f2p += c.force;
            slot.fp += on_pad;
            leg_torque[i] = bp.cross(&(-on_pad)); // eq. (66)
            leg_force[i] = -(pred.t_bi * on_pad); // eqs. (67)-(68)
            let pad = &mut state.pads[i];
            (pad.position, pad.velocity) = (c.position, c.velocity);
        }
    }
    loads.force += model.sum_order.sum(&leg_force);
    loads.torque += model.sum_order.sum(&leg_torque);
    state.leg_loads = (leg_force, leg_torque);
}

/// The corrector of footpad `i` off the surface over `dt` (s), the vehicle predicted at `pred`
/// and the footpad's gear at the start of the step and at the prediction in `gear`: the
/// average-acceleration rule x₁ = x_k + u_k·Δt + (a_k + a₁)·Δt²/4, u₁ = u_k + (a_k + a₁)·Δt/2,
/// with a₁ = a* + K·(x₁ − x*) linearised about the prediction x* along the primary strut:
/// K = −(k/PMASS)·ŵŵᵀ, ŵ the strut's axis as the footpad can move (a wall leaves its vertical
/// part), k the secant of the strut's law over the step bounded by its branch's slope (no
/// spring in its free play). Stable for any stiffness of that law (docs/errata.md, "Footpads
/// with inertia", "Numerics").
fn correct_footpad(
    model: &Model,
    state: &State,
    i: usize,
    pred: &VehicleState,
    (start, trial): (&GearState, &GearState),
    dt: f64,
) -> Corrected {
    let pad = &state.pads[i];
    let m = model.footpad_mass;
    let u0 = state.pad_start[i].1;
    let a0 = pad.acceleration;
    let a_star = state.pad_acceleration(model, i, pred, trial);
    let bp = pred.t_bi.transpose() * (pad.position - pred.position);
    let axis = (bp - model.legs[i].b2).normalize();
    let inertial_axis = pred.t_bi * axis;
    let w = if pad.walled {
        Vector3::new(0.0, 0.0, inertial_axis.z)
    } else {
        inertial_axis
    };
    // The law's secant over the step (regularised within 1e-9 of the strut's length, where a
    // stroke change is rounding), at most its stiffest slope: no state decides it at rounding
    // level, and a strut in its free play or on a plateau is no spring.
    let stiffest = model.laws.primary.honeycomb.stop.stiffest_rate();
    let dc = trial.primary_stroke - start.primary_stroke;
    let eps = 1e-9 * model.legs[i].l2p;
    let k = ((trial.fcp - start.fcp) * dc / (dc * dc + eps * eps)).clamp(0.0, stiffest);
    // (I + α·ŵŵᵀ)·δ = (a* − a_k)·Δt²/4 with α = k·Δt²/(4·PMASS), by Sherman–Morrison
    let alpha = k * dt * dt / (4.0 * m);
    let d0 = (a_star - a0) * (0.25 * dt * dt);
    let delta = d0 - w * (alpha * w.dot(&d0) / (1.0 + alpha * w.norm_squared()));
    // the compression stroke changes by −ŵ·δ: FCP by −k·ŵ·δ
    let force = -k * w.dot(&delta);
    let a1 = a_star + w * (force / m);
    Corrected {
        position: pad.position + delta,
        velocity: u0 + (a0 + a1) * (0.5 * dt),
        axis,
        force,
    }
}
