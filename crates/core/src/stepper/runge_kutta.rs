//! Runge–Kutta steppers, beyond the report: a method of [`crate::integrator`] at a fixed step
//! (`integrator.scheme = "rk4"`), and the Dormand–Prince 5(4) pair with error control and the
//! location of contact events (`"dopri5"`).

use super::{limit_step, Advance, Scratch, Stepper};
use crate::integrator::{self, Ode, Tableau, DOPRI5, MAX_STAGES, RK4};
use crate::ledger::{Quadrature, StageWork};
use crate::mechanisms::Power;
use crate::model::Model;
use crate::state::State;
use crate::surface::{ContactState, Footpad};
use crate::vehicle::VehicleState;
use nalgebra::Vector3;
use touchdown_record::RunError;

/// The rates of a footpad off the surface at each stage of a step: its velocity (m/s) and its
/// acceleration (m/s², eqs. 16-18), per leg.
type PadRates = Vec<[(Vector3<f64>, Vector3<f64>); MAX_STAGES]>;

/// A Runge–Kutta method at a fixed step `integrator.dt_max` (shortened only to land a footpad
/// or to end), with its own scratch space.
#[derive(Debug, Clone)]
pub(crate) struct Fixed {
    tableau: &'static Tableau,
    scratch: Scratch,
    pad_rates: PadRates,
}

impl Fixed {
    /// The classical fourth-order method working in `scratch`.
    pub(crate) fn rk4(scratch: Scratch, legs: usize) -> Fixed {
        Fixed {
            tableau: &RK4,
            scratch,
            pad_rates: vec![[(Vector3::zeros(), Vector3::zeros()); MAX_STAGES]; legs],
        }
    }
}

impl Stepper for Fixed {
    fn advance(
        &mut self,
        model: &Model,
        state: &mut State,
        old: &VehicleState,
    ) -> Result<Advance, RunError> {
        let dt = limit_step(model, state, model.integrator.dt_max);
        let pads = state.advance_pads(model, dt, old);
        let step = runge_kutta(
            model,
            state,
            (&mut self.scratch, &mut self.pad_rates),
            dt,
            old,
            self.tableau,
        )?;
        Ok(Advance {
            dt,
            quadrature: step.quadrature,
            pads,
        })
    }

    fn scratch(&mut self) -> &mut Scratch {
        &mut self.scratch
    }
}

/// The adaptive Dormand–Prince pair: its scratch space, the footpads at the start of the step
/// (restored when a step is rejected), its next step and its counts.
#[derive(Debug, Clone)]
pub(crate) struct Adaptive {
    scratch: Scratch,
    pad_rates: PadRates,
    pads_saved: Vec<Footpad>,
    /// The next step, s.
    next_dt: f64,
    /// Steps rejected.
    rejected: u64,
    /// Steps taken at `dt_min` without meeting the tolerance.
    forced: u64,
}

impl Adaptive {
    /// The Dormand–Prince pair working in `scratch` for `legs` legs, its first step `dt` (s).
    pub(crate) fn dopri5(scratch: Scratch, legs: usize, dt: f64) -> Adaptive {
        Adaptive {
            scratch,
            pad_rates: vec![[(Vector3::zeros(), Vector3::zeros()); MAX_STAGES]; legs],
            pads_saved: vec![Footpad::default(); legs],
            next_dt: dt,
            rejected: 0,
            forced: 0,
        }
    }
}

impl Stepper for Adaptive {
    /// One accepted step from `old`: steps whose error ratio exceeds 1 are rejected (the
    /// footpads restored) and retried shorter; a step at `dt_min` is accepted whatever its
    /// error, and counted.
    fn advance(
        &mut self,
        model: &Model,
        state: &mut State,
        old: &VehicleState,
    ) -> Result<Advance, RunError> {
        let (dt_min, dt_max) = (model.integrator.dt_min, model.integrator.dt_max);
        self.pads_saved.copy_from_slice(&state.pads);
        loop {
            let planned = self.next_dt.clamp(dt_min, dt_max);
            let dt = limit_step(model, state, planned);
            let pads = state.advance_pads(model, dt, old);
            let floor = dt <= dt_min * (1.0 + 1e-9);
            // A stage that takes a law out of its domain (a strut stretched past its bearings
            // by a step too long to see its footpad leave) rejects the step, above dt_min.
            let space = (&mut self.scratch, &mut self.pad_rates);
            let step = match runge_kutta(model, state, space, dt, old, &DOPRI5) {
                Ok(step) => step,
                Err(_) if !floor => {
                    self.rejected += 1;
                    self.next_dt = 0.5 * dt;
                    state.pads.copy_from_slice(&self.pads_saved);
                    continue;
                }
                Err(e) => return Err(e),
            };
            let ratio = if step.ratio.is_finite() {
                step.ratio
            } else {
                f64::INFINITY
            };
            // A footpad that lands or leaves within the step is located to dt_min: the step is
            // retried at half its length until it ends within dt_min of the event.
            let s = &self.scratch;
            let event = !floor && state.contact_event(model, &s.new, &s.trial);
            if (ratio <= 1.0 && !event) || floor {
                self.forced += u64::from(ratio > 1.0);
                let proposal = integrator::next_step(dt, ratio, DOPRI5.error_order);
                // A step shortened to land a footpad or to end keeps the plan it cut short.
                let shortened = dt < planned * (1.0 - 1e-9);
                self.next_dt = if shortened {
                    proposal.max(planned)
                } else {
                    proposal
                };
                return Ok(Advance {
                    dt,
                    quadrature: step.quadrature,
                    pads,
                });
            }
            self.rejected += 1;
            self.next_dt = if ratio <= 1.0 {
                0.5 * dt
            } else {
                integrator::next_step(dt, ratio, DOPRI5.error_order)
            };
            state.pads.copy_from_slice(&self.pads_saved);
        }
    }

    fn scratch(&mut self) -> &mut Scratch {
        &mut self.scratch
    }

    fn describe(&self, settings: &mut serde_json::Map<String, serde_json::Value>) {
        settings.insert("rejected_steps".into(), self.rejected.into());
        settings.insert("steps_forced_at_dt_min".into(), self.forced.into());
    }
}

/// A Runge–Kutta step: the step's quadrature and the error ratio (0 without an embedded
/// estimate).
struct Step {
    quadrature: Quadrature,
    ratio: f64,
}

/// One step of the Runge–Kutta method `tab` from the accepted state `old` of `state` over
/// `dt` (s), the sliding footpads already advanced; the new state is written into
/// `scratch.new`, the footpads off the surface advanced with the vehicle (their stage rates in
/// `pad_rates`). Each stage evaluates the forces at its own state into `scratch.trial`,
/// committing nothing. With a first-same-as-last method the last stage is the new state: it
/// comes back evaluated, its forces in `scratch.trial`.
fn runge_kutta(
    model: &Model,
    state: &mut State,
    (scratch, pad_rates): (&mut Scratch, &mut PadRates),
    dt: f64,
    old: &VehicleState,
    tab: &Tableau,
) -> Result<Step, RunError> {
    let form = model.integrator.attitude;
    let y0 = old.ode();
    let mut k = [Ode::zeros(); MAX_STAGES];
    k[0] = old.rate(form);
    for (rates, p) in pad_rates.iter_mut().zip(&state.pads) {
        rates[0] = (p.velocity, p.acceleration);
    }
    let mut work = StageWork::default();
    work.add(
        tab.b[0] * dt,
        &scratch.previous,
        state.applied_power.applied,
    );
    let mut v = *old;
    let mut last_power = Power::default();
    for i in 1..tab.stages {
        let mut y = y0;
        for (a, kj) in tab.a[i].iter().zip(&k).take(i) {
            if *a != 0.0 {
                y.add_scaled(dt * a, kj);
            }
        }
        v.set_ode(&y, form);
        for (n, rates) in pad_rates.iter().enumerate() {
            if moves_freely(model, state, n) {
                (state.pads[n].position, state.pads[n].velocity) =
                    pad_stage(state.pad_start[n], rates, &tab.a[i], i, dt);
            }
        }
        let t = state.t + tab.c[i] * dt;
        let loads = state.loads_at(model, t, &v, tab.c[i], &mut scratch.trial)?;
        state.evaluations += 1;
        state.accelerate(model, &mut v, &loads)?;
        k[i] = v.rate(form);
        for (n, rates) in pad_rates.iter_mut().enumerate() {
            if moves_freely(model, state, n) {
                let a = state.pad_acceleration(model, n, &v, &scratch.trial[n]);
                rates[i] = (state.pads[n].velocity, a);
            }
        }
        work.add(tab.b[i] * dt, &scratch.trial, loads.applied_power.applied);
        last_power = loads.applied_power;
    }
    let mut y1 = y0;
    for (b, ki) in tab.b.iter().zip(&k).take(tab.stages) {
        y1.add_scaled(dt * b, ki);
    }
    let mut pad_ratio: f64 = 0.0;
    for (n, rates) in pad_rates.iter().enumerate() {
        if !moves_freely(model, state, n) {
            continue;
        }
        let start = state.pad_start[n];
        let end = pad_stage(start, rates, &tab.b, tab.stages, dt);
        (state.pads[n].position, state.pads[n].velocity) = end;
        if let Some(e) = &tab.e {
            let origin = (Vector3::zeros(), Vector3::zeros());
            let error = pad_stage(origin, rates, e, tab.stages, dt);
            let it = &model.integrator;
            let pairs = [(start.0, end.0, error.0), (start.1, end.1, error.1)];
            for (a, b, e) in pairs {
                for c in 0..3 {
                    let scale = it.atol + it.rtol * a[c].abs().max(b[c].abs());
                    pad_ratio = pad_ratio.max(e[c].abs() / scale);
                }
            }
        }
    }
    let ratio = match &tab.e {
        Some(e) => {
            let mut error = Ode::zeros();
            for (w, ki) in e.iter().zip(&k).take(tab.stages) {
                error.add_scaled(dt * w, ki);
            }
            let it = &model.integrator;
            integrator::error_ratio(&y0, &y1, &error, it.rtol, it.atol).max(pad_ratio)
        }
        None => 0.0,
    };
    if tab.fsal {
        // The last stage's state is y1 (its coupling row is b).
        let evaluated = Some(last_power);
        let quadrature = Quadrature::Stages { work, evaluated };
        scratch.new = v;
        return Ok(Step { quadrature, ratio });
    }
    scratch.new = *old;
    scratch.new.set_ode(&y1, form);
    let evaluated = None;
    Ok(Step {
        quadrature: Quadrature::Stages { work, evaluated },
        ratio,
    })
}

/// Whether footpad `n` of `state` is integrated with the vehicle: it has inertia and is off
/// its surface.
fn moves_freely(model: &Model, state: &State, n: usize) -> bool {
    model.inertial && state.pads[n].state != ContactState::Contact
}

/// A footpad's position and velocity (m, m/s) from `start` after `dt` (s) with the weights
/// `w` of its first `stages` stage rates (a row of the tableau, its solution or its error).
fn pad_stage(
    start: (Vector3<f64>, Vector3<f64>),
    rates: &[(Vector3<f64>, Vector3<f64>); MAX_STAGES],
    w: &[f64; MAX_STAGES],
    stages: usize,
    dt: f64,
) -> (Vector3<f64>, Vector3<f64>) {
    let (mut p, mut u) = start;
    for (w, (rp, ru)) in w.iter().zip(rates).take(stages) {
        if *w != 0.0 {
            p += rp * (dt * w);
            u += ru * (dt * w);
        }
    }
    (p, u)
}
