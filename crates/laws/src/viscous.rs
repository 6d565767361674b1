//! Stroking-velocity-dependent strut force, eq. (49).

/// Viscous strut force `F = C·sgn(v)·|v|^γ` (eq. (49), sign-preserving power: the printed
/// `C·v^γ` is undefined for v < 0 and non-integer γ, and loses the sign; see docs/errata.md).
///
/// The force is returned in the strut's own positive sense: for the primary strut pass the
/// compression rate (compression positive), for a secondary the extension rate (tension
/// positive). It then opposes the stroking velocity, as the report's text requires.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Viscous {
    /// Coefficient C (report CP, CS), N/(m/s)^γ.
    pub coefficient: f64,
    /// Exponent γ (report γp, γs), dimensionless, > 0.
    pub exponent: f64,
}

impl Viscous {
    /// No viscous force.
    pub const NONE: Viscous = Viscous {
        coefficient: 0.0,
        exponent: 1.0,
    };

    /// Force, N, for a stroking rate `rate`, m/s (positive in the strut's positive sense).
    #[inline]
    pub fn force(&self, rate: f64) -> f64 {
        if self.coefficient == 0.0 || rate == 0.0 {
            return 0.0;
        }
        self.coefficient * rate.signum() * rate.abs().powf(self.exponent)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn opposes_motion_with_the_sign_of_the_rate() {
        let v = Viscous {
            coefficient: 2.0,
            exponent: 1.5,
        };
        assert_eq!(v.force(4.0), 16.0);
        assert_eq!(v.force(-4.0), -16.0);
        assert_eq!(v.force(0.0), 0.0);
        assert_eq!(Viscous::NONE.force(3.0), 0.0);
    }
}
