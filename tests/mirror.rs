//! Mirror images of scenarios: the mirror matrix, mirrored pseudovectors, leg maps and the
//! map under which a scenario is its own mirror image (docs/errata.md, "Decisions at rounding
//! level").

use nalgebra::{Matrix3, Vector3};
use touchdown_scenario::Scenario;

/// The mirror matrix M = diag(−1, 1, 1) (`touchdown_scenario::mirror::matrix`).
pub fn m() -> Matrix3<f64> {
    touchdown_scenario::mirror::matrix()
}

/// A pseudovector (body rates) mirrored (`touchdown_scenario::mirror::pseudovector`).
pub fn mirror_pseudo(w: &Vector3<f64>) -> Vector3<f64> {
    touchdown_scenario::mirror::pseudovector(w)
}

/// What a renumbering or mirroring does to the legs: new leg k is old leg `legs[k]`, with its
/// secondaries swapped (3-1 ↔ 4-1) when `swap`.
#[derive(Debug, Clone)]
pub struct Map {
    /// New leg k is old leg `legs[k]` (leg i's mirror image, for [`self_mirror`]).
    pub legs: Vec<usize>,
    /// Whether the secondaries are swapped.
    pub swap: bool,
}

/// The leg map under which a scenario is its own mirror image
/// (`touchdown_scenario::mirror::self_mirror`), secondaries swapped.
pub fn self_mirror(sc: &Scenario) -> Option<Map> {
    touchdown_scenario::mirror::self_mirror(sc).map(|legs| Map { legs, swap: true })
}
