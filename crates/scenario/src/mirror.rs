//! Mirror images: the mirror x → −x in the gravity, surface and body frames, and the map of
//! legs under which a landing is its own mirror image (docs/errata.md, "Decisions at rounding
//! level"). A landing that is its own mirror image lands each leg's stroke twice, on the leg
//! and on its image; how far apart an engine lands the two is its own arithmetic's
//! (`touchdown_compare::rounding`).

use crate::model::Leg;
use crate::Scenario;
use nalgebra::{Matrix3, Vector3};

/// The mirror matrix M = diag(−1, 1, 1): x → −x in the gravity, surface and body frames.
pub fn matrix() -> Matrix3<f64> {
    Matrix3::from_diagonal(&Vector3::new(-1.0, 1.0, 1.0))
}

/// A pseudovector (body rates, rad/s) mirrored: det(M)·M·ω.
pub fn pseudovector(w: &Vector3<f64>) -> Vector3<f64> {
    Vector3::new(w.x, -w.y, -w.z)
}

/// The legs' images under which a scenario is its own mirror image in the vertical plane
/// X = x_cm of the gravity frame at touchdown (leg i's mirror image is leg `legs[i]`, its
/// secondaries 3-1 and 4-1 exchanged), or `None` if it is not mirror-symmetric: the touchdown
/// geometry, velocity, rates, inertia, per-footpad surface and mechanisms are compared in
/// inertial axes, to rounding (1e-12 of each quantity's own scale: the gear's largest extent,
/// the velocity's and the rates' magnitudes, so that the answer does not depend on the units
/// or the vehicle's size).
pub fn self_mirror(sc: &Scenario) -> Option<Vec<usize>> {
    let init = crate::initial::initial_state(sc);
    let t = init.t_bi;
    let m = matrix();
    let close_to =
        |scale: f64| move |a: &Vector3<f64>, b: &Vector3<f64>| (a - b).norm() <= 1e-12 * scale;
    let w = t * init.omega;
    if !close_to(init.velocity.norm())(&(m * init.velocity), &init.velocity)
        || !close_to(w.norm())(&pseudovector(&w), &w)
    {
        return None;
    }
    let extent = (sc.legs.iter())
        .flat_map(|l| [l.b2, l.b3, l.b4, l.bp])
        .map(|p| p.norm())
        .fold(0.0, f64::max);
    let close = close_to(extent);
    let inertia = t * sc.vehicle.inertia * t.transpose();
    if (m * inertia * m - inertia).norm() > 1e-12 * inertia.norm() {
        return None;
    }
    if let Some(thrust) = &sc.thrust {
        let r = t * thrust.nozzle_exit;
        if !close(&(m * r), &r) {
            return None;
        }
    }
    if sc.slosh.is_some_and(|s| s.initial_amplitude != [0.0, 0.0])
        || sc.rcs.is_some()
        || !sc.surface.curbs.is_empty()
    {
        return None;
    }
    // Each leg's trunnions B2, B3, B4 and footpad BP in inertial axes; its image is the mirror
    // of each, B3 and B4 exchanged (a mirror reverses the sense of rotation).
    let points: Vec<[Vector3<f64>; 4]> = (sc.legs.iter())
        .map(|l: &Leg| [l.b2, l.b3, l.b4, l.bp].map(|p| t * p))
        .collect();
    (points.iter().enumerate())
        .map(|(i, [b2, b3, b4, bp])| {
            let image = [b2, b4, b3, bp].map(|p| m * p);
            (points.iter().enumerate()).position(|(j, own)| {
                image.iter().zip(own).all(|(a, b)| close(a, b))
                    && sc.surface.pads[i] == sc.surface.pads[j]
            })
        })
        .collect()
}
