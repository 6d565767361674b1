//! `touchdown`: runs landing scenarios and reports them.

mod history;
mod report;

use anyhow::{Context, Result};
use clap::{Parser, Subcommand, ValueEnum};
use std::path::PathBuf;
use touchdown_scenario::Scenario;

#[derive(Parser)]
#[command(
    name = "touchdown",
    version,
    about = "Touchdown dynamics of soft-landing spacecraft (NASA TN D-7045 testbench)"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run one landing and print its summary.
    Run {
        /// Scenario file (TOML).
        scenario: PathBuf,
        /// Output format of the summary on standard output.
        #[arg(long, value_enum, default_value_t = Format::Text)]
        format: Format,
        /// Also write summary.json, history.csv and scenario.resolved.toml into this folder.
        #[arg(long)]
        out: Option<PathBuf>,
        /// Engine to run.
        #[arg(long, value_enum, default_value_t = Engine::Core)]
        engine: Engine,
    },
}

#[derive(Clone, Copy, ValueEnum)]
enum Format {
    Text,
    Json,
}

#[derive(Clone, Copy, ValueEnum)]
enum Engine {
    /// The report-faithful core.
    Core,
}

fn main() -> std::process::ExitCode {
    match run(Cli::parse()) {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            std::process::ExitCode::FAILURE
        }
    }
}

fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Run {
            scenario,
            format,
            out,
            engine: Engine::Core,
        } => {
            let sc = Scenario::load(&scenario)?;
            let mut sim = touchdown_core::Simulation::new(&sc)?;
            let summary = match &out {
                Some(dir) => {
                    std::fs::create_dir_all(dir)
                        .with_context(|| format!("cannot create {}", dir.display()))?;
                    let mut rec =
                        history::Recorder::create(&dir.join("history.csv"), sc.legs.len())?;
                    let summary = sim.run(&mut rec)?;
                    rec.finish()?;
                    std::fs::write(
                        dir.join("scenario.resolved.toml"),
                        report::resolved_scenario(&sc),
                    )?;
                    std::fs::write(dir.join("summary.json"), report::json(&summary)?)?;
                    summary
                }
                None => sim.run(&mut ())?,
            };
            match format {
                Format::Text => print!("{}", report::text(&sc, &summary)),
                Format::Json => println!("{}", report::json(&summary)?),
            }
            Ok(())
        }
    }
}
