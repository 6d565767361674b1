//! The search on a scenario, landed by each engine asked for: the landing of one point, and
//! the points of every engine and end-stop law.

use super::search::{search_streaming, BoundaryPoint, Landed, RefinedLand, RefinedLanding};
use super::settings::Settings;
use super::speed::SiSpeed;
use crate::ValidationError;
use serde::Serialize;
use std::path::Path;
use touchdown_core::RunError;
use touchdown_scenario::schema::{Engine, ACCURACY_REFINEMENT};
use touchdown_scenario::units::Short;
use touchdown_scenario::{Scenario, ScenarioBase, ScenarioError};

/// A landing closure for [`super::search`] on the scenario `base` with `overrides` (field path and
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
        return Err(ScenarioError::field(
            base.source(),
            "touchdown.horizontal_velocity",
            "expected a non-zero horizontal velocity, whose direction the search runs along \
             (its size is the search's), got zero",
        )
        .into());
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

/// One engine's boundary at one descent speed, its speeds `V` in the scenario's velocity unit
/// as the search finds them; in SI ([`EnginePoint::in_si`]) the fields of a line of
/// `touchdown boundary --format json` after its envelope (docs/schemas/boundary.schema.json).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(bound(serialize = "V: SiSpeed"))]
pub struct EnginePoint<V = f64> {
    /// The engine that searched.
    pub engine: Engine,
    /// The end stops' coefficient of restitution the search set on every strut's load-stroke
    /// diagram (`None`: the scenario's own; left out of a document).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stop_restitution: Option<f64>,
    /// What it found.
    #[serde(flatten)]
    pub point: BoundaryPoint<V>,
}

/// The boundary search of the scenario `base` with `overrides` ([`scenario_landing`]), `sc`
/// being it resolved, on each of `engines` (in engine order, each once, each applicable to the
/// scenario), at the descent speeds `vvs`, once with the scenario's own end stops if
/// `restitutions` is empty, else once per coefficient of restitution in it, set on every
/// strut's load-stroke diagram (`Scenario::strut_diagrams`): one point per engine, restitution
/// and descent speed, in that order, each also handed to `found` as soon as it and those before
/// it are found. The settings and the rest are checked by [`super::Request::resolve`].
#[allow(clippy::too_many_arguments)]
pub(super) fn search_engines(
    base: &ScenarioBase,
    overrides: &[(&str, toml::Value)],
    sc: &Scenario,
    vvs: &[f64],
    settings: Settings,
    engines: &[Engine],
    restitutions: &[f64],
    tick: &(dyn Fn() + Sync),
    found: &(dyn Fn(&EnginePoint) + Sync),
) -> Result<Vec<EnginePoint>, ValidationError> {
    let path = Path::new(base.source());
    let laws: Vec<Option<f64>> = if restitutions.is_empty() {
        vec![None]
    } else {
        restitutions.iter().copied().map(Some).collect()
    };
    let stop_fields = sc
        .strut_diagrams()
        .map(|(diagram, _)| format!("{diagram}.stop_restitution"));
    let mut points = Vec::new();
    for &engine in engines {
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
            // The core's transitions are landed again with every step limit refined
            // (`Integrator::refine`); a multibody engine's step is its own, not refined here.
            let refined_core = match engine {
                Engine::Core => Some(scenario_landing(base, &values, |sc: &Scenario| {
                    let sc = (sc.clone())
                        .with_integrator(|it| it.refine(ACCURACY_REFINEMENT))
                        .map_err(RunError::Refused)?;
                    touchdown_registry::land(Engine::Core, path, &sc, &mut (), None)
                        .map(|s| s.outcome)
                        .map_err(|f| f.error)
                })?),
                _ => None,
            };
            let refined: Option<RefinedLanding> =
                (refined_core.as_ref()).map(|land| (ACCURACY_REFINEMENT, land as RefinedLand));
            let point = |p: &BoundaryPoint| {
                found(&EnginePoint {
                    engine,
                    stop_restitution,
                    point: p.clone(),
                })
            };
            let found = search_streaming(vvs, settings, landing, refined, tick, &point).map_err(
                |e| match e {
                    ValidationError::Run { scenario, source } => ValidationError::Run {
                        scenario: format!("{engine} engine on {scenario}"),
                        source,
                    },
                    other => other,
                },
            )?;
            points.extend(found.into_iter().map(|point| EnginePoint {
                engine,
                stop_restitution,
                point,
            }));
        }
    }
    Ok(points)
}
