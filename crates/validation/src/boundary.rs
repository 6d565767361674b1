//! The report's automatic stability-boundary search (section "Stability criteria"): for each
//! vertical velocity Vv, the horizontal velocities Vh at which the landing changes between
//! stable and unstable.
//!
//! At each Vv the search lands on the whole grid `vh_start + i·vh_step` (i = 0, 1, … up to
//! `vh_max`), then bisects every change of outcome between two neighbouring grid points, in
//! either direction, to the tolerance. Undecided landings are never counted as stable or
//! unstable: they are listed; a change of outcome across undecided grid points, or a bisection
//! whose midpoint ends undecided, is reported as an unresolved bracket. The reported boundary
//! is the lowest stable → unstable transition, so it does not depend on the grid step once the
//! grid resolves every transition.
//!
//! Each landing ends early on the stability decision. Vertical velocities, grid points and
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
    /// Whether the bracket was narrowed to the tolerance. False when undecided grid points lie
    /// between its ends (it was never bisected) or a bisection midpoint ended undecided (the
    /// bracket is the one at that moment).
    pub resolved: bool,
    /// The undecided landings inside the bracket, scenario velocity unit, ascending: the grid
    /// points between its ends, or the bisection midpoint that stopped it; empty if resolved.
    pub undecided_at: Vec<f64>,
}

impl Transition {
    /// The bracket's lower end, scenario velocity unit.
    pub fn lower(&self) -> f64 {
        self.stable_at.min(self.unstable_at)
    }
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
    /// largest grid Vh found stable if none was found unstable, else `None`. Scenario velocity
    /// unit.
    pub stable_at: Option<f64>,
    /// The unstable end of the lowest stable → unstable transition's bracket; without one, the
    /// smallest grid Vh found unstable (`None` if none). Scenario velocity unit.
    pub unstable_at: Option<f64>,
    /// Every transition, in either direction, ascending in Vh.
    pub transitions: Vec<Transition>,
    /// The Vh of every landing that ended undecided (grid points and bisection midpoints),
    /// scenario velocity unit, ascending.
    pub undecided_at: Vec<f64>,
    /// Landings run (grid and bisection).
    pub landings: usize,
    /// Landings that ended undecided (the length of `undecided_at`).
    pub undecided: usize,
}

/// Searches the transitions at each vertical velocity `vvs` (scenario velocity unit, positive
/// down). `landing(vv, vh)` runs one landing to its outcome; `tick` is called after each
/// landing (for a progress bar). The outcome need not be monotonic in Vh: every change between
/// neighbouring grid points is found (changes closer together than the step can hide between
/// two grid points with the same outcome). Refuses bad settings (see [`Settings::validate`])
/// before any landing; of several failed landings, the error is that of the lowest Vv and Vh.
pub fn search<F>(
    vvs: &[f64],
    settings: Settings,
    landing: F,
    tick: &(dyn Fn() + Sync),
) -> Result<Vec<BoundaryPoint>, ValidationError>
where
    F: Fn(f64, f64) -> Result<Outcome, ValidationError> + Sync,
{
    search_streaming(vvs, settings, landing, tick, &|_| ())
}

/// [`search`], handing each point to `found` as soon as it and every point before it (in the
/// order of `vvs`) are found: the points stream in the order of the result, whatever the
/// threads, so that a stream of them is deterministic.
pub fn search_streaming<F>(
    vvs: &[f64],
    settings: Settings,
    landing: F,
    tick: &(dyn Fn() + Sync),
    found: &(dyn Fn(&BoundaryPoint) + Sync),
) -> Result<Vec<BoundaryPoint>, ValidationError>
where
    F: Fn(f64, f64) -> Result<Outcome, ValidationError> + Sync,
{
    let grid = settings.grid()?;
    if let Some(&vv) = vvs.iter().find(|v| !v.is_finite()) {
        return Err(refuse("--vv", "finite descent speeds".into(), vv));
    }
    let run = |vv: f64, vh: f64| -> Result<Outcome, ValidationError> {
        let o = landing(vv, vh)?;
        tick();
        Ok(o)
    };
    // The points found out of order wait here until those before them are found.
    let waiting = std::sync::Mutex::new((0usize, std::collections::BTreeMap::new()));
    let points: Vec<Result<BoundaryPoint, ValidationError>> = vvs
        .par_iter()
        .enumerate()
        .map(|(i, &vv)| {
            let point = at_descent_speed(vv, &grid, settings.tolerance, &|vh| run(vv, vh))?;
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

/// The search at one descent speed `vv` over `grid`.
fn at_descent_speed(
    vv: f64,
    grid: &[f64],
    tolerance: f64,
    land: &(dyn Fn(f64) -> Result<Outcome, ValidationError> + Sync),
) -> Result<BoundaryPoint, ValidationError> {
    let outcomes = in_order(grid.par_iter().map(|&vh| land(vh)).collect())?;
    let mut undecided_at: Vec<f64> = grid
        .iter()
        .zip(&outcomes)
        .filter(|(_, &o)| o == Outcome::Undecided)
        .map(|(&vh, _)| vh)
        .collect();
    let decided: Vec<usize> = (0..grid.len())
        .filter(|&i| outcomes[i] != Outcome::Undecided)
        .collect();
    let mut transitions = Vec::new();
    let mut to_bisect = Vec::new();
    for w in decided.windows(2) {
        let (i, j) = (w[0], w[1]);
        if outcomes[i] == outcomes[j] {
            continue;
        }
        let (direction, stable_at, unstable_at) = if outcomes[i] == Outcome::Stable {
            (Direction::StableToUnstable, grid[i], grid[j])
        } else {
            (Direction::UnstableToStable, grid[j], grid[i])
        };
        let t = Transition {
            direction,
            stable_at,
            unstable_at,
            vh: None,
            resolved: false,
            undecided_at: grid[i + 1..j].to_vec(),
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
            .map(|t| bisect(t, tolerance, land))
            .collect(),
    )?;
    let mut landings = grid.len();
    for (t, n) in bisected {
        landings += n;
        undecided_at.extend_from_slice(&t.undecided_at);
        transitions.push(t);
    }
    transitions.sort_by(|a, b| a.lower().total_cmp(&b.lower()));
    undecided_at.sort_by(f64::total_cmp);
    let (vh, stable_at, unstable_at) = match transitions
        .iter()
        .find(|t| t.direction == Direction::StableToUnstable)
    {
        Some(t) => (t.vh, Some(t.stable_at), Some(t.unstable_at)),
        None => {
            let at = |o: Outcome| grid.iter().zip(&outcomes).filter(move |(_, &x)| x == o);
            let unstable = at(Outcome::Unstable).map(|(&vh, _)| vh).next();
            let stable = at(Outcome::Stable).map(|(&vh, _)| vh).next_back();
            (None, stable.filter(|_| unstable.is_none()), unstable)
        }
    };
    Ok(BoundaryPoint {
        vv,
        vh,
        stable_at,
        unstable_at,
        transitions,
        undecided: undecided_at.len(),
        undecided_at,
        landings,
    })
}

/// Bisects the bracket of `t` (no undecided grid point inside) until it is no wider than
/// `tolerance` or a midpoint ends undecided; returns it with the landings it ran.
fn bisect(
    mut t: Transition,
    tolerance: f64,
    land: &(dyn Fn(f64) -> Result<Outcome, ValidationError> + Sync),
) -> Result<(Transition, usize), ValidationError> {
    let mut landings = 0;
    while (t.unstable_at - t.stable_at).abs() > tolerance {
        let mid = 0.5 * (t.stable_at + t.unstable_at);
        landings += 1;
        match land(mid)? {
            Outcome::Stable => t.stable_at = mid,
            Outcome::Unstable => t.unstable_at = mid,
            Outcome::Undecided => {
                t.undecided_at = vec![mid];
                return Ok((t, landings));
            }
        }
    }
    t.resolved = true;
    t.vh = Some(0.5 * (t.stable_at + t.unstable_at));
    Ok((t, landings))
}

/// A landing closure for [`search`] on the scenario `base` with `overrides` (field path and
/// value in the file's units, [`ScenarioBase::with`]): its vertical velocity set to −vv and
/// its horizontal velocity to vh along the scenario's own horizontal direction (file units),
/// landed by `land` (one engine's run of the changed scenario, to its outcome).
pub fn scenario_landing<'a, L>(
    base: &'a ScenarioBase,
    overrides: &'a [(&'a str, toml::Value)],
    land: L,
) -> Result<impl Fn(f64, f64) -> Result<Outcome, ValidationError> + Sync + 'a, ValidationError>
where
    L: Fn(&Scenario) -> Result<Outcome, RunError> + Sync + 'a,
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
        let sc = base.with(&values)?;
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
    /// What it found.
    pub point: BoundaryPoint,
}

/// The boundary search of the scenario `base` with `overrides` ([`scenario_landing`]) on each
/// of `engines` (in engine order, each once; every one must apply to the scenario), at the
/// descent speeds `vvs`: one point per engine and descent speed, engine by engine, each also
/// handed to `found` as soon as it and those before it are found.
pub fn search_engines(
    base: &ScenarioBase,
    overrides: &[(&str, toml::Value)],
    vvs: &[f64],
    settings: Settings,
    engines: &[Engine],
    tick: &(dyn Fn() + Sync),
    found: &(dyn Fn(&EnginePoint) + Sync),
) -> Result<Vec<EnginePoint>, ValidationError> {
    settings.validate()?;
    let mut engines = engines.to_vec();
    engines.sort();
    engines.dedup();
    let sc = base.with(overrides)?;
    let path = Path::new(base.source());
    for &e in &engines {
        touchdown_registry::require(e, &sc)?;
    }
    let mut points = Vec::new();
    for &engine in &engines {
        let landing = scenario_landing(base, overrides, move |sc: &Scenario| {
            touchdown_registry::land(engine, path, sc, &mut (), None)
                .map(|s| s.outcome)
                .map_err(|f| f.error)
        })?;
        let point = |p: &BoundaryPoint| {
            found(&EnginePoint {
                engine,
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
        points.extend(found.into_iter().map(|point| EnginePoint { engine, point }));
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
}

/// One engine's boundary at one descent speed in SI, its vertical velocity signed as in the
/// scenario files (negative down): the fields of a line of `touchdown boundary --format json`
/// after its envelope (docs/schemas/boundary.schema.json). The fields mean what those of
/// [`BoundaryPoint`] do.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PointSi {
    /// The engine that searched.
    pub engine: &'static str,
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
                })
                .collect(),
            undecided_at_vh_m_s: all(&p.undecided_at),
            landings: p.landings,
            undecided: p.undecided,
        }
    }
}

/// The descent speeds (positive down, as the search takes them) of vertical velocities `vvs`
/// written as in the scenario files (negative down); refuses a vertical velocity that is not
/// negative, naming `argument`.
pub fn descent_speeds(vvs: &[f64], argument: &'static str) -> Result<Vec<f64>, ValidationError> {
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
/// `vvs` (negative down), the grid and the tolerance as given, in the scenario's velocity unit
/// `unit` (`ft/s`, written into each name as `_ft_s`), and the engines.
pub fn options(vvs: &[f64], s: Settings, unit: &str, engines: &[Engine]) -> serde_json::Value {
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
    o.insert("engines".into(), serde_json::json!(engines));
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

    fn settings(vh_step: f64, vh_max: f64, tolerance: f64) -> Settings {
        Settings {
            vh_start: 0.0,
            vh_step,
            vh_max,
            tolerance,
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
