//! The resolved scenario: every value in SI, geometry derived, ready for an engine.

use crate::error::Warning;
use crate::schema::{
    self, Arrangement, AttitudeReference, CountedEnergy, ReleaseRule, ScenarioFile, WallRule,
};
use nalgebra::{Matrix3, Vector3};

/// A validated scenario in SI units (m, kg, N, s, rad).
#[derive(Debug, Clone, PartialEq)]
pub struct Scenario {
    /// Path of the file it was read from, as given (for messages).
    pub source: String,
    /// The merged file with every default written out (in the file's units), for `--out`.
    pub file: ScenarioFile,
    /// Rigid vehicle.
    pub vehicle: Vehicle,
    /// Gear arrangement (fig. 4).
    pub arrangement: Arrangement,
    /// Legs in counter-clockwise order seen from above.
    pub legs: Vec<Leg>,
    /// Primary strut.
    pub primary: PrimaryStrut,
    /// Secondary struts.
    pub secondary: SecondaryStrut,
    /// Effective footpad.
    pub footpad: Footpad,
    /// Landing surface.
    pub surface: Surface,
    /// Touchdown conditions.
    pub touchdown: Touchdown,
    /// Integrator settings.
    pub integrator: Integrator,
    /// Stability criteria.
    pub stability: Stability,
    /// The `touchdown compare` tolerances the file sets, each a ratio in (0, 10] (the others
    /// are the testbench's).
    pub comparison: schema::Comparison,
    /// The engines that apply to the scenario, in comparison order, without repeats.
    pub applicable_engines: Vec<schema::Engine>,
    /// Settings of the rapier multibody rebuild.
    pub rapier: Rapier,
    /// Settings of the MuJoCo export.
    pub mujoco: Mujoco,
    /// The gear links of the multibody engines.
    pub links: GearLinks,
    /// Descent engine (eqs. 69-74), if the scene has one.
    pub thrust: Option<Thrust>,
    /// Reaction control system (eqs. 75-82), if the scene has one.
    pub rcs: Option<Rcs>,
    /// Propellant sloshing (eqs. 108-117), if the scene has it.
    pub slosh: Option<Slosh>,
    /// The files of the `extends` chain with their own tables (this file first), to name the
    /// file that sets a field in messages.
    pub(crate) layers: Vec<(String, toml::Table)>,
    /// Values accepted but outside their usual range ([`Scenario::warnings`]).
    pub(crate) warnings: Vec<Warning>,
}

impl Scenario {
    /// The values this scenario holds that are legal (inside their plausible range) but outside
    /// their field's usual range (docs/scenario-format.md, "Ranges"), in the order they were
    /// checked, each naming the file, the field, the value and the usual range. Loading does
    /// not print them: a caller shows them to the user (e.g. on standard error, one a line, as
    /// `warning.to_string()`). Empty for every bundled scenario.
    pub fn warnings(&self) -> &[Warning] {
        &self.warnings
    }

    /// The least energy scale the energy guard judges a residual against, J: the work of the
    /// whole lander's weight, (M + n·PMASS)·g, over DIST, the relative motion eq. (25) resolves
    /// in one step (docs/errata.md, "Energy guard"). Below it a residual is the schemes'
    /// resolution, not a divergence.
    pub fn energy_floor_j(&self) -> f64 {
        let mass = self.vehicle.mass + self.legs.len() as f64 * self.footpad.mass;
        mass * self.vehicle.gravity * self.integrator.dist
    }

    /// The struts' load-stroke diagrams with their field paths: the primary in compression,
    /// the secondaries in compression and in tension.
    pub fn strut_diagrams(&self) -> [(&'static str, &LoadStroke); 3] {
        [
            ("primary_strut.compression", &self.primary.compression),
            ("secondary_strut.compression", &self.secondary.compression),
            ("secondary_strut.tension", &self.secondary.tension),
        ]
    }
}

/// Rigid vehicle (excluding the effective footpad masses).
#[derive(Debug, Clone, PartialEq)]
pub struct Vehicle {
    /// Mass M, kg.
    pub mass: f64,
    /// Inertia tensor J about the centre of mass, body axes, kg·m² (products with the report's
    /// sign: off-diagonal terms are −Ixy, −Ixz, −Iyz).
    pub inertia: Matrix3<f64>,
    /// Gravitational acceleration g, m/s².
    pub gravity: f64,
}

/// One leg's undeformed geometry in body axes (origin at the centre of mass), m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Leg {
    /// B2, primary trunnion, m.
    pub b2: Vector3<f64>,
    /// B3, first secondary trunnion, m.
    pub b3: Vector3<f64>,
    /// B4, second secondary trunnion, m.
    pub b4: Vector3<f64>,
    /// BP, footpad ball joint (undeformed), m.
    pub bp: Vector3<f64>,
    /// L21, B2 to point 1 along the primary strut, m.
    pub l21: f64,
    /// L2P, undeformed primary strut length |BP − B2|, m.
    pub l2p: f64,
    /// L31, undeformed length of the first secondary strut, m.
    pub l31: f64,
    /// L41, undeformed length of the second secondary strut, m.
    pub l41: f64,
}

impl Leg {
    /// Builds a leg from its points, deriving the undeformed lengths (eqs. 27-34 at zero
    /// stroke).
    pub fn from_points(
        b2: Vector3<f64>,
        b3: Vector3<f64>,
        b4: Vector3<f64>,
        bp: Vector3<f64>,
        l21: f64,
    ) -> Leg {
        let v2p = bp - b2;
        let l2p = v2p.norm();
        let b1 = b2 + v2p * (l21 / l2p);
        Leg {
            b2,
            b3,
            b4,
            bp,
            l21,
            l2p,
            l31: (b1 - b3).norm(),
            l41: (b1 - b4).norm(),
        }
    }

    /// Point 1 (secondary attachment) of the undeformed leg, m.
    pub fn b1(&self) -> Vector3<f64> {
        self.b2 + (self.bp - self.b2) * (self.l21 / self.l2p)
    }
}

/// One load-stroke diagram, SI.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadStroke {
    /// Onset rate, N/m.
    pub onset_rate: f64,
    /// Backoff rate, N/m.
    pub backoff_rate: f64,
    /// Stroke-out rate, N/m.
    pub stroke_out_rate: f64,
    /// (crush load N, stroke at end of plateau m), in loading order.
    pub stages: Vec<(f64, f64)>,
    /// Coefficient of restitution of the end stops, in [0, 1].
    pub stop_restitution: f64,
}

impl LoadStroke {
    /// Stroke at which the last stage ends (bottoming begins), m.
    pub fn capacity(&self) -> f64 {
        self.stages.last().map_or(0.0, |s| s.1)
    }
}

/// Viscous law, SI: F = coefficient·sgn(v)·|v|^exponent, N with v in m/s.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Viscous {
    /// N/(m/s)^exponent.
    pub coefficient: f64,
    /// Dimensionless.
    pub exponent: f64,
}

/// Primary strut, SI.
#[derive(Debug, Clone, PartialEq)]
pub struct PrimaryStrut {
    /// Compression load-stroke diagram.
    pub compression: LoadStroke,
    /// Trunnion spring rate K_TP, N/m; `None` if the diagram is already trunnion-modified.
    pub trunnion_rate: Option<f64>,
    /// Viscous law.
    pub viscous: Viscous,
    /// Bearing friction coefficient μB.
    pub bearing_friction: f64,
    /// D1, m.
    pub inner_cylinder_length: f64,
    /// Initial D2, m.
    pub initial_overlap: f64,
    /// Bending stiffness EI of the primary strut (eqs. 40-48), N·m²; `None`: rigid in bending.
    pub bending_stiffness: Option<f64>,
}

/// Secondary struts, SI.
#[derive(Debug, Clone, PartialEq)]
pub struct SecondaryStrut {
    /// Tension diagram.
    pub tension: LoadStroke,
    /// Compression diagram.
    pub compression: LoadStroke,
    /// Trunnion spring rate K_TS, N/m; `None` if rigid.
    pub trunnion_rate: Option<f64>,
    /// Viscous law.
    pub viscous: Viscous,
}

/// Effective footpad, SI.
#[derive(Debug, Clone, PartialEq)]
pub struct Footpad {
    /// PMASS, kg.
    pub mass: f64,
    /// PR, m.
    pub radius: f64,
    /// Footpad height (bounds the frontal area in soil), m; required with soil.
    pub height: Option<f64>,
    /// Footpad crushing diagram against curbs (fig. 18); required with curbs.
    pub crush: Option<LoadStroke>,
    /// How the footpad moves off the surface.
    pub detached: schema::Detached,
}

/// Surface under one footpad.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PadSurface {
    /// HOLE_n, m: the local plane is Z = −hole.
    pub hole: f64,
    /// OBST_n, m: > 0 a wall this high holds the footpad laterally after contact (the
    /// rigid footpad: while in contact); ≤ 0 none.
    pub obstacle: f64,
    /// Spikes' engagement depth, m: > 0 the footpad is held laterally after contact while it
    /// is within this depth of its plane; 0 none. At most one of `obstacle` and `spike_depth`
    /// is positive.
    pub spike_depth: f64,
    /// U_n, sliding friction coefficient.
    pub friction: f64,
}

impl PadSurface {
    /// Height of the local surface plane, Z = −HOLE, m.
    pub fn plane(&self) -> f64 {
        -self.hole
    }
    /// Whether the footpad is locked laterally after contact (OBST > 0, or spikes).
    pub fn locked(&self) -> bool {
        self.hold_height() > 0.0
    }
    /// The height above its plane up to which a landed footpad is held laterally, m: its
    /// obstacle's wall (OBST > 0) or its spikes' engagement depth; ≤ 0 where it slides.
    pub fn hold_height(&self) -> f64 {
        if self.obstacle > 0.0 {
            self.obstacle
        } else {
            self.spike_depth
        }
    }
}

/// Landing surface, SI.
#[derive(Debug, Clone, PartialEq)]
pub struct Surface {
    /// Slope α, rad.
    pub slope: f64,
    /// One entry per leg.
    pub pads: Vec<PadSurface>,
    /// Release rule.
    pub release: ReleaseRule,
    /// Soil constants (eqs. 101-102); `None` on the rigid surface.
    pub soil: Option<Soil>,
    /// Curbs on the rigid surface (eqs. 86-95).
    pub curbs: Vec<Curb>,
}

/// Soil constants of eqs. (101)-(102), SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Soil {
    /// K1, Pa.
    pub k1: f64,
    /// K2, Pa/m.
    pub k2: f64,
    /// K3, Pa·s/m.
    pub k3: f64,
    /// K4, Pa·s²/m².
    pub k4: f64,
    /// K5, Pa.
    pub k5: f64,
    /// K6, Pa/m.
    pub k6: f64,
    /// K7, Pa/m.
    pub k7: f64,
    /// K8, Pa·s²/m².
    pub k8: f64,
}

/// One curb (fig. 19), SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Curb {
    /// Index of the leg (0-based).
    pub leg: usize,
    /// DWALLI, m.
    pub distance: f64,
    /// WALANG, rad.
    pub angle: f64,
    /// UW.
    pub friction: f64,
}

/// Descent engine, SI (eqs. 69-74).
#[derive(Debug, Clone, PartialEq)]
pub struct Thrust {
    /// F1, N.
    pub thrust: f64,
    /// t2 on the thrust-curve clock, s.
    pub tailoff_start: f64,
    /// t_p, the thrust-curve clock at simulation time 0, s.
    pub clock_at_touchdown: f64,
    /// K, 1/s; `None`: no exponential term.
    pub decay_rate: Option<f64>,
    /// M_i, N/s^i.
    pub polynomial: Vec<f64>,
    /// R_T, body axes, m.
    pub nozzle_exit: Vector3<f64>,
    /// AMP table: (clearance m, factor); `None`: AMP = 1.
    pub amplification: Option<Vec<(f64, f64)>>,
    /// Nozzle crushing: (exit radius m, crush load N); `None`: no crushing.
    pub nozzle_crushing: Option<(f64, f64)>,
}

/// RCS control mode of eqs. (78)-(79), as the law takes it (the file's `rcs.mode`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RcsMode {
    /// Attitude hold: the switching error weighs the attitude and the rate errors.
    AttitudeHold,
    /// Rate command: the attitude gains are zero.
    RateCommand,
}

/// Reaction control system, SI (eqs. 75-82).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rcs {
    /// Mode.
    pub mode: RcsMode,
    /// k_i1 (zero in rate command).
    pub attitude_gain: Vector3<f64>,
    /// k_i2, s.
    pub rate_gain: Vector3<f64>,
    /// EM_i, rad.
    pub deadband: Vector3<f64>,
    /// TORQ_i, N·m.
    pub torque: Vector3<f64>,
    /// Cθ, rad.
    pub commanded_attitude: Vector3<f64>,
    /// Cω, rad/s.
    pub commanded_rates: Vector3<f64>,
    /// Downward translation, if the scene has it.
    pub downward_translation: Option<DownwardTranslation>,
}

/// The RCS downward-translation mode (eq. 81), SI: after `delay` from first contact, no torques
/// and a force FRCSZ along −Z_B.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DownwardTranslation {
    /// Delay after the first footpad contact, s.
    pub delay: f64,
    /// FRCSZ, N.
    pub force: f64,
}

/// Propellant sloshing, SI (eqs. 108-117).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Slosh {
    /// F_s, kg/m.
    pub force_coefficient: f64,
    /// ω², 1/m.
    pub frequency_parameter: f64,
    /// ℓ1, m.
    pub free_surface_depth: f64,
    /// ℓ, m.
    pub mass_depth: f64,
    /// q0, m.
    pub initial_amplitude: [f64; 2],
}

/// An optional mechanism of the model, declared by the scene or not.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Mechanism {
    /// Trunnion springs applied to raw load-stroke diagrams (eqs. 35-39).
    TrunnionSprings,
    /// Primary-strut bending (eqs. 40-48).
    Bending,
    /// The tripod gear arrangement.
    Tripod,
    /// Soil surface (eqs. 101-104).
    Soil,
    /// Curbs and footpad crushing (eqs. 86-95).
    Curbs,
    /// Descent-engine thrust and tailoff (eqs. 69-71, 74).
    Thrust,
    /// Nozzle crushing (eqs. 72-73).
    NozzleCrushing,
    /// Reaction control (eqs. 75-82).
    Rcs,
    /// Propellant sloshing (eqs. 108-117).
    Slosh,
}

impl Mechanism {
    /// Every mechanism, in the order of the report.
    pub const ALL: [Mechanism; 9] = [
        Mechanism::TrunnionSprings,
        Mechanism::Bending,
        Mechanism::Tripod,
        Mechanism::Soil,
        Mechanism::Curbs,
        Mechanism::Thrust,
        Mechanism::NozzleCrushing,
        Mechanism::Rcs,
        Mechanism::Slosh,
    ];

    /// Short name, as in summaries and docs/engines.md.
    pub fn name(self) -> &'static str {
        match self {
            Mechanism::TrunnionSprings => "trunnion springs",
            Mechanism::Bending => "strut bending",
            Mechanism::Tripod => "tripod gear",
            Mechanism::Soil => "soil",
            Mechanism::Curbs => "curbs",
            Mechanism::Thrust => "thrust",
            Mechanism::NozzleCrushing => "nozzle crushing",
            Mechanism::Rcs => "rcs",
            Mechanism::Slosh => "slosh",
        }
    }

    /// The scenario field that declares it.
    pub fn field(self) -> &'static str {
        match self {
            Mechanism::TrunnionSprings => "primary_strut.trunnion",
            Mechanism::Bending => "primary_strut.bending",
            Mechanism::Tripod => "gear.arrangement",
            Mechanism::Soil => "surface.soil",
            Mechanism::Curbs => "surface.curbs",
            Mechanism::Thrust => "thrust",
            Mechanism::NozzleCrushing => "thrust.nozzle_crushing",
            Mechanism::Rcs => "rcs",
            Mechanism::Slosh => "slosh",
        }
    }
}

impl Scenario {
    /// The optional mechanisms this scene declares, in the order of [`Mechanism::ALL`]: the
    /// engines build these and nothing else.
    pub fn mechanisms(&self) -> Vec<Mechanism> {
        Mechanism::ALL
            .into_iter()
            .filter(|m| self.declares(*m))
            .collect()
    }

    /// Whether the scene declares mechanism `m`.
    pub fn declares(&self, m: Mechanism) -> bool {
        match m {
            Mechanism::TrunnionSprings => {
                self.primary.trunnion_rate.is_some() || self.secondary.trunnion_rate.is_some()
            }
            Mechanism::Bending => self.primary.bending_stiffness.is_some(),
            Mechanism::Tripod => self.arrangement == Arrangement::Tripod,
            Mechanism::Soil => self.surface.soil.is_some(),
            Mechanism::Curbs => !self.surface.curbs.is_empty(),
            Mechanism::Thrust => self.thrust.is_some(),
            Mechanism::NozzleCrushing => self
                .thrust
                .as_ref()
                .is_some_and(|t| t.nozzle_crushing.is_some()),
            Mechanism::Rcs => self.rcs.is_some(),
            Mechanism::Slosh => self.slosh.is_some(),
        }
    }
}

/// Touchdown conditions, SI.
#[derive(Debug, Clone, PartialEq)]
pub struct Touchdown {
    /// Euler angles as given, rad.
    pub attitude: Vector3<f64>,
    /// Frame of `attitude`.
    pub attitude_reference: AttitudeReference,
    /// Centre-of-mass velocity in the gravity frame, m/s.
    pub velocity_g: Vector3<f64>,
    /// Body rates, rad/s.
    pub body_rates: Vector3<f64>,
    /// Height of the first footpad above its plane at the start, m.
    pub clearance: f64,
}

/// Integrator settings, SI.
#[derive(Debug, Clone, PartialEq)]
pub struct Integrator {
    /// Scheme.
    pub scheme: schema::Scheme,
    /// DIST, m.
    pub dist: f64,
    /// Smallest step, s.
    pub dt_min: f64,
    /// Largest step, s.
    pub dt_max: f64,
    /// End time, s.
    pub t_end: f64,
    /// Land airborne footpads on their plane instead of overshooting.
    pub contact_step_limit: bool,
    /// Divergence guard on the energy residual (fraction of the energy scale).
    pub energy_tolerance: f64,
    /// Run budget, accepted steps (force evaluations: ten times as many).
    pub max_steps: u64,
    /// Attitude representation.
    pub attitude: schema::AttitudeForm,
    /// `dopri5` relative tolerance.
    pub rtol: f64,
    /// `dopri5` absolute tolerance, SI units of each state component.
    pub atol: f64,
    /// The report's scheme: the longest step as a multiple of `dt_max` where the engaged
    /// gear is softer than its end stops (1: Δt ≤ `dt_max`).
    pub stride: f64,
    /// The `strides` scheme's largest ω·Δt on the gear's stiffest engaged mode (trace bound).
    pub mode_step: f64,
}

/// Stability criteria, SI.
#[derive(Debug, Clone, PartialEq)]
pub struct Stability {
    /// Kinetic-energy fraction of condition 1.
    pub kinetic_energy_fraction: f64,
    /// Energy counted by condition 1.
    pub counted_energy: CountedEnergy,
    /// Minimum separation velocity of condition 4, m/s.
    pub min_separation_velocity: f64,
    /// Walls counted for the unstable declaration.
    pub walls: WallRule,
    /// End the run at an unstable decision (a stable landing runs to its end time).
    pub terminate_on_decision: bool,
    /// The core ends a stable landing once no maximum stroke can grow by more than this, m,
    /// and no overturn is reachable; `None`: every landing runs to its end time.
    pub settled_tolerance: Option<f64>,
}

/// Settings of the rapier multibody rebuild, SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rapier {
    /// Fixed time step, s; `None`: derived from the scenario's scale
    /// (`touchdown_multibody::RapierSettings`).
    pub timestep: Option<f64>,
    /// Contact natural frequency, Hz; `None`: derived.
    pub contact_frequency: Option<f64>,
    /// Contact damping ratio.
    pub contact_damping_ratio: f64,
    /// The most time steps one step may take between the end stops (≥ 1; 1: the time step
    /// throughout).
    pub stride: u32,
}

/// Settings of the MuJoCo export, SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mujoco {
    /// Fixed time step, s; `None`: derived from the scenario's scale
    /// (`touchdown_multibody::MujocoSettings`).
    pub timestep: Option<f64>,
    /// Contact time constant (`solref[0]`), s; `None`: derived.
    pub contact_timeconst: Option<f64>,
    /// Contact damping ratio (`solref[1]`).
    pub contact_damping_ratio: f64,
    /// Width of the contact impedance ramp (`solimp[2]`), m; `None`: derived.
    pub contact_width: Option<f64>,
}

impl Mujoco {
    /// The least contact time constant MuJoCo takes, in time steps (it silently raises a
    /// smaller one).
    pub const MIN_TIMECONST_PER_STEP: f64 = 2.0;
}

/// The gear links the multibody engines add.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GearLinks {
    /// Outer-cylinder link mass / effective footpad mass.
    pub outer_cylinder_mass_ratio: f64,
    /// Link inertia radius / L2P.
    pub link_radius_ratio: f64,
}

impl GearLinks {
    /// Length of a gear's outer-cylinder link, m: trunnion B2 to the gland bearing at D1 − D2
    /// above the footpad; for the cantilever at least L21, so that point 1 is on it (the
    /// tripod's point 1 is the footpad, on the inner cylinder).
    pub fn outer_cylinder_length(
        &self,
        leg: &Leg,
        primary: &PrimaryStrut,
        arrangement: Arrangement,
    ) -> f64 {
        let gland = leg.l2p - primary.inner_cylinder_length + primary.initial_overlap;
        match arrangement {
            Arrangement::Cantilever => gland.max(leg.l21),
            Arrangement::Tripod => gland,
        }
    }

    /// Radius of a footpad's contact sphere, m: 0.002 L2P. The footpad body turns with the
    /// strut (the report's ball joint is not modelled), so its contact sphere rolls as the
    /// strut rotates; a small sphere keeps that rolling, which moves the ball joint by radius ×
    /// rotation, negligible (about 0.3 mm on the 1/6-scale model).
    pub fn contact_radius(&self, leg: &Leg) -> f64 {
        0.002 * leg.l2p
    }

    /// Radius of a gear's links for their inertia, m.
    pub fn radius(&self, leg: &Leg) -> f64 {
        self.link_radius_ratio * leg.l2p
    }

    /// Moment of inertia, kg·m², of a gear link of mass `mass` (kg) and length `length` (m): a
    /// solid cylinder's transverse moment about its centre, used about every axis. The spin
    /// about the strut axis is a degree of freedom the report's gear does not have; giving it
    /// the transverse moment, not a thin rod's tiny axial one, keeps the gyroscopic term
    /// ω × Jω zero, which multibody engines integrate explicitly and which turns unstable for
    /// slender links.
    pub fn moment(&self, leg: &Leg, mass: f64, length: f64) -> f64 {
        let r = self.radius(leg);
        mass * (3.0 * r * r + length * length) / 12.0
    }
}
