//! Work a long computation has finished, kept on disk so that a run stopped part-way (killed,
//! out of time) resumes where it stopped and ends with the same result, byte for byte, as a run
//! that was never stopped (docs/validation.md, "Cross-validation").
//!
//! Each unit of work (a fold, the fit to every row, one point of a profile) is stored when it
//! ends as `<unit>.toml` in the checkpoint's folder: its value in the computation's own units
//! (TOML numbers are read back exactly), the landings it ran and a key. A unit is taken from
//! the folder only if its key is the run's: the key names everything the result depends on
//! (the program that computes it, the reference files and scenarios it reads), so that work of
//! another program or other inputs is computed again, never mixed in. A unit is written to a
//! temporary name and renamed, so a kill during a write leaves no half unit.

use crate::calibrate::Predict;
use crate::reference::Row;
use crate::ValidationError;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

/// Where a computation keeps its finished units, and the key they must carry.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Checkpoint {
    dir: PathBuf,
    key: String,
}

/// One unit as stored.
#[derive(Serialize, Deserialize)]
struct Kept<T> {
    key: String,
    landings: usize,
    value: T,
}

impl Checkpoint {
    /// A checkpoint in `dir` (created if missing) for the run identified by `key`.
    pub fn new(dir: &Path, key: impl Into<String>) -> Result<Checkpoint, ValidationError> {
        std::fs::create_dir_all(dir).map_err(|e| io(dir, "cannot create", e))?;
        Ok(Checkpoint {
            dir: dir.to_path_buf(),
            key: key.into(),
        })
    }

    /// The folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// How many units of this run the folder holds, and the landings they ran.
    pub fn kept(&self) -> (usize, usize) {
        let Ok(entries) = std::fs::read_dir(&self.dir) else {
            return (0, 0);
        };
        entries
            .filter_map(Result::ok)
            .filter(|e| e.path().extension().is_some_and(|x| x == "toml"))
            .filter_map(|e| self.read::<toml::Value>(&e.path()))
            .fold((0, 0), |(units, landings), (_, n)| {
                (units + 1, landings + n)
            })
    }

    /// Removes the folder, once the whole result is written.
    pub fn finish(self) -> Result<(), ValidationError> {
        std::fs::remove_dir_all(&self.dir).map_err(|e| io(&self.dir, "cannot remove", e))
    }

    fn read<T: DeserializeOwned>(&self, path: &Path) -> Option<(T, usize)> {
        let text = std::fs::read_to_string(path).ok()?;
        let kept: Kept<T> = toml::from_str(&text).ok()?;
        (kept.key == self.key).then_some((kept.value, kept.landings))
    }

    /// The unit `name`: from the folder if this run's key holds it, else `compute`d with
    /// `predict` (its landings counted) and stored. Returns the value and the landings it ran.
    pub(crate) fn unit<T: Serialize + DeserializeOwned>(
        &self,
        name: &str,
        predict: &Predict,
        compute: impl FnOnce(&Predict) -> Result<T, ValidationError>,
    ) -> Result<(T, usize), ValidationError> {
        let path = self.dir.join(format!("{name}.toml"));
        if let Some(kept) = self.read(&path) {
            return Ok(kept);
        }
        let (value, landings) = counted(predict, compute)?;
        let text = toml::to_string(&Kept {
            key: self.key.clone(),
            landings,
            value,
        })
        .map_err(|e| ValidationError::Calibration(format!("checkpoint unit {name}: {e}")))?;
        let partial = self.dir.join(format!("{name}.toml.partial"));
        std::fs::write(&partial, text).map_err(|e| io(&partial, "cannot write", e))?;
        std::fs::rename(&partial, &path).map_err(|e| io(&path, "cannot write", e))?;
        // Read back what was stored, so that a resumed run and this one use the same numbers.
        self.read(&path).ok_or_else(|| {
            ValidationError::Calibration(format!(
                "checkpoint unit {} does not read back",
                path.display()
            ))
        })
    }
}

/// `compute` with `predict`, and the landings it ran.
pub(crate) fn counted<T>(
    predict: &Predict,
    compute: impl FnOnce(&Predict) -> Result<T, ValidationError>,
) -> Result<(T, usize), ValidationError> {
    let landings = AtomicUsize::new(0);
    let counting = |row: &Row, x: &[f64]| {
        landings.fetch_add(1, Ordering::Relaxed);
        predict(row, x)
    };
    let value = compute(&counting)?;
    Ok((value, landings.load(Ordering::Relaxed)))
}

/// A key naming the contents of `inputs`: files, and folders with every file under them (in
/// path order, each file's path relative to its folder hashed with it); SHA-256, hex. Give it
/// the program itself and everything it reads.
pub fn key_of(inputs: &[PathBuf]) -> Result<String, ValidationError> {
    use sha2::{Digest, Sha256};
    let mut hash = Sha256::new();
    for input in inputs {
        let mut files = Vec::new();
        collect(input, &mut files)?;
        files.sort();
        for file in files {
            let bytes = std::fs::read(&file).map_err(|e| io(&file, "cannot read", e))?;
            let name = file.strip_prefix(input).unwrap_or(&file);
            hash.update(name.to_string_lossy().as_bytes());
            hash.update((bytes.len() as u64).to_le_bytes());
            hash.update(&bytes);
        }
    }
    Ok(format!("{:x}", hash.finalize()))
}

/// Every file at or under `path`.
fn collect(path: &Path, files: &mut Vec<PathBuf>) -> Result<(), ValidationError> {
    if path.is_dir() {
        let entries = std::fs::read_dir(path).map_err(|e| io(path, "cannot read", e))?;
        for entry in entries {
            let entry = entry.map_err(|e| io(path, "cannot read", e))?;
            collect(&entry.path(), files)?;
        }
    } else {
        files.push(path.to_path_buf());
    }
    Ok(())
}

fn io(path: &Path, what: &str, e: std::io::Error) -> ValidationError {
    ValidationError::Calibration(format!("checkpoint: {what} {}: {e}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, PartialEq, Serialize, Deserialize)]
    struct Unit {
        x: Vec<f64>,
        y: Option<f64>,
    }

    #[test]
    fn a_unit_reads_back_exactly_and_only_under_its_key() {
        let dir = tempfile::tempdir().unwrap();
        let x = vec![
            0.1 + 0.2,
            1e-300,
            -2.5e300,
            std::f64::consts::PI / 7.0,
            5e-324,
        ];
        let predict = |_: &Row, _: &[f64]| Ok(0.0);
        let a = Checkpoint::new(dir.path(), "a").unwrap();
        let computed = a
            .unit("u", &predict, |_| {
                Ok(Unit {
                    x: x.clone(),
                    y: None,
                })
            })
            .unwrap();
        let kept = a
            .unit("u", &predict, |_| -> Result<Unit, _> {
                panic!("computed again")
            })
            .unwrap();
        assert_eq!(computed, kept);
        for (p, q) in kept.0.x.iter().zip(&x) {
            assert_eq!(p.to_bits(), q.to_bits());
        }
        assert_eq!(a.kept().0, 1);
        // Another key computes again.
        let b = Checkpoint::new(dir.path(), "b").unwrap();
        let other = b
            .unit("u", &predict, |_| {
                Ok(Unit {
                    x: vec![1.0],
                    y: Some(2.0),
                })
            })
            .unwrap();
        assert_eq!(other.0.x, vec![1.0]);
        b.finish().unwrap();
        assert!(!dir.path().exists());
    }
}
