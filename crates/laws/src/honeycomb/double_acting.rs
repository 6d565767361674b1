//! The double-acting honeycomb of the secondary struts: tension and compression apart.

use super::{Branch, CrushMemory, Honeycomb};
use crate::LawError;

/// Memories of a double-acting honeycomb: tension and compression, both referenced to the
/// original zero stroke.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DoubleActingMemory {
    /// Tension-side memory.
    pub tension: CrushMemory,
    /// Compression-side memory.
    pub compression: CrushMemory,
}

/// A double-acting honeycomb (the secondary struts): independent tension and compression
/// cartridges, fig. 9. Stroke and force are **tension positive**, as eq. (34) defines S31.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DoubleActingHoneycomb {
    /// Tension side (stations A-D, rebound D-E).
    pub tension: Honeycomb,
    /// Compression side (stations F-I, rebound I-J).
    pub compression: Honeycomb,
}

impl DoubleActingHoneycomb {
    /// The cartridge stroke `s` (m, tension positive) loads: the tension side for s ≥ 0, the
    /// compression side below.
    #[inline]
    pub fn side(&self, s: f64) -> &Honeycomb {
        if s >= 0.0 {
            &self.tension
        } else {
            &self.compression
        }
    }

    /// Force, N (tension positive), at stroke `s` (m, tension positive). Zero between the two
    /// permanent sets (J < s < E in fig. 9).
    #[inline]
    pub fn force(&self, s: f64, memory: DoubleActingMemory) -> f64 {
        if s >= 0.0 {
            self.tension.force(s, memory.tension)
        } else {
            -self.compression.force(-s, memory.compression)
        }
    }

    /// Commits an accepted stroke `s` (m, tension positive) into both sides' memories (a
    /// side's largest stroke only grows on its own side; its stop's engagement ends on the
    /// other).
    #[inline]
    pub fn commit(&self, s: f64, memory: &mut DoubleActingMemory) {
        self.tension.commit(s, &mut memory.tension);
        self.compression.commit(-s, &mut memory.compression);
    }

    /// The force of the stop the stroke `s` (m, tension positive) is on, beyond its side's last
    /// crush load, N (tension positive; zero within both capacities).
    #[inline]
    pub fn stop_force(&self, s: f64, memory: DoubleActingMemory) -> f64 {
        if s >= 0.0 {
            self.tension.stop_force(s, memory.tension)
        } else {
            -self.compression.stop_force(-s, memory.compression)
        }
    }

    /// The branch stroke `s` (m, tension positive) lies on and its rate, N/m: the tension
    /// side's for s ≥ 0, the compression side's below.
    pub fn branch(&self, s: f64, memory: DoubleActingMemory) -> (Branch, f64) {
        if s >= 0.0 {
            self.tension.branch(s, memory.tension)
        } else {
            self.compression.branch(-s, memory.compression)
        }
    }

    /// Recoverable elastic energy at stroke `s`, J.
    #[inline]
    pub fn stored_energy(&self, s: f64, memory: DoubleActingMemory) -> f64 {
        self.stored_energy_at(s, self.force(s, memory), memory)
    }

    /// [`DoubleActingHoneycomb::stored_energy`] at stroke `s` (m, tension positive) where the
    /// law gives the force `f` (N, tension positive).
    #[inline]
    pub fn stored_energy_at(&self, s: f64, f: f64, memory: DoubleActingMemory) -> f64 {
        if s >= 0.0 {
            self.tension.stored_energy_at(s, f, memory.tension)
        } else {
            self.compression
                .stored_energy_at(-s, -f, memory.compression)
        }
    }

    /// The same strut behind a trunnion spring `k_t`, N/m (both sides, eqs. 35-36, 38-39).
    pub fn with_trunnion(&self, k_t: f64) -> Result<Self, LawError> {
        Ok(DoubleActingHoneycomb {
            tension: self.tension.with_trunnion(k_t)?,
            compression: self.compression.with_trunnion(k_t)?,
        })
    }
}
