//! Campaigns (docs/campaigns.md): the same bytes whatever the threads, shards or order;
//! extensions that leave the first landings alone; folders replaced only when complete and
//! resumed to the same bytes; the values applied are the values drawn and reach the model; the
//! accuracy statement, a probability known in closed form and the energy imbalance; bad files,
//! bad merges and hostile folders refused by name; paired campaigns and the multi-fidelity
//! interval; the Parquet records read back in pandas, polars and DuckDB.

use std::path::{Path, PathBuf};
use touchdown_campaign::run::run;
use touchdown_campaign::{merge, Campaign, Shard};
use touchdown_tests::scenario;

mod folders;
mod hostile;
mod paired;
mod records;
mod refusals;
mod shards;
mod statistics;

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

/// The `run.json` of the run that writes the folder whose manifest is `manifest`, as the run
/// writes it when it starts: the manifest it will write, but for the accuracy it measures once
/// its landings have run and the seal of its files.
fn run_file_of(manifest: &[u8]) -> String {
    let mut identity: touchdown_campaign::store::Manifest =
        serde_json::from_slice(manifest).unwrap();
    identity.accuracy.take();
    identity.multibody_accuracy.clear();
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
