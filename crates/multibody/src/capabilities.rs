//! What the multibody engines model of the scene's optional mechanisms (docs/engines.md,
//! "Mechanisms each engine models"): both build the gear as bodies and joints and apply the shared laws
//! to them, so both have the same limits.

use touchdown_scenario::model::Mechanism;

/// Why a multibody engine does not model `mechanism`, or `None` if it does. They take the
/// trunnion springs through the shared strut laws, the engine and RCS as loads on the vehicle
/// body, the curbs as loads on the footpads and the tripod gear with its secondaries attached
/// at the footpad body.
pub fn unsupported(mechanism: Mechanism) -> Option<&'static str> {
    match mechanism {
        Mechanism::TrunnionSprings
        | Mechanism::Thrust
        | Mechanism::NozzleCrushing
        | Mechanism::Rcs
        | Mechanism::Curbs
        | Mechanism::Tripod => None,
        Mechanism::Bending => Some(
            "its primary strut is a rigid stroke joint; a beam-column would need a flexible link",
        ),
        Mechanism::Soil => Some(
            "soil holds a resting footpad rigid-plastically (eq. 103), a load-limited constraint its contact solver cannot take from an applied force",
        ),
        Mechanism::Slosh => {
            Some("the slosh mass is a degree of freedom its exported body tree does not have")
        }
    }
}
