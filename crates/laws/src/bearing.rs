//! Primary-strut bearing loads and Coulomb bearing friction, eqs. (59)-(63).
//!
//! Geometry (fig. 14, as the statics of eqs. 59-62 imply): bearing 1 is at the top of the inner
//! cylinder, a distance D1 from the footpad; bearing 2 is the gland at the lower end of the outer
//! cylinder, and D2 (the bearing separation) is the distance between the two bearings, so that
//! F2 − F1 = FM and the moments about the pad balance. D2 grows with compression stroke:
//! `D2 = D2_0 + c` (docs/errata.md, "Eqs. (59)-(63): bearing geometry — interpreted").

use crate::LawError;
use nalgebra::Vector3;

/// Side load FM at the footpad, N, eqs. (53)-(58) with eq. (54) corrected (MS = V21 × FS), in
/// closed form: `FM = −(L21/V2P)·(FS − (FS·V̂2P)·V̂2P)`. `fs` is the force of the primary on the
/// secondaries at point 1 (eq. 52), `axis` the unit primary direction V̂2P (trunnion to pad),
/// `l21` the trunnion-to-point-1 distance and `length` the current primary length V2P, m.
#[inline]
pub fn side_load(fs: &Vector3<f64>, axis: &Vector3<f64>, l21: f64, length: f64) -> Vector3<f64> {
    -(fs - axis * fs.dot(axis)) * (l21 / length) // eq. (54) corrected, (55)-(58)
}

/// Primary-strut bearing: geometry and friction coefficient.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bearing {
    /// Bearing friction coefficient μB, dimensionless.
    pub friction_coefficient: f64,
    /// Inner-cylinder length D1 (footpad to bearing 1), m.
    pub inner_cylinder_length: f64,
    /// Initial bearing separation (overlap) D2 at zero stroke, m.
    pub initial_overlap: f64,
}

/// Normal loads at the two bearings, N (magnitudes).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BearingLoads {
    /// F1, at bearing 1 (top of the inner cylinder), N.
    pub f1: f64,
    /// F2, at bearing 2 (outer-cylinder gland), N.
    pub f2: f64,
}

impl Bearing {
    /// Bearing separation D2 at compression stroke `c` (m, compression positive), m.
    #[inline]
    pub fn separation(&self, compression_stroke: f64) -> f64 {
        self.initial_overlap + compression_stroke
    }

    /// Bearing normal loads for a side load `fm` (N, magnitude of FM at the pad), eqs. (59)-(62):
    /// `F2 = FM·D1/D2`, `F1 = FM·(D1 − D2)/D2`.
    pub fn loads(&self, fm: f64, compression_stroke: f64) -> Result<BearingLoads, LawError> {
        let d1 = self.inner_cylinder_length;
        let d2 = self.separation(compression_stroke);
        if !(d2 > 0.0 && d2 < d1) {
            return Err(LawError::BearingGeometry {
                d2,
                d1,
                stroke: compression_stroke,
            });
        }
        Ok(BearingLoads {
            f2: fm * d1 / d2,        // eq. (60)
            f1: fm * (d1 - d2) / d2, // eq. (62)
        })
    }

    /// Bearing friction FBR, N, in the primary strut's compression-positive sense, eq. (63):
    /// magnitude `μB·(F1 + F2)`, opposing the stroking direction: positive while compressing
    /// (`compression_rate` > 0), negative while extending, zero at exactly zero rate (the report
    /// gives no rule at rest; docs/errata.md, "Eqs. (59)-(63): bearing geometry — interpreted").
    pub fn friction(
        &self,
        fm: f64,
        compression_stroke: f64,
        compression_rate: f64,
    ) -> Result<f64, LawError> {
        if compression_rate == 0.0 {
            return Ok(0.0);
        }
        Ok(self.friction_bound(fm, compression_stroke)? * compression_rate.signum())
    }

    /// Magnitude of the bearing friction, N, eq. (63): `μB·(F1 + F2)` for a side load `fm` (N)
    /// at compression stroke `compression_stroke` (m). A multibody engine uses it as the bound
    /// of a dry-friction constraint on the stroke joint.
    pub fn friction_bound(&self, fm: f64, compression_stroke: f64) -> Result<f64, LawError> {
        if self.friction_coefficient == 0.0 || fm == 0.0 {
            return Ok(0.0);
        }
        let l = self.loads(fm, compression_stroke)?;
        Ok(self.friction_coefficient * (l.f1 + l.f2)) // eq. (63)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const B: Bearing = Bearing {
        friction_coefficient: 0.1,
        inner_cylinder_length: 0.3,
        initial_overlap: 0.1,
    };

    #[test]
    fn inner_cylinder_statics_balance() {
        // Pad load FM at s = 0, bearing 2 at D1 − D2 from the pad, bearing 1 at D1.
        let fm = 250.0;
        let c = 0.05;
        let l = B.loads(fm, c).unwrap();
        let (d1, d2) = (B.inner_cylinder_length, B.separation(c));
        assert!((l.f2 - l.f1 - fm).abs() < 1e-9, "force balance");
        assert!(
            (l.f2 * (d1 - d2) - l.f1 * d1).abs() < 1e-9,
            "moment about the pad"
        );
    }

    /// Eqs. (53)-(58): the primary, pinned at its trunnion B2, takes −FS from the secondaries at
    /// point 1 (L21 along its axis) and −FM from the footpad at its length; its moments about
    /// B2 balance, and FM is normal to it (an axial FS leaves none). The printed eq. (54),
    /// MS = FS × V21, turns FM the other way and fails the balance.
    #[test]
    fn the_side_load_balances_the_primary_about_its_trunnion() {
        let cases = [
            (
                Vector3::new(120.0, -40.0, 35.0),
                Vector3::new(0.6, 0.0, -0.8),
                0.35,
                1.1,
            ),
            (
                Vector3::new(-5.0, 300.0, 0.0),
                Vector3::new(-0.36, 0.48, -0.8),
                0.2,
                0.9,
            ),
            (
                Vector3::new(0.0, 0.0, -80.0),
                Vector3::new(0.0, 0.0, -1.0),
                0.5,
                0.8,
            ),
        ];
        for (fs, axis, l21, length) in cases {
            let axis: Vector3<f64> = axis.normalize();
            let fm = side_load(&fs, &axis, l21, length);
            let moment = (axis * l21).cross(&-fs) + (axis * length).cross(&-fm);
            assert!(moment.norm() < 1e-12 * fs.norm(), "moment {moment}");
            assert!(fm.dot(&axis).abs() < 1e-12 * fs.norm(), "axial part");
            let normal = (fs - axis * fs.dot(&axis)).norm();
            assert!((fm.norm() - normal * l21 / length).abs() < 1e-12 * fs.norm());
        }
        let axial = side_load(&Vector3::new(0.0, 0.0, 50.0), &Vector3::z(), 0.3, 1.0);
        assert_eq!(axial.norm(), 0.0);
    }

    #[test]
    fn friction_opposes_stroking() {
        let l = B.loads(100.0, 0.0).unwrap();
        let mag = 0.1 * (l.f1 + l.f2);
        assert!((B.friction(100.0, 0.0, 2.0).unwrap() - mag).abs() < 1e-12);
        assert!((B.friction(100.0, 0.0, -2.0).unwrap() + mag).abs() < 1e-12);
        assert_eq!(B.friction(100.0, 0.0, 0.0).unwrap(), 0.0);
    }

    #[test]
    fn separation_beyond_inner_cylinder_is_an_error() {
        assert!(matches!(
            B.loads(1.0, 0.25),
            Err(LawError::BearingGeometry { .. })
        ));
    }
}
