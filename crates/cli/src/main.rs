//! `touchdown`: runs landing scenarios and reports them.

mod history;
mod report;
mod validation;

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
        /// rapier engine: fixed time step, s (overrides engines.rapier.timestep).
        #[arg(long)]
        timestep: Option<f64>,
    },
    /// Write the scenario's lander as a standalone MuJoCo model (MJCF); docs/engines.md tells
    /// how to open it in MuJoCo's viewer.
    ExportMjcf {
        /// Scenario file (TOML).
        scenario: PathBuf,
        /// Output file (MJCF XML).
        #[arg(short, long)]
        output: PathBuf,
    },
    /// Run every Table I landing and the figure 25-26 landing against the report.
    Validate {
        /// Output format.
        #[arg(long, value_enum, default_value_t = Format::Text)]
        format: Format,
        /// Workspace root holding reference/ and scenarios/.
        #[arg(long, default_value = ".")]
        root: PathBuf,
        /// Also write validation.json and fig-25-26-series.json (the data behind the plots) here.
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Fit the estimated parameters to the calibration rows (reference/calibration-protocol.toml)
    /// and write scenarios/vehicles/lm-1-6-calibrated.toml and reference/calibration-result.toml.
    Calibrate {
        /// Table I rows to calibrate on, e.g. 3,7 (default: the protocol's).
        #[arg(long, value_delimiter = ',')]
        rows: Option<Vec<u32>>,
        /// Workspace root holding reference/ and scenarios/.
        #[arg(long, default_value = ".")]
        root: PathBuf,
    },
    /// How each estimated parameter (±fraction) moves each Table I stroke.
    Sensitivity {
        /// Relative change of each parameter.
        #[arg(long, default_value_t = 0.2)]
        fraction: f64,
        /// Output format.
        #[arg(long, value_enum, default_value_t = Format::Text)]
        format: Format,
        /// Workspace root holding reference/ and scenarios/.
        #[arg(long, default_value = ".")]
        root: PathBuf,
    },
    /// The report's stability-boundary search: for each descent speed, the horizontal speed at
    /// which the landing turns unstable (velocities in the scenario's length unit per second;
    /// the horizontal direction is the scenario's).
    Boundary {
        /// Scenario file (TOML).
        scenario: PathBuf,
        /// Descent speeds FROM:TO:STEP (positive down).
        #[arg(long)]
        vv: String,
        /// First horizontal speed tried.
        #[arg(long, default_value_t = 0.0)]
        vh_start: f64,
        /// Horizontal-speed step while bracketing.
        #[arg(long, default_value_t = 2.0)]
        vh_step: f64,
        /// Largest horizontal speed tried.
        #[arg(long, default_value_t = 30.0)]
        vh_max: f64,
        /// Bisection tolerance on the horizontal speed.
        #[arg(long, default_value_t = 0.05)]
        tol: f64,
        /// Output format.
        #[arg(long, value_enum, default_value_t = TableFormat::Text)]
        format: TableFormat,
    },
}

#[derive(Clone, Copy, ValueEnum)]
enum TableFormat {
    Text,
    Json,
    Csv,
}

#[derive(Clone, Copy, ValueEnum)]
enum Format {
    Text,
    Json,
}

#[derive(Clone, Copy, PartialEq, ValueEnum)]
enum Engine {
    /// The report-faithful core.
    Core,
    /// The rapier multibody rebuild (engine settings in [engines.rapier]).
    Rapier,
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
            engine,
            timestep,
        } => {
            let mut sc = Scenario::load(&scenario)?;
            if let Some(t) = timestep {
                if engine != Engine::Rapier {
                    anyhow::bail!("--timestep sets the rapier engine's step; add --engine rapier");
                }
                sc = sc.with_rapier(|r| r.timestep = t)?;
            }
            let mut recorder = match &out {
                Some(dir) => {
                    std::fs::create_dir_all(dir)
                        .with_context(|| format!("cannot create {}", dir.display()))?;
                    Some(history::Recorder::create(
                        &dir.join("history.csv"),
                        sc.legs.len(),
                    )?)
                }
                None => None,
            };
            let summary = match engine {
                Engine::Core => {
                    let mut sim = touchdown_core::Simulation::new(&sc)?;
                    match recorder.as_mut() {
                        Some(r) => sim.run(r)?,
                        None => sim.run(&mut ())?,
                    }
                }
                Engine::Rapier => {
                    let mut sim = touchdown_rapier::RapierSimulation::new(&sc)?;
                    match recorder.as_mut() {
                        Some(r) => sim.run(r)?,
                        None => sim.run(&mut ())?,
                    }
                }
            };
            if let (Some(dir), Some(rec)) = (&out, recorder) {
                rec.finish()?;
                std::fs::write(
                    dir.join("scenario.resolved.toml"),
                    report::resolved_scenario(&sc),
                )?;
                std::fs::write(dir.join("summary.json"), report::json(&summary)?)?;
            }
            match format {
                Format::Text => print!("{}", report::text(&sc, &summary)),
                Format::Json => println!("{}", report::json(&summary)?),
            }
            Ok(())
        }
        Command::ExportMjcf { scenario, output } => {
            let sc = Scenario::load(&scenario)?;
            let xml = touchdown_mujoco::export(&sc);
            std::fs::write(&output, xml)
                .with_context(|| format!("cannot write {}", output.display()))?;
            Ok(())
        }
        Command::Validate { format, root, out } => {
            validation::validate(&root, matches!(format, Format::Json), out.as_deref())
        }
        Command::Calibrate { rows, root } => validation::calibrate(&root, rows),
        Command::Sensitivity {
            fraction,
            format,
            root,
        } => validation::sensitivity(&root, fraction, matches!(format, Format::Json)),
        Command::Boundary {
            scenario,
            vv,
            vh_start,
            vh_step,
            vh_max,
            tol,
            format,
        } => {
            let settings = touchdown_validation::boundary::Settings {
                vh_start,
                vh_step,
                vh_max,
                tolerance: tol,
            };
            let format = match format {
                TableFormat::Text => validation::BoundaryFormat::Text,
                TableFormat::Json => validation::BoundaryFormat::Json,
                TableFormat::Csv => validation::BoundaryFormat::Csv,
            };
            validation::boundary(&scenario, &vv, settings, format)
        }
    }
}
