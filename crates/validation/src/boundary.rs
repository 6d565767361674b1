//! The report's automatic stability-boundary search (section "Stability criteria"): for each
//! vertical velocity Vv, the horizontal velocities Vh at which the landing changes between
//! stable and unstable, where a strut first goes past its capacity, and how far the landing is
//! safe (stable and within every strut's capacity).
//!
//! At each Vv the search lands on the whole grid `vh_start + i·vh_step` (i = 0, 1, … up to
//! `vh_max`). Around each change of outcome the grid finds, a finer scan (`scan_step`) lands
//! every point from one grid step below it to one grid step above it, so that an outcome
//! alternating faster than the grid near a change is seen. Every
//! change of outcome between neighbouring landed points is then bisected to the tolerance, in
//! either direction, and so is the first Vh past capacity. Undecided landings are never counted
//! as stable or unstable: they are listed; a change of outcome across undecided points, or a
//! bisection whose midpoint ends undecided, is reported as an unresolved bracket.
//!
//! What the search reports at each Vv: every transition, each end with the end stops it
//! engaged (how many struts past their capacity, the largest stop force); the boundary, the
//! lowest stable → unstable transition; the band over which the outcome alternates when there
//! are several transitions (its ends and how many changes), never collapsed to one number; the
//! first Vh past capacity; and the safe envelope, up to the first landing that overturned,
//! ended undecided or went past a capacity (docs/validation.md, "Stability boundary").
//!
//! A stable landing runs to its end time, an unstable one to its wall crossing
//! (docs/errata.md, "Stability decisions and maxima"). Vertical velocities, grid points and
//! transitions run in parallel; every result is ordered by Vh, never by completion.
//!
//! All velocities here are in the scenario's velocity unit (its length unit per second).

use crate::ValidationError;
use rayon::prelude::*;
use serde::Serialize;
use std::path::Path;
use touchdown_core::{Outcome, RunError};
use touchdown_scenario::schema::Engine;
use touchdown_scenario::units::Short;
use touchdown_scenario::{Scenario, ScenarioBase};

/// Largest number of grid points at one vertical velocity.
pub const MAX_GRID_POINTS: usize = 10_000;

/// Largest ratio of the largest |Vh| searched (or 1 if that is smaller) to the tolerance and
/// to the step: beyond it a bisection could not narrow its bracket in floating point.
pub const MAX_RELATIVE_RESOLUTION: f64 = 1e9;

/// Search settings; velocities in the scenario's velocity unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// First grid point (`--vh-start`), scenario velocity unit.
    pub vh_start: f64,
    /// Grid step (`--vh-step`), scenario velocity unit; finite and > 0.
    pub vh_step: f64,
    /// Largest horizontal velocity tried on the grid (`--vh-max`), scenario velocity unit;
    /// ≥ `vh_start`. It is a grid point when it lies within 1e-9 (relative) of one.
    pub vh_max: f64,
    /// Bisection stops when a bracket is no wider than this (`--tol`), scenario velocity unit;
    /// finite, > 0 and at least max(|vh_start|, |vh_max|, 1) / [`MAX_RELATIVE_RESOLUTION`].
    pub tolerance: f64,
    /// Step of the finer scan around the changes of outcome the grid finds (`--scan-step`),
    /// scenario velocity unit: finite, > 0 and below `vh_step`; `None` scans nothing but the
    /// grid.
    pub scan_step: Option<f64>,
}

/// The grid step when none is asked for, as a fraction of the vehicle's velocity scale
/// ([`touchdown_scenario::scales::Scales::velocity_m_s`]): 2.11 ft/s on the 1/6-scale model
/// (velocity scale 8.45 ft/s, 2.58 m/s), whose boundary moves by about 2 ft/s per 2 ft/s of
/// descent speed.
pub const DEFAULT_VH_STEP: f64 = 0.25;

/// The grid's largest horizontal speed when none is asked for, as a fraction of the vehicle's
/// velocity scale: 29.6 ft/s on the 1/6-scale model, past its boundary at every descent speed
/// of Table I (23.6 ft/s at 8 ft/s, docs/engines.md).
pub const DEFAULT_VH_MAX: f64 = 3.5;

/// The bisection tolerance when none is asked for, as a fraction of the vehicle's velocity
/// scale: 0.051 ft/s on the 1/6-scale model, the report's 0.05 ft/s.
pub const DEFAULT_TOLERANCE: f64 = 0.006;

/// The scan step when none is asked for, as a fraction of the grid step: 0.25 ft/s on a grid
/// of 2 ft/s, 0.264 ft/s on the 1/6-scale model's default grid.
pub const DEFAULT_SCAN_STEP: f64 = 0.125;

/// A search's settings as asked (`--vh-start`, `--vh-step`, `--vh-max`, `--tol`,
/// `--scan-step`), scenario velocity unit: each one left out takes its default, a ratio of the
/// vehicle's velocity scale ([`Asked::settings`]), so that a dynamically similar vehicle is
/// searched alike whatever its size and units.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Asked {
    /// First grid point; default 0.
    pub vh_start: Option<f64>,
    /// Grid step; default [`DEFAULT_VH_STEP`] of the velocity scale.
    pub vh_step: Option<f64>,
    /// Largest grid point; default [`DEFAULT_VH_MAX`] of the velocity scale.
    pub vh_max: Option<f64>,
    /// Bisection tolerance; default [`DEFAULT_TOLERANCE`] of the velocity scale.
    pub tolerance: Option<f64>,
    /// Scan step: 0 scans nothing but the grid; default [`DEFAULT_SCAN_STEP`] of the grid
    /// step.
    pub scan_step: Option<f64>,
}

impl Asked {
    /// The settings of a search of `sc`: what is asked as asked, the rest from the vehicle's
    /// velocity scale in the scenario's velocity unit; an error for a vehicle with no velocity
    /// scale (neither gravity nor a touchdown speed) if a default needs it.
    pub fn settings(&self, sc: &Scenario) -> Result<Settings, ValidationError> {
        let scale = || -> Result<f64, ValidationError> {
            let v = touchdown_scenario::scales::Scales::of(sc)?.velocity_m_s;
            Ok(v / sc.units().velocity())
        };
        let or_scaled = |asked: Option<f64>, ratio: f64| -> Result<f64, ValidationError> {
            match asked {
                Some(v) => Ok(v),
                None => Ok(ratio * scale()?),
            }
        };
        let vh_step = or_scaled(self.vh_step, DEFAULT_VH_STEP)?;
        let scan_step = match self.scan_step {
            Some(0.0) => None,
            Some(s) => Some(s),
            None => Some(DEFAULT_SCAN_STEP * vh_step),
        };
        Ok(Settings {
            vh_start: self.vh_start.unwrap_or(0.0),
            vh_step,
            vh_max: or_scaled(self.vh_max, DEFAULT_VH_MAX)?,
            tolerance: or_scaled(self.tolerance, DEFAULT_TOLERANCE)?,
            scan_step,
        })
    }
}

fn refuse(argument: &'static str, expected: String, got: f64) -> ValidationError {
    ValidationError::Setting {
        argument,
        expected,
        got: Short(got).to_string(),
    }
}

impl Settings {
    /// Checks the settings: an error ([`ValidationError::Setting`]) names the command-line
    /// argument at fault and what it must be.
    pub fn validate(&self) -> Result<(), ValidationError> {
        self.grid().map(|_| ())
    }

    /// The grid of horizontal velocities, scenario velocity unit: `vh_start + i·vh_step` for
    /// i = 0, 1, …, the last no more than 1e-9 (relative to the largest of |vh_start|,
    /// |vh_max| and the step) above `vh_max`. Refused as [`Settings::validate`] says.
    pub fn grid(&self) -> Result<Vec<f64>, ValidationError> {
        let &Settings {
            vh_start,
            vh_step,
            vh_max,
            tolerance,
            scan_step,
        } = self;
        if !vh_start.is_finite() {
            return Err(refuse("--vh-start", "a finite speed".into(), vh_start));
        }
        if !vh_max.is_finite() {
            return Err(refuse("--vh-max", "a finite speed".into(), vh_max));
        }
        if !(vh_step.is_finite() && vh_step > 0.0) {
            return Err(refuse("--vh-step", "a finite step > 0".into(), vh_step));
        }
        if !(tolerance.is_finite() && tolerance > 0.0) {
            return Err(refuse("--tol", "a finite tolerance > 0".into(), tolerance));
        }
        if let Some(scan) = scan_step {
            if !(scan.is_finite() && scan > 0.0 && scan < vh_step) {
                return Err(refuse(
                    "--scan-step",
                    format!("a finite step > 0 and below --vh-step ({})", Short(vh_step)),
                    scan,
                ));
            }
            // The scan covers at most the whole grid: as many points as a grid of its step.
            if (vh_max - vh_start) / scan > MAX_GRID_POINTS as f64 {
                return Err(refuse(
                    "--scan-step",
                    format!(
                        "a step giving at most {MAX_GRID_POINTS} points from --vh-start {} to --vh-max {}",
                        Short(vh_start),
                        Short(vh_max)
                    ),
                    scan,
                ));
            }
        }
        if vh_max < vh_start {
            return Err(refuse(
                "--vh-max",
                format!("a speed ≥ --vh-start ({})", Short(vh_start)),
                vh_max,
            ));
        }
        let scale = vh_start.abs().max(vh_max.abs()).max(1.0);
        let finest = scale / MAX_RELATIVE_RESOLUTION;
        if tolerance < finest {
            return Err(refuse(
                "--tol",
                format!(
                    "a tolerance ≥ {} (1e-9 of the largest |Vh| searched, or of 1), \
                     which bisection can reach in floating point",
                    Short(finest)
                ),
                tolerance,
            ));
        }
        if vh_step < finest {
            return Err(refuse(
                "--vh-step",
                format!(
                    "a step ≥ {} (1e-9 of the largest |Vh| searched, or of 1)",
                    Short(finest)
                ),
                vh_step,
            ));
        }
        let too_many = || {
            refuse(
                "--vh-step",
                format!(
                    "a step giving at most {MAX_GRID_POINTS} grid points from --vh-start \
                     {} to --vh-max {} (a step ≥ {})",
                    Short(vh_start),
                    Short(vh_max),
                    Short((vh_max - vh_start) / (MAX_GRID_POINTS - 1) as f64)
                ),
                vh_step,
            )
        };
        let intervals = (vh_max - vh_start) / vh_step;
        if intervals.is_nan() || intervals > MAX_GRID_POINTS as f64 {
            return Err(too_many());
        }
        let slack = vh_start.abs().max(vh_max.abs()).max(vh_step) / MAX_RELATIVE_RESOLUTION;
        let point = |i: usize| vh_start + i as f64 * vh_step;
        let mut last = intervals.floor() as usize;
        if point(last + 1) <= vh_max + slack {
            last += 1;
        } else if last > 0 && point(last) > vh_max + slack {
            last -= 1;
        }
        if last + 1 > MAX_GRID_POINTS {
            return Err(too_many());
        }
        Ok((0..=last).map(point).collect())
    }
}

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

/// One change of outcome between two neighbouring decided landings at one Vv (written in SI
/// as a [`TransitionSi`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Transition {
    /// Which way the outcome changes as Vh increases.
    pub direction: Direction,
    /// The bracket's end found stable, scenario velocity unit (the lower end for
    /// [`Direction::StableToUnstable`], the upper one otherwise).
    pub stable_at: f64,
    /// The bracket's end found unstable, scenario velocity unit.
    pub unstable_at: f64,
    /// The transition's Vh, middle of the final bracket (no wider than the tolerance),
    /// scenario velocity unit; `None` if unresolved.
    pub vh: Option<f64>,
    /// Whether the bracket was narrowed to the tolerance. False when undecided points lie
    /// between its ends (it was never bisected) or a bisection midpoint ended undecided (the
    /// bracket is the one at that moment).
    pub resolved: bool,
    /// The undecided landings inside the bracket, scenario velocity unit, ascending: the
    /// points between its ends, or the bisection midpoint that stopped it; empty if resolved.
    pub undecided_at: Vec<f64>,
    /// The end stops engaged by the landing at the stable end.
    pub stable_stops: Stops,
    /// The end stops engaged by the landing at the unstable end.
    pub unstable_stops: Stops,
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
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Band {
    /// The band's lower end, scenario velocity unit.
    pub from: f64,
    /// The band's upper end, scenario velocity unit.
    pub to: f64,
    /// How many times the outcome changes within it (the number of transitions).
    pub changes: usize,
}

/// The first Vh at which a strut goes past its capacity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CapacityEdge {
    /// The bracket's end within every capacity, scenario velocity unit (`None` when the first
    /// landing searched already went past one).
    pub within_at: Option<f64>,
    /// The bracket's end past a capacity, scenario velocity unit.
    pub past_at: f64,
    /// The middle of the final bracket (no wider than the tolerance), scenario velocity unit;
    /// `None` when the first landing searched went past.
    pub vh: Option<f64>,
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
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SafeEdge {
    /// The largest Vh below the first unsafe landing, scenario velocity unit (`None` when the
    /// first landing searched is unsafe).
    pub safe_to: Option<f64>,
    /// The first unsafe landing's Vh, scenario velocity unit (`None` when all were safe).
    pub unsafe_at: Option<f64>,
    /// Why that landing is unsafe (`None` when all were safe).
    pub limit: Option<Limit>,
}

/// The boundary at one vertical velocity (written in SI as a [`PointSi`]).
#[derive(Debug, Clone, PartialEq)]
pub struct BoundaryPoint {
    /// Descent speed (positive down), scenario velocity unit.
    pub vv: f64,
    /// The boundary: the Vh of the lowest stable → unstable transition, scenario velocity
    /// unit; `None` if there is none or it is unresolved.
    pub vh: Option<f64>,
    /// The stable end of the lowest stable → unstable transition's bracket; without one, the
    /// largest Vh found stable if none was found unstable, else `None`. Scenario velocity
    /// unit.
    pub stable_at: Option<f64>,
    /// The unstable end of the lowest stable → unstable transition's bracket; without one, the
    /// smallest Vh found unstable (`None` if none). Scenario velocity unit.
    pub unstable_at: Option<f64>,
    /// Every transition, in either direction, ascending in Vh.
    pub transitions: Vec<Transition>,
    /// Where the outcome alternates, when there are two or more transitions.
    pub band: Option<Band>,
    /// The first Vh past a strut's capacity (`None` if no landing went past one).
    pub capacity: Option<CapacityEdge>,
    /// The safe envelope.
    pub safe: SafeEdge,
    /// The Vh of every landing that ended undecided (grid, scan and bisection), scenario
    /// velocity unit, ascending.
    pub undecided_at: Vec<f64>,
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
    search_streaming(vvs, settings, landing, tick, &|_| ())
}

/// [`search`], handing each point to `found` as soon as it and every point before it (in the
/// order of `vvs`) are found: the points stream in the order of the result, whatever the
/// threads, so that a stream of them is deterministic.
pub fn search_streaming<F, L>(
    vvs: &[f64],
    settings: Settings,
    landing: F,
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
            let point = at_descent_speed(vv, &grid, &settings, &|vh| run(vv, vh))?;
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

/// A landing closure for [`search`] on the scenario `base` with `overrides` (field path and
/// value in the file's units, [`ScenarioBase::with`]): its vertical velocity set to −vv and
/// its horizontal velocity to vh along the scenario's own horizontal direction (file units),
/// landed by `land` (one engine's run of the changed scenario, to its outcome).
pub fn scenario_landing<'a, L, T>(
    base: &'a ScenarioBase,
    overrides: &'a [(&'a str, toml::Value)],
    land: L,
) -> Result<impl Fn(f64, f64) -> Result<T, ValidationError> + Sync + 'a, ValidationError>
where
    L: Fn(&Scenario) -> Result<T, RunError> + Sync + 'a,
{
    let sc = base.with(overrides)?;
    let [hx, hy] = sc.file.touchdown.horizontal_velocity;
    let norm = hx.hypot(hy);
    if norm == 0.0 {
        return Err(ValidationError::Reference(format!(
            "{}: touchdown.horizontal_velocity is zero, so it gives no direction to search along",
            base.source()
        )));
    }
    let (dx, dy) = (hx / norm, hy / norm);
    Ok(move |vv: f64, vh: f64| {
        let mut values = overrides.to_vec();
        values.extend([
            ("touchdown.vertical_velocity", toml::Value::Float(-vv)),
            (
                "touchdown.horizontal_velocity[0]",
                toml::Value::Float(dx * vh),
            ),
            (
                "touchdown.horizontal_velocity[1]",
                toml::Value::Float(dy * vh),
            ),
        ]);
        let sc = base
            .with(&values)
            .map_err(|source| ValidationError::Point {
                scenario: base.source().to_string(),
                vv: Short(-vv).to_string(),
                vh: Short(vh).to_string(),
                source: Box::new(source),
            })?;
        land(&sc).map_err(|source| ValidationError::Run {
            scenario: format!("{} at Vv = {vv}, Vh = {vh}", base.source()),
            source,
        })
    })
}

/// One engine's boundary at one descent speed (written in SI by [`EnginePoint::si`]).
#[derive(Debug, Clone, PartialEq)]
pub struct EnginePoint {
    /// The engine that searched.
    pub engine: Engine,
    /// The end stops' coefficient of restitution the search set on every strut's load-stroke
    /// diagram (`None`: the scenario's own).
    pub stop_restitution: Option<f64>,
    /// What it found.
    pub point: BoundaryPoint,
}

/// The boundary search of the scenario `base` with `overrides` ([`scenario_landing`]) on each
/// of `engines` (in engine order, each once; every one must apply to the scenario), at the
/// descent speeds `vvs`, once with the scenario's own end stops if `restitutions` is empty,
/// else once per coefficient of restitution in it, set on every strut's load-stroke diagram
/// (`Scenario::strut_diagrams`): one point per engine, restitution and descent speed, in
/// that order, each also handed to `found` as soon as it and those before it are found.
#[allow(clippy::too_many_arguments)]
pub fn search_engines(
    base: &ScenarioBase,
    overrides: &[(&str, toml::Value)],
    vvs: &[f64],
    settings: Settings,
    engines: &[Engine],
    restitutions: &[f64],
    tick: &(dyn Fn() + Sync),
    found: &(dyn Fn(&EnginePoint) + Sync),
) -> Result<Vec<EnginePoint>, ValidationError> {
    settings.validate()?;
    if let Some(&e) = restitutions.iter().find(|e| !(0.0..=1.0).contains(*e)) {
        return Err(refuse(
            "--stop-restitution",
            "coefficients of restitution in [0, 1]".into(),
            e,
        ));
    }
    let mut engines = engines.to_vec();
    engines.sort();
    engines.dedup();
    let sc = base.with(overrides)?;
    let path = Path::new(base.source());
    for &e in &engines {
        touchdown_registry::require(e, &sc)?;
    }
    let laws: Vec<Option<f64>> = if restitutions.is_empty() {
        vec![None]
    } else {
        restitutions.iter().copied().map(Some).collect()
    };
    let stop_fields = sc
        .strut_diagrams()
        .map(|(diagram, _)| format!("{diagram}.stop_restitution"));
    let mut points = Vec::new();
    for &engine in &engines {
        for &stop_restitution in &laws {
            let mut values = overrides.to_vec();
            if let Some(e) = stop_restitution {
                let fields = stop_fields
                    .iter()
                    .map(|f| (f.as_str(), toml::Value::Float(e)));
                values.extend(fields);
            }
            let landing = scenario_landing(base, &values, move |sc: &Scenario| {
                touchdown_registry::land(engine, path, sc, &mut (), None)
                    .map(|s| Landed::of(&s))
                    .map_err(|f| f.error)
            })?;
            let point = |p: &BoundaryPoint| {
                found(&EnginePoint {
                    engine,
                    stop_restitution,
                    point: p.clone(),
                })
            };
            let found =
                search_streaming(vvs, settings, landing, tick, &point).map_err(|e| match e {
                    ValidationError::Run { scenario, source } => ValidationError::Run {
                        scenario: format!("{engine} engine on {scenario}"),
                        source,
                    },
                    other => other,
                })?;
            points.extend(found.into_iter().map(|point| EnginePoint {
                engine,
                stop_restitution,
                point,
            }));
        }
    }
    Ok(points)
}

/// A transition in SI, in a boundary document.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TransitionSi {
    /// Which way the outcome changes as Vh increases.
    pub direction: Direction,
    /// The bracket's end found stable, m/s.
    pub stable_at_vh_m_s: f64,
    /// The bracket's end found unstable, m/s.
    pub unstable_at_vh_m_s: f64,
    /// The transition's Vh, m/s; left out if unresolved.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub vh_m_s: Option<f64>,
    /// Whether the bracket was narrowed to the tolerance.
    pub resolved: bool,
    /// The undecided landings inside the bracket, m/s, ascending.
    pub undecided_at_vh_m_s: Vec<f64>,
    /// The end stops engaged at the stable end.
    pub stable_stops: Stops,
    /// The end stops engaged at the unstable end.
    pub unstable_stops: Stops,
}

/// A band of alternating outcomes in SI.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BandSi {
    /// Its lower end, m/s.
    pub from_vh_m_s: f64,
    /// Its upper end, m/s.
    pub to_vh_m_s: f64,
    /// How many times the outcome changes within it.
    pub changes: usize,
}

/// The first Vh past a capacity in SI.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CapacityEdgeSi {
    /// The bracket's end within every capacity, m/s (left out when the first landing went
    /// past).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub within_at_vh_m_s: Option<f64>,
    /// The bracket's end past a capacity, m/s.
    pub past_at_vh_m_s: f64,
    /// The middle of the bracket, m/s (left out when the first landing went past).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub vh_m_s: Option<f64>,
    /// The stops engaged at the past end.
    pub stops: Stops,
}

/// The safe envelope in SI.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SafeEdgeSi {
    /// The largest Vh below the first unsafe landing, m/s (left out when the first landing
    /// was unsafe).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub safe_to_vh_m_s: Option<f64>,
    /// The first unsafe landing's Vh, m/s (left out when every landing was safe).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unsafe_at_vh_m_s: Option<f64>,
    /// Why it is unsafe (left out when every landing was safe).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub limit: Option<Limit>,
}

/// One engine's boundary at one descent speed in SI, its vertical velocity signed as in the
/// scenario files (negative down): the fields of a line of `touchdown boundary --format json`
/// after its envelope (docs/schemas/boundary.schema.json). The fields mean what those of
/// [`BoundaryPoint`] do.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PointSi {
    /// The engine that searched.
    pub engine: &'static str,
    /// The end stops' restitution set on every diagram (left out: the scenario's own).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stop_restitution: Option<f64>,
    /// The vertical velocity, m/s, negative down (`touchdown.vertical_velocity`).
    pub vv_m_s: f64,
    /// The boundary's horizontal speed, m/s (left out if none or unresolved).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub vh_m_s: Option<f64>,
    /// The stable end of the boundary's bracket (or the largest Vh found stable), m/s.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stable_at_vh_m_s: Option<f64>,
    /// The unstable end of the boundary's bracket (or the smallest Vh found unstable), m/s.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unstable_at_vh_m_s: Option<f64>,
    /// Every transition, ascending in Vh.
    pub transitions: Vec<TransitionSi>,
    /// Where the outcome alternates (left out with fewer than two transitions).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub band: Option<BandSi>,
    /// The first Vh past a capacity (left out if no landing went past one).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub capacity: Option<CapacityEdgeSi>,
    /// The safe envelope.
    pub safe: SafeEdgeSi,
    /// The Vh of every undecided landing, m/s, ascending.
    pub undecided_at_vh_m_s: Vec<f64>,
    /// Landings run.
    pub landings: usize,
    /// Landings that ended undecided.
    pub undecided: usize,
}

impl EnginePoint {
    /// The point in SI, `velocity` being the scenario's velocity unit in m/s.
    pub fn si(&self, velocity: f64) -> PointSi {
        let p = &self.point;
        let si = |v: f64| v * velocity;
        let all = |v: &[f64]| v.iter().map(|x| si(*x)).collect();
        PointSi {
            engine: self.engine.name(),
            stop_restitution: self.stop_restitution,
            vv_m_s: -si(p.vv),
            vh_m_s: p.vh.map(si),
            stable_at_vh_m_s: p.stable_at.map(si),
            unstable_at_vh_m_s: p.unstable_at.map(si),
            transitions: p
                .transitions
                .iter()
                .map(|t| TransitionSi {
                    direction: t.direction,
                    stable_at_vh_m_s: si(t.stable_at),
                    unstable_at_vh_m_s: si(t.unstable_at),
                    vh_m_s: t.vh.map(si),
                    resolved: t.resolved,
                    undecided_at_vh_m_s: all(&t.undecided_at),
                    stable_stops: t.stable_stops,
                    unstable_stops: t.unstable_stops,
                })
                .collect(),
            band: p.band.map(|b| BandSi {
                from_vh_m_s: si(b.from),
                to_vh_m_s: si(b.to),
                changes: b.changes,
            }),
            capacity: p.capacity.map(|c| CapacityEdgeSi {
                within_at_vh_m_s: c.within_at.map(si),
                past_at_vh_m_s: si(c.past_at),
                vh_m_s: c.vh.map(si),
                stops: c.stops,
            }),
            safe: SafeEdgeSi {
                safe_to_vh_m_s: p.safe.safe_to.map(si),
                unsafe_at_vh_m_s: p.safe.unsafe_at.map(si),
                limit: p.safe.limit,
            },
            undecided_at_vh_m_s: all(&p.undecided_at),
            landings: p.landings,
            undecided: p.undecided,
        }
    }
}

/// The descent speeds (positive down, as the search takes them) of vertical velocities `vvs`
/// written as in the scenario files (negative down); refuses a vertical velocity that is not
/// negative, and none or more than [`MAX_GRID_POINTS`] of them, naming `argument`.
pub fn descent_speeds(vvs: &[f64], argument: &'static str) -> Result<Vec<f64>, ValidationError> {
    if vvs.is_empty() || vvs.len() > MAX_GRID_POINTS {
        return Err(refuse(
            argument,
            format!("1 to {MAX_GRID_POINTS} vertical velocities"),
            vvs.len() as f64,
        ));
    }
    vvs.iter()
        .map(|&v| {
            if v.is_finite() && v < 0.0 {
                Ok(-v)
            } else {
                Err(refuse(
                    argument,
                    "vertical velocities as the scenario files write them, negative down (e.g. -8.0)".into(),
                    v,
                ))
            }
        })
        .collect()
}

/// The options of a boundary search as its documents record them: the vertical velocities
/// `vvs` (negative down), the grid, the tolerance and the scan step as given, in the
/// scenario's velocity unit `unit` (`ft/s`, written into each name as `_ft_s`), the engines
/// and the end stops' restitutions searched (`stop_restitution`, when given).
pub fn options(
    vvs: &[f64],
    s: Settings,
    unit: &str,
    engines: &[Engine],
    restitutions: &[f64],
) -> serde_json::Value {
    let suffix = unit.replace('/', "_");
    let mut o = serde_json::Map::new();
    let mut put = |name: &str, value: serde_json::Value| {
        o.insert(format!("{name}_{suffix}"), value);
    };
    put("vv", serde_json::json!(vvs));
    put("vh_start", serde_json::json!(s.vh_start));
    put("vh_step", serde_json::json!(s.vh_step));
    put("vh_max", serde_json::json!(s.vh_max));
    put("tolerance", serde_json::json!(s.tolerance));
    if let Some(scan) = s.scan_step {
        put("scan_step", serde_json::json!(scan));
    }
    o.insert("engines".into(), serde_json::json!(engines));
    if !restitutions.is_empty() {
        o.insert("stop_restitution".into(), serde_json::json!(restitutions));
    }
    serde_json::Value::Object(o)
}

/// A point as one line of `touchdown boundary --format json` (JSON Lines): the envelope
/// naming the scenario `id` and the `settings`, then the point in SI ([`EnginePoint::si`];
/// `velocity` is the scenario's velocity unit in m/s).
pub fn document_line(
    point: &EnginePoint,
    velocity: f64,
    id: &touchdown_record::ScenarioId,
    settings: &serde_json::Value,
) -> String {
    touchdown_record::Document::new("boundary", Some(id), settings, &point.si(velocity)).line()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};

    #[test]
    fn the_defaults_are_ratios_of_the_vehicle_s_velocity_scale() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios/fig-25-26.toml");
        let sc = Scenario::load(&path).unwrap();
        let twin = Scenario::load_with(
            &path,
            &[
                ("similarity.length", 6.0),
                ("similarity.mass", 216.0),
                ("similarity.time", 6.0),
            ],
        )
        .unwrap();
        // The 1/6-scale model in ft/s: √(32.174 ft/s² · 2.221 ft) = 8.4533 ft/s.
        let v = (32.174f64 * 2.221).sqrt();
        let close = |x: f64, y: f64| (x - y).abs() <= 1e-9 * y.abs();
        let s = Asked::default().settings(&sc).unwrap();
        assert_eq!(s.vh_start, 0.0);
        assert!(close(s.vh_step, DEFAULT_VH_STEP * v), "{s:?}");
        assert!(close(s.vh_max, DEFAULT_VH_MAX * v), "{s:?}");
        assert!(close(s.tolerance, DEFAULT_TOLERANCE * v), "{s:?}");
        assert_eq!(s.scan_step, Some(DEFAULT_SCAN_STEP * s.vh_step), "{s:?}");
        s.validate().unwrap();
        // the Froude twin moves as fast: the same settings in its (the same) velocity unit
        let t = Asked::default().settings(&twin).unwrap();
        for (x, y) in [
            (t.vh_step, s.vh_step),
            (t.vh_max, s.vh_max),
            (t.tolerance, s.tolerance),
            (t.scan_step.unwrap(), s.scan_step.unwrap()),
        ] {
            assert!(close(x, y), "{t:?} {s:?}");
        }
        // what is asked is kept, the scan an eighth of the grid's step (0.25 ft/s on 2 ft/s)
        let asked = Asked {
            vh_start: Some(1.0),
            vh_step: Some(2.0),
            vh_max: Some(30.0),
            tolerance: Some(0.05),
            scan_step: None,
        };
        let expected = settings_from(1.0, 2.0, 30.0, 0.05, Some(0.25));
        assert_eq!(asked.settings(&sc).unwrap(), expected);
        let grid_only = Asked {
            scan_step: Some(0.0),
            ..Asked::default()
        };
        assert_eq!(grid_only.settings(&sc).unwrap().scan_step, None);
    }

    fn settings_from(
        vh_start: f64,
        vh_step: f64,
        vh_max: f64,
        tolerance: f64,
        scan_step: Option<f64>,
    ) -> Settings {
        Settings {
            vh_start,
            vh_step,
            vh_max,
            tolerance,
            scan_step,
        }
    }

    fn settings(vh_step: f64, vh_max: f64, tolerance: f64) -> Settings {
        Settings {
            vh_start: 0.0,
            vh_step,
            vh_max,
            tolerance,
            scan_step: None,
        }
    }

    /// By construction: a landing that overturns exactly when Vh > 3.7 + 0.1·Vv.
    #[test]
    fn bisection_finds_a_boundary_known_by_construction() {
        let settings = settings(1.0, 10.0, 1e-3);
        let landing = |vv: f64, vh: f64| {
            Ok(if vh > 3.7 + 0.1 * vv {
                Outcome::Unstable
            } else {
                Outcome::Stable
            })
        };
        let points = search(&[0.0, 5.0, 10.0], settings, landing, &|| {}).unwrap();
        for p in &points {
            let exact = 3.7 + 0.1 * p.vv;
            let vh = p.vh.unwrap();
            assert!(
                (vh - exact).abs() <= 0.5e-3 + 1e-12,
                "Vv {}: {vh} vs {exact}",
                p.vv
            );
            assert!(p.stable_at.unwrap() <= exact && p.unstable_at.unwrap() > exact);
            assert_eq!(p.transitions.len(), 1);
            assert!(p.transitions[0].resolved);
            assert_eq!(p.transitions[0].vh, p.vh);
        }
        // Never unstable: no boundary; unstable from the start: no stable point. The whole
        // grid (0, 1, ..., 10) is landed either way.
        let never = search(&[1.0], settings, |_, _| Ok(Outcome::Stable), &|| {}).unwrap();
        assert_eq!(
            (never[0].vh, never[0].stable_at, never[0].unstable_at),
            (None, Some(10.0), None)
        );
        assert_eq!(never[0].landings, 11);
        let always = search(&[1.0], settings, |_, _| Ok(Outcome::Unstable), &|| {}).unwrap();
        assert_eq!(
            (always[0].vh, always[0].stable_at, always[0].unstable_at),
            (None, None, Some(0.0))
        );
        assert_eq!(always[0].landings, 11);
        assert!(never[0].transitions.is_empty() && always[0].transitions.is_empty());
    }

    /// Unstable on (10 + s, 14 + s) and above 20 + s (s = 0.1·Vv), stable elsewhere, undecided
    /// exactly at the grid point 17.
    fn non_monotonic(vv: f64, vh: f64) -> Result<Outcome, ValidationError> {
        let s = 0.1 * vv;
        Ok(if vh == 17.0 {
            Outcome::Undecided
        } else if (vh > 10.0 + s && vh < 14.0 + s) || vh > 20.0 + s {
            Outcome::Unstable
        } else {
            Outcome::Stable
        })
    }

    #[test]
    fn every_transition_is_found_whatever_the_step_when_the_grid_resolves_them() {
        let tol = 1e-3;
        let vvs = [0.0, 3.0];
        let ticks = AtomicUsize::new(0);
        let tick = || {
            ticks.fetch_add(1, Ordering::Relaxed);
        };
        let coarse = search(&vvs, settings(1.0, 30.0, tol), non_monotonic, &tick).unwrap();
        let fine = search(&vvs, settings(0.5, 30.0, tol), non_monotonic, &tick).unwrap();
        let landings: usize = coarse.iter().chain(&fine).map(|p| p.landings).sum();
        assert_eq!(
            ticks.load(Ordering::Relaxed),
            landings,
            "one tick per landing"
        );
        for (a, b) in coarse.iter().zip(&fine) {
            assert_eq!(a.vv, b.vv);
            let s = 0.1 * a.vv;
            let exact = [
                (Direction::StableToUnstable, 10.0 + s),
                (Direction::UnstableToStable, 14.0 + s),
                (Direction::StableToUnstable, 20.0 + s),
            ];
            for p in [a, b] {
                assert_eq!(p.transitions.len(), 3, "{p:?}");
                for (t, &(direction, vh)) in p.transitions.iter().zip(&exact) {
                    assert_eq!(t.direction, direction);
                    assert!(t.resolved && t.undecided_at.is_empty());
                    assert!((t.vh.unwrap() - vh).abs() <= 0.5 * tol + 1e-12, "{t:?}");
                    assert!((t.stable_at - t.unstable_at).abs() <= tol);
                    // The stable end is stable and the unstable end unstable.
                    assert_eq!(non_monotonic(p.vv, t.stable_at).unwrap(), Outcome::Stable);
                    assert_eq!(
                        non_monotonic(p.vv, t.unstable_at).unwrap(),
                        Outcome::Unstable
                    );
                }
                // The reported boundary is the lowest stable -> unstable transition.
                assert_eq!(p.vh, p.transitions[0].vh);
                assert_eq!(p.stable_at, Some(p.transitions[0].stable_at));
                assert_eq!(p.unstable_at, Some(p.transitions[0].unstable_at));
                // The undecided grid point is listed, between two stable ones: no transition.
                assert_eq!((p.undecided, &p.undecided_at[..]), (1, &[17.0][..]));
            }
            // The steps agree on every transition to the tolerance.
            assert!((a.vh.unwrap() - b.vh.unwrap()).abs() <= tol);
            for (ta, tb) in a.transitions.iter().zip(&b.transitions) {
                assert_eq!(ta.direction, tb.direction);
                assert!((ta.vh.unwrap() - tb.vh.unwrap()).abs() <= tol);
            }
        }
        // Deterministic, however the landings were scheduled.
        let again = search(&vvs, settings(1.0, 30.0, tol), non_monotonic, &|| {}).unwrap();
        assert_eq!(again, coarse);
    }

    #[test]
    fn undecided_landings_are_counted_and_listed_never_taken_as_stable_or_unstable() {
        let s = settings(1.0, 10.0, 1e-3);
        // Stable up to 3, undecided on [4, 6], unstable from 7: the change lies somewhere in
        // (3, 7) and is not bisected across the undecided points.
        let gap = |_: f64, vh: f64| {
            Ok(match vh {
                v if v < 3.5 => Outcome::Stable,
                v if v < 6.5 => Outcome::Undecided,
                _ => Outcome::Unstable,
            })
        };
        let p = &search(&[2.0], s, gap, &|| {}).unwrap()[0];
        assert_eq!(p.landings, 11, "no bisection across undecided points");
        assert_eq!(
            (p.undecided, &p.undecided_at[..]),
            (3, &[4.0, 5.0, 6.0][..])
        );
        assert_eq!(
            p.transitions,
            vec![Transition {
                direction: Direction::StableToUnstable,
                stable_at: 3.0,
                unstable_at: 7.0,
                vh: None,
                resolved: false,
                undecided_at: vec![4.0, 5.0, 6.0],
                stable_stops: Stops::default(),
                unstable_stops: Stops::default(),
            }]
        );
        assert_eq!(
            (p.vh, p.stable_at, p.unstable_at),
            (None, Some(3.0), Some(7.0))
        );
        // Undecided on top of the grid: neither stable nor unstable, so no boundary and the
        // largest stable point is the last stable one, not vh_max.
        let top = |_: f64, vh: f64| {
            Ok(if vh < 7.5 {
                Outcome::Stable
            } else {
                Outcome::Undecided
            })
        };
        let p = &search(&[2.0], s, top, &|| {}).unwrap()[0];
        assert!(p.transitions.is_empty());
        assert_eq!((p.vh, p.stable_at, p.unstable_at), (None, Some(7.0), None));
        assert_eq!(
            (p.undecided, &p.undecided_at[..]),
            (3, &[8.0, 9.0, 10.0][..])
        );
        // All undecided: nothing stable, nothing unstable.
        let none = search(&[2.0], s, |_, _| Ok(Outcome::Undecided), &|| {}).unwrap();
        assert_eq!((none[0].stable_at, none[0].unstable_at), (None, None));
        assert_eq!((none[0].undecided, none[0].landings), (11, 11));
        // An undecided point below a resolved boundary leaves it alone.
        let low = |_: f64, vh: f64| {
            Ok(if vh == 2.0 {
                Outcome::Undecided
            } else if vh > 5.25 {
                Outcome::Unstable
            } else {
                Outcome::Stable
            })
        };
        let p = &search(&[2.0], s, low, &|| {}).unwrap()[0];
        assert_eq!(p.transitions.len(), 1);
        assert!((p.vh.unwrap() - 5.25).abs() <= 0.5e-3 + 1e-12);
        assert_eq!(p.undecided_at, vec![2.0]);
    }

    #[test]
    fn an_undecided_midpoint_leaves_its_transition_unresolved_with_its_bracket() {
        // Stable up to 5.7, undecided on (5.7, 5.8), unstable from 5.8: grid bracket [5, 6],
        // midpoint 5.5 stable, midpoint 5.75 undecided.
        let landing = |_: f64, vh: f64| {
            Ok(match vh {
                v if v <= 5.7 => Outcome::Stable,
                v if v < 5.8 => Outcome::Undecided,
                _ => Outcome::Unstable,
            })
        };
        let p = &search(&[4.0], settings(1.0, 10.0, 1e-3), landing, &|| {}).unwrap()[0];
        let t = &p.transitions[..];
        assert_eq!(
            t,
            [Transition {
                direction: Direction::StableToUnstable,
                stable_at: 5.5,
                unstable_at: 6.0,
                vh: None,
                resolved: false,
                undecided_at: vec![5.75],
                stable_stops: Stops::default(),
                unstable_stops: Stops::default(),
            }]
        );
        assert_eq!(
            (p.vh, p.stable_at, p.unstable_at),
            (None, Some(5.5), Some(6.0))
        );
        assert_eq!(
            (p.landings, p.undecided, &p.undecided_at[..]),
            (13, 1, &[5.75][..])
        );
    }

    /// Stable up to 11.3, unstable on (11.3, 11.6), stable again up to 12.2, unstable above:
    /// an island narrower than the grid step, next to the change the grid sees.
    fn island(_: f64, vh: f64) -> Result<Outcome, ValidationError> {
        Ok(if (vh > 11.3 && vh < 11.6) || vh > 12.2 {
            Outcome::Unstable
        } else {
            Outcome::Stable
        })
    }

    #[test]
    fn the_scan_finds_an_island_the_grid_steps_over_and_reports_a_band() {
        let tol = 1e-3;
        let grid_only = &search(&[1.0], settings(1.0, 20.0, tol), island, &|| {}).unwrap()[0];
        assert_eq!(grid_only.transitions.len(), 1, "the grid sees one change");
        assert_eq!(grid_only.band, None);
        let scanned = Settings {
            scan_step: Some(0.25),
            ..settings(1.0, 20.0, tol)
        };
        let p = &search(&[1.0], scanned, island, &|| {}).unwrap()[0];
        let exact = [
            (Direction::StableToUnstable, 11.3),
            (Direction::UnstableToStable, 11.6),
            (Direction::StableToUnstable, 12.2),
        ];
        assert_eq!(p.transitions.len(), 3, "{p:?}");
        for (t, (direction, vh)) in p.transitions.iter().zip(exact) {
            assert_eq!(t.direction, direction);
            assert!((t.vh.unwrap() - vh).abs() <= 0.5 * tol + 1e-12, "{t:?}");
        }
        // The boundary is still the lowest stable -> unstable transition, inside its band.
        assert!((p.vh.unwrap() - 11.3).abs() <= 0.5 * tol + 1e-12);
        let band = p.band.unwrap();
        assert_eq!(band.changes, 3);
        assert!(band.from <= 11.3 && band.from > 11.3 - tol);
        assert!(band.to >= 12.2 && band.to < 12.2 + tol);
        // Every landing counted: 21 grid points, the scan of [11, 14] every 0.25 less its
        // grid points (9), and the bisections.
        assert!(p.landings > 30, "{}", p.landings);
    }

    /// Past a strut's capacity above 7.4 (one strut, stop force 1 kN per unit of Vh beyond),
    /// two struts above 10; unstable above 12.2.
    fn bottoming(_: f64, vh: f64) -> Result<Landed, ValidationError> {
        let struts = (vh > 7.4) as usize + (vh > 10.0) as usize;
        Ok(Landed {
            outcome: if vh > 12.2 {
                Outcome::Unstable
            } else {
                Outcome::Stable
            },
            stops: Stops {
                struts_past_capacity: struts,
                peak_stop_force_n: if struts > 0 { 1e3 * (vh - 7.4) } else { 0.0 },
            },
        })
    }

    #[test]
    fn the_first_speed_past_capacity_and_the_safe_envelope_are_found_with_their_stops() {
        let tol = 1e-3;
        let p = &search(&[1.0], settings(1.0, 20.0, tol), bottoming, &|| {}).unwrap()[0];
        let c = p.capacity.unwrap();
        assert!((c.vh.unwrap() - 7.4).abs() <= 0.5 * tol + 1e-12, "{c:?}");
        assert!(c.within_at.unwrap() <= 7.4 && c.past_at > 7.4);
        assert_eq!(c.stops.struts_past_capacity, 1);
        assert!(c.stops.peak_stop_force_n > 0.0 && c.stops.peak_stop_force_n <= 1e3 * tol);
        // Safe up to the capacity, not to the overturn.
        assert_eq!(p.safe.limit, Some(Limit::Capacity));
        assert_eq!(p.safe.safe_to, c.within_at);
        assert_eq!(p.safe.unsafe_at, Some(c.past_at));
        // The overturn's ends say which stops they engaged.
        let t = &p.transitions[0];
        assert!((t.vh.unwrap() - 12.2).abs() <= 0.5 * tol + 1e-12);
        assert_eq!(t.stable_stops.struts_past_capacity, 2);
        assert_eq!(t.unstable_stops.struts_past_capacity, 2);
        assert!((t.unstable_stops.peak_stop_force_n - 1e3 * (t.unstable_at - 7.4)).abs() < 1e-9);
        // Past capacity from the first landing: no bracket; never past: no edge.
        let early = |vv: f64, vh: f64| bottoming(vv, vh + 8.0);
        let p = &search(&[1.0], settings(1.0, 20.0, tol), early, &|| {}).unwrap()[0];
        let c = p.capacity.unwrap();
        assert_eq!((c.within_at, c.past_at, c.vh), (None, 0.0, None));
        assert_eq!((p.safe.safe_to, p.safe.unsafe_at), (None, Some(0.0)));
        let p = &search(&[1.0], settings(1.0, 5.0, tol), bottoming, &|| {}).unwrap()[0];
        assert_eq!(p.capacity, None);
        assert_eq!(
            p.safe,
            SafeEdge {
                safe_to: Some(5.0),
                unsafe_at: None,
                limit: None
            }
        );
    }

    #[test]
    fn bad_settings_are_refused_naming_the_argument() {
        let panics = |_: f64, _: f64| -> Result<Outcome, ValidationError> {
            panic!("no landing with bad settings")
        };
        let cases = [
            (settings(0.0, 10.0, 0.1), "--vh-step"),
            (settings(-1.0, 10.0, 0.1), "--vh-step"),
            (settings(f64::NAN, 10.0, 0.1), "--vh-step"),
            (settings(f64::INFINITY, 10.0, 0.1), "--vh-step"),
            (settings(1.0, 10.0, 0.0), "--tol"),
            (settings(1.0, 10.0, -0.1), "--tol"),
            (settings(1.0, 10.0, f64::NAN), "--tol"),
            (settings(1.0, 10.0, f64::INFINITY), "--tol"),
            (settings(1.0, 1e3, 1e-7), "--tol"), // below 1e-9·1000
            (settings(1.0, -1.0, 0.1), "--vh-max"),
            (settings(1.0, f64::NAN, 0.1), "--vh-max"),
            (settings(1e-3, 100.0, 0.1), "--vh-step"), // 100,001 points
            (settings(1e-300, 1e300, 1e292), "--vh-step"),
            (
                Settings {
                    scan_step: Some(1.0),
                    ..settings(1.0, 10.0, 0.1)
                },
                "--scan-step",
            ),
            (
                Settings {
                    scan_step: Some(0.0),
                    ..settings(1.0, 10.0, 0.1)
                },
                "--scan-step",
            ),
        ];
        for (s, argument) in cases {
            let e = search(&[1.0], s, panics, &|| {}).unwrap_err();
            assert!(
                matches!(e, ValidationError::Setting { argument: a, .. } if a == argument),
                "{s:?}: {e}"
            );
            let message = e.to_string();
            assert!(message.starts_with(argument), "{message}");
            assert!(message.contains("expected"), "{message}");
            assert_eq!(s.validate().unwrap_err().to_string(), message);
        }
        let e = settings(1e-3, 100.0, 0.1)
            .validate()
            .unwrap_err()
            .to_string();
        assert!(e.contains("10000"), "{e}");
        let e = settings(1.0, 1e3, 1e-7).validate().unwrap_err().to_string();
        assert!(e.contains("1e-06"), "{e}");
        // At the limits: accepted.
        assert_eq!(settings(1e-2, 99.99, 0.1).grid().unwrap().len(), 10_000);
        assert!(settings(1.0, 1e3, 1e-6).validate().is_ok());
        let e = search(&[f64::NAN], settings(1.0, 2.0, 0.1), panics, &|| {}).unwrap_err();
        assert!(e.to_string().starts_with("--vv"), "{e}");
    }

    #[test]
    fn the_grid_is_computed_not_accumulated_and_includes_vh_max() {
        // 0.1 + 0.1 + 0.1 > 0.3 and 0.3 / 0.1 < 3: still four points, each i·0.1.
        let g = settings(0.1, 0.3, 0.01).grid().unwrap();
        assert_eq!(g, vec![0.0, 0.1, 0.2, 0.1 * 3.0]);
        let g = Settings {
            vh_start: 1.0,
            vh_step: 0.7,
            vh_max: 3.0,
            tolerance: 0.1,
            scan_step: None,
        }
        .grid()
        .unwrap();
        assert_eq!(g, vec![1.0, 1.7, 1.0 + 2.0 * 0.7]);
        // Just over one step beyond vh_max by less than 1e-9 relative: included.
        let g = settings(1.0, 3.0 - 1e-12, 0.1).grid().unwrap();
        assert_eq!(g.len(), 4);
        let g = settings(2.0, 2.0, 0.1).grid().unwrap();
        assert_eq!(g, vec![0.0, 2.0]);
        assert_eq!(settings(5.0, 0.0, 0.1).grid().unwrap(), vec![0.0]);
    }
}
