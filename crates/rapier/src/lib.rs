//! The TN D-7045 lander rebuilt as a rapier multibody (`rapier3d-f64`), driven by the same force
//! laws as the core (`touchdown_laws`), to show where an idealised massless-gear model and a
//! multibody model agree and where they part (docs/engines.md).
//!
//! | module | content |
//! |---|---|
//! | `assembly` | the multibody: vehicle root, per gear a universal trunnion joint (two hinges and a massless yoke), outer-cylinder link, prismatic stroke joint, inner cylinder with footpad; one ground plane per footpad |
//! | `struts` | the shared laws applied to the joints: honeycomb (explicit elastic, plateau as a one-sided velocity motor), viscous, bearing friction as per-DOF dry friction, secondary struts as massless two-force members |
//! | `simulation` | the fixed-step run, energy ledger, stability criteria (`touchdown_record`), divergence checks |
//!
//! Frames: rapier's world frame is the report's inertial (surface) frame, Z normal to the surface,
//! so the slope is a tilted gravity vector; every body's local axes are the vehicle's body axes
//! at touchdown (the gear links start aligned with the vehicle).

mod assembly;
mod simulation;
mod struts;

pub use assembly::LinkMasses;
pub use simulation::RapierSimulation;
pub use touchdown_multibody::unsupported;
pub use touchdown_record::{Landing, Observer, RunError};

/// Runs a scenario to its end on the rapier engine and returns its summary.
pub fn run(scenario: &touchdown_scenario::Scenario) -> Result<touchdown_record::Summary, RunError> {
    RapierSimulation::new(scenario)?.run(&mut ())
}
