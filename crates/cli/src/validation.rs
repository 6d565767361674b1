//! The validation commands: validate, calibrate, sensitivity, boundary.

use anyhow::{bail, Context, Result};
use serde::Serialize;
use std::fmt::Write;
use std::io::IsTerminal;
use std::path::Path;
use touchdown_scenario::schema::Engine;
use touchdown_scenario::Scenario;
use touchdown_validation::boundary::{self, BoundaryPoint, Settings};
use touchdown_validation::reference::{self, Paths, Protocol};
use touchdown_validation::sensitivity::ParameterSensitivity;
use touchdown_validation::table::{Role, Validation};
use touchdown_validation::{calibrate, facts, sensitivity, table};

/// `touchdown validate`.
pub fn validate(root: &Path, json: bool, out: Option<&Path>) -> Result<()> {
    let paths = Paths::new(root);
    let v = table::validate(&paths)?;
    if let Some(dir) = out {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
        std::fs::write(
            dir.join("validation.json"),
            serde_json::to_string_pretty(&v)?,
        )?;
        let run = facts::check(&paths)?;
        std::fs::write(
            dir.join("fig-25-26-series.json"),
            serde_json::to_string(&run.series)?,
        )?;
    }
    if json {
        println!("{}", serde_json::to_string_pretty(&v)?);
    } else {
        print!("{}", validation_text(&v));
    }
    Ok(())
}

fn role(r: Role) -> &'static str {
    match r {
        Role::Calibration => "calibration",
        Role::HeldOut => "held out",
    }
}

/// The validation as a readable table.
pub fn validation_text(v: &Validation) -> String {
    let mut o = String::new();
    let _ = writeln!(
        o,
        "Table I (TN D-7045): maximum compression strokes, in; errors in %"
    );
    let _ = writeln!(o, "row  landing  Vv ft/s  Vh ft/s  strut       experiment  report   ours    vs exp  vs report  role");
    for r in &v.rows {
        let strut = match r.strut {
            reference::Strut::Primary => "primary",
            reference::Strut::Secondary => "secondary",
        };
        let _ = writeln!(
            o,
            "{:>3}  {:<7}  {:>7.1}  {:>7.1}  {:<10}  {:>10.3}  {:>6.3}  {:>6.3}  {:>+7.1}  {:>+9.1}  {}",
            r.id,
            r.landing,
            r.vv_ft_s,
            r.vh_ft_s,
            strut,
            r.experiment_in,
            r.analysis_in,
            r.ours_in,
            r.error_vs_experiment_pct,
            r.error_vs_analysis_pct,
            role(r.role)
        );
    }
    let (a, b) = (&v.held_out_ours, &v.held_out_report);
    let _ = writeln!(o, "\nheld-out rows ({}): |error| vs experiment", a.rows);
    let _ = writeln!(
        o,
        "  ours:              mean {:5.1} %   max {:5.1} %",
        a.mean_abs_error_pct, a.max_abs_error_pct
    );
    let _ = writeln!(
        o,
        "  report's analysis: mean {:5.1} %   max {:5.1} %",
        b.mean_abs_error_pct, b.max_abs_error_pct
    );
    match &v.calibration {
        Some(c) => {
            let rows: Vec<String> = c.rows.iter().map(u32::to_string).collect();
            let _ = writeln!(
                o,
                "calibration: rows {} ({}, objective {:.2e})",
                rows.join(", "),
                c.optimiser,
                c.objective
            );
            for p in &c.parameter {
                let _ = writeln!(o, "  {}: {} -> {:.4}", p.name, p.initial, p.value);
            }
        }
        None => {
            let _ = writeln!(
                o,
                "calibration: none (estimates as reconstructed; every row is held out)"
            );
        }
    }
    let verdict = |ok: bool| if ok { "MET" } else { "NOT MET" };
    let _ = writeln!(o, "\ntargets");
    let _ = writeln!(
        o,
        "  every held-out row within 10 % of experiment:        {}",
        verdict(v.targets.held_out_within_10_pct)
    );
    let _ = writeln!(
        o,
        "  mean held-out error no worse than the report's own: {}",
        verdict(v.targets.mean_no_worse_than_report)
    );
    let _ = writeln!(
        o,
        "\nfigure 25-26 landing: the report's statements beside our run"
    );
    for f in &v.facts {
        let _ = writeln!(
            o,
            "  {:<58} report {:<34} ours {:<12} {}",
            f.fact,
            f.report,
            f.ours,
            if f.agrees { "agrees" } else { "differs" }
        );
    }
    o
}

/// `touchdown calibrate`.
pub fn calibrate(root: &Path, rows: Option<Vec<u32>>) -> Result<()> {
    let paths = Paths::new(root);
    let protocol: Protocol = reference::read(&paths.reference("calibration-protocol.toml"))?;
    let record = calibrate::calibrate(&paths, &protocol, rows.as_deref())?;
    calibrate::write(&paths, &record)?;
    let ids: Vec<String> = record.rows.iter().map(u32::to_string).collect();
    println!(
        "calibrated on Table I rows {} ({}: {} iterations, objective {:.3e})",
        ids.join(", "),
        record.optimiser,
        record.iterations,
        record.objective
    );
    for p in &record.parameter {
        println!("  {}: {} -> {:.6}", p.name, p.initial, p.value);
    }
    println!(
        "wrote scenarios/vehicles/lm-1-6-calibrated.toml and reference/calibration-result.toml"
    );
    Ok(())
}

/// `touchdown sensitivity`.
pub fn sensitivity(root: &Path, fraction: f64, json: bool) -> Result<()> {
    if !(fraction > 0.0 && fraction < 1.0) {
        bail!("--fraction must be in (0, 1), got {fraction}");
    }
    let table = sensitivity::sensitivity(&Paths::new(root), fraction)?;
    if json {
        println!("{}", serde_json::to_string_pretty(&table)?);
    } else {
        print!("{}", sensitivity_text(&table, fraction));
    }
    Ok(())
}

/// The sensitivity table as text: for each parameter, the stroke change of each row at −/+.
pub fn sensitivity_text(table: &[ParameterSensitivity], fraction: f64) -> String {
    let mut o = String::new();
    let pct = 100.0 * fraction;
    let _ = writeln!(o, "stroke change (%) of each Table I row with each estimated parameter at −{pct:.0} % / +{pct:.0} %");
    let mut header = format!("{:<62}", "parameter (value)");
    if let Some(first) = table.first() {
        for r in &first.rows {
            let _ = write!(header, "   row {:<9}", r.id);
        }
    }
    let _ = writeln!(o, "{header}");
    for p in table {
        let mut line = format!("{:<62}", format!("{} ({:.4})", p.parameter, p.value));
        for r in &p.rows {
            let _ = write!(line, "  {:>+6.1}/{:<+6.1}", r.minus_pct, r.plus_pct);
        }
        let _ = writeln!(o, "{line}");
    }
    o
}

/// Parses FROM:TO:STEP.
fn range(spec: &str) -> Result<Vec<f64>> {
    let parts: Vec<f64> = spec
        .split(':')
        .map(|s| s.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .with_context(|| format!("--vv {spec:?}: expected FROM:TO:STEP numbers"))?;
    let [from, to, step] = parts[..] else {
        bail!("--vv {spec:?}: expected FROM:TO:STEP")
    };
    if !(step > 0.0 && to >= from && from >= 0.0) {
        bail!("--vv {spec:?}: expected 0 ≤ FROM ≤ TO and STEP > 0 (descent speeds, positive down)");
    }
    let n = ((to - from) / step + 1e-9).floor() as usize;
    Ok((0..=n).map(|i| from + step * i as f64).collect())
}

/// Output of `touchdown boundary`.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum BoundaryFormat {
    /// Readable table.
    Text,
    /// JSON array.
    Json,
    /// CSV.
    Csv,
}

/// `touchdown boundary`.
pub fn boundary(
    scenario: &Path,
    vv: &str,
    settings: Settings,
    engines: &[Engine],
    format: BoundaryFormat,
    plot: Option<&Path>,
) -> Result<()> {
    let vvs = range(vv)?;
    if !(settings.vh_step > 0.0 && settings.tolerance > 0.0 && settings.vh_max >= settings.vh_start)
    {
        bail!("expected --vh-step > 0, --tol > 0 and --vh-max ≥ --vh-start");
    }
    let mut engines = engines.to_vec();
    engines.sort();
    engines.dedup();
    let sc = Scenario::load(scenario)?;
    for &e in &engines {
        sc.require_engine(e)?;
    }
    let bar = if std::io::stderr().is_terminal() {
        let b = indicatif::ProgressBar::new(0);
        b.set_message("landings");
        b
    } else {
        indicatif::ProgressBar::hidden()
    };
    let tick = || bar.inc(1);
    let mut points = Vec::new();
    for &engine in &engines {
        let landing = boundary::scenario_landing(scenario, move |sc: &Scenario| {
            touchdown_compare::run(engine, scenario, sc).map(|r| r.summary.outcome)
        })?;
        let found = boundary::search(&vvs, settings, landing, &tick)?;
        points.extend(found.into_iter().map(|point| EnginePoint { engine, point }));
    }
    bar.finish_and_clear();
    let vunit = format!("{}/s", sc.file.units.length_label());
    let json = serde_json::to_string_pretty(&points)?;
    match format {
        BoundaryFormat::Json => println!("{json}"),
        BoundaryFormat::Csv => print!("{}", boundary_csv(&points)?),
        BoundaryFormat::Text => print!("{}", boundary_text(&points, &vunit, settings)),
    }
    if let Some(png) = plot {
        let title = format!("{}\nstability boundary per engine", sc.file.name);
        crate::plots::boundaries(&json, &title, &vunit, png)?;
    }
    Ok(())
}

/// One engine's boundary at one descent speed.
#[derive(Serialize)]
struct EnginePoint {
    engine: Engine,
    #[serde(flatten)]
    point: BoundaryPoint,
}

fn opt(x: Option<f64>) -> String {
    x.map(|v| format!("{v:.3}")).unwrap_or_else(|| "—".into())
}

fn boundary_text(points: &[EnginePoint], unit: &str, s: Settings) -> String {
    let mut o = String::new();
    let _ = writeln!(o, "stability boundary: horizontal velocity at which the landing turns unstable ({unit}; tolerance {})", s.tolerance);
    let _ = writeln!(
        o,
        "  engine   descent Vv   boundary Vh   stable at   unstable at   landings   undecided"
    );
    for EnginePoint { engine, point: p } in points {
        let _ = writeln!(
            o,
            "  {:<6}   {:>10.3}   {:>11}   {:>9}   {:>11}   {:>8}   {:>9}",
            engine.name(),
            p.vv,
            opt(p.vh),
            opt(p.stable_at),
            opt(p.unstable_at),
            p.landings,
            p.undecided
        );
    }
    let _ = writeln!(
        o,
        "(— : stable up to Vh = {} with no overturn, or unstable already at Vh = {})",
        s.vh_max, s.vh_start
    );
    o
}

fn boundary_csv(points: &[EnginePoint]) -> Result<String> {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record([
        "engine",
        "vv_descent",
        "vh_boundary",
        "vh_stable",
        "vh_unstable",
        "landings",
        "undecided",
    ])?;
    let f = |x: Option<f64>| x.map(|v| format!("{v}")).unwrap_or_default();
    for EnginePoint { engine, point: p } in points {
        w.write_record([
            engine.name().to_string(),
            format!("{}", p.vv),
            f(p.vh),
            f(p.stable_at),
            f(p.unstable_at),
            p.landings.to_string(),
            p.undecided.to_string(),
        ])?;
    }
    Ok(String::from_utf8(w.into_inner()?)?)
}
