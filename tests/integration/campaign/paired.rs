//! Paired campaigns on several engines, and the multi-fidelity interval's measured coverage.

use super::{assert_same_files, copy_dir, paired_with, sharded, small};
use touchdown_campaign::landing::draws;
use touchdown_campaign::record::Cell;
use touchdown_campaign::run::run;
use touchdown_campaign::Campaign;
use touchdown_tests::root;

/// A paired campaign states each multibody engine's accuracy as it states the core's
/// (docs/campaigns.md, "Accuracy"): its first landing landed again on rapier at the step the
/// file gives, and at a half and a quarter of it, written here by hand: the quarter takes four
/// times the steps, and the manifest's errors and outcomes are those runs'.
#[test]
fn a_paired_campaign_states_each_multibody_engines_accuracy_against_its_step_refined() {
    use touchdown_scenario::schema::Engine;
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("paired.toml");
    paired_with(&file, 4);
    let campaign = Campaign::load(&file).unwrap();
    let (manifest, _) = run(&campaign, None, Some(1), None, false, |_| ()).unwrap();
    assert_eq!(manifest.accuracy.map(|a| a.engine), Some("core".into()));
    let [a] = manifest.multibody_accuracy.as_slice() else {
        panic!(
            "expected rapier's accuracy: {:?}",
            manifest.multibody_accuracy
        );
    };
    assert_eq!(
        (a.engine.as_str(), a.sample_landings, a.refinement),
        ("rapier", 1, 4.0)
    );
    let sc = touchdown_campaign::landing::scenario(&campaign, &draws(&campaign, 0)).unwrap();
    let dt = touchdown_registry::time_step(Engine::Rapier, &sc).unwrap();
    let seconds = sc.units().time();
    let at = |f: f64| {
        let sc = (sc.clone())
            .with_rapier(|r| r.timestep = Some(dt / f / seconds))
            .and_then(|sc| sc.with_integrator(|it| it.max_steps *= f))
            .unwrap();
        touchdown_registry::land(Engine::Rapier, &file, &sc, &mut (), None).unwrap()
    };
    let (x, half, x_ref) = (at(1.0), at(2.0), at(4.0));
    assert!(
        x_ref.steps >= 4 * x.steps - 4,
        "{} against {}",
        x_ref.steps,
        x.steps
    );
    assert_eq!(a.outcomes_identical, u64::from(x.outcome == x_ref.outcome));
    let largest = |s: &touchdown_record::Summary| {
        s.max_primary_stroke_m.iter().fold(0.0f64, |m, x| m.max(*x))
    };
    let both = a.maxima.expect("the three runs completed");
    let error =
        |s: &touchdown_record::Summary| (largest(s) - largest(&x_ref)).abs() / largest(&x_ref);
    assert_eq!(both.settings.largest_primary_stroke.fraction, error(&x));
    assert_eq!(both.reference.largest_primary_stroke.fraction, error(&half));
    assert!(error(&x) > 0.0, "the refined runs are other runs");
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
/// `lm-1-6-d3117-paired` (tests/data/fidelity/d3117-core-mujoco-stable.csv, from its run on
/// the wall at 0.5 s, docs/campaigns.md "Multi-fidelity estimate") taken as the population,
/// whose MuJoCo P(stable) is known; 2,000 seeds each draw m landings from it with replacement, the first n paired.
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
