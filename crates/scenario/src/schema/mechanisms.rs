//! The optional mechanisms: soil, curbs, descent-engine thrust, RCS and propellant slosh.

use serde::{Deserialize, Serialize};

/// The soil model of eqs. (101)-(102) (corrected: docs/errata.md). Pressures are force/length²
/// in the file's units (the report gives psi). The footpad bottom area AP is π·PR².
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Soil {
    /// K1, bearing strength at the surface; force/length².
    pub k1: f64,
    /// K2, increase of bearing strength with penetration depth; force/length³.
    pub k2: f64,
    /// K3, increase of bearing strength with penetration rate; force·time/length³.
    #[serde(default)]
    pub k3: f64,
    /// K4, increase of bearing strength with the penetration rate squared; force·time²/length⁴.
    #[serde(default)]
    pub k4: f64,
    /// K5, static resistance to horizontal movement; force/length².
    #[serde(default)]
    pub k5: f64,
    /// K6, increase of lateral resistance with lateral displacement; force/length³.
    #[serde(default)]
    pub k6: f64,
    /// K7, increase of lateral resistance with penetration depth; force/length³.
    #[serde(default)]
    pub k7: f64,
    /// K8, increase of lateral resistance with the horizontal speed squared;
    /// force·time²/length⁴.
    #[serde(default)]
    pub k8: f64,
}

/// One curb beside a footpad (fig. 19), placed relative to the footpad's first contact point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Curb {
    /// The leg whose footpad meets this curb, 1-based in leg order.
    pub leg: usize,
    /// DWALLI: normal distance from the footpad centre to the curb at first contact; length.
    pub distance: f64,
    /// WALANG: angle from +X to the curb's normal (from the footpad toward the curb) in the
    /// surface plane; angle.
    pub angle: f64,
    /// UW: friction coefficient between the footpad and the curb; dimensionless.
    #[serde(default)]
    pub friction: f64,
}

/// The descent engine (eqs. 69-74): thrust along +Z_B through the nozzle exit centroid, its
/// tailoff, amplification near the surface and nozzle crushing.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Thrust {
    /// F1, thrust before the tailoff (eq. 69); force.
    pub thrust: f64,
    /// t2, start of the tailoff on the thrust-curve clock (fig. 15); time.
    pub tailoff_start: f64,
    /// t_p, the thrust-curve clock at touchdown (simulation time 0); time.
    #[serde(default)]
    pub clock_at_touchdown: f64,
    /// K, exponential decay rate of the tailoff (eq. 70); 1/time. Absent: no exponential term.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub decay_rate: Option<f64>,
    /// M0, M1, M2, ... polynomial tailoff coefficients (eq. 70); force, force/time,
    /// force/time², ... The curve must be continuous at t2: M0 = 0 with the exponential,
    /// M0 = F1 without it.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub polynomial: Vec<f64>,
    /// R_T, centroid of the nozzle exit plane in body axes; length.
    pub nozzle_exit: [f64; 3],
    /// AMP(ZNOZ), the thrust amplification table of fig. 16 (eq. 71); absent: AMP = 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub amplification: Option<Amplification>,
    /// Nozzle crushing (eqs. 72-73); absent: the nozzle never touches.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nozzle_crushing: Option<NozzleCrushing>,
}

/// The thrust amplification factor as a function of nozzle clearance, linear between points
/// and constant beyond the ends.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Amplification {
    /// ZNOZ, clearance of the nozzle exit centroid above the surface, increasing; length.
    pub clearance: Vec<f64>,
    /// AMP at each clearance; dimensionless.
    pub factor: Vec<f64>,
}

/// The nozzle's crushing under constant load (eqs. 72-73, docs/errata.md, "Eqs. (72)-(73): nozzle crushing").
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NozzleCrushing {
    /// Radius of the nozzle exit rim; length.
    pub exit_radius: f64,
    /// Crushing load of the whole rim, shared in proportion to the rim in contact; force.
    pub crush_load: f64,
}

/// RCS control mode of eqs. (78)-(79).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RcsMode {
    /// Attitude hold: errors from attitude and rate.
    AttitudeHold,
    /// Rate command: the attitude gains are zero.
    RateCommand,
}

/// The reaction control system (eqs. 75-82): fixed torques about each body axis switched on
/// outside a deadband, then optionally a downward translation force.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Rcs {
    /// Control mode.
    pub mode: RcsMode,
    /// k11, k21, k31: attitude gains (eq. 78); dimensionless. Ignored (zero) in rate command.
    #[serde(default)]
    pub attitude_gain: [f64; 3],
    /// k12, k22, k32: rate gains (eq. 78); time.
    pub rate_gain: [f64; 3],
    /// EXM, EYM, EZM: deadbands of the errors (eq. 79); angle.
    pub deadband: [f64; 3],
    /// TORQX, TORQY, TORQZ: torque magnitudes about the body axes; force·length.
    pub torque: [f64; 3],
    /// Cθx, Cθy, Cθz: commanded Euler angles (eq. 76); angle.
    #[serde(default)]
    pub commanded_attitude: [f64; 3],
    /// Cωx, Cωy, Cωz: commanded body rates (eq. 75); angle/time.
    #[serde(default)]
    pub commanded_rates: [f64; 3],
    /// Downward translation after a delay from first contact (eq. 81); absent: none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub downward_translation: Option<DownwardTranslation>,
}

/// The downward-translation mode: no couples, a force down the centre line.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DownwardTranslation {
    /// Delay from the first footpad contact; time.
    pub delay: f64,
    /// FRCSZ, the force along −Z_B; force.
    pub force: f64,
}

/// Propellant sloshing, first mode (appendix, eqs. 108-117, corrected): a slosh mass
/// M_s = F_s/ω² on a spring in the X_B-Y_B plane, ℓ1 + ℓ below the total centre of mass.
/// The vehicle's mass and inertia include the propellant as rigid.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Slosh {
    /// F_s, wall force per unit axial acceleration per unit amplitude (eq. 108);
    /// mass/length (F_s = M_s·ω², eq. 112).
    pub force_coefficient: f64,
    /// ω², slosh frequency squared per unit axial acceleration (eq. 109); 1/length.
    pub frequency_parameter: f64,
    /// ℓ1, from the total centre of mass down to the quiescent free surface; length.
    pub free_surface_depth: f64,
    /// ℓ, from the free surface down to the slosh mass (and the force centroid); length.
    pub mass_depth: f64,
    /// Initial slosh amplitude q (X_B, Y_B); length.
    #[serde(default)]
    pub initial_amplitude: [f64; 2],
}
