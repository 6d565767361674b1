//! Force laws of NASA TN D-7045, written once and used by every engine.
//!
//! All quantities are SI: strokes in m, forces in N, rates in N/m, speeds in m/s, pressures in Pa.
//! Each law is a pure function of its inputs plus, for the crushable honeycomb, an explicit
//! memory ([`CrushMemory`]) that the caller commits only at accepted states.
//!
//! | module | report | law |
//! |---|---|---|
//! | [`honeycomb`] | Figs. 8, 9; eqs. 35-39 | crushable honeycomb load-stroke with elastic onset, plateaus, rebound (backoff) and permanent set; trunnion-spring modification |
//! | [`viscous`] | eq. 49 | stroking-velocity force `C·sgn(v)·|v|^γ` |
//! | [`bearing`] | eqs. 59-63 | primary-strut bearing normal loads and Coulomb bearing friction |
//! | [`sliding`] | eqs. 85, 96 | Coulomb sliding friction on the footpad bottom |
//! | [`thrust`] | Figs. 15, 16; eqs. 69-74 | descent-engine thrust tailoff, thrust amplification table AMP(ZNOZ), constant-load nozzle-rim crushing, engine force and moment |
//! | [`rcs`] | eqs. 75-82 | RCS attitude-hold / rate-command on-off torques with deadbands; delayed downward-translation force |
//! | [`scene`] | eqs. 69-82, 108-117 | the vehicle-level laws a scene declares (descent engine, RCS, slosh), built from the scenario once for every engine |
//! | [`slosh`] | Appendix, eqs. 108-117 | first-mode propellant slosh as a spring-mass: slosh mass, CM shift, rigid inertia, amplitude equation, wall force and torque |
//! | [`curb`] | Figs. 18-20; eqs. 86-95 | curbs on the rigid surface: footpad-curb distance, crushing with memory, curb friction |
//! | [`soil`] | eqs. 101-104 | non-rigid surface: rigid-plastic bearing with rate terms, lateral drag, constant-force vertical step |
//! | [`beam`] | eqs. 40-48 | primary-strut bending as a beam-column, Euler cap, apparent change in secondary-strut length |

pub mod beam;
pub mod bearing;
pub mod curb;
pub mod gear;
pub mod honeycomb;
pub mod rcs;
pub mod scene;
pub mod sliding;
pub mod slosh;
pub mod soil;
pub mod thrust;
pub mod viscous;

pub use beam::{euler_load, normal_load, secondary_lengthening, Bending, Deflection, EULER_CAP};
pub use bearing::{side_load, Bearing, BearingLoads};
pub use curb::{Curb, Curbs, FootpadCrush};
pub use gear::{
    GearLaws, GearMemory, PrimaryMemory, PrimaryStrutLaw, SecondaryForces, SecondaryStrutLaw,
    StrutLoad,
};
pub use honeycomb::{
    Branch, CrushMemory, DoubleActingHoneycomb, DoubleActingMemory, Honeycomb, LoadStroke, Stage,
    Stop, StrutReach,
};
pub use rcs::{DownwardTranslation, Rcs, RcsLoads, RcsMode, RcsParams};
pub use sliding::sliding_friction;
pub use slosh::Slosh;
pub use soil::{Soil, VerticalStep};
pub use thrust::{
    engine_loads, Amplification, EngineLoads, Nozzle, RimArrest, RimContact, Tailoff,
};
pub use viscous::Viscous;

/// An error raised by a force law: bad parameters at construction, or a state in which the law
/// is not defined during a run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LawError {
    /// The load-stroke stage table is not usable.
    #[error("load-stroke table: {0}")]
    StageTable(String),
    /// A rate or coefficient is not a positive finite number.
    #[error("{name} must be a positive finite number, got {value}")]
    NotPositive { name: &'static str, value: f64 },
    /// The primary-strut bearing geometry left its domain (D2 must stay in (0, D1)).
    #[error(
        "bearing friction: bearing separation D2 = {d2} m is outside (0, D1 = {d1} m) \
         at compression stroke {stroke} m"
    )]
    BearingGeometry { d2: f64, d1: f64, stroke: f64 },
    /// A magnitude, delay or gain is not a non-negative finite number.
    #[error("{name} must be a non-negative finite number, got {value}")]
    Negative { name: &'static str, value: f64 },
    /// A signed quantity (angle, rate, length) is not finite.
    #[error("{name} must be finite, got {value}")]
    NotFinite { name: &'static str, value: f64 },
    /// The thrust tailoff curve (eqs. 69-70) is not usable.
    #[error("thrust tailoff: {0}")]
    Tailoff(String),
    /// A tabulated function (e.g. the thrust amplification AMP(ZNOZ)) is not usable.
    #[error("table: {0}")]
    Table(String),
    /// The slosh mass M_s = F_s/ω² (eq. 112) is not below the total vehicle mass M.
    #[error("slosh mass M_s = {slosh_mass} kg must be below the total mass M = {total_mass} kg")]
    SloshMass { slosh_mass: f64, total_mass: f64 },
    /// A coefficient of restitution outside [0, 1].
    #[error("stop restitution must be a number in [0, 1], got {0}")]
    Restitution(f64),
    /// The primary-strut load point lies outside the beam (need 0 ≤ L21 ≤ V2P).
    #[error("beam: load point a = {a} m is outside the span [0, L = {l} m]")]
    BeamGeometry { a: f64, l: f64 },
}

/// Series combination of two spring rates, eqs. (35)-(36): `K' = K1·K2/(K1 + K2)`, N/m.
pub fn series_rate(k1: f64, k2: f64) -> f64 {
    k1 * k2 / (k1 + k2)
}

/// `value` if it is a positive finite number, else [`LawError::NotPositive`] naming `name`.
pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64, LawError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(LawError::NotPositive { name, value })
    }
}

/// `value` if it is finite, else [`LawError::NotFinite`] naming `name`.
pub(crate) fn finite(name: &'static str, value: f64) -> Result<f64, LawError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(LawError::NotFinite { name, value })
    }
}

/// `value` if it is a finite number ≥ 0, else [`LawError::Negative`] naming `name`.
pub(crate) fn non_negative(name: &'static str, value: f64) -> Result<f64, LawError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(LawError::Negative { name, value })
    }
}
