//! Non-rigid surface (soil), eqs. (101)-(104), with the review's corrections.
//!
//! Depth ZPEN ≥ 0 (m) is the penetration below the surface, ZPEN = −HOLE − ZP; the penetration
//! rate ṗ = −ŻP (m/s) is positive going deeper. All constants are SI (the report's psi and psi/ft
//! become Pa and Pa/m; no factor 144 is needed).
//!
//! - eq. (101), corrected: while penetrating (ṗ > 0), `FZP = AP·[K1 + K2·ZPEN + K3·ṗ + K4·ṗ²]`.
//!   The printed form uses ŻP (negative while penetrating), so K3 would reduce the resistance and
//!   K4 would push a withdrawing pad. At rest the soil is rigid-plastic: it supplies the load up
//!   to `AP·(K1 + K2·ZPEN)`; while withdrawing FZP = 0.
//! - eq. (102), corrected: `FDRAG = APF·[K5 + K6·SP + K7·ZPEN + K8·‖SṖ‖²]` along −v̂_xy (the
//!   printed unit vector SṖ/SP is dimensionally wrong); APF = 2·PR·min(ZPEN, pad height).
//! - eq. (103): `ZP̈ = (FZP − FZI)/PMASS + g_z`, integrated with constant forces over a step
//!   ([`Soil::advance_vertical`]), with friction-like stops at ṗ = 0.
//! - eq. (104): FGRND = FDRAG + FDRAGP, both along −v̂: the caller adds the magnitudes.

use crate::{non_negative, positive, LawError};
use touchdown_scenario::model;

/// Soil constants and footpad geometry of eqs. (101)-(102).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Soil {
    /// K1-K8 of eqs. (101)-(102), SI (the scenario's resolved constants).
    pub k: model::Soil,
    /// AP, footpad bottom area, m².
    pub pad_area: f64,
    /// PR, footpad radius, m.
    pub pad_radius: f64,
    /// Footpad (cylinder) height, m: bounds the frontal area.
    pub pad_height: f64,
}

/// Result of one vertical step of a footpad in soil ([`Soil::advance_vertical`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VerticalStep {
    /// ZPEN at the end of the step, m (may become negative while withdrawing: the pad has left
    /// its hole and the caller detaches it; docs/errata.md, "Contact and release").
    pub depth: f64,
    /// ṗ at the end of the step, m/s (positive deeper; exactly 0 when the pad came to rest).
    pub rate: f64,
    /// Mean upward soil force over the step, N (soil impulse / dt, ≥ 0).
    pub force: f64,
    /// Work done by the soil on the pad over the step, J (≤ 0). With constant force phases the
    /// balance `½·m·(ṗ₁² − ṗ₀²) = load·(depth₁ − depth₀) + work` holds exactly.
    pub work: f64,
}

impl Soil {
    /// Soil from the constants `k` (SI, all ≥ 0 finite), AP (m²), PR (m) and pad height (m),
    /// all positive finite.
    pub fn new(
        k: model::Soil,
        pad_area: f64,
        pad_radius: f64,
        pad_height: f64,
    ) -> Result<Self, LawError> {
        let values = [k.k1, k.k2, k.k3, k.k4, k.k5, k.k6, k.k7, k.k8];
        const NAMES: [&str; 8] = ["K1", "K2", "K3", "K4", "K5", "K6", "K7", "K8"];
        for (name, value) in NAMES.into_iter().zip(values) {
            non_negative(name, value)?;
        }
        Ok(Soil {
            k,
            pad_area: positive("footpad area AP", pad_area)?,
            pad_radius: positive("footpad radius PR", pad_radius)?,
            pad_height: positive("footpad height", pad_height)?,
        })
    }

    /// Soil resistance to penetration FZP, N (≥ 0), at `depth` = ZPEN (m, taken as ≥ 0) and
    /// `rate` = ṗ = −ŻP (m/s). Eq. (101) corrected for ṗ > 0; [`Soil::static_capacity`] at
    /// ṗ = 0 (the most a resting pad can receive); 0 for ṗ < 0 (withdrawing).
    #[inline]
    pub fn bearing(&self, depth: f64, rate: f64) -> f64 {
        if rate < 0.0 {
            return 0.0;
        }
        // eq. (101), corrected: rate terms in ṗ = −ŻP > 0
        self.pad_area
            * (self.k.k1 + self.k.k2 * depth.max(0.0) + rate * (self.k.k3 + self.k.k4 * rate))
    }

    /// Holding capacity of a resting pad, `AP·(K1 + K2·ZPEN)`, N (rigid-plastic; `depth` in m).
    #[inline]
    pub fn static_capacity(&self, depth: f64) -> f64 {
        self.pad_area * (self.k.k1 + self.k.k2 * depth.max(0.0))
    }

    /// Frontal area APF = 2·PR·min(ZPEN, height), m² (cylindrical pad; 0 for depth ≤ 0).
    #[inline]
    pub fn frontal_area(&self, depth: f64) -> f64 {
        2.0 * self.pad_radius * depth.clamp(0.0, self.pad_height)
    }

    /// Lateral drag magnitude, N, eq. (102) corrected: APF·[K5 + K6·SP + K7·ZPEN + K8·‖SṖ‖²].
    /// `depth` = ZPEN (m), `displacement` = SP, lateral distance from the touchdown point (m),
    /// `speed` = ‖SṖ‖ (m/s). Acts along −v̂_xy; at zero speed the K5 term is a static limit for
    /// the caller's stick logic.
    #[inline]
    pub fn lateral_drag(&self, depth: f64, displacement: f64, speed: f64) -> f64 {
        // eq. (102), corrected to a magnitude
        self.frontal_area(depth)
            * (self.k.k5
                + self.k.k6 * displacement.abs()
                + self.k.k7 * depth.max(0.0)
                + self.k.k8 * speed * speed)
    }

    /// One vertical step of a footpad in soil, eq. (103) with constant forces over the step.
    ///
    /// `depth` = ZPEN (m), `rate` = ṗ (m/s, positive deeper), `load` (N, positive downward): the
    /// net force on the pad from everything but the soil (FZI plus the pad's weight component,
    /// −PMASS·g_z), `mass` = PMASS (kg, positive), `dt` (s; ≤ 0 leaves the state unchanged).
    ///
    /// Rules (docs/errata.md, "Eq. (101): soil bearing", rigid-plastic):
    /// - penetrating (ṗ > 0): FZP = [`Soil::bearing`] at the start, frozen; ṗ′ = (load − FZP)/m.
    ///   If ṗ would reach 0 within the step the pad stops there (position from the mean velocity
    ///   up to the stop) and the at-rest rule covers the rest of the step;
    /// - at rest (ṗ = 0): held while 0 ≤ load ≤ [`Soil::static_capacity`] (the soil supplies
    ///   `load`); above the capacity it penetrates with net force load − capacity; with
    ///   load < 0 it withdraws;
    /// - withdrawing (ṗ < 0): no soil force; if ṗ would reach 0 it stops there and the at-rest
    ///   rule covers the rest of the step.
    #[inline]
    pub fn advance_vertical(
        &self,
        depth: f64,
        rate: f64,
        load: f64,
        mass: f64,
        dt: f64,
    ) -> VerticalStep {
        let (mut z, mut v) = (depth, rate);
        let (mut t_left, mut impulse, mut work) = (dt.max(0.0), 0.0, 0.0);
        // At most: moving phase → stop → at-rest phase (which always ends the step).
        while t_left > 0.0 {
            let (f, rest) = if v != 0.0 {
                (self.bearing(z, v), false)
            } else {
                let cap = self.static_capacity(z);
                if (0.0..=cap).contains(&load) {
                    impulse += load * t_left; // held: the soil supplies the load
                    break;
                }
                (if load > cap { cap } else { 0.0 }, true)
            };
            // eq. (103) with constant force: ṗ′ = (load − FZP)/PMASS
            let acc = (load - f) / mass;
            let t_stop = if !rest && acc * v < 0.0 {
                -v / acc
            } else {
                f64::INFINITY
            };
            let t = t_stop.min(t_left);
            let v1 = if t_stop <= t_left { 0.0 } else { v + acc * t };
            let dz = 0.5 * (v + v1) * t;
            z += dz;
            v = v1;
            impulse += f * t;
            work -= f * dz;
            t_left -= t;
            if t_stop > t {
                break;
            }
        }
        VerticalStep {
            depth: z,
            rate: v,
            force: if dt > 0.0 { impulse / dt } else { 0.0 },
            work,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // AP = 0.1 m², K1 = 1e4 Pa, K2 = 1e6 Pa/m: capacity 1000 N + 1e5 N/m·z.
    fn soil(k3: f64, k4: f64) -> Soil {
        Soil::new(
            constants([1e4, 1e6, k3, k4, 2e3, 5e4, 3e5, 40.0]),
            0.1,
            0.2,
            0.05,
        )
        .unwrap()
    }

    fn constants([k1, k2, k3, k4, k5, k6, k7, k8]: [f64; 8]) -> model::Soil {
        model::Soil {
            k1,
            k2,
            k3,
            k4,
            k5,
            k6,
            k7,
            k8,
        }
    }

    #[test]
    fn resting_pad_below_capacity_stays_put() {
        let s = soil(100.0, 10.0);
        let r = s.advance_vertical(0.01, 0.0, 1500.0, 10.0, 1e-3);
        // capacity at 0.01 m: 0.1·(1e4 + 1e6·0.01) = 2000 N ≥ 1500 N
        assert_eq!(r.depth, 0.01);
        assert_eq!(r.rate, 0.0);
        assert_eq!(r.force, 1500.0);
        assert_eq!(r.work, 0.0);
    }

    #[test]
    fn rate_terms_resist_penetration_and_nothing_resists_withdrawal() {
        let s = soil(100.0, 10.0);
        // 0.1·(1e4 + 1e6·0.02 + 100·2 + 10·4) = 3024 N (eq. 101 with ṗ = +2 m/s)
        assert!((s.bearing(0.02, 2.0) - 3024.0).abs() < 1e-9);
        assert!(s.bearing(0.02, 2.0) > s.bearing(0.02, 0.0));
        assert_eq!(s.bearing(0.02, 0.0), s.static_capacity(0.02));
        assert_eq!(s.bearing(0.02, -2.0), 0.0);
        // A withdrawing pad under upward load: free flight, no soil work.
        let r = s.advance_vertical(0.02, -1.0, -100.0, 10.0, 1e-3);
        assert_eq!((r.force, r.work), (0.0, 0.0));
        assert!((r.rate - (-1.0 - 10.0 * 1e-3)).abs() < 1e-15);
    }

    #[test]
    fn step_load_from_rest_stops_at_twice_the_static_depth_and_holds() {
        // K3 = K4 = 0, load L from rest at the surface: m·z̈ = (L − AP·K1) − AP·K2·z, a spring
        // half-cycle from rest, stopping at z* = 2(L − AP·K1)/(AP·K2); rigid-plastic, it then
        // holds since capacity(z*) = 2L − AP·K1 > L.
        let s = soil(0.0, 0.0);
        let (load, m, dt) = (3000.0, 10.0, 1e-5);
        let z_star = 2.0 * (3000.0 - 1000.0) / 1e5;
        let (mut z, mut v) = (0.0, 0.0);
        let mut steps = 0;
        while steps == 0 || v > 0.0 {
            let r = s.advance_vertical(z, v, load, m, dt);
            (z, v) = (r.depth, r.rate);
            steps += 1;
        }
        assert!((z - z_star).abs() < 1e-3 * z_star, "z = {z}, z* = {z_star}");
        // π·√(m/k) = π·0.01 s to stop
        assert!((steps as f64 * dt - 0.01 * std::f64::consts::PI).abs() < 1e-4);
        for _ in 0..100 {
            let r = s.advance_vertical(z, v, load, m, dt);
            assert_eq!((r.depth, r.rate, r.force), (z, 0.0, load));
        }
    }

    #[test]
    fn slow_load_ramp_follows_the_static_depth() {
        // Quasi-static: load ramped 1000 → 6000 N over 5 s, then held; at rest the depth must
        // satisfy capacity ≥ load (z ≥ z_eq) and lie close to z_eq = (L/AP − K1)/K2 = 0.05 m.
        let s = soil(0.0, 0.0);
        let (m, dt) = (10.0, 1e-4);
        let (mut z, mut v) = (0.0, 0.0);
        for i in 0..60_000 {
            let load = 1000.0 + 5000.0 * (i as f64 * dt / 5.0).min(1.0);
            let r = s.advance_vertical(z, v, load, m, dt);
            (z, v) = (r.depth, r.rate);
        }
        let z_eq = (6000.0 / 0.1 - 1e4) / 1e6;
        assert_eq!(v, 0.0);
        assert!(z >= z_eq - 1e-12 && z - z_eq < 1e-2 * z_eq, "z = {z}");
    }

    #[test]
    fn energy_balance_closes() {
        // ½m(ṗ₁² − ṗ₀²) = Σ load·Δz + Σ work, exactly per constant-force phase, through
        // penetration, stops, holds and withdrawal (the load dips to −500 N), staying in soil.
        let s = soil(300.0, 50.0);
        let (m, dt) = (200.0, 2e-4);
        let (mut z, mut v) = (0.0, 3.0);
        let (v0, mut input, mut soil_work) = (v, 0.0, 0.0);
        let mut seen = [0; 3]; // withdrawing, at rest, penetrating
        for i in 0..5000 {
            let t = i as f64 * dt;
            let load = 3000.0 * (11.0 * t).sin() + 2500.0;
            let r = s.advance_vertical(z, v, load, m, dt);
            input += load * (r.depth - z);
            soil_work += r.work;
            assert!(r.work <= 0.0 && r.force >= 0.0 && r.depth > 0.0);
            (z, v) = (r.depth, r.rate);
            seen[if v < 0.0 {
                0
            } else if v == 0.0 {
                1
            } else {
                2
            }] += 1;
        }
        assert!(seen.iter().all(|&n| n > 100), "{seen:?}");
        let dke = 0.5 * m * (v * v - v0 * v0);
        assert!((dke - input - soil_work).abs() < 1e-9 * input.abs().max(1.0));
        assert!(soil_work < 0.0);
    }

    #[test]
    fn lateral_drag_and_frontal_area() {
        let s = soil(0.0, 0.0);
        // APF = 2·0.2·0.03 = 0.012 m²; [2e3 + 5e4·0.1 + 3e5·0.03 + 40·1.5²] = 16090 Pa
        assert!((s.frontal_area(0.03) - 0.012).abs() < 1e-15);
        assert!((s.lateral_drag(0.03, 0.1, 1.5) - 0.012 * 16090.0).abs() < 1e-9);
        // Frontal area saturates at the pad height (0.05 m) and is 0 out of the soil.
        assert!((s.frontal_area(0.5) - 2.0 * 0.2 * 0.05).abs() < 1e-15);
        assert_eq!(s.frontal_area(-0.1), 0.0);
        assert!(Soil::new(
            constants([1.0, -1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]),
            0.1,
            0.2,
            0.05
        )
        .is_err());
        assert!(Soil::new(constants([0.0; 8]), 0.0, 0.2, 0.05).is_err());
    }
}
