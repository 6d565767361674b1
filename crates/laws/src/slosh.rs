//! First-mode propellant sloshing as a spring-mass analogy, appendix eqs. (108)-(117), with the
//! corrections in docs/errata.md (eqs. 108-117, and "The slosh mass's axial load — added").
//!
//! The residual propellant splits into a fixed part (rigid with the vehicle) and a slosh mass
//! M_s = F_s/ω² (eq. 112) that moves laterally (2-D amplitude q in the X_B–Y_B plane) on a
//! spring of stiffness k = M_s·ω_n², ω_n² = ω²·Z̈_B,eff (eqs. 110-111). Z̈_B,eff is the
//! *effective* axial acceleration, the specific force (A_tank − G)·Ẑ_B (docs/errata.md, "Eq. (108): effective axial acceleration, lagged one step — corrected"): at rest
//! on the surface it is +g, not the kinematic 0.
//!
//! Geometry (docs/errata.md, "Eqs. (113)-(114): geometry re-referenced to the rigid centre of mass", fig. 29 missing): the slosh mass lies ℓ1 + ℓ below the total
//! (rigid-propellant) centre of mass along −Z_B. Removing it moves the rigid vehicle's CM up by
//! ℓ2 (eq. 113) along +Z_B, and the slosh mass then lies at r_s = (0, 0, −d) from the rigid CM,
//! d = ℓ1 + ℓ2 + ℓ. Lengths are signed Z_B distances.
//!
//! What the caller does (not this module): re-reference all body-frame geometry (gear
//! attachment points, R_T, R_F, ...) by −ℓ2·ẑ_B to the rigid CM; use M − M_s and
//! [`Slosh::rigid_inertia`] in eqs. (10)-(15); apply the wall force (eq. 115) at the CM as
//! T_BI·(F_x, F_y, 0) (eq. 116) and the torque of [`Slosh::torque`] (eq. 117). The appendix
//! transmits only the lateral force, so the slosh mass's axial load (≈ M_s·Z̈_B,eff) is lost
//! with M − M_s in eqs. (10)-(12) (docs/errata.md, "The slosh mass's axial load — added"): the caller either applies it along −Z_B at r_s
//! or treats the slosh mass as axially rigid. There is no slosh damping (the report has none),
//! and the linear model holds only for small amplitudes.
//!
//! Units: kg, m, s, N.

use crate::{finite, positive};
use nalgebra::{Matrix3, Vector2, Vector3};

use crate::LawError;

/// The slosh model's constants.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Slosh {
    fs: f64,
    omega2: f64,
    l1: f64,
    l: f64,
    total_mass: f64,
    ms: f64,
    l2: f64,
}

impl Slosh {
    /// A slosh model from:
    /// - `fs`: F_s, the wall force per unit axial acceleration per unit amplitude,
    ///   N/(m·m/s²) = kg/m (> 0);
    /// - `omega2`: ω², the sloshing frequency squared per unit axial acceleration,
    ///   (rad/s)²/(m/s²) = 1/m (> 0);
    /// - `l1`, `l`: ℓ1 and ℓ, m (finite, signed): the slosh mass lies ℓ1 + ℓ below the total
    ///   centre of mass along −Z_B (ℓ: depth of the slosh-force centroid below the quiescent
    ///   free surface);
    /// - `total_mass`: M, kg (> 0), the whole vehicle with the propellant as rigid.
    ///
    /// Errors if an input is out of range or M_s = F_s/ω² (eq. 112) is not below M.
    pub fn new(fs: f64, omega2: f64, l1: f64, l: f64, total_mass: f64) -> Result<Self, LawError> {
        positive("slosh force coefficient F_s", fs)?;
        positive("slosh frequency coefficient ω²", omega2)?;
        finite("slosh length ℓ1", l1)?;
        finite("slosh length ℓ", l)?;
        positive("total mass M", total_mass)?;
        let ms = fs / omega2; // eq. (112)
        if ms >= total_mass {
            return Err(LawError::SloshMass {
                slosh_mass: ms,
                total_mass,
            });
        }
        let l2 = ms * (l1 + l) / (total_mass - ms); // eq. (113)
        Ok(Slosh {
            fs,
            omega2,
            l1,
            l,
            total_mass,
            ms,
            l2,
        })
    }

    /// Slosh mass M_s = F_s/ω², kg (eq. 112).
    pub fn slosh_mass(&self) -> f64 {
        self.ms
    }

    /// Rigid-vehicle mass M − M_s, kg.
    pub fn rigid_mass(&self) -> f64 {
        self.total_mass - self.ms
    }

    /// CM shift ℓ2 = M_s·(ℓ1 + ℓ)/(M − M_s), m (eq. 113): the rigid vehicle's CM lies ℓ2 above
    /// the total CM along +Z_B. Body-frame geometry given about the total CM must be
    /// re-referenced by −ℓ2·ẑ_B; the caller does it.
    pub fn cm_shift(&self) -> f64 {
        self.l2
    }

    /// Slosh arm d = ℓ1 + ℓ2 + ℓ, m: the slosh mass lies at r_s = (0, 0, −d) from the rigid CM.
    pub fn arm(&self) -> f64 {
        self.l1 + self.l2 + self.l
    }

    /// Inertia of the rigid vehicle about its own CM, body axes, kg·m² (eq. 114), from the
    /// inertia `total` of the whole vehicle about the total CM with the propellant rigid:
    /// Ixx and Iyy reduced by (M − M_s)·ℓ2² + M_s·(ℓ1 + ℓ)², everything else unchanged.
    ///
    /// This is exact for a point slosh mass on the Z_B axis: by the parallel-axis theorem
    /// I_total = I_rigid,own + (M − M_s)·ℓ2² + M_s·(ℓ1 + ℓ)² about X_B and Y_B (both masses lie
    /// on Z_B, at +ℓ2 and −(ℓ1 + ℓ)), while Izz and the products of inertia get no transfer
    /// terms because both offsets have zero X_B and Y_B components. (With eq. 113 the reduction
    /// equals M_s·(ℓ1 + ℓ)·d = μ·d², μ = M_s(M − M_s)/M.) The caller checks that the result is
    /// still a valid inertia.
    pub fn rigid_inertia(&self, total: &Matrix3<f64>) -> Matrix3<f64> {
        let h = self.l1 + self.l;
        let dec = self.rigid_mass() * self.l2 * self.l2 + self.ms * h * h; // eq. (114)
        let mut out = *total;
        out[(0, 0)] -= dec;
        out[(1, 1)] -= dec;
        out
    }

    /// Effective axial acceleration Z̈_B,eff, m/s² (≥ 0), from the specific force at the tank in
    /// body axes, (A_tank − G)_B (docs/errata.md, "Eq. (108): effective axial acceleration, lagged one step — corrected"): its Z_B component, positive when the liquid is
    /// pressed to the tank floor. A negative value (liquid thrown off the floor) breaks the
    /// linear model; it is clamped to 0 (no restoring spring) and the caller flags it.
    #[inline]
    pub fn axial(&self, specific_force_body: &Vector3<f64>) -> f64 {
        specific_force_body.z.max(0.0)
    }

    /// Natural slosh frequency squared ω_n² = ω²·Z̈_B,eff, (rad/s)², for `axial` = Z̈_B,eff (m/s²).
    #[inline]
    pub fn natural_frequency_squared(&self, axial: f64) -> f64 {
        self.omega2 * axial
    }

    /// Slosh acceleration q̈, m/s², eq. (109) corrected (docs/errata.md, "Eq. (109): 2-D amplitude, lateral specific force — corrected"): for the 2-D amplitude
    /// `q` (m, X_B–Y_B) and the lateral specific force at the slosh-mass location
    /// `lateral_specific_force` (m/s², body X_B–Y_B: the rigid vehicle's acceleration there,
    /// including the rotational terms, minus gravity), `q̈ = −f_lat − ω²·Z̈_B,eff·q`. No damping.
    #[inline]
    pub fn acceleration(
        &self,
        q: &Vector2<f64>,
        lateral_specific_force: &Vector2<f64>,
        axial: f64,
    ) -> Vector2<f64> {
        -lateral_specific_force - q * self.natural_frequency_squared(axial) // eq. (109)
    }

    /// Force of the sloshing propellant on the tank wall, i.e. on the rigid vehicle, N (body
    /// X_B–Y_B), eqs. (108)/(110): `F_w = F_s·Z̈_B,eff·q = M_s·ω_n²·q`.
    ///
    /// Sign: in the spring-mass analogy the spring joins the tank to the slosh mass, displaced
    /// by q from its rest point; the spring pulls the mass back with −k·q and pulls the tank
    /// toward the mass with +k·q, k = M_s·ω_n². So the force on the vehicle is along +q.
    #[inline]
    pub fn wall_force(&self, q: &Vector2<f64>, axial: f64) -> Vector2<f64> {
        q * (self.fs * axial) // eq. (108) ≡ eq. (110)
    }

    /// Torque of the wall force about the rigid CM, N·m, body axes, eq. (117) corrected
    /// (docs/errata.md, "Eq. (117): sign of T_y — corrected"): r_s × F with r_s = (0, 0, −d), F = (F_x, F_y, 0):
    /// T_x = +d·F_y, T_y = −d·F_x (the printed T_y has the wrong sign), T_z = 0.
    #[inline]
    pub fn torque(&self, force: &Vector2<f64>) -> Vector3<f64> {
        let d = self.arm();
        Vector3::new(d * force.y, -d * force.x, 0.0) // eq. (117), corrected
    }

    /// Slosh energy, J: kinetic ½·M_s·|q̇|² relative to the tank plus spring
    /// ½·M_s·ω²·Z̈_B,eff·|q|², for amplitude `q` (m), rate `q_dot` (m/s) and `axial` (m/s²).
    #[inline]
    pub fn energy(&self, q: &Vector2<f64>, q_dot: &Vector2<f64>, axial: f64) -> f64 {
        0.5 * self.ms
            * (q_dot.norm_squared() + self.natural_frequency_squared(axial) * q.norm_squared())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const G_MOON: f64 = 1.62;

    // F_s = 200 kg/m, ω² = 0.5 1/m → M_s = 400 kg; ℓ1 = 1.0 m, ℓ = 0.5 m; M = 10 000 kg.
    fn slosh() -> Slosh {
        Slosh::new(200.0, 0.5, 1.0, 0.5, 10_000.0).unwrap()
    }

    #[test]
    fn mass_shift_and_inertia_by_hand() {
        let s = slosh();
        assert_eq!(s.slosh_mass(), 400.0, "M_s = 200/0.5, eq. (112)");
        assert_eq!(s.rigid_mass(), 9600.0);
        // ℓ2 = 400·1.5/9600 = 0.0625 m (eq. 113); d = 1.0 + 0.0625 + 0.5 = 1.5625 m.
        assert!((s.cm_shift() - 0.0625).abs() < 1e-15);
        assert!((s.arm() - 1.5625).abs() < 1e-15);
        // Moment balance about the total CM: (M − M_s)·ℓ2 = M_s·(ℓ1 + ℓ).
        assert!((9600.0 * s.cm_shift() - 400.0 * 1.5).abs() < 1e-12);
        // eq. (114): reduction 9600·0.0625² + 400·1.5² = 37.5 + 900 = 937.5 kg·m².
        let i = Matrix3::new(2.0e4, -10.0, 30.0, -10.0, 2.5e4, 20.0, 30.0, 20.0, 1.5e4);
        let f = s.rigid_inertia(&i);
        assert!((f[(0, 0)] - (2.0e4 - 937.5)).abs() < 1e-9);
        assert!((f[(1, 1)] - (2.5e4 - 937.5)).abs() < 1e-9);
        assert_eq!(f[(2, 2)], 1.5e4, "Izz unchanged");
        assert_eq!(f[(0, 1)], -10.0, "products unchanged");
        assert_eq!(f[(0, 2)], 30.0);
        // The reduction is the two-mass reduced-mass form μ·d², μ = M_s(M − M_s)/M.
        let mu = 400.0 * 9600.0 / 10_000.0;
        assert!((mu * s.arm().powi(2) - 937.5).abs() < 1e-9);
    }

    #[test]
    fn rejects_a_slosh_mass_not_below_the_total() {
        assert!(matches!(
            Slosh::new(200.0, 0.5, 1.0, 0.5, 400.0),
            Err(LawError::SloshMass { .. })
        ));
        assert!(Slosh::new(0.0, 0.5, 1.0, 0.5, 1e4).is_err());
        assert!(Slosh::new(200.0, 0.0, 1.0, 0.5, 1e4).is_err());
        assert!(Slosh::new(200.0, 0.5, f64::NAN, 0.5, 1e4).is_err());
    }

    #[test]
    fn axial_specific_force_is_clamped() {
        let s = slosh();
        // At rest upright on the Moon: A = 0, G_B = (0, 0, −g) → (A − G)_z = +g.
        assert_eq!(s.axial(&Vector3::new(0.1, 0.2, G_MOON)), G_MOON);
        assert_eq!(s.axial(&Vector3::new(0.0, 0.0, -3.0)), 0.0);
    }

    fn rk4<const N: usize>(y: [f64; N], h: f64, f: impl Fn(&[f64; N]) -> [f64; N]) -> [f64; N] {
        let add = |a: &[f64; N], b: &[f64; N], c: f64| std::array::from_fn(|i| a[i] + c * b[i]);
        let k1 = f(&y);
        let k2 = f(&add(&y, &k1, h / 2.0));
        let k3 = f(&add(&y, &k2, h / 2.0));
        let k4 = f(&add(&y, &k3, h));
        std::array::from_fn(|i| y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
    }

    #[test]
    fn free_slosh_oscillates_at_the_natural_frequency_and_keeps_its_energy() {
        // Constant axial specific force g, no lateral forcing: q̈ = −ω²·g·q, so
        // ω_n = √(0.5·1.62) = 0.9 rad/s and T = 2π/0.9 s.
        let s = slosh();
        let a = G_MOON;
        let period = std::f64::consts::TAU / (s.natural_frequency_squared(a)).sqrt();
        assert!((period - std::f64::consts::TAU / 0.9).abs() < 1e-12);
        let h = period / 2000.0;
        let deriv = |y: &[f64; 4]| {
            let qdd = s.acceleration(&Vector2::new(y[0], y[1]), &Vector2::zeros(), a);
            [y[2], y[3], qdd.x, qdd.y]
        };
        let mut y = [0.1, -0.05, 0.0, 0.0];
        let e0 = s.energy(&Vector2::new(y[0], y[1]), &Vector2::new(y[2], y[3]), a);
        let mut crossings = [0.0f64; 4];
        let mut n = 0;
        let mut t = 0.0;
        while n < crossings.len() {
            let next = rk4(y, h, deriv);
            if y[0] > 0.0 && next[0] <= 0.0 {
                // downward zero crossing of q_x, linear interpolation within the step
                crossings[n] = t + h * y[0] / (y[0] - next[0]);
                n += 1;
            }
            y = next;
            t += h;
            let e = s.energy(&Vector2::new(y[0], y[1]), &Vector2::new(y[2], y[3]), a);
            assert!((e - e0).abs() < 1e-9 * e0, "energy drift at t = {t}");
        }
        for w in crossings.windows(2) {
            assert!(
                ((w[1] - w[0]) / period - 1.0).abs() < 1e-4,
                "{w:?} vs {period}"
            );
        }
        assert!(
            (crossings[0] / period - 0.25).abs() < 1e-4,
            "q0 released at rest"
        );
        // q_y stays in phase with q_x (same mode in both directions): q_y/q_x = −0.5.
        assert!((y[1] / y[0] + 0.5).abs() < 1e-9);
    }

    #[test]
    fn torque_is_r_cross_f() {
        let s = slosh();
        let f = Vector2::new(30.0, -70.0);
        let r = Vector3::new(0.0, 0.0, -s.arm());
        let expect = r.cross(&Vector3::new(f.x, f.y, 0.0));
        assert!((s.torque(&f) - expect).norm() < 1e-12);
        // T_y = −d·F_x: a wall force along +X_B acting below the CM turns the vehicle about
        // −Y_B (the printed +d·F_x has the wrong sign).
        assert!(s.torque(&Vector2::new(1.0, 0.0)).y < 0.0);
    }

    /// Rigid vehicle (M − M_s) on a frictionless lateral line, slosh mass on the spring; returns
    /// the largest relative change of total momentum and of total energy over 30 s. `sign`
    /// multiplies the wall force applied to the vehicle (+1: as implemented).
    fn two_mass(sign: f64) -> (f64, f64) {
        let s = slosh();
        let (mr, ms, a) = (s.rigid_mass(), s.slosh_mass(), G_MOON);
        let k = ms * s.natural_frequency_squared(a);
        // y = [v_t (2), q (2), q̇ (2)]: the vehicle's lateral velocity, slosh amplitude and rate.
        let deriv = |y: &[f64; 6]| {
            let q = Vector2::new(y[2], y[3]);
            let acc = sign * s.wall_force(&q, a) / mr; // rigid vehicle, no lateral gravity
            let qdd = s.acceleration(&q, &acc, a); // lateral specific force at the tank = acc
            [acc.x, acc.y, y[4], y[5], qdd.x, qdd.y]
        };
        let momentum = |y: &[f64; 6]| {
            // slosh-mass velocity = tank velocity + q̇
            Vector2::new(
                mr * y[0] + ms * (y[0] + y[4]),
                mr * y[1] + ms * (y[1] + y[5]),
            )
        };
        let energy = |y: &[f64; 6]| {
            let (v, q, qd) = (
                Vector2::new(y[0], y[1]),
                Vector2::new(y[2], y[3]),
                Vector2::new(y[4], y[5]),
            );
            0.5 * mr * v.norm_squared()
                + 0.5 * ms * (v + qd).norm_squared()
                + 0.5 * k * q.norm_squared()
        };
        let mut y = [0.5, 0.0, 0.2, 0.1, 0.0, 0.0];
        let (p0, e0) = (momentum(&y), energy(&y));
        let (mut dp, mut de) = (0.0f64, 0.0f64);
        for _ in 0..30_000 {
            y = rk4(y, 1e-3, deriv);
            dp = dp.max((momentum(&y) - p0).norm() / p0.norm());
            de = de.max((energy(&y) - e0).abs() / e0);
        }
        (dp, de)
    }

    #[test]
    fn two_mass_system_conserves_momentum_and_energy() {
        // With the wall force along +q on the vehicle, the pair is a closed system: momentum is
        // a linear invariant (exact under RK4 up to rounding) and energy is conserved.
        let (dp, de) = two_mass(1.0);
        assert!(dp < 1e-12, "momentum drift {dp}");
        assert!(de < 1e-9, "energy drift {de}");
        // The opposite sign breaks both: the check is sensitive to the sign.
        let (dp, de) = two_mass(-1.0);
        assert!(dp > 1e-3 && de > 1e-3, "{dp} {de}");
    }
}
