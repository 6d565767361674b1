//! The work ledger: the work of the struts (eqs. 49-50, 62), of the sliding footpads (eq. 97)
//! and of the vehicle-level mechanisms (eqs. 83-84) over each step, and the energies of the
//! vehicle, the footpads and the honeycombs at a state, whose balance the energy guard checks
//! (docs/errata.md, "Energy guard — judged against the energy put in").

use crate::gear::GearState;
use crate::mechanisms::Power;
use crate::model::Model;
use crate::state::State;
use crate::surface::ContactState;
use touchdown_record::EnergyReport;

/// Work of the struts and the vehicle-level mechanisms over one Runge–Kutta step: the method's
/// quadrature Δt·Σ b_i·P_i of each power, J.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct StageWork {
    honeycomb: f64,
    viscous: f64,
    bearing: f64,
    pub(crate) applied: f64,
}

impl StageWork {
    /// Adds weight `w` (s) of the powers of the gear states `gear` and the applied power
    /// `applied` (W).
    pub(crate) fn add(&mut self, w: f64, gear: &[GearState], applied: f64) {
        for g in gear {
            self.honeycomb += w
                * (g.fcp * g.primary_rate
                    + g.fc_secondary[0] * g.secondary_rate[0]
                    + g.fc_secondary[1] * g.secondary_rate[1]);
            self.viscous += w
                * (g.fvp * g.primary_rate
                    + g.fv_secondary[0] * g.secondary_rate[0]
                    + g.fv_secondary[1] * g.secondary_rate[1]);
            self.bearing += w * g.fbr * g.primary_rate;
        }
        self.applied += w * applied;
    }
}

/// How the strut work of a step is booked.
pub(crate) enum Quadrature {
    /// The report's scheme: trapezoids of the accepted and trial forces (eq. 24), with the
    /// mechanisms' power at the trial, W.
    Trapezoid { trial_power: f64 },
    /// A Runge–Kutta method's own quadrature; `evaluated` is the mechanisms' power at the new
    /// state when the method's last stage already evaluated it (its forces in the trial gear
    /// states).
    Stages {
        work: StageWork,
        evaluated: Option<Power>,
    },
}

/// Work of the sliding footpads' step (eq. 97), J: of the gear on them, of the soil and of the
/// curbs, and the change of their kinetic and potential energy.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct PadWork {
    pub(crate) gear: f64,
    pub(crate) energy_change: f64,
    pub(crate) soil: f64,
    pub(crate) curbs: f64,
}

impl State {
    /// Adds the strut work of the step from the gear states at its start (`previous`) and at
    /// the trial (`trial`). The report's scheme books it with the forces the corrector used
    /// (eq. 24: the accepted state k and the trial at the prediction), so that the ledger and
    /// the vehicle's energy see the same forces even when a footpad leaves the surface in the
    /// step: honeycomb and bearing friction ½(F_k + F*)·(x_{k+1} − x_k), viscous ½(P_k + P*)·Δt.
    /// (Bearing friction booked by its power, μB·(F1 + F2)·|ċ| at both ends, counted as
    /// dissipated what the mean force did not remove wherever ċ changes sign within a step:
    /// docs/errata.md, "Bearing friction booked with the force the vehicle feels".) A
    /// Runge–Kutta scheme books its own quadrature of the stage powers.
    /// Every gear strokes through the step as its footpad moves, on the surface or off it.
    pub(crate) fn book_strut_work(
        &mut self,
        dt: f64,
        quadrature: &Quadrature,
        previous: &[GearState],
        trial: &[GearState],
    ) {
        let steps = previous.iter().zip(trial).zip(&self.gear);
        for (((a, t), b), relaxed) in steps.zip(&mut self.relaxation) {
            let l = &mut self.ledger;
            // The strokes at the end of the step, before a leaving rigid footpad's gear relaxed.
            let r = std::mem::take(relaxed);
            let c_end = b.primary_stroke + r.primary;
            // The force at the end of the step: the trial's (report) or the accepted state's.
            let end = match quadrature {
                Quadrature::Trapezoid { .. } => {
                    l.honeycomb += 0.5 * (a.fcp + t.fcp) * (c_end - a.primary_stroke);
                    l.viscous += 0.5 * (a.fvp * a.primary_rate + t.fvp * t.primary_rate) * dt;
                    l.bearing += 0.5 * (a.fbr + t.fbr) * (c_end - a.primary_stroke);
                    t
                }
                Quadrature::Stages { .. } => b,
            };
            for (j, ds) in r.secondary.into_iter().enumerate() {
                let (fa, ft) = (a.fc_secondary[j], end.fc_secondary[j]);
                // The honeycombs see the bending-corrected strokes; the change of the bending
                // lengthening is work the vehicle did not do on the struts (eq. 47, lagged), up
                // to the end of the step: a relaxing gear's lengthening goes with its load,
                // without work (docs/errata.md, "Contact and release").
                let dl = b.bending_lengthening[j] + r.bending[j] - a.bending_lengthening[j];
                l.mechanisms -= 0.5 * (fa + ft) * dl;
                if let Quadrature::Trapezoid { .. } = quadrature {
                    let s_end = b.secondary_stroke[j] + ds;
                    l.honeycomb += 0.5 * (fa + ft) * (s_end - a.secondary_stroke[j]);
                    let (pa, pt) = (
                        a.fv_secondary[j] * a.secondary_rate[j],
                        t.fv_secondary[j] * t.secondary_rate[j],
                    );
                    l.viscous += 0.5 * (pa + pt) * dt;
                }
            }
        }
        if let Quadrature::Stages { work: w, .. } = quadrature {
            self.ledger.honeycomb += w.honeycomb;
            self.ledger.viscous += w.viscous;
            self.ledger.bearing += w.bearing;
        }
    }

    /// Vehicle kinetic energy ½MV² + ½ωᵀJω, J.
    pub(crate) fn kinetic_energy(&self, model: &Model) -> f64 {
        model
            .mass
            .kinetic_energy(&self.vehicle.velocity, &self.vehicle.omega)
    }

    /// Vehicle potential energy −M·G·R, J.
    pub(crate) fn potential_energy(&self, model: &Model) -> f64 {
        -model.mass.mass * model.gravity.dot(&self.vehicle.position)
    }

    /// Kinetic + potential energy of the footpads with dynamics, J: with inertia all of them,
    /// since the start (`footpad0`, once set); rigid ones only in contact.
    pub(crate) fn footpad_energy(&self, model: &Model) -> f64 {
        let m = model.footpad_mass;
        let now: f64 = self
            .pads
            .iter()
            .filter(|p| model.inertial || p.state == ContactState::Contact)
            .map(|p| 0.5 * m * p.velocity.norm_squared() - m * model.gravity.dot(&p.position))
            .sum();
        now - model.footpad0
    }

    /// Elastic energy stored in the gear's honeycombs now, J. A gear carrying its footpad was
    /// evaluated at these strokes, and its honeycomb forces are the laws' at them with the
    /// committed memories ([`touchdown_laws::GearLaws::stored_energy_at`]); a rigid footpad's
    /// gear off the surface carries no force and its laws are evaluated.
    fn stored_energy(&self, model: &Model) -> f64 {
        (0..model.legs.len())
            .map(|i| {
                let (g, laws) = (&self.gear[i], &model.laws);
                let (c, s) = (g.primary_stroke, g.secondary_stroke);
                if model.inertial || self.pads[i].state == ContactState::Contact {
                    let e = laws.stored_energy_at(c, s, g.fcp, g.fc_secondary, &self.memory[i]);
                    debug_assert_eq!(
                        e.to_bits(),
                        laws.stored_energy(c, s, &self.memory[i]).to_bits(),
                        "leg {i}: the evaluated forces are the laws' at the committed memory"
                    );
                    e
                } else {
                    laws.stored_energy(c, s, &self.memory[i])
                }
            })
            .sum()
    }

    /// Energy report at the current state.
    pub(crate) fn energy(&self, model: &Model) -> EnergyReport {
        self.energy_with_footpads(model, self.footpad_energy(model))
    }

    /// [`State::energy`] with the footpads' energy `footpads` (J) already computed at this
    /// state ([`State::footpad_energy`]): the step's contact logic has it.
    pub(crate) fn energy_with_footpads(&self, model: &Model, footpads: f64) -> EnergyReport {
        debug_assert_eq!(
            footpads.to_bits(),
            self.footpad_energy(model).to_bits(),
            "the footpads' energy is the state's"
        );
        self.ledger.report(
            self.stability.initial_kinetic_energy(),
            self.kinetic_energy(model),
            self.potential_energy(model) - model.potential0,
            footpads,
            self.stored_energy(model),
        )
    }
}
