//! The source revision the campaign manifests name: `git rev-parse HEAD` of the workspace at
//! build time, or `unknown` outside a git checkout.
//!
//! It is read again whenever HEAD moves: cargo is told to watch `.git/HEAD` and the file of the
//! branch HEAD names (`.git/refs/heads/<branch>`, which a commit rewrites; watching the folder
//! `refs/heads` would not see it, a folder's time changing only when a branch is added or
//! removed), or that folder while the branch's ref is packed and has no file, and
//! `packed-refs`. In a linked worktree `.git` is a file naming the git folder.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The git folder of the checkout at `root`: `.git`, or the folder a worktree's `.git` file
/// names (`gitdir: <path>`).
fn git_dir(root: &Path) -> Option<PathBuf> {
    let dot = root.join(".git");
    if dot.is_dir() {
        return Some(dot);
    }
    let text = std::fs::read_to_string(&dot).ok()?;
    let dir = text.strip_prefix("gitdir:")?.trim();
    Some(root.join(dir))
}

fn main() {
    // The manifest folder as cargo gives it to this run, not as it was when this script was
    // compiled: a build script's binary is reused by a checkout that shares its target folder
    // (a worktree of the same sources), and would name the other checkout's revision.
    let manifest = std::env::var_os("CARGO_MANIFEST_DIR").unwrap_or_default();
    let root = Path::new(&manifest).join("../..");
    if let Some(git) = git_dir(&root) {
        let head = git.join("HEAD");
        let mut watched = vec![head.clone(), git.join("packed-refs")];
        // `ref: refs/heads/main`: the branch's file, in this git folder or, for a worktree, in
        // the repository's (its `commondir`).
        if let Some(branch) = std::fs::read_to_string(&head)
            .ok()
            .and_then(|h| h.strip_prefix("ref:").map(|r| r.trim().to_string()))
        {
            let mut branches = vec![git.join(&branch)];
            if let Ok(common) = std::fs::read_to_string(git.join("commondir")) {
                branches.push(git.join(common.trim()).join(&branch));
            }
            // A branch whose ref is packed has no file until its next commit writes one: then
            // the folder that file will appear in is watched instead.
            for file in branches {
                let watch = match file.parent() {
                    Some(folder) if !file.exists() => folder.to_path_buf(),
                    _ => file,
                };
                watched.push(watch);
            }
        }
        for path in watched.iter().filter(|p| p.exists()) {
            println!("cargo:rerun-if-changed={}", path.display());
        }
    }
    let revision = Command::new("git")
        .arg("-C")
        .arg(&root)
        .args(["rev-parse", "HEAD"])
        .output()
        .ok()
        .filter(|o| o.status.success())
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
        .unwrap_or_else(|| "unknown".into());
    println!("cargo:rustc-env=TOUCHDOWN_REVISION={revision}");
}
