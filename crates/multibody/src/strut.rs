//! The strut laws at one state of a multibody gear (a massive outer cylinder on a trunnion
//! joint, a stroke joint, a footpad link), shared by the multibody engines (the rapier rebuild
//! and the MuJoCo runner) so that both apply the same forces to the same joints:
//!
//! - primary strut: the honeycomb's elastic branches (onset, rebound, bottoming, extension stop)
//!   and the viscous force are explicit axial forces; a honeycomb crushing on a plateau
//!   (compressing on its virgin curve) is the crush load, which rapier's joint motor takes as a
//!   bound that may stop the stroke but never drive it, and MuJoCo applies as a force, the
//!   core's law (a friction row would hold the stroke both ways); bearing friction is
//!   a dry-friction bound μB·(F1 + F2) from the report's statics (eqs. 53-63), with the side load
//!   FM of the massless-strut closed form; the tripod's primary, a two-force member, has neither
//!   (FM = 0, FBR = 0: docs/errata.md, "Tripod gear");
//! - secondary struts: massless two-force members between their trunnions on the vehicle and
//!   point 1, on the outer cylinder for the cantilever and at the footpad ball joint BP for the
//!   tripod, with the double-acting honeycomb and viscous laws.

use nalgebra::Vector3;
use touchdown_laws::{side_load, GearLaws, GearMemory, LawError};
use touchdown_record::Law;
use touchdown_scenario::model::Leg;
use touchdown_scenario::schema::Arrangement;

/// Geometry and rates of one gear at one state (inertial axes).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StrutKinematics {
    /// Primary compression stroke c = −q (q: the stroke joint's extension), m.
    pub c: f64,
    /// Compression rate ċ, m/s.
    pub c_dot: f64,
    /// Secondary strokes S31, S41 (tension positive), m.
    pub s: [f64; 2],
    /// Secondary stroking rates, m/s.
    pub s_dot: [f64; 2],
    /// Unit vectors trunnion → point 1 of the secondaries.
    pub u: [Vector3<f64>; 2],
    /// Secondary trunnions B3, B4, m.
    pub trunnion: [Vector3<f64>; 2],
    /// Point 1, m: on the outer cylinder (cantilever), the footpad ball joint BP (tripod).
    pub point1: Vector3<f64>,
    /// Strut axis V̂2P (trunnion to footpad, unit).
    pub axis: Vector3<f64>,
    /// Footpad ball joint BP, m.
    pub footpad: Vector3<f64>,
}

/// The forces of one gear for a step, from its kinematics and committed memory.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StrutForces {
    /// Explicit primary honeycomb force (elastic branches, stops), N, compression positive;
    /// zero while the strut crushes on a plateau (`crush_load`).
    pub honeycomb: f64,
    /// The crush load, N, while the strut crushes on a plateau, zero otherwise: rapier holds it as
    /// the bound of its plateau motor, MuJoCo applies it as a force with `honeycomb`.
    pub crush_load: f64,
    /// Primary viscous force FVP, N, compression positive.
    pub viscous: f64,
    /// Bearing-friction bound μB·(F1 + F2), N.
    pub bearing_bound: f64,
    /// Secondary honeycomb forces FC31, FC41, N, tension positive.
    pub secondary_honeycomb: [f64; 2],
    /// Secondary viscous forces FV31, FV41, N, tension positive.
    pub secondary_viscous: [f64; 2],
}

/// Work done on each law over one step, J (positive: absorbed by the gear).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StrutWork {
    /// On the honeycombs (primary and secondaries), J.
    pub honeycomb: f64,
    /// On the viscous forces, J.
    pub viscous: f64,
    /// On the bearing friction, J.
    pub bearing: f64,
}

impl StrutForces {
    /// Secondary axial forces F31, F41, N, tension positive (eq. 51).
    pub fn secondary(&self) -> [f64; 2] {
        [
            self.secondary_honeycomb[0] + self.secondary_viscous[0],
            self.secondary_honeycomb[1] + self.secondary_viscous[1],
        ]
    }

    /// The primary's axial force without the bearing friction, N, compression positive: the
    /// honeycomb's law (the plateau at its crush load while engaged) and the viscous force.
    pub fn axial(&self) -> f64 {
        self.honeycomb + self.crush_load + self.viscous
    }

    /// The primary axial force F2P, N, compression positive (eq. 50), with the plateau at its
    /// bound while engaged and the bearing friction at its bound against the stroking rate.
    pub fn primary(&self, c_dot: f64) -> f64 {
        let friction = if c_dot == 0.0 {
            0.0
        } else {
            self.bearing_bound * c_dot.signum()
        };
        self.axial() + friction
    }

    /// The work done on the gear between the states `a` and `b` by the laws whose forces are
    /// these at `a` and `end` at `b` (each evaluated with the memory committed before the
    /// step): each force's mean over the step times its stroke increment, the plateau and the
    /// bearing friction at their bounds. This is the laws' own path integral (exact on a
    /// linear branch, which the stiff elastic branches are), not the work of the forces the
    /// engine held over the step: on an elastic branch of rate K that would book ½·K·Δx² per
    /// step against its stored energy, a first-order error of the ledger and not of the
    /// engine (docs/engines.md, "Energy ledger").
    pub fn work(&self, end: &StrutForces, a: &StrutKinematics, b: &StrutKinematics) -> StrutWork {
        let mean = |x: f64, y: f64| 0.5 * (x + y);
        let dc = b.c - a.c;
        let mut w = StrutWork {
            honeycomb: mean(
                self.honeycomb + self.crush_load,
                end.honeycomb + end.crush_load,
            ) * dc,
            viscous: mean(self.viscous, end.viscous) * dc,
            bearing: mean(self.bearing_bound, end.bearing_bound) * dc.abs(),
        };
        for j in 0..2 {
            let ds = b.s[j] - a.s[j];
            w.honeycomb += mean(self.secondary_honeycomb[j], end.secondary_honeycomb[j]) * ds;
            w.viscous += mean(self.secondary_viscous[j], end.secondary_viscous[j]) * ds;
        }
        w
    }

    /// The first non-finite force, named by its law, if any.
    pub fn non_finite(&self) -> Option<(Law, f64)> {
        [
            (Law::PrimaryHoneycomb, self.honeycomb + self.crush_load),
            (Law::PrimaryViscous, self.viscous),
            (Law::BearingFriction, self.bearing_bound),
            (
                Law::SecondaryHoneycomb,
                self.secondary_honeycomb[0] + self.secondary_honeycomb[1],
            ),
            (
                Law::SecondaryViscous,
                self.secondary_viscous[0] + self.secondary_viscous[1],
            ),
        ]
        .into_iter()
        .find(|(_, x)| !x.is_finite())
    }
}

/// The shared laws at one gear state (eqs. 49-63) of a gear in `arrangement`.
pub fn strut_forces(
    laws: &GearLaws,
    memory: &GearMemory,
    leg: &Leg,
    arrangement: Arrangement,
    k: &StrutKinematics,
) -> Result<StrutForces, LawError> {
    let sec = laws.secondary.forces(k.s, k.s_dot, &k.u, &memory.secondary); // eqs. (49), (51)-(52)
    let p = &laws.primary;
    let bearing_bound = match arrangement {
        Arrangement::Cantilever => {
            let length = leg.l2p - k.c;
            let fm = side_load(&sec.fs, &k.axis, leg.l21, length).norm(); // eqs. (53)-(58)
            p.bearing.friction_bound(fm, k.c)? // eqs. (59)-(63)
        }
        // eqs. (50), (64)-(65) with B1 = BP: no side load, no bearing friction.
        Arrangement::Tripod => 0.0,
    };
    let crushing = if k.c_dot > 0.0 {
        p.honeycomb.crush_load(k.c, memory.primary.compression)
    } else {
        None
    };
    let (honeycomb, crush_load) = match crushing {
        Some(load) => (0.0, load),
        None => (p.stroke_force(k.c, memory.primary), 0.0),
    };
    Ok(StrutForces {
        honeycomb,
        crush_load,
        viscous: p.viscous.force(k.c_dot), // eq. (49)
        bearing_bound,
        secondary_honeycomb: sec.honeycomb,
        secondary_viscous: sec.viscous,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_work_of_a_step_is_each_laws_mean_force_on_its_stroke_increment() {
        let f = StrutForces {
            honeycomb: 0.0,
            crush_load: 1000.0,
            viscous: 50.0,
            bearing_bound: 20.0,
            secondary_honeycomb: [300.0, -200.0],
            secondary_viscous: [10.0, -5.0],
        };
        let a = StrutKinematics::default();
        let b = StrutKinematics {
            c: 0.002,
            s: [0.001, -0.003],
            ..Default::default()
        };
        // Forces that hold over the step: each on its own increment.
        let w = f.work(&f, &a, &b);
        assert!((w.honeycomb - (1000.0 * 0.002 + 300.0 * 0.001 + 200.0 * 0.003)).abs() < 1e-12);
        assert!((w.viscous - (50.0 * 0.002 + 10.0 * 0.001 + 5.0 * 0.003)).abs() < 1e-12);
        // Dry friction dissipates whichever way the strut strokes.
        assert!((w.bearing - 20.0 * 0.002).abs() < 1e-12);
        assert_eq!(f.work(&f, &b, &a).bearing, w.bearing);
        assert_eq!(f.primary(1.0), 1000.0 + 50.0 + 20.0);
        assert_eq!(f.secondary(), [310.0, -205.0]);
        let bad = StrutForces {
            viscous: f64::NAN,
            ..f
        };
        assert_eq!(
            bad.non_finite().map(|(law, _)| law),
            Some(Law::PrimaryViscous)
        );
    }

    #[test]
    fn an_elastic_branch_books_its_stored_energy_over_any_step() {
        // A stop of rate K loaded from x_a to x_b in one step: the work booked is the energy
        // it stores, ½·K·(x_b² − x_a²), however long the step; the force at the start held
        // over the step would book ½·K·(x_b − x_a)² less.
        let k = 4.0e7;
        let at = |c: f64| StrutForces {
            honeycomb: k * c,
            ..Default::default()
        };
        let state = |c: f64| StrutKinematics {
            c,
            ..Default::default()
        };
        for (xa, xb) in [(0.0, 1.0e-4), (1.0e-4, 3.0e-4), (3.0e-4, 0.5e-4)] {
            let w = at(xa).work(&at(xb), &state(xa), &state(xb)).honeycomb;
            let stored = 0.5 * k * (xb * xb - xa * xa);
            assert!(
                (w - stored).abs() < 1e-12 * k * 1e-8,
                "{w} J against {stored} J"
            );
        }
    }
}
