//! `touchdown precision`: a scenario's work-precision study (error against run time).

use crate::args::{Format, PrecisionArgs};
use crate::{load, out, out_file, outln, plots, settings, warn};
use anyhow::{Context, Result};

/// `touchdown precision`: the work-precision study of a scenario.
pub fn precision(args: PrecisionArgs) -> Result<()> {
    let PrecisionArgs {
        scenario,
        set,
        engines,
        repeats,
        rungs,
        format,
        out,
        plot,
    } = args;
    let (scenario, set, engines, out) = (scenario.as_path(), &set.set, &engines, out.as_deref());
    use touchdown_compare::precision::{self, Method};
    if repeats == 0 {
        anyhow::bail!("--repeats: expected at least 1 timed run per rung");
    }
    if rungs == Some(0) {
        anyhow::bail!("--rungs: expected at least 1 rung per ladder");
    }
    let methods: Vec<Method> = Method::ALL
        .into_iter()
        .filter(|m| engines.contains(&m.engine()))
        .collect();
    eprintln!("computing the converged reference ...");
    let sc = load(scenario, set)?.1;
    warn(&sc);
    let planned: usize = (methods.iter())
        .filter(|m| sc.applicable_engines.contains(&m.engine()))
        .map(|m| m.rungs(rungs).len())
        .sum();
    let bar = crate::progress_bar(planned as u64, "rungs");
    let study =
        precision::work_precision_resolved(scenario, &sc, &methods, rungs, repeats, |rung| {
            bar.suspend(|| {
                eprintln!(
                    "  {} {}: {}",
                    rung.method.name(),
                    precision::setting_label(rung.method, rung.value),
                    match (&rung.measured, &rung.failure) {
                        (Some(m), _) =>
                            format!("stroke error {:.3} %", 100.0 * m.errors.max_stroke),
                        (None, f) => format!("failed: {}", f.as_deref().unwrap_or("?")),
                    }
                )
            });
            bar.inc(1);
        })?;
    bar.finish_and_clear();
    let mut options = serde_json::json!({
        "engines": engines,
        "repeats": repeats,
    });
    if let Some(n) = rungs {
        options["rungs"] = n.into();
    }
    let id = touchdown_record::ScenarioId {
        path: study.file.clone(),
        sha256: study.scenario_sha256.clone(),
    };
    let settings = settings(set, options);
    let json = touchdown_record::Document::new("precision", Some(&id), &settings, &study).pretty();
    if let Some(dir) = out {
        let data = out_file(dir, "precision-", scenario, "json")?;
        std::fs::write(&data, &json).with_context(|| format!("cannot write {}", data.display()))?;
        if plot {
            plots::precision(&data, &study.scenario, &data.with_extension("png"))?;
        }
    }
    match format {
        Format::Text => out!("{}", precision::text(&study))?,
        Format::Json => outln!("{json}")?,
    }
    Ok(())
}
