//! One landing of a campaign: its values drawn from its own stream, the base scenario with them
//! applied and read back, landed on each of the campaign's engines (its history kept when the
//! campaign asks), its record; and the thread pool landings run on.

use crate::distribution::{scores, Value};
use crate::record::{self, Row};
use crate::spec::Campaign;
use crate::CampaignError;
use std::path::Path;
use touchdown_record::{History, RunError, Summary};
use touchdown_registry::{Engine, EngineFailure};
use touchdown_scenario::{Scenario, ScenarioError};

/// The values landing `landing` draws, one per dispersion.
pub fn draws(campaign: &Campaign, landing: u64) -> Vec<Value> {
    let z = scores(
        campaign.seed,
        landing,
        campaign.dispersions.len(),
        campaign.copula.as_ref(),
    );
    campaign
        .dispersions
        .iter()
        .zip(z)
        .map(|(d, z)| d.distribution.quantile(z, landing))
        .collect()
}

/// One landing: drawn, resolved, read back, landed on each of the campaign's engines; its
/// record. `histories` is the folder for the histories the campaign asks for (a paired
/// campaign's in a folder per engine). An engine that cannot be set up stops the campaign.
pub fn land(
    campaign: &Campaign,
    landing: u64,
    histories: Option<&Path>,
) -> Result<Row, CampaignError> {
    let drawn = draws(campaign, landing);
    let refused_by_all = |applied: &[Value], e: ScenarioError| {
        let refused = RunError::Refused(e);
        let results = vec![Err(&refused); campaign.engines.len()];
        record::row(campaign, landing, applied, &results)
    };
    let sc = match scenario(campaign, &drawn) {
        Ok(sc) => sc,
        Err(e) => return Ok(refused_by_all(&drawn, e)),
    };
    let applied = read_back(campaign, landing, &sc)?;
    let history_dir = histories.filter(|_| campaign.histories.contains(&landing));
    let mut results = Vec::with_capacity(campaign.engines.len());
    for &engine in &campaign.engines {
        if let Err(e) = touchdown_registry::require(engine, &sc) {
            results.push(Err(RunError::Refused(e)));
            continue;
        }
        let dir = history_dir.map(|d| {
            if campaign.paired() {
                d.join(engine.name())
            } else {
                d.to_path_buf()
            }
        });
        let result = match dir {
            Some(dir) => land_with_history(campaign, engine, landing, &sc, &dir)?,
            None => touchdown_registry::land_reusing_runner(
                engine,
                &campaign.scenario_path,
                &sc,
                &mut (),
                None,
            ),
        };
        results.push(outcome(result)?);
    }
    let results: Vec<_> = results.iter().map(Result::as_ref).collect();
    Ok(record::row(campaign, landing, &applied, &results))
}

/// What an engine's run of a landing gives a campaign: its summary or why the landing did not
/// complete (a record), or, when the engine could not be set up, the error that stops the
/// campaign.
pub(crate) fn outcome(
    result: Result<Summary, EngineFailure>,
) -> Result<Result<Summary, RunError>, CampaignError> {
    match result {
        Err(f) if matches!(f.error, RunError::Setup(_)) => Err(CampaignError::Engine(Box::new(f))),
        r => Ok(r.map_err(|f| f.error)),
    }
}

/// The pool of `threads` threads the landings run on (one per core with `None`).
pub(crate) fn pool(threads: Option<usize>) -> Result<rayon::ThreadPool, CampaignError> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .build()
        .map_err(|e| CampaignError::Threads(e.to_string()))
}

/// A landing on `engine` whose history is kept: `dir/landing-N.csv` (the MuJoCo runner writes
/// its own files into `dir/landing-N/`). A history that cannot be written is an error of the
/// campaign's folder (`Err`), not of the engine.
fn land_with_history(
    campaign: &Campaign,
    engine: Engine,
    landing: u64,
    sc: &Scenario,
    dir: &Path,
) -> Result<Result<Summary, EngineFailure>, CampaignError> {
    let store = |path: &Path, message: String| CampaignError::Store {
        path: path.display().to_string(),
        message,
    };
    std::fs::create_dir_all(dir).map_err(|e| store(dir, e.to_string()))?;
    if engine == Engine::Mujoco {
        let own = dir.join(format!("landing-{landing}"));
        std::fs::create_dir_all(&own).map_err(|e| store(&own, e.to_string()))?;
        return Ok(touchdown_registry::land_reusing_runner(
            engine,
            &campaign.scenario_path,
            sc,
            &mut (),
            Some(&own),
        ));
    }
    let path = dir.join(format!("landing-{landing}.csv"));
    let mut history =
        Some(History::create(&path, sc.legs.len()).map_err(|e| store(&path, e.to_string()))?);
    let summary = touchdown_registry::land_reusing_runner(
        engine,
        &campaign.scenario_path,
        sc,
        &mut history,
        None,
    );
    if let Some(h) = history {
        h.finish().map_err(|e| store(&path, e.to_string()))?;
    }
    Ok(summary)
}

/// The scenario of a landing that drew the values `drawn` ([`draws`]): the base with them
/// applied, refused if they are out of their fields' domains or change the vehicle's legs.
pub fn scenario(campaign: &Campaign, drawn: &[Value]) -> Result<Scenario, ScenarioError> {
    campaign
        .base
        .with(&campaign.overrides(drawn))
        .and_then(|sc| same_legs(campaign, sc))
}

/// The scenario, refused if a dispersed value changed its number of legs (the records have a
/// column per leg of the base).
fn same_legs(campaign: &Campaign, sc: Scenario) -> Result<Scenario, ScenarioError> {
    let (n, base) = (sc.legs.len(), campaign.base_scenario.legs.len());
    if n == base {
        return Ok(sc);
    }
    Err(ScenarioError::field(
        &campaign.file,
        "dispersion",
        format!("a dispersed value gives the vehicle {n} legs, the base scenario has {base}: a campaign keeps its vehicle's legs"),
    ))
}

/// The dispersed fields' values as the resolved scenario holds them.
fn read_back(
    campaign: &Campaign,
    landing: u64,
    sc: &Scenario,
) -> Result<Vec<Value>, CampaignError> {
    let held = sc.values_of(campaign.dispersions.iter().map(|d| d.field.as_str()));
    campaign
        .dispersions
        .iter()
        .zip(held)
        .map(|(d, v)| {
            v.as_ref()
                .and_then(Value::from_toml)
                .ok_or_else(|| CampaignError::NotApplied {
                    landing,
                    field: d.field.clone(),
                })
        })
        .collect()
}
