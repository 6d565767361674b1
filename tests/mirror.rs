//! Mirror images of scenarios: the mirror matrix, mirrored pseudovectors, leg maps and the
//! map under which a scenario is its own mirror image (docs/errata.md, "Decisions at rounding
//! level").

use nalgebra::{Matrix3, Vector3};
use touchdown_scenario::model::Leg;
use touchdown_scenario::Scenario;

/// The mirror matrix M = diag(−1, 1, 1): x → −x in the gravity, surface and body frames.
pub fn m() -> Matrix3<f64> {
    Matrix3::from_diagonal(&Vector3::new(-1.0, 1.0, 1.0))
}

/// A pseudovector (body rates) mirrored: det(M)·M·ω.
pub fn mirror_pseudo(w: &Vector3<f64>) -> Vector3<f64> {
    Vector3::new(w.x, -w.y, -w.z)
}

/// What a renumbering or mirroring does to the legs: new leg k is old leg `legs[k]`, with its
/// secondaries swapped (3-1 ↔ 4-1) when `swap`.
#[derive(Debug, Clone)]
pub struct Map {
    /// New leg k is old leg `legs[k]` (leg i's mirror image, for [`self_mirror`]).
    pub legs: Vec<usize>,
    /// Whether the secondaries are swapped.
    pub swap: bool,
}

/// The leg map under which a scenario is its own mirror image in the vertical plane X = x_cm of
/// the gravity frame at touchdown (leg i's mirror image is leg `legs[i]`, secondaries swapped),
/// or `None` if it is not mirror-symmetric: the touchdown geometry, velocity, rates, inertia,
/// per-footpad surface and mechanisms are compared in inertial axes, to rounding.
pub fn self_mirror(sc: &Scenario) -> Option<Map> {
    let init = touchdown_scenario::initial::initial_state(sc);
    let t = init.t_bi;
    let m = m();
    let close = |a: &Vector3<f64>, b: &Vector3<f64>| (a - b).norm() < 1e-12;
    let w = t * init.omega;
    if !close(&(m * init.velocity), &init.velocity) || !close(&mirror_pseudo(&w), &w) {
        return None;
    }
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
    let image = |l: &Leg| [m * t * l.b2, m * t * l.b4, m * t * l.b3, m * t * l.bp];
    let legs = sc
        .legs
        .iter()
        .enumerate()
        .map(|(i, l)| {
            let mirrored = image(l);
            sc.legs.iter().enumerate().position(|(j, k)| {
                let own = [t * k.b2, t * k.b3, t * k.b4, t * k.bp];
                mirrored.iter().zip(&own).all(|(a, b)| close(a, b))
                    && sc.surface.pads[i] == sc.surface.pads[j]
            })
        })
        .collect::<Option<Vec<usize>>>()?;
    Some(Map { legs, swap: true })
}
