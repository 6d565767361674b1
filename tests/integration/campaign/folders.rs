//! Campaign folders: replaced only when complete, resumed to the same bytes, never claiming more.

use super::{assert_same_files, copy_dir, run_file_of, small, small_with};
use std::path::{Path, PathBuf};
use touchdown_campaign::record::Cell;
use touchdown_campaign::run::run;
use touchdown_campaign::{merge, Campaign, CampaignError, Shard};

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
