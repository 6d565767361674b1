//! The state of a landing: what a step changes (time, the vehicle, its footpads and gear, the
//! committed memories of the laws and the mechanisms, the work ledger, the stability criteria
//! and the running extremes), with the buffers the evaluations reuse so that no step
//! allocates. The fixed part of the landing is its [`crate::model::Model`].

use crate::gear::GearState;
use crate::mechanisms::{MechanismState, Power};
use crate::settling::LegTerms;
use crate::stiction::Held;
use crate::surface::{Footpad, SlidingForces};
use crate::vehicle::VehicleState;
use nalgebra::Vector3;
use touchdown_laws::GearMemory;
use touchdown_record::{EnergyLedger, Extremes, PadView, StabilityTracker};

/// What a step of a landing on the core changes.
#[derive(Debug, Clone)]
pub(crate) struct State {
    /// Time, s.
    pub(crate) t: f64,
    /// Accepted steps so far.
    pub(crate) steps: u64,
    /// Evaluations of the loads so far.
    pub(crate) evaluations: u64,
    /// The rigid vehicle at the accepted state.
    pub(crate) vehicle: VehicleState,
    /// The footpads.
    pub(crate) pads: Vec<Footpad>,
    /// The gear laws' committed memories, per leg.
    pub(crate) memory: Vec<GearMemory>,
    /// Gear states at the accepted state.
    pub(crate) gear: Vec<GearState>,
    /// What the mechanisms commit (the nozzle crush, the curbs' crush, the lagged slosh
    /// specific force) and their evaluation counts.
    pub(crate) mechanisms: MechanismState,
    /// Point-1 bending displacement per leg at the last accepted state (lagged: docs/errata.md,
    /// "Eqs. (47)-(48): bending coupling"), m.
    pub(crate) bending_lag: Vec<Vector3<f64>>,
    /// Per leg, how far its gear went back when its rigid footpad left in this step and the
    /// gear relaxed: not work of the vehicle, so the strut work of the step is booked to the
    /// strokes before it.
    pub(crate) relaxation: Vec<Relaxation>,
    /// Per rigid footpad, the accepted states in a row it has been in contact: the adaptive
    /// scheme locates the leaving of a footpad that has stayed (a footpad that lands and is
    /// pulled off at once, as a dragged footpad of a massless gear does step after step, is not
    /// located: locating it would hold the step at dt_min).
    pub(crate) contact_steps: Vec<u32>,
    /// Power of the vehicle-level mechanisms on the vehicle at the accepted state, W.
    pub(crate) applied_power: Power,
    /// The work ledger, J.
    pub(crate) ledger: EnergyLedger,
    /// The stability criteria (eqs. 105-107).
    pub(crate) stability: StabilityTracker,
    /// Running maxima of strokes, forces, the pitch rate and the acceleration.
    pub(crate) extremes: Extremes,
    /// Footpad views for the stability criteria (reused every step).
    pub(crate) pad_views: Vec<PadView>,
    /// Footpad positions and velocities at the start of the step (Runge–Kutta stages
    /// interpolate the sliding footpads between these and their end of step; the footpads off
    /// the surface start their stages from them), m, m/s.
    pub(crate) pad_start: Vec<(Vector3<f64>, Vector3<f64>)>,
    /// Each footpad sliding on the surface at the start of the step, with its frozen forces
    /// (reused; `None` for the others).
    pub(crate) sliding_start: Vec<Option<SlidingStart>>,
    /// The footpads off the surface whose bearing friction an evaluation sets last (reused).
    pub(crate) held: Vec<Held>,
    /// Each leg's force on the vehicle (inertial axes, N) and torque about its centre of mass
    /// (body axes, N·m) at the last evaluation (reused).
    pub(crate) leg_loads: (Vec<Vector3<f64>>, Vec<Vector3<f64>>),
    /// When the landing was proved settled ([`crate::settling`]), s.
    pub(crate) settled: Option<f64>,
    /// When the settled end's certificate is next checked, s.
    pub(crate) next_settling_check: f64,
    /// What the certificate needs of each leg (reused).
    pub(crate) settling_terms: Vec<LegTerms>,
}

/// How far a gear went back in a step as its rigid footpad left and it relaxed
/// ([`State::relaxation`]), each the stroke before less the stroke after, m.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Relaxation {
    /// Primary compression stroke.
    pub(crate) primary: f64,
    /// Secondary strokes S31, S41 (tension positive).
    pub(crate) secondary: [f64; 2],
    /// The secondaries' bending lengthening λ31, λ41 (eq. 47), gone with the bending load.
    pub(crate) bending: [f64; 2],
}

/// What the corrector needs, besides its position and velocity in
/// [`State::pad_start`], to advance a footpad on the surface again from the start of the step
/// ([`State::correct_sliding_pads`]): whether it was stuck there and the forces frozen on it
/// (eq. 97).
#[derive(Debug, Clone, Copy)]
pub(crate) struct SlidingStart {
    /// Whether the footpad was stuck at the start of the step ([`Footpad::stuck`]).
    pub(crate) stuck: bool,
    /// Its forces at the accepted state.
    pub(crate) forces: SlidingForces,
    /// The soil's lateral drag FDRAG in `forces.drag`, N (eq. 102; 0 off soil).
    pub(crate) soil_drag: f64,
}
