//! Crushable honeycomb load-stroke law with elastic onset, plateaus, rebound and permanent set
//! (figs. 8 and 9), the trunnion-spring modification of eqs. (35)-(39), and the end stops.
//!
//! Each loading direction is a *virgin curve* `F_v(x)`: from 0 the load rises at the onset rate
//! to the first crush load FP1 (station A), stays on that plateau to the end of the first stage
//! (B), rises at the onset rate to FP2 (C), and so on. Beyond the end of the last stage the strut
//! bottoms (strokes out): the load rises at the stroke-out rate, a steep final segment the report
//! leaves unspecified (docs/errata.md, "Modelling choices the report leaves open").
//!
//! The memory is the largest stroke reached, `x_max` ([`CrushMemory`]). At stroke x:
//! `F = F_v(x)` if `x ≥ x_max`, otherwise `F = max(0, F_v(x_max) − K_B·(x_max − x))` (elastic
//! rebound along the backoff rate K_B, F → G in fig. 8). The permanent set is
//! `G = x_max − F_v(x_max)/K_B`. Memories are committed only at accepted states.
//!
//! Bottoming is a [`Stop`] with a coefficient of restitution e, in parallel with the exhausted
//! honeycomb: past the capacity the last stage goes on crushing at its plateau load F_c (the
//! work F_c·d carried through the stop's depth d is crushing, not stored: it rebounds along
//! K_B from the deepest stroke like any crush), and the stop's own spring loads at the
//! stroke-out rate K_so and unloads along the stiffer curve of [`Stop::force`], returning e² of
//! the energy it took. The stop's memory is its deepest depth in the current engagement, cleared
//! when the stroke comes back to the stop's start, so every hit loads the stop afresh and loses
//! (1 − e²) of what its spring took (docs/errata.md, "End stops"). e = 1 is the lossless stop,
//! e = 0 a perfectly plastic one.

mod crush;
mod curve;
mod double_acting;
pub mod reach;
mod stop;

pub use crush::{Branch, CrushMemory, Honeycomb};
pub use curve::{LoadStroke, Stage, MAX_STAGES};
pub use double_acting::{DoubleActingHoneycomb, DoubleActingMemory};
pub use reach::StrutReach;
pub use stop::Stop;

#[cfg(test)]
mod tests;
