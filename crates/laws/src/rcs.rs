//! Reaction-control-system torques and force, eqs. (75)-(82) (docs/errata.md, "Eqs. (76), (78)-(79): RCS switching — interpreted").
//!
//! Per body axis i, the switching error `E_i = k_i1·Eθ_i + k_i2·Eω_i` (eq. 78) drives an
//! on-off torque of fixed magnitude TORQ_i against the error outside a deadband EM_i (eq. 79);
//! no hysteresis, minimum on-time or sampling (the report's simplification). The optional
//! downward-translation mode replaces the torques, a delay after first contact, by a force
//! FRCSZ along −Z_B (eq. 81).
//!
//! Units: SI throughout (rad, rad/s, s, N, N·m). The report gives angles in deg and rates in
//! deg/s; with k_i1 dimensionless and k_i2 in seconds, E = k1·Eθ + k2·Eω scales uniformly with
//! the angle unit, so the report's gains carry over unchanged and only the deadbands EM_i (and
//! the commanded angles and rates) convert from deg to rad.

use nalgebra::Vector3;
use touchdown_frames::t_eb;

use crate::{finite, non_negative, positive, LawError};

/// Input data of the RCS law: the scenario's resolved table (SI; per-axis vectors are
/// (X_B, Y_B, Z_B); commanded angles are used in attitude hold, commanded rates in rate
/// command) and its control mode (eqs. 78-79).
pub use touchdown_scenario::model::{DownwardTranslation, Rcs as RcsParams, RcsMode};

/// RCS loads on the vehicle, body axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RcsLoads {
    /// Control torque MRCS, N·m, body axes (eq. 80).
    pub torque: Vector3<f64>,
    /// Control force FRCS, N, body axes (eq. 81); the caller applies FRCSI = T_BI·FRCS (eq. 82).
    pub force: Vector3<f64>,
}

/// The RCS law with the mode's constraints applied (see [`Rcs::new`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rcs {
    mode: RcsMode,
    k1: Vector3<f64>,
    k2: Vector3<f64>,
    deadband: Vector3<f64>,
    torque: Vector3<f64>,
    cmd_theta: Vector3<f64>,
    cmd_omega: Vector3<f64>,
    translation: Option<DownwardTranslation>,
}

/// Checks every component of `v` with `check` (one of the crate's parameter checks).
fn each(
    name: &'static str,
    v: &Vector3<f64>,
    check: fn(&'static str, f64) -> Result<f64, LawError>,
) -> Result<(), LawError> {
    v.iter().try_for_each(|&x| check(name, x).map(|_| ()))
}

/// `x` wrapped into (−π, π], rad (docs/errata.md, "Eqs. (76), (78)-(79): RCS switching — interpreted").
#[inline]
fn wrap_pi(x: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    PI - (PI - x).rem_euclid(TAU)
}

impl Rcs {
    /// Builds the law, deriving the mode's constraints rather than trusting the input: in
    /// [`RcsMode::RateCommand`] the attitude gains are set to 0 (the report's definition of the
    /// mode); in [`RcsMode::AttitudeHold`] the commanded rates are set to 0 (as the report
    /// states for eq. 78).
    ///
    /// Errors if a gain, torque or translation parameter is negative or not finite, a deadband
    /// is not positive, or a commanded angle or rate is not finite.
    pub fn new(p: RcsParams) -> Result<Self, LawError> {
        each("RCS attitude gain k_i1", &p.attitude_gain, non_negative)?;
        each("RCS rate gain k_i2", &p.rate_gain, non_negative)?;
        each("RCS deadband EM", &p.deadband, positive)?;
        each("RCS torque TORQ", &p.torque, non_negative)?;
        each("RCS commanded angle", &p.commanded_attitude, finite)?;
        each("RCS commanded rate", &p.commanded_rates, finite)?;
        if let Some(t) = p.downward_translation {
            non_negative("RCS translation delay", t.delay)?;
            non_negative("RCS translation force FRCSZ", t.force)?;
        }
        let (k1, cmd_omega) = match p.mode {
            RcsMode::AttitudeHold => (p.attitude_gain, Vector3::zeros()),
            RcsMode::RateCommand => (Vector3::zeros(), p.commanded_rates),
        };
        Ok(Rcs {
            mode: p.mode,
            k1,
            k2: p.rate_gain,
            deadband: p.deadband,
            torque: p.torque,
            cmd_theta: p.commanded_attitude,
            cmd_omega,
            translation: p.downward_translation,
        })
    }

    /// Switching errors (EX, EY, EZ), rad, for Euler angles `theta` (rad) and body rates
    /// `omega` (rad/s):
    /// - Eω = ω − Cω (eq. 75);
    /// - Dθ = θ − Cθ, each wrapped into (−π, π] (eq. 76, docs/errata.md, "Eqs. (76), (78)-(79): RCS switching — interpreted");
    /// - Eθ = T_EB(θ)·Dθ (eq. 77): the report's small-deviation treatment, mapping the Euler
    ///   deviations like Euler rates with T_EB (eq. 6) evaluated at the current attitude θ;
    /// - E = k1∘Eθ + k2∘Eω (eq. 78, per axis).
    #[inline]
    pub fn errors(&self, theta: &Vector3<f64>, omega: &Vector3<f64>) -> Vector3<f64> {
        let e_omega = omega - self.cmd_omega; // eq. (75)
        let d_theta = (theta - self.cmd_theta).map(wrap_pi); // eq. (76), wrapped
        let e_theta = t_eb(theta) * d_theta; // eq. (77)
        self.k1.component_mul(&e_theta) + self.k2.component_mul(&e_omega) // eq. (78)
    }

    /// On-off torque MRCS, N·m, body axes, from the switching errors (rad), eqs. (79)-(80):
    /// per axis −TORQ if E ≥ EM, +TORQ if E ≤ −EM, 0 strictly inside the deadband. The report
    /// leaves |E| = EM unspecified; the jets fire there (docs/errata.md, "Eqs. (76), (78)-(79): RCS switching — interpreted").
    #[inline]
    pub fn torque(&self, errors: &Vector3<f64>) -> Vector3<f64> {
        Vector3::from_fn(|i, _| {
            let (e, em, torq) = (errors[i], self.deadband[i], self.torque[i]);
            // eq. (79)
            if e >= em {
                -torq
            } else if e <= -em {
                torq
            } else {
                0.0
            }
        })
    }

    /// Whether the law has a downward-translation mode (which needs the first contact time).
    #[inline]
    pub fn translates(&self) -> bool {
        self.translation.is_some()
    }

    /// Whether the downward-translation phase is active at time `t` (s), given the time of the
    /// first pad contact (s), if any: translation mode configured and `t ≥ first_contact + delay`.
    #[inline]
    pub fn translating(&self, t: f64, first_contact: Option<f64>) -> bool {
        match (self.translation, first_contact) {
            (Some(tr), Some(tc)) => t >= tc + tr.delay,
            _ => false,
        }
    }

    /// RCS loads at time `t` (s) for Euler angles `theta` (rad), body rates `omega` (rad/s) and
    /// the time of first pad contact `first_contact` (s, `None` before it). Before first
    /// contact + delay (or without the translation mode): the torque of eqs. (75)-(80) and no
    /// force (pure couples). From then on: no torque and FRCS = (0, 0, −FRCSZ) along −Z_B
    /// (eq. 81); the caller applies FRCSI = T_BI·FRCS (eq. 82).
    #[inline]
    pub fn loads(
        &self,
        t: f64,
        first_contact: Option<f64>,
        theta: &Vector3<f64>,
        omega: &Vector3<f64>,
    ) -> RcsLoads {
        match self.translation {
            Some(tr) if self.translating(t, first_contact) => RcsLoads {
                torque: Vector3::zeros(),
                force: Vector3::new(0.0, 0.0, -tr.force), // eq. (81)
            },
            _ => RcsLoads {
                torque: self.torque(&self.errors(theta, omega)), // eq. (80)
                force: Vector3::zeros(),
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const DEG: f64 = std::f64::consts::PI / 180.0;

    fn params(mode: RcsMode) -> RcsParams {
        RcsParams {
            mode,
            attitude_gain: Vector3::new(1.0, 1.0, 1.0),
            rate_gain: Vector3::new(0.5, 0.5, 0.5),
            deadband: Vector3::new(0.3 * DEG, 0.5 * DEG, 1.0 * DEG),
            torque: Vector3::new(500.0, 600.0, 700.0),
            commanded_attitude: Vector3::zeros(),
            commanded_rates: Vector3::new(2.0 * DEG, 0.0, 0.0),
            downward_translation: None,
        }
    }

    #[test]
    fn fires_outside_the_deadband_and_at_its_edge() {
        let rcs = Rcs::new(params(RcsMode::AttitudeHold)).unwrap();
        let em = 0.5 * DEG; // Y axis
                            // Scan E_y across ±2·EM: the torque is −TORQ for E ≥ EM, +TORQ for E ≤ −EM, else 0.
        for i in -200..=200 {
            let e = em * i as f64 / 100.0;
            let t = rcs.torque(&Vector3::new(0.0, e, 0.0)).y;
            let expect = if i >= 100 {
                -600.0
            } else if i <= -100 {
                600.0
            } else {
                0.0
            };
            assert_eq!(t, expect, "E = {i}% of EM");
        }
        // The switching points themselves (docs/errata.md, "Eqs. (76), (78)-(79): RCS switching — interpreted": fire at |E| = EM).
        assert_eq!(rcs.torque(&Vector3::new(0.0, em, 0.0)).y, -600.0);
        assert_eq!(rcs.torque(&Vector3::new(0.0, -em, 0.0)).y, 600.0);
        let inside = em * (1.0 - f64::EPSILON);
        assert_eq!(rcs.torque(&Vector3::new(0.0, inside, 0.0)).y, 0.0);
        assert_eq!(rcs.torque(&Vector3::new(0.0, -inside, 0.0)).y, 0.0);
    }

    #[test]
    fn negative_feedback() {
        // Upright at the command with a positive roll rate of 1 deg/s (E_x = 0.5 s·1°/s = 0.5°
        // > EXM = 0.3°): the torque about X_B opposes the rate. Likewise a positive pitch error.
        let rcs = Rcs::new(params(RcsMode::AttitudeHold)).unwrap();
        let l = rcs.loads(0.0, None, &Vector3::zeros(), &Vector3::new(DEG, 0.0, 0.0));
        assert_eq!(l.torque, Vector3::new(-500.0, 0.0, 0.0));
        assert_eq!(l.force, Vector3::zeros(), "pure couples");
        let l = rcs.loads(
            0.0,
            None,
            &Vector3::new(0.0, 0.0, -2.0 * DEG),
            &Vector3::zeros(),
        );
        assert_eq!(l.torque, Vector3::new(0.0, 0.0, 700.0));
    }

    #[test]
    fn attitude_hold_ignores_commanded_rates() {
        // params() gives Cω_x = 2°/s; attitude hold zeroes it, so ω = 0 gives no rate error.
        let rcs = Rcs::new(params(RcsMode::AttitudeHold)).unwrap();
        assert_eq!(rcs.cmd_omega, Vector3::zeros());
        assert_eq!(
            rcs.errors(&Vector3::zeros(), &Vector3::zeros()),
            Vector3::zeros()
        );
    }

    #[test]
    fn rate_command_ignores_attitude_errors() {
        let rcs = Rcs::new(params(RcsMode::RateCommand)).unwrap();
        assert_eq!(rcs.k1, Vector3::zeros(), "k11 = k21 = k31 = 0");
        // A 20° attitude error and the commanded 2°/s roll rate: no error, no torque.
        let theta = Vector3::new(20.0 * DEG, -20.0 * DEG, 20.0 * DEG);
        let omega = Vector3::new(2.0 * DEG, 0.0, 0.0);
        let e = rcs.errors(&theta, &omega);
        assert!(e.norm() < 1e-15);
        assert_eq!(rcs.torque(&e), Vector3::zeros());
        // Rolling at 0 instead of 2°/s: E_x = 0.5 s·(−2°/s) = −1° ≤ −EXM: +TORQX.
        let e = rcs.errors(&theta, &Vector3::zeros());
        assert!((e.x + 1.0 * DEG).abs() < 1e-15);
        assert_eq!(rcs.torque(&e).x, 500.0);
    }

    #[test]
    fn attitude_deviation_wraps() {
        // θx − Cθx = 350° wraps to −10°. At θ = (θx, 0, 0), T_EB is the identity (eq. 6 with
        // θy = θz = 0), so E_x = k11·(−10°) = −10°.
        let mut p = params(RcsMode::AttitudeHold);
        p.rate_gain = Vector3::zeros();
        p.commanded_attitude = Vector3::new(-175.0 * DEG, 0.0, 0.0);
        let rcs = Rcs::new(p).unwrap();
        let e = rcs.errors(&Vector3::new(175.0 * DEG, 0.0, 0.0), &Vector3::zeros());
        assert!((e.x + 10.0 * DEG).abs() < 1e-12, "{}", e.x / DEG);
        assert_eq!(
            wrap_pi(std::f64::consts::PI),
            std::f64::consts::PI,
            "(−π, π]"
        );
        assert_eq!(wrap_pi(-std::f64::consts::PI), std::f64::consts::PI);
        assert!((wrap_pi(-350.0 * DEG) - 10.0 * DEG).abs() < 1e-12);
    }

    #[test]
    fn attitude_errors_use_t_eb_at_the_current_attitude() {
        // θ = (5°, 0, 90°), command 0, so Dθ = θ. Eq. (6) at θz = 90°: the second row of T_EB is
        // (−cθy·sθz, cθz, 0) = (−1, 0, 0), so the 5° deviation in θx appears about −Y_B.
        let mut p = params(RcsMode::AttitudeHold);
        p.rate_gain = Vector3::zeros();
        let rcs = Rcs::new(p).unwrap();
        let theta = Vector3::new(5.0 * DEG, 0.0, 90.0 * DEG);
        let e = rcs.errors(&theta, &Vector3::zeros());
        let expect = t_eb(&theta) * theta;
        assert!((e - expect).norm() < 1e-15);
        assert!((e.y + 5.0 * DEG).abs() < 1e-12);
    }

    #[test]
    fn translation_switches_to_pure_force_after_the_delay() {
        let mut p = params(RcsMode::AttitudeHold);
        p.downward_translation = Some(DownwardTranslation {
            delay: 1.0,
            force: 800.0,
        });
        let rcs = Rcs::new(p).unwrap();
        let (theta, omega) = (Vector3::zeros(), Vector3::new(DEG, 0.0, 0.0));
        let torque_only = RcsLoads {
            torque: Vector3::new(-500.0, 0.0, 0.0),
            force: Vector3::zeros(),
        };
        let force_only = RcsLoads {
            torque: Vector3::zeros(),
            force: Vector3::new(0.0, 0.0, -800.0),
        };
        assert_eq!(
            rcs.loads(5.0, None, &theta, &omega),
            torque_only,
            "no contact yet"
        );
        // First contact at 0.25 s: the switch is at 1.25 s (exact in binary).
        assert_eq!(
            rcs.loads(1.2, Some(0.25), &theta, &omega),
            torque_only,
            "in delay"
        );
        assert_eq!(
            rcs.loads(1.25, Some(0.25), &theta, &omega),
            force_only,
            "at delay"
        );
        assert_eq!(rcs.loads(4.0, Some(0.25), &theta, &omega), force_only);
        // Without the translation mode, contact changes nothing.
        let plain = Rcs::new(params(RcsMode::AttitudeHold)).unwrap();
        assert_eq!(plain.loads(4.0, Some(0.25), &theta, &omega), torque_only);
    }

    #[test]
    fn rejects_bad_parameters() {
        let mut p = params(RcsMode::AttitudeHold);
        p.deadband.x = 0.0;
        assert!(matches!(Rcs::new(p), Err(LawError::NotPositive { .. })));
        let mut p = params(RcsMode::AttitudeHold);
        p.torque.z = -1.0;
        assert!(matches!(Rcs::new(p), Err(LawError::Negative { .. })));
        let mut p = params(RcsMode::AttitudeHold);
        p.commanded_attitude.y = f64::NAN;
        assert!(matches!(Rcs::new(p), Err(LawError::NotFinite { .. })));
        let mut p = params(RcsMode::AttitudeHold);
        p.downward_translation = Some(DownwardTranslation {
            delay: -1.0,
            force: 1.0,
        });
        assert!(Rcs::new(p).is_err());
    }
}
