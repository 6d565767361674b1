//! Landing-gear geometry, strokes and force resolution at the footpad for one cantilever gear
//! assembly, eqs. (26)-(34), (49)-(66). Body axes throughout; the gear is massless.
//!
//! Sign conventions (docs/errata.md, "Conventions fixed first"; verified by independent
//! statics, `tests::footpad_force_balances_the_trunnion_loads`):
//! the primary stroke S2P = V2P − L2P is negative in compression; the code works with the
//! compression stroke c = −S2P and FCP, FVP, FBR, F2P compression-positive. Secondary strokes
//! and forces are tension positive. FS = F31·V̂31 + F41·V̂41 is the force the primary exerts on
//! the secondaries at point 1. FP is the force the gear exerts on the footpad.

use nalgebra::Vector3;
use touchdown_laws::{Bending, GearLaws, GearMemory, LawError};
use touchdown_record::Law;
use touchdown_scenario::model::Leg;
use touchdown_scenario::schema::Arrangement;

/// Everything computed for one gear at one state.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GearState {
    /// Primary compression stroke c = L2P − V2P (eq. 33, sign flipped), m.
    pub primary_stroke: f64,
    /// Primary compression rate ċ = −V̇2P, m/s.
    pub primary_rate: f64,
    /// Secondary strokes S31, S41 (eq. 34), tension positive, m.
    pub secondary_stroke: [f64; 2],
    /// Secondary stroking rates V̇31, V̇41, m/s.
    pub secondary_rate: [f64; 2],
    /// FCP, honeycomb force, N (compression positive).
    pub fcp: f64,
    /// FVP, viscous force, N (compression positive).
    pub fvp: f64,
    /// FBR, bearing friction, N (compression positive).
    pub fbr: f64,
    /// F2P = FCP + FVP + FBR, eq. (50), N.
    pub f2p: f64,
    /// FC31, FC41 honeycomb forces, N (tension positive).
    pub fc_secondary: [f64; 2],
    /// FV31, FV41 viscous forces, N (tension positive).
    pub fv_secondary: [f64; 2],
    /// |FM|, side load at the footpad, N.
    pub fm: f64,
    /// FP, force of the gear on the footpad, body axes, N (eq. 65).
    pub fp: Vector3<f64>,
    /// Displacement of point 1 by primary-strut bending at this state, body axes, m (|η|
    /// along FN̂, eqs. 43-47): the next step's secondaries see it (lagged: docs/errata.md,
    /// "Eqs. (47)-(48): bending coupling").
    pub point1_deflection: Vector3<f64>,
    /// λ31, λ41: the apparent lengthening of the secondaries by the lagged bending
    /// displacement (eq. 47), m, included in `secondary_stroke`.
    pub bending_lengthening: [f64; 2],
}

/// The primary strut of a gear at one state, as its evaluation found it: the unit vector V̂2P
/// from the trunnion B2 to the footpad (eq. 28, body axes) and the strut's length |V2P| (eq. 27,
/// m). The bearing friction off the surface (`crate::stiction`) works along it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrimaryAxis {
    /// V̂2P, body axes, dimensionless.
    pub axis: Vector3<f64>,
    /// |V2P|, m.
    pub length: f64,
}

/// A law that left its domain while evaluating a gear.
#[derive(Debug, Clone, PartialEq)]
pub struct GearFault {
    /// The law ([`Law::BearingFriction`], [`Law::Bending`]).
    pub law: Law,
    /// What happened.
    pub error: LawError,
}

/// The gear's arrangement and its optional bending law with the lagged point-1 deflection
/// (body axes, m).
#[derive(Debug, Clone, Copy)]
pub struct GearOptions<'a> {
    /// Cantilever or tripod.
    pub arrangement: Arrangement,
    /// Primary-strut bending with the previous accepted state's point-1 displacement.
    pub bending: Option<(&'a Bending, Vector3<f64>)>,
}

impl GearState {
    /// Secondary axial forces F31, F41 = FC + FV (eq. 51), N, tension positive.
    pub fn f_secondary(&self) -> [f64; 2] {
        [
            self.fc_secondary[0] + self.fv_secondary[0],
            self.fc_secondary[1] + self.fv_secondary[1],
        ]
    }
}

/// Geometry and strut forces for one gear with the footpad at `bp` (body axes, m) moving at
/// `bp_dot` (its velocity relative to the body, in body axes, m/s), eqs. (26)-(65), written
/// into `out` (in place: the state is too large to move cheaply on the hot path); returns the
/// primary strut's axis and length.
pub fn evaluate(
    leg: &Leg,
    laws: &GearLaws,
    memory: &GearMemory,
    bp: &Vector3<f64>,
    bp_dot: &Vector3<f64>,
    options: &GearOptions,
    out: &mut GearState,
) -> Result<PrimaryAxis, GearFault> {
    if options.arrangement == Arrangement::Tripod {
        return Ok(evaluate_tripod(leg, laws, memory, bp, bp_dot, out));
    }
    let bearing = |error| GearFault {
        law: Law::BearingFriction,
        error,
    };
    // eqs. (27)-(28): primary strut vector, length and direction (from point 2 to the pad)
    let v2p = bp - leg.b2;
    let len = v2p.norm();
    let e = v2p / len;
    // eqs. (29)-(30): point 1 at L21 along the primary (cantilever)
    let v21 = e * leg.l21;
    let b1 = leg.b2 + v21;
    // eqs. (31)-(32): secondary strut vectors and directions (trunnion → point 1)
    let v31 = b1 - leg.b3;
    let v41 = b1 - leg.b4;
    let (l31, l41) = (v31.norm(), v41.norm());
    let u = [v31 / l31, v41 / l41];
    // eqs. (33)-(34): strokes (primary as compression c = −S2P; secondaries tension positive)
    let c = leg.l2p - len;
    let mut s = [l31 - leg.l31, l41 - leg.l41];
    let mut bending_lengthening = [0.0; 2];
    // eq. (47), as a stroke correction (docs/errata.md, "Eqs. (47)-(48): bending coupling"):
    // the lagged bending displacement of point 1
    // lengthens secondary i by λ_i = d·V̂i1 (a strut in tension is eased: a softer series spring).
    if let Some((_, d)) = &options.bending {
        let lambda = touchdown_laws::secondary_lengthening(*d, u[0], u[1]);
        s = [s[0] + lambda[0], s[1] + lambda[1]];
        bending_lengthening = lambda;
    }
    // Stroking rates (eq. 49 row): V̇2P = V̂2P·Ḃp; point 1 moves with L21·dV̂2P/dt.
    let v2p_dot = e.dot(bp_dot);
    let e_dot = (bp_dot - e * v2p_dot) / len;
    let b1_dot = e_dot * leg.l21;
    let c_dot = -v2p_dot;
    let s_dot = [u[0].dot(&b1_dot), u[1].dot(&b1_dot)];

    // eqs. (49), (51)-(52): secondary forces, tension positive, and FS, the force of the
    // primary on the secondaries at point 1
    let sec = laws.secondary.forces(s, s_dot, &u, &memory.secondary);
    let (fc, fv, fs) = (sec.honeycomb, sec.viscous, sec.fs);
    // eqs. (53)-(58) with eq. (54) corrected, closed form
    let fm = touchdown_laws::side_load(&fs, &e, leg.l21, len);
    let fm_mag = fm.norm();
    // eqs. (59)-(63): bearing friction, opposing the stroking direction
    let pri = &laws.primary;
    let fbr = pri.bearing.friction(fm_mag, c, c_dot).map_err(bearing)?;
    // eq. (49): primary viscous force (compression positive opposes extension: FVP = CP·sgn(ċ)|ċ|^γ)
    let fvp = pri.viscous.force(c_dot);
    let fcp = pri.stroke_force(c, memory.primary);
    // eq. (50)
    let f2p = fcp + fvp + fbr;
    // eqs. (64)-(65): force on the footpad
    let fp = e * f2p + fm;
    // eqs. (43)-(47), corrected: point 1's deflection under FN (from the honeycomb forces FC
    // only) and the axial load F2P, for the next step.
    let mut point1_deflection = Vector3::zeros();
    if let Some((law, _)) = &options.bending {
        let normal = touchdown_laws::normal_load(fc, u[0], u[1], e);
        let fn_mag = normal.norm();
        if fn_mag > 0.0 {
            let d = law
                .deflection(fn_mag, f2p, leg.l21, len)
                .map_err(|error| GearFault {
                    law: Law::Bending,
                    error,
                })?;
            point1_deflection = normal * (d.magnitude / fn_mag);
        }
    }
    *out = GearState {
        primary_stroke: c,
        primary_rate: c_dot,
        secondary_stroke: s,
        secondary_rate: s_dot,
        fcp,
        fvp,
        fbr,
        f2p,
        fc_secondary: fc,
        fv_secondary: fv,
        fm: fm_mag,
        fp,
        point1_deflection,
        bending_lengthening,
    };
    Ok(PrimaryAxis {
        axis: e,
        length: len,
    })
}

/// The tripod gear (docs/errata.md, "Tripod gear"; docs/model.md, "Tripod gear"): the secondaries meet the primary at the footpad (B1 = BP,
/// eqs. 29-30 with L21 = V2P), so the primary is a two-force member with no side load and no
/// bearing friction, and FP = F2P·V̂2P − FS (eqs. 64-65 rows). Returns the primary's axis and
/// length.
fn evaluate_tripod(
    leg: &Leg,
    laws: &GearLaws,
    memory: &GearMemory,
    bp: &Vector3<f64>,
    bp_dot: &Vector3<f64>,
    out: &mut GearState,
) -> PrimaryAxis {
    let v2p = bp - leg.b2; // eq. (27)
    let len = v2p.norm();
    let e = v2p / len; // eq. (28)
    let (v31, v41) = (bp - leg.b3, bp - leg.b4); // eqs. (31)-(32) with B1 = BP
    let (l31, l41) = (v31.norm(), v41.norm());
    let u = [v31 / l31, v41 / l41];
    let c = leg.l2p - len; // eq. (33)
    let s = [l31 - leg.l31, l41 - leg.l41]; // eq. (34)
    let c_dot = -e.dot(bp_dot);
    let s_dot = [u[0].dot(bp_dot), u[1].dot(bp_dot)];
    let sec = laws.secondary.forces(s, s_dot, &u, &memory.secondary); // eqs. (49)-(52)
    let pri = &laws.primary;
    let fvp = pri.viscous.force(c_dot);
    let fcp = pri.stroke_force(c, memory.primary);
    let f2p = fcp + fvp; // eq. (50) with FBR = 0
    *out = GearState {
        primary_stroke: c,
        primary_rate: c_dot,
        secondary_stroke: s,
        secondary_rate: s_dot,
        fcp,
        fvp,
        fbr: 0.0,
        f2p,
        fc_secondary: sec.honeycomb,
        fv_secondary: sec.viscous,
        fm: 0.0,
        fp: e * f2p - sec.fs, // eq. (65), tripod
        point1_deflection: Vector3::zeros(),
        bending_lengthening: [0.0; 2],
    };
    PrimaryAxis {
        axis: e,
        length: len,
    }
}

/// The gradients of the strokes in the footpad's position BP (`bp`, body axes, m): the
/// primary's compression c (eq. 33), −ê; the secondaries' S31, S41 (eq. 34, tension positive),
/// for a tripod's, which run to the footpad, û (eqs. 31-32 with B1 = BP), for a cantilever's,
/// which run to point 1 at L21 along the primary, (L21/|V2P|)·(I − êêᵀ)·û (eqs. 29-32). Body
/// axes, dimensionless. The lagged bending displacement of point 1 is held over a step and has
/// no gradient (eq. 47).
pub(crate) fn stroke_gradients(
    leg: &Leg,
    arrangement: Arrangement,
    bp: &Vector3<f64>,
) -> [Vector3<f64>; 3] {
    let v2p = bp - leg.b2;
    let len = v2p.norm();
    let e = v2p / len;
    if arrangement == Arrangement::Tripod {
        return [-e, (bp - leg.b3).normalize(), (bp - leg.b4).normalize()];
    }
    let b1 = leg.b2 + e * leg.l21;
    let lever = |u: Vector3<f64>| (u - e * e.dot(&u)) * (leg.l21 / len);
    [
        -e,
        lever((b1 - leg.b3).normalize()),
        lever((b1 - leg.b4).normalize()),
    ]
}

/// The gear of a footpad that has left its surface, relaxed (docs/errata.md, "Contact and
/// release"): a massless gear cannot hold a load without a reaction, so each strut goes back
/// along its unloading branch to the nearest stroke at which it carries no force (the
/// honeycombs' permanent sets, the extension stop's set; bending unloads with them).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Relaxed {
    /// The footpad's body-frame position with the relaxed strokes, m.
    pub bp: Vector3<f64>,
    /// Primary compression stroke, m.
    pub primary_stroke: f64,
    /// Secondary strokes S31, S41 (tension positive), m.
    pub secondary_stroke: [f64; 2],
}

/// Relaxes the gear of `leg` whose footpad is at `bp` (body axes, m) with strokes
/// `primary_stroke` and `secondary_stroke` (m, the honeycombs' strokes, bending included) and
/// the committed `memory` (the leaving state committed first): each stroke is clamped to the
/// range over which its strut carries no force and the footpad is placed where the relaxed
/// struts meet (point 1 from the secondaries and L21 for the cantilever, the footpad from all
/// three for the tripod). `None` if the relaxed struts do not meet.
pub fn relax(
    leg: &Leg,
    laws: &GearLaws,
    memory: &GearMemory,
    arrangement: Arrangement,
    bp: &Vector3<f64>,
    primary_stroke: f64,
    secondary_stroke: [f64; 2],
) -> Option<Relaxed> {
    let p = &laws.primary.honeycomb;
    let c = primary_stroke.clamp(
        -p.stop.slack(memory.primary.extension_depth),
        p.permanent_set(memory.primary.compression),
    );
    let h = &laws.secondary.honeycomb;
    let s = [0, 1].map(|j| {
        let m = memory.secondary[j];
        secondary_stroke[j].clamp(
            -h.compression.permanent_set(m.compression),
            h.tension.permanent_set(m.tension),
        )
    });
    if c == primary_stroke && s == secondary_stroke {
        return Some(Relaxed {
            bp: *bp,
            primary_stroke: c,
            secondary_stroke: s,
        });
    }
    let radii = [leg.l31 + s[0], leg.l41 + s[1]];
    let bp = match arrangement {
        Arrangement::Cantilever => {
            let b1 = leg.b2 + (bp - leg.b2).normalize() * leg.l21;
            let b1 = trilaterate([leg.b2, leg.b3, leg.b4], [leg.l21, radii[0], radii[1]], &b1)?;
            leg.b2 + (b1 - leg.b2) * ((leg.l2p - c) / leg.l21)
        }
        Arrangement::Tripod => trilaterate(
            [leg.b2, leg.b3, leg.b4],
            [leg.l2p - c, radii[0], radii[1]],
            bp,
        )?,
    };
    Some(Relaxed {
        bp,
        primary_stroke: c,
        secondary_stroke: s,
    })
}

/// The point at distances `r` (m) from the three centres `c` (m) nearest to `near`: the
/// intersection of three spheres; `None` if they do not meet (a negative square beyond
/// rounding) or the centres are collinear.
fn trilaterate(c: [Vector3<f64>; 3], r: [f64; 3], near: &Vector3<f64>) -> Option<Vector3<f64>> {
    let d01 = c[1] - c[0];
    let d = d01.norm();
    let ex = d01 / d;
    let d02 = c[2] - c[0];
    let i = ex.dot(&d02);
    let ey = d02 - ex * i;
    let j = ey.norm();
    if j.is_nan() || j <= 1e-12 * d {
        return None;
    }
    let ey = ey / j;
    let ez = ex.cross(&ey);
    let x = (r[0] * r[0] - r[1] * r[1] + d * d) / (2.0 * d);
    let y = (r[0] * r[0] - r[2] * r[2] + i * i + j * j) / (2.0 * j) - x * i / j;
    let z2 = r[0] * r[0] - x * x - y * y;
    if z2 < -1e-9 * r[0] * r[0] {
        return None;
    }
    let base = c[0] + ex * x + ey * y;
    let z = ez * z2.max(0.0).sqrt();
    let (a, b) = (base + z, base - z);
    Some(if (a - near).norm() <= (b - near).norm() {
        a
    } else {
        b
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use touchdown_laws::{
        Bearing, DoubleActingHoneycomb, Honeycomb, LoadStroke, PrimaryStrutLaw, SecondaryStrutLaw,
        Stage, Viscous,
    };

    /// [`evaluate`] into a fresh state.
    fn evaluated(
        leg: &Leg,
        laws: &GearLaws,
        memory: &GearMemory,
        bp: &Vector3<f64>,
        bp_dot: &Vector3<f64>,
        options: &GearOptions,
    ) -> Result<GearState, GearFault> {
        let mut out = GearState::default();
        evaluate(leg, laws, memory, bp, bp_dot, options, &mut out).map(|_| out)
    }

    const CANTILEVER: GearOptions = GearOptions {
        arrangement: Arrangement::Cantilever,
        bending: None,
    };

    fn laws(mu: f64) -> GearLaws {
        let h = |f: f64| {
            Honeycomb::new(
                LoadStroke::new(
                    1e5,
                    &[Stage {
                        crush_load: f,
                        stroke_end: 0.2,
                    }],
                    1e7,
                )
                .unwrap(),
                1e6,
                1.0,
            )
            .unwrap()
        };
        GearLaws {
            primary: PrimaryStrutLaw {
                honeycomb: h(3000.0),
                viscous: Viscous::NONE,
                bearing: Bearing {
                    friction_coefficient: mu,
                    inner_cylinder_length: 0.6,
                    initial_overlap: 0.2,
                },
            },
            secondary: SecondaryStrutLaw {
                honeycomb: DoubleActingHoneycomb {
                    tension: h(1000.0),
                    compression: h(1200.0),
                },
                viscous: Viscous::NONE,
            },
        }
    }

    fn leg() -> Leg {
        Leg::from_points(
            Vector3::new(1.0, 0.0, 0.5),
            Vector3::new(0.9, 0.35, 0.2),
            Vector3::new(0.9, -0.3, 0.1),
            Vector3::new(1.6, 0.05, -0.9),
            0.9,
        )
    }

    /// A deformed footpad position near `bp`: compressed and pushed sideways, m.
    fn deformed(bp: Vector3<f64>) -> Vector3<f64> {
        bp + Vector3::new(-0.03, 0.04, 0.08)
    }

    /// The forces `on_body` (trunnion point, force; body axes) balance −FP in force and its
    /// moment BP × (−FP) about the origin (eq. 66), for the footpad force `fp` at `bp`.
    fn assert_body_balances(
        on_body: &[(Vector3<f64>, Vector3<f64>)],
        bp: &Vector3<f64>,
        fp: &Vector3<f64>,
    ) {
        let total: Vector3<f64> = on_body.iter().map(|(_, f)| *f).sum();
        let moment: Vector3<f64> = on_body.iter().map(|(p, f)| p.cross(f)).sum();
        assert!((total + fp).norm() < 1e-9 * fp.norm());
        assert!((moment - bp.cross(&(-fp))).norm() < 1e-9 * fp.norm());
    }

    /// The strokes' gradients are those of the strokes [`evaluate`] gives, by central
    /// differences of the footpad's position, on both arrangements (a secondary's gradient that
    /// left out the lever L21/|V2P|, 0.63 here, or the projection off the primary fails).
    #[test]
    fn stroke_gradients_are_those_of_the_evaluated_strokes() {
        let (leg, laws, mem) = (leg(), laws(0.0), GearMemory::default());
        let bp = deformed(leg.bp);
        let tripod = GearOptions {
            arrangement: Arrangement::Tripod,
            bending: None,
        };
        for options in [CANTILEVER, tripod] {
            let strokes = |p: Vector3<f64>| {
                let g = evaluated(&leg, &laws, &mem, &p, &Vector3::zeros(), &options).unwrap();
                [
                    g.primary_stroke,
                    g.secondary_stroke[0],
                    g.secondary_stroke[1],
                ]
            };
            let gradients = stroke_gradients(&leg, options.arrangement, &bp);
            let h = 1e-6;
            for axis in 0..3 {
                let mut d = Vector3::zeros();
                d[axis] = h;
                let (plus, minus) = (strokes(bp + d), strokes(bp - d));
                for j in 0..3 {
                    let difference = (plus[j] - minus[j]) / (2.0 * h);
                    assert!(
                        (difference - gradients[j][axis]).abs() < 1e-7,
                        "{:?}, stroke {j}, axis {axis}: {difference} by differences, {} stated",
                        options.arrangement,
                        gradients[j][axis]
                    );
                }
            }
        }
    }

    /// Independent statics of the massless gear: the primary pinned
    /// at 2, secondaries two-force members, pad force FP; the forces at the trunnions on the
    /// body must balance −FP and their moments about the origin must equal BP × (−FP) (eq. 66).
    #[test]
    fn footpad_force_balances_the_trunnion_loads() {
        let leg = leg();
        let laws = laws(0.0);
        let mem = GearMemory::default();
        let bp = deformed(leg.bp);
        let g = evaluated(&leg, &laws, &mem, &bp, &Vector3::zeros(), &CANTILEVER).unwrap();
        assert!(g.fcp > 0.0 && g.fc_secondary.iter().any(|f| f.abs() > 0.0));
        // Reconstruct the trunnion forces on the body.
        let e = (bp - leg.b2).normalize();
        let b1 = leg.b2 + e * leg.l21;
        let u3 = (b1 - leg.b3).normalize();
        let u4 = (b1 - leg.b4).normalize();
        let f = g.f_secondary();
        // Secondary in tension pulls the body trunnion toward point 1.
        let f3 = u3 * f[0];
        let f4 = u4 * f[1];
        // Primary equilibrium: forces on it are −FP (pad), −(f3 + f4) (secondaries pull point 1
        // toward their trunnions when in tension) and R2 at point 2.
        let r2 = g.fp + f3 + f4; // force of the body on the primary at 2
        assert_body_balances(&[(leg.b2, -r2), (leg.b3, f3), (leg.b4, f4)], &bp, &g.fp);
        // Moment balance of the primary about point 2 (the check that fails with printed eq. 54).
        let m2 = (bp - leg.b2).cross(&(-g.fp)) + (b1 - leg.b2).cross(&(-(f3 + f4)));
        assert!(
            m2.norm() < 1e-9 * g.fp.norm(),
            "primary moment about 2: {m2}"
        );
    }

    #[test]
    fn bearing_friction_opposes_stroking() {
        let leg = leg();
        let laws = laws(0.2);
        let mem = GearMemory::default();
        let bp = deformed(leg.bp);
        let e = (bp - leg.b2).normalize();
        let compressing = evaluated(&leg, &laws, &mem, &bp, &(-e * 0.5), &CANTILEVER).unwrap();
        let extending = evaluated(&leg, &laws, &mem, &bp, &(e * 0.5), &CANTILEVER).unwrap();
        assert!(compressing.primary_rate > 0.0 && compressing.fbr > 0.0);
        assert!(extending.fbr < 0.0);
        assert!((compressing.fbr + extending.fbr).abs() < 1e-9);
    }

    /// A tripod gear's footpad force balances the trunnion loads by statics: the primary and
    /// both secondaries are two-force members meeting at the footpad, so FP is the sum of
    /// their axial forces and the body's three trunnion forces balance −FP in force and moment.
    #[test]
    fn tripod_footpad_force_balances_its_three_struts() {
        let l = leg();
        let tripod = Leg::from_points(l.b2, l.b3, l.b4, l.bp, (l.bp - l.b2).norm());
        let laws = laws(0.3); // bearing friction must play no part
        let bp = deformed(tripod.bp);
        let options = GearOptions {
            arrangement: Arrangement::Tripod,
            bending: None,
        };
        let g = evaluated(
            &tripod,
            &laws,
            &GearMemory::default(),
            &bp,
            &Vector3::zeros(),
            &options,
        )
        .unwrap();
        assert_eq!((g.fbr, g.fm), (0.0, 0.0));
        assert!(g.fcp > 0.0 && g.fc_secondary.iter().all(|f| f.abs() > 0.0));
        let e = (bp - tripod.b2).normalize();
        let u3 = (bp - tripod.b3).normalize();
        let u4 = (bp - tripod.b4).normalize();
        let f = g.f_secondary();
        // Each strut pushes (compression) or pulls (tension) the footpad along its axis.
        let on_pad = e * g.f2p - u3 * f[0] - u4 * f[1];
        assert!((on_pad - g.fp).norm() < 1e-9 * g.fp.norm());
        // The body feels each strut's reaction at its trunnion.
        let on_body = [
            (tripod.b2, -e * g.f2p),
            (tripod.b3, u3 * f[0]),
            (tripod.b4, u4 * f[1]),
        ];
        assert_body_balances(&on_body, &bp, &g.fp);
    }

    /// Bending: the point-1 deflection is the beam-column's under FN and F2P, perpendicular to
    /// the strut; a stiff strut tends to the rigid gear, and the lagged deflection eases a
    /// secondary in tension (a softer spring in series).
    #[test]
    fn bending_deflects_point_one_along_the_normal_load_and_softens_the_secondaries() {
        let leg = leg();
        let laws = laws(0.0);
        let mem = GearMemory::default();
        let bp = deformed(leg.bp);
        let rigid = evaluated(&leg, &laws, &mem, &bp, &Vector3::zeros(), &CANTILEVER).unwrap();
        let beam = Bending::new(2.0e4).unwrap();
        let bent = |lag: Vector3<f64>| {
            let options = GearOptions {
                arrangement: Arrangement::Cantilever,
                bending: Some((&beam, lag)),
            };
            evaluated(&leg, &laws, &mem, &bp, &Vector3::zeros(), &options).unwrap()
        };
        let first = bent(Vector3::zeros());
        assert_eq!(
            first.fc_secondary, rigid.fc_secondary,
            "no lag yet: same forces"
        );
        let e = (bp - leg.b2).normalize();
        let d = first.point1_deflection;
        assert!(d.norm() > 0.0 && d.dot(&e).abs() < 1e-12 * d.norm());
        let len = (bp - leg.b2).norm();
        let fn_mag = touchdown_laws::normal_load(
            rigid.fc_secondary,
            (leg.b2 + e * leg.l21 - leg.b3).normalize(),
            (leg.b2 + e * leg.l21 - leg.b4).normalize(),
            e,
        )
        .norm();
        let expected = touchdown_laws::beam::deflection(fn_mag, rigid.f2p, leg.l21, len, 2.0e4)
            .unwrap()
            .magnitude;
        assert!((d.norm() - expected).abs() < 1e-12 * expected);
        // The next step sees it: the secondaries' normal load on the primary eases (a softer
        // spring in series), by less than it was.
        let second = bent(d);
        let u = [
            (leg.b2 + e * leg.l21 - leg.b3).normalize(),
            (leg.b2 + e * leg.l21 - leg.b4).normalize(),
        ];
        let fn2 = touchdown_laws::normal_load(second.fc_secondary, u[0], u[1], e).norm();
        assert!(fn2 < fn_mag && fn2 > 0.0, "{fn2} vs {fn_mag}");
        // A very stiff strut: the deflection vanishes.
        let stiff = Bending::new(1.0e12).unwrap();
        let options = GearOptions {
            arrangement: Arrangement::Cantilever,
            bending: Some((&stiff, Vector3::zeros())),
        };
        let g = evaluated(&leg, &laws, &mem, &bp, &Vector3::zeros(), &options).unwrap();
        assert!(g.point1_deflection.norm() < 1e-9);
    }

    /// A leaving gear relaxes to strokes at which every strut carries no force, and the
    /// footpad goes where the relaxed struts meet: the geometry gives back those strokes.
    #[test]
    fn a_released_gear_relaxes_to_zero_force_strokes() {
        let laws = laws(0.0);
        let cantilever = leg();
        let l = cantilever;
        let tripod = Leg::from_points(l.b2, l.b3, l.b4, l.bp, (l.bp - l.b2).norm());
        for (leg, arrangement) in [
            (cantilever, Arrangement::Cantilever),
            (tripod, Arrangement::Tripod),
        ] {
            let options = GearOptions {
                arrangement,
                bending: None,
            };
            let bp = deformed(leg.bp);
            let fresh = GearMemory::default();
            let g = evaluated(&leg, &laws, &fresh, &bp, &Vector3::zeros(), &options).unwrap();
            let mut memory = fresh;
            laws.commit(g.primary_stroke, g.secondary_stroke, &mut memory);
            assert!(laws.stored_energy(g.primary_stroke, g.secondary_stroke, &memory) > 0.0);
            let r = relax(
                &leg,
                &laws,
                &memory,
                arrangement,
                &bp,
                g.primary_stroke,
                g.secondary_stroke,
            )
            .unwrap();
            let again =
                evaluated(&leg, &laws, &memory, &r.bp, &Vector3::zeros(), &options).unwrap();
            assert!((again.primary_stroke - r.primary_stroke).abs() < 1e-12);
            for j in 0..2 {
                assert!((again.secondary_stroke[j] - r.secondary_stroke[j]).abs() < 1e-12);
            }
            assert!(again.fp.norm() < 1e-6, "{arrangement:?}: {}", again.fp);
            let stored = laws.stored_energy(r.primary_stroke, r.secondary_stroke, &memory);
            assert!(stored < 1e-20, "{arrangement:?}: {stored} J left");
        }
    }
}
