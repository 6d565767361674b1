//! The speed a boundary document is written in: metres per second, the only speed the search's
//! types serialise in, so that a point still in the scenario's velocity unit cannot be written
//! under the `_m_s` names.

use serde::{Serialize, Serializer};

/// A speed in metres per second, written as the number.
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd, Serialize)]
#[serde(transparent)]
pub struct MetresPerSecond(pub f64);

/// The speeds a boundary document is written in: metres per second only, so that a point still
/// in the scenario's velocity unit cannot be written under the `_m_s` names.
pub trait SiSpeed: Serialize + Copy + private::Sealed {
    /// The speed with its sign changed.
    fn negated(self) -> Self;
}

impl SiSpeed for MetresPerSecond {
    fn negated(self) -> Self {
        MetresPerSecond(-self.0)
    }
}

mod private {
    /// Only the SI speed is a [`super::SiSpeed`].
    pub trait Sealed {}
    impl Sealed for super::MetresPerSecond {}
}

/// Writes a descent speed (positive down) as the vertical velocity of the scenario files,
/// negative down.
pub(super) fn negative_down<V: SiSpeed, S: Serializer>(v: &V, s: S) -> Result<S::Ok, S::Error> {
    v.negated().serialize(s)
}
