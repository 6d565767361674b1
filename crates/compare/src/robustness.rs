//! The stiff and extreme catalogue (docs/robustness.md): landings generated from the shared
//! scenarios by changing a few fields, run on every engine that applies, each classified as
//! completed (with finite outputs, an energy residual within the scenario's
//! `integrator.energy_tolerance` of the energy scale, strokes within the struts and footpads on
//! their surfaces), stopped or refused
//! with a diagnostic that names the cause, or failed (a run that ended with garbage: the class
//! that must stay empty). For the stiff cases, the largest stable step of each fixed-step method.

use crate::precision::Method;
use crate::{CompareError, Engine};
use serde::Serialize;
use std::path::{Path, PathBuf};
use touchdown_record::{Outcome, Summary};
use touchdown_registry::{land, time_step, RunError};
use touchdown_scenario::{Scenario, ScenarioError};

/// A change to one field of a base scenario (file units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Change {
    /// Set the field to the value.
    Set(&'static str, f64),
    /// Multiply the field by the factor.
    Scale(&'static str, f64),
}

/// A case of the catalogue.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Case {
    /// Short name.
    pub name: &'static str,
    /// What it exercises.
    pub what: &'static str,
    /// Base scenario, relative to `scenarios/`.
    pub base: &'static str,
    /// Changes to the base.
    pub changes: &'static [Change],
    /// A stiff case: the largest stable step of each fixed-step method is measured.
    pub stiff: bool,
}

/// Every honeycomb rate of the gear (onset, backoff and stroke-out on every strut and side)
/// scaled by `k`: the stroke-out rate keeps its ratio to the onset rate.
macro_rules! rates {
    ($k:expr) => {
        &[
            Change::Scale("primary_strut.compression.onset_rate", $k),
            Change::Scale("primary_strut.compression.backoff_rate", $k),
            Change::Scale("primary_strut.compression.stroke_out_rate", $k),
            Change::Scale("secondary_strut.tension.onset_rate", $k),
            Change::Scale("secondary_strut.tension.backoff_rate", $k),
            Change::Scale("secondary_strut.tension.stroke_out_rate", $k),
            Change::Scale("secondary_strut.compression.onset_rate", $k),
            Change::Scale("secondary_strut.compression.backoff_rate", $k),
            Change::Scale("secondary_strut.compression.stroke_out_rate", $k),
        ]
    };
}

const TABLE_I: &str = "table-i-2-2-vv8.toml";

/// The stiff and extreme catalogue (docs/robustness.md).
pub const CATALOGUE: &[Case] = &[
    Case {
        name: "onset-x10",
        what: "honeycomb onset, backoff and stroke-out rates ×10 (Table I 2-2, 8 ft/s)",
        base: TABLE_I,
        changes: rates!(10.0),
        stiff: true,
    },
    Case {
        name: "onset-x100",
        what: "honeycomb rates ×100",
        base: TABLE_I,
        changes: rates!(100.0),
        stiff: true,
    },
    Case {
        name: "onset-x1000",
        what: "honeycomb rates ×1000",
        base: TABLE_I,
        changes: rates!(1000.0),
        stiff: true,
    },
    Case {
        name: "footpad-mass-div10",
        what: "footpad mass ÷10 (Table I 2-2, 8 ft/s)",
        base: TABLE_I,
        changes: &[Change::Scale("footpad.mass", 0.1)],
        stiff: true,
    },
    Case {
        name: "hard-soil",
        what: "soil bearing strength K1, K2 ×100 (soil drop, 10 ft/s)",
        base: "soil-drop.toml",
        changes: &[
            Change::Scale("surface.soil.k1", 100.0),
            Change::Scale("surface.soil.k2", 100.0),
        ],
        stiff: true,
    },
    Case {
        name: "vv-30",
        what: "vertical drop at 30 ft/s (flat ground; every primary bottoms)",
        base: "stroke-out.toml",
        changes: &[Change::Set("touchdown.vertical_velocity", -30.0)],
        stiff: true,
    },
    Case {
        name: "vh-15",
        what: "horizontal velocity 15 ft/s (Table I 2-2, 8 ft/s down)",
        base: TABLE_I,
        changes: &[Change::Set("touchdown.horizontal_velocity[1]", 15.0)],
        stiff: false,
    },
    Case {
        name: "attitude+30",
        what: "pitched +30° (Table I 2-2, 8 ft/s)",
        base: TABLE_I,
        changes: &[Change::Set("touchdown.attitude[0]", 30.0)],
        stiff: false,
    },
    Case {
        name: "attitude-30",
        what: "pitched −30° (Table I 2-2, 8 ft/s)",
        base: TABLE_I,
        changes: &[Change::Set("touchdown.attitude[0]", -30.0)],
        stiff: false,
    },
    Case {
        name: "slope-15",
        what: "15° slope (Table I 2-2, 8 ft/s)",
        base: TABLE_I,
        changes: &[Change::Set("surface.slope", 15.0)],
        stiff: false,
    },
    Case {
        name: "friction-0",
        what: "frictionless sliding footpads (level ground, 8 ft/s down, 6 ft/s across)",
        base: "level-sliding.toml",
        changes: &[Change::Set("surface.friction", 0.0)],
        stiff: false,
    },
    Case {
        name: "friction-1.5",
        what: "sliding friction 1.5 (level ground)",
        base: "level-sliding.toml",
        changes: &[Change::Set("surface.friction", 1.5)],
        stiff: false,
    },
    Case {
        name: "stroke-out-primary",
        what: "every primary strut bottoms (vertical drop at 20 ft/s)",
        base: "stroke-out.toml",
        changes: &[],
        stiff: true,
    },
    Case {
        name: "stroke-out-secondary",
        what: "secondary cartridges 30 % as long: both secondary sides bottom (Table I 2-2, 8 ft/s)",
        base: TABLE_I,
        changes: &[
            Change::Scale("secondary_strut.tension.stages[0].stroke_end", 0.3),
            Change::Scale("secondary_strut.tension.stages[1].stroke_end", 0.3),
            Change::Scale("secondary_strut.compression.stages[0].stroke_end", 0.3),
            Change::Scale("secondary_strut.compression.stages[1].stroke_end", 0.3),
        ],
        stiff: false,
    },
    Case {
        name: "overturn-through-90",
        what: "overturn through θy = 90° (locked footpads, 1-2-1 at 40 ft/s; quaternion attitude on the core)",
        base: "robustness/overturn-through-90.toml",
        changes: &[],
        stiff: true,
    },
];

impl Case {
    /// The case's scenario, built from its base in `scenarios`.
    pub fn scenario(&self, scenarios: &Path) -> Result<(PathBuf, Scenario), CompareError> {
        let path = scenarios.join(self.base);
        let mut overrides = Vec::with_capacity(self.changes.len());
        for change in self.changes {
            let (field, value) = match *change {
                Change::Set(field, v) => (field, v),
                Change::Scale(field, k) => {
                    let v = Scenario::value_at(&path, field)?.ok_or_else(|| {
                        ScenarioError::field(
                            &path.display().to_string(),
                            field,
                            format!("expected a number for case {} to scale", self.name),
                        )
                    })?;
                    (field, v * k)
                }
            };
            overrides.push((field, value));
        }
        let sc = Scenario::load_with(&path, &overrides)?;
        Ok((path, sc))
    }
}

/// How a run of a case ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    /// Ran to its end with a bounded energy balance, finite outputs, strokes within the struts
    /// and footpads on their surfaces.
    Completed,
    /// The engine stopped the run with a diagnostic naming the time, the law and the state.
    Stopped,
    /// The engine refused the case before running it, naming the field or the limit.
    Refused,
    /// Ran to its end with outputs that fail the checks: never acceptable.
    Failed,
    /// The engine could not be set up (its runtime missing, or failing outside the landing):
    /// no verdict on the case.
    Unavailable,
}

/// Largest stroke of a completed run, as a multiple of the strut's capacity (bottoming is an
/// elastic stop at the stroke-out rate: a stroke goes a little past the capacity, never far).
pub const STROKE_BOUND: f64 = 1.2;

/// Deepest footpad penetration into a rigid surface a completed multibody run may show (their
/// contacts are soft), as a fraction of the primary strut's capacity: deeper, the contact
/// moves the strokes by more than the comparison resolves (0.1 mm on the Table I landings,
/// 0.4 mm under bottoming at 30 ft/s, against a capacity of 0.14 m).
pub const PENETRATION_BOUND: f64 = 0.01;

/// The checks of a completed run: `None` if it passes, else what fails.
pub fn implausible(sc: &Scenario, s: &Summary) -> Option<String> {
    let e = &s.energy;
    let numbers = [
        s.t_end_s,
        s.peak_pitch_rate_rad_s,
        s.energy_residual_j,
        e.kinetic_j,
        e.potential_change_j,
        e.honeycomb_dissipated_j,
        e.honeycomb_stored_j,
    ];
    let strokes: Vec<f64> = crate::precision::max_strokes(s).collect();
    if let Some(x) = numbers.iter().chain(&strokes).find(|x| !x.is_finite()) {
        return Some(format!("a non-finite output ({x})"));
    }
    let (scale, bound) = (
        e.guard_scale(sc.energy_floor_j()),
        sc.integrator.energy_tolerance,
    );
    if s.energy_residual_j.abs() > bound * scale {
        return Some(format!(
            "energy residual {:.3e} J beyond {bound} (integrator.energy_tolerance) of the energy scale {scale:.3e} J",
            s.energy_residual_j
        ));
    }
    let primary = sc.primary.compression.capacity();
    let penetration = s
        .engine_settings
        .get("max_footpad_penetration_m")
        .and_then(|x| x.as_f64());
    if let Some(depth) = penetration.filter(|d| *d > PENETRATION_BOUND * primary) {
        return Some(format!(
            "a footpad {depth:.3e} m into its surface, beyond {PENETRATION_BOUND} of the primary strut's capacity {primary:.4} m"
        ));
    }
    let secondary = sc
        .secondary
        .compression
        .capacity()
        .max(sc.secondary.tension.capacity());
    let over = |x: &f64, cap: f64| *x > STROKE_BOUND * cap;
    if s.max_primary_stroke_m.iter().any(|x| over(x, primary))
        || strokes[s.max_primary_stroke_m.len()..]
            .iter()
            .any(|x| over(x, secondary))
    {
        return Some(format!(
            "a stroke beyond {STROKE_BOUND} × its strut's capacity ({primary:.4} m primary, {secondary:.4} m secondary)"
        ));
    }
    None
}

/// One case on one engine.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CaseRun {
    /// The case.
    pub case: &'static str,
    /// The engine.
    pub engine: Engine,
    /// How it ended.
    pub verdict: Verdict,
    /// The diagnostic (stopped, refused, failed).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub message: Option<String>,
    /// Outcome of a run that ended.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub outcome: Option<Outcome>,
    /// Steps of a run that ended.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub steps: Option<u64>,
    /// Energy residual over the energy scale ([`touchdown_record::EnergyReport::scale`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    #[serde(rename = "energy_residual_fraction")]
    pub energy_residual: Option<f64>,
    /// Largest primary stroke over the primary capacity.
    #[serde(skip_serializing_if = "Option::is_none")]
    #[serde(rename = "primary_stroke_over_capacity_fraction")]
    pub primary_stroke_over_capacity: Option<f64>,
}

/// Runs `sc` (built for `case` from `path`) on `engine` and classifies the run.
pub fn classify(case: &'static str, path: &Path, sc: &Scenario, engine: Engine) -> CaseRun {
    let mut run = CaseRun {
        case,
        engine,
        verdict: Verdict::Completed,
        message: None,
        outcome: None,
        steps: None,
        energy_residual: None,
        primary_stroke_over_capacity: None,
    };
    match land(engine, path, sc, &mut (), None) {
        Ok(s) => {
            let e = &s.energy;
            run.outcome = Some(s.outcome);
            run.steps = Some(s.steps);
            run.energy_residual = Some(s.energy_residual_j / e.scale());
            run.primary_stroke_over_capacity = Some(
                s.max_primary_stroke_m.iter().fold(0.0f64, |m, x| m.max(*x))
                    / sc.primary.compression.capacity(),
            );
            if let Some(why) = implausible(sc, &s) {
                run.verdict = Verdict::Failed;
                run.message = Some(why);
            }
        }
        Err(e) => {
            run.verdict = match e.error {
                RunError::Stopped(_) => Verdict::Stopped,
                RunError::Refused(_) => Verdict::Refused,
                RunError::Setup(_) => Verdict::Unavailable,
            };
            run.message = Some(e.to_string());
        }
    }
    run
}

/// The largest stable step of a fixed-step method on a case: from the scenario's own step,
/// doubled while the run completes (up to [`STEP_SEARCH_CEILING`]), or halved until it does
/// (down to [`STEP_SEARCH_FLOOR`]). The result is the largest step of the stable band on that
/// ladder of factors of two (a much larger step may complete again by jumping a stiff phase in
/// one step; that is no stability).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StepSearch {
    /// The case.
    pub case: &'static str,
    /// The method ([`Method::Report`]: dt_max, with DIST scaled alike; the others: the step).
    pub method: Method,
    /// The scenario's own step, s (stated or derived); absent if the method refuses the case.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub default_step_s: Option<f64>,
    /// The largest step that completed, s.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub largest_stable_step_s: Option<f64>,
    /// The next step of the ladder above it, s, and why it did not complete (`None` if the
    /// ceiling completed).
    #[serde(skip_serializing_if = "Option::is_none")]
    #[serde(with = "first_unstable")]
    pub first_unstable: Option<(f64, String)>,
    /// Why the method does not apply to the case at any step (the report's scheme refuses a
    /// quaternion attitude), if it does not; nothing is searched then.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub refused: Option<String>,
}

/// The first unstable step as `{"step_s": ..., "why": ...}` rather than a pair.
mod first_unstable {
    use serde::{Serialize, Serializer};

    #[derive(Serialize)]
    struct FirstUnstable<'a> {
        step_s: f64,
        why: &'a str,
    }

    pub fn serialize<S: Serializer>(v: &Option<(f64, String)>, s: S) -> Result<S::Ok, S::Error> {
        v.as_ref()
            .map(|(step_s, why)| FirstUnstable {
                step_s: *step_s,
                why,
            })
            .serialize(s)
    }
}

/// Largest step of the search, s.
pub const STEP_SEARCH_CEILING: f64 = 2.0e-3;

/// Smallest step of the search, s.
pub const STEP_SEARCH_FLOOR: f64 = 1.0e-6;

/// The case `sc` with `method` at step `dt` (s); the report's scheme scales DIST with dt_max.
fn at_step(sc: &Scenario, method: Method, dt: f64) -> Result<Scenario, ScenarioError> {
    let value = match method {
        Method::Report | Method::Strides => sc.integrator.dt_max / dt,
        _ => dt,
    };
    method.apply(sc, value)
}

/// Whether `method` at step `dt` (s) completes on the case `sc`; else the diagnostic.
fn completes(
    case: &'static str,
    path: &Path,
    sc: &Scenario,
    method: Method,
    dt: f64,
) -> Result<(), String> {
    let scm = at_step(sc, method, dt).map_err(|e| e.to_string())?;
    let run = classify(case, path, &scm, method.engine());
    match run.verdict {
        Verdict::Completed => Ok(()),
        _ => Err(run.message.unwrap_or_default()),
    }
}

/// The step the search of `method` on `sc` starts from, s: the multibody step the scenario
/// states, whether or not its engine accepts it, else the engine's own ([`time_step`]).
fn own_step(method: Method, sc: &Scenario) -> Result<f64, ScenarioError> {
    let stated = match method {
        Method::Rapier => sc.rapier.timestep,
        Method::Mujoco => sc.mujoco.timestep,
        Method::Report | Method::Strides | Method::Rk4 | Method::Dopri5 => None,
    };
    stated.map_or_else(|| time_step(method.engine(), sc), Ok)
}

/// Searches the largest stable step of `method` on the case `sc` (from `path`).
pub fn largest_stable_step(
    case: &'static str,
    path: &Path,
    sc: &Scenario,
    method: Method,
) -> StepSearch {
    let mut search = StepSearch {
        case,
        method,
        default_step_s: None,
        largest_stable_step_s: None,
        first_unstable: None,
        refused: None,
    };
    let default = match own_step(method, sc) {
        Ok(dt) => dt,
        Err(e) => {
            search.refused = Some(e.to_string());
            return search;
        }
    };
    // A method the case's own fields rule out is not a step's failure: no step of the ladder
    // would do. A step the engine refuses for its size (a multibody step too large for the
    // stiffest explicit strut law) is a rung that did not complete: the search goes below it.
    if let Err(e) = at_step(sc, method, default) {
        let mut ladder = std::iter::successors(Some(default * 0.5), |dt| Some(dt * 0.5))
            .take_while(|&dt| dt >= STEP_SEARCH_FLOOR)
            .chain(
                std::iter::successors(Some(default * 2.0), |dt| Some(dt * 2.0))
                    .take_while(|&dt| dt <= STEP_SEARCH_CEILING),
            );
        if !ladder.any(|dt| at_step(sc, method, dt).is_ok()) {
            search.refused = Some(e.to_string());
            return search;
        }
    }
    search.default_step_s = Some(default);
    let mut dt = default;
    match completes(case, path, sc, method, dt) {
        Ok(()) => {
            search.largest_stable_step_s = Some(dt);
            while dt * 2.0 <= STEP_SEARCH_CEILING {
                if let Err(why) = completes(case, path, sc, method, dt * 2.0) {
                    search.first_unstable = Some((dt * 2.0, why));
                    break;
                }
                dt *= 2.0;
                search.largest_stable_step_s = Some(dt);
            }
        }
        Err(why) => {
            search.first_unstable = Some((dt, why));
            while dt * 0.5 >= STEP_SEARCH_FLOOR {
                dt *= 0.5;
                match completes(case, path, sc, method, dt) {
                    Ok(()) => {
                        search.largest_stable_step_s = Some(dt);
                        break;
                    }
                    Err(why) => search.first_unstable = Some((dt, why)),
                }
            }
        }
    }
    search
}

/// The fixed-step methods whose largest stable step is searched.
pub const STEP_METHODS: [Method; 4] = [Method::Report, Method::Rk4, Method::Rapier, Method::Mujoco];

/// The catalogue's results.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Robustness {
    /// Every case on every engine that applies.
    pub runs: Vec<CaseRun>,
    /// The largest stable steps of the stiff cases.
    pub steps: Vec<StepSearch>,
}

/// Runs `cases` (scenarios under `scenarios`) on those of `engines` that apply to each; with
/// `search`, the largest stable step of each stiff case and fixed-step method of those engines.
/// `progress` hears of each run.
pub fn run_catalogue(
    scenarios: &Path,
    cases: &[Case],
    engines: &[Engine],
    search: bool,
    mut progress: impl FnMut(&str),
) -> Result<Robustness, CompareError> {
    let mut out = Robustness {
        runs: Vec::new(),
        steps: Vec::new(),
    };
    for case in cases {
        let (path, sc) = case.scenario(scenarios)?;
        for &engine in engines.iter().filter(|e| sc.applicable_engines.contains(e)) {
            let run = classify(case.name, &path, &sc, engine);
            progress(&format!(
                "{} on {}: {:?}",
                case.name,
                engine.name(),
                run.verdict
            ));
            out.runs.push(run);
        }
        if search && case.stiff {
            for method in STEP_METHODS.into_iter().filter(|m| {
                engines.contains(&m.engine()) && sc.applicable_engines.contains(&m.engine())
            }) {
                let s = largest_stable_step(case.name, &path, &sc, method);
                let found = match (&s.refused, s.largest_stable_step_s) {
                    (Some(_), _) => "refused".to_string(),
                    (None, Some(dt)) => format!("{:.3} µs", dt * 1e6),
                    (None, None) => "none".to_string(),
                };
                progress(&format!(
                    "{} on {}: largest stable step {found}",
                    case.name,
                    method.name()
                ));
                out.steps.push(s);
            }
        }
    }
    Ok(out)
}

/// The catalogue's results as text tables (the cases, then the largest stable steps).
pub fn text(r: &Robustness, cases: &[Case]) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let rows = r.runs.iter().map(|run| {
        vec![
            run.case.to_string(),
            run.engine.name().to_string(),
            format!("{:?}", run.verdict).to_lowercase(),
            run.outcome
                .map(|o| format!("{o:?}").to_lowercase())
                .unwrap_or_default(),
            run.steps.map(|n| n.to_string()).unwrap_or_default(),
            run.energy_residual
                .map(|e| format!("{e:.1e}"))
                .unwrap_or_default(),
            run.primary_stroke_over_capacity
                .map(|x| format!("{x:.2}"))
                .unwrap_or_default(),
            run.message.clone().unwrap_or_default(),
        ]
    });
    s.push_str(&crate::report::text_table(
        &[
            "case",
            "engine",
            "verdict",
            "outcome",
            "steps",
            "energy res",
            "stroke/cap",
            "diagnostic",
        ],
        &[4, 5, 6],
        rows,
    ));
    if !r.steps.is_empty() {
        let _ = writeln!(
            s,
            "\nlargest stable step (from the scenario's own step, doubled or halved, within {STEP_SEARCH_FLOOR} s to {STEP_SEARCH_CEILING} s)"
        );
        for st in &r.steps {
            if let Some(why) = &st.refused {
                let _ = writeln!(s, "{:<22} {:<12} refused: {why}", st.case, st.method.name());
                continue;
            }
            let _ = writeln!(
                s,
                "{:<22} {:<12} default {:>9} {:>12}  first unstable: {}",
                st.case,
                st.method.name(),
                st.default_step_s
                    .map(|dt| format!("{:.3} µs", dt * 1e6))
                    .unwrap_or_default(),
                st.largest_stable_step_s
                    .map(|dt| format!("{:.3} µs", dt * 1e6))
                    .unwrap_or_else(|| "none".into()),
                st.first_unstable
                    .as_ref()
                    .map(|(dt, why)| format!("{:.3} µs: {why}", dt * 1e6))
                    .unwrap_or_else(|| "—".into())
            );
        }
    }
    let _ = writeln!(s, "\ncases");
    for c in cases {
        let _ = writeln!(
            s,
            "{:<22} {}{}",
            c.name,
            c.what,
            if c.stiff { " (stiff)" } else { "" }
        );
    }
    s
}
