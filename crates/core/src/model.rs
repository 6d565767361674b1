//! The model of a landing: what its scenario fixes (the geometry, the laws, the mass
//! properties, the surfaces, the integrator's settings and the thresholds derived from them).
//! No step changes it: the steppers, the loads, the contact logic and the ledger take it by
//! shared reference beside the [`crate::state::State`] they change, as MuJoCo passes its
//! `mjModel` beside its `mjData`.

use crate::mechanisms::Mechanisms;
use crate::rigid_body::MassProperties;
use crate::settling::Settling;
use crate::summation::SumOrder;
use nalgebra::Vector3;
use touchdown_laws::GearLaws;
use touchdown_scenario::model::{Integrator, Leg, PadSurface};
use touchdown_scenario::schema::{Arrangement, ReleaseRule};

/// What a scenario fixes of a landing on the core.
#[derive(Debug, Clone)]
pub(crate) struct Model {
    /// The scenario's name, for the summary.
    pub(crate) name: String,
    /// The legs' geometry (body axes, m).
    pub(crate) legs: Vec<Leg>,
    /// The gear's force laws.
    pub(crate) laws: GearLaws,
    /// The rigid vehicle's mass (kg) and inertia (kg·m²).
    pub(crate) mass: MassProperties,
    /// Gravity in inertial axes, m/s².
    pub(crate) gravity: Vector3<f64>,
    /// Each footpad's surface.
    pub(crate) surfaces: Vec<PadSurface>,
    /// Footpad mass, kg.
    pub(crate) footpad_mass: f64,
    /// Whether the footpads have inertia off the surface (`footpad.detached = "inertial"`), or
    /// ride rigidly with the vehicle on a relaxed massless gear (`"rigid"`, the report's).
    pub(crate) inertial: bool,
    /// When a rigid footpad leaves the surface.
    pub(crate) release: ReleaseRule,
    /// The integration scheme and its settings.
    pub(crate) integrator: Integrator,
    /// The energy guard's least scale, J (`Scenario::energy_floor_j`).
    pub(crate) energy_floor_j: f64,
    /// The gear's arrangement (the stability walls' order).
    pub(crate) arrangement: Arrangement,
    /// Footpad radius, m.
    pub(crate) footpad_radius: f64,
    /// Footpads this close to their planes (m) touch: 1e-10 of the primary strut's length, far
    /// above the rounding of positions, so mirror-image footpads touch together.
    pub(crate) contact_tolerance: f64,
    /// Forces within this of zero (N) count as zero in the contact decisions: 1e-9 of the
    /// primary strut's last crush load.
    pub(crate) force_rounding: f64,
    /// The time over which the bearing friction brings a footpad's stroking to rest off the
    /// surface, s ([`crate::stiction::relaxation`]).
    pub(crate) held_relaxation: f64,
    /// The largest mobility of a strut's stroke on the vehicle, 1/kg: an upper bound of
    /// g·M⁻¹·g over the struts and their states, g a stroke's gradient in the vehicle's
    /// displacement and M its mass and inertia ([`crate::stepper::stroke_mobility`]).
    pub(crate) stroke_mobility: f64,
    /// The settled end the scenario asks for ([`crate::settling`]).
    pub(crate) settling: Option<Settling>,
    /// The scene's optional mechanisms' laws.
    pub(crate) mechanisms: Mechanisms,
    /// The order in which the legs' loads are summed ([`crate::summation`]).
    pub(crate) sum_order: SumOrder,
    /// Potential energy of the vehicle at the start, J.
    pub(crate) potential0: f64,
    /// Kinetic plus potential energy of the footpads with inertia at the start, J.
    pub(crate) footpad0: f64,
}
