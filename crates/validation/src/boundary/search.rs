//! The search at each descent speed: the grid, the finer scan around each change of outcome,
//! the bisections of every transition and of the first speed past a capacity, and the safe
//! envelope; what it finds, in the scenario's velocity unit.

use super::settings::{refuse, Settings};
use super::speed::{negative_down, SiSpeed};
use crate::ValidationError;
use rayon::prelude::*;
use serde::Serialize;
use touchdown_core::Outcome;

/// Which way the outcome changes as Vh increases.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Direction {
    /// Stable below, unstable above (`"stable_to_unstable"`): the usual boundary.
    StableToUnstable,
    /// Unstable below, stable above (`"unstable_to_stable"`).
    UnstableToStable,
}

/// The end stops one landing engaged.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Stops {
    /// Struts that went past their capacity onto their end stops.
    pub struts_past_capacity: usize,
    /// The largest force among their stops beyond the last crush load, N (0 if none).
    pub peak_stop_force_n: f64,
}

impl Stops {
    /// The stops of a landing's summary.
    pub fn of(summary: &touchdown_record::Summary) -> Stops {
        Stops {
            struts_past_capacity: summary.past_capacity.len(),
            peak_stop_force_n: (summary.past_capacity.iter())
                .map(|p| p.peak_stop_force_n)
                .fold(0.0, f64::max),
        }
    }

    /// Whether a strut went past its capacity.
    pub fn engaged(&self) -> bool {
        self.struts_past_capacity > 0
    }
}

/// What the search needs of one landing: its outcome and the end stops it engaged.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Landed {
    /// The stability outcome.
    pub outcome: Outcome,
    /// The end stops engaged.
    pub stops: Stops,
}

impl Landed {
    /// The landing of a summary.
    pub fn of(summary: &touchdown_record::Summary) -> Landed {
        Landed {
            outcome: summary.outcome,
            stops: Stops::of(summary),
        }
    }

    /// Stable and within every strut's capacity.
    fn safe(&self) -> bool {
        self.outcome == Outcome::Stable && !self.stops.engaged()
    }
}

/// A landing that engaged no stop.
impl From<Outcome> for Landed {
    fn from(outcome: Outcome) -> Landed {
        Landed {
            outcome,
            stops: Stops::default(),
        }
    }
}

/// A transition's bracket ends landed again with every step limit of the core divided by
/// `refinement` (`Integrator::refine`; docs/validation.md, "Stability boundary"). Where both
/// ends keep their outcomes the finer steps change outcome within the same bracket too; where
/// one does not, the transition moves with the step by at least the bracket's width.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Refined {
    /// The divisor of every step limit.
    pub refinement: f64,
    /// The outcome at the bracket's stable end, refined.
    #[serde(rename = "stable_at_outcome")]
    pub stable_end: Outcome,
    /// The outcome at the bracket's unstable end, refined.
    #[serde(rename = "unstable_at_outcome")]
    pub unstable_end: Outcome,
    /// Both ends keep their outcomes.
    pub holds: bool,
}

impl Refined {
    /// The ends' outcomes `stable_end` and `unstable_end` with every step limit ÷ `refinement`.
    pub fn new(refinement: f64, stable_end: Outcome, unstable_end: Outcome) -> Refined {
        Refined {
            refinement,
            stable_end,
            unstable_end,
            holds: stable_end == Outcome::Stable && unstable_end == Outcome::Unstable,
        }
    }
}

/// One landing's outcome with every step limit refined, at a descent and a horizontal speed
/// (scenario velocity unit).
pub(super) type RefinedLand<'a> = &'a (dyn Fn(f64, f64) -> Result<Outcome, ValidationError> + Sync);

/// A [`RefinedLand`] and the divisor of the step limits it lands with.
pub(super) type RefinedLanding<'a> = (f64, RefinedLand<'a>);

/// One change of outcome between two neighbouring decided landings at one Vv, its speeds `V`
/// in the scenario's velocity unit as the search finds them (written in SI by
/// [`BoundaryPoint::in_si`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(bound(serialize = "V: SiSpeed"))]
pub struct Transition<V = f64> {
    /// Which way the outcome changes as Vh increases.
    pub direction: Direction,
    /// The bracket's end found stable, scenario velocity unit (the lower end for
    /// [`Direction::StableToUnstable`], the upper one otherwise).
    #[serde(rename = "stable_at_vh_m_s")]
    pub stable_at: V,
    /// The bracket's end found unstable, scenario velocity unit.
    #[serde(rename = "unstable_at_vh_m_s")]
    pub unstable_at: V,
    /// The transition's Vh, middle of the final bracket (no wider than the tolerance),
    /// scenario velocity unit; `None` if unresolved.
    #[serde(rename = "vh_m_s", skip_serializing_if = "Option::is_none")]
    pub vh: Option<V>,
    /// Whether the bracket was narrowed to the tolerance. False when undecided points lie
    /// between its ends (it was never bisected) or a bisection midpoint ended undecided (the
    /// bracket is the one at that moment).
    pub resolved: bool,
    /// The undecided landings inside the bracket, scenario velocity unit, ascending: the
    /// points between its ends, or the bisection midpoint that stopped it; empty if resolved.
    #[serde(rename = "undecided_at_vh_m_s")]
    pub undecided_at: Vec<V>,
    /// The end stops engaged by the landing at the stable end.
    pub stable_stops: Stops,
    /// The end stops engaged by the landing at the unstable end.
    pub unstable_stops: Stops,
    /// The bracket's ends landed again with every step limit refined (the core's searches;
    /// left out of a document otherwise).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub refined: Option<Refined>,
}

impl Transition {
    /// The bracket's lower end, scenario velocity unit.
    pub fn lower(&self) -> f64 {
        self.stable_at.min(self.unstable_at)
    }

    /// The bracket's upper end, scenario velocity unit.
    pub fn upper(&self) -> f64 {
        self.stable_at.max(self.unstable_at)
    }
}

/// Where the outcome alternates: from the lower end of the lowest transition's bracket to the
/// upper end of the highest one, when there are two or more transitions.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(bound(serialize = "V: SiSpeed"))]
pub struct Band<V = f64> {
    /// The band's lower end, scenario velocity unit.
    #[serde(rename = "from_vh_m_s")]
    pub from: V,
    /// The band's upper end, scenario velocity unit.
    #[serde(rename = "to_vh_m_s")]
    pub to: V,
    /// How many times the outcome changes within it (the number of transitions).
    pub changes: usize,
}

/// The first Vh at which a strut goes past its capacity.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(bound(serialize = "V: SiSpeed"))]
pub struct CapacityEdge<V = f64> {
    /// The bracket's end within every capacity, scenario velocity unit (`None` when the first
    /// landing searched already went past one).
    #[serde(rename = "within_at_vh_m_s", skip_serializing_if = "Option::is_none")]
    pub within_at: Option<V>,
    /// The bracket's end past a capacity, scenario velocity unit.
    #[serde(rename = "past_at_vh_m_s")]
    pub past_at: V,
    /// The middle of the final bracket (no wider than the tolerance), scenario velocity unit;
    /// `None` when the first landing searched went past.
    #[serde(rename = "vh_m_s", skip_serializing_if = "Option::is_none")]
    pub vh: Option<V>,
    /// The stops engaged at `past_at`.
    pub stops: Stops,
}

/// What ends the safe envelope (written as [`Limit::name`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Limit {
    /// The landing overturned.
    Overturn,
    /// The landing ended undecided.
    Undecided,
    /// A strut went past its capacity (the landing stable).
    Capacity,
    /// The landing overturned with a strut past its capacity.
    OverturnAndCapacity,
}

impl Limit {
    /// Its name in documents and tables: `overturn`, `undecided`, `capacity`,
    /// `overturn_and_capacity`.
    pub fn name(self) -> &'static str {
        match self {
            Limit::Overturn => "overturn",
            Limit::Undecided => "undecided",
            Limit::Capacity => "capacity",
            Limit::OverturnAndCapacity => "overturn_and_capacity",
        }
    }
}

impl Serialize for Limit {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

/// The safe envelope: every landing searched up to `safe_to` was stable and within every
/// strut's capacity.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(bound(serialize = "V: SiSpeed"))]
pub struct SafeEdge<V = f64> {
    /// The largest Vh below the first unsafe landing, scenario velocity unit (`None` when the
    /// first landing searched is unsafe).
    #[serde(rename = "safe_to_vh_m_s", skip_serializing_if = "Option::is_none")]
    pub safe_to: Option<V>,
    /// The first unsafe landing's Vh, scenario velocity unit (`None` when all were safe).
    #[serde(rename = "unsafe_at_vh_m_s", skip_serializing_if = "Option::is_none")]
    pub unsafe_at: Option<V>,
    /// Why that landing is unsafe (`None` when all were safe).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub limit: Option<Limit>,
}

/// The boundary at one vertical velocity, its speeds `V` in the scenario's velocity unit as
/// the search finds them; in SI ([`BoundaryPoint::in_si`]) it is the fields of a line of
/// `touchdown boundary --format json` after the engine (docs/schemas/boundary.schema.json),
/// each speed's name ending in `_m_s` and the vertical velocity signed as in the scenario
/// files (negative down).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(bound(serialize = "V: SiSpeed"))]
pub struct BoundaryPoint<V = f64> {
    /// Descent speed (positive down), scenario velocity unit; written as the vertical
    /// velocity, negative down (`touchdown.vertical_velocity`).
    #[serde(rename = "vv_m_s", serialize_with = "negative_down")]
    pub vv: V,
    /// The boundary: the Vh of the lowest stable → unstable transition, scenario velocity
    /// unit; `None` if there is none or it is unresolved.
    #[serde(rename = "vh_m_s", skip_serializing_if = "Option::is_none")]
    pub vh: Option<V>,
    /// The stable end of the lowest stable → unstable transition's bracket; without one, the
    /// largest Vh found stable if none was found unstable, else `None`. Scenario velocity
    /// unit.
    #[serde(rename = "stable_at_vh_m_s", skip_serializing_if = "Option::is_none")]
    pub stable_at: Option<V>,
    /// The unstable end of the lowest stable → unstable transition's bracket; without one, the
    /// smallest Vh found unstable (`None` if none). Scenario velocity unit.
    #[serde(rename = "unstable_at_vh_m_s", skip_serializing_if = "Option::is_none")]
    pub unstable_at: Option<V>,
    /// Every transition, in either direction, ascending in Vh.
    pub transitions: Vec<Transition<V>>,
    /// Where the outcome alternates, when there are two or more transitions.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub band: Option<Band<V>>,
    /// The first Vh past a strut's capacity (`None` if no landing went past one).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub capacity: Option<CapacityEdge<V>>,
    /// The safe envelope.
    pub safe: SafeEdge<V>,
    /// The Vh of every landing that ended undecided (grid, scan and bisection), scenario
    /// velocity unit, ascending.
    #[serde(rename = "undecided_at_vh_m_s")]
    pub undecided_at: Vec<V>,
    /// Landings run (grid, scan and bisection).
    pub landings: usize,
    /// Landings that ended undecided (the length of `undecided_at`).
    pub undecided: usize,
}

/// Searches the transitions at each vertical velocity `vvs` (scenario velocity unit, positive
/// down). `landing(vv, vh)` runs one landing to its outcome (a [`Landed`], or an [`Outcome`]
/// for a landing that engages no stop); `tick` is called after each landing (for a progress
/// bar). The outcome need not be monotonic in Vh: every change between neighbouring landed
/// points is found (changes closer together than the scan step, or than the grid step where
/// nothing changes, can hide between two points with the same outcome). Refuses bad settings
/// (see [`Settings::validate`]) before any landing; of several failed landings, the error is
/// that of the lowest Vv and Vh.
pub fn search<F, L>(
    vvs: &[f64],
    settings: Settings,
    landing: F,
    tick: &(dyn Fn() + Sync),
) -> Result<Vec<BoundaryPoint>, ValidationError>
where
    F: Fn(f64, f64) -> Result<L, ValidationError> + Sync,
    L: Into<Landed>,
{
    search_streaming(vvs, settings, landing, None, tick, &|_| ())
}

/// [`search`], handing each point to `found` as soon as it and every point before it (in the
/// order of `vvs`) are found: the points stream in the order of the result, whatever the
/// threads, so that a stream of them is deterministic. With `refined`, every transition's
/// bracket ends are landed again by it ([`Transition::refined`]).
pub(super) fn search_streaming<F, L>(
    vvs: &[f64],
    settings: Settings,
    landing: F,
    refined: Option<RefinedLanding>,
    tick: &(dyn Fn() + Sync),
    found: &(dyn Fn(&BoundaryPoint) + Sync),
) -> Result<Vec<BoundaryPoint>, ValidationError>
where
    F: Fn(f64, f64) -> Result<L, ValidationError> + Sync,
    L: Into<Landed>,
{
    let grid = settings.grid()?;
    if let Some(&vv) = vvs.iter().find(|v| !v.is_finite()) {
        return Err(refuse("--vv", "finite descent speeds".into(), vv));
    }
    let run = |vv: f64, vh: f64| -> Result<Landed, ValidationError> {
        let l = landing(vv, vh)?.into();
        tick();
        Ok(l)
    };
    // The points found out of order wait here until those before them are found.
    let waiting = std::sync::Mutex::new((0usize, std::collections::BTreeMap::new()));
    let points: Vec<Result<BoundaryPoint, ValidationError>> = vvs
        .par_iter()
        .enumerate()
        .map(|(i, &vv)| {
            let mut point = at_descent_speed(vv, &grid, &settings, &|vh| run(vv, vh))?;
            if let Some((refinement, land)) = refined {
                let refined = |vh: f64| -> Result<Outcome, ValidationError> {
                    let o = land(vv, vh)?;
                    tick();
                    Ok(o)
                };
                let ends = (point.transitions.par_iter())
                    .map(|t| {
                        let (s, u) =
                            rayon::join(|| refined(t.stable_at), || refined(t.unstable_at));
                        Ok(Refined::new(refinement, s?, u?))
                    })
                    .collect();
                for (t, r) in point.transitions.iter_mut().zip(in_order(ends)?) {
                    t.refined = Some(r);
                }
            }
            let mut w = waiting.lock().unwrap_or_else(|e| e.into_inner());
            w.1.insert(i, point.clone());
            loop {
                let next = w.0;
                let Some(p) = w.1.remove(&next) else { break };
                found(&p);
                w.0 += 1;
            }
            Ok(point)
        })
        .collect();
    points.into_iter().collect()
}

/// Collects ordered parallel results, the first error in order winning.
fn in_order<T>(results: Vec<Result<T, ValidationError>>) -> Result<Vec<T>, ValidationError> {
    results.into_iter().collect()
}

/// One landing of the search: its Vh (scenario velocity unit) and what it says.
type Point = (f64, Landed);

/// Lands every Vh of `vhs`, in parallel, in order.
fn land_all(vhs: &[f64], land: &Land) -> Result<Vec<Point>, ValidationError> {
    in_order(vhs.par_iter().map(|&vh| Ok((vh, land(vh)?))).collect())
}

/// One landing at a horizontal speed, scenario velocity unit.
type Land<'a> = dyn Fn(f64) -> Result<Landed, ValidationError> + Sync + 'a;

/// The scan points between `from` and `to` (scenario velocity unit) every `step`, computed
/// from `from` (not accumulated), ascending.
fn scan_points(from: f64, to: f64, step: f64) -> impl Iterator<Item = f64> {
    let n = ((to - from) / step + 1e-9).floor() as usize;
    (0..=n).map(move |i| from + i as f64 * step)
}

/// The search at one descent speed `vv`: the `grid`, a scan at `settings.scan_step` around
/// its changes, the bisections.
fn at_descent_speed(
    vv: f64,
    grid: &[f64],
    settings: &Settings,
    land: &Land,
) -> Result<BoundaryPoint, ValidationError> {
    let mut landed = land_all(grid, land)?;
    // Around each change of outcome the grid sees, scan finer from a grid step below it to a
    // grid step above it, where an outcome alternating faster than the grid would hide.
    if let Some(step) = settings.scan_step {
        // Points within 1e-9 of a step of one another, or of a grid point, are one point.
        let same = |a: f64, b: f64| (a - b).abs() <= 1e-9 * step;
        let mut scan: Vec<f64> = (landed.windows(2))
            .filter(|w| w[0].1.outcome != w[1].1.outcome)
            .flat_map(|w| {
                let from = (w[0].0 - settings.vh_step).max(grid[0]);
                let to = (w[1].0 + settings.vh_step).min(grid[grid.len() - 1]);
                scan_points(from, to, step)
            })
            .filter(|&vh| !landed.iter().any(|p| same(p.0, vh)))
            .collect();
        scan.sort_by(f64::total_cmp);
        scan.dedup_by(|a, b| same(*a, *b));
        landed.extend(land_all(&scan, land)?);
        landed.sort_by(|a, b| a.0.total_cmp(&b.0));
    }
    let decided: Vec<usize> = (0..landed.len())
        .filter(|&i| landed[i].1.outcome != Outcome::Undecided)
        .collect();
    let mut transitions = Vec::new();
    let mut to_bisect = Vec::new();
    for w in decided.windows(2) {
        let (i, j) = (w[0], w[1]);
        let ((vi, li), (vj, lj)) = (landed[i], landed[j]);
        if li.outcome == lj.outcome {
            continue;
        }
        let (direction, (stable_at, stable), (unstable_at, unstable)) =
            if li.outcome == Outcome::Stable {
                (Direction::StableToUnstable, (vi, li), (vj, lj))
            } else {
                (Direction::UnstableToStable, (vj, lj), (vi, li))
            };
        let t = Transition {
            direction,
            stable_at,
            unstable_at,
            vh: None,
            resolved: false,
            undecided_at: landed[i + 1..j].iter().map(|p| p.0).collect(),
            stable_stops: stable.stops,
            unstable_stops: unstable.stops,
            refined: None,
        };
        if j == i + 1 {
            to_bisect.push(t);
        } else {
            transitions.push(t);
        }
    }
    let bisected = in_order(
        to_bisect
            .into_par_iter()
            .map(|t| bisect(t, settings.tolerance, land))
            .collect(),
    )?;
    let mut midpoints = Vec::new();
    for (t, points) in bisected {
        midpoints.extend(points);
        transitions.push(t);
    }
    transitions.sort_by(|a, b| a.lower().total_cmp(&b.lower()));
    // The first landing past a capacity, bisected against the landing below it.
    let capacity = match landed.iter().position(|p| p.1.stops.engaged()) {
        None => None,
        Some(0) => Some(CapacityEdge {
            within_at: None,
            past_at: landed[0].0,
            vh: None,
            stops: landed[0].1.stops,
        }),
        Some(k) => {
            let (edge, points) =
                bisect_capacity(landed[k - 1].0, landed[k], settings.tolerance, land)?;
            midpoints.extend(points);
            Some(edge)
        }
    };
    landed.extend(midpoints);
    landed.sort_by(|a, b| a.0.total_cmp(&b.0));
    let undecided_at: Vec<f64> = (landed.iter())
        .filter(|p| p.1.outcome == Outcome::Undecided)
        .map(|p| p.0)
        .collect();
    let (vh, stable_at, unstable_at) = match transitions
        .iter()
        .find(|t| t.direction == Direction::StableToUnstable)
    {
        Some(t) => (t.vh, Some(t.stable_at), Some(t.unstable_at)),
        None => {
            let at = |o: Outcome| landed.iter().filter(move |p| p.1.outcome == o);
            let unstable = at(Outcome::Unstable).map(|p| p.0).next();
            let stable = at(Outcome::Stable).map(|p| p.0).next_back();
            (None, stable.filter(|_| unstable.is_none()), unstable)
        }
    };
    let band = match (transitions.first(), transitions.last()) {
        (Some(a), Some(b)) if transitions.len() > 1 => Some(Band {
            from: a.lower(),
            to: b.upper(),
            changes: transitions.len(),
        }),
        _ => None,
    };
    Ok(BoundaryPoint {
        vv,
        vh,
        stable_at,
        unstable_at,
        transitions,
        band,
        capacity,
        safe: safe_edge(&landed),
        undecided: undecided_at.len(),
        undecided_at,
        landings: landed.len(),
    })
}

/// The safe envelope of the landings `landed` (ascending in Vh).
fn safe_edge(landed: &[Point]) -> SafeEdge {
    match landed.iter().position(|p| !p.1.safe()) {
        None => SafeEdge {
            safe_to: landed.last().map(|p| p.0),
            unsafe_at: None,
            limit: None,
        },
        Some(k) => {
            let l = landed[k].1;
            let limit = match (l.outcome, l.stops.engaged()) {
                (Outcome::Undecided, _) => Limit::Undecided,
                (Outcome::Unstable, false) => Limit::Overturn,
                (Outcome::Unstable, true) => Limit::OverturnAndCapacity,
                (Outcome::Stable, _) => Limit::Capacity,
            };
            SafeEdge {
                safe_to: k.checked_sub(1).map(|j| landed[j].0),
                unsafe_at: Some(landed[k].0),
                limit: Some(limit),
            }
        }
    }
}

/// Bisects the bracket of `t` (no undecided point inside) until it is no wider than
/// `tolerance` or a midpoint ends undecided; returns it with the landings it ran.
fn bisect(
    mut t: Transition,
    tolerance: f64,
    land: &Land,
) -> Result<(Transition, Vec<Point>), ValidationError> {
    let mut points = Vec::new();
    while (t.unstable_at - t.stable_at).abs() > tolerance {
        let mid = 0.5 * (t.stable_at + t.unstable_at);
        let l = land(mid)?;
        points.push((mid, l));
        match l.outcome {
            Outcome::Stable => (t.stable_at, t.stable_stops) = (mid, l.stops),
            Outcome::Unstable => (t.unstable_at, t.unstable_stops) = (mid, l.stops),
            Outcome::Undecided => {
                t.undecided_at = vec![mid];
                return Ok((t, points));
            }
        }
    }
    t.resolved = true;
    t.vh = Some(0.5 * (t.stable_at + t.unstable_at));
    Ok((t, points))
}

/// Bisects between `within` (a Vh whose landing stayed within every capacity) and the landing
/// `past` (one that went past a capacity) until the bracket is no wider than `tolerance`, on
/// the capacity alone (whatever the outcome); returns the edge with the landings it ran.
fn bisect_capacity(
    mut within: f64,
    (mut past, first): Point,
    tolerance: f64,
    land: &Land,
) -> Result<(CapacityEdge, Vec<Point>), ValidationError> {
    let mut stops = first.stops;
    let mut points = Vec::new();
    while (past - within).abs() > tolerance {
        let mid = 0.5 * (within + past);
        let l = land(mid)?;
        points.push((mid, l));
        if l.stops.engaged() {
            (past, stops) = (mid, l.stops);
        } else {
            within = mid;
        }
    }
    let edge = CapacityEdge {
        within_at: Some(within),
        past_at: past,
        vh: Some(0.5 * (within + past)),
        stops,
    };
    Ok((edge, points))
}
