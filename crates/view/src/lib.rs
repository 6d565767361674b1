//! A landing to watch: the trajectory file every viewer can read, and the self-contained HTML
//! page that plays the engines' landings side by side (docs/outputs.md, "The trajectory file";
//! docs/engines.md, "Watching the engines land").
//!
//! | module | content |
//! |---|---|
//! | `trajectory` | the scene (vehicle and ground) and an engine's frames, decimated with every contact event kept, from the samples every engine records |
//! | `page` | the HTML page: the trajectory embedded, the page's script and the vendored plotting library inlined |
//! | `report` | one page per landing: the outcome and why, strokes against capacity with their times, the energy ledger, the time histories, as inline SVG |

mod page;
mod report;
mod trajectory;

pub use page::page;
pub use report::{landing_page, Series};
use serde::Serialize;
use touchdown_record::{Outcome, PastCapacity, Summary};
use touchdown_scenario::schema::Engine;
pub use trajectory::{
    ContactEvent, CurbView, Frames, LegFrames, LegView, PadGround, Recorder, Recording, Scene,
    SurfaceView, VehicleView, WallFrames, DEFAULT_FRAME_INTERVAL,
};

/// One engine's landing in a trajectory file.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EngineTrajectory<'a> {
    /// The engine (`core`, `rapier`, `mujoco`).
    pub name: Engine,
    /// What computed it.
    pub version: String,
    /// The landing's outcome.
    pub outcome: Outcome,
    /// When the outcome was decided, s (left out when undecided).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub decision_time_s: Option<f64>,
    /// Accepted steps of the landing.
    pub steps: u64,
    /// The struts that went past their capacity onto their end stops (empty when none did),
    /// as the run's summary names them.
    pub past_capacity: Vec<PastCapacity>,
    /// Its events, curbs and frames.
    #[serde(flatten)]
    pub recording: &'a Recording,
}

impl<'a> EngineTrajectory<'a> {
    /// The landing of `summary` recorded into `recording` by the engine `name` at `version`.
    pub fn new(name: Engine, version: String, summary: &Summary, recording: &'a Recording) -> Self {
        EngineTrajectory {
            name,
            version,
            outcome: summary.outcome,
            decision_time_s: summary.decision_time_s.map(trajectory::time),
            steps: summary.steps,
            past_capacity: summary.past_capacity.clone(),
            recording,
        }
    }
}

/// The body of a trajectory document (`touchdown.trajectory/1`): the scene, then each engine's
/// landing.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Trajectory<'a> {
    /// The vehicle and the ground.
    #[serde(flatten)]
    pub scene: Scene,
    /// The engines' landings, in engine order.
    pub engines: Vec<EngineTrajectory<'a>>,
}
