//! Running a campaign: each landing drawn, resolved, read back and landed; landings in parallel
//! (rayon) with their records handed on in landing order; shards, merges and extensions.

use crate::accuracy;
use crate::analysis;
use crate::folder::{self, Staging};
use crate::landing::{land, pool};
use crate::paired::Report;
use crate::record::{self, Row};
use crate::spec::Campaign;
use crate::store::{self, Manifest, Part};
use crate::CampaignError;
use rayon::prelude::*;
use std::collections::BTreeMap;
use std::ops::Range;
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};

/// A shard `K/N` (K from 1): the landings `⌊(K−1)·n/N⌋ .. ⌊K·n/N⌋` of a campaign of n.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// K, from 1.
    pub index: u64,
    /// N.
    pub count: u64,
}

impl std::str::FromStr for Shard {
    type Err = String;
    fn from_str(s: &str) -> Result<Shard, String> {
        let bad = || format!("{s:?}: expected K/N with 1 ≤ K ≤ N, e.g. 2/4");
        let (k, n) = s.split_once('/').ok_or_else(bad)?;
        let (index, count) = (
            k.trim().parse().map_err(|_| bad())?,
            n.trim().parse().map_err(|_| bad())?,
        );
        if index == 0 || index > count {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

impl Shard {
    /// The landings of this shard of a campaign of `landings`.
    pub fn range(self, landings: u64) -> Range<u64> {
        let at = |k: u64| ((k as u128 * landings as u128) / self.count as u128) as u64;
        at(self.index - 1)..at(self.index)
    }
}

/// Runs the landings `range` on `threads` threads (all the machine's with `None`), handing each
/// record to `each` in landing order as soon as it and every earlier one have finished (the
/// records are not kept). The first landing (in order) whose engine cannot be set up, or the
/// first error of `each` (a record that cannot be written), stops the run.
pub fn run_range(
    campaign: &Campaign,
    range: Range<u64>,
    threads: Option<usize>,
    histories: Option<&Path>,
    mut each: impl FnMut(&Row) -> Result<(), CampaignError>,
) -> Result<(), CampaignError> {
    let pool = pool(threads)?;
    let cancel = AtomicBool::new(false);
    let (tx, rx) = std::sync::mpsc::channel::<(u64, Result<Row, CampaignError>)>();
    let mut failure: Option<(u64, CampaignError)> = None;
    std::thread::scope(|s| {
        let work = range.clone();
        let cancel = &cancel;
        s.spawn(move || {
            pool.install(|| {
                // Landings are taken in order (`par_bridge` hands the next one to whichever
                // thread is free), so the records waiting for an earlier one stay about as
                // many as the threads: a split range would let a thread run far ahead.
                work.into_iter().par_bridge().for_each_with(tx, |tx, i| {
                    if cancel.load(Ordering::Relaxed) {
                        return;
                    }
                    let r = land(campaign, i, histories);
                    if r.is_err() {
                        cancel.store(true, Ordering::Relaxed);
                    }
                    let _ = tx.send((i, r));
                })
            })
        });
        // Records finished out of order wait here for the earlier ones.
        let mut pending = BTreeMap::new();
        let mut next = range.start;
        for (i, r) in rx {
            match r {
                Ok(row) => {
                    pending.insert(i, row);
                    while let Some(row) = pending.remove(&next) {
                        if failure.is_none() {
                            if let Err(e) = each(&row) {
                                cancel.store(true, Ordering::Relaxed);
                                failure = Some((next, e));
                            }
                        }
                        next += 1;
                    }
                }
                Err(e) => {
                    if failure.as_ref().is_none_or(|(j, _)| i < *j) {
                        failure = Some((i, e));
                    }
                }
            }
        }
    });
    match failure {
        Some((_, e)) => Err(e),
        None => Ok(()),
    }
}

/// The name of the file, in a campaign folder being built, that names the run building it: the
/// manifest the folder will have but for the accuracy measured at the end, so that `--resume`
/// goes on only with the same run.
const RUN_FILE: &str = "run.json";

/// Runs a campaign, or one shard of it, writing its files into `out` when given (else into a
/// temporary folder, removed at the end); `each` sees every record in landing order. Returns
/// the manifest and the statistics. `out` must be new, empty, or this very part of this
/// campaign (which is replaced): it is checked before any landing runs. The folder is built
/// beside `out` (module [`crate::folder`]), each record written as its landing finishes, and
/// takes the place of `out` only when complete. With `resume`, a run of this same part by this
/// same build that was stopped (killed, out of time, out of disk) goes on from the records it
/// wrote, which `each` sees first; the result is the same, byte for byte, as an uninterrupted
/// run's. The records are never held: what grows with the landings is 16 bytes a landing of
/// the statistics and 10 of the Parquet footer (docs/campaigns.md, "Output").
pub fn run(
    campaign: &Campaign,
    shard: Option<Shard>,
    threads: Option<usize>,
    out: Option<&Path>,
    resume: bool,
    mut each: impl FnMut(&Row),
) -> Result<(Manifest, Report), CampaignError> {
    let (range, manifest) = planned(campaign, shard);
    let scratch;
    let (staging, dir) = match out {
        Some(dir) => {
            folder::check_out(dir, |held| same_part(&manifest, held))?;
            // What a stopped run left is kept or cleared by `staged_journal`.
            let staging = Staging::keeping(dir)?;
            let dir = staging.dir().to_path_buf();
            (Some(staging), dir)
        }
        None => {
            scratch = tempfile::tempdir().map_err(|e| {
                let message = format!("cannot create a temporary folder: {e}");
                CampaignError::store(&std::env::temp_dir(), message)
            })?;
            (None, scratch.path().to_path_buf())
        }
    };
    let histories = staging.as_ref().map(|s| s.dir().join("histories"));
    let (mut journal, done) = match &staging {
        Some(staging) => staged_journal(staging, &manifest, resume, range.clone(), &mut each)?,
        None => fresh_journal(&dir, &manifest)?,
    };
    run_range(
        campaign,
        range.start + done..range.end,
        threads,
        histories.as_deref(),
        |row| {
            journal.append(row)?;
            each(row);
            Ok(())
        },
    )?;
    let mut manifest = manifest;
    if range.start == 0 && !range.is_empty() {
        manifest.state(accuracy::measure(campaign, campaign.landings, threads)?);
    }
    finish(&dir, journal, manifest, staging)
}

/// Whether `held`, a folder's manifest, is of the part `manifest` plans of the same campaign:
/// `Err` says what differs and what to do.
fn same_part(manifest: &Manifest, held: &Manifest) -> Result<(), String> {
    held.same_campaign(manifest).map_err(|m| {
        format!("holds another campaign's landings ({m}): name a new or empty folder")
    })?;
    if held.part != manifest.part || held.landings != manifest.landings {
        return Err(format!(
            "holds landings {} to {} of {} of this campaign, this run writes {} to {} of {}: name a new or empty folder (or extend a finished campaign with --add)",
            held.part.first_landing,
            held.part.end_landing.saturating_sub(1),
            held.landings,
            manifest.part.first_landing,
            manifest.part.end_landing.saturating_sub(1),
            manifest.landings
        ));
    }
    Ok(())
}

/// Whether `dir` holds the finished `shard` (or, without one, the whole) of `campaign`, as
/// this build runs it: what a scheduler of shards counts as done. A folder with no manifest
/// holds nothing finished; a manifest that does not read is an error.
pub fn holds_part(
    campaign: &Campaign,
    shard: Option<Shard>,
    dir: &Path,
) -> Result<bool, CampaignError> {
    if !dir.join("manifest.json").is_file() {
        return Ok(false);
    }
    let (_, manifest) = planned(campaign, shard);
    Ok(same_part(&manifest, &store::read_manifest(dir)?).is_ok())
}

/// The landings `shard` (or, without one, the whole campaign) runs, and the manifest its folder
/// will have but for the accuracy.
fn planned(campaign: &Campaign, shard: Option<Shard>) -> (Range<u64>, Manifest) {
    let range = shard.map_or(0..campaign.landings, |s| s.range(campaign.landings));
    let part = Part {
        first_landing: range.start,
        end_landing: range.end,
        shard: shard.map(|s| s.to_string()),
    };
    let manifest = Manifest::new(
        campaign,
        campaign.landings,
        part,
        &record::columns(campaign),
    );
    (range, manifest)
}

/// The landing a record is of (its first column).
fn landing(row: &Row) -> u64 {
    match row[0] {
        record::Cell::Integer(l) => l as u64,
        _ => u64::MAX,
    }
}

/// The journal of a run of the landings `landings` whose folder is built in `staging`, and how
/// many of its records it already holds: with `resume`, what the same run (its `run.json` the
/// manifest it will write) stopped there left, each record handed to `each`, refused if it
/// holds more records than the run has landings; otherwise, or when there is nothing of this
/// run to resume, an empty one in a cleared folder.
fn staged_journal(
    staging: &Staging,
    manifest: &Manifest,
    resume: bool,
    landings: Range<u64>,
    each: &mut impl FnMut(&Row),
) -> Result<(store::Journal, u64), CampaignError> {
    let dir = staging.dir();
    let same_run = resume
        && dir.join("landings.jsonl").is_file()
        && std::fs::read_to_string(dir.join(RUN_FILE))
            .is_ok_and(|text| text == store::pretty(manifest));
    if !same_run {
        staging.clear()?;
        return fresh_journal(dir, manifest);
    }
    let (journal, done) = store::Journal::resume(dir, &manifest.columns, landings.start, each)?;
    let planned = landings.end - landings.start;
    if done > planned {
        return Err(CampaignError::Store {
            path: dir.join("landings.jsonl").display().to_string(),
            message: format!(
                "holds {done} records where this run has {planned} landings to write: it was not written by this run; delete {} and run again without --resume",
                dir.display()
            ),
        });
    }
    Ok((journal, done))
}

/// An empty journal in `dir`, beside the `run.json` that names the run writing it.
fn fresh_journal(dir: &Path, manifest: &Manifest) -> Result<(store::Journal, u64), CampaignError> {
    let run_file = dir.join(RUN_FILE);
    std::fs::write(&run_file, store::pretty(manifest))
        .map_err(|e| CampaignError::store(&run_file, e))?;
    Ok((store::Journal::create(dir, &manifest.columns)?, 0))
}

/// Completes the folder `dir` whose records `journal` holds (the Parquet file, the statistics
/// and the scenarios they name, the manifest last: [`store::write_parquet`],
/// [`analysis::analyse`], [`store::seal`]), which then takes the place of the folder it is built
/// for, when there is one.
fn finish(
    dir: &Path,
    journal: store::Journal,
    mut manifest: Manifest,
    staging: Option<Staging>,
) -> Result<(Manifest, Report), CampaignError> {
    journal.close()?;
    let landings = store::write_parquet(dir, &manifest)?;
    let statistics = analysis::analyse(dir, &manifest, landings)?;
    store::seal(dir, &mut manifest, &statistics)?;
    // Kept until the folder is complete, so that a run stopped while completing it resumes.
    let run_file = dir.join(RUN_FILE);
    if run_file.exists() {
        std::fs::remove_file(&run_file).map_err(|e| CampaignError::store(&run_file, e))?;
    }
    if let Some(staging) = staging {
        staging.commit()?;
    }
    Ok((manifest, statistics))
}

/// Adds `more` landings to the finished campaign in `dir` (written by a run or a merge of the
/// same campaign file), without changing the landings it holds: landings n..n+more are run and
/// the folder replaced, when they have all run, by the one the campaign would have written had
/// it planned n + more from the start. `each` sees the added records. With `resume`, an `--add`
/// of the same landings to the same folder that was stopped goes on from the records it wrote.
pub fn add(
    campaign: &Campaign,
    dir: &Path,
    more: u64,
    threads: Option<usize>,
    resume: bool,
    mut each: impl FnMut(&Row),
) -> Result<(Manifest, Report), CampaignError> {
    let old = store::read_manifest(dir)?;
    old.check_files(dir)?;
    let columns = record::columns(campaign);
    let mut manifest = Manifest::new(campaign, old.landings, old.part.clone(), &columns);
    manifest.same_campaign(&old).map_err(|m| {
        CampaignError::Mismatch(format!("{}: not this campaign's: {m}", dir.display()))
    })?;
    if old.part.first_landing != 0 || old.part.end_landing != old.landings {
        return Err(CampaignError::Mismatch(format!(
            "{}: holds landings {} to {} of {}: merge the shards first (`touchdown campaign merge`)",
            dir.display(),
            old.part.first_landing,
            old.part.end_landing,
            old.landings
        )));
    }
    let total = old
        .landings
        .checked_add(more)
        .filter(|n| *n <= crate::spec::MAX_LANDINGS)
        .ok_or_else(|| {
            CampaignError::Mismatch(format!(
                "--add {more}: more than {} landings in all",
                crate::spec::MAX_LANDINGS
            ))
        })?;
    manifest.landings = total;
    manifest.part = Part {
        first_landing: 0,
        end_landing: total,
        shard: None,
    };
    let staging = Staging::keeping(dir)?;
    let building = staging.dir().to_path_buf();
    let (mut journal, done) = staged_journal(&staging, &manifest, resume, 0..total, &mut |row| {
        if landing(row) >= old.landings {
            each(row)
        }
    })?;
    // The finished campaign's records, those a stopped run had not copied yet.
    let kept = store::for_each_record(&dir.join("landings.jsonl"), &columns, 0, |row| {
        if landing(&row) >= done {
            journal.append(&row)?;
        }
        Ok(())
    })?;
    if kept != old.landings {
        return Err(CampaignError::Store {
            path: dir.join("landings.jsonl").display().to_string(),
            message: format!("holds {kept} landings, its manifest {}", old.landings),
        });
    }
    let histories = building.join("histories");
    if dir.join("histories").is_dir() {
        folder::copy_histories(&old, &dir.join("histories"), &histories)?;
    }
    run_range(
        campaign,
        done.max(old.landings)..total,
        threads,
        Some(&histories),
        |row| {
            journal.append(row)?;
            each(row);
            Ok(())
        },
    )?;
    manifest.state(accuracy::measure(campaign, total, threads)?);
    finish(&building, journal, manifest, Some(staging))
}

/// Merges the campaign folders `parts` (shards of one campaign, run by one build) into `out`:
/// refused unless they are parts of the same campaign and together hold each of its landings
/// once. The result is the folder the whole campaign run at once writes, byte for byte; `each`
/// sees every record in order as it is copied; returns the manifest and statistics. `out` may
/// be one of the parts or an earlier merge of the same campaign (it is replaced when the merge
/// is complete), or a new or empty folder. The records are streamed, never held.
pub fn merge(
    parts: &[&Path],
    out: &Path,
    mut each: impl FnMut(&Row),
) -> Result<(Manifest, Report), CampaignError> {
    let mut read: Vec<(Manifest, &Path)> = parts
        .iter()
        .map(|p| {
            let m = store::read_manifest(p)?;
            m.check_files(p)?;
            Ok::<_, CampaignError>((m, *p))
        })
        .collect::<Result<_, _>>()?;
    let Some((first, _)) = read.first() else {
        return Err(CampaignError::Mismatch(
            "nothing to merge: name the shards' folders".into(),
        ));
    };
    let first = first.clone();
    for (m, path) in &read {
        first.same_campaign(m).map_err(|e| {
            CampaignError::Mismatch(format!(
                "{} and {}: {e}",
                parts[0].display(),
                path.display()
            ))
        })?;
        if m.landings != first.landings {
            return Err(CampaignError::Mismatch(format!(
                "{} plans {} landings, {} plans {}",
                parts[0].display(),
                first.landings,
                path.display(),
                m.landings
            )));
        }
    }
    folder::check_out(out, |held| {
        first.same_campaign(held).map_err(|m| {
            format!("holds another campaign's landings ({m}): name a new or empty folder")
        })
    })?;
    read.sort_by_key(|(m, _)| m.part.first_landing);
    let mut next = 0;
    for (m, _) in &read {
        if m.part.first_landing != next {
            let what = if m.part.first_landing < next {
                "overlap"
            } else {
                "leave a gap"
            };
            return Err(CampaignError::Mismatch(format!(
                "the parts {what} at landing {}: each landing must be in exactly one part",
                m.part.first_landing.min(next)
            )));
        }
        next = m.part.end_landing;
    }
    if next != first.landings {
        return Err(CampaignError::Mismatch(format!(
            "the parts hold landings 0 to {} of {}: landings {next} to {} are missing",
            next.saturating_sub(1),
            first.landings,
            first.landings - 1
        )));
    }
    let mut manifest = first;
    // The accuracy is the part's that holds landing 0, measured as the whole campaign would.
    let holder = (read.iter()).find(|(m, _)| m.part.first_landing < m.part.end_landing);
    manifest.accuracy = holder.and_then(|(m, _)| m.accuracy.clone());
    manifest.multibody_accuracy =
        holder.map_or_else(Vec::new, |(m, _)| m.multibody_accuracy.clone());
    manifest.part = Part {
        first_landing: 0,
        end_landing: manifest.landings,
        shard: None,
    };
    let staging = Staging::begin(out)?;
    let building = staging.dir().to_path_buf();
    let mut journal = store::Journal::create(&building, &manifest.columns)?;
    for (m, path) in &read {
        let file = path.join("landings.jsonl");
        let n = store::for_each_record(&file, &manifest.columns, m.part.first_landing, |row| {
            journal.append(&row)?;
            each(&row);
            Ok(())
        })?;
        if n != m.part.end_landing - m.part.first_landing {
            return Err(CampaignError::Store {
                path: file.display().to_string(),
                message: format!(
                    "expected landings {} to {} in order, one per line",
                    m.part.first_landing,
                    m.part.end_landing.saturating_sub(1)
                ),
            });
        }
        let histories = path.join("histories");
        if histories.is_dir() {
            folder::copy_histories(m, &histories, &building.join("histories"))?;
        }
    }
    finish(&building, journal, manifest, Some(staging))
}
