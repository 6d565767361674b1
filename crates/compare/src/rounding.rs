//! Rounding-decided channels (docs/engines.md, "Rounding-decided channels"): each engine lands
//! a scenario once as given and once for each of [`CROSSWISE_ULPS`], the touchdown velocity's
//! X_G component moved by that many units in the last place of the touchdown speed, a change
//! of the order of the rounding of any input. A landing that decides a maximum through an
//! unstable symmetric state (a rocking stance, two struts on one plateau) amplifies such a
//! change to a spread of its own; a verdict that a change of this size can flip is reported as
//! not determined at this precision ([`Verdict::NotDetermined`]) with that spread, not as a
//! pass or a fail.

use crate::metrics::{channels, stroke_channels, Channel, Sense, Strut, Verdict, ENERGY};
use crate::{CompareError, Engine, EngineRun};
use serde::Serialize;
use std::path::Path;
use touchdown_record::Summary;
use touchdown_scenario::{Scenario, ScenarioError};

/// The perturbed members of a landing's ensemble, in units in the last place of the touchdown
/// speed added to the touchdown velocity's X_G component: one each way, so that a landing
/// symmetric about the Y_G-Z_G plane gets both mirror images.
pub const CROSSWISE_ULPS: [f64; 2] = [1.0, -1.0];

/// One unit in the last place of `x` (the spacing of doubles at |x|); of 1 at `x` = 0.
pub fn ulp(x: f64) -> f64 {
    let x = if x == 0.0 { 1.0 } else { x.abs() };
    f64::from_bits(x.to_bits() + 1) - x
}

/// The scenario `sc` with its touchdown velocity's X_G component moved by `ulps` units in the
/// last place of the touchdown speed (file units, as the file gives the velocity).
pub fn crosswise(sc: &Scenario, ulps: f64) -> Result<Scenario, ScenarioError> {
    let td = &sc.file.touchdown;
    let [vx, vy] = td.horizontal_velocity;
    let speed = (vx * vx + vy * vy + td.vertical_velocity * td.vertical_velocity).sqrt();
    let step = ulps * ulp(speed);
    sc.clone()
        .with_touchdown(|t| t.horizontal_velocity[0] += step)
}

/// The ensemble's perturbed scenarios of `sc`, one per [`CROSSWISE_ULPS`].
pub fn perturbed(sc: &Scenario) -> Result<Vec<Scenario>, ScenarioError> {
    CROSSWISE_ULPS.iter().map(|u| crosswise(sc, *u)).collect()
}

/// How far one engine's own rounding ensemble (the landing and its perturbed copies) lands
/// apart on one channel: its rounding spread.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OwnSpread {
    /// The channel as the text reports name it ("secondary stroke leg 2 3-1").
    pub channel: String,
    /// The quantity: the `quantity` of its tolerance.
    pub quantity: &'static str,
    /// The leg, numbered from 1 (stroke channels).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub leg: Option<usize>,
    /// The strut (stroke channels).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub strut: Option<Strut>,
    /// The energy account (energy channels; never among the maxima [`undetermined`] lists).
    #[serde(skip)]
    pub account: Option<&'static str>,
    /// The sense of a pitch-rate extreme (the peak pitch rate channels).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sense: Option<Sense>,
    /// The SI unit of `range`.
    pub unit: &'static str,
    /// Smallest and largest value over the ensemble, in `unit` (`None` for a history channel,
    /// which has no single value).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub range: Option<[f64; 2]>,
    /// Largest difference between two members, as the tolerance measures it, in
    /// `difference_unit`.
    pub spread: f64,
    /// What `spread` and `tolerance` are ratios to: `fraction` (the channel's own value) or
    /// one of the vehicle's scales (`footprint_radius`, `time_scale`, `velocity_scale`).
    pub difference_unit: &'static str,
    /// The tolerance, in `difference_unit`.
    pub tolerance: f64,
    /// Whether every pair of members has the channel (one that only some outcomes have, such
    /// as the overturn velocity, exists by rounding).
    #[serde(skip)]
    pub everywhere: bool,
}

impl OwnSpread {
    /// The spread of a channel of the landing compared with itself: nothing yet.
    fn of(c: &Channel) -> OwnSpread {
        OwnSpread {
            channel: c.name(),
            quantity: c.quantity,
            leg: c.leg,
            strut: c.strut,
            account: c.account,
            sense: c.sense,
            unit: c.unit,
            range: c.a.map(|a| [a; 2]),
            spread: 0.0,
            difference_unit: c.difference_unit,
            tolerance: c.tolerance,
            everywhere: true,
        }
    }

    /// Whether `c` is about the same thing.
    pub(crate) fn is_of(&self, c: &Channel) -> bool {
        c.key()
            == (
                self.quantity,
                self.leg,
                self.strut,
                self.account,
                self.sense,
            )
    }

    /// Widened by the same channel of two members (`None`: that pair has no such channel).
    fn widen(&mut self, c: Option<&Channel>) {
        let Some(c) = c else {
            self.everywhere = false;
            return;
        };
        self.spread = self.spread.max(c.difference);
        if let (Some(r), Some(a), Some(b)) = (self.range.as_mut(), c.a, c.b) {
            *r = [r[0].min(a).min(b), r[1].max(a).max(b)];
        }
    }
}

/// Every channel's rounding spread over the members of `run` ([`crate::run_ensemble`]), in
/// channel order. On a landing that is its own mirror image ([`crate::metrics::Basis::mirror`]) each
/// member also lands every leg's strokes a second time, on the leg's image: a stroke channel's
/// spread counts each member's leg against its image too. That probes what the copies do not
/// on an engine whose arithmetic is not mirror-symmetric (rapier's and MuJoCo's solvers: they
/// put an asymmetry of the order of rounding into every step, which outweighs the copies' one
/// unit in the last place; docs/engines.md, "Rounding-decided channels"); on the core, whose
/// mirror legs are equal bit for bit, it adds nothing.
pub(crate) fn own_spreads(run: &EngineRun) -> Vec<OwnSpread> {
    let members = run.members();
    let mut own: Vec<OwnSpread> = channels(run, run).iter().map(OwnSpread::of).collect();
    for (i, x) in members.iter().enumerate() {
        for y in &members[i + 1..] {
            let set = channels(x, y);
            for o in &mut own {
                o.widen(set.iter().find(|c| o.is_of(c)));
            }
        }
    }
    if let Some(legs) = &run.basis.mirror {
        for x in &members {
            let set = stroke_channels(&x.summary, &mirrored(&x.summary, legs), &run.basis);
            for o in own.iter_mut().filter(|o| o.leg.is_some()) {
                o.widen(set.iter().find(|c| o.is_of(c)));
            }
        }
    }
    own
}

/// The summary `s` seen in the mirror that maps its landing onto itself: leg i's maximum
/// strokes are those of its image `legs[i]`, with the image's secondaries 3-1 and 4-1
/// exchanged (the stroke channels are all [`own_spreads`] reads of it).
fn mirrored(s: &Summary, legs: &[usize]) -> Summary {
    let swap = |[a, b]: [f64; 2]| [b, a];
    Summary {
        max_primary_stroke_m: legs.iter().map(|&j| s.max_primary_stroke_m[j]).collect(),
        max_secondary_compression_m: (legs.iter())
            .map(|&j| swap(s.max_secondary_compression_m[j]))
            .collect(),
        max_secondary_tension_m: (legs.iter())
            .map(|&j| swap(s.max_secondary_tension_m[j]))
            .collect(),
        ..s.clone()
    }
}

/// The maxima of `run` ([`crate::run_ensemble`]: the landing and its perturbed copies on one
/// engine) that its members land further apart than their tolerance, in channel order. The
/// energy accounts are totals, not maxima, and the pitch-rate histories compare two engines:
/// neither is listed.
pub fn undetermined(run: &EngineRun) -> Vec<OwnSpread> {
    own_spreads(run)
        .into_iter()
        .filter(|o| o.range.is_some() && o.quantity != ENERGY.quantity && o.spread > o.tolerance)
        .collect()
}

/// What the rounding ensemble says of one engine's landing (`touchdown run --rounding`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Determinacy {
    /// The copies' perturbations, in units in the last place of the touchdown speed added to
    /// the touchdown velocity's X_G component ([`CROSSWISE_ULPS`]).
    pub crosswise_ulps: [f64; 2],
    /// Whether the landing and its copies have one outcome.
    pub outcome_determined: bool,
    /// The maxima not determined at this precision ([`undetermined`]).
    pub undetermined: Vec<OwnSpread>,
}

/// What the rounding ensemble says of `sc` landed on `engine` (`path` names it in errors): the
/// landing and its perturbed copies ([`crate::run_ensemble`]), judged on their own.
pub fn determinacy(
    engine: Engine,
    path: &Path,
    sc: &Scenario,
) -> Result<Determinacy, CompareError> {
    let run = crate::run_ensemble(engine, path, sc, None)?;
    Ok(Determinacy {
        crosswise_ulps: CROSSWISE_ULPS,
        outcome_determined: run.outcome_determined(),
        undetermined: undetermined(&run),
    })
}

/// A summary with what the rounding ensemble says of it: `rounding` of
/// docs/schemas/run.schema.json.
#[derive(Serialize)]
struct WithRounding<'a> {
    #[serde(flatten)]
    summary: &'a touchdown_record::Summary,
    rounding: &'a Determinacy,
}

/// The summary's document (`touchdown run --format json`, `summary.json`): with `rounding`,
/// its `rounding` field says what the ensemble found ([`determinacy`]).
pub fn run_document(
    summary: &touchdown_record::Summary,
    scenario: &touchdown_record::ScenarioId,
    settings: &serde_json::Value,
    rounding: Option<&Determinacy>,
) -> String {
    match rounding {
        Some(d) => touchdown_record::Document::new(
            "run",
            Some(scenario),
            settings,
            &WithRounding {
                summary,
                rounding: d,
            },
        )
        .pretty(),
        None => summary.document(scenario, settings),
    }
}

/// What the ensemble says of one channel of a pair: how far apart the engines' members land,
/// and how far apart each engine's own members land.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Spread {
    /// Smallest and largest difference between a member of the first engine and one of the
    /// second, as the tolerance measures it.
    pub between: [f64; 2],
    /// Largest difference between two members of the same engine, as the tolerance measures
    /// it: the first engine's, the second's.
    pub within: [f64; 2],
    /// Smallest and largest value of each engine over its members (`None` for a history
    /// channel, which has no single value).
    pub values: [Option<[f64; 2]>; 2],
    /// Whether every pair of members has the channel (a channel that only some outcomes have,
    /// such as the overturn velocity, exists by rounding).
    pub everywhere: bool,
}

impl Spread {
    /// The spread of channel `c` of the landings as given, with each engine's own spreads
    /// ([`own_spreads`]): nothing yet between the engines' other members.
    pub(crate) fn of(c: &Channel, own: [&[OwnSpread]; 2]) -> Spread {
        let mine = own.map(|o| o.iter().find(|s| s.is_of(c)));
        Spread {
            between: [c.difference; 2],
            within: mine.map(|m| m.map_or(0.0, |m| m.spread)),
            values: mine.map(|m| m.and_then(|m| m.range)),
            everywhere: mine.iter().all(|m| m.is_some_and(|m| m.everywhere)),
        }
    }

    /// Widened by the same channel of a pair of members of the two engines (`None`: that pair
    /// has no such channel).
    pub(crate) fn between(&mut self, c: Option<&Channel>) {
        match c {
            Some(c) => {
                self.between = [
                    self.between[0].min(c.difference),
                    self.between[1].max(c.difference),
                ]
            }
            None => self.everywhere = false,
        }
    }

    /// The verdict on a channel of tolerance `limit`: a pass or a fail if every pair of members
    /// gives it and neither engine's members are further apart than the tolerance (a value, or
    /// for a history channel the history, that rounding alone moves by more than the tolerance
    /// cannot be judged against it); not determined otherwise.
    pub(crate) fn verdict(&self, limit: f64) -> Verdict {
        let [low, high] = self.between;
        if !self.everywhere || self.within.iter().any(|w| *w > limit) {
            Verdict::NotDetermined
        } else if high <= limit {
            Verdict::Pass
        } else if low > limit {
            Verdict::Fail
        } else {
            Verdict::NotDetermined
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_unit_in_the_last_place() {
        assert_eq!(ulp(1.0), f64::EPSILON);
        assert_eq!(ulp(-1.0), f64::EPSILON);
        assert_eq!(ulp(0.0), f64::EPSILON);
        assert_eq!(ulp(4.0), 4.0 * f64::EPSILON);
        // the next double up is x + ulp, exactly
        let x = 12.25_f64;
        assert_eq!(x + ulp(x), f64::from_bits(x.to_bits() + 1));
    }

    #[test]
    fn a_copy_differs_from_its_landing_by_one_unit_in_the_last_place_on_every_engine() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../scenarios/table-i-1-2-1-vv5.toml");
        let sc = Scenario::load(&path).unwrap();
        let td = &sc.file.touchdown;
        let speed = (td.horizontal_velocity[1].powi(2) + td.vertical_velocity.powi(2)).sqrt();
        for u in CROSSWISE_ULPS {
            let copy = crosswise(&sc, u).unwrap();
            let vx = copy.file.touchdown.horizontal_velocity[0];
            assert_eq!(vx, u * ulp(speed));
            // the resolved velocity (core, rapier) carries it, in SI
            assert!(copy.touchdown.velocity_g.x * u > 0.0);
            assert_eq!(copy.touchdown.velocity_g.yz(), sc.touchdown.velocity_g.yz());
            // so does the resolved file the MuJoCo runner reads, to the bit
            let back = Scenario::from_toml("copy", &copy.to_toml()).unwrap();
            assert_eq!(back.file.touchdown.horizontal_velocity[0], vx);
            assert_ne!(copy.sha256(), sc.sha256());
        }
    }

    #[test]
    fn an_engine_that_lands_a_leg_and_its_mirror_image_apart_has_them_undetermined() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../scenarios/table-i-1-2-1-vv5.toml");
        let sc = Scenario::load(&path).unwrap();
        let run = crate::run_recorded(crate::Engine::Core, &path, &sc, None).unwrap();
        // The 1-2-1 landing is its own mirror image in the plane through legs 2 and 4.
        assert_eq!(run.basis.mirror, Some(vec![2, 1, 0, 3]));
        // The core lands each leg and its image bit for bit alike: the probe adds nothing.
        assert!(own_spreads(&run).iter().all(|o| o.spread == 0.0));
        // An engine that lands leg 1's primary a fifth beyond its image's (leg 3's), and leg
        // 2's 3-1 secondary (its own image's 4-1) a fifth short of its 4-1.
        let mut lopsided = run.clone();
        lopsided.summary.max_primary_stroke_m[0] *= 1.2;
        lopsided.summary.max_secondary_compression_m[1][0] *= 0.8;
        lopsided.summary.max_secondary_tension_m[1][0] *= 0.8;
        let named: Vec<_> = (undetermined(&lopsided).iter())
            .map(|o| (o.leg.unwrap(), o.strut.unwrap()))
            .collect();
        assert_eq!(
            named,
            [
                (1, Strut::Primary),
                (3, Strut::Primary),
                (2, Strut::Secondary31),
                (2, Strut::Secondary41)
            ]
        );
        // A landing that is not its own mirror image has no such probe.
        let sloped = sc
            .clone()
            .with_touchdown(|t| t.horizontal_velocity[0] = 1.0)
            .unwrap();
        assert_eq!(crate::metrics::Basis::of(&sloped).unwrap().mirror, None);
    }

    fn spread(between: [f64; 2], within: [f64; 2]) -> Spread {
        Spread {
            between,
            within,
            values: [Some([0.0; 2]); 2],
            everywhere: true,
        }
    }

    #[test]
    fn a_verdict_the_members_share_is_a_verdict() {
        assert_eq!(
            spread([0.01, 0.04], [0.0, 0.01]).verdict(0.05),
            Verdict::Pass
        );
        assert_eq!(
            spread([0.06, 0.09], [0.0, 0.01]).verdict(0.05),
            Verdict::Fail
        );
    }

    #[test]
    fn a_verdict_rounding_can_flip_is_not_determined() {
        // the members fall on both sides of the tolerance
        let s = spread([0.04, 0.06], [0.0, 0.0]);
        assert_eq!(s.verdict(0.05), Verdict::NotDetermined);
        // an engine's own members further apart than the tolerance
        let s = spread([0.5, 0.6], [0.07, 0.0]);
        assert_eq!(s.verdict(0.05), Verdict::NotDetermined);
        // a history channel too: rounding moves one engine's history by more than the tolerance
        let mut s = spread([0.5, 0.6], [0.07, 0.0]);
        s.values = [None; 2];
        assert_eq!(s.verdict(0.05), Verdict::NotDetermined);
        // a channel only some members have
        let mut s = spread([0.0, 0.0], [0.0, 0.0]);
        s.between(None);
        assert_eq!(s.verdict(0.05), Verdict::NotDetermined);
    }
}
