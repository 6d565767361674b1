//! The report's integration scheme: the linear-acceleration predictor-corrector of
//! eqs. (20)-(24), one update per degree of freedom (position, Euler angles, slosh amplitude),
//! and its step-size rule, eq. (25).

use super::secant::{secant, strut_secants};
use super::{limit_step, strides, Advance, Scratch, Stepper, Stride};
use crate::gear;
use crate::gear::GearState;
use crate::ledger::{PadWork, Quadrature};
use crate::loads::Loads;
use crate::model::Model;
use crate::state::State;
use crate::surface::ContactState;
use crate::vehicle::VehicleState;
use nalgebra::{Matrix3, Vector3};
use std::ops::{Add, Div, Mul};
use touchdown_record::RunError;
use touchdown_scenario::schema::Scheme;

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
        let (dt, explicit) = step_size(model, state);
        let dt = limit_step(model, state, dt);
        state.advance_pads(model, dt, old);
        let implicit = dt > explicit;
        let (trial_power, pads) =
            predict_correct(model, state, &mut self.scratch, dt, old, implicit)?;
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

/// Step size by eq. (25), Δt = DIST/VEL clamped to [Δt_min, Δt_max], s; Δt_max is `dt_max`
/// or, with a stride, the longest step the engaged gear allows ([`State::stride_step`]); with
/// the longest step the scheme's explicit corrector takes, s.
fn step_size(model: &Model, state: &State) -> (f64, f64) {
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
    // eq. (25); the stride is sought only where it asks for more than dt_max
    let dt = if vel > 0.0 {
        it.dist / vel
    } else {
        f64::INFINITY
    };
    let stride = if dt > it.dt_max {
        state.stride_step(model)
    } else {
        Stride::none(it.dt_max)
    };
    (dt.clamp(it.dt_min, stride.longest), stride.explicit)
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
/// evaluated into `scratch.trial`, the corrected state written into `scratch.new` (the vehicle
/// corrected `implicit`ly on its footpads on the surface, [`strides`], on a step past the
/// explicit corrector's): returns the vehicle-level mechanisms' power at the trial, W, and
/// the work on the sliding footpads, advanced again with the forces the corrector uses.
fn predict_correct(
    model: &Model,
    state: &mut State,
    scratch: &mut Scratch,
    dt: f64,
    old: &VehicleState,
    implicit: bool,
) -> Result<(f64, PadWork), RunError> {
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
    // the footpads on the surface with the gear's force the vehicle's corrector uses
    let pads = state.correct_sliding_pads(model, dt, &pred, &scratch.trial);
    state.accelerate(model, &mut pred, &loads)?;
    if implicit {
        // the vehicle on the struts of its footpads on the surface, implicit
        strides::correct_vehicle(model, state, scratch, &pred, old, dt);
    } else {
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
    }
    let new = &mut scratch.new;
    if slosh {
        (new.slosh_q, new.slosh_q_dot) = correct(
            old.slosh_q,
            old.slosh_q_dot,
            old.slosh_q_ddot,
            pred.slosh_q_ddot,
            dt,
        );
    }
    Ok((loads.applied_power.applied, pads))
}

/// A footpad's corrected state and the changes of its struts' forces the correction found.
struct Corrected {
    /// Position, m, and velocity, m/s, inertial.
    position: Vector3<f64>,
    velocity: Vector3<f64>,
    /// The change of its primary's force FCP over the trial's, N (compression positive).
    force: f64,
    /// The changes of its secondaries' forces FC31, FC41 over the trial's, N (tension
    /// positive), where the scheme corrects them (`strides`).
    secondary: Option<[f64; 2]>,
    /// The change of the gear's force on the footpad FP, body axes, N.
    on_pad: Vector3<f64>,
}

/// Step 5 of the report's scheme for the footpads off the surface: each corrected by
/// [`FreePad::primary_implicit`], the change of its primary's force put into the trial's forces
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
            let gear = (&scratch.previous[i], &scratch.trial[i]);
            let free = FreePad::new(model, state, i, pred, gear, dt);
            let c = match model.integrator.scheme {
                Scheme::Strides => free.every_strut_implicit(model),
                _ => free.primary_implicit(model),
            };
            let (bp, on_pad) = (free.bp, c.on_pad);
            let slot = &mut scratch.trial[i];
            slot.fcp += c.force;
            slot.f2p += c.force;
            if let Some(secondary) = c.secondary {
                slot.fc_secondary[0] += secondary[0];
                slot.fc_secondary[1] += secondary[1];
            }
            slot.fp += on_pad;
            leg_torque[i] = bp.cross(&(-on_pad)); // eq. (66)
            leg_force[i] = -(pred.t_bi * on_pad); // eqs. (67)-(68)
            let pad = &mut state.pads[i];
            (pad.position, pad.velocity) = (c.position, c.velocity);
        }
    }
    let (force, torque) = model.sum_order.sum_loads(&leg_force, &leg_torque);
    loads.force += force;
    loads.torque += torque;
    state.leg_loads = (leg_force, leg_torque);
}

/// Footpad `i` off the surface at the trial of a step of `dt` (s), as both correctors start
/// from it: the vehicle predicted at `pred`, its gear at the start of the step and at the
/// trial in `start` and `trial`.
struct FreePad<'a> {
    i: usize,
    dt: f64,
    pred: &'a VehicleState,
    start: &'a GearState,
    trial: &'a GearState,
    /// Its predicted position x*, m, and its velocity u_k and acceleration a_k at the start of
    /// the step, m/s and m/s², inertial.
    position: Vector3<f64>,
    u0: Vector3<f64>,
    a0: Vector3<f64>,
    /// Its acceleration at the trial a*, m/s², inertial.
    a_star: Vector3<f64>,
    /// Its position BP in the predicted vehicle's body axes, m.
    bp: Vector3<f64>,
    /// Held laterally by its wall or spikes.
    walled: bool,
}

impl<'a> FreePad<'a> {
    /// Footpad `i` of `state` over a step of `dt` (s) with the vehicle predicted at `pred`
    /// and its gear at the start of the step and at the trial in `gear`.
    fn new(
        model: &Model,
        state: &State,
        i: usize,
        pred: &'a VehicleState,
        (start, trial): (&'a GearState, &'a GearState),
        dt: f64,
    ) -> Self {
        let pad = &state.pads[i];
        FreePad {
            i,
            dt,
            pred,
            start,
            trial,
            position: pad.position,
            u0: state.pad_start[i].1,
            a0: pad.acceleration,
            a_star: state.pad_acceleration(model, i, pred, trial),
            bp: pred.t_bi.transpose() * (pad.position - pred.position),
            walled: pad.walled,
        }
    }

    /// The body-axes direction `g` in inertial axes as the footpad can move along it: a wall
    /// leaves its vertical part.
    fn movable(&self, g: &Vector3<f64>) -> Vector3<f64> {
        let w = self.pred.t_bi * g;
        if self.walled {
            Vector3::new(0.0, 0.0, w.z)
        } else {
            w
        }
    }

    /// The average-acceleration rule's correction δ = x₁ − x* with nothing but the trial's
    /// forces, (a* − a_k)·Δt²/4, m.
    fn uncorrected(&self) -> Vector3<f64> {
        (self.a_star - self.a0) * (0.25 * self.dt * self.dt)
    }

    /// The corrected footpad from δ (m) and a₁ (m/s²), with the changes of its struts'
    /// forces.
    fn corrected(
        &self,
        (delta, a1): (Vector3<f64>, Vector3<f64>),
        (force, secondary, on_pad): (f64, Option<[f64; 2]>, Vector3<f64>),
    ) -> Corrected {
        Corrected {
            position: self.position + delta,
            velocity: self.u0 + (self.a0 + a1) * (0.5 * self.dt),
            force,
            secondary,
            on_pad,
        }
    }

    /// The report's corrector: the average-acceleration rule x₁ = x_k + u_k·Δt + (a_k + a₁)·Δt²/4,
    /// u₁ = u_k + (a_k + a₁)·Δt/2, with a₁ = a* + K·(x₁ − x*) linearised about the prediction
    /// x* along the primary strut: K = −(k/PMASS)·ŵŵᵀ, ŵ the strut's axis as the footpad can
    /// move (a wall leaves its vertical part), k the secant of the strut's law over the step
    /// bounded by its branch's slope (no spring in its free play). Stable for any stiffness of
    /// that law (docs/errata.md, "Footpads with inertia", "Numerics").
    fn primary_implicit(&self, model: &Model) -> Corrected {
        let (m, dt, i) = (model.footpad_mass, self.dt, self.i);
        let axis = (self.bp - model.legs[i].b2).normalize();
        let w = self.movable(&axis);
        let stiffest = model.laws.primary.honeycomb.stop.stiffest_rate();
        let eps = 1e-9 * model.legs[i].l2p;
        let k = secant(
            (self.start.primary_stroke, self.start.fcp),
            (self.trial.primary_stroke, self.trial.fcp),
            eps,
            stiffest,
        );
        // (I + α·ŵŵᵀ)·δ = (a* − a_k)·Δt²/4 with α = k·Δt²/(4·PMASS), by Sherman–Morrison
        let alpha = k * dt * dt / (4.0 * m);
        let d0 = self.uncorrected();
        let delta = d0 - w * (alpha * w.dot(&d0) / (1.0 + alpha * w.norm_squared()));
        // the compression stroke changes by −ŵ·δ: FCP by −k·ŵ·δ
        let force = -k * w.dot(&delta);
        let a1 = self.a_star + w * (force / m);
        self.corrected((delta, a1), (force, None, axis * force))
    }

    /// The `strides` scheme's corrector: [`FreePad::primary_implicit`]'s average-acceleration
    /// rule with every strut of the gear linearised about the prediction,
    /// a₁ = a* − Σ_j ŵ_j·k_j·ŵ_j·(x₁ − x*)/PMASS, ŵ_j the gradient of strut j's stroke in the
    /// footpad's position ([`gear::stroke_gradients`], inertial, as the footpad can move) and k_j its law's secant
    /// over the step: the 3×3 system (I + Δt²/(4·PMASS)·Σ_j k_j·ŵ_jŵ_jᵀ)·δ = (a* − a_k)·Δt²/4,
    /// symmetric positive definite, by Cholesky. Stable for any stiffness of the three laws;
    /// each strut's force changes by k_j·ŵ_j·δ, the footpad's by −Σ_j ∂S_j/∂BP times it
    /// (virtual work on the massless gear) (docs/errata.md, "Long strides where the gear is
    /// soft").
    fn every_strut_implicit(&self, model: &Model) -> Corrected {
        let (m, dt) = (model.footpad_mass, self.dt);
        let (leg, laws) = (&model.legs[self.i], &model.laws);
        let (start, trial) = (self.start, self.trial);
        let gradients = gear::stroke_gradients(leg, model.arrangement, &self.bp);
        let w = gradients.each_ref().map(|g| self.movable(g));
        let k = strut_secants(leg, laws, start, trial);
        let alpha = dt * dt / (4.0 * m);
        let mut system = Matrix3::identity();
        for (wj, kj) in w.iter().zip(k) {
            system += wj * wj.transpose() * (alpha * kj);
        }
        let d0 = self.uncorrected();
        // I plus a positive semi-definite matrix: its factorisation fails only on a NaN,
        // which the step's divergence guard then reports.
        let delta = system.cholesky().map_or(d0, |c| c.solve(&d0));
        let df = [0, 1, 2].map(|j| k[j] * w[j].dot(&delta));
        let on_pad = -(gradients[0] * df[0] + gradients[1] * df[1] + gradients[2] * df[2]);
        let a1 = self.a_star - (w[0] * df[0] + w[1] * df[1] + w[2] * df[2]) / m;
        self.corrected((delta, a1), (df[0], Some([df[1], df[2]]), on_pad))
    }
}
