//! Bad campaign files and bad merges are refused, naming the file and the field or the part.

use super::{copy_dir, run_file_of, small, small_with};
use std::path::Path;
use touchdown_campaign::run::run;
use touchdown_campaign::{merge, Campaign, CampaignError, Shard};
use touchdown_tests::scenario;

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
            "unit = \"ft/s\"\ndistribution = \"normal\"",
            "unit = \"1/s\"\ndistribution = \"normal\"",
            "field `dispersion[0].unit`: \"1/s\" is a 1/time, but `touchdown.vertical_velocity` is a length/time: write its numbers in ft/s",
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
            "confidence = 0.9",
            "confidence = 0.9\n[accuracy]\nlandings = 0",
            "field `accuracy.landings`: expected at least 1 landing in the accuracy sample, got 0",
        ),
        (
            "confidence = 0.9",
            "confidence = 0.9\n[accuracy]\nsample = 5",
            "field `accuracy.sample`",
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

/// A rate is written per second (`1/s`): a multibody contact's natural frequency dispersed
/// over a list of values loads, and its record column names its unit.
#[test]
fn a_rate_is_dispersed_in_its_own_unit_per_second() {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("rate.toml");
    small_with(&file, 4);
    let mut text = std::fs::read_to_string(&file).unwrap();
    text.push_str(
        "\n[[dispersion]]\nfield = \"engines.rapier.contact_frequency\"\nunit = \"1/s\"\ndistribution = \"list\"\nvalues = [4000.0, 6000.0]\n",
    );
    std::fs::write(&file, &text).unwrap();
    let campaign = Campaign::load(&file).unwrap();
    let rate = campaign.dispersions.last().unwrap();
    assert_eq!(rate.column, "engines.rapier.contact_frequency_per_s");
    std::fs::write(&file, text.replace("unit = \"1/s\"", "unit = \"1/m\"")).unwrap();
    let message = Campaign::load(&file).unwrap_err().to_string();
    assert!(
        message.contains("the scenario states lengths in ft"),
        "{message}"
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

/// The JSON Lines `text` with the first record's `failure` left out.
fn without_failure(text: &str) -> String {
    let (first, rest) = text.split_once('\n').unwrap();
    let mut record: serde_json::Map<String, serde_json::Value> =
        serde_json::from_str(first).unwrap();
    record.remove("failure").unwrap();
    format!("{}\n{rest}", serde_json::Value::Object(record))
}
