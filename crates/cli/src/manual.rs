//! `touchdown man` and `touchdown completions`: the manual pages and the shell completions,
//! both generated from the argument definitions (`crate::args`).

use crate::args::Cli;
use crate::{out, outln};
use anyhow::{Context, Result};
use std::path::Path;

/// `touchdown man`: the manual page of the command and of each subcommand into `dir`.
pub fn man_pages(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let cmd = <Cli as clap::CommandFactory>::command();
    let write = |name: &str, cmd: clap::Command| -> Result<()> {
        let path = dir.join(format!("{name}.1"));
        let mut bytes = Vec::new();
        clap_mangen::Man::new(cmd).title(name).render(&mut bytes)?;
        std::fs::write(&path, bytes).with_context(|| format!("cannot write {}", path.display()))
    };
    for sub in cmd.get_subcommands() {
        write(&format!("touchdown-{}", sub.get_name()), sub.clone())?;
    }
    write("touchdown", cmd)?;
    outln!("wrote the manual pages into {}", dir.display())?;
    Ok(())
}

/// `touchdown completions`: the completion script of `shell` on standard output.
pub fn completions(shell: clap_complete::Shell) -> Result<()> {
    let mut cmd = <Cli as clap::CommandFactory>::command();
    let mut script = Vec::new();
    clap_complete::generate(shell, &mut cmd, "touchdown", &mut script);
    out!("{}", String::from_utf8_lossy(&script))
}
