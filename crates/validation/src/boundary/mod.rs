//! The report's automatic stability-boundary search (section "Stability criteria"): for each
//! vertical velocity Vv, the horizontal velocities Vh at which the landing changes between
//! stable and unstable, where a strut first goes past its capacity, and how far the landing is
//! safe (stable and within every strut's capacity).
//!
//! At each Vv the search lands on the whole grid `vh_start + i·vh_step` (i = 0, 1, … up to
//! `vh_max`). Around each change of outcome the grid finds, a finer scan (`scan_step`) lands
//! every point from one grid step below it to one grid step above it, so that an outcome
//! alternating faster than the grid near a change is seen. Every
//! change of outcome between neighbouring landed points is then bisected to the tolerance, in
//! either direction, and so is the first Vh past capacity. Undecided landings are never counted
//! as stable or unstable: they are listed; a change of outcome across undecided points, or a
//! bisection whose midpoint ends undecided, is reported as an unresolved bracket.
//!
//! What the search reports at each Vv: every transition, each end with the end stops it
//! engaged (how many struts past their capacity, the largest stop force); the boundary, the
//! lowest stable → unstable transition; the band over which the outcome alternates when there
//! are several transitions (its ends and how many changes), never collapsed to one number; the
//! first Vh past capacity; and the safe envelope, up to the first landing that overturned,
//! ended undecided or went past a capacity (docs/validation.md, "Stability boundary").
//!
//! A stable landing runs to its end time, an unstable one to its wall crossing
//! (docs/errata.md, "Stability decisions and maxima"). Vertical velocities, grid points and
//! transitions run in parallel; every result is ordered by Vh, never by completion.
//!
//! All velocities here are in the scenario's velocity unit (its length unit per second).
//!
//! One folder, a module a job: [`Request`] (the study as asked, checked once into a
//! [`Study`]), `settings` (the grid and its defaults), `search` (the search at each descent
//! speed and what it finds), `speed` (the SI speed documents are written in), `engines` (the
//! landings of a scenario on each engine and end-stop law), `document` (the points in SI, their
//! JSON Lines and CSV) and `text` (the table).

mod document;
mod engines;
mod request;
mod search;
mod settings;
mod speed;
#[cfg(test)]
mod tests;
mod text;

pub use engines::{scenario_landing, EnginePoint};
pub use request::{Request, Study};
pub use search::{
    search, Band, BoundaryPoint, CapacityEdge, Direction, Landed, Limit, Refined, SafeEdge, Stops,
    Transition,
};
pub use settings::{
    Asked, Settings, DEFAULT_SCAN_STEP, DEFAULT_TOLERANCE, DEFAULT_VH_MAX, DEFAULT_VH_STEP,
    MAX_GRID_POINTS, MAX_RELATIVE_RESOLUTION,
};
pub use speed::{MetresPerSecond, SiSpeed};
