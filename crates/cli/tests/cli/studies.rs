//! `validate`, `calibrate`, `precision` and `robustness`: their outputs and refusals.

use super::{temp, touchdown};

#[test]
fn validate_json_carries_every_row_and_the_targets() {
    let out = touchdown(&["validate", "--format", "json", "--report-only"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 8);
    for key in [
        "id",
        "landing",
        "vv_m_s",
        "vh_m_s",
        "strut",
        "experiment_m",
        "analysis_m",
        "ours_m",
        "error_vs_experiment_pct",
        "error_vs_analysis_pct",
        "role",
    ] {
        assert!(rows[0].get(key).is_some(), "row field {key}");
    }
    assert!(v["held_out_ours"]["mean_abs_error_pct"].is_number());
    assert!(v["held_out_report"]["mean_abs_error_pct"].is_number());
    assert!(v["targets"]["held_out_within_10_pct"].is_boolean());
    assert_eq!(v["facts"].as_array().unwrap().len(), 7);
}

/// `touchdown calibrate` writes where it is told: one row for two parameters is refused before
/// any landing, and without `--out DIR` or `--update-tracked` nothing is written (a usage
/// error), so the tracked calibrated vehicle changes only when asked.
#[test]
fn calibrate_refuses_what_its_rows_cannot_determine_and_writes_only_where_told() {
    let out = temp("calibrate-one-row");
    let o = touchdown(&["calibrate", "--rows", "3", "--out", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("1 row(s) cannot determine 2 parameters"),
        "{err}"
    );
    assert!(!out.exists(), "nothing is written on refusal");
    let o = touchdown(&["calibrate"]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("--out"), "{err}");
}

/// `precision` whose reference refinements run past the scenario's budget says which one, how
/// far the ladder got and how to give it more, rather than the engine's stop; `robustness`
/// refuses a case named twice.
#[test]
fn a_reference_past_its_budget_and_a_case_named_twice_are_said_as_such() {
    let o = touchdown(&[
        "precision",
        "scenarios/flat-drop.toml",
        "--engines",
        "core",
        "--set",
        "integrator.max_steps=50000",
        "-q",
    ]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    // The flat drop takes about 33,000 steps at ÷64, the first refinement, and 66,000 at ÷128.
    assert!(
        err.contains("no converged reference within the run budget: refinement 1 (the report's scheme, DIST and dt_max ÷128)")
            && err.contains("--set integrator.max_steps=N (now 50000)"),
        "{err}"
    );
    let o = touchdown(&["robustness", "--cases", "onset-x10,onset-x10"]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("--cases: \"onset-x10\" is named twice"),
        "{err}"
    );
}

/// A campaign whose base is the flat drop (about 33,000 steps at the reference's first
/// refinement), three landings of dispersed descent speed, written into `dir`.
fn flat_drop_campaign(dir: &std::path::Path) -> std::path::PathBuf {
    std::fs::create_dir_all(dir).unwrap();
    let file = dir.join("drops.toml");
    let base = super::root().join("scenarios/flat-drop.toml");
    std::fs::write(
        &file,
        format!(
            "schema_version = 1\nname = \"flat drops\"\ndescription = \"three descent speeds\"\nscenario = {:?}\nengine = \"core\"\nlandings = 3\nseed = 1\nconfidence = 0.9\n\n[[dispersion]]\nfield = \"touchdown.vertical_velocity\"\nunit = \"ft/s\"\ndistribution = \"uniform\"\nmin = -9.0\nmax = -7.0\n",
            base.display().to_string()
        ),
    )
    .unwrap();
    file
}

/// `precision CAMPAIGN --landings 2 --engines core --rungs 2 --repeats 1` and `extra`, its
/// JSON document.
fn mix_of_two(campaign: &std::path::Path, extra: &[&str]) -> serde_json::Value {
    let c = campaign.to_str().unwrap();
    let mut args = vec![
        "precision",
        c,
        "--landings",
        "2",
        "--engines",
        "core",
        "--rungs",
        "2",
        "--repeats",
        "1",
        "--format",
        "json",
        "-q",
    ];
    args.extend(extra);
    let o = touchdown(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    serde_json::from_slice(&o.stdout).unwrap()
}

/// `precision CAMPAIGN --landings N` studies the campaign's first landings together: each has
/// its reference with its resolution, each rung its median and worst error over them (the
/// median never above the worst) and the cheapest rungs per method; the document names the
/// campaign in its settings, not a scenario. A time budget no landing meets ends each ladder
/// at its first rung, after one landing, and leaves that rung out of the cheapest.
#[test]
fn precision_studies_a_campaign_mix() {
    let dir = temp("precision-mix");
    let campaign = flat_drop_campaign(&dir);
    let v = mix_of_two(&campaign, &[]);
    assert_eq!(v["schema"], "touchdown.precision-mix/1");
    assert!(v.get("scenario").is_none());
    assert_eq!(v["settings"]["landings"], 2);
    assert_eq!(v["settings"]["max_landing_time_s"], 5.0);
    assert_eq!(
        (v["landings"].as_u64(), v["referenced"].as_u64()),
        (Some(2), Some(2))
    );
    let references = v["references"].as_array().unwrap();
    assert_eq!(references[1]["landing"], "landing 1");
    for r in references {
        assert!(r["divisor"].as_f64().unwrap() >= 128.0, "{r}");
        assert!(r["resolution_max_stroke_fraction"].as_f64().unwrap() >= 0.0);
    }
    let rungs = v["rungs"].as_array().unwrap();
    assert_eq!(rungs.len(), 8, "four core schemes, two rungs each");
    for r in rungs {
        assert_eq!(
            (r["landings"].as_u64(), r["failed"].as_u64()),
            (Some(2), Some(0)),
            "{r}"
        );
        for spread in ["max_stroke_fraction", "largest_primary_fraction"] {
            let s = &r[spread];
            assert!(
                s["median"].as_f64().unwrap() <= s["worst"].as_f64().unwrap(),
                "{r}"
            );
        }
        assert!(
            r["largest_primary_fraction"]["worst"].as_f64().unwrap() < 0.2,
            "{r}"
        );
    }
    assert_eq!(v["at_error"].as_array().unwrap().len(), 4);
    let v = mix_of_two(&campaign, &["--max-landing-time", "1e-9"]);
    let rungs = v["rungs"].as_array().unwrap();
    assert_eq!(rungs.len(), 4, "one rung of each scheme");
    for r in rungs {
        assert_eq!(r["landings"], 1, "{r}");
        let stopped = r["stopped"].as_str().unwrap();
        assert!(stopped.starts_with("after 1 of 2 landings"), "{stopped}");
    }
    for a in v["at_error"].as_array().unwrap() {
        assert!(
            a.get("median_value").is_none(),
            "a stopped rung is not of the mix: {a}"
        );
    }
}

/// The campaign mix's refusals: a campaign file without `--landings` is named as one, `--set`
/// is refused (a campaign's landings are its file's), and so are more landings than it plans.
#[test]
fn precision_refuses_a_campaign_mix_it_cannot_study() {
    let dir = temp("precision-mix-refusals");
    let campaign = flat_drop_campaign(&dir);
    let c = campaign.to_str().unwrap();
    let o = touchdown(&["precision", c, "--engines", "core", "-q"]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains(
            "is a campaign file, not a scenario: study its first N landings with --landings N"
        ),
        "{err}"
    );
    let o = touchdown(&[
        "precision",
        c,
        "--landings",
        "1",
        "--set",
        "integrator.dist=0.001",
    ]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("--set: a campaign's landings are its file's"),
        "{err}"
    );
    let o = touchdown(&[
        "precision",
        "scenarios/flat-drop.toml",
        "--max-landing-time",
        "1",
    ]);
    assert_eq!(
        o.status.code(),
        Some(2),
        "clap: --max-landing-time requires --landings"
    );
    let o = touchdown(&["precision", c, "--landings", "4"]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("--landings: expected 1 to 3"), "{err}");
}
