//! The settled end's settings and the per-leg terms its certificate works with
//! (docs/errata.md, "Settled landings: an early end with a proof"): what the scenario fixes
//! ([`Settling`], part of the landing's model) and the scratch a check reuses ([`LegTerms`],
//! part of its state). The certificate itself is [`crate::certificate`].

use nalgebra::{Matrix3, SVector, Vector3};
use touchdown_laws::StrutReach;
use touchdown_scenario::model::Mechanism;
use touchdown_scenario::schema::Arrangement;
use touchdown_scenario::{Scenario, ScenarioError};

/// The most legs the settled end handles (its motion's size is fixed, so that a check
/// allocates nothing).
pub(crate) const MAX_LEGS: usize = 6;

/// Largest steps (`integrator.dt_max`) between two checks of the certificate: a check costs
/// about as much as ten steps, and one every hundred spends about what the early ends save on
/// the bundled campaign (docs/performance.md, "The settled end: proved, and rarely in time to
/// pay").
const CHECK_STEPS: f64 = 100.0;

/// The settled end's settings, fixed by the scenario.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Settling {
    /// ε, m.
    pub(crate) tolerance: f64,
    /// The vehicle's least principal moment of inertia, kg·m².
    pub(crate) inertia_min: f64,
    /// Time between two checks, s.
    pub(crate) interval: f64,
}

impl Settling {
    /// The settled end `scenario` asks for, if any: refused, naming the field, where the
    /// certificate's derivation does not cover the scene (a mechanism other than trunnion
    /// springs, the tripod gear, a footpad its surface does not hold laterally).
    pub(crate) fn new(scenario: &Scenario) -> Result<Option<Settling>, ScenarioError> {
        let Some(tolerance) = scenario.stability.settled_tolerance else {
            return Ok(None);
        };
        let field = "stability.settled_tolerance";
        let refuse = |why: String| {
            ScenarioError::field(
                scenario.file_of(field),
                field,
                format!("{why}: the settled end is derived for the cantilever gear on a rigid surface that holds every footpad (docs/errata.md, \"Settled landings: an early end with a proof\"); leave it out to run to the end time"),
            )
        };
        if let Some(m) = scenario
            .mechanisms()
            .into_iter()
            .find(|m| *m != Mechanism::TrunnionSprings)
        {
            return Err(refuse(format!("the scene declares {}", m.name())));
        }
        if scenario.legs.len() > MAX_LEGS {
            return Err(refuse(format!(
                "the scene has {} legs, more than {MAX_LEGS}",
                scenario.legs.len()
            )));
        }
        if scenario.arrangement == Arrangement::Tripod {
            return Err(refuse("the scene's gear is a tripod".into()));
        }
        if let Some(n) = scenario.surface.pads.iter().position(|p| !p.locked()) {
            return Err(refuse(format!(
                "footpad {} slides on its surface (surface.obstacle and surface.spike_depth are 0)",
                n + 1
            )));
        }
        let inertia_min = scenario.vehicle.inertia.symmetric_eigenvalues().min();
        Ok(Some(Settling {
            tolerance,
            inertia_min,
            interval: CHECK_STEPS * scenario.integrator.dt_max,
        }))
    }
}

/// What the certificate needs of one leg (reused between checks).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct LegTerms {
    /// Footpad position from the centre of mass, body axes, m.
    pub(crate) bp: Vector3<f64>,
    /// ∂(c, S31, S41)/∂BP, 1.
    pub(crate) jacobian: Matrix3<f64>,
    /// Strokes c, S31, S41, m.
    pub(crate) strokes: Vector3<f64>,
    /// Honeycomb forces at the accepted state, N (the strokes' senses).
    pub(crate) forces: Vector3<f64>,
    /// The rebound rates K_B of the sides the strokes are on, N/m.
    pub(crate) rates: Vector3<f64>,
    /// Stored energies at the accepted state, J.
    pub(crate) stored: Vector3<f64>,
    /// The loads f holding the vehicle at rest, N (the strokes' senses).
    pub(crate) loads: Vector3<f64>,
    /// Whether its footpad is in contact and bears.
    pub(crate) bearing: bool,
    /// Its struts' minorants.
    pub(crate) reach: Option<[StrutReach; 3]>,
    /// The strokes each strut can reach with the energy left, m.
    pub(crate) intervals: [(f64, f64); 3],
    /// How far its footpad can move on the vehicle with the energy left, m.
    pub(crate) give: f64,
    /// Which struts are slack (no load, within the band between their permanent sets).
    pub(crate) slack: [bool; 3],
    /// The surface's reaction on a bearing footpad along the surface's normal, N.
    pub(crate) pressing: f64,
    /// Its footpad's lift's place in the motion ([`Motion`]).
    pub(crate) lift: usize,
    /// The compliances the balance weighs its struts' loads by, N/m.
    pub(crate) compliance: Vector3<f64>,
    /// The loads, bearing and pressing of the best balance so far.
    pub(crate) kept: (Vector3<f64>, bool, f64),
}

impl LegTerms {
    /// Strut `j`'s stroke as a linear function of the motion (its row a, 1 and m): the
    /// footpad moves on the vehicle by −Δx + BP × δθ + n̂·Δz.
    pub(crate) fn row(&self, j: usize, up_b: &Vector3<f64>) -> Motion {
        let dj = self.jacobian.row(j).transpose();
        let mut a = Motion::zeros();
        a.fixed_rows_mut::<3>(0).copy_from(&(-dj));
        a.fixed_rows_mut::<3>(3).copy_from(&dj.cross(&self.bp));
        a[self.lift] = dj.dot(up_b);
        a
    }
}

/// Body translation and rotation (body axes), then each bearing footpad's lift.
pub(crate) type Motion = SVector<f64, { 6 + MAX_LEGS }>;
