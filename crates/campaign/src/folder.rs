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

/// `out` with `.suffix` added to its name.
fn beside(out: &Path, suffix: &str) -> Result<PathBuf, CampaignError> {
    let name = out.file_name().ok_or_else(|| CampaignError::Store {
        path: out.display().to_string(),
        message: "expected a folder's name for --out (not `.`, `..` or `/`)".into(),
    })?;
    let mut name = name.to_os_string();
    name.push(format!(".{suffix}"));
    Ok(out.with_file_name(name))
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

    /// Goes on building the folder that will replace `out`, with what a stopped run left in
    /// `<out>.partial` (nothing if none did): refused while another process builds it.
    pub fn resume(out: &Path) -> Result<Staging, CampaignError> {
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
        let (dir, replaced) = (beside(out, PARTIAL)?, beside(out, REPLACED)?);
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
        std::fs::create_dir_all(&dir).map_err(|e| CampaignError::store(&dir, e))?;
        let lock_path = dir.join(LOCK);
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

    /// The complete folder takes the place of `out` (the previous one, if any, is deleted).
    pub fn commit(self) -> Result<(), CampaignError> {
        let lock_path = self.dir.join(LOCK);
        std::fs::remove_file(&lock_path).map_err(|e| CampaignError::store(&lock_path, e))?;
        if self.out.exists() {
            let replaced = beside(&self.out, REPLACED)?;
            std::fs::rename(&self.out, &replaced)
                .map_err(|e| CampaignError::store(&self.out, e))?;
            std::fs::rename(&self.dir, &self.out)
                .map_err(|e| CampaignError::store(&self.dir, e))?;
            std::fs::remove_dir_all(&replaced).map_err(|e| CampaignError::store(&replaced, e))
        } else {
            std::fs::rename(&self.dir, &self.out).map_err(|e| CampaignError::store(&self.dir, e))
        }
    }
}

/// Copies the folder tree `from` into `to` (created), file by file.
pub fn copy_tree(from: &Path, to: &Path) -> Result<(), CampaignError> {
    std::fs::create_dir_all(to).map_err(|e| CampaignError::store(to, e))?;
    for entry in std::fs::read_dir(from).map_err(|e| CampaignError::store(from, e))? {
        let path = entry.map_err(|e| CampaignError::store(from, e))?.path();
        let Some(name) = path.file_name() else {
            continue;
        };
        if path.is_dir() {
            copy_tree(&path, &to.join(name))?;
        } else {
            std::fs::copy(&path, to.join(name)).map_err(|e| CampaignError::store(&path, e))?;
        }
    }
    Ok(())
}
