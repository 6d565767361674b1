//! Primary-strut bending as a beam-column, eqs. (40)-(48), with the review's corrections.
//!
//! The primary strut is a pinned-pinned uniform beam of length L = V2P (m) between the trunnion
//! (point 2, s = 0) and the footpad (s = L), stiffness EI (N·m²), under a uniform axial load
//! P = F2P (N, compression positive) and a lateral point load FN (N) at s = a = L21 (point 1,
//! where the secondaries attach); b = L − a.
//!
//! - eqs. (41)-(42): `EI·η″ + P·η = M(s)`, `M = FN·b·s/L` (s < a), `FN·a·(1 − s/L)` (s > a).
//!   Their solution is negative under the load (eq. 40's implicit convention: η positive
//!   opposite to FN). This module returns the **magnitude along FN**, i.e. −η(a).
//! - eq. (43), corrected (garbled in print): with k = √(P/EI),
//!   `|η| = (FN/P)·[sin(ka)·sin(kb)/(k·sin(kL)) − a·b/L]`; in tension, κ = √(−P/EI),
//!   `|η| = (FN/|P|)·[a·b/L − sinh(κa)·sinh(κb)/(κ·sinh(κL))]`. Both are one analytic function
//!   of P; checked against the ODE symbolically (sympy) and, in the tests, by finite differences.
//! - eq. (46), corrected: P = 0 gives `|η| = FN·a²·b²/(3·EI·L)` (printed with 6).
//!   For |kL| < 0.5 a Taylor series in q = P·L²/EI is used instead of the closed form, so there
//!   is no cancellation near P = 0 (the series and the closed form agree to ~1e-12 at the switch).
//! - The closed form diverges at the Euler load P_E = π²·EI/L²; P is capped at
//!   [`EULER_CAP`]·P_E and the cap is reported (docs/errata.md, "Eqs. (47)-(48): bending coupling").
//! - eq. (47), with its sign worked out (docs/errata.md, "Eqs. (47)-(48): bending coupling"): see [`secondary_lengthening`].
//!   The singular series spring of eq. (48), KB = FC/δ, is not provided; the review's
//!   equivalent stroke correction `S_eff = S_i1 + λ_i = S_i1 − δ_i` (lagged η) is.

use crate::{finite, positive};
use std::f64::consts::PI;

use nalgebra::Vector3;

use crate::LawError;

/// Fraction of the Euler load at which the axial load of the deflection law is capped (docs/errata.md, "Eqs. (47)-(48): bending coupling").
pub const EULER_CAP: f64 = 0.9;

/// |kL| below which the Taylor series replaces the closed form, i.e. |q| = |P|·L²/EI < 0.25.
const SERIES_LIMIT: f64 = 0.25;

/// Euler buckling load of a pinned-pinned column, `P_E = π²·EI/L²`, N (EI in N·m², L in m).
#[inline]
pub fn euler_load(ei: f64, l: f64) -> f64 {
    PI * PI * ei / (l * l)
}

/// Lateral deflection of the primary strut under the point load.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Deflection {
    /// Deflection of point 1 along FN, m (−η of eqs. 43/46; ≥ 0 for FN ≥ 0).
    pub magnitude: f64,
    /// Axial load actually used, N (compression positive): F2P, or the cap.
    pub axial_load: f64,
    /// True when F2P exceeded [`EULER_CAP`]·P_E and was capped.
    pub capped: bool,
}

/// Primary-strut bending stiffness.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bending {
    /// Bending stiffness EI, N·m².
    pub stiffness: f64,
}

impl Bending {
    /// Bending law from EI (N·m², positive finite).
    pub fn new(ei: f64) -> Result<Self, LawError> {
        Ok(Bending {
            stiffness: positive("bending stiffness EI", ei)?,
        })
    }

    /// [`deflection`] with this stiffness.
    #[inline]
    pub fn deflection(&self, fn_load: f64, p: f64, a: f64, l: f64) -> Result<Deflection, LawError> {
        deflection(fn_load, p, a, l, self.stiffness)
    }
}

/// Deflection of the load point along FN, eqs. (43)/(46) corrected.
///
/// `fn_load` = FN (N, magnitude of the normal load), `p` = F2P (N, compression positive),
/// `a` = L21 (m, trunnion to point 1), `l` = V2P (m), `ei` = EI (N·m²). The result is linear in
/// FN. P above [`EULER_CAP`]·P_E is capped (`capped = true`); the result is always finite.
///
/// Errors on non-finite FN or P, L or EI not positive, or a outside [0, L].
#[inline]
pub fn deflection(fn_load: f64, p: f64, a: f64, l: f64, ei: f64) -> Result<Deflection, LawError> {
    finite("normal load FN", fn_load)?;
    finite("axial load F2P", p)?;
    positive("strut length V2P", l)?;
    positive("bending stiffness EI", ei)?;
    if !(0.0..=l).contains(&a) {
        return Err(LawError::BeamGeometry { a, l });
    }
    let cap = EULER_CAP * euler_load(ei, l);
    let capped = p > cap;
    let axial_load = if capped { cap } else { p };
    let x = a / l;
    let q = axial_load * l * l / ei;
    Ok(Deflection {
        magnitude: fn_load * l * l * l / ei * shape(q, x),
        axial_load,
        capped,
    })
}

/// Dimensionless deflection h(q, x) = |η|·EI/(FN·L³) at x = a/L, q = P·L²/EI = (kL)².
#[inline]
fn shape(q: f64, x: f64) -> f64 {
    let y = 1.0 - x;
    let xy = x * y;
    if q.abs() < SERIES_LIMIT {
        // Taylor series of eq. (43) in q (sympy), c_n a polynomial in p = x·y; c_0 = p²/3 is
        // eq. (46) corrected. Truncation error < 1e-11 relative for |q| < 0.25.
        let p = xy;
        let c = [
            p * p / 3.0,
            p * p * (1.0 + 2.0 * p) / 45.0,
            p * p * (2.0 / 945.0 + p * (4.0 / 945.0 + p / 315.0)),
            p * p * (1.0 / 4725.0 + p * (2.0 / 4725.0 + p * (1.0 / 2835.0 + p * 2.0 / 14175.0))),
            p * p
                * (2.0 / 93555.0
                    + p * (4.0 / 93555.0
                        + p * (17.0 / 467775.0 + p * (8.0 / 467775.0 + p * 2.0 / 467775.0)))),
            p * p
                * (1382.0 / 638512875.0
                    + p * (2764.0 / 638512875.0
                        + p * (472.0 / 127702575.0
                            + p * (164.0 / 91216125.0
                                + p * (2.0 / 3648645.0 + p * 4.0 / 42567525.0))))),
            p * p
                * (4.0 / 18243225.0
                    + p * (8.0 / 18243225.0
                        + p * (718.0 / 1915538625.0
                            + p * (32.0 / 174139875.0
                                + p * (16.0 / 273648375.0
                                    + p * (8.0 / 638512875.0 + p / 638512875.0)))))),
        ];
        c.iter().rev().fold(0.0, |acc, cn| acc * q + cn)
    } else if q > 0.0 {
        // eq. (43) corrected, compression: (1/q)·[sin(ux)·sin(uy)/(u·sin u) − x·y], u = kL.
        let u = q.sqrt();
        ((u * x).sin() * (u * y).sin() / (u * u.sin()) - xy) / q
    } else {
        // Tension: (1/|q|)·[x·y − sinh(ux)·sinh(uy)/(u·sinh u)], u = κL; with x + y = 1,
        // sinh(ux)·sinh(uy)/sinh(u) = (1 − e^{−2ux})(1 − e^{−2uy})/(2(1 − e^{−2u})): no overflow.
        let u = (-q).sqrt();
        let s = (-2.0 * u * x).exp_m1() * (-2.0 * u * y).exp_m1() / (-2.0 * (-2.0 * u).exp_m1());
        (xy - s / u) / (-q)
    }
}

/// Normal load on the primary strut at point 1 from the secondaries, N (eqs. 47-48 setup).
///
/// `FN = −(FS_c − (FS_c·V̂2P)·V̂2P)` with `FS_c = FC31·V̂31 + FC41·V̂41` the force of the primary
/// on the secondaries built from the honeycomb forces only (`fc` = [FC31, FC41], N, tension
/// positive), `u31`, `u41` = V̂31, V̂41 (unit, from trunnion i to point 1) and `axis` = V̂2P
/// (unit). FN is the component of the force on the primary perpendicular to its axis.
#[inline]
pub fn normal_load(
    fc: [f64; 2],
    u31: Vector3<f64>,
    u41: Vector3<f64>,
    axis: Vector3<f64>,
) -> Vector3<f64> {
    let fs = u31 * fc[0] + u41 * fc[1];
    -(fs - axis * fs.dot(&axis))
}

/// Apparent lengthening λ_i of secondaries 3 and 4 from the bending of the primary, m
/// (lengthening positive); eq. (47) with its sign worked out.
///
/// `displacement` is the displacement of point 1, `|η|·FN̂` (m): the primary deflects along the
/// normal load it receives ([`normal_load`], [`Deflection::magnitude`]). Secondary i runs from
/// its trunnion to point 1 along V̂i1 (`u31`, `u41`), so to first order its length grows by
/// `λ_i = (|η|·FN̂)·V̂i1`. The kinematic strut length ignores this, so the honeycomb stroke is
/// `S_eff = S_i1 + λ_i` (lagged η; docs/errata.md, "Eqs. (47)-(48): bending coupling"). Check: a lone strut in tension (FC > 0) pulls
/// point 1 toward its trunnion, so FN̂·V̂i1 < 0 and λ_i < 0: bending acts as a softer spring in
/// series, as eq. (48) intends. Eq. (47)'s δ_i = η·(FN̂·V̂i1) with the printed η ≤ 0 is −λ_i
/// (docs/errata.md).
#[inline]
pub fn secondary_lengthening(
    displacement: Vector3<f64>,
    u31: Vector3<f64>,
    u41: Vector3<f64>,
) -> [f64; 2] {
    [displacement.dot(&u31), displacement.dot(&u41)]
}

#[cfg(test)]
mod tests {
    use super::*;

    const EI: f64 = 2.0e5; // N·m²
    const L: f64 = 2.5; // m
    const A: f64 = 0.9; // m

    fn rel(x: f64, y: f64) -> f64 {
        (x - y).abs() / y.abs()
    }

    /// Finite-difference solution of eqs. (41)-(42), EI·η″ + P·η = M(s), η(0) = η(L) = 0,
    /// returning −η(a) (the magnitude along FN). Thomas algorithm on n intervals.
    fn finite_difference(fn_load: f64, p: f64, n: usize) -> f64 {
        let h = L / n as f64;
        let b = L - A;
        let m = |s: f64| {
            if s <= A {
                fn_load * b * s / L
            } else {
                fn_load * A * (1.0 - s / L)
            }
        };
        let k = n - 1; // interior unknowns
        let (off, diag) = (EI / (h * h), -2.0 * EI / (h * h) + p);
        let mut c = vec![0.0; k];
        let mut d = vec![0.0; k];
        for i in 0..k {
            let rhs = m((i + 1) as f64 * h);
            let den = diag - if i > 0 { off * c[i - 1] } else { 0.0 };
            c[i] = off / den;
            d[i] = (rhs - if i > 0 { off * d[i - 1] } else { 0.0 }) / den;
        }
        let mut eta = vec![0.0; k];
        eta[k - 1] = d[k - 1];
        for i in (0..k - 1).rev() {
            eta[i] = d[i] - c[i] * eta[i + 1];
        }
        let ia = (A / h).round() as usize; // A is on the grid
        assert!((ia as f64 * h - A).abs() < 1e-12);
        -eta[ia - 1]
    }

    #[test]
    fn zero_axial_load_is_the_textbook_deflection() {
        // Q·a²·b²/(3·EI·L) (eq. 46 corrected; e.g. Roark, simply supported beam, load at a).
        let q = 1500.0;
        let b = L - A;
        let want = q * A * A * b * b / (3.0 * EI * L);
        let d = deflection(q, 0.0, A, L, EI).unwrap();
        assert!(rel(d.magnitude, want) < 1e-14, "{} vs {want}", d.magnitude);
        assert!(!d.capped);
        assert_eq!(deflection(q, 0.0, 0.0, L, EI).unwrap().magnitude, 0.0);
    }

    #[test]
    fn series_and_closed_form_join_continuously() {
        let q = 1500.0;
        let p0 = deflection(q, 0.0, A, L, EI).unwrap().magnitude;
        // P → 0± tends to the P = 0 value.
        for p in [1e-6, -1e-6] {
            assert!(rel(deflection(q, p, A, L, EI).unwrap().magnitude, p0) < 1e-9);
        }
        // Across the series switch |q| = 0.25, from both sides, compression and tension.
        let p_switch = SERIES_LIMIT * EI / (L * L);
        for sign in [1.0, -1.0] {
            let below = deflection(q, sign * p_switch * (1.0 - 1e-12), A, L, EI).unwrap();
            let above = deflection(q, sign * p_switch * (1.0 + 1e-12), A, L, EI).unwrap();
            assert!(
                rel(below.magnitude, above.magnitude) < 1e-9,
                "{sign}: {} vs {}",
                below.magnitude,
                above.magnitude
            );
        }
        // And the series against the closed form a bit inside its range, both directions.
        for q in [0.2, -0.2, 0.05, -0.05] {
            for x in [0.1, 0.36, 0.5] {
                let y = 1.0 - x;
                let u = f64::abs(q).sqrt();
                let closed = if q > 0.0 {
                    ((u * x).sin() * (u * y).sin() / (u * u.sin()) - x * y) / q
                } else {
                    (x * y - (u * x).sinh() * (u * y).sinh() / (u * u.sinh())) / -q
                };
                assert!(rel(shape(q, x), closed) < 1e-10, "q {q} x {x}");
            }
        }
    }

    #[test]
    fn closed_form_matches_finite_differences() {
        // Independent check of eq. (43) corrected: FD on 2500 intervals (h² error ~ 1e-7).
        let pe = euler_load(EI, L);
        for p in [0.5 * pe, 0.05 * pe, -0.3 * pe, -3.0 * pe] {
            let fd = finite_difference(1000.0, p, 2500);
            let d = deflection(1000.0, p, A, L, EI).unwrap();
            assert!(!d.capped);
            assert!(
                rel(d.magnitude, fd) < 1e-4,
                "P {p}: {} vs {fd}",
                d.magnitude
            );
        }
        // Compression magnifies, tension stiffens.
        let d0 = deflection(1000.0, 0.0, A, L, EI).unwrap().magnitude;
        assert!(deflection(1000.0, 0.5 * pe, A, L, EI).unwrap().magnitude > d0);
        assert!(deflection(1000.0, -0.5 * pe, A, L, EI).unwrap().magnitude < d0);
        // Very large tension stays finite (no sinh overflow) and tends to zero.
        let t = deflection(1000.0, -1e15, A, L, EI).unwrap().magnitude;
        assert!(t.is_finite() && t > 0.0 && t < 1e-9);
    }

    #[test]
    fn euler_load_cap() {
        let pe = euler_load(EI, L);
        let x = A / L;
        // The uncapped law grows like 1/(1 − P/P_E): each decade closer multiplies it by ~10.
        let mut last = shape(PI * PI * (1.0 - 1e-2), x);
        for eps in [1e-3, 1e-4, 1e-5] {
            let h = shape(PI * PI * (1.0 - eps), x);
            assert!(h / last > 9.0, "eps {eps}");
            last = h;
        }
        // The public law caps at 0.9·P_E and says so; the result is finite and equals the cap's.
        let at_cap = deflection(1000.0, EULER_CAP * pe, A, L, EI).unwrap();
        assert!(!at_cap.capped);
        for p in [0.95 * pe, pe, 10.0 * pe, 1e300] {
            let d = deflection(1000.0, p, A, L, EI).unwrap();
            assert!(d.capped && d.magnitude.is_finite());
            assert_eq!(d.magnitude, at_cap.magnitude);
            assert_eq!(d.axial_load, EULER_CAP * pe);
        }
        assert!(matches!(
            deflection(1000.0, f64::NAN, A, L, EI),
            Err(LawError::NotFinite { .. })
        ));
        assert!(matches!(
            deflection(1000.0, 0.0, 3.0, L, EI),
            Err(LawError::BeamGeometry { .. })
        ));
        assert!(Bending::new(0.0).is_err());
    }

    #[test]
    fn normal_load_and_apparent_length_change() {
        let axis = Vector3::z();
        let u31 = Vector3::new(1.0, 0.0, 1.0).normalize();
        let u41 = Vector3::new(-1.0, 0.2, 1.0).normalize();
        // Only strut 3 loaded, 1000 N tension: it pulls point 1 toward trunnion 3.
        let fnv = normal_load([1000.0, 0.0], u31, u41, axis);
        assert!(fnv.dot(&axis).abs() < 1e-12, "FN is perpendicular to V̂2P");
        assert!((fnv - Vector3::new(-1000.0 / 2f64.sqrt(), 0.0, 0.0)).norm() < 1e-9);
        let bend = Bending::new(EI).unwrap();
        let eta = bend.deflection(fnv.norm(), 5000.0, A, L).unwrap().magnitude;
        let disp = fnv.normalize() * eta;
        let [l3, l4] = secondary_lengthening(disp, u31, u41);
        // Strut 4 has a positive component along FN̂: it is apparently lengthened, by |η|·FN̂·V̂41.
        assert!(u41.dot(&fnv) > 0.0 && l4 > 0.0);
        assert!((l4 - eta / 2.04f64.sqrt()).abs() < 1e-15);
        // The loaded tensile strut is apparently shortened: series softening.
        assert!(l3 < 0.0 && (l3 + eta / 2f64.sqrt()).abs() < 1e-15);
        // Eq. (47) as printed, δ_i = η·(FN̂·V̂i1) with η ≤ 0, is the apparent shortening −λ_i.
        let printed = [
            -eta * fnv.normalize().dot(&u31),
            -eta * fnv.normalize().dot(&u41),
        ];
        assert!((printed[0] + l3).abs() < 1e-15 && (printed[1] + l4).abs() < 1e-15);
    }
}
