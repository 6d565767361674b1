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
