//! The universal joint at a primary trunnion B2 (two hinges normal to the strut axis, so that
//! the strut cannot spin about itself, as the report's massless gear cannot): the hinges both
//! multibody engines build it from.

use nalgebra::Vector3;

/// The universal joint's hinge axes at a primary trunnion `b2` (body axes, m) for a strut
/// along the unit vector `axis`: the first, fixed in the vehicle, along the leg's tangential
/// direction ẑ × r̂ (r̂ the horizontal direction of B2 from the centre line; of the strut where
/// B2 is on it) made normal to the strut, the second normal to both. A universal joint's two
/// hinges do not commute (the orientations (a, b) reaches differ from those of (b, a) at second
/// order in its angles), so the axes come from the leg's own geometry: a leg and its mirror
/// image get mirror-image joints in the same order, and a symmetric landing stays symmetric
/// (test `a_leg_and_its_mirror_image_get_mirror_image_trunnions`). Where the tangential
/// direction runs along the strut, the radial one.
pub fn hinge_axes(axis: &Vector3<f64>, b2: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let horizontal = |v: &Vector3<f64>| Vector3::new(v.x, v.y, 0.0);
    let radial = [horizontal(b2), horizontal(axis)]
        .into_iter()
        .find(|r| r.norm() > 0.0)
        .map_or_else(Vector3::x, |r| r.normalize());
    // The tangential and radial directions are normal to each other: a strut within 6° of
    // the one is at least 84° from the other.
    let normal_to_strut = |v: Vector3<f64>| v - axis * axis.dot(&v);
    let tangential = normal_to_strut(Vector3::z().cross(&radial));
    let e1 = if tangential.norm() > 0.1 {
        tangential
    } else {
        normal_to_strut(radial)
    }
    .normalize();
    (e1, axis.cross(&e1))
}

#[cfg(test)]
mod tests {
    use super::hinge_axes;
    use nalgebra::{Matrix3, Vector3};

    /// The report's gear: a leg at azimuth `deg` (degrees, from +X_B) with its trunnion at
    /// radius 0.5 m, 0.12 m up, and its footpad at radius 0.68 m, 0.29 m below it: a strut
    /// 23° off the vertical, as the 1/6-scale model's (|V̂2P·ẑ| = 0.92).
    fn leg(deg: f64) -> (Vector3<f64>, Vector3<f64>) {
        let (s, c) = deg.to_radians().sin_cos();
        let b2 = Vector3::new(0.5 * c, 0.5 * s, 0.12);
        let bp = Vector3::new(0.68 * c, 0.68 * s, -0.29);
        ((bp - b2).normalize(), b2)
    }

    /// A leg and its mirror image get mirror-image universal joints with their hinges in the
    /// same order, under the mirrors that map the report's four legs onto each other: x → −x
    /// (the 1-2-1 landing's), y → −y, and x ↔ y (the 2-2 landing's, which maps leg 1 onto
    /// leg 2). Hinges are axes: parallel either way. With the hinges picked against the body
    /// axes (the first along V̂2P × x̂ wherever the strut is within 26° of the vertical) legs
    /// along X_B took the tangential hinge first and legs along Y_B last, and a symmetric 2-2
    /// landing on MuJoCo came out asymmetric: the uphill primaries of `fig-25-26` 10.0 and
    /// 16.3 mm on mirror legs 3 and 4.
    #[test]
    fn a_leg_and_its_mirror_image_get_mirror_image_trunnions() {
        let mirrors = [
            Matrix3::from_diagonal(&Vector3::new(-1.0, 1.0, 1.0)),
            Matrix3::from_diagonal(&Vector3::new(1.0, -1.0, 1.0)),
            Matrix3::new(0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0),
        ];
        for deg in [0.0, 30.0, 45.0, 90.0, 135.0, 180.0, 270.0, 300.0] {
            let (axis, b2) = leg(deg);
            let (e1, e2) = hinge_axes(&axis, &b2);
            // unit, normal to the strut and to each other
            for (u, v) in [(e1, axis), (e2, axis), (e1, e2)] {
                assert!(u.dot(&v).abs() < 1e-15, "{deg}°: {u} against {v}");
            }
            assert!((e1.norm() - 1.0).abs() < 1e-15 && (e2.norm() - 1.0).abs() < 1e-15);
            // the first hinge is the leg's tangential direction, fixed in the vehicle
            let tangential = Vector3::z().cross(&Vector3::new(b2.x, b2.y, 0.0).normalize());
            assert!(
                (e1.dot(&tangential).abs() - 1.0).abs() < 1e-15,
                "{deg}°: {e1}"
            );
            for m in mirrors {
                let (f1, f2) = hinge_axes(&(m * axis), &(m * b2));
                for (image, hinge) in [(f1, m * e1), (f2, m * e2)] {
                    assert!(
                        (image.dot(&hinge).abs() - 1.0).abs() < 1e-15,
                        "{deg}°: the image's hinge {image} is not the hinge's image {hinge}"
                    );
                }
            }
        }
        // A vertical strut (the primaries of a lander whose footpads hang below their
        // trunnions) still has the tangential hinge first.
        let b2 = Vector3::new(0.0, 0.5, 0.1);
        let (e1, _) = hinge_axes(&-Vector3::z(), &b2);
        assert!((e1.x.abs() - 1.0).abs() < 1e-15, "{e1}");
        // A strut along its leg's tangential direction takes the radial one first.
        let (e1, e2) = hinge_axes(&Vector3::x(), &b2);
        assert!((e1.y.abs() - 1.0).abs() < 1e-15 && e2.dot(&Vector3::x()).abs() < 1e-15);
    }
}
