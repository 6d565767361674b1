//! Descent-engine thrust and nozzle-crushing forces, eqs. (69)-(74).
//!
//! - [`Tailoff`]: the thrust history F_THRUST(t) of fig. 15, eqs. (69)-(70).
//! - [`Amplification`]: the ground-effect factor AMP(ZNOZ) of fig. 16 (missing from the report:
//!   a table), eq. (71): TAF = AMP·F_THRUST along +Z_B.
//! - [`Nozzle`]: constant-load crushing of the nozzle exit rim against the surface plane
//!   (docs/errata.md, "Eqs. (72)-(73): nozzle crushing"): the force FFL = F_c·(fraction of
//!   the rim in contact) along +Z_B, applied at the centroid R_F of the contacting arc, bounded
//!   by what stops the rim within a step ([`RimArrest`]).
//! - [`engine_loads`]: F_TF = TAF + FFL and MTF = R_T×TAF + R_F×FFL in body axes,
//!   eqs. (72)-(73). Eq. (74), FTFI = T_BI·F_TF, is the caller's.
//!
//! Units: N, m, s. Body vectors are measured from the rigid-vehicle centre of mass.

use crate::{finite, non_negative, positive};
use nalgebra::{Matrix3, Vector3};

use crate::LawError;

/// Maximum number of polynomial coefficients M0, M1, ... of eq. (70).
pub const MAX_TERMS: usize = 6;
/// Maximum number of points in the amplification table.
pub const MAX_POINTS: usize = 32;
/// Number of equally spaced points sampling the nozzle exit rim.
pub const RIM_SAMPLES: usize = 72;
/// Smallest (T_BI·ẑ_B)_z used to convert a vertical depth into a depth along Z_B: keeps the
/// penetration finite when the vehicle axis is at or beyond horizontal (overturned, outside the
/// law's domain).
const AXIS_Z_MIN: f64 = 1e-6;

/// Engine thrust tailoff, eqs. (69)-(70), on the thrust-curve clock `t_curve = tp + t_sim`
/// (docs/errata.md, "Eq. (70): tailoff continuity at t2 and clamp — corrected").
///
/// For `t_curve ≤ t2` the thrust is F1 (eq. 69). For `t_curve > t2`, with τ = t_curve − t2,
/// `F = [F1·e^(−K·τ)] + M0 + M1·τ + M2·τ² + ...` (eq. 70; the exponential only if a decay
/// constant K is given), clamped at ≥ 0 (docs/errata.md, "Eq. (70): tailoff continuity at t2 and clamp — corrected"). The printed form jumps at t2 unless
/// M0 = 0 with the exponential, or M0 = F1 without it; [`Tailoff::new`] rejects a
/// discontinuous curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tailoff {
    f1: f64,
    t2: f64,
    tp: f64,
    decay: Option<f64>,
    poly: [f64; MAX_TERMS],
    n_terms: usize,
}

impl Tailoff {
    /// A tailoff curve from:
    /// - `f1`: the constant thrust F1 before tailoff, N (≥ 0; the hover thrust for the LM);
    /// - `t2`: start of the tailoff on the thrust-curve clock, s (finite, or +∞ for no tailoff);
    /// - `tp`: the thrust-curve clock at simulation time 0 (station t_p of fig. 15), s;
    /// - `decay`: the exponential decay constant K, 1/s (≥ 0), or `None` for no exponential;
    /// - `poly`: M0, M1, M2, ... in N, N/s, N/s², ... (at most [`MAX_TERMS`]; may be empty).
    ///
    /// Errors on non-finite or negative inputs, too many terms, or a curve whose value just
    /// after t2 differs from F1 by more than 1e-9·max(F1, 1) N.
    pub fn new(
        f1: f64,
        t2: f64,
        tp: f64,
        decay: Option<f64>,
        poly: &[f64],
    ) -> Result<Self, LawError> {
        non_negative("thrust F1", f1)?;
        if t2.is_nan() || t2 == f64::NEG_INFINITY {
            return Err(LawError::Tailoff(format!(
                "tailoff start t2 must be finite or +inf, got {t2}"
            )));
        }
        finite("thrust-curve time at simulation start tp", tp)?;
        if let Some(k) = decay {
            non_negative("tailoff decay constant K", k)?;
        }
        if poly.len() > MAX_TERMS {
            return Err(LawError::Tailoff(format!(
                "at most {MAX_TERMS} polynomial coefficients, got {}",
                poly.len()
            )));
        }
        let mut coeffs = [0.0; MAX_TERMS];
        for (c, &m) in coeffs.iter_mut().zip(poly) {
            *c = finite("tailoff polynomial coefficient", m)?;
        }
        let curve = Tailoff {
            f1,
            t2,
            tp,
            decay,
            poly: coeffs,
            n_terms: poly.len(),
        };
        if t2.is_finite() {
            let after = curve.tail(0.0);
            if (after - f1).abs() > 1e-9 * f1.max(1.0) {
                return Err(LawError::Tailoff(format!(
                    "the curve jumps at t2 from F1 = {f1} N to {after} N; use M0 = 0 with the \
                     exponential, or M0 = F1 without it (docs/errata.md, eq. 70)"
                )));
            }
        }
        Ok(curve)
    }

    /// Eq. (70) before clamping, N, at τ = t_curve − t2 ≥ 0 s.
    #[inline]
    fn tail(&self, tau: f64) -> f64 {
        // eq. (70): F1·e^(−K·τ) + M0 + M1·τ + M2·τ² + ... (polynomial by Horner)
        let exp = self.decay.map_or(0.0, |k| self.f1 * (-k * tau).exp());
        let poly = self.poly[..self.n_terms]
            .iter()
            .rev()
            .fold(0.0, |acc, &m| acc * tau + m);
        exp + poly
    }

    /// Engine thrust F_THRUST, N (≥ 0), at simulation time `t_sim`, s.
    #[inline]
    pub fn thrust(&self, t_sim: f64) -> f64 {
        let t = self.tp + t_sim; // thrust-curve clock (docs/errata.md, "Eq. (70): tailoff continuity at t2 and clamp — corrected")
        if t <= self.t2 {
            self.f1 // eq. (69)
        } else {
            // eq. (70), clamped ≥ 0 (NaN from overflowing terms also maps to 0)
            self.tail(t - self.t2).max(0.0)
        }
    }
}

/// Thrust amplification factor AMP(ZNOZ) (fig. 16, missing: a table), dimensionless, as a
/// function of the nozzle clearance ZNOZ, m. Linear interpolation between the points, constant
/// beyond the ends. Eq. (71): TAF = AMP·F_THRUST, along +Z_B.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Amplification {
    clearance: [f64; MAX_POINTS],
    factor: [f64; MAX_POINTS],
    n: usize,
}

impl Amplification {
    /// A table from clearances ZNOZ (m, strictly increasing) and factors AMP (dimensionless,
    /// > 0), 1 to [`MAX_POINTS`] points.
    pub fn new(clearance: &[f64], factor: &[f64]) -> Result<Self, LawError> {
        let n = clearance.len();
        if n != factor.len() {
            return Err(LawError::Table(format!(
                "amplification: {n} clearances but {} factors",
                factor.len()
            )));
        }
        if n == 0 || n > MAX_POINTS {
            return Err(LawError::Table(format!(
                "amplification: expected 1 to {MAX_POINTS} points, got {n}"
            )));
        }
        let mut out = Amplification {
            clearance: [0.0; MAX_POINTS],
            factor: [0.0; MAX_POINTS],
            n,
        };
        for i in 0..n {
            let (z, a) = (clearance[i], factor[i]);
            finite("amplification clearance", z)?;
            positive("amplification factor", a)?;
            if i > 0 && z <= clearance[i - 1] {
                return Err(LawError::Table(format!(
                    "amplification: clearances must increase strictly, got {} then {z} m",
                    clearance[i - 1]
                )));
            }
            out.clearance[i] = z;
            out.factor[i] = a;
        }
        Ok(out)
    }

    /// AMP = 1 at every clearance (no ground effect).
    pub fn unit() -> Self {
        let mut out = Amplification {
            clearance: [0.0; MAX_POINTS],
            factor: [0.0; MAX_POINTS],
            n: 1,
        };
        out.factor[0] = 1.0;
        out
    }

    /// Amplification factor AMP, dimensionless, at nozzle clearance ZNOZ = `clearance`, m.
    #[inline]
    pub fn factor(&self, clearance: f64) -> f64 {
        let (z, a) = (&self.clearance[..self.n], &self.factor[..self.n]);
        if clearance <= z[0] {
            return a[0];
        }
        for i in 1..self.n {
            if clearance <= z[i] {
                return a[i - 1] + (a[i] - a[i - 1]) * (clearance - z[i - 1]) / (z[i] - z[i - 1]);
            }
        }
        a[self.n - 1]
    }
}

/// The part of the nozzle exit rim at or below the surface plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RimContact {
    /// Fraction of the rim (of the [`RIM_SAMPLES`] sample points) at or below the plane, 0..1.
    pub fraction: f64,
    /// Centroid of the contacting rim points, body axes, m (R_F of eq. 73); the crushed exit
    /// centroid R_T + c·ẑ_B when no point is in contact.
    pub centroid: Vector3<f64>,
    /// Largest depth of a contacting point below the plane, measured along Z_B
    /// (vertical depth / (T_BI·ẑ_B)_z), m, ≥ 0: the further crush that would bring the rim back
    /// to the plane.
    pub penetration: f64,
}

/// What arrests the nozzle's rim within a step (docs/errata.md, "Eqs. (72)-(73): nozzle
/// crushing"): the vehicle's mass M (kg) and inverse inertia J⁻¹ (body axes, 1/(kg·m²)),
/// which give the rim's effective mass along Z_B, and the arrest time τ (s), the longest step
/// of the engine that applies the law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RimArrest {
    mass: f64,
    inertia_inv: Matrix3<f64>,
    time: f64,
}

impl RimArrest {
    /// From the vehicle's mass M (kg, > 0) and inertia J about its centre of mass (body axes,
    /// kg·m², positive definite) and the arrest time τ (s, > 0).
    pub fn new(mass: f64, inertia: &Matrix3<f64>, time: f64) -> Result<Self, LawError> {
        positive("vehicle mass", mass)?;
        positive("nozzle arrest time", time)?;
        let inertia_inv = inertia
            .try_inverse()
            .filter(|j| j.iter().all(|x| x.is_finite()))
            .ok_or(LawError::NotPositive {
                name: "vehicle inertia's determinant",
                value: inertia.determinant(),
            })?;
        Ok(RimArrest {
            mass,
            inertia_inv,
            time,
        })
    }

    /// The vehicle's effective mass for a force along Z_B at `at` (body axes, m from the
    /// centre of mass), kg: 1/m_eff = 1/M + (r×ẑ_B)·J⁻¹·(r×ẑ_B), the free rigid body's
    /// response at that point (the legs and footpads can only make it heavier).
    pub fn effective_mass(&self, at: &Vector3<f64>) -> f64 {
        let arm = at.cross(&Vector3::z());
        1.0 / (1.0 / self.mass + arm.dot(&(self.inertia_inv * arm)))
    }
}

/// Constant-load crushing of the descent-engine nozzle (eqs. 72-73, docs/errata.md, "Eqs. (72)-(73): nozzle crushing").
///
/// The exit rim is the circle of radius r_e about the exit-plane centroid R_T in the
/// X_B–Y_B plane, shifted by the stored crush c (m, ≥ 0) along +Z_B (the nozzle shortens).
/// The crushing force FFL acts along +Z_B at the centroid R_F of the contacting arc while the
/// rim moves into the surface at speed s: F_c·(rim fraction in contact), or less, what stops
/// the rim within the arrest time τ, m_eff·s/τ ([`RimArrest`]); none while the rim stands or
/// leaves. It never does work on the vehicle but negative. The crush c is the law's memory:
/// the caller commits `c ← c + penetration` at accepted states, so a force exists only while
/// the rim is at or beyond the stored crush (constant-load crushing, no rebound force).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Nozzle {
    exit_centroid: Vector3<f64>,
    exit_radius: f64,
    crush_load: f64,
    arrest: RimArrest,
}

impl Nozzle {
    /// A nozzle from its exit-plane centroid R_T (body axes, m), exit radius r_e (m, > 0),
    /// crush load F_c (N, ≥ 0: the constant compressive failure load of the whole rim) and
    /// what arrests its rim.
    pub fn new(
        exit_centroid: Vector3<f64>,
        exit_radius: f64,
        crush_load: f64,
        arrest: RimArrest,
    ) -> Result<Self, LawError> {
        for &v in exit_centroid.iter() {
            finite("nozzle exit centroid R_T", v)?;
        }
        positive("nozzle exit radius", exit_radius)?;
        non_negative("nozzle crush load", crush_load)?;
        Ok(Nozzle {
            exit_centroid,
            exit_radius,
            crush_load,
            arrest,
        })
    }

    /// The exit radius r_e, m.
    pub fn exit_radius(&self) -> f64 {
        self.exit_radius
    }

    /// The rim's contact with the surface plane Z = `surface_z` (m, inertial), sampled at
    /// [`RIM_SAMPLES`] equally spaced points, for stored crush `crush` (m), CM `position`
    /// (inertial, m) and body → inertial rotation `t_bi` (eq. 3). A point is in contact when its
    /// inertial Z is at or below the plane.
    #[inline]
    pub fn rim_contact(
        &self,
        crush: f64,
        position: &Vector3<f64>,
        t_bi: &Matrix3<f64>,
        surface_z: f64,
    ) -> RimContact {
        let center = self.exit_centroid + Vector3::new(0.0, 0.0, crush);
        let axis_z = t_bi[(2, 2)].max(AXIS_Z_MIN); // (T_BI·ẑ_B)_z
        let mut count = 0usize;
        let mut sum = Vector3::zeros();
        let mut deepest = 0.0f64;
        for k in 0..RIM_SAMPLES {
            let phi = std::f64::consts::TAU * k as f64 / RIM_SAMPLES as f64;
            let (s, c) = phi.sin_cos();
            let p = center + Vector3::new(self.exit_radius * c, self.exit_radius * s, 0.0);
            let depth = surface_z - (position.z + (t_bi * p).z);
            if depth >= 0.0 {
                count += 1;
                sum += p;
                deepest = deepest.max(depth);
            }
        }
        if count == 0 {
            return RimContact {
                fraction: 0.0,
                centroid: center,
                penetration: 0.0,
            };
        }
        RimContact {
            fraction: count as f64 / RIM_SAMPLES as f64,
            centroid: sum / count as f64, // R_F of eq. (73)
            penetration: deepest / axis_z,
        }
    }

    /// Nozzle crushing load FFL, N, along +Z_B (eq. 72) on the vehicle whose centre of mass
    /// moves at `velocity` (m/s) and which turns at `omega` (rad/s), both body axes: with the
    /// rim moving into the surface at s = −ẑ_B·(v + ω×R_F), min(F_c·fraction of the rim in
    /// contact, m_eff·s/τ); 0 for s ≤ 0, so FFL·s ≥ 0 at every evaluation.
    #[inline]
    pub fn force(
        &self,
        contact: &RimContact,
        velocity: &Vector3<f64>,
        omega: &Vector3<f64>,
    ) -> f64 {
        if contact.fraction == 0.0 {
            return 0.0;
        }
        let approach = -(velocity + omega.cross(&contact.centroid)).z;
        if approach <= 0.0 {
            return 0.0;
        }
        let arrest = self.arrest.effective_mass(&contact.centroid) * approach / self.arrest.time;
        (self.crush_load * contact.fraction).min(arrest)
    }
}

/// Nozzle clearance ZNOZ, m: height of the (crushed) exit-plane centroid `exit` (R_T, body
/// axes, m) above the surface plane Z = `surface_z` (m, inertial), for the CM at `position`
/// (inertial, m), body → inertial rotation `t_bi` (eq. 3) and stored crush `crush` (m). Review
/// row 71: `ZNOZ = Z_cm + (T_BI·(R_T + c·ẑ_B))_z − z_s`.
#[inline]
pub fn nozzle_clearance(
    exit: &Vector3<f64>,
    crush: f64,
    position: &Vector3<f64>,
    t_bi: &Matrix3<f64>,
    surface_z: f64,
) -> f64 {
    let r = exit + Vector3::new(0.0, 0.0, crush);
    position.z + (t_bi * r).z - surface_z
}

/// Engine force and moment on the vehicle, body axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EngineLoads {
    /// F_TF = TAF + FFL, N (eq. 72), body axes (along +Z_B).
    pub force: Vector3<f64>,
    /// MTF = R_T×TAF + R_F×FFL, N·m (eq. 73), body axes, about the CM.
    pub torque: Vector3<f64>,
    /// The thrust's part of `force` and `torque` (TAF and R_T×TAF), N and N·m, body axes: the
    /// part that drives the vehicle (the nozzle's crushing load only absorbs).
    pub thrust: (Vector3<f64>, Vector3<f64>),
}

/// Engine loads, eqs. (72)-(73), from the amplified thrust `taf` (TAF = AMP·F_THRUST, N, eq. 71)
/// acting at the exit-plane centroid `r_t` (R_T, body, m) and the nozzle crushing load `ffl`
/// (FFL, N) acting at the contact centroid `r_f` (R_F, body, m); both along +Z_B. The inertial
/// force FTFI = T_BI·F_TF (eq. 74) is the caller's.
#[inline]
pub fn engine_loads(taf: f64, r_t: &Vector3<f64>, ffl: f64, r_f: &Vector3<f64>) -> EngineLoads {
    let taf_v = Vector3::new(0.0, 0.0, taf);
    let ffl_v = Vector3::new(0.0, 0.0, ffl);
    let thrust_torque = r_t.cross(&taf_v);
    EngineLoads {
        force: taf_v + ffl_v,                      // eq. (72)
        torque: thrust_torque + r_f.cross(&ffl_v), // eq. (73)
        thrust: (taf_v, thrust_torque),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use touchdown_frames::{rot_x, t_bi};

    const F1: f64 = 1.0e4;

    #[test]
    fn hover_thrust_before_tailoff_on_the_curve_clock() {
        // t2 = 2 s on the curve clock, tp = 1.5 s: tailoff starts at t_sim = 0.5 s.
        let k = std::f64::consts::LN_2 / 0.5;
        let t = Tailoff::new(F1, 2.0, 1.5, Some(k), &[]).unwrap();
        assert_eq!(t.thrust(0.0), F1, "eq. (69)");
        assert_eq!(t.thrust(0.5), F1, "eq. (69) up to and including t2");
        assert!(t.thrust(0.6) < F1, "tailing off after t2");
        let constant = Tailoff::new(F1, f64::INFINITY, 0.0, None, &[]).unwrap();
        assert_eq!(constant.thrust(1e6), F1, "no tailoff: constant thrust");
    }

    #[test]
    fn continuous_at_t2() {
        let k = std::f64::consts::LN_2 / 0.5;
        let exp = Tailoff::new(F1, 2.0, 0.0, Some(k), &[0.0, -10.0]).unwrap();
        let poly = Tailoff::new(F1, 2.0, 0.0, None, &[F1, -3000.0]).unwrap();
        for t in [exp, poly] {
            assert!((t.thrust(2.0 + 1e-12) - F1).abs() < 1e-6, "F(t2+) = F1");
        }
        // The printed form with M0 ≠ 0 beside the exponential jumps by M0 (docs/errata.md, "Eq. (70): tailoff continuity at t2 and clamp — corrected").
        assert!(matches!(
            Tailoff::new(F1, 2.0, 0.0, Some(k), &[500.0]),
            Err(LawError::Tailoff(_))
        ));
        // A polynomial without the exponential must start at M0 = F1.
        assert!(Tailoff::new(F1, 2.0, 0.0, None, &[0.0, -1.0]).is_err());
        assert!(Tailoff::new(F1, 2.0, 0.0, None, &[]).is_err(), "drop to 0");
        assert!(Tailoff::new(F1, 2.0, 0.0, None, &[F1; MAX_TERMS + 1]).is_err());
        assert!(Tailoff::new(-1.0, 2.0, 0.0, None, &[]).is_err());
    }

    #[test]
    fn exponential_half_life() {
        // K = ln 2 / 0.5 s: the thrust halves every 0.5 s after t2 (F1·e^(−K·τ), eq. 70).
        let k = std::f64::consts::LN_2 / 0.5;
        let t = Tailoff::new(F1, 2.0, 0.0, Some(k), &[]).unwrap();
        assert!((t.thrust(2.5) - F1 / 2.0).abs() < 1e-9);
        assert!((t.thrust(3.0) - F1 / 4.0).abs() < 1e-9);
    }

    #[test]
    fn polynomial_value_and_clamping() {
        // M0 = F1, M1 = −2000 N/s, M2 = −500 N/s²: at τ = 1 s, 1e4 − 2000 − 500 = 7500 N.
        let t = Tailoff::new(F1, 2.0, 0.0, None, &[F1, -2000.0, -500.0]).unwrap();
        assert!((t.thrust(3.0) - 7500.0).abs() < 1e-9);
        // At τ = 10 s the raw value is 1e4 − 2e4 − 5e4 < 0: clamped to 0 (docs/errata.md, "Eq. (70): tailoff continuity at t2 and clamp — corrected").
        assert_eq!(t.thrust(12.0), 0.0);
        // Huge times stay finite and non-negative.
        assert_eq!(t.thrust(1e300), 0.0);
    }

    #[test]
    fn amplification_table_interpolates_and_holds_its_ends() {
        let a = Amplification::new(&[0.0, 1.0, 3.0], &[1.5, 1.2, 1.0]).unwrap();
        assert_eq!(a.factor(-0.2), 1.5, "constant below the first point");
        assert!((a.factor(0.5) - 1.35).abs() < 1e-12, "midway 1.5 → 1.2");
        assert!((a.factor(2.0) - 1.1).abs() < 1e-12, "midway 1.2 → 1.0");
        assert_eq!(a.factor(10.0), 1.0, "constant beyond the last point");
        assert_eq!(Amplification::unit().factor(-5.0), 1.0);
        assert_eq!(Amplification::unit().factor(5.0), 1.0);
        assert!(Amplification::new(&[0.0, 0.0], &[1.0, 1.0]).is_err());
        assert!(Amplification::new(&[0.0], &[0.0]).is_err());
        assert!(Amplification::new(&[], &[]).is_err());
    }

    // Exit plane 2 m below the CM, exit radius 0.5 m, crush load 2e4 N, on a 1,000 kg vehicle
    // of inertia diag(2000, 3000, 4000) kg·m², arrested within 1 ms.
    fn arrest() -> RimArrest {
        let inertia = Matrix3::from_diagonal(&Vector3::new(2000.0, 3000.0, 4000.0));
        RimArrest::new(1000.0, &inertia, 1e-3).unwrap()
    }

    fn nozzle() -> Nozzle {
        Nozzle::new(Vector3::new(0.0, 0.0, -2.0), 0.5, 2.0e4, arrest()).unwrap()
    }

    /// Falling at 10 m/s: the arrest bound (1000 kg·10 m/s / 1 ms = 1e7 N) is far above F_c.
    fn falling() -> Vector3<f64> {
        Vector3::new(0.0, 0.0, -10.0)
    }

    #[test]
    fn the_rim_pushes_only_while_it_moves_into_the_surface() {
        // Upright, the whole rim at the plane (centroid on the axis: m_eff = M).
        let n = nozzle();
        let pos = Vector3::new(0.0, 0.0, 1.95);
        let c = n.rim_contact(0.0, &pos, &Matrix3::identity(), 0.0);
        let still = Vector3::zeros();
        assert_eq!(n.force(&c, &falling(), &still), 2.0e4, "crushing: F_c");
        assert_eq!(n.force(&c, &still, &still), 0.0, "standing: no push");
        assert_eq!(n.force(&c, &-falling(), &still), 0.0, "leaving: no push");
        // Slower than F_c·τ/M = 2 cm/s the load is what stops the rim within τ: M·s/τ.
        let slow = Vector3::new(0.0, 0.0, -0.005);
        assert!((n.force(&c, &slow, &still) - 1000.0 * 0.005 / 1e-3).abs() < 1e-9);
        // Whatever the motion, the load never does positive work on the vehicle: FFL·s ≥ 0.
        for k in 0..200 {
            let a = k as f64;
            let v = Vector3::new((a * 0.7).sin(), (a * 1.3).cos(), 0.05 * (a * 0.37).sin());
            let w = Vector3::new(0.02 * (a * 0.9).cos(), 0.02 * (a * 1.1).sin(), 0.1);
            let f = n.force(&c, &v, &w);
            let s = -(v + w.cross(&c.centroid)).z;
            assert!(
                f >= 0.0 && f * s >= 0.0 && (s > 0.0 || f == 0.0),
                "{f} N at {s} m/s"
            );
            assert!(f <= 2.0e4);
        }
    }

    #[test]
    fn an_offset_rim_is_arrested_through_its_effective_mass() {
        // A force along ẑ at r = (x, y, z) turns the body about r×ẑ = (y, −x, 0):
        // 1/m_eff = 1/M + y²/Jxx + x²/Jyy, whatever z.
        let a = arrest();
        let r = Vector3::new(0.3, -0.4, -2.0);
        let expected = 1.0 / (1.0 / 1000.0 + 0.16 / 2000.0 + 0.09 / 3000.0);
        assert!((a.effective_mass(&r) - expected).abs() < 1e-9);
        assert!((a.effective_mass(&Vector3::new(0.0, 0.0, -5.0)) - 1000.0).abs() < 1e-12);
        // Rolling: the low side of a rolling vehicle descends at ω_x·|y| though its centre of
        // mass stands still, and the rim crushes there.
        let n = nozzle();
        let th = 0.2f64;
        let tbi = t_bi(&Vector3::new(th, 0.0, 0.0));
        let pos = Vector3::new(0.0, 0.0, 2.0 * th.cos() + 1e-9);
        let c = n.rim_contact(0.0, &pos, &tbi, 0.0);
        let rolling = Vector3::new(1.0, 0.0, 0.0); // low side (y < 0) moves along −Z_B
        assert!(n.force(&c, &Vector3::zeros(), &rolling) > 0.0);
        assert_eq!(n.force(&c, &Vector3::zeros(), &-rolling), 0.0);
        assert!(RimArrest::new(0.0, &Matrix3::identity(), 1e-3).is_err());
        assert!(RimArrest::new(1.0, &Matrix3::identity(), 0.0).is_err());
        assert!(RimArrest::new(1.0, &Matrix3::zeros(), 1e-3).is_err());
    }

    #[test]
    fn upright_clear_of_the_surface_has_no_contact() {
        let n = nozzle();
        let pos = Vector3::new(0.0, 0.0, 2.1); // exit plane 0.1 m above z = 0
        let c = n.rim_contact(0.0, &pos, &Matrix3::identity(), 0.0);
        assert_eq!(c.fraction, 0.0);
        assert_eq!(c.penetration, 0.0);
        assert_eq!(n.force(&c, &falling(), &Vector3::zeros()), 0.0);
        let clearance = nozzle_clearance(&n.exit_centroid, 0.0, &pos, &Matrix3::identity(), 0.0);
        assert!((clearance - 0.1).abs() < 1e-12);
    }

    #[test]
    fn upright_below_the_surface_touches_all_round() {
        // Exit plane 0.05 m below the plane, upright: the whole rim, 0.05 m deep.
        let n = nozzle();
        let pos = Vector3::new(0.0, 0.0, 1.95);
        let c = n.rim_contact(0.0, &pos, &Matrix3::identity(), 0.0);
        assert_eq!(c.fraction, 1.0);
        assert!((c.penetration - 0.05).abs() < 1e-12);
        assert!((c.centroid - Vector3::new(0.0, 0.0, -2.0)).norm() < 1e-12);
        assert_eq!(n.force(&c, &falling(), &Vector3::zeros()), 2.0e4);
        // Committing the crush brings the rim up to the plane along +Z_B.
        let c2 = n.rim_contact(c.penetration, &pos, &Matrix3::identity(), 0.0);
        assert!(c2.penetration < 1e-12);
    }

    #[test]
    fn tilted_half_rim_dips_on_the_low_side() {
        // Roll θx = 0.2 rad: a body point (x, y, z) has inertial z = y·sin θ + z·cos θ. Put the
        // exit centroid 1e-9 m above the plane so the rim points with y < 0 (φ in (π, 2π), 35 of
        // the 72 samples) dip: fraction 35/72 ≈ 0.5, and the centroid lies on the low side
        // (half-circle centroid y = −2·r_e/π ≈ −0.318 m).
        let n = nozzle();
        let th = 0.2f64;
        let tbi = t_bi(&Vector3::new(th, 0.0, 0.0));
        let pos = Vector3::new(0.0, 0.0, 2.0 * th.cos() + 1e-9);
        let c = n.rim_contact(0.0, &pos, &tbi, 0.0);
        assert!((c.fraction - 0.5).abs() <= 1.5 / RIM_SAMPLES as f64);
        assert!((c.fraction - 35.0 / 72.0).abs() < 1e-12);
        // Discrete centroid: y = −r_e·Σ_{k=1}^{35} sin(kπ/36)/35 = −r_e·cot(π/72)/35.
        let discrete = -0.5 / (std::f64::consts::PI / 72.0).tan() / 35.0;
        assert!((c.centroid.y - discrete).abs() < 1e-12);
        assert!((c.centroid.y + 2.0 * 0.5 / std::f64::consts::PI).abs() < 0.02);
        assert!(c.centroid.x.abs() < 1e-9, "symmetric about the roll axis");
        assert!((c.centroid.z + 2.0).abs() < 1e-12);
        assert!((n.force(&c, &falling(), &Vector3::zeros()) - 2.0e4 * 35.0 / 72.0).abs() < 1e-9);
    }

    #[test]
    fn penetration_against_hand_geometry() {
        // Roll θx = 0.1 rad, CM at z = 1.9 m. The lowest rim point is y = −0.5, z = −2 (φ = 270°,
        // a sample): inertial z = 1.9 − 0.5·sin 0.1 − 2·cos 0.1 = −0.09992 m; measured along Z_B
        // (T_BI·ẑ_B)_z = cos 0.1, so penetration = 0.09992/cos 0.1.
        let n = nozzle();
        let th = 0.1f64;
        let tbi = rot_x(th);
        let pos = Vector3::new(0.0, 0.0, 1.9);
        let depth = -(1.9 - 0.5 * th.sin() - 2.0 * th.cos());
        let c = n.rim_contact(0.0, &pos, &tbi, 0.0);
        assert!((c.penetration - depth / th.cos()).abs() < 1e-12);
        // After committing c ← c + penetration the lowest point is back on the plane.
        let c2 = n.rim_contact(c.penetration, &pos, &tbi, 0.0);
        assert!(c2.penetration < 1e-12);
        assert!(
            c2.fraction <= 1.0 / RIM_SAMPLES as f64,
            "at most the lowest sample"
        );
    }

    #[test]
    fn centre_line_engine_has_no_thrust_moment() {
        let l = engine_loads(
            1.2e4,
            &Vector3::new(0.0, 0.0, -2.0),
            0.0,
            &Vector3::new(0.0, 0.0, -2.0),
        );
        assert_eq!(l.force, Vector3::new(0.0, 0.0, 1.2e4));
        assert_eq!(l.torque, Vector3::zeros());
    }

    #[test]
    fn offset_engine_and_crush_give_r_cross_f() {
        // R × (0, 0, F) = (R_y·F, −R_x·F, 0), eq. (73), checked against nalgebra's cross.
        let (r_t, r_f) = (Vector3::new(0.3, -0.2, -2.0), Vector3::new(0.0, -0.4, -2.0));
        let (taf, ffl) = (1.0e4, 5.0e3);
        let l = engine_loads(taf, &r_t, ffl, &r_f);
        assert_eq!(l.force, Vector3::new(0.0, 0.0, taf + ffl), "eq. (72)");
        let expect =
            r_t.cross(&Vector3::new(0.0, 0.0, taf)) + r_f.cross(&Vector3::new(0.0, 0.0, ffl));
        assert!((l.torque - expect).norm() < 1e-9);
        let hand = Vector3::new(-0.2 * taf - 0.4 * ffl, -0.3 * taf, 0.0);
        assert!((l.torque - hand).norm() < 1e-9);
    }
}
