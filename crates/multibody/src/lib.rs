//! What the multibody engines (the rapier rebuild, the MuJoCo runner) share around their own
//! stepping, so that both apply the same forces to the same joints and report alike:
//!
//! | module | content |
//! |---|---|
//! | `capabilities` | what the multibody engines model of the scene's optional mechanisms |
//! | `strut` | the strut laws at one state of a multibody gear (eqs. 49-63): explicit forces, the plateau and bearing-friction bounds, their work over a step |
//! | `step` | the time step and footpad contact, stated or derived from the stiffest gear mode and the contact radius, and the explicit-step check |
//! | `stride` | the step between the end stops: a longer step where no stop is engaged or can engage within it |
//! | `motion` | the vehicle body's motion after a step, and what stops a run before it is placed in time and state |
//! | `applied` | the vehicle-level mechanisms applied as a force and torque on the vehicle: descent engine, nozzle crushing, RCS (eqs. 69-82), their work, the nozzle crush committed |
//! | `trunnion` | the universal joint at a primary trunnion: its two hinges, in the leg's own order |
//! | `wall` | the obstacle wall that holds a locked footpad laterally from its landing until it rises above the wall (fig. 17) |
//! | `book` | the gear bookkeeping, a model no step changes and a state: kinematics before and after a step, hysteresis committed once per step, contact work, the curbs' force on the footpads (eqs. 86-95) with their crush committed once per step, energy ledger, stability criteria, extremes, summary and history samples |

mod applied;
mod book;
mod capabilities;
mod motion;
mod step;
mod stride;
mod strut;
mod trunnion;
mod wall;

pub use applied::{StepWork, VehicleLoads};
pub use book::{
    BodyEnergy, GearModel, GearState, PadStep, Reading, StepTaken, CONTACT_FLAG_SETTINGS,
};
pub use capabilities::unsupported;
pub use motion::{BodyMotion, Fault};
pub use step::{MujocoSettings, RapierSettings};
pub use strut::{StrutForces, StrutKinematics, StrutWork};
pub use trunnion::hinge_axes;
