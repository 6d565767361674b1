//! The `touchdown` command as a user runs it.
//!
//! One test binary (each file directly in `tests/` would link one of its own): a module per
//! command or subject, the helpers they share here.

use std::path::{Path, PathBuf};
use std::process::Command;

mod boundary;
mod campaign;
mod campaign_stopped;
mod compare;
mod engines;
mod errors;
mod help;
mod new_check;
mod run;
mod set;
mod settled;
mod studies;
mod view;

pub(crate) fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .unwrap()
}

pub(crate) fn touchdown(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_touchdown"))
        .args(args)
        .current_dir(root())
        .output()
        .expect("the touchdown binary runs")
}

/// A path in a folder of its own that is removed, with everything in it, when the value goes
/// out of scope: no test leaves files behind.
pub(crate) struct Scratch {
    _folder: tempfile::TempDir,
    path: PathBuf,
}

impl std::ops::Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.path
    }
}

impl AsRef<Path> for Scratch {
    fn as_ref(&self) -> &Path {
        &self.path
    }
}

impl AsRef<std::ffi::OsStr> for Scratch {
    fn as_ref(&self) -> &std::ffi::OsStr {
        self.path.as_os_str()
    }
}

/// A folder path `name` that does not exist yet (the command under test may create it).
pub(crate) fn temp(name: &str) -> Scratch {
    let folder = tempfile::Builder::new()
        .prefix("touchdown-cli-")
        .tempdir()
        .unwrap();
    let path = folder.path().join(name);
    Scratch {
        _folder: folder,
        path,
    }
}

/// Writes `dir/file`, a scenario named `name` that extends the bundled `base` (a path under
/// scenarios/) with the TOML `extra`; returns its path.
pub(crate) fn extending(dir: &str, file: &str, base: &str, name: &str, extra: &str) -> Scratch {
    let d = temp(dir);
    std::fs::create_dir_all(&*d).unwrap();
    let f = d.join(file);
    let base = root().join("scenarios").join(base);
    std::fs::write(
        &f,
        format!(
            "schema_version = 1\nextends = {:?}\nname = {name:?}\n{extra}",
            base.display().to_string()
        ),
    )
    .unwrap();
    Scratch {
        _folder: d._folder,
        path: f,
    }
}

/// A PNG of some substance at `path`.
pub(crate) fn assert_png(path: &Path) {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert!(
        bytes.starts_with(b"\x89PNG\r\n\x1a\n") && bytes.len() > 10_000,
        "{} is not a plot ({} bytes)",
        path.display(),
        bytes.len()
    );
}
