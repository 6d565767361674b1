//! A strut law linearised over a step: its secant from the start of the step to the trial,
//! which the implicit correctors of the footpads ([`super::report`]) and of the vehicle
//! ([`super::strides`]) take as the strut's stiffness (docs/errata.md, "Footpads with
//! inertia", "Numerics"; "Long strides where the gear is soft").

use crate::gear::GearState;
use touchdown_laws::GearLaws;
use touchdown_scenario::model::Leg;

/// The secants over the step of a gear's three struts (primary, 3-1, 4-1) of `leg` with the
/// laws `laws`, from their strokes and honeycomb forces at its start `start` to those at the
/// trial `trial`, N/m ([`secant`], each bounded by its law's stiffest slope).
#[inline]
pub(super) fn strut_secants(
    leg: &Leg,
    laws: &GearLaws,
    start: &GearState,
    trial: &GearState,
) -> [f64; 3] {
    let eps = 1e-9 * leg.l2p;
    let sec = &laws.secondary.honeycomb;
    let sec_stiffest = sec
        .tension
        .stop
        .stiffest_rate()
        .max(sec.compression.stop.stiffest_rate());
    let side = |j: usize| {
        secant(
            (start.secondary_stroke[j], start.fc_secondary[j]),
            (trial.secondary_stroke[j], trial.fc_secondary[j]),
            eps,
            sec_stiffest,
        )
    };
    let primary = secant(
        (start.primary_stroke, start.fcp),
        (trial.primary_stroke, trial.fcp),
        eps,
        laws.primary.honeycomb.stop.stiffest_rate(),
    );
    [primary, side(0), side(1)]
}

/// A strut law's secant over the step from (stroke, force) at its start to those at the
/// trial, N/m, regularised within `eps` (m; 1e-9 of the strut's length, where a stroke change
/// is rounding) and at most `stiffest` (N/m), its stiffest slope: no state decides it at
/// rounding level, and a strut in its free play or on a plateau is no spring.
#[inline]
pub(super) fn secant(start: (f64, f64), trial: (f64, f64), eps: f64, stiffest: f64) -> f64 {
    let dc = trial.0 - start.0;
    ((trial.1 - start.1) * dc / (dc * dc + eps * eps)).clamp(0.0, stiffest)
}
