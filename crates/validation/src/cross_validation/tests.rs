//! The protocol on stroke laws known in closed form: folds, determination, intervals, resuming.

use super::*;
use crate::reference::{Strut, INCH};

fn row(id: u32, vv: f64, experiment: f64) -> Row {
    Row {
        id,
        landing: "test".into(),
        vv,
        vh: 0.0,
        strut: Strut::Primary,
        experiment,
        analysis: experiment * 1.01,
        scenario: String::new(),
    }
}

fn parameter(name: &str, initial: f64) -> FitParameter {
    FitParameter {
        name: name.into(),
        initial,
        lower: 0.1,
        upper: 10.0,
    }
}

fn protocol(parameter: Vec<FitParameter>) -> CvProtocol {
    CvProtocol {
        folds: Folds::LeaveOneOut,
        max_iterations: 400,
        restart_simplex: 0.25,
        max_restarts: 4,
        restart_improvement: 1e-6,
        jacobian_step: 0.01,
        determined_ratio: 0.5,
        samples: 32,
        seed: 7,
        scheme: None,
        parameter,
    }
}

/// A stroke law known in closed form: s = a·|vv| + b, made exact by construction.
fn linear(x: &[f64], vv: f64) -> f64 {
    x[0] * vv.abs() + x[1]
}

#[test]
fn an_exact_model_is_predicted_out_of_fold_and_its_parameters_are_determined() {
    let truth = [1.5, 2.0];
    let table: Vec<Row> = (1..=6)
        .map(|i| row(i, -(i as f64) - 3.0, linear(&truth, -(i as f64) - 3.0)))
        .collect();
    let predict = |r: &Row, x: &[f64]| Ok(linear(x, r.vv));
    let p = protocol(vec![parameter("a", 1.0), parameter("b", 1.0)]);
    let cv = cross_validate_with(&table, &p, &[1, 2, 3], &predict, (&predict, 8.0), None).unwrap();
    assert_eq!(cv.folds.len(), 6);
    for f in &cv.folds {
        assert!(
            f.error_pct.abs() < 1e-3,
            "row {}: {}",
            f.held_out,
            f.error_pct
        );
    }
    assert!(cv.identifiability.parameters.iter().all(|d| d.determined));
    assert!(
        (cv.full_fit.value[0] - 1.5).abs() < 1e-3 && (cv.full_fit.value[1] - 2.0).abs() < 1e-3,
        "{:?}",
        cv.full_fit
    );
    assert_eq!(cv.two_row_held_out.rows, vec![1, 2, 3]);
    // The report's analysis is 1 % off on every row by construction.
    assert!((cv.all_rows.report_mean_pct - 1.0).abs() < 1e-9);
}

/// Two parameters that enter only through their product, and one that does not enter at
/// all: the rows fix the product, the sum and nothing of the third, and the analysis must
/// say so.
#[test]
fn parameters_the_rows_cannot_separate_are_not_determined() {
    let table: Vec<Row> = (1..=6)
        .map(|i| row(i, -(i as f64), 3.0 * i as f64 + 1.0))
        .collect();
    let predict = |r: &Row, x: &[f64]| Ok(x[0] * x[1] * r.vv.abs() + x[2]);
    let p = protocol(vec![
        parameter("m", 2.0),
        parameter("k", 2.0),
        parameter("c", 2.0),
        parameter("unused", 2.0),
    ]);
    let cv = cross_validate_with(&table, &p, &[1], &predict, (&predict, 8.0), None).unwrap();
    let id = &cv.identifiability;
    let d = &id.parameters;
    assert!(d[2].determined && d[2].ratio < 0.1, "{d:?}");
    assert!(!d[3].determined && d[3].ratio > 0.95, "{d:?}");
    assert!(!(d[0].determined && d[1].determined), "{d:?}");
    // Two directions of the scaled Jacobian are null: the unused parameter, and m against k.
    let s = &id.singular_values;
    assert!(s[2] < 1e-3 * s[0] && s[3] < 1e-3 * s[0], "{s:?}");
    assert!(id.correlation[0][1] < -0.5, "{:?}", id.correlation);
    // Out of fold, the product and the sum are still predicted.
    assert!(cv.all_rows.mean_pct < 1e-2, "{:?}", cv.all_rows);
}

#[test]
fn the_held_out_row_never_enters_its_fold() {
    let table: Vec<Row> = (1..=5)
        .map(|i| row(i, -(i as f64), 2.0 * i as f64 + 0.3 * (i as f64).sin()))
        .collect();
    let predict = |r: &Row, x: &[f64]| Ok(x[0] * r.vv.abs() + x[1]);
    let p = protocol(vec![parameter("a", 1.0), parameter("b", 1.0)]);
    let cv = cross_validate_with(&table, &p, &[1], &predict, (&predict, 8.0), None).unwrap();
    let mut moved = table.clone();
    moved[2].experiment *= 2.0;
    let again = cross_validate_with(&moved, &p, &[1], &predict, (&predict, 8.0), None).unwrap();
    // Row 3's own fold is bit for bit the same fit; every other fold, which sees row 3, moves.
    assert_eq!(cv.folds[2].fit, again.folds[2].fit);
    assert_eq!(cv.folds[2].predicted_in, again.folds[2].predicted_in);
    for i in [0, 1, 3, 4] {
        assert_ne!(cv.folds[i].fit, again.folds[i].fit, "fold {i}");
    }
}

#[test]
fn a_run_stopped_part_way_resumes_from_its_checkpoint_to_the_same_result() {
    let table: Vec<Row> = (1..=5)
        .map(|i| row(i, -(i as f64), 2.0 * i as f64 + 0.3 * (i as f64).sin()))
        .collect();
    let predict = |r: &Row, x: &[f64]| Ok(x[0] * r.vv.abs() + x[1]);
    let p = protocol(vec![parameter("a", 1.0), parameter("b", 1.0)]);
    let whole = cross_validate_with(&table, &p, &[1], &predict, (&predict, 8.0), None).unwrap();
    // A run that dies after a third of its landings (as a killed run would) ...
    let dir = tempfile::tempdir().unwrap();
    let checkpoint = Checkpoint::new(dir.path(), "this run").unwrap();
    let calls = std::sync::atomic::AtomicUsize::new(0);
    let dying = |r: &Row, x: &[f64]| {
        if calls.fetch_add(1, std::sync::atomic::Ordering::Relaxed) > whole.landings / 3 {
            Err(ValidationError::Calibration("killed".into()))
        } else {
            predict(r, x)
        }
    };
    assert!(
        cross_validate_with(&table, &p, &[1], &dying, (&dying, 8.0), Some(&checkpoint)).is_err()
    );
    let (kept, kept_landings) = checkpoint.kept();
    assert!(kept > 0, "some units finished before the kill");
    // ... resumes from what it kept, landing fewer, to the same result and count.
    let resumed_calls = std::sync::atomic::AtomicUsize::new(0);
    let counting = |r: &Row, x: &[f64]| {
        resumed_calls.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        predict(r, x)
    };
    let resumed = cross_validate_with(
        &table,
        &p,
        &[1],
        &counting,
        (&counting, 8.0),
        Some(&checkpoint),
    )
    .unwrap();
    assert_eq!(resumed, whole);
    let landed = resumed_calls.load(std::sync::atomic::Ordering::Relaxed);
    assert!(landed < whole.landings, "{landed} of {}", whole.landings);
    // The kept units' landings and the resumed run's make the whole run's (what a resumed
    // run's progress starts from).
    assert_eq!(kept_landings + landed, whole.landings);
    // Units of another run's key are not taken.
    let other = Checkpoint::new(dir.path(), "another program").unwrap();
    assert_eq!(other.kept(), (0, 0));
}

#[test]
fn intervals_widen_with_the_misfit_and_cover_the_truth_of_a_noisy_law() {
    // A law with a ±5 % wobble the model cannot follow: the misfit sets s², so the
    // intervals are a few per cent wide, not zero.
    let table: Vec<Row> = (1..=8)
        .map(|i| {
            let vv = -(i as f64);
            let wobble = if i % 2 == 0 { 1.05 } else { 0.95 };
            row(i, vv, linear(&[1.5, 2.0], vv) * wobble)
        })
        .collect();
    let predict = |r: &Row, x: &[f64]| Ok(linear(x, r.vv));
    let p = protocol(vec![parameter("a", 1.0), parameter("b", 1.0)]);
    let cv = cross_validate_with(&table, &p, &[1], &predict, (&predict, 8.0), None).unwrap();
    for f in &cv.folds {
        let width = (f.interval_in[1] - f.interval_in[0]) / f.predicted_in;
        assert!(width > 0.01 && width < 0.5, "row {}: {width}", f.held_out);
        assert!(f.interval_in[0] <= f.predicted_in && f.predicted_in <= f.interval_in[1]);
    }
    assert!(cv.identifiability.residual_variance > 0.0);
}

/// Each fold's prediction is landed again at its fit with the refined model, and the landings
/// are counted: here the refined model is the exact law 1 % longer, so that every row's stated
/// refined stroke is 1.01 times the fold's law at its own fit, not its prediction or the truth.
#[test]
fn a_cross_validation_states_the_accuracy_of_its_predictions_against_refined_runs() {
    let table: Vec<Row> = (1..=5)
        .map(|i| row(i, -(i as f64), 2.0 * i as f64 + 0.3 * (i as f64).sin()))
        .collect();
    let predict = |r: &Row, x: &[f64]| Ok(linear(x, r.vv));
    let calls = std::sync::atomic::AtomicUsize::new(0);
    let refined = |r: &Row, x: &[f64]| {
        calls.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        Ok(1.01 * linear(x, r.vv))
    };
    let p = protocol(vec![parameter("a", 1.0), parameter("b", 1.0)]);
    let cv = cross_validate_with(&table, &p, &[1], &predict, (&refined, 8.0), None).unwrap();
    let unrefined = cross_validate_with(&table, &p, &[1], &predict, (&predict, 8.0), None).unwrap();
    let a = &cv.accuracy;
    assert_eq!(a.refinement, 8.0);
    let ids: Vec<u32> = a.row.iter().map(|r| r.id).collect();
    assert_eq!(ids, vec![1, 2, 3, 4, 5]);
    for ((r, f), row) in a.row.iter().zip(&cv.folds).zip(&table) {
        assert_eq!(r.stroke_m, f.predicted_in * INCH, "row {}", r.id);
        assert_eq!(
            r.refined_stroke_m,
            1.01 * linear(&f.fit.value, row.vv) * INCH,
            "row {}",
            r.id
        );
    }
    assert_eq!(calls.load(std::sync::atomic::Ordering::Relaxed), 5);
    // The folds are the same whatever the refined model; its landings are counted.
    assert_eq!(cv.folds, unrefined.folds);
    assert_eq!(cv.landings, unrefined.landings);
    assert!(cv.landings > 5);
}

#[test]
fn a_bad_protocol_names_its_field() {
    let mut p = protocol(vec![parameter("a", 1.0)]);
    p.samples = 1;
    let e = p.check().unwrap_err().to_string();
    assert!(e.contains("samples"), "{e}");
    let mut p = protocol(vec![parameter("a", 1.0)]);
    p.parameter[0].initial = 20.0;
    let e = p.check().unwrap_err().to_string();
    assert!(e.contains(": a: expected finite bounds"), "{e}");
}
