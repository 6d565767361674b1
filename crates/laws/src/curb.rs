//! Curbs on the rigid surface and footpad crushing against them, eqs. (86)-(95), figs. 18-20.
//!
//! A curb is fixed at the footpad's first contact (XPI, YPI) by its normal distance DWALLI and
//! the angle WALANG of its normal from +X (fig. 19). All vectors are in the surface (inertial
//! X-Y) plane.
//!
//! - eqs. (87)-(89): a = DWALLI·cos W, b = DWALLI·sin W, Â = (a, b)/DWALLI (pad → curb).
//! - eq. (90): B̂ = Â × ẑ = (sin W, −cos W), along the curb.
//! - eqs. (91)-(92), corrected: DWALL = A·Â with A = (XPI + a − XP, YPI + b − YP); the printed
//!   eq. (92) divides by DWALL itself (circular), the divisor is DWALLI.
//! - eq. (93): PSTRK = PR − DWALL, crushing when positive.
//! - eq. (94): the crush force on the pad is −PFRC·Â (away from the curb).
//! - eq. (95), corrected (vector times vector in print): FWF = −UW·PFRC·sgn(SṖ·B̂)·B̂.
//!
//! PFRC comes from the footpad force-deflection diagram (fig. 18, missing) with memory: the
//! same virgin-curve/backoff law as the struts ([`Honeycomb`]), one [`CrushMemory`] per pad and
//! curb (docs/errata.md, "Modelling choices the report leaves open"). The pad bottom is rigid.

use nalgebra::Vector2;

use crate::sliding::VELOCITY_ROUNDING;
use crate::{finite, non_negative, positive, CrushMemory, Honeycomb, LawError};

/// One curb of one footpad (figs. 19-20).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Curb {
    /// DWALLI: normal distance from the pad centre to the curb at first contact, m.
    dwalli: f64,
    /// (a, b) of eqs. (87)-(88), m.
    ab: Vector2<f64>,
    /// Â of eq. (89): unit normal from the pad toward the curb.
    a_hat: Vector2<f64>,
    /// B̂ of eq. (90): unit vector along the curb.
    b_hat: Vector2<f64>,
    /// UW: pad-curb friction coefficient.
    friction: f64,
}

impl Curb {
    /// A curb from DWALLI (m, positive), WALANG (rad, from +X to the curb normal) and UW (≥ 0).
    pub fn new(dwalli: f64, walang: f64, uw: f64) -> Result<Self, LawError> {
        positive("curb distance DWALLI", dwalli)?;
        finite("curb angle WALANG", walang)?;
        non_negative("curb friction UW", uw)?;
        let (s, c) = walang.sin_cos();
        Ok(Curb {
            dwalli,
            // eqs. (87)-(88)
            ab: Vector2::new(dwalli * c, dwalli * s),
            // eq. (89): (a, b)/DWALLI
            a_hat: Vector2::new(c, s),
            // eq. (90): Â × ẑ
            b_hat: Vector2::new(s, -c),
            friction: uw,
        })
    }

    /// Â, unit normal from the pad toward the curb (eq. 89).
    pub fn normal(&self) -> Vector2<f64> {
        self.a_hat
    }

    /// B̂, unit vector along the curb (eq. 90).
    pub fn along(&self) -> Vector2<f64> {
        self.b_hat
    }

    /// DWALL, m: distance from the pad centre `pad_xy` = (XP, YP) to the curb, given the first
    /// contact point `touchdown_xy` = (XPI, YPI), both m.
    #[inline]
    pub fn distance(&self, touchdown_xy: Vector2<f64>, pad_xy: Vector2<f64>) -> f64 {
        // eq. (91): A = W − (XP, YP), W = (XPI + a, YPI + b)
        let a = touchdown_xy + self.ab - pad_xy;
        // eq. (92), corrected: A·(a, b)/DWALLI = A·Â
        a.dot(&self.a_hat)
    }

    /// PSTRK = PR − DWALL, m (eq. 93): footpad crushing normal to the curb when positive.
    /// `pad_radius` = PR, the undeformed footpad radius, m.
    #[inline]
    pub fn crush(&self, touchdown_xy: Vector2<f64>, pad_xy: Vector2<f64>, pad_radius: f64) -> f64 {
        pad_radius - self.distance(touchdown_xy, pad_xy)
    }

    /// In-plane force of the curb on the footpad, N: crush force plus curb friction.
    ///
    /// `crush_force` = PFRC (N, from [`FootpadCrush::force`]; negative values are taken as 0),
    /// `pad_velocity` = SṖ = (ẊP, ẎP), m/s. Returns `−PFRC·Â − UW·PFRC·sgn(SṖ·B̂)·B̂`
    /// (eqs. 94-95); no friction when the along-curb velocity is zero to rounding (within
    /// [`VELOCITY_ROUNDING`] of the footpad's speed: a footpad moving straight at a curb whose
    /// direction is rounded, such as cos 90° = 6e-17, does not slide along it).
    #[inline]
    pub fn force(&self, crush_force: f64, pad_velocity: Vector2<f64>) -> Vector2<f64> {
        let pfrc = crush_force.max(0.0);
        // eq. (94)
        let normal = -self.a_hat * pfrc;
        // eq. (95), corrected: PFRC scalar, sign from SṖ·B̂
        let v_along = pad_velocity.dot(&self.b_hat);
        let sgn = if v_along.abs() <= VELOCITY_ROUNDING * pad_velocity.norm() {
            0.0
        } else {
            v_along.signum()
        };
        normal - self.b_hat * (self.friction * pfrc * sgn)
    }
}

/// Footpad force-deflection diagram for crushing against a curb (fig. 18, missing from the
/// report), with memory: the [`Honeycomb`] virgin-curve/backoff law on PSTRK.
///
/// Keep one [`CrushMemory`] per pad and curb ("retain deformed footpad geometry"; crush along
/// different curbs is independent). Contact only while PSTRK exceeds the permanent set
/// (docs/errata.md, "Modelling choices the report leaves open"); the pad bottom is rigid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FootpadCrush {
    /// The load-deflection law: stroke = PSTRK, m; force = PFRC, N.
    pub table: Honeycomb,
}

impl FootpadCrush {
    /// Wraps a load-deflection law.
    pub fn new(table: Honeycomb) -> Self {
        FootpadCrush { table }
    }

    /// PFRC, N (≥ 0), at crushing `pstrk` (m, eq. 93) given the committed memory; zero at or
    /// below the permanent set.
    #[inline]
    pub fn force(&self, pstrk: f64, memory: CrushMemory) -> f64 {
        if self.in_contact(pstrk, memory) {
            self.table.force(pstrk, memory)
        } else {
            0.0
        }
    }

    /// True when the pad touches the curb: PSTRK > max(0, permanent set).
    #[inline]
    pub fn in_contact(&self, pstrk: f64, memory: CrushMemory) -> bool {
        pstrk > 0.0 && pstrk > self.table.permanent_set(memory)
    }

    /// Commits an accepted PSTRK (m) into the memory.
    #[inline]
    pub fn commit(&self, pstrk: f64, memory: &mut CrushMemory) {
        self.table.commit(pstrk, memory)
    }

    /// Recoverable elastic energy at `pstrk` (m), J.
    #[inline]
    pub fn stored_energy(&self, pstrk: f64, memory: CrushMemory) -> f64 {
        if self.in_contact(pstrk, memory) {
            self.table.stored_energy(pstrk, memory)
        } else {
            0.0
        }
    }
}

/// The curbs of a scene: each (leg, curb), and the footpad crushing diagram (fig. 18) they
/// share. The committed crush memories are the caller's, one per curb in the order of `list`
/// ([`Curbs::memories`]), as the gear's memories are ([`crate::GearMemory`]).
#[derive(Debug, Clone)]
pub struct Curbs {
    /// (leg index, curb), at most two per leg.
    pub list: Vec<(usize, Curb)>,
    /// Footpad crushing diagram with memory.
    pub crush: FootpadCrush,
}

impl Curbs {
    /// The memories of uncrushed curbs, one per curb of `list` (crush along different curbs is
    /// independent).
    pub fn memories(&self) -> Vec<CrushMemory> {
        vec![CrushMemory::default(); self.list.len()]
    }

    /// In-plane force of leg `leg`'s curbs on its footpad, N, with the footpad at `pad_xy`
    /// (m) moving at `velocity` (m/s), its first contact at `touchdown_xy` (m), radius `radius`
    /// (m), the curbs' committed memories `memory`: eqs. (91)-(95) per curb, summed over the
    /// footpad's curbs (eq. 96 corrected).
    pub fn force(
        &self,
        memory: &[CrushMemory],
        leg: usize,
        touchdown_xy: Vector2<f64>,
        pad_xy: Vector2<f64>,
        velocity: Vector2<f64>,
        radius: f64,
    ) -> Vector2<f64> {
        let mut f = Vector2::zeros();
        for ((l, curb), m) in self.list.iter().zip(memory) {
            if *l == leg {
                let pstrk = curb.crush(touchdown_xy, pad_xy, radius); // eq. (93)
                let pfrc = self.crush.force(pstrk, *m); // fig. 18 with memory
                if pfrc > 0.0 {
                    f += curb.force(pfrc, velocity); // eqs. (94)-(95)
                }
            }
        }
        f
    }

    /// Where a footpad of leg `leg` landing again at `pad_xy` (m; its first contact at
    /// `touchdown_xy`, radius `r`, m) meets its curbs (committed memories `memory`): moved back
    /// along each curb's normal to the crushed face, where the curb carries no load (its
    /// permanent set), if it would land beyond it. A footpad that comes down inside a curb's
    /// crushed zone lands against the curb, as it does on its plane: it does not crush the curb
    /// without work.
    pub fn landing(
        &self,
        memory: &[CrushMemory],
        leg: usize,
        touchdown_xy: Vector2<f64>,
        pad_xy: Vector2<f64>,
        r: f64,
    ) -> Vector2<f64> {
        let mut xy = pad_xy;
        for ((l, curb), m) in self.list.iter().zip(memory) {
            if *l == leg {
                let face = self.crush.table.permanent_set(*m).max(0.0);
                let beyond = curb.crush(touchdown_xy, xy, r) - face;
                if beyond > 0.0 {
                    xy -= curb.normal() * beyond;
                }
            }
        }
        xy
    }

    /// Commits into `memory` the crush of leg `leg`'s curbs with the footpad at `pad_xy`
    /// (accepted state).
    pub fn commit(
        &self,
        memory: &mut [CrushMemory],
        leg: usize,
        touchdown_xy: Vector2<f64>,
        pad_xy: Vector2<f64>,
        r: f64,
    ) {
        for ((l, curb), m) in self.list.iter().zip(memory) {
            if *l == leg {
                self.crush.commit(curb.crush(touchdown_xy, pad_xy, r), m);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{LoadStroke, Stage};

    fn curb() -> Curb {
        Curb::new(0.5, 30f64.to_radians(), 0.3).unwrap()
    }

    #[test]
    fn geometry() {
        let c = curb();
        let td = Vector2::new(1.0, -2.0);
        // At the touchdown point DWALL = DWALLI (eq. 92 corrected).
        assert!((c.distance(td, td) - 0.5).abs() < 1e-15);
        // Â from eq. (89) and B̂ ⟂ Â (eq. 90).
        let w = 30f64.to_radians();
        assert!((c.normal() - Vector2::new(w.cos(), w.sin())).norm() < 1e-15);
        assert!(c.normal().dot(&c.along()).abs() < 1e-15);
        // Moving toward the curb by d reduces DWALL by d; moving along it changes nothing.
        let d = 0.123;
        assert!((c.distance(td, td + c.normal() * d) - (0.5 - d)).abs() < 1e-15);
        assert!((c.distance(td, td + c.along() * 7.0) - 0.5).abs() < 1e-14);
        // PSTRK = PR − DWALL (eq. 93).
        assert!((c.crush(td, td + c.normal() * d, 0.5) - d).abs() < 1e-15);
        assert!(Curb::new(0.0, 0.0, 0.1).is_err());
        assert!(Curb::new(0.5, 0.0, -0.1).is_err());
    }

    #[test]
    fn force_directions() {
        let c = curb();
        // Crush force pushes the pad away from the curb (eq. 94).
        let f = c.force(1000.0, Vector2::zeros());
        assert!((f + c.normal() * 1000.0).norm() < 1e-12);
        // Friction opposes the along-curb velocity, magnitude UW·PFRC (eq. 95 corrected).
        for v in [c.along() * 2.0 + c.normal(), -c.along() * 0.1] {
            let fw = c.force(1000.0, v) - f;
            assert!((fw.norm() - 0.3 * 1000.0).abs() < 1e-9);
            assert!(fw.dot(&v) < 0.0 && fw.dot(&c.normal()).abs() < 1e-12);
        }
        // No friction for motion straight into the curb; no force when PFRC ≤ 0.
        assert!((c.force(1000.0, c.normal() * 3.0) - f).norm() < 1e-12);
        assert_eq!(c.force(-5.0, c.along()), Vector2::zeros());
        // A curb at 90° has B̂ = (−1, 6e-17): a footpad moving straight along +Y into it meets no
        // friction, like its mirror image, whose rounding has the other sign.
        let ahead = Curb::new(0.5, std::f64::consts::FRAC_PI_2, 0.3).unwrap();
        let straight = Vector2::new(0.0, 1.5);
        assert_ne!(
            straight.dot(&ahead.along()),
            0.0,
            "the rounding this guards against"
        );
        let f = ahead.force(1000.0, straight);
        assert_eq!(f, -ahead.normal() * 1000.0);
        let v = Vector2::new(1e-6, 1.5);
        assert!(
            (ahead.force(1000.0, v) - f).norm() > 299.0,
            "a real slide has friction"
        );
    }

    #[test]
    fn pad_pushed_into_a_curb_stops_on_the_table_and_keeps_its_set() {
        // Fig. 18 stand-in: onset 1e5 N/m to a 5000 N plateau (to 0.2 m), backoff 1e6 N/m.
        let (k, kb) = (1e5, 1e6);
        let stage = Stage {
            crush_load: 5000.0,
            stroke_end: 0.2,
        };
        let pad = FootpadCrush::new(
            Honeycomb::new(LoadStroke::new(k, &[stage], 1e8).unwrap(), kb, 1.0).unwrap(),
        );
        let c = curb();
        let (pr, m) = (0.5, 20.0); // PR = DWALLI: touching at first contact
        let td = Vector2::zeros();
        let mut mem = CrushMemory::default();
        // Pad pushed toward the curb by a constant force, critically damped on the active rate
        // (no overshoot), semi-implicit Euler; memory committed every step.
        let run = |push: f64, rate: f64, pos: &mut Vector2<f64>, mem: &mut CrushMemory| {
            let damping = 2.0 * (rate * m).sqrt();
            let mut vel = Vector2::zeros();
            let dt = 1e-5;
            for _ in 0..100_000 {
                let pstrk = c.crush(td, *pos, pr);
                let f = c.force(pad.force(pstrk, *mem), vel) + c.normal() * push - vel * damping;
                vel += f / m * dt;
                *pos += vel * dt;
                pad.commit(c.crush(td, *pos, pr), mem);
            }
        };
        let mut pos = td;
        let f = 2000.0;
        run(f, k, &mut pos, &mut mem);
        // Rest on the onset ramp where the table's load equals F: PSTRK = F/k = 0.02 m.
        let x = c.crush(td, pos, pr);
        assert!((x - f / k).abs() < 1e-6 * (f / k), "x = {x}");
        assert!((pad.force(x, mem) - f).abs() < 1e-3);
        // Unload: the pad rebounds along K_B; permanent set G = x_max − F/K_B = 0.018 m.
        run(0.0, kb, &mut pos, &mut mem);
        let g = pad.table.permanent_set(mem);
        assert!((g - (f / k - f / kb)).abs() < 1e-8, "G = {g}");
        assert!(c.crush(td, pos, pr) <= g + 1e-9);
        assert!(!pad.in_contact(g - 1e-6, mem) && pad.force(g - 1e-6, mem) == 0.0);
        // Second contact starts at the set: 1000 N rests on the backoff line at G + 1000/K_B.
        run(1000.0, kb, &mut pos, &mut mem);
        let x2 = c.crush(td, pos, pr);
        assert!((x2 - (g + 1000.0 / kb)).abs() < 1e-8, "x2 = {x2}");
    }
}
