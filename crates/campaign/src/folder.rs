//! A campaign's folder, written safely (docs/campaigns.md, "Output"): the new folder is built
//! whole beside the old one and takes its place only when complete, so that a full disk or a
//! kill part-way leaves the previous folder as it was; one writer at a time; and a folder that
//! holds something else is never written into.

use crate::store::{self, Manifest};
use crate::CampaignError;
use std::fs::File;
use std::path::{Path, PathBuf};

/// Suffix of the folder a campaign is built in, beside its `--out`.
const PARTIAL: &str = "partial";
/// Suffix the previous folder takes for the instant of the exchange.
const REPLACED: &str = "replaced";
/// The lock file inside the folder being built.
const LOCK: &str = ".lock";

/// A campaign folder being built: `<out>.partial` beside `out`, locked (an advisory lock the
/// system releases when the process ends, however it ends) for as long as this value lives.
#[derive(Debug)]
pub struct Staging {
    out: PathBuf,
    dir: PathBuf,
    _lock: File,
}

/// `out` with `.suffix` added to its name. A name that is itself a staging name (ending in
/// `.partial` or `.replaced`) is refused: the next run into the folder it stages for would
/// clear or replace it.
fn beside(out: &Path, suffix: &str) -> Result<PathBuf, CampaignError> {
    let refuse = |message: String| CampaignError::Store {
        path: out.display().to_string(),
        message,
    };
    let name = out.file_name().ok_or_else(|| {
        refuse("expected a folder's name for --out (not `.`, `..` or `/`)".into())
    })?;
    if let Some(ending) = [PARTIAL, REPLACED]
        .iter()
        .find(|s| name.to_string_lossy().ends_with(&format!(".{s}")))
    {
        return Err(refuse(format!(
            "a name ending in `.{ending}` is the one touchdown builds a campaign folder in, and a run into the folder without it would clear it: name the folder without `.{ending}`"
        )));
    }
    let mut name = name.to_os_string();
    name.push(format!(".{suffix}"));
    Ok(out.with_file_name(name))
}

/// The folder a campaign into `out` is built in, `<out>.partial`, where a stopped run's records
/// are kept.
pub fn staging_dir(out: &Path) -> Result<PathBuf, CampaignError> {
    beside(out, PARTIAL)
}

/// What `out` holds, checked before any landing runs: nothing (missing or empty), or a folder
/// this run may replace: `accepts` is given its manifest and says why not (`Err`). A file, a
/// folder with other files, or another campaign's folder is refused.
pub fn check_out(
    out: &Path,
    accepts: impl Fn(&Manifest) -> Result<(), String>,
) -> Result<(), CampaignError> {
    let refuse = |message: String| CampaignError::Store {
        path: out.display().to_string(),
        message,
    };
    if !out.exists() {
        return Ok(());
    }
    if !out.is_dir() {
        return Err(refuse(
            "exists and is not a folder: name a new or empty folder for the campaign".into(),
        ));
    }
    let empty = std::fs::read_dir(out)
        .map_err(|e| CampaignError::store(out, e))?
        .next()
        .is_none();
    if empty {
        return Ok(());
    }
    let manifest = store::read_manifest(out).map_err(|_| {
        refuse("holds files that are not a campaign's: name a new or empty folder".into())
    })?;
    accepts(&manifest).map_err(refuse)
}

impl Staging {
    /// Starts building the folder that will replace `out`: refused while another process
    /// builds it. What a killed run left in `<out>.partial` is cleared.
    pub fn begin(out: &Path) -> Result<Staging, CampaignError> {
        let staging = Staging::open(out)?;
        staging.clear()?;
        Ok(staging)
    }

    /// Opens the folder that will replace `out` as a stopped run left it in `<out>.partial`
    /// (empty if none did), for the caller to go on from it or clear it: refused while another
    /// process builds it.
    pub fn keeping(out: &Path) -> Result<Staging, CampaignError> {
        Staging::open(out)
    }

    /// Removes everything the folder being built holds.
    pub fn clear(&self) -> Result<(), CampaignError> {
        let lock_path = self.dir.join(LOCK);
        for entry in std::fs::read_dir(&self.dir).map_err(|e| CampaignError::store(&self.dir, e))? {
            let path = entry
                .map_err(|e| CampaignError::store(&self.dir, e))?
                .path();
            if path != lock_path {
                let removed = if path.is_dir() {
                    std::fs::remove_dir_all(&path)
                } else {
                    std::fs::remove_file(&path)
                };
                removed.map_err(|e| CampaignError::store(&path, e))?;
            }
        }
        Ok(())
    }

    /// `<out>.partial`, created if missing, locked.
    fn open(out: &Path) -> Result<Staging, CampaignError> {
        let (dir, replaced) = (staging_dir(out)?, beside(out, REPLACED)?);
        if replaced.exists() {
            return Err(CampaignError::Store {
                path: replaced.display().to_string(),
                message: format!(
                    "a run was stopped while it replaced {}: this folder holds the previous campaign and {} the new one; rename the one to keep to {} and delete the other",
                    out.display(),
                    dir.display(),
                    out.display()
                ),
            });
        }
        let lock_path = dir.join(LOCK);
        let refuse = |what: &str| {
            let message = format!(
                "{what}: touchdown builds the folder {} in it and will not clear what it did not write; move it away or delete it",
                out.display()
            );
            CampaignError::Store {
                path: dir.display().to_string(),
                message,
            }
        };
        if dir.exists() {
            if !dir.is_dir() {
                return Err(refuse("exists and is not a folder"));
            }
            // A folder touchdown builds holds its lock file from its creation to its exchange.
            let mut entries = std::fs::read_dir(&dir).map_err(|e| CampaignError::store(&dir, e))?;
            if entries.next().is_some() && !lock_path.is_file() {
                return Err(refuse(
                    "holds files touchdown did not leave there (no .lock)",
                ));
            }
        }
        std::fs::create_dir_all(&dir).map_err(|e| CampaignError::store(&dir, e))?;
        let lock = File::create(&lock_path).map_err(|e| CampaignError::store(&lock_path, e))?;
        match lock.try_lock() {
            Ok(()) => {}
            Err(std::fs::TryLockError::WouldBlock) => {
                return Err(CampaignError::Store {
                    path: out.display().to_string(),
                    message: format!(
                        "another touchdown is writing this folder (it holds {}): give each shard its own folder and merge them",
                        lock_path.display()
                    ),
                })
            }
            Err(std::fs::TryLockError::Error(e)) => return Err(CampaignError::store(&lock_path, e)),
        }
        Ok(Staging {
            out: out.to_path_buf(),
            dir,
            _lock: lock,
        })
    }

    /// The folder being built.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The complete folder takes the place of `out` (the previous one, if any, is deleted). The
    /// lock file goes last, so that a folder stopped anywhere in the exchange is still one
    /// touchdown knows for its own.
    pub fn commit(self) -> Result<(), CampaignError> {
        if self.out.exists() {
            let replaced = beside(&self.out, REPLACED)?;
            std::fs::rename(&self.out, &replaced)
                .map_err(|e| CampaignError::store(&self.out, e))?;
            std::fs::rename(&self.dir, &self.out)
                .map_err(|e| CampaignError::store(&self.dir, e))?;
            std::fs::remove_dir_all(&replaced).map_err(|e| CampaignError::store(&replaced, e))?;
        } else {
            std::fs::rename(&self.dir, &self.out)
                .map_err(|e| CampaignError::store(&self.dir, e))?;
        }
        let lock_path = self.out.join(LOCK);
        std::fs::remove_file(&lock_path).map_err(|e| CampaignError::store(&lock_path, e))
    }
}

/// Copies the `histories/` folder `from` of the campaign part `manifest` into `to`, file by
/// file. Anything that is not a history the part keeps ([`Manifest::keeps_history`]) is
/// refused, naming it: a merge or an extension carries the campaign's files only.
pub fn copy_histories(manifest: &Manifest, from: &Path, to: &Path) -> Result<(), CampaignError> {
    copy_under(manifest, from, Path::new(""), to)
}

/// [`copy_histories`] of the folder `root/rel`.
fn copy_under(
    manifest: &Manifest,
    root: &Path,
    rel: &Path,
    to: &Path,
) -> Result<(), CampaignError> {
    let from = root.join(rel);
    std::fs::create_dir_all(to.join(rel)).map_err(|e| CampaignError::store(&to.join(rel), e))?;
    for entry in std::fs::read_dir(&from).map_err(|e| CampaignError::store(&from, e))? {
        let path = entry.map_err(|e| CampaignError::store(&from, e))?.path();
        let Some(name) = path.file_name() else {
            continue;
        };
        let rel = rel.join(name);
        let engine_folder = manifest.engines.len() > 1
            && path.is_dir()
            && manifest.engines.iter().any(|e| Path::new(e) == rel);
        if !(engine_folder || manifest.keeps_history(&rel)) {
            return Err(CampaignError::Store {
                path: path.display().to_string(),
                message: format!(
                    "is no history of a landing this part keeps (landings {} to {}, histories of {:?}): move it out of the campaign folder and try again",
                    manifest.part.first_landing,
                    manifest.part.end_landing.saturating_sub(1),
                    manifest.histories
                ),
            });
        }
        if path.is_dir() {
            copy_under(manifest, root, &rel, to)?;
        } else {
            let target = to.join(&rel);
            std::fs::copy(&path, &target).map_err(|e| {
                CampaignError::store(&target, format!("{e} (copying {})", path.display()))
            })?;
        }
    }
    Ok(())
}
