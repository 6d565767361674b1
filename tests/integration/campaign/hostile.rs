//! Fuzzed: mutated campaign files and damaged campaign folders, refused by name or landed cleanly.

use super::{copy_dir, paired_with, run_file_of, small, small_with, tree};
use std::path::{Path, PathBuf};
use touchdown_campaign::record::Cell;
use touchdown_campaign::run::run;
use touchdown_campaign::{merge, Campaign, Shard};
use touchdown_tests::scenario;

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
