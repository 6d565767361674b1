//! The report-faithful core of Touchdown: NASA TN D-7045 (Zupp & Doiron, 1971), equation by
//! equation. A 6-DOF rigid vehicle on massless cantilever gear assemblies with effective
//! footpad point masses, on a rigid sloped surface with holes and obstacles, integrated with
//! the report's linear-acceleration predictor-corrector and its step-size rule.
//!
//! A landing is a [`Simulation`]: its model (`model`: what the scenario fixes), its state
//! (`state`: what a step changes) and the scheme that advances it (`stepper`). Every function
//! of a step takes the model by shared reference and the state by mutable reference.
//!
//! | module | report |
//! |---|---|
//! | `vehicle` | the rigid vehicle's state and kinematics, eqs. (5)-(15) |
//! | `rigid_body` | rigid-vehicle equations, eqs. (10)-(15) |
//! | `gear` | gear geometry, strokes, force resolution, eqs. (26)-(34), (49)-(66) |
//! | `surface` | footpads on the rigid surface, eqs. (16)-(19), (85)-(100) |
//! | `contact`, `release`, `stiction` | the contact logic of footpads with inertia and of rigid ones, eqs. (16)-(19), (59)-(63), (85)-(100) |
//! | `loads` | net loads and accelerations, eqs. (26)-(68), (83)-(84), (9)-(15) |
//! | `mechanisms` | the scene's optional mechanisms: thrust and nozzle crushing (69-74), RCS (75-82), slosh (108-117), soil (101-104), curbs (86-95), bending (40-48) |
//! | `ledger`, `diagnostics` | the work and energies, the energy guard and the divergence checks |
//! | `stepper` | integration, eqs. (20)-(25), and the accepted state with the criteria, eqs. (105)-(107) |
//! | `integrator` | beyond the report: fourth-order and embedded Dormand–Prince Runge–Kutta schemes, a quaternion attitude |
//! | `simulation` | a landing set up from its scenario (eq. 19) and the `Landing` interface |
//!
//! The stability criteria (eqs. 105-107) and the summary are shared with the other engines in
//! `touchdown_record`.
//!
//! The modules are private: other crates use what the crate root re-exports (kept deliberate
//! by `tests/integration/public_surface.rs`).
//!
//! Departures from the printed equations are listed with their derivations and tests in
//! `docs/errata.md`.

mod certificate;
mod contact;
mod diagnostics;
mod gear;
mod integrator;
mod ledger;
mod loads;
mod mechanisms;
mod model;
mod release;
mod rigid_body;
mod settling;
mod simulation;
mod state;
mod stepper;
mod stiction;
mod summation;
mod surface;
mod vehicle;

// The types `Simulation`'s accessors return (`footpads`, `gear`, `mechanisms`,
// `mechanism_state`), nameable where they are read.
pub use gear::GearState;
pub use mechanisms::{MechanismState, Mechanisms};
pub use simulation::Simulation;
pub use surface::{ContactState, Footpad};
pub use touchdown_record::{EnergyReport, Landing, Observer, Outcome, RunError, Summary};
pub use vehicle::VehicleState;

/// Why the core does not model `mechanism`: never; it models every mechanism of the report
/// (docs/engines.md, "Mechanisms each engine models").
pub fn unsupported(_mechanism: touchdown_scenario::model::Mechanism) -> Option<&'static str> {
    None
}

/// Runs a scenario to its end with no observer and returns its summary.
pub fn run(scenario: &touchdown_scenario::Scenario) -> Result<Summary, RunError> {
    Simulation::new(scenario)?.run(&mut ())
}
