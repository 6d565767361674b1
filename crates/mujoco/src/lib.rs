//! The TN D-7045 lander as a MuJoCo model (MJCF), generated from a scenario, and the runtime that
//! steps it with the shared force laws, MuJoCo loaded by its Python package (docs/engines.md,
//! "The MuJoCo engine").
//!
//! | module | content |
//! |---|---|
//! | `mjcf` | the MJCF document: vehicle, gear links, joints, secondary tendons, actuators, sensors, footpad planes, touchdown keyframe |
//! | `landing` | one law-driven landing over MuJoCo's arrays: kinematics in, strut laws out, with the bookkeeping shared with the rapier rebuild (`touchdown_multibody`): hysteresis committed once per step, energy ledger, stability criteria, history |
//! | `ffi` | the C ABI of `landing` and its step loop (this crate is also built as a `cdylib`), loaded with ctypes by the Python runner `python/mujoco/run.py` |
//! | `launch` | runs a scenario end to end: the project's Python environment, the runner and this library |
//!
//! Frames: MuJoCo's world frame is the report's inertial (surface) frame, Z normal to the
//! surface, so the slope is a tilted gravity vector, as in the other engines.
//!
//! One step of the runner: `mj_step1` (positions, velocities, tendons, sensors of the state),
//! then [`MujocoLanding::advance`] (book the last step, commit the honeycombs, evaluate
//! the laws, write the actuator controls, force ranges and bearing friction), then `mj_step2`
//! (forces, constraints, integration).

mod ffi;
mod landing;
mod launch;
mod mjcf;

pub use landing::{refusal, GearIndex, MjArrays, ModelSizes, MujocoLanding};
pub use launch::{Launch, Worker, RUNNER_STOPPED_STATUS};
pub use mjcf::{export, GENERATOR};
pub use touchdown_multibody::unsupported;

/// Errors of the MuJoCo engine.
#[derive(Debug, thiserror::Error)]
pub enum MujocoError {
    /// The scenario is invalid (names the file and field).
    #[error(transparent)]
    Scenario(#[from] touchdown_scenario::ScenarioError),
    /// The simulation diverged, left the domain of a law, or MuJoCo warned; the run was stopped.
    #[error(transparent)]
    Diverged(Box<touchdown_record::Divergence>),
    /// The runner passed arrays or indices that do not fit the model.
    #[error("MuJoCo runner: {0}")]
    Binding(String),
    /// Python, the project's venv, the pinned `mujoco` or this library is missing.
    #[error("MuJoCo engine not set up: {0}")]
    Setup(String),
    /// The Python runner failed (its message).
    #[error("MuJoCo runner failed: {0}")]
    Runner(String),
    /// Reading or writing a file.
    #[error("{0}")]
    Io(#[from] std::io::Error),
    /// The project's folder (runner, venv) cannot be found.
    #[error("{0}")]
    Home(String),
}

impl From<touchdown_home::HomeError> for MujocoError {
    fn from(e: touchdown_home::HomeError) -> Self {
        match e {
            touchdown_home::HomeError::NotFound(where_looked) => MujocoError::Home(where_looked),
            touchdown_home::HomeError::NoPython(what) => MujocoError::Setup(what),
        }
    }
}

impl From<MujocoError> for touchdown_record::RunError {
    fn from(e: MujocoError) -> Self {
        use touchdown_record::RunError;
        let engine = touchdown_scenario::schema::Engine::Mujoco;
        match e {
            MujocoError::Scenario(e) => RunError::Refused(e),
            MujocoError::Diverged(d) => RunError::Stopped(d),
            MujocoError::Setup(cause) => RunError::setup(engine, cause),
            other => RunError::setup(engine, other.to_string()),
        }
    }
}
