//! The integration schemes behind one trait, `Stepper`: the report's predictor-corrector with
//! its step rule (eqs. 20-25, [`report`]), the classical fourth-order Runge–Kutta method at a
//! fixed step and the adaptive Dormand–Prince 5(4) pair ([`runge_kutta`], tableaux in
//! [`crate::integrator`]). Each owns its scratch space.
//!
//! A step (the order is not stated by the report; docs/errata.md, "Eqs. (20)-(24): the
//! integration scheme — as printed, one per degree of freedom"):
//! 1. at t_k the state, the committed hysteresis and the accelerations a_k are known;
//! 2. footpads in sliding contact advance over Δt with their forces frozen at t_k (eq. 97);
//! 3. the vehicle is predicted with c = 0 (eqs. 22-23);
//! 4. forces and accelerations are evaluated at the prediction (trial, nothing committed);
//! 5. the sliding footpads advance again over Δt from t_k with the gear's force the vehicle's
//!    corrector uses, ½(F_k + F*) (F* at the trial), and the vehicle is corrected with c from
//!    eq. (24);
//! 6. forces are evaluated at the corrected state, the contact logic runs, and if a footpad
//!    changed state the forces are evaluated again;
//! 7. the honeycomb memories are committed at that accepted state, whose accelerations are
//!    a_{k+1}; energy and stability are updated;
//! 8. the next Δt follows eq. (25).
//!
//! With a Runge–Kutta scheme (`integrator.scheme = "rk4"` or `"dopri5"`) steps 3-5 are the
//! method's stages instead: each evaluates the forces at its stage state (the sliding footpads
//! interpolated along their step, nothing committed); the strut and mechanism work is the
//! method's quadrature of the stage powers. An adaptive step whose error estimate exceeds the
//! tolerance is rejected: the footpads go back to the start and the step is retried shorter.
//! Steps 6-8 are the same for every scheme (`State::finish_step`, in [`accept`]),
//! so the hysteresis is committed only at accepted states.
//!
//! Nothing in the step allocates.

mod accept;
pub mod report;
pub mod runge_kutta;
mod secant;
mod strides;

use crate::gear::GearState;
use crate::ledger::{PadWork, Quadrature};
use crate::model::Model;
use crate::rigid_body::MassProperties;
use crate::state::State;
use crate::surface::{ContactState, Footpad};
use crate::vehicle::VehicleState;
use touchdown_laws::{Branch, GearLaws, Stop};
use touchdown_record::RunError;
use touchdown_scenario::model::Leg;
use touchdown_scenario::schema::Scheme;

/// The space a stepper works in: the new state of the step, and gear states, one per leg (the
/// accepted ones at the start of the step, the trial or Runge–Kutta stage evaluations, and the
/// spare the accepted state's evaluation is written into before it replaces the current one).
#[derive(Debug, Clone)]
pub(crate) struct Scratch {
    /// The new state of the step, its accelerations set only once it is evaluated (or when a
    /// first-same-as-last stage was).
    pub(crate) new: VehicleState,
    pub(crate) previous: Vec<GearState>,
    pub(crate) trial: Vec<GearState>,
    pub(crate) spare: Vec<GearState>,
    /// The footpads on their surface linearised about the prediction (`strides`), one per leg.
    engaged: Vec<Option<strides::Engaged>>,
}

impl Scratch {
    /// Scratch space for `legs` legs, the new state starting as `vehicle`.
    pub(crate) fn new(legs: usize, vehicle: &VehicleState) -> Scratch {
        Scratch {
            new: *vehicle,
            previous: vec![GearState::default(); legs],
            trial: vec![GearState::default(); legs],
            spare: vec![GearState::default(); legs],
            engaged: vec![None; legs],
        }
    }
}

/// Steps 2-5 of one step (the new state is in the stepper's [`Scratch`]): its length, how its
/// strut work is booked and the work of the sliding footpads.
pub(crate) struct Advance {
    /// Step length, s.
    pub(crate) dt: f64,
    /// How the strut and mechanism work of the step is booked.
    pub(crate) quadrature: Quadrature,
    /// Work of the sliding footpads over the step, J.
    pub(crate) pads: PadWork,
}

/// The longest step the report's scheme may take from an accepted state, and the longest it
/// takes with its own explicit corrector, s ([`State::stride_step`]): a longer step is
/// corrected implicitly (the `strides` scheme).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Stride {
    pub(crate) longest: f64,
    pub(crate) explicit: f64,
}

impl Stride {
    /// No stride: every step at most `dt_max` (s), corrected explicitly.
    pub(crate) fn none(dt_max: f64) -> Stride {
        Stride {
            longest: dt_max,
            explicit: dt_max,
        }
    }
}

/// An integration scheme.
pub(crate) trait Stepper {
    /// Steps 2-5 from the accepted state `old` of `state` (its model `model`): the footpads advanced, the new
    /// state computed into the scratch space. Nothing is committed.
    fn advance(
        &mut self,
        model: &Model,
        state: &mut State,
        old: &VehicleState,
    ) -> Result<Advance, RunError>;

    /// The stepper's scratch space.
    fn scratch(&mut self) -> &mut Scratch;

    /// Adds the scheme's own counts to the summary's integrator settings (none by default).
    fn describe(&self, _settings: &mut serde_json::Map<String, serde_json::Value>) {}

    /// One accepted step of `state` (see the module documentation).
    fn step(&mut self, model: &Model, state: &mut State) -> Result<(), RunError> {
        let old = state.vehicle;
        self.scratch().previous.copy_from_slice(&state.gear);
        let power_old = state.applied_power;
        let step = self.advance(model, state, &old)?;
        state.finish_step(model, &old, &step, power_old, self.scratch())
    }
}

/// The scheme a scenario chose.
#[derive(Debug, Clone)]
pub(crate) enum Schemes {
    /// The report's predictor-corrector, eqs. (20)-(25).
    Report(report::PredictorCorrector),
    /// A Runge–Kutta method at a fixed step.
    Fixed(runge_kutta::Fixed),
    /// The adaptive Dormand–Prince pair.
    Adaptive(runge_kutta::Adaptive),
}

impl Schemes {
    /// The stepper for `scheme` on `legs` legs from the state `vehicle`, its first adaptive
    /// step `dt_max` (s).
    pub(crate) fn new(scheme: Scheme, legs: usize, vehicle: &VehicleState, dt_max: f64) -> Schemes {
        let scratch = Scratch::new(legs, vehicle);
        match scheme {
            Scheme::Report | Scheme::Strides => {
                Schemes::Report(report::PredictorCorrector::new(scratch))
            }
            Scheme::Rk4 => Schemes::Fixed(runge_kutta::Fixed::rk4(scratch, legs)),
            Scheme::Dopri5 => {
                Schemes::Adaptive(runge_kutta::Adaptive::dopri5(scratch, legs, dt_max))
            }
        }
    }

    /// The chosen stepper.
    pub(crate) fn get(&mut self) -> &mut dyn Stepper {
        match self {
            Schemes::Report(s) => s,
            Schemes::Fixed(s) => s,
            Schemes::Adaptive(s) => s,
        }
    }

    /// The chosen stepper, to read.
    pub(crate) fn get_ref(&self) -> &dyn Stepper {
        match self {
            Schemes::Report(s) => s,
            Schemes::Fixed(s) => s,
            Schemes::Adaptive(s) => s,
        }
    }
}

/// The step as a fraction of the period over 2π of a footpad's fastest mode on its gear, rad:
/// ω·Δt ≤ 0.5 (docs/errata.md, "Eq. (25): VEL and first contacts"). The report's scheme damps
/// an undamped mode by 3 % of its amplitude per period there (it is stable to ω·Δt = 2), the
/// classical Runge–Kutta method by less than 0.1 %.
pub(crate) const PAD_MODE_STEP: f64 = 0.5;

/// `dt` (s) shortened so that a footpad off the surface lands on its plane (docs/errata.md,
/// "Eq. (25): VEL and first contacts — interpreted, plus two additions"), that the modes of a
/// footpad with inertia on its gear are resolved ([`PAD_MODE_STEP`]) and that the end time is
/// met.
pub(crate) fn limit_step(model: &Model, state: &State, mut dt: f64) -> f64 {
    let it = &model.integrator;
    let v = &state.vehicle;
    for i in 0..model.legs.len() {
        dt = dt.min(state.plastic_stop_step(model, i).max(it.dt_min));
    }
    for (i, (p, s)) in state.pads.iter().zip(&model.surfaces).enumerate() {
        if p.state == ContactState::Contact {
            continue;
        }
        // A footpad with inertia moves on its own; a rigid one with its attachment point.
        let (height, rate) = if model.inertial {
            dt = dt.min(state.pad_mode_step(model, i).max(it.dt_min));
            (p.position.z, p.velocity.z)
        } else {
            (
                v.point(&p.bp_attached).z,
                v.point_velocity(&p.bp_attached).z,
            )
        };
        if it.contact_step_limit {
            let gap = height - s.plane();
            let approach = -rate;
            if gap > 0.0 && approach > 0.0 && gap < approach * dt {
                dt = (gap / approach).max(it.dt_min);
            }
        }
    }
    dt.min(it.t_end - state.t).max(f64::MIN_POSITIVE)
}

/// ω·Δt up to which the `strides` scheme takes a mode of the vehicle on its gear implicitly
/// (times `integrator.mode_step` where that is below 1): its corrector, the report's with the
/// struts' forces linearised about the prediction ([`strides`]), is Newmark's rule β = 1/6,
/// γ = 1/2, stable on an undamped mode for ω·Δt ≤ √12 ≈ 3.46.
pub(crate) const IMPLICIT_MODE_STEP: f64 = 3.0;

/// ω·Δt of an engaged plastic stop's loading mode on the footpad mass: a plastic stop (e = 0)
/// releases its load at once at its deepest point, and the step that straddles that point
/// gives back about ½·(ω·Δt)² of the energy E the stop holds (the trapezoid over a force that
/// vanishes within the step), 0.5 % here (docs/errata.md, "End stops — a coefficient of
/// restitution at every hit", "The plastic stop").
pub(crate) const PLASTIC_STOP_STEP: f64 = 0.1;

/// The release error ½·E·(ω·Δt)² that needs no shorter step, as a fraction of the vehicle's
/// kinetic energy at first contact: a footpad resting on a plastic stop holds nearly nothing.
pub(crate) const PLASTIC_STOP_ERROR: f64 = 1e-6;

impl State {
    /// The longest step that resolves the release of an engaged plastic stop of leg `i`, s:
    /// ω·Δt at most [`PLASTIC_STOP_STEP`] (ω² = K_so/PMASS), or the larger ω·Δt whose release
    /// error ½·E·(ω·Δt)² is [`PLASTIC_STOP_ERROR`] of the touchdown kinetic energy, E =
    /// F²/(2·K_so) the stop's energy at its force F at the accepted state. A plastic stop not
    /// engaged that its stroke approaches (its start, or past a release its deepest point) is
    /// reached and entered by at most ω·Δt = [`PLASTIC_STOP_STEP`] within the step: a step
    /// that went deeper would load and release it within the step, unresolved (a secondary
    /// resting at its capacity on `fig-25-26` grazed a 39 kN plastic stop so, each graze
    /// putting 0.19 J into the balance at the report's 0.2 ms step,
    /// `tests/integration/physics.rs`, `a_plastic_stop_lands_on_every_engine`).
    /// Unbounded when no plastic stop is engaged or approached.
    pub(crate) fn plastic_stop_step(&self, model: &Model, i: usize) -> f64 {
        let (g, laws) = (&self.gear[i], &model.laws);
        let (p, sec) = (&laws.primary.honeycomb, &laws.secondary.honeycomb);
        let plastic = |h: &touchdown_laws::Honeycomb| h.stop.restitution == 0.0;
        if !(plastic(p) || plastic(&sec.tension) || plastic(&sec.compression)) {
            return f64::INFINITY; // every step of a landing whose stops all give something back
        }
        let stops = [
            &p.stop,
            &sec.side(g.secondary_stroke[0]).stop,
            &sec.side(g.secondary_stroke[1]).stop,
        ];
        let memory = &self.memory[i];
        let forces = laws.stop_forces(g.primary_stroke, g.secondary_stroke, memory);
        let tolerance = PLASTIC_STOP_ERROR * self.stability.initial_kinetic_energy();
        let period = |stop: &touchdown_laws::Stop| (model.footpad_mass / stop.rate).sqrt();
        let mut dt = f64::INFINITY;
        for (stop, f) in stops.into_iter().zip(forces) {
            if stop.restitution > 0.0 || f == 0.0 {
                continue;
            }
            let held = f * f / (2.0 * stop.rate);
            let omega_dt = PLASTIC_STOP_STEP.max((2.0 * tolerance / held).sqrt());
            dt = dt.min(omega_dt * period(stop));
        }
        // A stop already loading (gap < 0) is bounded above, by what it holds.
        for (stop, gap, rate) in self.stop_approaches(model, i) {
            if stop.restitution > 0.0 || rate <= 0.0 || gap < 0.0 {
                continue;
            }
            dt = dt.min(gap / rate + PLASTIC_STOP_STEP * period(stop));
        }
        dt
    }

    /// The end stops of leg `i` its strokes approach, each with the stroke's distance to where
    /// it next loads (m; negative once loading) and the stroke's rate towards it (m/s): the
    /// primary's bottoming and extension stops, each secondary's on the side it is on.
    fn stop_approaches<'m>(&self, model: &'m Model, i: usize) -> [(&'m Stop, f64, f64); 4] {
        let (g, memory) = (&self.gear[i], &self.memory[i]);
        let (p, sec) = (
            &model.laws.primary.honeycomb,
            &model.laws.secondary.honeycomb,
        );
        let secondary = |j: usize| {
            let s = g.secondary_stroke[j];
            let (x, rate, m) = if s >= 0.0 {
                (s, g.secondary_rate[j], memory.secondary[j].tension)
            } else {
                (-s, -g.secondary_rate[j], memory.secondary[j].compression)
            };
            let h = sec.side(s);
            (
                &h.stop,
                h.curve.capacity() + h.stop.slack(m.stop_depth) - x,
                rate,
            )
        };
        let c = g.primary_stroke;
        [
            (
                &p.stop,
                p.curve.capacity() + p.stop.slack(memory.primary.compression.stop_depth) - c,
                g.primary_rate,
            ),
            (
                &p.stop,
                c + p.stop.slack(memory.primary.extension_depth),
                -g.primary_rate,
            ),
            secondary(0),
            secondary(1),
        ]
    }

    /// The report scheme's longest step: `integrator.dt_max`, or with the `strides` scheme the
    /// step its engaged gear allows (docs/errata.md, "Long strides where the gear is soft").
    /// Every mode of the vehicle on its gear has ω² ≤ Σ_j k_j·g_jᵀM⁻¹g_j ≤ μ·K (the trace
    /// bound), k_j each strut's rate, K their sum ([`State::engaged_stiffness`]) and μ the
    /// struts' largest mobility ([`stroke_mobility`]). The report's corrector resolves every
    /// mode to ω·Δt ≤ `integrator.mode_step` (default 1; it is stable to ω·Δt = 2, its
    /// amplification on an undamped mode having determinant 1 − (ω·Δt)⁴/12): that step is the
    /// explicit bound. Past it the vehicle is corrected implicitly ([`strides`]), the step
    /// resolving only the modes in which a maximum can be made to ω·Δt ≤ `mode_step` and every
    /// mode to [`IMPLICIT_MODE_STEP`]·min(`mode_step`, 1). Both within [Δt_max,
    /// `stride`·Δt_max]. While
    /// a footpad slides (with friction or without), Δt_max: the implicit corrector linearises
    /// the struts about footpads that stay where they are, and a sliding footpad moves on the
    /// gear's mean force (docs/errata.md, "Sliding footpads corrected with the vehicle"). While
    /// the nozzle's rim can reach the surface within a stride, Δt_max: the rim is arrested
    /// within that step (`touchdown_laws::RimArrest`).
    pub(crate) fn stride_step(&self, model: &Model) -> Stride {
        let it = &model.integrator;
        let sliding = |p: &Footpad| p.state == ContactState::Contact && !p.walled && !p.stuck;
        if it.scheme != Scheme::Strides || self.pads.iter().any(sliding) {
            return Stride::none(it.dt_max);
        }
        let longest = it.dt_max * it.stride;
        if (model.mechanisms).nozzle_within_reach(&self.mechanisms, &self.vehicle, longest) {
            return Stride::none(it.dt_max);
        }
        let (resolved, all) = self.engaged_stiffness(model, longest);
        let step = |omega_dt: f64, k: f64| {
            let omega_squared = model.stroke_mobility * k;
            if omega_squared > 0.0 {
                omega_dt / omega_squared.sqrt()
            } else {
                f64::INFINITY
            }
        };
        let explicit = step(it.mode_step, all).clamp(it.dt_max, longest);
        // every mode within the implicit corrector's stability, whatever `mode_step` above 1
        let stable = IMPLICIT_MODE_STEP * it.mode_step.min(1.0);
        Stride {
            longest: step(it.mode_step, resolved)
                .min(step(stable, all))
                .clamp(explicit, longest),
            explicit,
        }
    }

    /// The gear's stiffness a step of `dt` (s) from the accepted state can meet, N/m, as the
    /// step must resolve it and in all: the first the rates of the struts that can make a
    /// maximum within `dt` while every footpad is on its surface ([`State::loading_rate`]),
    /// otherwise every strut's rate on the branch of its law it is on (`branch`); the second
    /// every strut's; both with the stiffest rate of every end stop its stroke reaches within
    /// `dt` at its current rate. Summed over the legs in their geometric order
    /// (crate::summation), so that a landing with its legs renumbered or mirrored takes the
    /// same steps bit for bit.
    fn engaged_stiffness(&self, model: &Model, dt: f64) -> (f64, f64) {
        let grounded = self.pads.iter().all(|p| p.state == ContactState::Contact);
        model.sum_order.fold_by(
            (0.0, 0.0),
            |i| self.leg_stiffness(model, i, dt, grounded),
            |(a, b), (c, d)| (a + c, b + d),
        )
    }

    /// [`State::engaged_stiffness`] of leg `i`'s three struts, N/m.
    fn leg_stiffness(&self, model: &Model, i: usize, dt: f64, grounded: bool) -> (f64, f64) {
        let (primary, secondary) = (
            self.primary_branch(model, i),
            self.secondary_branches(model, i),
        );
        let mut all = primary.1 + secondary[0].1 + secondary[1].1;
        let mut resolved = if grounded {
            self.loading_rate(model, i, dt, primary, secondary)
        } else {
            all
        };
        for (stop, gap, rate) in self.stop_approaches(model, i) {
            if gap >= 0.0 && rate > 0.0 && gap < rate * dt {
                resolved += stop.stiffest_rate();
                all += stop.stiffest_rate();
            }
        }
        (resolved, all)
    }

    /// The rates of leg `i`'s struts that a step of `dt` (s) can see make a maximum, summed,
    /// N/m: each strut on its virgin curve (onset or plateau, with at least its rebound rate
    /// K_B, onto which its maximum turns) or on an end stop, or rebounding towards its largest
    /// stroke so fast that it reaches it within `dt`; `primary` and `secondary` are the branches
    /// its struts are on with their rates ([`State::primary_branch`],
    /// [`State::secondary_branches`]). The `strides` scheme takes
    /// the struts' laws implicitly ([`strides::correct_vehicle`], [`report`]'s footpad
    /// corrector), stable at any step; its step resolves the modes in which a maximum is made,
    /// and crosses a strut's rebound line below its maximum in long strides.
    fn loading_rate(
        &self,
        model: &Model,
        i: usize,
        dt: f64,
        primary: (Branch, f64),
        secondary: [(Branch, f64); 2],
    ) -> f64 {
        let (g, memory) = (&self.gear[i], &self.memory[i]);
        let laws = &model.laws;
        // (branch and rate, the law's rebound rate K_B, the distance to the largest stroke, m,
        // and the stroke's rate towards it, m/s). On its virgin curve a strut makes its
        // maximum and turns onto its rebound line: the stiffer of the two.
        let counted =
            |(branch, rate): (Branch, f64), backoff: f64, gap: f64, speed: f64| match branch {
                Branch::Onset | Branch::Plateau => rate.max(backoff),
                Branch::StrokeOut | Branch::ExtensionStop => rate,
                Branch::Rebound if speed > 0.0 && gap < speed * dt => rate,
                Branch::Rebound => 0.0,
            };
        let c = g.primary_stroke;
        let primary = counted(
            primary,
            laws.primary.honeycomb.backoff_rate,
            memory.primary.compression.max_stroke() - c,
            g.primary_rate,
        );
        let side = |j: usize| {
            let (s, rate, m) = (
                g.secondary_stroke[j],
                g.secondary_rate[j],
                memory.secondary[j],
            );
            let (gap, speed) = if s >= 0.0 {
                (m.tension.max_stroke() - s, rate)
            } else {
                (m.compression.max_stroke() + s, -rate)
            };
            let backoff = laws.secondary.honeycomb.side(s).backoff_rate;
            counted(secondary[j], backoff, gap, speed)
        };
        primary + side(0) + side(1)
    }

    /// The branch of its law leg `i`'s primary is on at the accepted state, with its rate, N/m
    /// (`branch`).
    fn primary_branch(&self, model: &Model, i: usize) -> (Branch, f64) {
        let (g, memory) = (&self.gear[i], &self.memory[i]);
        model.laws.primary.branch(g.primary_stroke, memory.primary)
    }

    /// The branches of their laws leg `i`'s 3-1 and 4-1 struts are on at the accepted state,
    /// with their rates, N/m (`branch`).
    fn secondary_branches(&self, model: &Model, i: usize) -> [(Branch, f64); 2] {
        let (g, memory) = (&self.gear[i], &self.memory[i]);
        let secondary = &model.laws.secondary.honeycomb;
        [0, 1].map(|j| secondary.branch(g.secondary_stroke[j], memory.secondary[j]))
    }

    /// The longest step that resolves the modes of footpad `i` on its gear (off the surface):
    /// [`PAD_MODE_STEP`]/ω with ω² = (k_2P + k_31 + k_41)/PMASS, each strut's rate the slope of
    /// the branch of its law it is on at the accepted state (the sum bounds the largest
    /// eigenvalue of the footpad's stiffness Σ k_j·û_j·û_jᵀ, each strut's stroke moving at most
    /// as fast as the footpad), s. The report's scheme leaves k_2P out: it takes that axial mode
    /// implicitly ([`report`]'s footpad corrector); the `strides` scheme takes every strut's
    /// implicitly, and the footpad's modes bound none of its steps.
    pub(crate) fn pad_mode_step(&self, model: &Model, i: usize) -> f64 {
        if model.integrator.scheme == Scheme::Strides {
            return f64::INFINITY;
        }
        let primary = match model.integrator.scheme {
            Scheme::Report => 0.0,
            _ => self.primary_branch(model, i).1,
        };
        let [s31, s41] = self.secondary_branches(model, i).map(|(_, rate)| rate);
        let k = primary + s31 + s41;
        if k > 0.0 {
            PAD_MODE_STEP * (model.footpad_mass / k).sqrt()
        } else {
            f64::INFINITY
        }
    }
}

/// The largest mobility of any strut's stroke on the vehicle of mass and inertia `mass` on
/// the gear of `legs` with the laws `laws`, 1/kg: 1/M + r²/J_min times the square of the
/// largest stroke gradient, r = |B2| + L2P bounding the footpad's distance from the centre of
/// mass (the primary no longer than its undeformed length), J_min the least principal moment
/// of inertia. A strut's stroke moves with the footpad relative to the vehicle (a vehicle
/// displacement (t, φ) moves it by −t + BP×φ), at most as fast as the footpad for the primary
/// (and a tripod's struts) and L21/(L2P − primary capacity) as fast for a cantilever's
/// secondaries, which move with point 1 (eqs. 29-34); infinite (every stride Δt_max) for a leg
/// whose primary capacity exceeds its length.
pub(crate) fn stroke_mobility(legs: &[Leg], laws: &GearLaws, mass: &MassProperties) -> f64 {
    let least_moment = mass.inertia.symmetric_eigenvalues().min();
    let capacity = laws.primary.honeycomb.curve.capacity();
    legs.iter()
        .map(|l| {
            let r = l.b2.norm() + l.l2p;
            // (a primary whose capacity would take its footpad past point 1: no bound)
            let reach = l.l2p - capacity;
            let gradient = if reach > 0.0 {
                (l.l21 / reach).max(1.0)
            } else {
                f64::INFINITY
            };
            (1.0 / mass.mass + r * r / least_moment) * gradient * gradient
        })
        .fold(0.0, f64::max)
}
