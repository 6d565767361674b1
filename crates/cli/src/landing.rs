//! `touchdown run`: one landing on one engine.

use crate::args::{Format, RunArgs};
use crate::{load, out, outln, report, settings, warn};
use anyhow::{Context, Result};
use std::path::Path;
use touchdown_record::History;
use touchdown_scenario::schema::Engine;

/// `touchdown run`: one landing on one engine, its summary on standard output and, with `--out`,
/// summary.json, history.csv and scenario.resolved.toml in that folder (and report.html, the
/// landing's page, with `--report`); with `--rounding`, what the rounding ensemble says of it
/// (its `rounding` field and section).
pub fn run(args: RunArgs) -> Result<()> {
    let RunArgs {
        scenario,
        set,
        format,
        out,
        report: page,
        every,
        engine,
        timestep,
        rounding,
    } = args;
    let (scenario, set, out) = (scenario.as_path(), set.set.as_slice(), out.as_deref());
    if every == Some(0) {
        anyhow::bail!("--every: expected at least 1 (every Nth step's row)");
    }
    let mut sc = load(scenario, set)?.1;
    touchdown_registry::require(engine, &sc)?;
    if let Some(t) = timestep {
        if !(t.is_finite() && t > 0.0) {
            anyhow::bail!("--timestep: expected a positive number of seconds, got {t:e}");
        }
        // In the file's time unit (its [similarity] applied), as the file would state it.
        let step = Some(t / sc.units().time());
        let changed = match engine {
            Engine::Core => anyhow::bail!(
                "--timestep sets the step of a multibody engine; add --engine rapier or --engine mujoco"
            ),
            Engine::Rapier => sc.with_rapier(|r| r.timestep = step),
            Engine::Mujoco => sc.with_mujoco(|m| m.timestep = step),
        };
        sc = changed.with_context(|| format!("--timestep {t:e} s"))?;
    }
    warn(&sc);
    if let Some(dir) = out {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    // The MuJoCo runner writes its own history.csv.
    let mut recorder = match out {
        Some(dir) if engine != Engine::Mujoco => {
            let path = dir.join("history.csv");
            Some(
                History::create(&path, sc.legs.len())
                    .with_context(|| format!("cannot write {}", path.display()))?,
            )
        }
        _ => None,
    };
    let landed = touchdown_registry::land(engine, scenario, &sc, &mut recorder, out)
        .map_err(|f| energy_hint(f, &sc, engine));
    // An engine that refuses the step it was given blames the argument first.
    let summary = match timestep {
        Some(t) => landed.with_context(|| format!("--timestep {t:e} s"))?,
        None => landed?,
    };
    let written = |dir: &Path, name: &str| format!("cannot write {}", dir.join(name).display());
    if let (Some(r), Some(dir)) = (recorder, out) {
        r.finish().with_context(|| written(dir, "history.csv"))?;
    }
    let mut rows = 0;
    if let Some(dir) = out {
        // Every engine has written the same history.csv: one thinning for all.
        let every = every.unwrap_or_else(|| history_every(&sc, &summary));
        rows = touchdown_record::history::decimate(&dir.join("history.csv"), every)
            .with_context(|| written(dir, "history.csv"))?;
        std::fs::write(
            dir.join("scenario.resolved.toml"),
            report::resolved_scenario(&sc),
        )
        .with_context(|| written(dir, "scenario.resolved.toml"))?;
    }
    let mut options = match timestep {
        Some(t) => serde_json::json!({ "timestep_s": t }),
        None => serde_json::json!({}),
    };
    let determinacy = if rounding {
        options["rounding"] = true.into();
        Some(touchdown_compare::rounding::determinacy(
            engine, scenario, &sc,
        )?)
    } else {
        None
    };
    let id = touchdown_record::ScenarioId::new(scenario.display(), &sc);
    let settings = settings(set, options);
    let document =
        touchdown_compare::rounding::run_document(&summary, &id, &settings, determinacy.as_ref());
    if let Some(dir) = out {
        std::fs::write(dir.join("summary.json"), &document)
            .with_context(|| written(dir, "summary.json"))?;
        if page {
            let series = touchdown_view::Series::read(&dir.join("history.csv"))?;
            let html = touchdown_view::landing_page(
                &sc.file.name,
                &scenario.display().to_string(),
                &summary,
                &series,
            );
            std::fs::write(dir.join("report.html"), html)
                .with_context(|| written(dir, "report.html"))?;
        }
    }
    if let Some(dir) = out {
        if !crate::QUIET.load(std::sync::atomic::Ordering::Relaxed) {
            eprintln!(
                "wrote {}: summary.json, history.csv ({rows} rows), scenario.resolved.toml{}",
                dir.display(),
                if page { ", report.html" } else { "" }
            );
        }
    }
    match format {
        Format::Text => {
            out!("{}", report::text(&sc, &summary, set))?;
            if let Some(d) = &determinacy {
                out!("\n{}", touchdown_compare::report::determinacy_text(d))?;
            }
        }
        Format::Json => outln!("{document}")?,
    }
    Ok(())
}

/// The default thinning of history.csv: rows no closer in time than the core's largest step
/// `integrator.dt_max` (scaled with the vehicle, so a row per 0.2 ms on the 1/6-scale model),
/// which is every step on the core and every Nth step on a fixed-step engine whose step is N
/// or more times finer (N = ⌊dt_max / step⌋: 10 for rapier's 20 µs on the 1/6-scale model).
fn history_every(sc: &touchdown_scenario::Scenario, summary: &touchdown_record::Summary) -> usize {
    let step = summary
        .engine_settings
        .get("timestep_s")
        .and_then(serde_json::Value::as_f64);
    match step {
        Some(step) if step > 0.0 => ((sc.integrator.dt_max / step).floor() as usize).max(1),
        _ => 1,
    }
}

/// A core run stopped on the energy balance, followed by the setting that resolves a stiffer
/// mode: a quarter of `integrator.dt_max`, in the file's time unit (a stop loading or
/// unloading, a bottoming strut, resolved by a step too long for it). Any other failure as
/// it is.
fn energy_hint(
    f: touchdown_registry::EngineFailure,
    sc: &touchdown_scenario::Scenario,
    engine: Engine,
) -> anyhow::Error {
    match &f.error {
        touchdown_record::RunError::Stopped(d)
            if engine == Engine::Core && d.law == touchdown_record::Law::EnergyBalance =>
        {
            let dt_max = sc.integrator.dt_max / sc.units().time();
            let hint = format!(
                "a stiffer mode than integrator.dt_max = {} resolves (a strut bottoming onto its stop, or unloading from it): try --set integrator.dt_max={} (in the file's time unit), and see docs/errata.md, \"End stops\"",
                touchdown_scenario::units::short(dt_max),
                touchdown_scenario::units::short(dt_max / 4.0)
            );
            anyhow::anyhow!("{f}\n  {hint}")
        }
        _ => f.into(),
    }
}
