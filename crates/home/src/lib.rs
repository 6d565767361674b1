//! The project's folder and its Python environment.
//!
//! The MuJoCo runner (`python/mujoco/run.py`), the plotting scripts (`python/figures/`), the
//! pinned `.venv` and the reference data live in the project's folder, not in a binary. Every
//! crate that runs one of them finds the folder here: `$TOUCHDOWN_HOME` if set, else the first
//! folder holding the project above the running executable (`target/release/touchdown`), then
//! above the current directory, else the folder this crate was built from.

use std::path::{Path, PathBuf};

/// The workspace this crate was built from: where [`home`] looks last.
const BUILT_IN: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");

/// The environment variable that names the project's folder.
const HOME_VARIABLE: &str = "TOUCHDOWN_HOME";

/// The environment variable that names the Python interpreter, in place of the project's
/// `.venv`.
const PYTHON_VARIABLE: &str = "TOUCHDOWN_PYTHON";

/// A file every copy of the project holds, by which [`home`] recognises it.
const MARKER: &str = "python/mujoco/run.py";

/// The command that sets up the Python environment.
const SETUP_COMMAND: &str = "scripts/setup-python";

/// Why the project's folder or its Python environment cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum HomeError {
    /// The project's folder was not found: where it was looked for.
    #[error("{0}")]
    NotFound(String),
    /// The Python environment is missing: what needs it, and how to create it
    /// ([`setup_hint`]).
    #[error("{0}")]
    NoPython(String),
}

/// The project's folder (holding `.venv/`, `python/`, `scripts/`, `reference/` and
/// `scenarios/`), found as the module documentation says. An error says where it looked.
pub fn home() -> Result<PathBuf, HomeError> {
    let holds = |d: &Path| d.join(MARKER).is_file();
    if let Some(h) = std::env::var_os(HOME_VARIABLE) {
        let h = PathBuf::from(h);
        return if holds(&h) {
            Ok(h.canonicalize().unwrap_or(h))
        } else {
            Err(HomeError::NotFound(format!(
                "${HOME_VARIABLE} is {}, which does not hold the project ({MARKER} is missing)",
                h.display()
            )))
        };
    }
    let above = |start: Option<PathBuf>| {
        start.and_then(|s| s.ancestors().find(|d| holds(d)).map(Path::to_path_buf))
    };
    let exe = std::env::current_exe()
        .ok()
        .and_then(|e| e.canonicalize().ok());
    let cwd = std::env::current_dir().ok();
    if let Some(found) = above(exe.clone()).or_else(|| above(cwd.clone())) {
        return Ok(found);
    }
    let built = PathBuf::from(BUILT_IN);
    if holds(&built) {
        return Ok(built.canonicalize().unwrap_or(built));
    }
    let shown = |p: Option<PathBuf>| p.map_or("?".into(), |p| p.display().to_string());
    Err(HomeError::NotFound(format!(
        "cannot find the project's folder (one holding {MARKER}): ${HOME_VARIABLE} is not set, \
         and none was found above the executable ({}), above the current directory ({}) or at \
         {}; set {HOME_VARIABLE} to the project's folder",
        shown(exe),
        shown(cwd),
        built.display()
    )))
}

/// The project's folder for a message: [`home`], or where this crate was built.
pub fn home_shown() -> PathBuf {
    home().unwrap_or_else(|_| PathBuf::from(BUILT_IN))
}

/// What to do about a missing Python environment, to end a message with: run
/// `scripts/setup-python` in the project's folder.
pub fn setup_hint() -> String {
    format!(
        "run `{SETUP_COMMAND}` in {} (it creates .venv with the pinned mujoco and matplotlib)",
        home_shown().display()
    )
}

/// The project's Python interpreter (`$TOUCHDOWN_PYTHON`, else the `.venv` of the project's
/// folder, [`home`]), or an error saying that `needed_for` needs it and how to create it.
pub fn project_python(needed_for: &str) -> Result<PathBuf, HomeError> {
    let python = match std::env::var_os(PYTHON_VARIABLE) {
        Some(p) => PathBuf::from(p),
        None => home()?.join(".venv").join("bin").join("python"),
    };
    if !python.is_file() {
        return Err(HomeError::NoPython(format!(
            "{needed_for} needs the project's Python environment, and {} does not exist; {}",
            python.display(),
            setup_hint()
        )));
    }
    Ok(python)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_project_is_found_from_where_it_was_built() {
        let h = home().unwrap();
        assert!(h.join(MARKER).is_file(), "{}", h.display());
        assert!(h.join("scenarios").is_dir());
        assert!(setup_hint().contains(SETUP_COMMAND));
    }
}
