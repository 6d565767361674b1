//! One boundary study as asked, whichever front door asks (the command line, Python, a
//! campaign's outcomes plot): the scenario with its overrides, the vertical velocities, the
//! settings asked, the engines and the end-stop laws. [`Request::resolve`] checks it all once,
//! before any landing, into a [`Study`] that runs the search and writes its documents and text.

use super::document::{self, options};
use super::engines::{search_engines, EnginePoint};
use super::settings::{refuse, Asked, Settings, MAX_GRID_POINTS};
use super::text;
use crate::ValidationError;
use touchdown_record::ScenarioId;
use touchdown_scenario::schema::Engine;
use touchdown_scenario::{Scenario, ScenarioBase};

/// A boundary study as asked.
#[derive(Debug, Clone, Copy)]
pub struct Request<'a> {
    /// The scenario as read, before its overrides.
    pub base: &'a ScenarioBase,
    /// Field overrides: path and value in the file's units ([`ScenarioBase::with`]).
    pub overrides: &'a [(&'a str, toml::Value)],
    /// The vertical velocities searched, as the scenario files write them (negative down),
    /// scenario velocity unit.
    pub vv: &'a [f64],
    /// The argument that gave `vv`, named by an error about it (`--vv`, `vv`).
    pub vv_argument: &'static str,
    /// The grid, tolerance and scan step as asked; the rest are ratios of the vehicle's
    /// velocity scale ([`Asked::settings`]).
    pub asked: Asked,
    /// The engines to search on, each once, in engine order whatever the order given.
    pub engines: &'a [Engine],
    /// The end stops' coefficients of restitution to search with, each set on every strut's
    /// load-stroke diagram; empty: the scenario's own stops, once.
    pub restitutions: &'a [f64],
}

/// A request checked and resolved: what a search of it lands and writes.
#[derive(Debug, Clone)]
pub struct Study<'a> {
    request: Request<'a>,
    scenario: Scenario,
    speeds: Vec<f64>,
    settings: Settings,
    engines: Vec<Engine>,
}

impl<'a> Request<'a> {
    /// Checks the request before any landing: the vertical velocities, the scenario with its
    /// overrides, the settings, the restitutions in [0, 1] and every engine applicable to the
    /// scenario; an error names the argument or field at fault.
    pub fn resolve(self) -> Result<Study<'a>, ValidationError> {
        let speeds = descent_speeds(self.vv, self.vv_argument)?;
        let scenario = self.base.with(self.overrides)?;
        let settings = self.asked.settings(&scenario)?;
        settings.validate()?;
        if let Some(&e) = (self.restitutions.iter()).find(|e| !(0.0..=1.0).contains(*e)) {
            return Err(refuse(
                "--stop-restitution",
                "coefficients of restitution in [0, 1]".into(),
                e,
            ));
        }
        let mut engines = self.engines.to_vec();
        engines.sort();
        engines.dedup();
        for &e in &engines {
            touchdown_registry::require(e, &scenario)?;
        }
        Ok(Study {
            request: self,
            scenario,
            speeds,
            settings,
            engines,
        })
    }
}

impl Study<'_> {
    /// The scenario with the request's overrides.
    pub fn scenario(&self) -> &Scenario {
        &self.scenario
    }

    /// The settings searched with, scenario velocity unit.
    pub fn settings(&self) -> Settings {
        self.settings
    }

    /// The scenario's velocity unit, as written in tables (`ft/s`).
    pub fn unit(&self) -> String {
        format!("{}/s", self.scenario.file.units.length_label())
    }

    /// The scenario's velocity unit in m/s.
    pub fn velocity(&self) -> f64 {
        self.scenario.units().velocity()
    }

    /// Runs the search on every engine and end-stop law: one point per
    /// engine, law and vertical velocity, in that order; `tick` is called after each landing
    /// and `found` with each point as soon as it and those before it are found.
    pub fn run(
        &self,
        tick: &(dyn Fn() + Sync),
        found: &(dyn Fn(&EnginePoint) + Sync),
    ) -> Result<Vec<EnginePoint>, ValidationError> {
        let r = &self.request;
        search_engines(
            r.base,
            r.overrides,
            &self.scenario,
            &self.speeds,
            self.settings,
            &self.engines,
            r.restitutions,
            tick,
            found,
        )
    }

    /// What the study's documents record of it: the overrides and the options searched with.
    pub fn document_settings(&self) -> serde_json::Value {
        let r = &self.request;
        let options = options(
            r.vv,
            self.settings,
            &self.unit(),
            &self.engines,
            r.restitutions,
        );
        let set = r.overrides.iter().map(|(k, v)| (*k, v));
        touchdown_record::document::settings(set, options)
    }

    /// The scenario as the study's documents name it: its source and content digest.
    pub fn scenario_id(&self) -> ScenarioId {
        ScenarioId::new(self.request.base.source(), &self.scenario)
    }

    /// A point as one line of `touchdown boundary --format json` (JSON Lines): the envelope
    /// naming the scenario `id` ([`Study::scenario_id`]) and the study's `settings`
    /// ([`Study::document_settings`]), each computed once for every line, then the point in SI
    /// ([`EnginePoint::in_si`]).
    pub fn document_line(
        &self,
        point: &EnginePoint,
        id: &ScenarioId,
        settings: &serde_json::Value,
    ) -> String {
        document::document_line(point, self.velocity(), id, settings)
    }

    /// The points as `touchdown boundary --format csv` writes them: one row per transition (one
    /// for a descent speed without any), in SI, the vertical velocity negative down.
    pub fn csv(&self, points: &[EnginePoint]) -> Result<String, ValidationError> {
        document::csv(points, self.velocity())
    }

    /// The points as `touchdown boundary` prints them: a table in the scenario's velocity unit,
    /// each point's transitions, band, capacity edge and undecided landings, and the spread of
    /// the boundary over the end-stop laws when there are several.
    pub fn text(&self, points: &[EnginePoint]) -> String {
        text::table(points, &self.unit(), self.settings)
    }
}

/// The descent speeds (positive down, as the search takes them) of vertical velocities `vvs`
/// written as in the scenario files (negative down); refuses a vertical velocity that is not
/// negative, and none or more than [`MAX_GRID_POINTS`] of them, naming `argument`.
fn descent_speeds(vvs: &[f64], argument: &'static str) -> Result<Vec<f64>, ValidationError> {
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
