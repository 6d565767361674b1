//! What became of a landing on an engine, as data: it completed (`Ok` with its
//! [`crate::Summary`]), or it did not ([`RunError`]): it stopped ([`Divergence`]: the time, the
//! law and leg involved, the state as numbers), the engine refused the scenario (a
//! [`ScenarioError`] naming the file and field), or the engine could not be set up
//! ([`SetupFailure`]). Campaigns count these; nothing downstream reads their messages back
//! (docs/robustness.md, the verdicts of the catalogue).

use serde::{Deserialize, Serialize};
use touchdown_scenario::schema::Engine;
use touchdown_scenario::ScenarioError;

/// The law, mechanism or check involved in a stopped run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Law {
    /// The primary strut's honeycomb (eqs. 49-53).
    PrimaryHoneycomb,
    /// The primary strut's viscous force (eq. 54).
    PrimaryViscous,
    /// The primary strut's bearing friction (eqs. 55-60).
    BearingFriction,
    /// The secondary struts' double-acting honeycomb (eqs. 61-64).
    SecondaryHoneycomb,
    /// The secondary struts' viscous force (eq. 65).
    SecondaryViscous,
    /// The gear geometry and strokes (eqs. 26-34).
    GearGeometry,
    /// The struts of a leaving gear relaxed to zero force (the release rule of the core).
    GearRelaxation,
    /// The primary strut's bending (eqs. 40-48).
    Bending,
    /// The curbs and footpad crushing (eqs. 86-95).
    Curbs,
    /// The descent engine's thrust and nozzle crushing (eqs. 69-74).
    Thrust,
    /// The reaction control system (eqs. 75-82).
    Rcs,
    /// The Euler-angle kinematics (eqs. 5-9): the singularity at θy = ±90°.
    Kinematics,
    /// The vehicle's equations of motion (eqs. 10-15): a state that is not finite.
    EquationsOfMotion,
    /// The energy balance guard (docs/errata.md, "Energy guard").
    EnergyBalance,
    /// The run budget, `integrator.max_steps` (docs/robustness.md, "Budgets").
    RunBudget,
    /// The engine's own constraint solver (MuJoCo's warnings, and its errors in a step).
    Solver,
}

impl Law {
    /// The law's name in messages.
    pub fn name(self) -> &'static str {
        match self {
            Law::PrimaryHoneycomb => "primary honeycomb",
            Law::PrimaryViscous => "primary viscous",
            Law::BearingFriction => "bearing friction",
            Law::SecondaryHoneycomb => "secondary honeycomb",
            Law::SecondaryViscous => "secondary viscous",
            Law::GearGeometry => "gear geometry",
            Law::GearRelaxation => "gear relaxation",
            Law::Bending => "strut bending",
            Law::Curbs => "curbs",
            Law::Thrust => "thrust",
            Law::Rcs => "RCS",
            Law::Kinematics => "kinematics",
            Law::EquationsOfMotion => "equations of motion",
            Law::EnergyBalance => "energy balance",
            Law::RunBudget => "run budget",
            Law::Solver => "MuJoCo solver",
        }
    }
}

impl std::fmt::Display for Law {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// The vehicle's state when a run stopped, in the inertial (surface) frame.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StateAtStop {
    /// Centre of mass, m.
    pub position_m: [f64; 3],
    /// Centre-of-mass velocity, m/s.
    pub velocity_m_s: [f64; 3],
    /// Euler angles θ (eq. 5), rad, where the engine integrates them (the core).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub euler_angles_rad: Option<[f64; 3]>,
    /// Angular velocity, rad/s, inertial axes.
    pub angular_velocity_rad_s: [f64; 3],
}

impl std::fmt::Display for StateAtStop {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let [x, u, w] = [
            self.position_m,
            self.velocity_m_s,
            self.angular_velocity_rad_s,
        ];
        write!(
            f,
            "R = [{:.6e}, {:.6e}, {:.6e}] m, V = [{:.6e}, {:.6e}, {:.6e}] m/s, ",
            x[0], x[1], x[2], u[0], u[1], u[2]
        )?;
        if let Some(t) = self.euler_angles_rad {
            write!(f, "θ = [{:.6e}, {:.6e}, {:.6e}] rad, ", t[0], t[1], t[2])?;
        }
        write!(
            f,
            "ω = [{:.6e}, {:.6e}, {:.6e}] rad/s (inertial)",
            w[0], w[1], w[2]
        )
    }
}

/// A run stopped because it diverged, left the domain of a law or exhausted its budget: when,
/// which law and leg, and the state, so that the user (and a campaign) can tell what failed.
/// Every engine reports it the same way.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Divergence {
    /// Time of the failure, s.
    pub time_s: f64,
    /// The law or mechanism involved.
    pub law: Law,
    /// The leg involved, numbered from 1 as in the report, where one is.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub leg: Option<usize>,
    /// What happened, for a reader.
    pub message: String,
    /// Vehicle state at the failure.
    pub state: StateAtStop,
}

impl Divergence {
    /// A stop at time `time_s` (s) in `law`, on the leg of 0-based index `leg_index` if one is
    /// involved (reported numbered from 1), with what happened and the state.
    pub fn new(
        time_s: f64,
        law: Law,
        leg_index: Option<usize>,
        message: String,
        state: StateAtStop,
    ) -> Divergence {
        Divergence {
            time_s,
            law,
            leg: leg_index.map(|i| i + 1),
            message,
            state,
        }
    }
}

impl std::fmt::Display for Divergence {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "simulation stopped at t = {:.6} s in {}",
            self.time_s, self.law
        )?;
        if let Some(leg) = self.leg {
            write!(f, " (leg {leg})")?;
        }
        write!(f, ": {}; state: {}", self.message, self.state)
    }
}

impl std::error::Error for Divergence {}

/// An engine that could not be set up: its runtime, library or runner is missing or failed
/// outside the landing itself.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{engine} engine not set up: {cause}")]
pub struct SetupFailure {
    /// The engine.
    pub engine: Engine,
    /// What is missing or failed, with the command that sets it up where there is one.
    pub cause: String,
}

/// Why an engine did not complete a landing.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// The engine refused the scenario: invalid, not applicable to it, or asking for what it does
    /// not model (names the file and the field).
    #[error(transparent)]
    Refused(#[from] ScenarioError),
    /// The run stopped with a diagnostic (boxed: it is the rare path, and keeps the results of
    /// the step loop small).
    #[error(transparent)]
    Stopped(Box<Divergence>),
    /// The engine could not be set up.
    #[error(transparent)]
    Setup(#[from] SetupFailure),
}

impl RunError {
    /// `engine` could not be set up, for `cause`.
    pub fn setup(engine: Engine, cause: impl Into<String>) -> RunError {
        RunError::Setup(SetupFailure {
            engine,
            cause: cause.into(),
        })
    }
}

impl From<Divergence> for RunError {
    fn from(d: Divergence) -> RunError {
        RunError::Stopped(Box::new(d))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_divergence_reads_and_round_trips_as_data() {
        let d = Divergence {
            time_s: 0.25,
            law: Law::BearingFriction,
            leg: Some(3),
            message: "bearing separation out of range".into(),
            state: StateAtStop {
                position_m: [0.0, 0.0, 1.0],
                velocity_m_s: [0.0, 0.0, -2.0],
                euler_angles_rad: None,
                angular_velocity_rad_s: [0.1, 0.0, 0.0],
            },
        };
        let text = d.to_string();
        assert!(
            text.starts_with("simulation stopped at t = 0.250000 s in bearing friction (leg 3): bearing separation"),
            "{text}"
        );
        assert!(!text.contains("θ"), "{text}");
        let json = serde_json::to_string(&d).unwrap();
        assert!(json.contains("\"law\":\"bearing_friction\""), "{json}");
        assert!(!json.contains("null"), "{json}");
        assert_eq!(serde_json::from_str::<Divergence>(&json).unwrap(), d);
    }
}
