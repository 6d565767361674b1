//! `touchdown precision`: a scenario's work-precision study (error against run time).

use crate::args::{Format, PrecisionArgs};
use crate::{load, out, out_file, outln, plots, settings, warn};
use anyhow::{Context, Result};
use std::path::Path;
use touchdown_compare::precision::mix::{self, MixLanding, Progress};
use touchdown_compare::precision::{self, Method};
use touchdown_registry::Engine;

/// `touchdown precision`: the work-precision study of a scenario.
pub fn precision(args: PrecisionArgs) -> Result<()> {
    let PrecisionArgs {
        scenario,
        set,
        landings,
        max_landing_time,
        engines,
        repeats,
        rungs,
        format,
        out,
        plot,
    } = args;
    let (scenario, set, engines, out) = (scenario.as_path(), &set.set, &engines, out.as_deref());
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
    if let Some(n) = landings {
        if !set.is_empty() {
            anyhow::bail!("--set: a campaign's landings are its file's; set the fields in its base scenario or its dispersions, not with --landings");
        }
        if !(max_landing_time > 0.0 && max_landing_time.is_finite()) {
            anyhow::bail!(
                "--max-landing-time: expected a positive number of seconds, got {max_landing_time}"
            );
        }
        let study = Study {
            max_landing_time,
            engines,
            methods: &methods,
            repeats,
            rungs,
            format,
            out,
        };
        return campaign_mix(scenario, n, &study);
    }
    let sc = match load(scenario, set) {
        Ok((_, sc)) => sc,
        Err(_) if touchdown_campaign::Campaign::load(scenario).is_ok() => anyhow::bail!(
            "{} is a campaign file, not a scenario: study its first N landings with --landings N",
            scenario.display()
        ),
        Err(e) => return Err(e),
    };
    eprintln!("computing the converged reference ...");
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

/// The options of a study the campaign mix shares with a scenario's.
struct Study<'a> {
    max_landing_time: f64,
    engines: &'a [Engine],
    methods: &'a [Method],
    repeats: usize,
    rungs: Option<usize>,
    format: Format,
    out: Option<&'a Path>,
}

/// `touchdown precision CAMPAIGN --landings N`: the work-precision study of the campaign's first
/// `n` landings together.
fn campaign_mix(file: &Path, n: u64, study: &Study) -> Result<()> {
    use touchdown_campaign::landing::{draws, scenario};
    let campaign = touchdown_campaign::Campaign::load(file)?;
    if n == 0 || n > campaign.landings {
        anyhow::bail!(
            "--landings: expected 1 to {} (the landings {} plans), got {n}",
            campaign.landings,
            file.display()
        );
    }
    let mut landings = Vec::new();
    for k in 0..n {
        match scenario(&campaign, &draws(&campaign, k)) {
            Ok(sc) => landings.push(MixLanding {
                label: format!("landing {k}"),
                scenario: sc,
            }),
            Err(e) => eprintln!("landing {k} left out: its draws are refused ({e})"),
        }
    }
    let methods: Vec<Method> = (study.methods.iter().copied())
        .filter(|m| campaign.engines.contains(&m.engine()))
        .collect();
    let planned = landings.len()
        + methods
            .iter()
            .map(|m| m.rungs(study.rungs).len())
            .sum::<usize>();
    eprintln!(
        "computing the references of {} landings, then {} rungs over them ...",
        landings.len(),
        planned - landings.len()
    );
    let bar = crate::progress_bar(planned as u64, "references and rungs");
    let result = mix::work_precision_mix(
        &campaign.scenario_path,
        &campaign.name,
        &landings,
        &methods,
        study.rungs,
        study.repeats,
        study.max_landing_time,
        |p| {
            bar.suspend(|| match p {
                Progress::Reference(r) => match (&r.found, &r.failure) {
                    (Some(f), _) => eprintln!(
                        "  {}: reference at ÷{}, resolving the strokes to {:.3} %",
                        r.landing,
                        f.divisor,
                        100.0 * f.resolution_max_stroke
                    ),
                    (None, failure) => eprintln!(
                        "  {}: no reference ({})",
                        r.landing,
                        failure.as_deref().unwrap_or("?")
                    ),
                },
                Progress::Rung(r) => eprintln!(
                    "  {} {}: median stroke error {}",
                    r.method.name(),
                    precision::setting_label(r.method, r.value),
                    (r.max_stroke.as_ref())
                        .map_or("-".into(), |e| format!("{:.3} %", 100.0 * e.median))
                ),
            });
            bar.inc(1);
        },
    );
    bar.finish_and_clear();
    let mut options = serde_json::json!({
        "campaign": file.display().to_string(),
        "landings": n,
        "engines": study.engines,
        "repeats": study.repeats,
        "max_landing_time_s": study.max_landing_time,
    });
    if let Some(r) = study.rungs {
        options["rungs"] = r.into();
    }
    let settings = settings(&[], options);
    let json = touchdown_record::Document::new("precision-mix", None, &settings, &result).pretty();
    if let Some(dir) = study.out {
        let data = out_file(dir, "precision-", file, "json")?;
        std::fs::write(&data, &json).with_context(|| format!("cannot write {}", data.display()))?;
    }
    match study.format {
        Format::Text => out!("{}", mix::text(&result))?,
        Format::Json => outln!("{json}")?,
    }
    Ok(())
}
