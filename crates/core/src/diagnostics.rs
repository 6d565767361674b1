//! Diagnostics that stop a run: a law that fails or leaves its domain, a state or a law output
//! that is no longer finite, the run budget (`integrator.max_steps`,
//! `touchdown_record::check_budget`) and an energy balance beyond its tolerance (docs/errata.md,
//! "Energy guard — judged against the energy put in"). Each names the law most involved and the
//! leg, with the state at the stop.

use crate::model::Model;
use crate::state::State;
use crate::vehicle::VehicleState;
use touchdown_laws::StrutLoad;
use touchdown_record::{Divergence, EnergyReport, Law, RunError, StateAtStop};

impl State {
    /// A divergence diagnostic at state `v`: `law` failed, on the leg of (0-based) index `leg`
    /// if one is involved (reported 1-based).
    pub(crate) fn diverged(
        &self,
        v: &VehicleState,
        message: String,
        law: Law,
        leg: Option<usize>,
    ) -> RunError {
        let state = StateAtStop {
            position_m: v.position.into(),
            velocity_m_s: v.velocity.into(),
            euler_angles_rad: Some(v.euler.theta.into()),
            angular_velocity_rad_s: v.omega_inertial().into(),
        };
        Divergence::new(self.t, law, leg, message, state).into()
    }

    /// Stops a run whose state is not finite or whose energy balance (`e`, this state's report)
    /// has drifted beyond the tolerance, naming the law most involved.
    pub(crate) fn check_divergence(&self, model: &Model, e: &EnergyReport) -> Result<(), RunError> {
        let v = &self.vehicle;
        let max_steps = model.integrator.max_steps;
        if let Err(budget) = touchdown_record::check_budget(self.steps, self.evaluations, max_steps)
        {
            return Err(self.diverged(v, budget.to_string(), Law::RunBudget, None));
        }
        for (i, g) in self.gear.iter().enumerate() {
            let checks = [
                (Law::PrimaryHoneycomb, g.fcp),
                (Law::PrimaryViscous, g.fvp),
                (Law::BearingFriction, g.fbr),
                (
                    Law::SecondaryHoneycomb,
                    g.fc_secondary[0] + g.fc_secondary[1],
                ),
                (Law::SecondaryViscous, g.fv_secondary[0] + g.fv_secondary[1]),
                (
                    Law::GearGeometry,
                    g.primary_stroke + g.secondary_stroke[0] + g.secondary_stroke[1],
                ),
            ];
            if let Some((law, value)) = checks.iter().find(|(_, x)| !x.is_finite()) {
                return Err(self.diverged(v, format!("non-finite value {value}"), *law, Some(i)));
            }
        }
        let finite = [
            v.position,
            v.velocity,
            v.acceleration,
            v.euler.theta,
            v.theta_dot,
            v.theta_ddot,
        ]
        .iter()
        .all(|x| x.iter().all(|c| c.is_finite()))
            && self.pads.iter().all(|p| {
                p.position
                    .iter()
                    .chain(p.velocity.iter())
                    .all(|c| c.is_finite())
            });
        if !finite {
            return Err(self.diverged(
                v,
                "non-finite vehicle or footpad state".into(),
                Law::EquationsOfMotion,
                None,
            ));
        }
        self.ledger
            .check_balance(
                e,
                model.integrator.energy_tolerance,
                model.energy_floor_j,
                "step too large for the stiffest mode?",
            )
            .map_err(|imbalance| {
                let loads =
                    (self.gear.iter().zip(&self.memory))
                        .enumerate()
                        .flat_map(|(i, (g, m))| {
                            let primary = (g.primary_stroke, g.fcp + g.fvp + g.fbr);
                            let secondary = [0, 1].map(|j| g.fc_secondary[j] + g.fv_secondary[j]);
                            model
                                .laws
                                .strut_loads(i, m, primary, (g.secondary_stroke, secondary))
                        });
                let message = format!("{imbalance}; {}", StrutLoad::stiffest(loads));
                self.diverged(v, message, Law::EnergyBalance, None)
            })
    }
}
