//! The validation against the 1/6-scale drop tests, in the test suite: the Table I results as
//! a reviewed snapshot, the targets asserted where they are met, the calibration protocol's
//! promise that held-out rows never enter the fit, and the boundary search end to end.

use std::fmt::Write;
use std::path::{Path, PathBuf};
use touchdown_core::Outcome;
use touchdown_validation::boundary::{self, Settings};
use touchdown_validation::reference::{self, Protocol, TableI};
use touchdown_validation::table::{self, Role};
use touchdown_validation::{calibrate, reference::Paths};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .unwrap()
}

/// Rounds to `digits` significant figures (snapshots must not depend on the last bits).
fn sig(x: f64, digits: i32) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let scale = 10f64.powi(digits - 1 - x.abs().log10().floor() as i32);
    let r = (x * scale).round() / scale;
    let decimals = (digits - 1 - x.abs().log10().floor() as i32).max(0) as usize;
    format!("{r:.decimals$}")
}

/// Table I with our strokes (3 significant figures) and errors (0.1 %), the held-out
/// statistics and the targets: any change to the model that moves a stroke shows up here as
/// a snapshot diff to review.
#[test]
fn table_i_validation_snapshot() {
    let v = table::validate(&Paths::new(root())).unwrap();
    let mut o = String::new();
    writeln!(
        o,
        "row landing strut experiment_in ours_in error_vs_exp_pct role outcome"
    )
    .unwrap();
    for r in &v.rows {
        writeln!(
            o,
            "{} {} {:?} {} {} {:+.1} {:?} {:?}",
            r.id,
            r.landing,
            r.strut,
            r.experiment_in,
            sig(r.ours_in, 3),
            r.error_vs_experiment_pct,
            r.role,
            r.outcome
        )
        .unwrap();
    }
    writeln!(
        o,
        "held-out mean |error| ours {:.1} %, report {:.1} %",
        v.held_out_ours.mean_abs_error_pct, v.held_out_report.mean_abs_error_pct
    )
    .unwrap();
    writeln!(
        o,
        "targets: all held-out within 10 %: {}, mean no worse than the report: {}",
        v.targets.held_out_within_10_pct, v.targets.mean_no_worse_than_report
    )
    .unwrap();
    for f in &v.facts {
        writeln!(
            o,
            "fact {}: report {} ours {} agrees {}",
            f.fact, f.report, f.ours, f.agrees
        )
        .unwrap();
    }
    insta::assert_snapshot!("table_i", o);
}

/// The targets that the current calibration meets are asserted (so a change that loses them
/// fails here); those it does not meet are in the snapshot and in docs/validation.md.
#[test]
fn targets_that_are_met_stay_met() {
    let v = table::validate(&Paths::new(root())).unwrap();
    let record = v
        .calibration
        .as_ref()
        .expect("the scenarios carry a calibration");
    assert_eq!(record.rows, vec![3, 7], "the protocol's rows");
    for r in &v.rows {
        assert_eq!(
            r.role == Role::Calibration,
            record.rows.contains(&r.id),
            "row {}",
            r.id
        );
    }
    let row7 = v.rows.iter().find(|r| r.id == 7).unwrap();
    assert!(
        row7.error_vs_experiment_pct.abs() < 10.0,
        "calibration row 7: {:+.1} %",
        row7.error_vs_experiment_pct
    );
    let fact = |name: &str| {
        v.facts
            .iter()
            .find(|f| f.fact == name)
            .unwrap_or_else(|| panic!("no fact {name}"))
    };
    // "primary stroke into the second stage" was met before the contact rule and the end stops
    // changed (docs/errata.md, "Contact and release", "End stops") and the calibration moved
    // FP1 from 149 to 223 lbf: the primaries now stop short of the second stage
    // (docs/validation.md).
    for name in [
        "downhill footpads strike",
        "pitch rate at the downhill strike",
        "pitch rate after the downhill impact (at maximum stroking)",
        "maximum stroking reached by",
        "outcome",
    ] {
        assert!(
            fact(name).agrees,
            "{name}: report {} ours {}",
            fact(name).report,
            fact(name).ours
        );
    }
    // Every Table I landing keeps its energy balance and ends decided.
    assert!(v.rows.iter().all(|r| r.outcome == Outcome::Stable));
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let p = e.unwrap().path();
        let target = to.join(p.file_name().unwrap());
        if p.is_dir() {
            copy_dir(&p, &target);
        } else {
            std::fs::copy(&p, &target).unwrap();
        }
    }
}

/// By construction: changing every held-out row's experimental value (×2) changes nothing in
/// the calibration, so held-out rows cannot have entered it.
#[test]
fn held_out_rows_never_enter_the_calibration() {
    let tmp = std::env::temp_dir().join(format!("touchdown-heldout-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&tmp);
    copy_dir(&root().join("reference"), &tmp.join("reference"));
    copy_dir(&root().join("scenarios"), &tmp.join("scenarios"));
    let paths = Paths::new(&tmp);
    let protocol: Protocol =
        reference::read(&paths.reference("calibration-protocol.toml")).unwrap();
    let before = calibrate::calibrate(&paths, &protocol, None).unwrap();
    let table_path = paths.reference("table-i.toml");
    let mut table: toml::Table =
        toml::from_str(&std::fs::read_to_string(&table_path).unwrap()).unwrap();
    let rows = table.get_mut("row").unwrap().as_array_mut().unwrap();
    let mut changed = 0;
    for row in rows.iter_mut() {
        let row = row.as_table_mut().unwrap();
        let id = row["id"].as_integer().unwrap() as u32;
        if !protocol.rows.contains(&id) {
            let e = row["experiment"].as_float().unwrap();
            row.insert("experiment".into(), toml::Value::Float(2.0 * e));
            changed += 1;
        }
    }
    assert_eq!(changed, 6);
    std::fs::write(&table_path, toml::to_string(&table).unwrap()).unwrap();
    let _: TableI = reference::read(&table_path).unwrap();
    let after = calibrate::calibrate(&paths, &protocol, None).unwrap();
    assert_eq!(
        before, after,
        "held-out experiments changed the calibration"
    );
    // And the calibration rows do enter it.
    let mut table: toml::Table =
        toml::from_str(&std::fs::read_to_string(&table_path).unwrap()).unwrap();
    for row in table.get_mut("row").unwrap().as_array_mut().unwrap() {
        let row = row.as_table_mut().unwrap();
        if row["id"].as_integer() == Some(7) {
            row.insert("experiment".into(), toml::Value::Float(2.0));
        }
    }
    std::fs::write(&table_path, toml::to_string(&table).unwrap()).unwrap();
    let moved = calibrate::calibrate(&paths, &protocol, None).unwrap();
    assert_ne!(moved.parameter, before.parameter);
    let _ = std::fs::remove_dir_all(&tmp);
}

/// The search end to end on a real case that overturns (the figure 25-26 configuration on a
/// 15° slope, Vv = 12 ft/s): the landings just either side of the boundary it reports, and of
/// every transition, are stable and unstable.
#[test]
fn boundary_search_brackets_a_real_overturn() {
    let tmp = std::env::temp_dir().join(format!("touchdown-boundary-{}.toml", std::process::id()));
    let base = root().join("scenarios/fig-25-26.toml");
    std::fs::write(
        &tmp,
        format!(
            "schema_version = 1\nextends = {:?}\nname = \"steep\"\n[surface]\nkind = \"rigid\"\nslope = 15.0\nhole = [0.3333, 0.3333, 0.0, 0.0]\nobstacle = 1.0\nfriction = 0.0\n",
            base.display().to_string()
        ),
    )
    .unwrap();
    let steep = touchdown_scenario::ScenarioBase::load(&tmp).unwrap();
    let landing =
        boundary::scenario_landing(&steep, &[], |sc| touchdown_core::run(sc).map(|s| s.outcome))
            .unwrap();
    let settings = Settings {
        vh_start: 0.0,
        vh_step: 2.0,
        vh_max: 12.0,
        tolerance: 0.05,
    };
    let points = boundary::search(&[12.0], settings, &landing, &|| {}).unwrap();
    let p = &points[0];
    let (lo, hi) = (p.stable_at.unwrap(), p.unstable_at.unwrap());
    assert!(hi - lo <= 0.05 + 1e-12 && p.vh.is_some());
    // Both ends decided: an undecided landing is never taken as either.
    assert_eq!(landing(12.0, lo).unwrap(), Outcome::Stable);
    assert_eq!(landing(12.0, hi).unwrap(), Outcome::Unstable);
    assert_eq!(p.undecided, p.undecided_at.len());
    for t in &p.transitions {
        assert_eq!(landing(12.0, t.stable_at).unwrap(), Outcome::Stable);
        assert_eq!(landing(12.0, t.unstable_at).unwrap(), Outcome::Unstable);
    }
    let _ = std::fs::remove_file(&tmp);
}

/// The figure 25-26 scenario lands at the velocities `touchdown estimate` chose from the text's
/// facts (reference/fig-25-26-velocities.toml), in the scenario's horizontal direction.
#[test]
fn the_figure_25_26_landing_uses_the_estimated_velocities() {
    let root = root();
    let text = std::fs::read_to_string(root.join("reference/fig-25-26-velocities.toml")).unwrap();
    let estimate: toml::Table = toml::from_str(&text).unwrap();
    let best = estimate["best"].as_table().unwrap();
    let vv = best["descent_speed_ft_s"].as_float().unwrap();
    let vh = best["horizontal_speed_ft_s"].as_float().unwrap();
    let sc = touchdown_scenario::Scenario::load(root.join("scenarios/fig-25-26.toml")).unwrap();
    assert_eq!(
        sc.file.units.length,
        touchdown_scenario::units::LengthUnit::Foot
    );
    let t = &sc.file.touchdown;
    assert_eq!(t.vertical_velocity, -vv);
    assert_eq!(t.horizontal_velocity[0].hypot(t.horizontal_velocity[1]), vh);
}
