//! Campaigns (docs/campaigns.md): the same bytes whatever the threads, shards or order;
//! extensions that leave the first landings alone; the values applied are the values drawn and
//! reach the model; a probability known in closed form comes out; bad files and bad merges are
//! refused by name; the Parquet records read back in pandas, polars and DuckDB.

use std::path::{Path, PathBuf};
use touchdown_campaign::distribution::Value;
use touchdown_campaign::landing::draws;
use touchdown_campaign::record::Cell;
use touchdown_campaign::run::run;
use touchdown_campaign::{merge, Campaign, CampaignError, Shard};
use touchdown_tests::{python, root, scenario};

/// The files a finished campaign folder holds, each compared byte for byte.
const FILES: [&str; 4] = [
    "manifest.json",
    "landings.jsonl",
    "landings.parquet",
    "statistics.json",
];

fn small() -> PathBuf {
    scenario("campaigns/small.toml")
}

/// Every file under `dir`, relative to it, sorted.
fn tree(dir: &Path) -> Vec<PathBuf> {
    fn walk(root: &Path, dir: &Path, out: &mut Vec<PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(root, &path, out);
            } else {
                out.push(path.strip_prefix(root).unwrap().to_path_buf());
            }
        }
    }
    let mut out = Vec::new();
    walk(dir, dir, &mut out);
    out.sort();
    out
}

/// The folders `a` and `b` hold the same files (histories included), byte for byte.
fn assert_same_files(a: &Path, b: &Path) {
    let files = tree(a);
    assert_eq!(files, tree(b), "{} and {}", a.display(), b.display());
    for f in FILES {
        assert!(files.contains(&PathBuf::from(f)), "{f} missing");
    }
    for f in files {
        let (x, y) = (
            std::fs::read(a.join(&f)).unwrap(),
            std::fs::read(b.join(&f)).unwrap(),
        );
        assert!(
            x == y,
            "{} differs between {} and {}",
            f.display(),
            a.display(),
            b.display()
        );
    }
}

/// A copy of the small campaign with `landings` landings, at `path` (the manifest names the
/// campaign file, so compared runs read the same path).
fn small_with(path: &Path, landings: u64) {
    let text = std::fs::read_to_string(small()).unwrap();
    let text = text.replace("landings = 24", &format!("landings = {landings}"));
    let text = text.replace(
        "scenario = \"../",
        &format!("scenario = \"{}/", scenario("").display()),
    );
    std::fs::write(path, text).unwrap();
}

/// `campaign` run as `order.len()` shards in the order `order` (on two threads each) into
/// folders under `tmp`, and merged: the merged folder.
fn sharded(campaign: &Campaign, tmp: &Path, order: &[u64]) -> PathBuf {
    let mut parts = Vec::new();
    for &k in order {
        let dir = tmp.join(format!("shard-{k}"));
        let shard = Shard {
            index: k,
            count: order.len() as u64,
        };
        run(campaign, Some(shard), Some(2), Some(&dir), false, |_| ()).unwrap();
        parts.push(dir);
    }
    let merged = tmp.join("merged");
    let refs: Vec<&Path> = parts.iter().map(PathBuf::as_path).collect();
    merge(&refs, &merged, |_| ()).unwrap();
    merged
}

#[test]
fn one_shard_or_four_in_any_order_on_any_threads_write_the_same_bytes() {
    let tmp = tempfile::tempdir().unwrap();
    let campaign = Campaign::load(small()).unwrap();
    let whole = tmp.path().join("whole");
    run(&campaign, None, Some(1), Some(&whole), false, |_| ()).unwrap();
    let merged = sharded(&campaign, tmp.path(), &[3, 1, 4, 2]);
    assert_same_files(&whole, &merged);
    // The landings come in order whatever finished first, and the history asked for is kept.
    let mut seen = Vec::new();
    run(&campaign, None, Some(2), None, false, |r| {
        seen.push(r[0].clone())
    })
    .unwrap();
    assert_eq!(seen, (0..24).map(Cell::Integer).collect::<Vec<_>>());
    assert!(whole.join("histories/landing-3.csv").is_file());
}

#[test]
fn added_landings_leave_the_first_ones_unchanged() {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("campaign.toml");
    small_with(&file, 16);
    let extended = tmp.path().join("extended");
    let c16 = Campaign::load(&file).unwrap();
    run(&c16, None, None, Some(&extended), false, |_| ()).unwrap();
    touchdown_campaign::add(&c16, &extended, 8, None, false, |_| ()).unwrap();
    small_with(&file, 24);
    let at_once = tmp.path().join("at-once");
    run(
        &Campaign::load(&file).unwrap(),
        None,
        None,
        Some(&at_once),
        false,
        |_| (),
    )
    .unwrap();
    assert_same_files(&extended, &at_once);
}

/// `--out` is checked before any landing runs (a file, a folder of other files, another part
/// of the campaign are refused), written by one process at a time, and replaced only when the
/// new folder is complete: a run stopped part-way leaves the previous folder as it was. A merge
/// may name one of its own parts as `--out`.
#[test]
fn a_campaign_folder_is_replaced_only_when_complete_and_by_one_writer() {
    use touchdown_campaign::folder::Staging;
    let tmp = tempfile::tempdir().unwrap();
    let campaign = Campaign::load(small()).unwrap();
    let refused = |out: &Path, shard: Option<Shard>, says: &str| {
        let mut landed = 0;
        match run(&campaign, shard, None, Some(out), false, |_| landed += 1) {
            Err(CampaignError::Store { path, message }) => {
                assert_eq!(path, out.display().to_string());
                assert!(message.contains(says), "{message}");
            }
            other => panic!("expected a refusal, got {other:?}"),
        }
        assert_eq!(landed, 0, "refused after landings ran");
    };
    let file = tmp.path().join("a-file");
    std::fs::write(&file, "keep").unwrap();
    refused(&file, None, "is not a folder");
    let foreign = tmp.path().join("foreign");
    std::fs::create_dir(&foreign).unwrap();
    std::fs::write(foreign.join("notes.txt"), "keep").unwrap();
    refused(&foreign, None, "not a campaign's");
    assert_eq!(
        std::fs::read_to_string(foreign.join("notes.txt")).unwrap(),
        "keep"
    );
    let whole = tmp.path().join("whole");
    run(&campaign, None, None, Some(&whole), false, |_| ()).unwrap();
    let copy = tmp.path().join("copy");
    copy_dir(&whole, &copy);
    refused(
        &whole,
        Some(Shard { index: 1, count: 3 }),
        "holds landings 0 to 23 of 24",
    );
    // While another writer holds the folder, a second is refused.
    let held = Staging::begin(&whole).unwrap();
    refused(&whole, None, "another touchdown is writing this folder");
    // A writer stopped part-way (its folder dropped unfinished) leaves the old one intact; the
    // next run clears what it left and replaces the folder with the same bytes.
    std::fs::write(held.dir().join("landings.jsonl"), "cut").unwrap();
    drop(held);
    assert_same_files(&whole, &copy);
    run(&campaign, None, None, Some(&whole), false, |_| ()).unwrap();
    assert_same_files(&whole, &copy);
    assert!(!tmp.path().join("whole.partial").exists());
    // A merge into one of its own parts.
    let parts: Vec<PathBuf> = (1..=2)
        .map(|k| {
            let dir = tmp.path().join(format!("part-{k}"));
            run(
                &campaign,
                Some(Shard { index: k, count: 2 }),
                None,
                Some(&dir),
                false,
                |_| (),
            )
            .unwrap();
            dir
        })
        .collect();
    merge(&[&parts[0], &parts[1]], &parts[0], |_| ()).unwrap();
    assert_same_files(&parts[0], &whole);
    assert!(matches!(
        merge(&[&parts[1]], &foreign, |_| ()),
        Err(CampaignError::Mismatch(_)) | Err(CampaignError::Store { .. })
    ));
}

/// The `run.json` of the run that writes the folder whose manifest is `manifest`, as the run
/// writes it when it starts: the manifest it will write, but for the accuracy it measures once
/// its landings have run and the seal of its files.
fn run_file_of(manifest: &[u8]) -> String {
    let mut identity: touchdown_campaign::store::Manifest =
        serde_json::from_slice(manifest).unwrap();
    identity.accuracy.take();
    identity.files_sha256.clear();
    identity.seal_sha256.clear();
    touchdown_campaign::store::pretty(&identity)
}

/// Copies the folder tree `from` into `to`.
fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let path = entry.unwrap().path();
        let target = to.join(path.file_name().unwrap());
        if path.is_dir() {
            copy_dir(&path, &target);
        } else {
            std::fs::copy(&path, target).unwrap();
        }
    }
}

/// What a run killed part-way leaves in `<out>.partial` is resumed from (`--resume`) to the same
/// bytes as an uninterrupted run: a last record cut short mid-line is dropped and landed again,
/// and a Parquet file cut short while a row group was being written is written again. (The
/// command line's `a_campaign_killed_at_any_moment_resumes_to_the_same_bytes` kills real
/// processes at ten moments.)
#[test]
fn a_run_stopped_mid_record_or_mid_row_group_resumes_to_the_same_bytes() {
    let tmp = tempfile::tempdir().unwrap();
    let campaign = Campaign::load(small()).unwrap();
    let whole = tmp.path().join("whole");
    run(&campaign, None, None, Some(&whole), false, |_| ()).unwrap();
    let read = |name: &str| std::fs::read(whole.join(name)).unwrap();
    let (manifest, jsonl, parquet) = (
        read("manifest.json"),
        read("landings.jsonl"),
        read("landings.parquet"),
    );
    let run_file = run_file_of(&manifest);
    let run_file = run_file.as_bytes();
    let line_ends: Vec<usize> = (jsonl.iter().enumerate())
        .filter(|(_, b)| **b == b'\n')
        .map(|(i, _)| i + 1)
        .collect();
    let stopped = [
        // Killed while writing record 11: ten whole lines and half of one.
        (
            jsonl[..line_ends[9] + (line_ends[10] - line_ends[9]) / 2].to_vec(),
            None,
        ),
        // Killed while writing the Parquet file's row group: every record, half the file.
        (jsonl.clone(), Some(parquet[..parquet.len() / 2].to_vec())),
    ];
    for (k, (records, columns)) in stopped.into_iter().enumerate() {
        let out = tmp.path().join(format!("stopped-{k}"));
        let partial = tmp.path().join(format!("stopped-{k}.partial"));
        // The kept landings' histories were written as they finished (the one asked for is of
        // landing 3).
        copy_dir(&whole.join("histories"), &partial.join("histories"));
        std::fs::write(partial.join(".lock"), "").unwrap();
        std::fs::write(partial.join("run.json"), run_file).unwrap();
        std::fs::write(partial.join("landings.jsonl"), records).unwrap();
        if let Some(columns) = columns {
            std::fs::write(partial.join("landings.parquet"), columns).unwrap();
        }
        let mut seen = Vec::new();
        run(&campaign, None, None, Some(&out), true, |r| {
            seen.push(r[0].clone())
        })
        .unwrap();
        assert_same_files(&whole, &out);
        assert!(!partial.exists());
        // Every record is handed on once, in order, the kept ones first.
        assert_eq!(seen, (0..24).map(Cell::Integer).collect::<Vec<_>>());
    }
    // The kept records are taken, not landed again: one altered before the resume stays so.
    let text = String::from_utf8(jsonl[..line_ends[9]].to_vec()).unwrap();
    let altered = {
        let (first, rest) = text.split_once('\n').unwrap();
        let mut record: serde_json::Map<String, serde_json::Value> =
            serde_json::from_str(first).unwrap();
        record.insert("peak_specific_force_m_s2".into(), 1234.5.into());
        format!("{}\n{rest}", serde_json::Value::Object(record))
    };
    let out = tmp.path().join("altered");
    let partial = tmp.path().join("altered.partial");
    copy_dir(&whole.join("histories"), &partial.join("histories"));
    std::fs::write(partial.join(".lock"), "").unwrap();
    std::fs::write(partial.join("run.json"), run_file).unwrap();
    std::fs::write(partial.join("landings.jsonl"), &altered).unwrap();
    run(&campaign, None, None, Some(&out), true, |_| ()).unwrap();
    let resumed = std::fs::read_to_string(out.join("landings.jsonl")).unwrap();
    assert!(
        resumed.starts_with(&altered),
        "the kept records were landed again"
    );
    assert_eq!(resumed.len() - altered.len(), jsonl.len() - line_ends[9]);
}

#[test]
fn the_values_applied_are_the_values_drawn_and_reach_the_model() {
    let campaign = Campaign::load(small()).unwrap();
    let mut rows = Vec::new();
    run(&campaign, None, None, None, false, |r| rows.push(r.clone())).unwrap();
    let n = campaign.dispersions.len();
    let mut references = std::collections::BTreeSet::new();
    for (i, row) in rows.iter().enumerate() {
        let drawn = draws(&campaign, i as u64);
        let applied: Vec<Cell> = drawn.iter().map(Cell::from).collect();
        assert_eq!(row[1..=n], applied[..], "landing {i}");
        if let Value::Text(t) = &drawn[4] {
            references.insert(t.clone());
        }
        // In SI in the model: the vertical velocity (ft/s in the file) and the heading (deg).
        let sc = campaign.base.with(&campaign.overrides(&drawn)).unwrap();
        let (Value::Number(vv), Value::Number(heading)) = (&drawn[0], &drawn[2]) else {
            panic!("numbers expected")
        };
        assert!((sc.touchdown.velocity_g.z - vv * 0.3048).abs() < 1e-12);
        assert!((sc.touchdown.attitude.z - heading.to_radians()).abs() < 1e-12);
    }
    // 24 landings of a 3:1 choice draw both values; the list cycles through its three slopes.
    assert_eq!(references.len(), 2);
    let slopes: Vec<&Cell> = rows.iter().take(3).map(|r| &r[6]).collect();
    assert_eq!(
        slopes,
        [&Cell::Float(0.0), &Cell::Float(5.0), &Cell::Float(10.0)]
    );
}

/// The accuracy a campaign states (docs/campaigns.md, "Accuracy") is its first landing landed
/// at its settings and with DIST and dt_max divided by 8, written here by hand: the refined run
/// takes several times the steps, the manifest's errors are those two runs', and settings four
/// times coarser state a larger error; the reference's own spread is that of the runs with
/// DIST and dt_max divided by 4 against it. A landing whose settings cannot be refined within
/// their ranges is listed as not measured.
#[test]
fn a_campaign_states_the_accuracy_of_its_settings_against_refined_runs() {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("campaign.toml");
    small_with(&file, 4);
    let coarse = tmp.path().join("coarse.toml");
    let text = std::fs::read_to_string(&file).unwrap();
    std::fs::write(
        &coarse,
        format!("{text}\n[[dispersion]]\nfield = \"integrator.dt_max\"\nunit = \"s\"\ndistribution = \"list\"\nvalues = [8.0e-4]\n"),
    )
    .unwrap();
    let mut errors = Vec::new();
    for file in [&file, &coarse] {
        let campaign = Campaign::load(file).unwrap();
        let (manifest, _) = run(&campaign, None, Some(1), None, false, |_| ()).unwrap();
        let a = manifest
            .accuracy
            .expect("a campaign on the core states its accuracy");
        assert_eq!((a.sample_landings, a.refinement), (1, 8.0));
        let sc = touchdown_campaign::landing::scenario(&campaign, &draws(&campaign, 0)).unwrap();
        let finer = |f: f64| {
            let sc = sc.clone().with_integrator(|it| {
                it.dist /= f;
                it.dt_max /= f;
            });
            touchdown_core::run(&sc.unwrap()).unwrap()
        };
        let (refined, half) = (finer(8.0), finer(4.0));
        let (x, x_ref) = (touchdown_core::run(&sc).unwrap(), refined);
        assert!(
            x_ref.steps > 4 * x.steps,
            "{} against {}",
            x_ref.steps,
            x.steps
        );
        assert_eq!(a.outcomes_identical, u64::from(x.outcome == x_ref.outcome));
        let largest = |s: &touchdown_record::Summary| {
            s.max_primary_stroke_m.iter().fold(0.0f64, |m, x| m.max(*x))
        };
        let both = a.maxima.expect("the three runs completed");
        let m = both.settings;
        assert_eq!(
            m.largest_primary_stroke.fraction,
            (largest(&x) - largest(&x_ref)).abs() / largest(&x_ref)
        );
        assert_eq!(
            both.reference.largest_primary_stroke.fraction,
            (largest(&half) - largest(&x_ref)).abs() / largest(&x_ref)
        );
        let capacity = x.strut_capacity.secondary_tension.stroke_m;
        let tension = |s: &touchdown_record::Summary| {
            s.max_secondary_tension_m
                .iter()
                .flatten()
                .copied()
                .collect::<Vec<_>>()
        };
        let worst_tension = tension(&x)
            .iter()
            .zip(tension(&x_ref))
            .fold(0.0f64, |w, (a, b)| w.max((a - b).abs() / capacity));
        assert!(m.stroke_of_capacity.fraction >= worst_tension);
        errors.push(m.stroke_of_capacity.fraction);
    }
    assert!(
        errors[1] > errors[0],
        "coarse {} against default {}",
        errors[1],
        errors[0]
    );
    // A budget that refined would leave its range (max_steps ≤ 1e9) is not measured, and not
    // counted as an outcome the refined run changed.
    let budget = tmp.path().join("budget.toml");
    std::fs::write(
        &budget,
        format!("{text}\n[[dispersion]]\nfield = \"integrator.max_steps\"\nunit = \"1\"\ndistribution = \"list\"\nvalues = [5.0e8]\n"),
    )
    .unwrap();
    let campaign = Campaign::load(&budget).unwrap();
    let (manifest, _) = run(&campaign, None, Some(1), None, false, |_| ()).unwrap();
    let a = manifest.accuracy.unwrap();
    assert_eq!(a.not_refined, [0]);
    assert_eq!((a.outcomes_identical, a.compared), (0, 0));
    assert!(a.outcomes_differ.is_empty() && a.maxima.is_none());
}

/// A vertical drop on flat ground strokes its primaries out exactly when it lands faster than
/// one speed V*, found here by bisection on single landings: with Vv ~ N(−15, 3²) ft/s, the
/// probability of a stroke-out is Φ((−V* + 15)/3) in closed form, and the campaign's count of
/// 400 landings must lie within the binomial 99.9 % interval around it.
#[test]
fn an_outcome_decided_by_one_input_has_its_analytic_probability() {
    use statrs::distribution::{Binomial, ContinuousCDF, DiscreteCDF, Normal};
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("drop.toml");
    std::fs::write(
        &file,
        format!(
            "schema_version = 1\nname = \"drop\"\nscenario = {:?}\nlandings = 400\nseed = 11\n\n[[dispersion]]\nfield = \"touchdown.vertical_velocity\"\nunit = \"ft/s\"\ndistribution = \"normal\"\nmean = -15.0\nstd_dev = 3.0\n",
            scenario("flat-drop.toml").display().to_string()
        ),
    )
    .unwrap();
    let campaign = Campaign::load(&file).unwrap();
    let strokes_out = |vv: f64| {
        let sc = campaign
            .base
            .with(&[("touchdown.vertical_velocity", toml::Value::Float(-vv))])
            .unwrap();
        let s = touchdown_registry::land(campaign.engines[0], &file, &sc, &mut (), None).unwrap();
        !s.past_capacity.is_empty()
    };
    let (mut lo, mut hi) = (5.0, 25.0);
    assert!(!strokes_out(lo) && strokes_out(hi));
    while hi - lo > 1e-3 {
        let mid = 0.5 * (lo + hi);
        if strokes_out(mid) {
            hi = mid
        } else {
            lo = mid
        }
    }
    let v_star = 0.5 * (lo + hi);
    let p = Normal::standard().cdf((15.0 - v_star) / 3.0);
    let mut rows = Vec::new();
    let (_, stats) = run(&campaign, None, None, None, false, |r| rows.push(r.clone())).unwrap();
    let outs = rows
        .iter()
        .filter(|r| r.contains(&Cell::Text("stroke_out".into())))
        .count() as u64;
    let b = Binomial::new(p, 400).unwrap();
    let (low, high) = (b.inverse_cdf(0.0005), b.inverse_cdf(0.9995));
    assert!(
        (low..=high).contains(&outs),
        "V* = {v_star:.3} ft/s, p = {p:.4}: {outs} stroke-outs of 400, expected {low} to {high}"
    );
    // Every landing that did not stroke out is stable; the bound is below the fraction.
    assert_eq!(stats.first().stable_within_capacity.landings, 400 - outs);
    assert!(stats.first().stable_within_capacity.lower_bound.unwrap() < 1.0 - p + 0.05);
}

fn refused(text: &str) -> String {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("bad.toml");
    std::fs::write(&file, text).unwrap();
    let e = Campaign::load(&file).unwrap_err();
    let message = e.to_string();
    assert!(
        message.starts_with(&file.display().to_string()),
        "{message}"
    );
    message.replace(&file.display().to_string(), "bad.toml")
}

#[test]
fn bad_campaign_files_are_refused_naming_the_file_and_the_field() {
    let good = std::fs::read_to_string(small()).unwrap().replace(
        "scenario = \"../",
        &format!("scenario = \"{}/", scenario("").display()),
    );
    let deep_field = format!("{}\"\nunit", vec!["a"; 60_000].join("."));
    let cases = [
        (
            "std_dev = 1.5",
            "std_dev = -1.5",
            "field `dispersion[0].std_dev`: expected a positive number",
        ),
        (
            "unit = \"ft/s\"\ndistribution = \"normal\"",
            "unit = \"m/s\"\ndistribution = \"normal\"",
            "field `dispersion[0].unit`: \"m/s\": the scenario states lengths in ft",
        ),
        (
            "unit = \"ft/s\"\ndistribution = \"normal\"",
            "unit = \"ft\"\ndistribution = \"normal\"",
            "field `dispersion[0].unit`: \"ft\" is a length, but `touchdown.vertical_velocity` is a length/time: write its numbers in ft/s",
        ),
        (
            "unit = \"deg\"",
            "unit = \"1\"",
            "is a pure number, but `touchdown.attitude[2]` is an angle: write its numbers in deg",
        ),
        (
            "touchdown.vertical_velocity\"\nunit",
            "touchdown.vertical_speed\"\nunit",
            "field `dispersion[0].field`: `touchdown.vertical_speed` cannot be set",
        ),
        (
            "landings = 24",
            "landings = 0",
            "field `landings`: expected between 1 and",
        ),
        (
            "distribution = \"uniform\"",
            "distribution = \"gamma\"",
            "field `dispersion[2]",
        ),
        (
            "weights = [3.0, 1.0]",
            "weights = [3.0]",
            "field `dispersion[4].weights`: expected one weight per value",
        ),
        (
            "weights = [3.0, 1.0]",
            "weights = [1e308, 1e308]",
            "field `dispersion[4].weights`: expected weights ≥ 0, not all zero, with a finite sum",
        ),
        (
            "touchdown.vertical_velocity\"\nunit",
            deep_field.as_str(),
            "a field path of 60000 parts",
        ),
        (
            "coefficient = -0.5",
            "coefficient = 1.5",
            "field `correlation[0].coefficient`",
        ),
        ("confidence = 0.9", "confidence = 95", "field `confidence`"),
        ("seed = 7", "seed = 7\nseeds = 8", "unknown field `seeds`"),
        (
            "histories = [3]",
            "histories = [24]",
            "field `record.histories`: landing 24 is not in the campaign",
        ),
        ("engine = \"core\"", "engine = \"bullet\"", "field `engine`"),
        (
            "engine = \"core\"",
            "engine = \"core\"\nengines = [\"core\", \"rapier\"]",
            "field `engines`: name the engines either with `engine` (one) or with `engines`",
        ),
        (
            "engine = \"core\"",
            "engines = [\"core\", \"core\"]",
            "field `engines`: core is named twice",
        ),
        ("engine = \"core\"", "engines = []", "field `engines`: expected at least one"),
        (
            "log_std_dev = 0.4",
            "log_std_dev = 1e300",
            "field `dispersion[3]`: its log_normal draws would overflow",
        ),
    ];
    for (from, to, expected) in cases {
        assert!(good.contains(from), "{from}");
        let message = refused(&good.replacen(from, to, 1));
        assert!(message.contains(expected), "{to}: {message}");
    }
    assert!(refused("").contains("empty file"));
    assert!(refused("landings = [").contains("not valid TOML"));
    let scene = refused(&good.replace("table-i-2-2-vv8.toml", "no-such.toml"));
    assert!(
        scene.contains("field `scenario`: the base scenario") && scene.contains("no-such.toml"),
        "{scene}"
    );
}

#[test]
fn merges_refuse_parts_of_other_campaigns_gaps_and_overlaps() {
    let tmp = tempfile::tempdir().unwrap();
    let campaign = Campaign::load(small()).unwrap();
    let part = |k: u64, n: u64, name: &str| {
        let dir = tmp.path().join(name);
        run(
            &campaign,
            Some(Shard { index: k, count: n }),
            None,
            Some(&dir),
            false,
            |_| (),
        )
        .unwrap();
        dir
    };
    let (a, b, c) = (part(1, 2, "a"), part(1, 3, "b"), part(3, 3, "c"));
    let message = |parts: &[&Path]| match merge(parts, &tmp.path().join("out"), |_| ()) {
        Err(CampaignError::Mismatch(m)) => m,
        other => panic!("expected a refusal, got {other:?}"),
    };
    assert!(message(&[&a, &b]).contains("overlap"));
    assert!(message(&[&a]).contains("landings 12 to 23 are missing"));
    assert!(message(&[&b, &c]).contains("leave a gap"));
    let other = tmp.path().join("other.toml");
    small_with(&other, 24);
    let text = std::fs::read_to_string(&other)
        .unwrap()
        .replace("seed = 7", "seed = 8");
    std::fs::write(&other, text).unwrap();
    let d = tmp.path().join("d");
    run(
        &Campaign::load(&other).unwrap(),
        Some(Shard { index: 2, count: 2 }),
        None,
        Some(&d),
        false,
        |_| (),
    )
    .unwrap();
    assert!(message(&[&a, &d]).contains("campaign (its SHA-256)"));
    // A paired part among one-engine parts: the engines are named, not two hashes.
    let paired = tmp.path().join("paired");
    let both = Campaign::load(small())
        .unwrap()
        .with_engines(
            vec![
                touchdown_scenario::schema::Engine::Core,
                touchdown_scenario::schema::Engine::Rapier,
            ],
            "--engines",
        )
        .unwrap();
    let last = Some(Shard {
        index: 24,
        count: 24,
    });
    run(&both, last, None, Some(&paired), false, |_| ()).unwrap();
    let engines = message(&[&a, &paired]);
    assert!(
        engines.contains("engines: core against core, rapier"),
        "{engines}"
    );
    // A record no landing could have written (an outcome of another name, or none): in a
    // finished part, refused by its manifest's seal; in the records a stopped run left, by file
    // and line when the run resumes: the counts would no longer add up.
    let middle = part(2, 3, "middle");
    let e = tmp.path().join("e");
    copy_dir(&c, &e);
    let jsonl = std::fs::read_to_string(c.join("landings.jsonl")).unwrap();
    let stopped = tmp.path().join("stopped");
    let partial = tmp.path().join("stopped.partial");
    let run_file = run_file_of(&std::fs::read(c.join("manifest.json")).unwrap());
    for (tampered, says) in [
        (
            jsonl.replacen("\"outcome\":\"", "\"outcome\":\"banana", 1),
            "\"banana",
        ),
        (
            jsonl.replacen("\"outcome\":", "\"outcome_was\":", 1),
            "unknown column",
        ),
        (without_failure(&jsonl), "column \"failure\" is missing"),
    ] {
        assert_ne!(tampered, jsonl);
        std::fs::write(e.join("landings.jsonl"), &tampered).unwrap();
        match merge(&[&b, &middle, &e], &tmp.path().join("out"), |_| ()) {
            Err(CampaignError::Store { path, message }) => {
                assert!(path.ends_with("e/landings.jsonl"), "{path}");
                assert!(
                    message.contains("is not the file its manifest sealed"),
                    "{message}"
                );
            }
            other => panic!("expected a refusal, got {other:?}"),
        }
        std::fs::create_dir_all(&partial).unwrap();
        std::fs::write(partial.join(".lock"), "").unwrap();
        std::fs::write(partial.join("run.json"), &run_file).unwrap();
        std::fs::write(partial.join("landings.jsonl"), &tampered).unwrap();
        let shard = Some(Shard { index: 3, count: 3 });
        match run(&campaign, shard, None, Some(&stopped), true, |_| ()) {
            Err(CampaignError::Store { path, message }) => {
                assert!(path.ends_with("stopped.partial/landings.jsonl:1"), "{path}");
                assert!(message.contains(says), "{message}");
            }
            other => panic!("expected a refusal, got {other:?}"),
        }
    }
}

/// A campaign folder loses nothing and claims nothing it does not hold: a `.partial` folder
/// touchdown did not make (no `.lock`) is never cleared, and a staging name is refused as
/// `--out`; records past the end of a part, an edited manifest, an edited record and a stray
/// history are refused by name; a run with nothing of its own to resume starts afresh; and an
/// `--add` stopped part-way resumes to the same bytes as one that was not.
#[test]
fn a_campaign_folder_keeps_what_it_did_not_write_and_claims_only_what_it_landed() {
    let tmp = tempfile::tempdir().unwrap();
    let campaign = Campaign::load(small()).unwrap();
    let refused = |result: Result<_, CampaignError>, at: &str, says: &str| match result {
        Err(CampaignError::Store { path, message }) => {
            assert!(path.ends_with(at), "{path} (expected …{at}): {message}");
            assert!(message.contains(says), "{message}");
        }
        other => panic!("expected a refusal naming {at}, got {other:?}"),
    };
    // A user's folder named as a staging folder is kept, whatever it holds.
    let notes = tmp.path().join("notes.partial");
    std::fs::create_dir(&notes).unwrap();
    std::fs::write(notes.join("notes.txt"), "keep").unwrap();
    let out = tmp.path().join("notes");
    refused(
        run(&campaign, None, None, Some(&out), false, |_| ()),
        "notes.partial",
        "did not leave there",
    );
    refused(
        run(&campaign, None, None, Some(&out), true, |_| ()),
        "notes.partial",
        "did not leave there",
    );
    assert_eq!(
        std::fs::read_to_string(notes.join("notes.txt")).unwrap(),
        "keep"
    );
    let file = tmp.path().join("file.partial");
    std::fs::write(&file, "keep").unwrap();
    refused(
        run(
            &campaign,
            None,
            None,
            Some(&tmp.path().join("file")),
            false,
            |_| (),
        ),
        "file.partial",
        "exists and is not a folder",
    );
    // A staging name as --out: the next run into its folder would clear it.
    let whole = tmp.path().join("whole");
    run(&campaign, None, None, Some(&whole), false, |_| ()).unwrap();
    for name in ["x.partial", "x.replaced"] {
        let staged = tmp.path().join(name);
        refused(
            run(&campaign, None, None, Some(&staged), false, |_| ()),
            name,
            "is the one touchdown builds a campaign folder in",
        );
        refused(
            merge(&[&whole], &staged, |_| ()),
            name,
            "is the one touchdown builds",
        );
    }
    // Records past the end of the part a stopped run resumes: not this run's.
    let half = Some(Shard { index: 1, count: 2 });
    let first = tmp.path().join("first");
    run(&campaign, half, None, Some(&first), false, |_| ()).unwrap();
    let run_file = run_file_of(&std::fs::read(first.join("manifest.json")).unwrap());
    let jsonl = std::fs::read_to_string(whole.join("landings.jsonl")).unwrap();
    let thirteen: String = jsonl.split_inclusive('\n').take(13).collect();
    let resumed = tmp.path().join("resumed");
    let partial = tmp.path().join("resumed.partial");
    std::fs::create_dir(&partial).unwrap();
    std::fs::write(partial.join(".lock"), "").unwrap();
    std::fs::write(partial.join("run.json"), &run_file).unwrap();
    std::fs::write(partial.join("landings.jsonl"), &thirteen).unwrap();
    refused(
        run(&campaign, half, None, Some(&resumed), true, |_| ()),
        "resumed.partial/landings.jsonl",
        "holds 13 records where this run has 12 landings",
    );
    // The run named but no records written: nothing to resume, a fresh run.
    std::fs::remove_file(partial.join("landings.jsonl")).unwrap();
    run(&campaign, half, None, Some(&resumed), true, |_| ()).unwrap();
    assert_same_files(&resumed, &first);
    // A finished part edited by hand: its manifest (the seed), a record (an outcome flipped),
    // a stray history.
    let second = tmp.path().join("second");
    run(
        &campaign,
        Some(Shard { index: 2, count: 2 }),
        None,
        Some(&second),
        false,
        |_| (),
    )
    .unwrap();
    let merged = tmp.path().join("merged");
    let edit = |name: &str, from: &str, to: &str| {
        let path = first.join(name);
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(text.contains(from), "{name} holds no {from}");
        std::fs::write(&path, text.replacen(from, to, 1)).unwrap();
        text
    };
    let manifest = edit("manifest.json", "\"seed\": 7", "\"seed\": 8");
    refused(
        merge(&[&first, &second], &merged, |_| ()),
        "first/manifest.json",
        "was edited",
    );
    std::fs::write(first.join("manifest.json"), manifest).unwrap();
    let records = edit(
        "landings.jsonl",
        "\"outcome\":\"stable\"",
        "\"outcome\":\"overturned\"",
    );
    refused(
        merge(&[&first, &second], &merged, |_| ()),
        "first/landings.jsonl",
        "is not the file its manifest sealed",
    );
    std::fs::write(first.join("landings.jsonl"), records).unwrap();
    std::fs::write(first.join("histories/landing-30.csv"), "t_s\n").unwrap();
    refused(
        merge(&[&first, &second], &merged, |_| ()),
        "first/histories/landing-30.csv",
        "is no history of a landing this part keeps",
    );
    std::fs::remove_file(first.join("histories/landing-30.csv")).unwrap();
    merge(&[&first, &second], &merged, |_| ()).unwrap();
    assert_same_files(&merged, &whole);
    // An empty shard (more shards than landings) claims no fraction, bound or correlation, and
    // merges with the others into the whole campaign.
    let empty = tmp.path().join("empty");
    let (manifest, statistics) = run(
        &campaign,
        Some(Shard {
            index: 1,
            count: 100,
        }),
        None,
        Some(&empty),
        false,
        |_| (),
    )
    .unwrap();
    assert_eq!(
        (manifest.part.first_landing, manifest.part.end_landing),
        (0, 0)
    );
    assert!(
        manifest.accuracy.is_none(),
        "an accuracy claimed for no landings"
    );
    let s = statistics.first();
    assert_eq!(
        (s.landings, s.stable.fraction, s.stable.lower_bound),
        (0, None, None)
    );
    assert!(s
        .influence
        .iter()
        .all(|i| i.correlation_with_stable.is_none()));
    let text = std::fs::read_to_string(empty.join("statistics.json")).unwrap();
    assert!(
        !text.contains("fraction") && !text.contains("correlation"),
        "{text}"
    );
    merge(&[&empty, &first, &second], &merged, |_| ()).unwrap();
    assert_same_files(&merged, &whole);
    // An --add stopped after copying the first records and landing two new ones resumes; `each`
    // sees the added records only, each once.
    let file = tmp.path().join("campaign.toml");
    small_with(&file, 16);
    let c16 = Campaign::load(&file).unwrap();
    let extended = tmp.path().join("extended");
    run(&c16, None, None, Some(&extended), false, |_| ()).unwrap();
    small_with(&file, 24);
    let c24 = Campaign::load(&file).unwrap();
    let at_once = tmp.path().join("at-once");
    run(&c24, None, None, Some(&at_once), false, |_| ()).unwrap();
    let staged = tmp.path().join("extended.partial");
    std::fs::create_dir(&staged).unwrap();
    std::fs::write(staged.join(".lock"), "").unwrap();
    std::fs::write(
        staged.join("run.json"),
        run_file_of(&std::fs::read(at_once.join("manifest.json")).unwrap()),
    )
    .unwrap();
    let eighteen: String = (std::fs::read_to_string(at_once.join("landings.jsonl")).unwrap())
        .split_inclusive('\n')
        .take(18)
        .collect();
    std::fs::write(staged.join("landings.jsonl"), eighteen).unwrap();
    let mut seen = Vec::new();
    touchdown_campaign::add(&c16, &extended, 8, None, true, |r| seen.push(r[0].clone())).unwrap();
    assert_same_files(&extended, &at_once);
    assert_eq!(seen, (16..24).map(Cell::Integer).collect::<Vec<_>>());
}

/// The JSON Lines `text` with the first record's `failure` left out.
fn without_failure(text: &str) -> String {
    let (first, rest) = text.split_once('\n').unwrap();
    let mut record: serde_json::Map<String, serde_json::Value> =
        serde_json::from_str(first).unwrap();
    record.remove("failure").unwrap();
    format!("{}\n{rest}", serde_json::Value::Object(record))
}

#[test]
fn the_parquet_records_read_back_in_pandas_polars_and_duckdb() {
    let tmp = tempfile::tempdir().unwrap();
    let campaign = Campaign::load(small()).unwrap();
    run(&campaign, None, None, Some(tmp.path()), false, |_| ()).unwrap();
    let out = std::process::Command::new(python())
        .arg(root().join("python/tests/campaign_read.py"))
        .arg(tmp.path())
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let report: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(report["rows"], 24);
    assert_eq!(
        report["readers"],
        serde_json::json!(["duckdb", "pandas", "polars"])
    );
}

/// A MuJoCo campaign lands through runners that serve many landings (one per thread): each
/// landing's record is that of a runner started for it alone.
#[test]
fn a_mujoco_campaign_lands_as_single_runs_do() {
    python();
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("mujoco.toml");
    small_with(&file, 4);
    let text = std::fs::read_to_string(&file).unwrap();
    std::fs::write(
        &file,
        text.replace("engine = \"core\"", "engine = \"mujoco\""),
    )
    .unwrap();
    let campaign = Campaign::load(&file).unwrap();
    let mut rows = Vec::new();
    let (manifest, _) = run(&campaign, None, Some(2), None, false, |r| {
        rows.push(r.clone())
    })
    .unwrap();
    let strokes: Vec<usize> = (0..4)
        .map(|leg| {
            let name = format!("leg{}.primary.stroke_m", leg + 1);
            manifest
                .columns
                .iter()
                .position(|c| c.name == name)
                .unwrap()
        })
        .collect();
    for (i, row) in rows.iter().enumerate() {
        let sc = campaign
            .base
            .with(&campaign.overrides(&draws(&campaign, i as u64)))
            .unwrap();
        let alone =
            touchdown_registry::land(campaign.engines[0], &file, &sc, &mut (), None).unwrap();
        for (leg, col) in strokes.iter().enumerate() {
            assert_eq!(
                row[*col],
                Cell::Float(alone.max_primary_stroke_m[leg]),
                "landing {i} leg {}",
                leg + 1
            );
        }
    }
}

/// Every leaf of the small campaign replaced, one at a time, by a hostile value: the campaign
/// is refused naming the file (and a field), or its first landings run to records with no
/// NaN and no panic (proptest, seeded as the scenario fuzzers are).
#[test]
fn mutated_campaign_files_are_refused_by_name_or_land_cleanly() {
    use proptest::prelude::*;
    let text = std::fs::read_to_string(small()).unwrap().replace(
        "scenario = \"../",
        &format!("scenario = \"{}/", scenario("").display()),
    );
    let table: toml::Table = toml::from_str(&text).unwrap();
    let mut leaves = Vec::new();
    fn walk(prefix: Vec<String>, v: &toml::Value, out: &mut Vec<Vec<String>>) {
        match v {
            toml::Value::Table(t) => {
                for (k, v) in t {
                    let mut p = prefix.clone();
                    p.push(k.clone());
                    walk(p, v, out);
                }
            }
            toml::Value::Array(a) => {
                for (i, v) in a.iter().enumerate() {
                    let mut p = prefix.clone();
                    p.push(i.to_string());
                    walk(p, v, out);
                }
            }
            _ => out.push(prefix),
        }
    }
    walk(Vec::new(), &toml::Value::Table(table.clone()), &mut leaves);
    let hostile: Vec<toml::Value> = vec![
        toml::Value::Float(f64::NAN),
        toml::Value::Float(f64::INFINITY),
        toml::Value::Float(-1e308),
        toml::Value::Float(1e308),
        toml::Value::Integer(0),
        toml::Value::Integer(-1),
        toml::Value::Integer(i64::MAX),
        toml::Value::Float(1e-300),
        toml::Value::String("x".into()),
        toml::Value::Boolean(true),
        toml::Value::Array(vec![]),
    ];
    let tmp = tempfile::tempdir().unwrap();
    let (mut runner, _, _) = touchdown_tests::fuzz_runner(48);
    let strategy = (any::<prop::sample::Index>(), any::<prop::sample::Index>());
    runner
        .run(&strategy, |(leaf, value)| {
            let path = &leaves[leaf.index(leaves.len())];
            let value = &hostile[value.index(hostile.len())];
            let mut t = toml::Value::Table(table.clone());
            let mut node = &mut t;
            for k in path {
                node = match node {
                    toml::Value::Table(t) => t.get_mut(k).unwrap(),
                    toml::Value::Array(a) => &mut a[k.parse::<usize>().unwrap()],
                    _ => unreachable!(),
                };
            }
            *node = value.clone();
            let file = tmp.path().join("mutant.toml");
            std::fs::write(&file, toml::to_string(&t).unwrap()).unwrap();
            let what = format!("{} = {value}", path.join("."));
            match Campaign::load(&file) {
                Err(e) => {
                    let m = e.to_string();
                    prop_assert!(m.starts_with(&file.display().to_string()), "{what}: {m}");
                }
                Ok(c) => {
                    for i in 0..c.landings.min(2) {
                        let row = touchdown_campaign::landing::land(&c, i, None)
                            .map_err(|e| TestCaseError::fail(format!("{what}: {e}")))?;
                        prop_assert!(
                            row.iter()
                                .all(|c| !matches!(c, Cell::Float(x) if !x.is_finite())),
                            "{what}: a non-finite number in landing {i}"
                        );
                    }
                }
            }
            Ok(())
        })
        .unwrap();
}

/// A paired copy of the small campaign: `landings` landings on the core and rapier, each run
/// 0.2 s (a one-value list), at `path`.
fn paired_with(path: &Path, landings: u64) {
    small_with(path, landings);
    let text = std::fs::read_to_string(path)
        .unwrap()
        .replace("engine = \"core\"", "engines = [\"core\", \"rapier\"]");
    let t_end = "\n[[dispersion]]\nfield = \"integrator.t_end\"\nunit = \"s\"\ndistribution = \"list\"\nvalues = [0.2]\n";
    let text = text.replacen("\n[[correlation]]", &format!("{t_end}\n[[correlation]]"), 1);
    std::fs::write(path, text).unwrap();
}

#[test]
fn a_paired_campaign_lands_each_draw_on_every_engine_and_lists_where_they_disagree() {
    use touchdown_scenario::schema::Engine;
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("paired.toml");
    paired_with(&file, 6);
    let campaign = Campaign::load(&file).unwrap();
    assert_eq!(campaign.engines, [Engine::Core, Engine::Rapier]);
    // The same bytes whole or in two shards merged, on one thread or two.
    let whole = tmp.path().join("whole");
    let mut rows = Vec::new();
    let (manifest, _) = run(&campaign, None, Some(1), Some(&whole), false, |r| {
        rows.push(r.clone())
    })
    .unwrap();
    let merged = sharded(&campaign, tmp.path(), &[2, 1]);
    assert_same_files(&whole, &merged);
    for engine in ["core", "rapier"] {
        assert!(whole
            .join(format!("histories/{engine}/landing-3.csv"))
            .is_file());
    }
    // One record a landing, a block per engine, each block what a single run of that engine
    // measures.
    let column = |name: &str| {
        manifest
            .columns
            .iter()
            .position(|c| c.name == name)
            .unwrap()
    };
    let mut differ = 0;
    for (i, row) in rows.iter().enumerate() {
        let sc = campaign
            .base
            .with(&campaign.overrides(&draws(&campaign, i as u64)))
            .unwrap();
        for engine in [Engine::Core, Engine::Rapier] {
            let alone = touchdown_registry::land(engine, &file, &sc, &mut (), None).unwrap();
            for leg in 0..4 {
                let name = format!("{}.leg{}.primary.stroke_m", engine.name(), leg + 1);
                assert_eq!(
                    row[column(&name)],
                    Cell::Float(alone.max_primary_stroke_m[leg]),
                    "landing {i}: {name}"
                );
            }
        }
        differ += usize::from(row[column("core.outcome")] != row[column("rapier.outcome")]);
    }
    // The pair's statistics count what the records show; every landing it lists is written as
    // the scenario that ran it.
    let text = std::fs::read_to_string(whole.join("statistics.json")).unwrap();
    let stats: serde_json::Value = serde_json::from_str(&text).unwrap();
    let pair = &stats["pairs"][0];
    assert_eq!(pair["engines"], serde_json::json!(["core", "rapier"]));
    assert_eq!(pair["disagreement"]["landings"], serde_json::json!(differ));
    // The one-value `integrator.t_end` list is the same on every landing: not an influence.
    for influence in [&pair["influence"], &stats["engines"][0]["influence"]] {
        let columns: Vec<&str> = (influence.as_array().unwrap().iter())
            .map(|i| i["column"].as_str().unwrap())
            .collect();
        assert!(
            !columns.is_empty() && !columns.contains(&"applied.integrator.t_end_s"),
            "{columns:?}"
        );
    }
    assert_eq!(stats["engines"][1]["engine"], "rapier");
    let worst = pair["worst"].as_array().unwrap();
    assert!(!worst.is_empty());
    for w in worst {
        let landing = w["landing"].as_u64().unwrap();
        let written =
            touchdown_scenario::Scenario::load(whole.join(w["scenario_file"].as_str().unwrap()))
                .unwrap();
        // The landing that ran, named and described as the file names it: every other value
        // the same.
        let mut overrides = campaign.overrides(&draws(&campaign, landing));
        assert_eq!(
            written.file.name,
            format!("{}: landing {landing}", campaign.name)
        );
        overrides.push(("name", toml::Value::String(written.file.name.clone())));
        overrides.push((
            "description",
            toml::Value::String(written.file.description.clone()),
        ));
        let ran = campaign.base.with(&overrides).unwrap();
        assert_eq!(written.sha256(), ran.sha256(), "landing {landing}");
    }
    // The multi-fidelity estimate reads this folder with 12 core landings of the same draws.
    let low = tmp.path().join("low");
    let core_alone = Campaign::load(&file)
        .unwrap()
        .with_engines(vec![Engine::Core], "--engines")
        .unwrap();
    run(&core_alone, None, Some(2), Some(&low), false, |_| ()).unwrap();
    touchdown_campaign::add(&core_alone, &low, 6, Some(2), false, |_| ()).unwrap();
    let mf = touchdown_campaign::fidelity::from_folders(&whole, &low, Some(100.0)).unwrap();
    assert_eq!(
        (mf.low_engine.as_str(), mf.high_engine.as_str()),
        ("core", "rapier")
    );
    assert_eq!((mf.paired_landings, mf.low_landings), (6, 12));
    let rapier_stable = rows
        .iter()
        .filter(|r| r[column("rapier.outcome")] == Cell::Text("stable".into()))
        .count();
    assert_eq!(mf.stable.high_alone, rapier_stable as f64 / 6.0);
    let other = tmp.path().join("other");
    run(
        &Campaign::load(small()).unwrap(),
        None,
        Some(2),
        Some(&other),
        false,
        |_| (),
    )
    .unwrap();
    let refused = touchdown_campaign::fidelity::from_folders(&whole, &other, None)
        .unwrap_err()
        .to_string();
    assert!(refused.contains("what draws the landings"), "{refused}");
    // Landings past the paired ones spliced in from another campaign: refused by the seal.
    let spliced = tmp.path().join("spliced");
    copy_dir(&low, &spliced);
    let own = std::fs::read_to_string(low.join("landings.jsonl")).unwrap();
    let theirs = std::fs::read_to_string(other.join("landings.jsonl")).unwrap();
    let mut lines: Vec<&str> = own.split_inclusive('\n').collect();
    lines[10] = theirs.split_inclusive('\n').nth(10).unwrap();
    std::fs::write(spliced.join("landings.jsonl"), lines.concat()).unwrap();
    let refused = touchdown_campaign::fidelity::from_folders(&whole, &spliced, None)
        .unwrap_err()
        .to_string();
    assert!(
        refused.contains("is not the file its manifest sealed"),
        "{refused}"
    );
    // `--engines` makes another campaign of the same file; an engine named twice is refused.
    let single = Campaign::load(small()).unwrap();
    let identity = single.identity.clone();
    let paired = single
        .with_engines(vec![Engine::Core, Engine::Rapier], "--engines")
        .unwrap();
    assert!(paired.paired() && paired.identity != identity);
    let twice = Campaign::load(small())
        .unwrap()
        .with_engines(vec![Engine::Rapier, Engine::Rapier], "--engines")
        .unwrap_err()
        .to_string();
    assert!(
        twice.contains("field `--engines`: rapier is named twice"),
        "{twice}"
    );
}

/// The multi-fidelity interval's coverage, measured: the 1,000 paired core/MuJoCo landings of
/// `lm-1-6-d3117-paired` (tests/data/fidelity/d3117-core-mujoco-stable.csv, from
/// docs/campaigns/d3117-paired-mujoco.txt's run) taken as the population, whose MuJoCo P(stable)
/// is known; 2,000 seeds each draw m landings from it with replacement, the first n paired.
/// From n = `MIN_PAIRED_LANDINGS` on (at m = 10·n and 100·n) the 95 % interval must cover the
/// truth as often as stated, within three binomial standard errors; at n = 8 it must not (the
/// minimum is needed). The variance reduction is what the engines' correlation allows
/// (ρ ≈ 0.5: 1/(1 − 0.9·ρ²) ≈ 1.3). `-- --nocapture` prints the coverages.
#[test]
fn the_multi_fidelity_interval_covers_a_known_probability_as_stated() {
    use touchdown_campaign::fidelity::estimate;
    let text =
        std::fs::read_to_string(root().join("tests/data/fidelity/d3117-core-mujoco-stable.csv"))
            .unwrap();
    let rows: Vec<(bool, bool)> = text
        .lines()
        .skip(1)
        .map(|l| {
            let v: Vec<&str> = l.split(',').collect();
            (v[1] == "1", v[2] == "1")
        })
        .collect();
    assert_eq!(rows.len(), 1000);
    let truth = rows.iter().filter(|r| r.1).count() as f64 / 1000.0;
    // SplitMix64: a seeded stream without a dependency.
    let mut state: u64 = 20261127;
    let mut next = move || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    };
    // From the stated minimum of paired landings on, at m = 10·n and 100·n: coverage within
    // three standard errors of the confidence; well below it, not (the minimum is needed).
    let seeds = 2000;
    let mut coverage = |n: usize, m: usize, reduction: &mut f64| {
        let mut covered = 0;
        for _ in 0..seeds {
            let drawn: Vec<(bool, bool)> = (0..m).map(|_| rows[(next() % 1000) as usize]).collect();
            let high: Vec<bool> = drawn[..n].iter().map(|r| r.1).collect();
            let low_all: Vec<bool> = drawn.iter().map(|r| r.0).collect();
            let e = estimate(&high, &low_all[..n], &low_all, 0.95, None).unwrap();
            covered += usize::from(e.lower <= truth && truth <= e.upper);
            *reduction += e.variance_reduction / seeds as f64;
        }
        covered as f64 / seeds as f64
    };
    let sigma = (0.95f64 * 0.05 / seeds as f64).sqrt();
    let n = touchdown_campaign::fidelity::MIN_PAIRED_LANDINGS as usize;
    let mut reduction = 0.0;
    for (m, mean_reduction) in [(10 * n, &mut reduction), (100 * n, &mut 0.0)] {
        let c = coverage(n, m, mean_reduction);
        eprintln!("coverage at n {n}, m {m}: {c:.4} over {seeds} seeds");
        assert!(
            (c - 0.95).abs() <= 3.0 * sigma,
            "coverage {c} at n {n}, m {m}"
        );
    }
    let below = coverage(8, 800, &mut 0.0);
    eprintln!("coverage at n 8, m 800: {below:.4}");
    assert!(below < 0.95 - 3.0 * sigma, "coverage {below} at n 8, m 800");
    // The mean variance reduction at m = 10·n.
    assert!(
        (1.2..1.5).contains(&reduction),
        "mean variance reduction {reduction}"
    );
}

/// The campaign folders fuzzed (docs/robustness.md, "Fuzzing"): a finished folder, a shard, a
/// stopped run's `.partial`, a user's folder of a staging name, each damaged one way or another
/// (a byte flipped, a file cut short, removed or replaced, a stray history, a record too many),
/// then run into, resumed, merged, extended or estimated from. Whatever the case: nothing
/// panics; a user's files are never touched; an operation that succeeds writes exactly the
/// folder an undamaged run writes; one that fails names a path and leaves its `--out` as it
/// was. `TOUCHDOWN_FUZZ_CASES` and `TOUCHDOWN_FUZZ_SEED` run more.
#[test]
fn hostile_campaign_folders_lose_nothing_and_claim_nothing() {
    use proptest::prelude::*;
    use touchdown_scenario::schema::Engine;
    let tmp = tempfile::tempdir().unwrap();
    let pristine = tmp.path().join("pristine");
    std::fs::create_dir(&pristine).unwrap();
    let (six, four) = (pristine.join("six.toml"), pristine.join("four.toml"));
    small_with(&six, 6);
    small_with(&four, 4);
    let (c6, c4) = (
        Campaign::load(&six).unwrap(),
        Campaign::load(&four).unwrap(),
    );
    let half = |k| Some(Shard { index: k, count: 2 });
    run(
        &c6,
        None,
        None,
        Some(&pristine.join("whole")),
        false,
        |_| (),
    )
    .unwrap();
    run(
        &c6,
        half(1),
        None,
        Some(&pristine.join("part-1")),
        false,
        |_| (),
    )
    .unwrap();
    run(
        &c6,
        half(2),
        None,
        Some(&pristine.join("part-2")),
        false,
        |_| (),
    )
    .unwrap();
    run(&c4, None, None, Some(&pristine.join("four")), false, |_| ()).unwrap();
    // What `four` extended by two landings is: the campaign of its file planned with six.
    small_with(&four, 6);
    let extended = Campaign::load(&four).unwrap();
    small_with(&four, 4);
    let four_plus_two = pristine.join("four-plus-two");
    run(&extended, None, None, Some(&four_plus_two), false, |_| ()).unwrap();
    let paired_file = pristine.join("paired.toml");
    paired_with(&paired_file, 4);
    let paired = Campaign::load(&paired_file).unwrap();
    run(
        &paired,
        None,
        None,
        Some(&pristine.join("paired")),
        false,
        |_| (),
    )
    .unwrap();
    paired_with(&paired_file, 6);
    let low = Campaign::load(&paired_file)
        .unwrap()
        .with_engines(vec![Engine::Core], "--engines")
        .unwrap();
    run(&low, None, None, Some(&pristine.join("low")), false, |_| ()).unwrap();
    let folders = ["whole", "part-1", "part-2", "four", "paired", "low"];
    let files = [
        "manifest.json",
        "landings.jsonl",
        "landings.parquet",
        "statistics.json",
    ];
    let (mut runner, _, _) = touchdown_tests::fuzz_runner(16);
    let strategy = (0..9usize, 0..6usize, 0..4usize, 0..7usize, any::<u64>());
    let case_number = std::cell::Cell::new(0);
    let (succeeded, refused) = (std::cell::Cell::new(0), std::cell::Cell::new(0));
    runner
        .run(&strategy, |(damage, target, file, operation, pick)| {
            let case = tmp.path().join(format!("case-{}", case_number.get()));
            case_number.set(case_number.get() + 1);
            for name in folders {
                copy_dir(&pristine.join(name), &case.join(name));
            }
            // The folder damaged: one the operation reads or writes.
            let inputs: &[&str] = match operation {
                0 | 1 => &["whole"],
                2 => &["part-1"],
                3 | 4 => &["part-1", "part-2"],
                5 => &["four"],
                _ => &["paired", "low"],
            };
            let target = inputs[target % inputs.len()];
            let folder = case.join(target);
            let file = folder.join(files[file]);
            let staging = case.join(format!("{target}.partial"));
            let user_file = staging.join("notes.txt");
            match damage {
                0 => {}
                1 => {
                    let mut bytes = std::fs::read(&file).unwrap();
                    let i = (pick % bytes.len() as u64) as usize;
                    bytes[i] ^= 0x20;
                    std::fs::write(&file, bytes).unwrap();
                }
                2 => {
                    let bytes = std::fs::read(&file).unwrap();
                    std::fs::write(&file, &bytes[..(pick % bytes.len() as u64) as usize]).unwrap();
                }
                3 => std::fs::remove_file(&file).unwrap(),
                4 => {
                    std::fs::create_dir_all(folder.join("histories")).unwrap();
                    std::fs::write(folder.join("histories/landing-99.csv"), "t_s\n").unwrap();
                }
                5 => {
                    std::fs::create_dir(&staging).unwrap();
                    std::fs::write(&user_file, "keep").unwrap();
                }
                6 => std::fs::write(&staging, "keep").unwrap(),
                7 => {
                    // A stopped run of this folder's campaign: its lock, its run file, the first
                    // records.
                    let manifest = std::fs::read(folder.join("manifest.json")).unwrap();
                    let jsonl = std::fs::read_to_string(folder.join("landings.jsonl")).unwrap();
                    let kept: String = jsonl
                        .split_inclusive('\n')
                        .take(pick as usize % 3)
                        .collect();
                    std::fs::create_dir(&staging).unwrap();
                    std::fs::write(staging.join(".lock"), "").unwrap();
                    std::fs::write(staging.join("run.json"), run_file_of(&manifest)).unwrap();
                    std::fs::write(staging.join("landings.jsonl"), kept).unwrap();
                }
                _ => {
                    let jsonl =
                        std::fs::read_to_string(file.with_file_name("landings.jsonl")).unwrap();
                    let last = jsonl.lines().last().unwrap().to_string();
                    std::fs::write(folder.join("landings.jsonl"), format!("{jsonl}{last}\n"))
                        .unwrap();
                }
            }
            let resume = pick % 2 == 0;
            let outs = [
                "whole", "whole", "part-1", "merged", "part-1", "four", "paired",
            ];
            let before = snapshot(&case.join(outs[operation]));
            let (out, expected, result) = match operation {
                0 | 1 => {
                    let out = case.join("whole");
                    let r = run(&c6, None, None, Some(&out), resume, |_| ()).map(|_| ());
                    (out, pristine.join("whole"), r)
                }
                2 => {
                    let out = case.join("part-1");
                    let r = run(&c6, half(1), None, Some(&out), resume, |_| ()).map(|_| ());
                    (out, pristine.join("part-1"), r)
                }
                3 | 4 => {
                    let out = case.join(if operation == 3 { "merged" } else { "part-1" });
                    let parts = [case.join("part-1"), case.join("part-2")];
                    let r = merge(&[&parts[0], &parts[1]], &out, |_| ()).map(|_| ());
                    (out, pristine.join("whole"), r)
                }
                5 => {
                    let out = case.join("four");
                    let r = touchdown_campaign::add(&c4, &out, 2, None, resume, |_| ()).map(|_| ());
                    (out, four_plus_two.clone(), r)
                }
                _ => {
                    let r = touchdown_campaign::fidelity::from_folders(
                        &case.join("paired"),
                        &case.join("low"),
                        None,
                    )
                    .map(|_| ());
                    let out = case.join("paired");
                    (out.clone(), out, r)
                }
            };
            let label = format!(
                "damage {damage} to {} ({}), operation {operation}",
                target,
                file.display()
            );
            let user = match damage {
                5 => std::fs::read_to_string(&user_file).ok(),
                6 => std::fs::read_to_string(&staging).ok(),
                _ => Some("keep".into()),
            };
            prop_assert_eq!(
                user.as_deref(),
                Some("keep"),
                "{}: a user's file was touched",
                label
            );
            match result {
                Ok(()) if operation < 6 => {
                    succeeded.set(succeeded.get() + 1);
                    prop_assert!(
                        snapshot(&out) == snapshot(&expected),
                        "{}: succeeded with another folder",
                        label
                    );
                }
                Ok(()) => succeeded.set(succeeded.get() + 1),
                Err(e) => {
                    refused.set(refused.get() + 1);
                    let message = e.to_string();
                    prop_assert!(
                        message.contains(&*case.to_string_lossy()),
                        "{}: {}",
                        label,
                        message
                    );
                    prop_assert!(
                        snapshot(&out) == before,
                        "{}: failed ({}) and changed its --out",
                        label,
                        message
                    );
                }
            }
            std::fs::remove_dir_all(&case).unwrap();
            Ok(())
        })
        .unwrap();
    eprintln!(
        "{} cases: {} succeeded as an undamaged run, {} refused naming a path",
        case_number.get(),
        succeeded.get(),
        refused.get()
    );
}

/// Every file under `dir` (none if it does not exist) with its bytes.
fn snapshot(dir: &Path) -> Vec<(PathBuf, Option<Vec<u8>>)> {
    if !dir.is_dir() {
        return Vec::new();
    }
    tree(dir)
        .into_iter()
        .map(|f| {
            let bytes = std::fs::read(dir.join(&f)).ok();
            (f, bytes)
        })
        .collect()
}

/// A campaign statistic added by the checklist of CONTRIBUTING.md ("Adding a campaign
/// statistic"): each landing's energy imbalance, |residual| / scale, is its summary's, every
/// completed landing keeps it within the energy guard's tolerance (the guard stops a run
/// beyond it), and the statistics give its percentiles, which never pass the largest.
#[test]
fn the_energy_imbalance_is_each_landing_s_and_within_the_guard() {
    let tmp = tempfile::tempdir().unwrap();
    let campaign = Campaign::load(small()).unwrap();
    let columns = touchdown_campaign::record::columns(&campaign);
    let at = |name: &str| columns.iter().position(|c| c.name == name).unwrap();
    let (imbalance, residual, scale) = (
        at("energy_imbalance_of_scale"),
        at("energy_residual_j"),
        at("energy_scale_j"),
    );
    let tolerance = campaign.base_scenario.integrator.energy_tolerance;
    let floor = campaign.base_scenario.energy_floor_j();
    let mut largest: f64 = 0.0;
    let mut measured = 0;
    let (_, report) = run(
        &campaign,
        None,
        Some(2),
        Some(&tmp.path().join("c")),
        false,
        |r| {
            if let (Cell::Float(i), Cell::Float(res), Cell::Float(s)) =
                (&r[imbalance], &r[residual], &r[scale])
            {
                assert_eq!(*i, res.abs() / s, "landing {:?}", r[0]);
                if *s >= floor {
                    assert!(*i <= tolerance, "landing {:?}: {i} of its scale", r[0]);
                }
                largest = largest.max(*i);
                measured += 1;
            }
        },
    )
    .unwrap();
    assert!(measured > 0);
    let p = (report.first().percentiles.iter())
        .find(|p| p.column == "energy_imbalance_of_scale")
        .expect("the imbalance's percentiles");
    assert_eq!(p.landings, measured);
    assert_eq!(p.max, largest);
    assert!(p.p50 <= p.p90 && p.p90 <= p.p99 && p.p99 <= p.max, "{p:?}");
}
