//! The vehicle's own scales: a length, its footprint radius, and from it and gravity the Froude
//! velocity, time and acceleration. A judgement that must not depend on the vehicle's size or
//! the file's units (a comparison's tolerances, a stability boundary's search grid) is a ratio of
//! these: a dynamically similar vehicle (`[similarity]`) has its scales in the similarity's
//! ratios, so the same ratios judge it alike (docs/engines.md, "Tolerances from the vehicle's
//! scales").

use crate::check::owner_of;
use crate::model::Scenario;
use crate::ScenarioError;

/// Where a vehicle's velocity scale comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum VelocityScale {
    /// The Froude velocity √(g·ℓ): the speed of a fall through the footprint radius, the
    /// velocity that tipping over the footprint's edge is measured in.
    Froude,
    /// Without gravity, the touchdown speed: the only velocity such a landing has.
    TouchdownSpeed,
}

/// A vehicle's length, velocity, time and acceleration scales, SI.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Scales {
    /// The footprint radius ℓ: the mean distance of the undeformed footpads from the body's
    /// centre line (its Z axis), m.
    pub length_m: f64,
    /// The velocity scale v: √(g·ℓ), or the touchdown speed without gravity, m/s.
    pub velocity_m_s: f64,
    /// The time scale ℓ/v, s.
    pub time_s: f64,
    /// The acceleration scale v²/ℓ (g with gravity), m/s².
    pub acceleration_m_s2: f64,
    /// Where the velocity scale comes from.
    pub velocity_from: VelocityScale,
}

impl Scales {
    /// The scales of `sc`; an error naming `vehicle.gravity` for a landing with neither gravity
    /// nor a touchdown speed, which has no velocity to judge a motion by.
    pub fn of(sc: &Scenario) -> Result<Scales, ScenarioError> {
        let legs = sc.legs.len().max(1) as f64;
        let length_m = sc.legs.iter().map(|l| l.bp.xy().norm()).sum::<f64>() / legs;
        let g = sc.vehicle.gravity;
        let speed = sc.touchdown.velocity_g.norm();
        let (velocity_m_s, velocity_from) = if g > 0.0 {
            ((g * length_m).sqrt(), VelocityScale::Froude)
        } else {
            (speed, VelocityScale::TouchdownSpeed)
        };
        if !(velocity_m_s > 0.0 && length_m > 0.0) {
            // Named in the file (or the overrides) that set the gravity.
            return Err(ScenarioError::field(
                owner_of(&sc.layers, "vehicle.gravity"),
                "vehicle.gravity",
                "a landing with neither gravity nor a touchdown speed has no velocity scale to judge its motion by; expected gravity > 0 or a touchdown velocity",
            ));
        }
        Ok(Scales {
            length_m,
            velocity_m_s,
            time_s: length_m / velocity_m_s,
            acceleration_m_s2: velocity_m_s * velocity_m_s / length_m,
            velocity_from,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    fn path(name: &str) -> PathBuf {
        PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("../../scenarios")
            .join(name)
    }

    #[test]
    fn a_similar_vehicle_has_its_scales_in_the_similarity_s_ratios() {
        let file = path("fig-25-26.toml");
        let sc = Scenario::load(&file).unwrap();
        let twin = Scenario::load_with(
            &file,
            &[
                ("similarity.length", 6.0),
                ("similarity.mass", 216.0),
                ("similarity.time", 6.0),
            ],
        )
        .unwrap();
        let (a, b) = (Scales::of(&sc).unwrap(), Scales::of(&twin).unwrap());
        let close = |x: f64, y: f64| (x - y).abs() <= 1e-12 * y.abs();
        assert!(close(b.length_m, 6.0 * a.length_m), "{a:?} {b:?}");
        assert!(close(b.velocity_m_s, a.velocity_m_s), "{a:?} {b:?}");
        assert!(close(b.time_s, 6.0 * a.time_s), "{a:?} {b:?}");
        assert!(close(b.acceleration_m_s2, a.acceleration_m_s2 / 6.0));
        // the 1/6-scale model: the footprint radius is its file's r3 = 2.221 ft
        assert!(close(a.length_m, 2.221 * 0.3048), "{a:?}");
        assert_eq!(a.velocity_from, VelocityScale::Froude);
    }

    #[test]
    fn without_gravity_the_touchdown_speed_is_the_velocity_scale_and_without_either_none() {
        let file = path("flat-drop.toml");
        let free = Scenario::load_with(&file, &[("vehicle.gravity", 0.0)]).unwrap();
        let s = Scales::of(&free).unwrap();
        assert_eq!(s.velocity_from, VelocityScale::TouchdownSpeed);
        assert_eq!(s.velocity_m_s, free.touchdown.velocity_g.norm());
        assert!(s.velocity_m_s > 0.0);
        let still = Scenario::load_with(
            &file,
            &[
                ("vehicle.gravity", 0.0),
                ("touchdown.vertical_velocity", 0.0),
                ("touchdown.horizontal_velocity[0]", 0.0),
                ("touchdown.horizontal_velocity[1]", 0.0),
            ],
        )
        .unwrap();
        let e = Scales::of(&still).unwrap_err().to_string();
        assert!(
            e.contains("vehicle.gravity") && e.contains("velocity scale"),
            "{e}"
        );
        // named where the zero gravity was set: here the overrides, not the file
        assert!(e.starts_with("overrides"), "{e}");
    }
}
