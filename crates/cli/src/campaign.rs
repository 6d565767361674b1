//! `touchdown campaign`: a Monte Carlo campaign of dispersed landings (docs/campaigns.md), its
//! shards, merges and extensions, and its statistics as text or JSON.

use crate::args::{CampaignAction, CampaignArgs, Format};
use crate::{out, outln};
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};
use touchdown_campaign::accuracy::Accuracy;
use touchdown_campaign::fidelity::MultiFidelity;
use touchdown_campaign::paired::{Pair, Report};
use touchdown_campaign::record::Row;
use touchdown_campaign::store::{self, Manifest};
use touchdown_campaign::{Campaign, Statistics};
use touchdown_compare::report::text_table;

/// How a campaign reports on standard output.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Output {
    /// The statistics as text.
    Text,
    /// A landing record per line as each finishes (in landing order), then one line
    /// `{"statistics": ...}`.
    JsonLines,
}

/// `touchdown campaign`: a campaign file run (or a shard of it, or landings added to a finished
/// campaign), or one of its actions (`merge`, `estimate`).
pub fn command(mut args: CampaignArgs) -> Result<()> {
    let output = |f| match f {
        Format::Text => Output::Text,
        Format::Json => Output::JsonLines,
    };
    match (args.action.take(), args.file.take()) {
        (Some(CampaignAction::Merge { parts, out, format }), _) => {
            merge(&parts, &out, output(format))
        }
        (
            Some(CampaignAction::Estimate {
                paired,
                low,
                cost_ratio,
                format,
            }),
            _,
        ) => estimate(&paired, &low, cost_ratio, format == Format::Json),
        (None, Some(file)) => {
            let format = output(args.format);
            run(&file, args, format)
        }
        (None, None) => anyhow::bail!("name a campaign file (docs/campaigns.md)"),
    }
}

/// `touchdown campaign FILE`: runs the campaign (or a shard of it, or landings added to the
/// finished campaign in `out`).
fn run(file: &Path, args: CampaignArgs, output: Output) -> Result<()> {
    let CampaignArgs {
        shard,
        add,
        threads,
        engines,
        out,
        resume,
        plot,
        view,
        ..
    } = args;
    let out = out.as_deref();
    let mut campaign = Campaign::load(file)?;
    if let Some(engines) = engines {
        campaign = campaign.with_engines(engines, "--engines")?;
    }
    if view.is_some() && !campaign.paired() {
        anyhow::bail!("--view: a campaign on one engine has no disagreements to watch; name several engines (--engines core,rapier)");
    }
    crate::warn(&campaign.base_scenario);
    if threads == Some(0) {
        anyhow::bail!("--threads: expected at least 1 thread");
    }
    let planned = match (add, shard) {
        (Some(0), _) => anyhow::bail!("--add: expected at least 1 landing to add"),
        (Some(_), Some(_)) => anyhow::bail!(
            "--add and --shard: add landings to a finished (merged) campaign, then shard a new campaign file if it is large"
        ),
        (Some(more), None) => more,
        (None, Some(s)) => {
            let r = s.range(campaign.landings);
            r.end - r.start
        }
        (None, None) => campaign.landings,
    };
    crate::signals::say_when_stopped(match out {
        Some(dir) => format!(
            "\ntouchdown: stopped by a signal. The records of the landings that finished are kept in {}; this goes on from them:\n  {}\n",
            touchdown_campaign::folder::staging_dir(dir)?.display(),
            crate::signals::resume_command()
        ),
        None => "\ntouchdown: stopped by a signal. Nothing is kept: without --out the campaign is written nowhere.\n".into(),
    });
    let bar = crate::progress_bar(planned, "landings");
    let columns = touchdown_campaign::record::columns(&campaign);
    // The first error writing the records ends the command once the landings have run.
    let mut unwritten = None;
    let mut each = |row: &Row| {
        bar.inc(1);
        if output == Output::JsonLines && unwritten.is_none() {
            unwritten = outln!("{}", store::json_line(&columns, row)).err();
        }
    };
    let (manifest, statistics) = match add {
        Some(more) => {
            let dir = out.context("--add: name the finished campaign's folder with --out")?;
            touchdown_campaign::add(&campaign, dir, more, threads, resume, &mut each)?
        }
        None => touchdown_campaign::run::run(&campaign, shard, threads, out, resume, &mut each)?,
    };
    bar.finish_and_clear();
    if let Some(e) = unwritten {
        return Err(e);
    }
    if let (Some(k), Some(dir), Report::Paired(p)) = (view, out, &statistics) {
        views(&campaign, dir, &p.pairs[0], k)?;
    }
    if let (true, Some(dir), Report::Paired(_)) = (plot, out, &statistics) {
        crate::plots::paired(dir)?;
    } else if let (true, Some(dir)) = (plot, out) {
        touchdown_campaign::boundary::write(&campaign, dir, &manifest, statistics.first(), || {
            eprintln!("the engine's boundary of the base configuration, for the plot ...")
        })?;
        crate::plots::campaign(dir)?;
    }
    report(&manifest, &statistics, output)
}

/// The first `k` landings `pair` lists as disagreeing most, each landed again on every engine of
/// the campaign from its scenario file and written as the page that plays them,
/// `dir/views/landing-N.html` with its trajectory file.
fn views(campaign: &Campaign, dir: &Path, pair: &Pair, k: usize) -> Result<()> {
    let pages = dir.join("views");
    for w in pair.worst.iter().take(k) {
        let path = dir.join(&w.scenario_file);
        let sc = touchdown_scenario::Scenario::load(&path)?;
        let interval = touchdown_view::DEFAULT_FRAME_INTERVAL;
        let (runs, _) = touchdown_compare::watch(&path, &sc, &campaign.engines, interval)?;
        let (_, page) = crate::view::write(&pages, (&path, &sc, &[]), &runs, interval)?;
        eprintln!("landing {}: {}", w.landing, page.display());
    }
    Ok(())
}

/// `touchdown campaign merge DIR... --out DIR`.
pub fn merge(parts: &[PathBuf], out: &Path, output: Output) -> Result<()> {
    let parts: Vec<&Path> = parts.iter().map(PathBuf::as_path).collect();
    // The first error writing the records ends the command once the merge is complete.
    // The records' columns are the parts' (the merge refuses parts whose manifests differ).
    let columns = (parts.first())
        .and_then(|p| store::read_manifest(p).ok())
        .map(|m| m.columns)
        .unwrap_or_default();
    let mut unwritten = None;
    let each = |row: &Row| {
        if output == Output::JsonLines && unwritten.is_none() {
            unwritten = outln!("{}", store::json_line(&columns, row)).err();
        }
    };
    let (manifest, statistics) = touchdown_campaign::merge(&parts, out, each)?;
    if let Some(e) = unwritten {
        return Err(e);
    }
    report(&manifest, &statistics, output)
}

fn report(manifest: &Manifest, statistics: &Report, output: Output) -> Result<()> {
    match output {
        Output::JsonLines => outln!(
            "{}",
            serde_json::to_string(&serde_json::json!({ "statistics": statistics }))?
        )?,
        Output::Text => out!("{}", text(manifest, statistics))?,
    }
    Ok(())
}

/// A percentage with its sign-free unit.
fn percent(x: f64) -> String {
    format!("{:.2} %", 100.0 * x)
}

/// The statistics as text: of the one engine, or of each engine of a paired campaign and of
/// each pair.
pub fn text(m: &Manifest, report: &Report) -> String {
    let mut t = header(m);
    t += &accuracy_text(m);
    match report {
        Report::One(s) => t += &engine_text(s),
        Report::Paired(p) => {
            for e in &p.engines {
                t += &format!("== {} ==\n", e.engine);
                t += &engine_text(&e.statistics);
                t += "\n";
            }
            for pair in &p.pairs {
                t += &pair_text(pair, p.landings, p.confidence);
            }
        }
    }
    t
}

/// What ran: the campaign, its base scenario, engines, seed and landings.
fn header(m: &Manifest) -> String {
    let part = match &m.part.shard {
        Some(k) if m.part.first_landing == m.part.end_landing => {
            format!("shard {k}: no landings (of {})", m.landings)
        }
        Some(k) => format!(
            "shard {k}: landings {} to {} of {}",
            m.part.first_landing,
            m.part.end_landing.saturating_sub(1),
            m.landings
        ),
        None => format!("{} landings", m.landings),
    };
    format!(
        "campaign: {} ({})\nbase scenario: {}\n{}: {}   seed: {}   {part}\n\n",
        m.campaign_name,
        m.campaign_file,
        m.base_scenario_file,
        if m.engines.len() > 1 {
            "engines (paired)"
        } else {
            "engine"
        },
        m.engines.join(", "),
        m.seed
    )
}

/// The accuracy of the campaign's settings on each engine (docs/campaigns.md, "Accuracy"), a
/// paragraph each.
fn accuracy_text(m: &Manifest) -> String {
    let stated: Vec<&Accuracy> = m.accuracy.iter().chain(&m.multibody_accuracy).collect();
    if stated.is_empty() {
        return if m.part.first_landing > 0 {
            "accuracy of the settings: stated by the part that holds landing 0\n\n".into()
        } else {
            "accuracy of the settings: not measured\n\n".into()
        };
    }
    stated.into_iter().map(engine_accuracy_text).collect()
}

/// The accuracy of the campaign's settings on one engine, as a paragraph.
fn engine_accuracy_text(a: &Accuracy) -> String {
    use touchdown_campaign::accuracy::{Comparison, Worst};
    let n = a.sample_landings;
    let sample = match n {
        1 => "landing 0".to_string(),
        _ => format!("landings 0 to {}", n.saturating_sub(1)),
    };
    let (fine, half) = (a.refinement, a.refinement / 2.0);
    let landings = |list: &[u64]| {
        let list: Vec<String> = list.iter().map(u64::to_string).collect();
        list.join(", ")
    };
    let limits = if a.engine == "core" {
        "every step limit"
    } else {
        "its time step"
    };
    let mut t = format!(
        "accuracy of the settings ({}, {sample}, against runs with {limits} {fine}x finer; in brackets the runs {half}x finer against those, the reference's own spread):\n  outcomes identical on {} of {}",
        a.engine,
        a.outcomes_identical,
        n.saturating_sub(a.not_refined.len() as u64),
    );
    if !a.not_refined.is_empty() {
        t += &format!(
            " (not measured: landing {}, whose settings refined leave their ranges)",
            landings(&a.not_refined)
        );
    }
    if !a.outcomes_differ.is_empty() {
        t += &format!(" (differ: landing {})", landings(&a.outcomes_differ));
    }
    if !a.reference_outcomes_differ.is_empty() {
        t += &format!(
            " [differ: landing {}]",
            landings(&a.reference_outcomes_differ)
        );
    }
    if let Some(b) = &a.outcomes_differ_bound {
        t += &format!(
            "; of the whole campaign, at most {} of the outcomes differ from the refined runs' ({} one-sided confidence)",
            percent(b.fraction),
            percent(b.confidence)
        );
    }
    t += "\n";
    let maxima = |what: &str, count: u64, c: &Option<Comparison>| {
        let w = |w: &Worst, r: &Worst| {
            format!(
                "{} (landing {}) [{} (landing {})]",
                percent(w.fraction),
                w.landing,
                percent(r.fraction),
                r.landing
            )
        };
        match c {
            Some(c) => {
                let (x, r) = (&c.settings, &c.reference);
                format!(
                    "  on the {count} {what}: largest primary stroke within {}, every maximum stroke within {} of its capacity, peak pitch rate within {} of the sample's largest\n",
                    w(&x.largest_primary_stroke, &r.largest_primary_stroke),
                    w(&x.stroke_of_capacity, &r.stroke_of_capacity),
                    w(&x.peak_pitch_rate_of_largest, &r.peak_pitch_rate_of_largest)
                )
            }
            None => format!("  no landing {what}: no maxima compared\n"),
        }
    };
    t += &maxima("all three runs completed", a.compared, &a.maxima);
    t += &maxima("all three runs found stable", a.stable, &a.stable_maxima);
    t + "\n"
}

/// A fraction as a percentage, or "not defined" (of no landings).
fn defined(x: Option<f64>) -> String {
    x.map_or_else(|| "not defined".into(), percent)
}

/// One engine's statistics as text.
fn engine_text(s: &Statistics) -> String {
    let mut t = String::new();
    if s.landings == 0 {
        return "no landings: no probability, count or percentile is defined\n".into();
    }
    let c = percent(s.confidence);
    t += &format!(
        "P(stable landing) = {} ({} of {}); lower bound at {c} confidence (one-sided Clopper-Pearson): {}\n",
        defined(s.stable.fraction),
        s.stable.landings,
        s.landings,
        defined(s.stable.lower_bound)
    );
    t += &format!(
        "P(stable and within every strut's capacity) = {}; lower bound: {}\n\n",
        defined(s.stable_within_capacity.fraction),
        defined(s.stable_within_capacity.lower_bound)
    );
    t += "landings by outcome and by failure mode (each landing has one of each)\n";
    let counts = s
        .outcomes
        .iter()
        .map(|o| vec!["outcome".into(), o.name.clone(), o.landings.to_string()])
        .chain(
            s.failures
                .iter()
                .map(|f| vec!["failure".into(), f.name.clone(), f.landings.to_string()]),
        )
        .chain(
            s.stroke_outs
                .iter()
                .map(|f| vec!["stroked out".into(), f.name.clone(), f.landings.to_string()]),
        );
    t += &text_table(&["", "", "landings"], &[2], counts);
    t += &influence_table(
        "a stable landing",
        s.influence
            .iter()
            .map(|i| (i.column.as_str(), i.correlation_with_stable)),
    );
    t += &format!("\nlandings to show a reliability with no failure at {c} confidence\n");
    t += &text_table(
        &["reliability", "landings"],
        &[0, 1],
        s.zero_failure
            .iter()
            .map(|z| vec![percent(z.reliability), z.landings.to_string()]),
    );
    t += "\npercentiles over the landings that completed: strokes as fractions of their strut's capacity\n(the struts that stroked), primary forces, specific force, stability distance (statistics.json\nhas every strut's force)\n";
    let shown = s.percentiles.iter().filter(|p| {
        (p.column.ends_with("stroke_of_capacity") && p.max > 0.0)
            || !p.column.contains(".secondary_")
    });
    t += &text_table(
        &[
            "quantity (unit in its name)",
            "landings",
            "p50",
            "p90",
            "p99",
            "max",
        ],
        &[1, 2, 3, 4, 5],
        shown.map(|p| {
            vec![
                p.column.clone(),
                p.landings.to_string(),
                format!("{:.4}", p.p50),
                format!("{:.4}", p.p90),
                format!("{:.4}", p.p99),
                format!("{:.4}", p.max),
            ]
        }),
    );
    t += &margins_text(&s.margins);
    t
}

/// The margins: how close the landings came to overturning and to each strut's capacity, and
/// the closest landings' scenario files.
fn margins_text(m: &touchdown_campaign::statistics::Margins) -> String {
    let mut t = String::from(
        "
margins, the least first: the closest approach to overturn (each landing's minimum stability\ndistance, m) and each strut's stroke margin (1 − its largest stroke over its capacity; the\nstruts with the least)\n",
    );
    let rows = m
        .stability_distance
        .iter()
        .chain(m.strokes.iter().take(6))
        .map(|x| {
            vec![
                x.margin.clone(),
                x.landings.to_string(),
                format!("{:.4}", x.min),
                format!("{:.4}", x.p1),
                format!("{:.4}", x.p10),
                format!("{:.4}", x.p50),
                x.landing.to_string(),
            ]
        });
    t += &text_table(
        &[
            "margin",
            "landings",
            "min",
            "p1",
            "p10",
            "p50",
            "landing of min",
        ],
        &[1, 2, 3, 4, 5, 6],
        rows,
    );
    for c in &m.closest {
        t += &format!(
            "closest by {}: landing {} ({} {:.4}), as a scenario: {}\n",
            c.by.replace('_', " "),
            c.landing,
            c.margin,
            c.value,
            c.scenario_file
        );
    }
    t
}

/// The dispersed inputs (applied columns) with their correlation with `what`, strongest first,
/// as a titled table.
fn influence_table<'a>(what: &str, rows: impl Iterator<Item = (&'a str, Option<f64>)>) -> String {
    let title = format!("\ndispersed inputs by their correlation with {what} (point-biserial)\n");
    title
        + &text_table(
            &["input (unit in its name)", "correlation"],
            &[1],
            rows.map(|(column, r)| {
                vec![
                    column.trim_start_matches("applied.").to_string(),
                    r.map_or("not defined".into(), |r| format!("{r:+.3}")),
                ]
            }),
        )
}

/// What a pair of engines says of each other, as text.
fn pair_text(p: &Pair, landings: u64, confidence: f64) -> String {
    let [a, b] = &p.engines;
    let d = &p.disagreement;
    let mut t = format!("== {a} against {b} (B = {b}, A = {a}) ==\n");
    t += &format!(
        "outcomes disagree on {} of {landings} landings: {}; {} interval (two-sided Clopper-Pearson): {} to {}\n",
        d.landings,
        defined(d.fraction),
        percent(confidence),
        defined(d.lower),
        defined(d.upper)
    );
    t += &format!(
        "stable on {a} only: {}; on {b} only: {}; McNemar's exact test of equal P(stable): p = {:.4}\n",
        p.stable_on_a_only, p.stable_on_b_only, p.mcnemar_p_value
    );
    t += "\npaired differences B − A over the landings both measured (primaries and the stability\ndistance; statistics.json has every secondary)\n";
    let shown = p
        .differences
        .iter()
        .filter(|x| !x.column.contains(".secondary_"));
    t += &text_table(
        &[
            "quantity (unit in its name)",
            "landings",
            "p05",
            "p50",
            "p95",
            "max |B − A|",
        ],
        &[1, 2, 3, 4, 5],
        shown.map(|x| {
            vec![
                x.column.clone(),
                x.landings.to_string(),
                format!("{:+.4}", x.p05),
                format!("{:+.4}", x.p50),
                format!("{:+.4}", x.p95),
                format!("{:.4}", x.max_abs),
            ]
        }),
    );
    t += &influence_table(
        "disagreement",
        p.influence
            .iter()
            .map(|i| (i.column.as_str(), i.correlation_with_disagreement)),
    );
    t += "\nthe landings that disagree most (differing outcomes first, then the largest stroke difference)\n";
    t += &text_table(
        &[
            "landing",
            &format!("{a} / {b}"),
            "largest |ΔS| m",
            "strut",
            "scenario file",
        ],
        &[0, 2],
        p.worst.iter().map(|w| {
            vec![
                w.landing.to_string(),
                format!("{} / {}", w.outcomes[0], w.outcomes[1]),
                format!("{:.4}", w.largest_stroke_difference_m),
                w.strut.clone(),
                w.scenario_file.clone(),
            ]
        }),
    );
    t + "\n"
}

/// `touchdown campaign estimate --paired DIR --low DIR`: the multi-fidelity estimate of the
/// expensive engine's probabilities (docs/campaigns.md, "Multi-fidelity estimate").
pub fn estimate(paired: &Path, low: &Path, cost_ratio: Option<f64>, json: bool) -> Result<()> {
    if let Some(r) = cost_ratio.filter(|r| !(r.is_finite() && *r > 0.0)) {
        anyhow::bail!("--cost-ratio: expected a positive number, got {r}");
    }
    let e = touchdown_campaign::fidelity::from_folders(paired, low, cost_ratio)?;
    if json {
        outln!("{}", serde_json::to_string_pretty(&e)?)?;
    } else {
        out!("{}", estimate_text(&e))?;
    }
    Ok(())
}

/// A multi-fidelity estimate as text.
fn estimate_text(e: &MultiFidelity) -> String {
    let mut t = format!(
        "multi-fidelity estimate on {high}: {n} landings paired with {low}, {m} on {low} alone (the same draws)\n\n",
        high = e.high_engine,
        low = e.low_engine,
        n = e.paired_landings,
        m = e.low_landings
    );
    if e.below_min_paired_landings {
        t += &format!(
            "warning: {} paired landings, fewer than the {} at which the intervals were measured to keep their\nconfidence (docs/campaigns.md, \"Multi-fidelity estimate\"): they may cover the probability less often\nthan they say. Pair more landings (--add to the paired campaign).\n\n",
            e.paired_landings, e.min_paired_landings
        );
    }
    let c = percent(e.confidence);
    let interval = |[a, b]: [f64; 2]| format!("{} to {}", percent(a), percent(b));
    let rows = [
        ("P(stable)", &e.stable),
        ("P(stable within capacity)", &e.stable_within_capacity),
    ];
    t += &text_table(
        &[
            "",
            &format!("{} alone", e.high_engine),
            &format!("its {c} interval (Wilson)"),
            "estimate",
            &format!("its {c} interval"),
            "ρ",
            "variance reduction",
            "at equal cost",
        ],
        &[1, 3, 5, 6, 7],
        rows.iter().map(|(name, x)| {
            vec![
                name.to_string(),
                percent(x.high_alone),
                interval(x.high_alone_interval),
                percent(x.estimate),
                interval([x.lower, x.upper]),
                format!("{:.3}", x.correlation),
                format!("{:.2}", x.variance_reduction),
                x.variance_reduction_at_equal_cost
                    .map_or("(give --cost-ratio)".into(), |r| format!("{r:.2}")),
            ]
        }),
    );
    t + "\nThe variance reduction is the high engine alone's variance over the estimate's at the same number of\nhigh landings; at equal cost, against the high engine alone given the cost of the low landings\n(--cost-ratio: a high landing's cost over a low one's).\n"
}
