//! The validation commands: validate (Table I, cross-validation), calibrate, estimate,
//! sensitivity.

use crate::{out, outln};
use anyhow::{bail, Context, Result};
use std::fmt::Write;
use std::path::Path;
use touchdown_record::Document;
use touchdown_scenario::units::Short;
use touchdown_validation::checkpoint::{self, Checkpoint};
use touchdown_validation::cross_validation::{self, CrossValidation};
use touchdown_validation::reference::{self, FitAccuracy, Paths, Protocol};
use touchdown_validation::sensitivity::ParameterSensitivity;
use touchdown_validation::table::{Role, Validation};
use touchdown_validation::{calibrate, estimate, facts, sensitivity, table};

/// `touchdown validate`: whether the targets are met.
pub fn validate(root: &Path, json: bool, out: Option<&Path>) -> Result<bool> {
    let paths = Paths::new(root);
    let v = table::validate(&paths)?;
    let settings = serde_json::json!({ "protocol": "two-row" });
    let document = Document::new("validate", None, &settings, &v).pretty();
    if let Some(dir) = out {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
        std::fs::write(dir.join("validation.json"), &document)?;
        let run = facts::check(&paths, &[])?;
        let series = Document::new("series", Some(&run.scenario), &settings, &run.series);
        std::fs::write(dir.join("fig-25-26-series.json"), series.line())?;
    }
    if json {
        outln!("{document}")?;
    } else {
        out!("{}", validation_text(&v))?;
    }
    Ok(v.targets.held_out_within_10_pct && v.targets.mean_no_worse_than_report)
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
    let rows = v.rows.iter().map(|r| {
        let strut = match r.strut {
            reference::Strut::Primary => "primary",
            reference::Strut::Secondary => "secondary",
        };
        vec![
            r.id.to_string(),
            r.landing.to_string(),
            format!("{:.1}", r.vv_ft_s),
            format!("{:.1}", r.vh_ft_s),
            strut.to_string(),
            format!("{:.3}", r.experiment_in),
            format!("{:.3}", r.analysis_in),
            format!("{:.3}", r.ours_in),
            format!("{:+.1}", r.error_vs_experiment_pct),
            format!("{:+.1}", r.error_vs_analysis_pct),
            role(r.role).to_string(),
        ]
    });
    o.push_str(&touchdown_compare::report::text_table(
        &[
            "row",
            "landing",
            "Vv ft/s",
            "Vh ft/s",
            "strut",
            "experiment",
            "report",
            "ours",
            "vs exp",
            "vs report",
            "role",
        ],
        &[0, 2, 3, 5, 6, 7, 8, 9],
        rows,
    ));
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
    facts_text(&mut o, &v.facts);
    o
}

/// The figure 25-26 facts as a table: the report's value beside ours, and the tolerance.
fn facts_text(o: &mut String, facts: &[facts::FactCheck]) {
    let rows = facts.iter().map(|f| {
        vec![
            f.fact.clone(),
            f.report.clone(),
            f.ours.clone(),
            f.tolerance.clone(),
            if f.agrees { "agrees" } else { "differs" }.to_string(),
        ]
    });
    o.push_str(&touchdown_compare::report::text_table(
        &["fact", "report", "ours", "tolerance", ""],
        &[],
        rows,
    ));
}

/// `touchdown validate --protocol cv`: whether the target is met.
pub fn cross_validate(root: &Path, json: bool, out: Option<&Path>) -> Result<bool> {
    let paths = Paths::new(root);
    eprintln!("cross-validating: 8 folds, the fit to every row and its profiles (about {} landings: about 70 minutes on 2 cores in a release build) ...", indicatif::HumanCount(cross_validation::LANDINGS_ABOUT));
    let bar = crate::progress_bar(cross_validation::LANDINGS_ABOUT, "landings");
    // With --out, finished work is kept under it, so that a stopped run resumes: the key names
    // this program and every file it reads, so work of another build or other data is redone.
    let checkpoint = match out {
        Some(dir) => {
            let exe = std::env::current_exe().context("cannot find this program's file")?;
            let key = checkpoint::key_of(&[exe, root.join("reference"), root.join("scenarios")])?;
            let c = Checkpoint::new(&dir.join("cross-validation.checkpoint"), key)?;
            let (units, landings) = c.kept();
            if units > 0 {
                bar.suspend(|| {
                    eprintln!(
                        "resuming: {units} finished units of this run ({landings} landings) kept in {}",
                        c.dir().display()
                    )
                });
                bar.inc(landings as u64);
                bar.reset_eta();
            }
            Some(c)
        }
        None => None,
    };
    let cv = cross_validation::cross_validate(&paths, checkpoint.as_ref(), &|| bar.inc(1))?;
    bar.finish_and_clear();
    let settings = serde_json::json!({ "protocol": "cv" });
    let text = Document::new("cross-validation", None, &settings, &cv).pretty();
    if let Some(dir) = out {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
        let path = dir.join("cross-validation.json");
        std::fs::write(&path, &text).with_context(|| format!("cannot write {}", path.display()))?;
    }
    if let Some(c) = checkpoint {
        c.finish()?;
    }
    if json {
        outln!("{text}")?;
    } else {
        out!("{}", cross_validation_text(&cv))?;
    }
    Ok(cv.target_met())
}

/// The cross-validation as a readable report.
pub fn cross_validation_text(cv: &CrossValidation) -> String {
    let mut o = String::new();
    let p = &cv.protocol;
    let _ = writeln!(
        o,
        "Cross-validation over Table I (reference/cross-validation-protocol.toml): leave-one-out, \
         {} parameters fitted to the other {} rows of each fold",
        p.parameter.len(),
        cv.folds.len().saturating_sub(1)
    );
    let _ = writeln!(
        o,
        "every landing on the core with {}",
        match p.scheme {
            Some(scheme) => format!("the {} scheme (the protocol's `scheme`)", scheme.name()),
            None => "each Table I scenario's own scheme".to_string(),
        }
    );
    let _ = writeln!(
        o,
        "strokes in inches; errors (ours or the report's − experiment) / experiment in %; \
         interval: 2.5-97.5 % over the calibration's uncertainty ({} draws)\n",
        p.samples
    );
    let yes = |b: bool| if b { "yes" } else { "no" }.to_string();
    let rows = cv.folds.iter().map(|f| {
        vec![
            f.held_out.to_string(),
            format!("{:.3}", f.experiment_in),
            format!("{:.3}", f.predicted_in),
            format!("{:.3}-{:.3}", f.interval_in[0], f.interval_in[1]),
            format!("{:+.1}", f.error_pct),
            format!("{:.3}", f.report_in),
            format!("{:+.1}", f.report_error_pct),
            yes(f.within_10_pct),
            yes(f.within_interval),
        ]
    });
    o.push_str(&touchdown_compare::report::text_table(
        &[
            "row",
            "experiment in",
            "ours (out of fold) in",
            "interval in",
            "ours %",
            "report in",
            "report %",
            "within 10 %",
            "exp. in interval",
        ],
        &[0, 1, 2, 3, 4, 5, 6],
        rows,
    ));
    for (what, e) in [
        ("every row", &cv.all_rows),
        ("the two-row protocol's held-out rows", &cv.two_row_held_out),
    ] {
        let ids: Vec<String> = e.rows.iter().map(u32::to_string).collect();
        let _ = writeln!(
            o,
            "\n{what} ({}): |error| mean {:.1} %, max {:.1} % (the report's analysis: mean {:.1} %, max {:.1} %)",
            ids.join(", "),
            e.mean_pct,
            e.max_pct,
            e.report_mean_pct,
            e.report_max_pct
        );
    }
    let _ = writeln!(
        o,
        "rows within 10 %: {} of {}; experiment within the interval: {} of {}",
        cv.rows_within_10_pct,
        cv.folds.len(),
        cv.rows_within_interval,
        cv.folds.len()
    );
    let _ = writeln!(
        o,
        "accuracy of the step settings, each fold's prediction at its fit against a run with \
         every step limit {}x finer: {}",
        cv.accuracy.refinement,
        refined_rows(&cv.accuracy)
    );
    let id = &cv.identifiability;
    let _ = writeln!(
        o,
        "\nthe fit to every row ({} iterations, objective {:.3e}; residual variance s² {:.3e}): \
         what Table I determines",
        cv.full_fit.iterations, cv.full_fit.objective, id.residual_variance
    );
    let rows = id.parameters.iter().map(|d| {
        vec![
            d.name.clone(),
            format!("{}", Short(d.value)),
            format!("{}", Short(d.sd)),
            format!("{}", Short(d.prior_sd)),
            format!("{:.2}", d.ratio),
            if d.determined {
                "determined".into()
            } else {
                "NOT determined".into()
            },
        ]
    });
    o.push_str(&touchdown_compare::report::text_table(
        &[
            "parameter (file units)",
            "value",
            "sd",
            "bounds' sd",
            "sd / bounds' sd",
            "by the rows",
        ],
        &[1, 2, 3, 4],
        rows,
    ));
    let sv: Vec<String> = id
        .singular_values
        .iter()
        .map(|v| format!("{}", Short(*v)))
        .collect();
    let _ = writeln!(
        o,
        "singular values of the Jacobian (relative error per unit of each parameter's range): {}",
        sv.join(", ")
    );
    let _ = writeln!(
        o,
        "a parameter is NOT determined when its sd exceeds {} of its bounds' (the rows narrow it by less than that); its value is then the optimiser's end point, not a fit",
        p.determined_ratio
    );
    let _ = writeln!(
        o,
        "profiles (each parameter held over its bounds, the others fitted again): objective, lowest to highest"
    );
    for pr in &cv.profiles {
        let lo = pr.objective.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = pr
            .objective
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max);
        let _ = writeln!(
            o,
            "  {:<62} {} to {} over {} points",
            pr.name,
            Short(lo),
            Short(hi),
            pr.value.len()
        );
    }
    let _ = writeln!(o, "correlations at the fit (|r| ≥ 0.5):");
    let names = &id.parameters;
    for (a, row) in id.correlation.iter().enumerate() {
        for (b, r) in row.iter().enumerate().skip(a + 1) {
            if r.abs() >= 0.5 {
                let _ = writeln!(o, "  {:+.2}  {} ~ {}", r, names[a].name, names[b].name);
            }
        }
    }
    let _ = writeln!(
        o,
        "\nthe figure 25-26 facts (never fitted) at the fit to every row"
    );
    facts_text(&mut o, &cv.facts);
    let verdict = if cv.target_met() { "MET" } else { "NOT MET" };
    let _ = writeln!(
        o,
        "\ntarget (out-of-fold mean below the report's on the two-row protocol's held-out rows, every row within 10 %): {verdict}"
    );
    let _ = writeln!(o, "{} landings", cv.landings);
    o
}

/// Each row of a fit's accuracy `a`: its stroke at the step settings and refined, mm, and the
/// settings' difference from the refined run, %.
fn refined_rows(a: &FitAccuracy) -> String {
    let rows: Vec<String> = (a.row.iter())
        .map(|r| {
            format!(
                "row {} {:.2} mm, {:.2} mm refined ({:+.2} %)",
                r.id,
                1e3 * r.stroke_m,
                1e3 * r.refined_stroke_m,
                100.0 * (r.stroke_m - r.refined_stroke_m) / r.refined_stroke_m
            )
        })
        .collect();
    rows.join("; ")
}

/// `touchdown calibrate`: into `out`, or over the tracked files when `out` is `None`.
pub fn calibrate(root: &Path, rows: Option<Vec<u32>>, out: Option<&Path>) -> Result<()> {
    let paths = Paths::new(root);
    let protocol: Protocol = reference::read(&paths.reference("calibration-protocol.toml"))?;
    let record = calibrate::calibrate(&paths, &protocol, rows.as_deref())?;
    let ids: Vec<String> = record.rows.iter().map(u32::to_string).collect();
    outln!(
        "calibrated on Table I rows {} ({}: {} iterations, objective {:.3e})",
        ids.join(", "),
        record.optimiser,
        record.iterations,
        record.objective
    )?;
    if let Some(a) = &record.accuracy {
        outln!(
            "  the rows at the fit against runs with every step limit {}x finer: {}",
            a.refinement,
            refined_rows(a)
        )?;
    }
    let determined = cross_validation::determination(&paths, &record, &protocol.parameter)?;
    for (p, d) in record.parameter.iter().zip(&determined.parameters) {
        outln!(
            "  {}: {} -> {:.6}  (sd {}, {:.2} of its bounds'; {})",
            p.name,
            p.initial,
            p.value,
            Short(d.sd),
            d.ratio,
            if d.determined {
                "determined by the rows"
            } else {
                "NOT determined by the rows"
            }
        )?;
    }
    let undetermined: Vec<&str> = determined
        .parameters
        .iter()
        .filter(|d| !d.determined)
        .map(|d| d.name.as_str())
        .collect();
    if !undetermined.is_empty() {
        eprintln!(
            "WARNING: Table I rows {} do not determine {}: the optimiser's end point is not a fit \
             (criterion: reference/cross-validation-protocol.toml)",
            ids.join(", "),
            undetermined.join("; ")
        );
        if out.is_none() {
            bail!(
                "--update-tracked: refusing to write parameters the rows do not determine over the \
                 tracked calibrated vehicle; write them to a folder with --out DIR"
            );
        }
    }
    let written = calibrate::write(&paths, &record, out)?;
    outln!(
        "wrote {} and {}",
        written[0].display(),
        written[1].display()
    )?;
    Ok(())
}

/// `touchdown estimate`.
pub fn estimate(root: &Path) -> Result<()> {
    let paths = Paths::new(root);
    let e = estimate::estimate(&paths)?;
    let path = paths.reference("fig-25-26-velocities.toml");
    std::fs::write(&path, estimate::result_text(&e)?)
        .with_context(|| format!("cannot write {}", path.display()))?;
    let b = &e.best;
    let m = &b.measured;
    outln!(
        "figure 25-26 landing: Vv = {:.2} ft/s down, Vh = {:.2} ft/s (objective {:.3}; {} landings, {} failed)",
        b.descent_speed_ft_s, b.horizontal_speed_ft_s, b.objective, e.landings, e.failed
    )?;
    outln!(
        "  within 1 of it ({} landings): Vv {:.2}-{:.2} ft/s, Vh {:.2}-{:.2} ft/s",
        e.within_1,
        e.descent_speed_within_1_ft_s[0],
        e.descent_speed_within_1_ft_s[1],
        e.horizontal_speed_within_1_ft_s[0],
        e.horizontal_speed_within_1_ft_s[1]
    )?;
    outln!(
        "  free flight {:.3} s, downhill strike {:.3} s, pitch rate {:+.2} -> {:+.2} rad/s, second stage {:+.3} ft, {:?}",
        m.free_flight_s,
        m.downhill_strike_s,
        m.pitch_rate_at_strike_rad_s,
        m.pitch_rate_after_rad_s,
        m.second_stage_depth_ft,
        m.outcome
    )?;
    // Named within the project, so the report reads the same on every machine.
    let shown = path.strip_prefix(root).unwrap_or(&path);
    outln!("wrote {}", shown.display())?;
    Ok(())
}

/// `touchdown sensitivity`.
pub fn sensitivity(root: &Path, fraction: f64, json: bool) -> Result<()> {
    if !(fraction > 0.0 && fraction < 1.0) {
        bail!("--fraction must be in (0, 1), got {fraction}");
    }
    let table = sensitivity::sensitivity(&Paths::new(root), fraction)?;
    if json {
        let settings = serde_json::json!({ "fraction": fraction });
        let body = serde_json::json!({ "parameters": table });
        outln!(
            "{}",
            Document::new("sensitivity", None, &settings, &body).pretty()
        )?;
    } else {
        out!("{}", sensitivity_text(&table, fraction))?;
    }
    Ok(())
}

/// The sensitivity table as text: for each parameter (its value in the scenario file's units),
/// the stroke change of each row at −/+.
pub fn sensitivity_text(table: &[ParameterSensitivity], fraction: f64) -> String {
    let mut o = String::new();
    let pct = 100.0 * fraction;
    let _ = writeln!(
        o,
        "stroke change (%) of each Table I row with each estimated parameter at −{pct:.0} % / +{pct:.0} % \
         (values in the scenario file's units)"
    );
    let ids: Vec<String> = table
        .first()
        .map(|p| {
            p.rows
                .iter()
                .map(|r| format!("row {} −/+ %", r.id))
                .collect()
        })
        .unwrap_or_default();
    let mut header = vec!["parameter", "value", "unit"];
    header.extend(ids.iter().map(String::as_str));
    let rows = table.iter().map(|p| {
        let mut row = vec![
            p.parameter.clone(),
            Short(p.value).to_string(),
            p.unit.clone(),
        ];
        row.extend(
            p.rows
                .iter()
                .map(|r| format!("{}/{}", Change(r.minus_pct), Change(r.plus_pct))),
        );
        row
    });
    let right: Vec<usize> = std::iter::once(1).chain(3..header.len()).collect();
    o.push_str(&touchdown_compare::report::text_table(
        &header, &right, rows,
    ));
    for p in table {
        for r in &p.refused {
            let _ = writeln!(
                o,
                "refused: {} × {}: {}",
                p.parameter,
                Short(r.factor),
                r.reason
            );
        }
    }
    o
}

/// A stroke change, %, or "refused" where the scaled value was refused.
struct Change(Option<f64>);

impl std::fmt::Display for Change {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.0 {
            Some(c) => write!(f, "{c:+.1}"),
            None => f.write_str("refused"),
        }
    }
}
