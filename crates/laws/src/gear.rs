//! The strut laws of one landing-gear assembly, built from a resolved scenario. Every engine
//! builds its laws here, so the mapping from scenario to law exists once.

use crate::{
    Bearing, Branch, CrushMemory, DoubleActingHoneycomb, DoubleActingMemory, Honeycomb, LawError,
    LoadStroke, Stage, StrutReach, Viscous,
};
use nalgebra::Vector3;
use touchdown_scenario::{model, Scenario, ScenarioError};

/// Primary-strut laws: compression honeycomb (trunnion-modified if a K_TP is given), viscous
/// force and bearing friction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrimaryStrutLaw {
    /// Compression honeycomb FCP(c).
    pub honeycomb: Honeycomb,
    /// FVP of eq. (49), compression positive.
    pub viscous: Viscous,
    /// Bearing friction of eqs. (59)-(63).
    pub bearing: Bearing,
}

impl PrimaryStrutLaw {
    /// Stroke-dependent force FCP(c), N (compression positive), at compression stroke `c`, m:
    /// the honeycomb for c ≥ 0; for c < 0 the strut is past its full extension and its
    /// extension stop pulls back (a tension force), the same [`Stop`](crate::Stop) law as the bottoming stop
    /// (its rate and restitution) with its own memory. The report gives the primary no tension
    /// capacity beyond friction; a real telescoping strut has a stop at full extension
    /// (docs/errata.md, "End stops").
    #[inline]
    pub fn stroke_force(&self, c: f64, memory: PrimaryMemory) -> f64 {
        if c >= 0.0 {
            self.honeycomb.force(c, memory.compression)
        } else {
            -self.honeycomb.stop.force(-c, memory.extension_depth)
        }
    }

    /// The force of the end stop the compression stroke `c` (m) is on, N (compression
    /// positive): the bottoming stop beyond the last crush load, or the extension stop pulling
    /// (negative); zero between them.
    #[inline]
    pub fn stop_force(&self, c: f64, memory: PrimaryMemory) -> f64 {
        if c >= 0.0 {
            self.honeycomb.stop_force(c, memory.compression)
        } else {
            self.stroke_force(c, memory)
        }
    }

    /// The branch compression stroke `c` (m) lies on and its rate, N/m: the extension stop
    /// below 0 (loading or unloading), the honeycomb's above.
    pub fn branch(&self, c: f64, memory: PrimaryMemory) -> (Branch, f64) {
        if c < 0.0 {
            let stop = &self.honeycomb.stop;
            let rate = if -c >= memory.extension_depth {
                stop.rate
            } else {
                stop.unloading_rate()
            };
            (Branch::ExtensionStop, rate)
        } else {
            self.honeycomb.branch(c, memory.compression)
        }
    }

    /// Elastic energy at compression stroke `c`, J: the honeycomb's recoverable energy, or
    /// what the extension stop would return.
    #[inline]
    pub fn stored_energy(&self, c: f64, memory: PrimaryMemory) -> f64 {
        self.stored_energy_at(c, self.stroke_force(c, memory), memory)
    }

    /// [`PrimaryStrutLaw::stored_energy`] at compression stroke `c` (m) where the law gives
    /// the force `f` ([`PrimaryStrutLaw::stroke_force`], N, compression positive) with the
    /// committed `memory`.
    #[inline]
    pub fn stored_energy_at(&self, c: f64, f: f64, memory: PrimaryMemory) -> f64 {
        if c >= 0.0 {
            self.honeycomb.stored_energy_at(c, f, memory.compression)
        } else {
            self.honeycomb.stop.returned_energy(-c, -f)
        }
    }

    /// The minorant of the energy it takes to reach a stroke from the committed `memory`
    /// (its compression honeycomb above, its extension stop below; docs/errata.md, "Settled
    /// landings: an early end with a proof"), `None` while its bottoming stop is engaged.
    pub fn reach(&self, memory: PrimaryMemory, tolerance: f64) -> Option<StrutReach> {
        StrutReach::crushing_with_extension_stop(
            &self.honeycomb,
            memory.compression,
            memory.extension_depth,
            tolerance,
        )
    }

    /// Commits an accepted compression stroke `c` (m): the honeycomb's memory (its x_max only
    /// grows in compression; its stop's engagement ends below the capacity), and the extension
    /// stop's engagement ([`Stop::commit`](crate::Stop::commit)).
    #[inline]
    pub fn commit(&self, c: f64, memory: &mut PrimaryMemory) {
        self.honeycomb.commit(c, &mut memory.compression);
        crate::Stop::commit(-c, &mut memory.extension_depth);
    }
}

/// Committed memory of a primary strut: the honeycomb's and the depth of the extension stop's
/// current engagement.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PrimaryMemory {
    /// Honeycomb memory (largest compression stroke, its bottoming stop's engagement).
    pub compression: CrushMemory,
    /// The extension stop's deepest extension past the undeformed length in its current
    /// engagement, m (zero while it is open).
    pub extension_depth: f64,
}

/// Secondary-strut laws: double-acting honeycomb and viscous force, tension positive.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SecondaryStrutLaw {
    /// FC31(S31), tension positive.
    pub honeycomb: DoubleActingHoneycomb,
    /// FV31 of eq. (49), tension positive.
    pub viscous: Viscous,
}

/// Both secondaries' forces at one state, tension positive.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SecondaryForces {
    /// FC31, FC41, honeycomb forces, N (eq. 49).
    pub honeycomb: [f64; 2],
    /// FV31, FV41, viscous forces, N (eq. 49).
    pub viscous: [f64; 2],
    /// FS = F31·V̂31 + F41·V̂41, the force of the primary on the secondaries at their
    /// attachment, N (eqs. 51-52).
    pub fs: Vector3<f64>,
}

impl SecondaryStrutLaw {
    /// The forces of both secondaries at strokes `s` (m), stroking rates `s_dot` (m/s), unit
    /// directions `u` (trunnion → attachment) and committed memories `memory`.
    #[inline(always)]
    pub fn forces(
        &self,
        s: [f64; 2],
        s_dot: [f64; 2],
        u: &[Vector3<f64>; 2],
        memory: &[DoubleActingMemory; 2],
    ) -> SecondaryForces {
        let fc = [
            self.honeycomb.force(s[0], memory[0]),
            self.honeycomb.force(s[1], memory[1]),
        ]; // eq. (49)
        let fv = [self.viscous.force(s_dot[0]), self.viscous.force(s_dot[1])]; // eq. (49)
        SecondaryForces {
            honeycomb: fc,
            viscous: fv,
            fs: u[0] * (fc[0] + fv[0]) + u[1] * (fc[1] + fv[1]), // eqs. (51)-(52)
        }
    }
}

/// Committed hysteresis of one gear: primary compression and both secondaries.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GearMemory {
    /// Primary-strut memory.
    pub primary: PrimaryMemory,
    /// Secondary struts 3-1 and 4-1.
    pub secondary: [DoubleActingMemory; 2],
}

/// Laws of one gear assembly (identical for every leg).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GearLaws {
    /// Primary strut.
    pub primary: PrimaryStrutLaw,
    /// Both secondary struts.
    pub secondary: SecondaryStrutLaw,
}

pub(crate) fn honeycomb(
    s: &Scenario,
    field: &str,
    ls: &model::LoadStroke,
    trunnion: Option<f64>,
) -> Result<Honeycomb, ScenarioError> {
    let err = |e: LawError| ScenarioError::field(&s.source, field, e.to_string());
    let mut stages = [Stage {
        crush_load: 0.0,
        stroke_end: 0.0,
    }; crate::honeycomb::MAX_STAGES];
    for (slot, (load, end)) in stages.iter_mut().zip(&ls.stages) {
        *slot = Stage {
            crush_load: *load,
            stroke_end: *end,
        };
    }
    let curve = LoadStroke::new(
        ls.onset_rate,
        &stages[..ls.stages.len()],
        ls.stroke_out_rate,
    )
    .map_err(err)?;
    let h = Honeycomb::new(curve, ls.backoff_rate, ls.stop_restitution).map_err(err)?;
    match trunnion {
        Some(k) => h.with_trunnion(k).map_err(err),
        None => Ok(h),
    }
}

fn viscous(v: &model::Viscous) -> Viscous {
    Viscous {
        coefficient: v.coefficient,
        exponent: v.exponent,
    }
}

/// One strut's load at a state, for a divergence diagnostic: the stiffest law engaged is the
/// one a step too large mistreats first.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StrutLoad {
    /// Leg, from 0.
    pub leg: usize,
    /// Which strut of the leg.
    pub strut: &'static str,
    /// Axial force, N (primary: compression positive; secondaries: tension positive).
    pub force: f64,
    /// Stroke, m (same signs).
    pub stroke: f64,
    /// The branch of its honeycomb law at that stroke.
    pub branch: Branch,
    /// The branch's rate (the law's local stiffness), N/m.
    pub rate: f64,
}

impl StrutLoad {
    /// The stiffest law engaged (a non-zero force) among `loads`, the larger force between
    /// equal rates, as a diagnostic's text.
    pub fn stiffest(loads: impl IntoIterator<Item = StrutLoad>) -> String {
        let stiffest = loads
            .into_iter()
            .filter(|l| l.force.is_finite() && l.force != 0.0)
            .max_by(|a, b| {
                (a.rate.total_cmp(&b.rate)).then(a.force.abs().total_cmp(&b.force.abs()))
            });
        match stiffest {
            Some(l) => format!("the stiffest strut law engaged now: {l}"),
            None => "no strut law engaged".into(),
        }
    }
}

impl std::fmt::Display for StrutLoad {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "leg {} {} on {} ({:.4e} N/m), {:.4e} N at stroke {:.4e} m",
            self.leg + 1,
            self.strut,
            self.branch,
            self.rate,
            self.force,
            self.stroke
        )
    }
}

impl GearLaws {
    /// Each honeycomb's capacity and its stop's loading rate, (m, N/m): the primary in
    /// compression, the secondaries in compression, the secondaries in tension (behind a
    /// trunnion spring, those of the modified diagram, in the stroke the engines report).
    pub fn capacities(&self) -> [(f64, f64); 3] {
        [
            &self.primary.honeycomb,
            &self.secondary.honeycomb.compression,
            &self.secondary.honeycomb.tension,
        ]
        .map(|h| (h.curve.capacity(), h.stop.rate))
    }

    /// The minorants of a leg's three struts (primary, secondaries 3-1 and 4-1) at the
    /// committed `memory`, the maxima's tolerance `tolerance` (m); `None` while a stop is
    /// engaged ([`StrutReach`]).
    pub fn reach(&self, memory: &GearMemory, tolerance: f64) -> Option<[StrutReach; 3]> {
        let h = &self.secondary.honeycomb;
        Some([
            self.primary.reach(memory.primary, tolerance)?,
            StrutReach::secondary(h, memory.secondary[0], tolerance)?,
            StrutReach::secondary(h, memory.secondary[1], tolerance)?,
        ])
    }

    /// Commits an accepted state into the memory (honeycomb x_max per side): primary
    /// compression stroke `c` and secondary strokes `s` (tension positive), m.
    #[inline]
    pub fn commit(&self, c: f64, s: [f64; 2], memory: &mut GearMemory) {
        self.primary.commit(c, &mut memory.primary);
        for (s, m) in s.into_iter().zip(&mut memory.secondary) {
            self.secondary.honeycomb.commit(s, m);
        }
    }

    /// The forces of the end stops the primary compression stroke `c` and the secondary strokes
    /// `s` (m, tension positive) are on, N: the primary's (compression positive, the extension
    /// stop negative) and the secondaries' (tension positive), zero for a strut within its
    /// stroke range.
    #[inline]
    pub fn stop_forces(&self, c: f64, s: [f64; 2], memory: &GearMemory) -> [f64; 3] {
        let sec = |j: usize| {
            self.secondary
                .honeycomb
                .stop_force(s[j], memory.secondary[j])
        };
        [self.primary.stop_force(c, memory.primary), sec(0), sec(1)]
    }

    /// The three struts of leg `leg` (from 0) at primary compression stroke `c` and secondary
    /// strokes `s` (m, tension positive) with their axial forces `primary` (N, compression
    /// positive) and `secondary` (N, tension positive): for a diagnostic.
    pub fn strut_loads(
        &self,
        leg: usize,
        memory: &GearMemory,
        (c, primary): (f64, f64),
        (s, secondary): ([f64; 2], [f64; 2]),
    ) -> [StrutLoad; 3] {
        let side = |j: usize, strut| {
            let (branch, rate) = self.secondary.honeycomb.branch(s[j], memory.secondary[j]);
            StrutLoad {
                leg,
                strut,
                force: secondary[j],
                stroke: s[j],
                branch,
                rate,
            }
        };
        let (branch, rate) = self.primary.branch(c, memory.primary);
        [
            StrutLoad {
                leg,
                strut: "primary strut",
                force: primary,
                stroke: c,
                branch,
                rate,
            },
            side(0, "secondary strut 3-1"),
            side(1, "secondary strut 4-1"),
        ]
    }

    /// Elastic energy stored in the gear's honeycombs and stops (recoverable), J, at primary
    /// compression stroke `c` and secondary strokes `s`, m.
    pub fn stored_energy(&self, c: f64, s: [f64; 2], memory: &GearMemory) -> f64 {
        let h = &self.secondary.honeycomb;
        let fc = [0, 1].map(|j| h.force(s[j], memory.secondary[j]));
        self.stored_energy_at(
            c,
            s,
            self.primary.stroke_force(c, memory.primary),
            fc,
            memory,
        )
    }

    /// [`GearLaws::stored_energy`] where the laws give the primary's honeycomb force `fcp`
    /// ([`PrimaryStrutLaw::stroke_force`], N) and the secondaries' `fc` (N, tension positive):
    /// the gear state of an evaluation at these strokes holds them, and committing the strokes
    /// it evaluated does not change them (a stroke at or past x_max lies on the virgin curve
    /// before and after, and a stop's engagement ends only where it carries nothing), with
    /// the committed `memory`.
    #[inline]
    pub fn stored_energy_at(
        &self,
        c: f64,
        s: [f64; 2],
        fcp: f64,
        fc: [f64; 2],
        memory: &GearMemory,
    ) -> f64 {
        let h = &self.secondary.honeycomb;
        let secondary = h.stored_energy_at(s[0], fc[0], memory.secondary[0])
            + h.stored_energy_at(s[1], fc[1], memory.secondary[1]);
        self.primary.stored_energy_at(c, fcp, memory.primary) + secondary
    }

    /// Builds and checks the laws of a scenario's gear. Stage tables out of order, and a bearing
    /// that would leave its domain (D2 ≥ D1) within the primary stroke capacity, are reported
    /// against the scenario field.
    pub fn from_scenario(s: &Scenario) -> Result<GearLaws, ScenarioError> {
        let p = &s.primary;
        let primary = PrimaryStrutLaw {
            honeycomb: honeycomb(
                s,
                "primary_strut.compression",
                &p.compression,
                p.trunnion_rate,
            )?,
            viscous: viscous(&p.viscous),
            bearing: Bearing {
                friction_coefficient: p.bearing_friction,
                inner_cylinder_length: p.inner_cylinder_length,
                initial_overlap: p.initial_overlap,
            },
        };
        let capacity = primary.honeycomb.curve.capacity();
        if primary.bearing.separation(capacity) >= primary.bearing.inner_cylinder_length {
            let field = "primary_strut.bearing.inner_cylinder_length";
            return Err(ScenarioError::field(
                s.file_of(field),
                field,
                format!(
                    "expected D1 longer than the initial overlap plus the stroke capacity ({:.6} m + {:.6} m), so that the bearings stay apart over the whole stroke",
                    p.initial_overlap, capacity
                ),
            ));
        }
        let q = &s.secondary;
        let secondary = SecondaryStrutLaw {
            honeycomb: DoubleActingHoneycomb {
                tension: honeycomb(s, "secondary_strut.tension", &q.tension, q.trunnion_rate)?,
                compression: honeycomb(
                    s,
                    "secondary_strut.compression",
                    &q.compression,
                    q.trunnion_rate,
                )?,
            },
            viscous: viscous(&q.viscous),
        };
        Ok(GearLaws { primary, secondary })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Stroke-out rate of [`strut`], N/m (the extension stop's rate too).
    const K_SO: f64 = 1e7;

    /// A primary strut: onset 1e5 N/m, 1,000 N to 0.1 m, stops at [`K_SO`] with restitution
    /// `e`; no viscous force, no bearing friction.
    fn strut(e: f64) -> PrimaryStrutLaw {
        let stages = [Stage {
            crush_load: 1000.0,
            stroke_end: 0.1,
        }];
        PrimaryStrutLaw {
            honeycomb: Honeycomb::new(LoadStroke::new(1e5, &stages, K_SO).unwrap(), 1e6, e)
                .unwrap(),
            viscous: Viscous::NONE,
            bearing: Bearing {
                friction_coefficient: 0.0,
                inner_cylinder_length: 0.3,
                initial_overlap: 0.1,
            },
        }
    }

    /// The extension stop's mapping by hand: past full extension (c < 0) the primary pulls
    /// back with K_so·(−c) on first loading, a tension (negative in the compression-positive
    /// convention), on the loading line below its deepest point and on the unloading curve
    /// K_so·d_max·(d/d_max)^n above it; its memory is its own (a bottomed honeycomb keeps its
    /// x_max through an extension, its bottoming ended as at any stroke below its capacity, and
    /// the extension stop's engagement ends above full extension); it stores what it would
    /// return, e²·F·d/2.
    #[test]
    fn the_extension_stop_pulls_back_with_its_own_memory() {
        let e = 0.5;
        let law = strut(e);
        let n = 2.0 / (e * e) - 1.0;
        let fresh = PrimaryMemory::default();
        let d = 2e-3;
        assert_eq!(law.stroke_force(-d, fresh), -K_SO * d);
        assert_eq!(law.stop_force(-d, fresh), -K_SO * d);
        assert_eq!(law.branch(-d, fresh), (Branch::ExtensionStop, K_SO));
        let stored = law.stored_energy(-d, fresh);
        assert!((stored - e * e * K_SO * d * d / 2.0).abs() <= 1e-12 * stored);
        // Between full extension and the honeycomb's onset nothing acts.
        assert_eq!(law.stroke_force(0.0, fresh), 0.0);

        // Bottomed first: 5 mm past the capacity, committed, then out to −d.
        let mut memory = fresh;
        law.commit(0.105, &mut memory);
        let bottomed = memory.compression;
        assert!(law.stop_force(0.105, memory) > 0.0);
        law.commit(-d, &mut memory);
        let mut unbottomed = bottomed;
        law.honeycomb.commit(0.05, &mut unbottomed);
        assert_eq!(unbottomed.max_stroke(), 0.105);
        assert_eq!(
            memory.compression, unbottomed,
            "the honeycomb's memory is its own"
        );
        assert_eq!(memory.extension_depth, d);
        assert_eq!(
            law.stroke_force(-d, memory),
            -K_SO * d,
            "the stop is its own"
        );
        // Coming back: the unloading curve, its own rate.
        let half = law.stroke_force(-d / 2.0, memory);
        assert!((half + K_SO * d * 0.5f64.powf(n)).abs() <= 1e-12 * K_SO * d);
        assert_eq!(
            law.branch(-d / 2.0, memory),
            (Branch::ExtensionStop, law.honeycomb.stop.unloading_rate())
        );
        // Back above full extension the engagement ends and the honeycomb is as it was.
        law.commit(0.01, &mut memory);
        assert_eq!(memory.extension_depth, 0.0);
        assert_eq!(memory.compression, unbottomed);
        assert_eq!(
            law.stroke_force(-d, memory),
            -K_SO * d,
            "a new engagement loads afresh"
        );
    }

    /// A footpad mass m pulling the strut past full extension at speed v, m·c̈ = −F(c) with
    /// each accepted stroke committed (velocity Verlet, as an engine steps): the closed forms
    /// of a linear stop. It goes v·√(m/K_so) deep, stores e² of its kinetic energy there,
    /// and leaves full extension at e·v, compressing (a plastic stop keeps it where it
    /// stopped).
    #[test]
    fn a_footpad_pulling_past_full_extension_leaves_at_e_times_its_speed() {
        let (m, v) = (5.0, 2.0);
        let depth = v * (m / K_SO).sqrt();
        for e in [0.0, 0.3, 0.5, 0.8, 1.0] {
            let law = strut(e);
            let dt = 1e-3 * (m / law.honeycomb.stop.stiffest_rate()).sqrt();
            let mut memory = PrimaryMemory::default();
            let (mut c, mut rate) = (0.0, -v);
            let mut deepest_energy = 0.0;
            for _ in 0..10_000_000 {
                let a0 = -law.stroke_force(c, memory) / m;
                c += rate * dt + 0.5 * a0 * dt * dt;
                let a1 = -law.stroke_force(c, memory) / m;
                let was = rate;
                rate += 0.5 * (a0 + a1) * dt;
                law.commit(c, &mut memory);
                if was < 0.0 && rate >= 0.0 {
                    deepest_energy = law.stored_energy(c, memory);
                    if e == 0.0 {
                        break;
                    }
                }
                if c >= 0.0 {
                    break;
                }
            }
            let kinetic = 0.5 * m * v * v;
            assert!(
                (deepest_energy - e * e * kinetic).abs() <= 2e-3 * kinetic,
                "e = {e}: stored {deepest_energy} J at the deepest point, e²·{kinetic} J expected"
            );
            if e == 0.0 {
                assert!((-c - depth).abs() < 1e-3 * depth, "e = 0: held at {c} m");
                assert!(rate.abs() < 1e-3 * v, "a plastic stop keeps it: {rate} m/s");
            } else {
                assert!((memory.extension_depth, c >= 0.0) == (0.0, true));
                assert!(
                    (rate - e * v).abs() < 2e-3 * e * v,
                    "e = {e}: left at {rate} m/s, {} expected",
                    e * v
                );
            }
        }
    }

    #[test]
    fn the_stiffest_law_engaged_is_named_with_its_branch() {
        let load = |leg, force, branch, rate| StrutLoad {
            leg,
            strut: "primary strut",
            force,
            stroke: -0.001,
            branch,
            rate,
        };
        let text = StrutLoad::stiffest([
            load(0, 9e5, Branch::Plateau, 0.0),
            load(1, -1.0e3, Branch::ExtensionStop, 1e7),
            load(2, -1.2e5, Branch::ExtensionStop, 1e7),
            load(3, 0.0, Branch::Onset, 1e9),
            load(3, f64::NAN, Branch::Onset, 1e9),
        ]);
        assert_eq!(
            text,
            "the stiffest strut law engaged now: leg 3 primary strut on its extension stop (1.0000e7 N/m), -1.2000e5 N at stroke -1.0000e-3 m"
        );
        assert_eq!(StrutLoad::stiffest([]), "no strut law engaged");
    }
}
