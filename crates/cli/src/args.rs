//! The command line's arguments: every subcommand and option as clap derives them, and what
//! the shared ones mean (`--set` overrides applied to a scenario). Each command's work is in
//! its own module (`crate::landing`, `crate::compare`, ...); `main.rs` dispatches.

use anyhow::{Context, Result};
use clap::{Parser, Subcommand, ValueEnum};
use std::path::{Path, PathBuf};
use touchdown_scenario::schema::Engine;
use touchdown_scenario::Scenario;

#[derive(Parser)]
#[command(
    name = "touchdown",
    version,
    about = "Touchdown dynamics of soft-landing spacecraft (NASA TN D-7045 testbench)",
    max_term_width = 100
)]
pub(crate) struct Cli {
    #[command(subcommand)]
    pub(crate) command: Command,
    /// No progress bars on standard error (they are drawn only when it is a terminal, for
    /// `campaign`, `boundary`, `validate --protocol cv` and `precision`).
    #[arg(long, short, global = true)]
    pub(crate) quiet: bool,
}

#[derive(Subcommand)]
pub(crate) enum Command {
    /// Run one landing and print its summary.
    Run(RunArgs),
    /// Draft a first vehicle and landing from a handful of numbers (docs/authoring.md, "A
    /// vehicle in minutes"): writes DIR/vehicle.toml (every value not given derived by a rule
    /// written beside it, from the bundled robotic lander's proportions) and DIR/landing.toml,
    /// then reviews them as `touchdown check` does (exit 3 when it finds something). Numbers in
    /// the --units given; angles in degrees.
    New(DraftArgs),
    /// Review a vehicle and its landing before it runs (docs/authoring.md, "Checked before it
    /// lands"): the gear's crush load against the weight, its stroke energy against the
    /// touchdown energy, the static tip-over angle against the slope, the principal moments,
    /// and every finding with the file that set the value. Exits 3 when there is a finding;
    /// `run` prints the findings as warnings.
    Check(CheckArgs),
    /// Run scenarios through several engines and report how far apart they land, channel by
    /// channel against written tolerances (docs/engines.md, "Comparing the engines").
    Compare(CompareArgs),
    /// Watch a landing: run the scenario on each engine and write a page that plays them side by
    /// side or overlaid in a browser (struts coloured by force, footpad contact, the ground, the
    /// stability walls; strokes and pitch rate linked to a time slider), with the trajectory file
    /// it plays (docs/engines.md, "Watching the engines land").
    View(ViewArgs),
    /// Work-precision: each engine and integration scheme over a ladder of step sizes or
    /// tolerances, its error against a converged reference (maximum strokes, pitch-rate history,
    /// final attitude) against its cost (steps, force evaluations, wall time); with
    /// --landings N, the same over a campaign's first N landings (median and worst error).
    /// Build with --release: wall times of a debug build say nothing.
    Precision(PrecisionArgs),
    /// The stiff and extreme catalogue (docs/robustness.md): every case on every engine that
    /// applies, classified as completed (bounded energy, strokes within the struts), stopped or
    /// refused with a diagnostic, or failed; with --search, the largest stable step of each
    /// stiff case and fixed-step method. Build with --release.
    Robustness(RobustnessArgs),
    /// Write the scenario's lander as a standalone MuJoCo model (MJCF); docs/engines.md tells
    /// how to open it in MuJoCo's viewer.
    ExportMjcf(ExportMjcfArgs),
    /// Run every Table I landing and the figure 25-26 landing against the report.
    Validate(ValidateArgs),
    /// Fit the estimated parameters to the calibration rows (reference/calibration-protocol.toml)
    /// and write the calibrated vehicle and the record into --out, or over the tracked
    /// scenarios/vehicles/lm-1-6-calibrated.toml and reference/calibration-result.toml with
    /// --update-tracked. Refused when the rows are fewer than the parameters; parameters the
    /// rows do not determine are flagged, and never written over the tracked files.
    Calibrate(CalibrateArgs),
    /// Estimate the figure 25-26 landing's touchdown velocities from the facts the text states
    /// (reference/fig-25-26-velocity-protocol.toml) and write reference/fig-25-26-velocities.toml.
    Estimate(EstimateArgs),
    /// How each estimated parameter (±fraction) moves each Table I stroke.
    Sensitivity(SensitivityArgs),
    /// A Monte Carlo campaign: landings of a base scenario with dispersed touchdown conditions,
    /// in parallel, with the probability of a stable landing and its lower confidence bound,
    /// failure modes, strokes against capacities and peak loads (docs/campaigns.md).
    Campaign(CampaignArgs),
    /// Print the shell completion script for SHELL (bash, zsh, fish, elvish, powershell), e.g.
    /// `touchdown completions bash > ~/.local/share/bash-completion/completions/touchdown`.
    Completions(CompletionsArgs),
    /// Write the manual pages (roff): touchdown.1 and one touchdown-COMMAND.1 per command, into
    /// DIR (read with `man -l DIR/touchdown.1`).
    Man(ManArgs),
    /// The report's stability-boundary search: for each vertical velocity, every horizontal
    /// speed at which the landing changes between stable and unstable (a band where it
    /// alternates), the first at which a strut goes past its capacity, and the safe envelope,
    /// found on a grid of Vh, scanned finer around the changes and bisected; undecided
    /// landings are listed, never counted as either; on the core, each transition's bracket
    /// ends are landed again with every step limit ÷ 8 to state whether the step moves it
    /// (settings in the scenario's length unit per second, the horizontal direction the
    /// scenario's; JSON and CSV in SI).
    Boundary(BoundaryArgs),
}

/// The arguments of `touchdown run` (the command's documentation is on [`Command::Run`]).
#[derive(clap::Args)]
pub(crate) struct RunArgs {
    /// Scenario file (TOML).
    pub(crate) scenario: PathBuf,
    #[command(flatten)]
    pub(crate) set: Overrides,
    /// Output format of the summary on standard output.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub(crate) format: Format,
    /// Also write summary.json, history.csv and scenario.resolved.toml into this folder.
    #[arg(long, value_name = "DIR")]
    pub(crate) out: Option<PathBuf>,
    /// Also write report.html into the --out folder: one self-contained page of the landing
    /// (the outcome and why, each strut's maximum stroke against its capacity with its
    /// time, the energy ledger as bars, the time histories), no script, no network.
    #[arg(long, requires = "out")]
    pub(crate) report: bool,
    /// history.csv: keep every Nth step's row (and the last). By default rows are no closer
    /// than the core's largest step integrator.dt_max: every step on the core, every Nth on
    /// rapier and MuJoCo with N = floor(dt_max / timestep) (10 on the 1/6-scale model);
    /// --every 1 keeps every step.
    #[arg(long, value_name = "N", requires = "out")]
    pub(crate) every: Option<usize>,
    /// Engine to run: core (the report-faithful core), rapier (the multibody rebuild,
    /// settings in [engines.rapier]) or mujoco (the MuJoCo export, run by the pinned `mujoco`
    /// in the project's Python environment with the shared laws; settings in
    /// [engines.mujoco]; set up by scripts/setup-python). The scenario's engines.applicable
    /// must list it.
    #[arg(long, default_value = "core", value_parser = str::parse::<Engine>)]
    pub(crate) engine: Engine,
    /// rapier and MuJoCo engines: fixed time step, s (overrides engines.rapier.timestep or
    /// engines.mujoco.timestep).
    #[arg(long)]
    pub(crate) timestep: Option<f64>,
    /// Also land two copies with the touchdown velocity moved by one unit in the last place
    /// across, each way, and name the maxima (and the outcome) they move by more than the
    /// tolerance `touchdown compare` judges them by, or that a landing which is its own mirror
    /// image lands apart on a leg and its image: not determined at this precision
    /// (docs/engines.md, "Rounding-decided channels"). Three more landings.
    #[arg(long)]
    pub(crate) rounding: bool,
}

/// The arguments of `touchdown check` (the command's documentation is on [`Command::Check`]).
#[derive(clap::Args)]
pub(crate) struct CheckArgs {
    /// Scenario file (TOML).
    pub(crate) scenario: PathBuf,
    #[command(flatten)]
    pub(crate) set: Overrides,
    /// Output format: text, or the review as one JSON document
    /// (docs/schemas/check.schema.json).
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub(crate) format: Format,
}

/// The arguments of `touchdown compare` (the command's documentation is on [`Command::Compare`]).
#[derive(clap::Args)]
pub(crate) struct CompareArgs {
    /// Scenario files (TOML).
    #[arg(required = true)]
    pub(crate) scenarios: Vec<PathBuf>,
    #[command(flatten)]
    pub(crate) set: Overrides,
    /// Engines to compare, comma-separated (every pair is compared); each scenario runs on
    /// those its engines.applicable lists.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "core,rapier,mujoco",
        value_parser = str::parse::<Engine>
    )]
    pub(crate) engines: Vec<Engine>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub(crate) format: Format,
    /// Also write each scenario's comparison into DIR: DIR/<scenario>.json (its document, as
    /// --format json prints it) and the traces the metrics were computed from,
    /// DIR/<scenario>.<engine>.csv.
    #[arg(long, value_name = "DIR")]
    pub(crate) out: Option<PathBuf>,
    /// Also draw each scenario's engines overlaid (vertical acceleration over the 2 ms
    /// window, pitch rate, strokes against time, each channel's verdict) into
    /// DIR/<scenario>.png (matplotlib, in the project's Python environment).
    #[arg(long, requires = "out")]
    pub(crate) plot: bool,
    /// Also write each scenario's landings to watch into DIR: DIR/<scenario>.html (a
    /// self-contained page playing the engines side by side) and the trajectory file it
    /// plays, DIR/<scenario>.trajectory.json (as `touchdown view` writes them).
    #[arg(long, value_name = "DIR")]
    pub(crate) view: Option<PathBuf>,
    /// With --view: landing time between the frames kept, s (every contact event is kept
    /// besides).
    #[arg(long, value_name = "S", requires = "view", default_value_t = touchdown_view::DEFAULT_FRAME_INTERVAL)]
    pub(crate) frame_interval: f64,
    /// Exit 0 whatever the verdict (by default a failing pair exits with status 3).
    #[arg(long)]
    pub(crate) report_only: bool,
}

/// The arguments of `touchdown view` (the command's documentation is on [`Command::View`]).
#[derive(clap::Args)]
pub(crate) struct ViewArgs {
    /// Scenario file (TOML).
    pub(crate) scenario: PathBuf,
    #[command(flatten)]
    pub(crate) set: Overrides,
    /// Engines to run, comma-separated: those the scenario's engines.applicable lists.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "core,rapier,mujoco",
        value_parser = str::parse::<Engine>
    )]
    pub(crate) engines: Vec<Engine>,
    /// Landing time between the frames kept, s (every contact event is kept besides).
    #[arg(long, value_name = "S", default_value_t = touchdown_view::DEFAULT_FRAME_INTERVAL)]
    pub(crate) frame_interval: f64,
    /// Write DIR/<scenario>.html and DIR/<scenario>.trajectory.json here.
    #[arg(long, value_name = "DIR")]
    pub(crate) out: PathBuf,
}

/// The arguments of `touchdown precision` (the command's documentation is on [`Command::Precision`]).
#[derive(clap::Args)]
pub(crate) struct PrecisionArgs {
    /// Scenario file (TOML); with --landings, a campaign file.
    pub(crate) scenario: PathBuf,
    #[command(flatten)]
    pub(crate) set: Overrides,
    /// The file is a campaign (docs/campaigns.md): study its first N landings together, the
    /// campaign mix (docs/performance.md, "Work-precision on the campaign mix"): each
    /// landing's reference (the report's scheme refined, with its resolution), then each
    /// rung's median and worst error over them, for the campaign's engines among --engines.
    #[arg(long, value_name = "N", conflicts_with = "plot")]
    pub(crate) landings: Option<u64>,
    /// With --landings: end a method's ladder at the first rung whose landings take longer
    /// than this on average, s (its finer rungs cost more; the Dormand–Prince pair at tight
    /// tolerances takes minutes a landing).
    #[arg(long, value_name = "S", requires = "landings", default_value_t = 5.0)]
    pub(crate) max_landing_time: f64,
    /// Engines to measure, comma-separated (the core with each of its schemes); those the
    /// scenario's engines.applicable lists.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "core,rapier,mujoco",
        value_parser = str::parse::<Engine>
    )]
    pub(crate) engines: Vec<Engine>,
    /// Timed runs per rung (the wall time is their median).
    #[arg(long, default_value_t = 3)]
    pub(crate) repeats: usize,
    /// Only the first N (coarsest) rungs of each ladder.
    #[arg(long, value_name = "N")]
    pub(crate) rungs: Option<usize>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub(crate) format: Format,
    /// Also write the study into DIR/precision-<scenario>.json (its document, as --format
    /// json prints it).
    #[arg(long, value_name = "DIR")]
    pub(crate) out: Option<PathBuf>,
    /// Also draw the log-log work-precision plot into DIR/precision-<scenario>.png
    /// (matplotlib, in the project's Python environment).
    #[arg(long, requires = "out")]
    pub(crate) plot: bool,
}

/// The arguments of `touchdown robustness` (the command's documentation is on [`Command::Robustness`]).
#[derive(clap::Args)]
pub(crate) struct RobustnessArgs {
    /// Engines, comma-separated.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "core,rapier,mujoco",
        value_parser = str::parse::<Engine>
    )]
    pub(crate) engines: Vec<Engine>,
    /// Only these cases, comma-separated (default: the whole catalogue).
    #[arg(long, value_delimiter = ',')]
    pub(crate) cases: Option<Vec<String>>,
    /// Also search the largest stable step of each stiff case.
    #[arg(long)]
    pub(crate) search: bool,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub(crate) format: Format,
    /// The project's folder, holding scenarios/ (default: $TOUCHDOWN_HOME, else the project
    /// found above the executable or the current directory).
    #[arg(long)]
    pub(crate) root: Option<PathBuf>,
}

/// The arguments of `touchdown export-mjcf` (the command's documentation is on [`Command::ExportMjcf`]).
#[derive(clap::Args)]
pub(crate) struct ExportMjcfArgs {
    /// Scenario file (TOML).
    pub(crate) scenario: PathBuf,
    #[command(flatten)]
    pub(crate) set: Overrides,
    /// Folder to write the model into, as DIR/<scenario>.xml.
    #[arg(long, value_name = "DIR")]
    pub(crate) out: PathBuf,
}

/// The arguments of `touchdown validate` (the command's documentation is on [`Command::Validate`]).
#[derive(clap::Args)]
pub(crate) struct ValidateArgs {
    /// Which protocol: `two-row` (reference/calibration-protocol.toml: the calibrated
    /// scenarios against the rows they were not fitted to) or `cv` (reference/
    /// cross-validation-protocol.toml: leave-one-out over every row, what the rows
    /// determine, an interval on every prediction; about 2.7 million landings, about 70
    /// minutes on 2 cores, release).
    #[arg(long, value_enum, default_value_t = ValidationProtocol::TwoRow)]
    pub(crate) protocol: ValidationProtocol,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub(crate) format: Format,
    /// The project's folder, holding reference/ and scenarios/ (default: $TOUCHDOWN_HOME,
    /// else the project found above the executable or the current directory).
    #[arg(long)]
    pub(crate) root: Option<PathBuf>,
    /// Also write the data behind the plots here: validation.json and fig-25-26-series.json
    /// (two-row), cross-validation.json (cv).
    #[arg(long)]
    pub(crate) out: Option<PathBuf>,
    /// Exit 0 whatever the verdict (by default a target not met exits with status 3).
    #[arg(long)]
    pub(crate) report_only: bool,
}

/// The arguments of `touchdown calibrate` (the command's documentation is on [`Command::Calibrate`]).
#[derive(clap::Args)]
pub(crate) struct CalibrateArgs {
    /// Table I rows to calibrate on, e.g. 3,7 (default: the protocol's).
    #[arg(long, value_delimiter = ',')]
    pub(crate) rows: Option<Vec<u32>>,
    /// Write the calibrated vehicle and the record into this folder.
    #[arg(
        long,
        required_unless_present = "update_tracked",
        conflicts_with = "update_tracked"
    )]
    pub(crate) out: Option<PathBuf>,
    /// Write them over the tracked files the Table I scenarios extend.
    #[arg(long)]
    pub(crate) update_tracked: bool,
    /// The project's folder, holding reference/ and scenarios/ (default: $TOUCHDOWN_HOME,
    /// else the project found above the executable or the current directory).
    #[arg(long)]
    pub(crate) root: Option<PathBuf>,
}

/// The arguments of `touchdown estimate` (the command's documentation is on [`Command::Estimate`]).
#[derive(clap::Args)]
pub(crate) struct EstimateArgs {
    /// The project's folder, holding reference/ and scenarios/ (default: $TOUCHDOWN_HOME,
    /// else the project found above the executable or the current directory).
    #[arg(long)]
    pub(crate) root: Option<PathBuf>,
}

/// The arguments of `touchdown sensitivity` (the command's documentation is on [`Command::Sensitivity`]).
#[derive(clap::Args)]
pub(crate) struct SensitivityArgs {
    /// Relative change of each parameter.
    #[arg(long, default_value_t = 0.2)]
    pub(crate) fraction: f64,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub(crate) format: Format,
    /// The project's folder, holding reference/ and scenarios/ (default: $TOUCHDOWN_HOME,
    /// else the project found above the executable or the current directory).
    #[arg(long)]
    pub(crate) root: Option<PathBuf>,
}

/// The arguments of `touchdown completions` (the command's documentation is on [`Command::Completions`]).
#[derive(clap::Args)]
pub(crate) struct CompletionsArgs {
    /// The shell.
    pub(crate) shell: clap_complete::Shell,
}

/// The arguments of `touchdown man` (the command's documentation is on [`Command::Man`]).
#[derive(clap::Args)]
pub(crate) struct ManArgs {
    /// Folder for the pages.
    #[arg(long, value_name = "DIR")]
    pub(crate) out: PathBuf,
}

/// The arguments of `touchdown boundary` (the command's documentation is on [`Command::Boundary`]).
#[derive(clap::Args)]
pub(crate) struct BoundaryArgs {
    /// Scenario file (TOML).
    pub(crate) scenario: PathBuf,
    #[command(flatten)]
    pub(crate) set: Overrides,
    /// Vertical velocities FROM:TO:STEP as the scenario files write them, negative down, in
    /// the scenario's length unit per second (`--vv=-4:-12:2`: −4, −6, ... −12), or one
    /// (`--vv=-8`).
    #[arg(long, allow_hyphen_values = true, value_name = "FROM:TO:STEP")]
    pub(crate) vv: String,
    /// First horizontal speed of the grid, in the scenario's length unit per second
    /// [default: 0].
    #[arg(long, allow_negative_numbers = true, value_name = "VH")]
    pub(crate) vh_start: Option<f64>,
    /// Step of the horizontal-speed grid: every grid point is landed, and every change of
    /// outcome between neighbours is bisected [default: 0.25 of the vehicle's velocity
    /// scale √(g·footprint radius), 2.11 ft/s on the 1/6-scale model].
    #[arg(long, value_name = "STEP")]
    pub(crate) vh_step: Option<f64>,
    /// Largest horizontal speed of the grid [default: 3.5 of the velocity scale, 29.6 ft/s
    /// on the 1/6-scale model].
    #[arg(long, allow_negative_numbers = true, value_name = "VH")]
    pub(crate) vh_max: Option<f64>,
    /// Bisection tolerance on the horizontal speed [default: 0.006 of the velocity scale,
    /// 0.051 ft/s on the 1/6-scale model].
    #[arg(long, value_name = "TOL")]
    pub(crate) tol: Option<f64>,
    /// Step of the finer scan from a grid step below the first change the grid finds to a
    /// grid step above the last, so that an outcome alternating faster than the grid is
    /// seen [default: an eighth of --vh-step; 0: the grid only].
    #[arg(long, value_name = "STEP")]
    pub(crate) scan_step: Option<f64>,
    /// Search once per end-stop coefficient of restitution in this comma-separated list,
    /// set on every strut's load-stroke diagram (`--stop-restitution 0.1,0.25,0.5,1`), and
    /// report the spread: how much of the boundary the estimated stop law decides.
    #[arg(long, value_delimiter = ',', value_name = "E,...")]
    pub(crate) stop_restitution: Vec<f64>,
    /// Engines that search, comma-separated; each searches the same configuration and the
    /// output has one row per engine and descent speed.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "core",
        value_parser = str::parse::<Engine>
    )]
    pub(crate) engines: Vec<Engine>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = TableFormat::Text)]
    pub(crate) format: TableFormat,
    /// Also write the points into DIR/boundary-<scenario>.jsonl (as --format json prints
    /// them).
    #[arg(long, value_name = "DIR")]
    pub(crate) out: Option<PathBuf>,
    /// Also draw the engines' boundaries, overlaid, into DIR/boundary-<scenario>.png
    /// (matplotlib, in the project's Python environment).
    #[arg(long, requires = "out")]
    pub(crate) plot: bool,
}

#[derive(clap::Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub(crate) struct CampaignArgs {
    #[command(subcommand)]
    pub(crate) action: Option<CampaignAction>,
    /// Campaign file (TOML; docs/campaigns.md).
    #[arg(required = true)]
    pub(crate) file: Option<PathBuf>,
    /// Run only shard K of N (landings ⌊(K−1)·n/N⌋ to ⌊K·n/N⌋ − 1); `touchdown campaign merge`
    /// joins the shards' folders.
    #[arg(long, value_name = "K/N", value_parser = str::parse::<touchdown_campaign::Shard>)]
    pub(crate) shard: Option<touchdown_campaign::Shard>,
    /// Write manifest.json, landings.jsonl, landings.parquet and statistics.json (and the
    /// histories the campaign asks for) into DIR; with --add, the finished campaign to extend.
    #[arg(long, value_name = "DIR")]
    pub(crate) out: Option<PathBuf>,
    /// Output on standard output: the statistics as text, or JSON Lines (a landing record per
    /// line as they finish, in landing order, then one line {"statistics": ...}).
    #[arg(long, value_enum, default_value_t = Format::Text)]
    pub(crate) format: Format,
    /// Add M landings to the finished campaign in --out, leaving its landings unchanged.
    #[arg(long, value_name = "M")]
    pub(crate) add: Option<u64>,
    /// Go on with the run of this campaign (or shard) into --out that was stopped (killed, out
    /// of time, out of disk), from the records it wrote in DIR.partial: the folder ends as an
    /// uninterrupted run's, byte for byte. With --add, the same for landings being added.
    /// Starts afresh when there is nothing of this run to resume.
    #[arg(long, requires = "out")]
    pub(crate) resume: bool,
    /// Threads that land (default: one per core); the records do not depend on it.
    #[arg(long, value_name = "N")]
    pub(crate) threads: Option<usize>,
    /// Land every landing's draws on each of these engines, comma-separated, instead of the
    /// campaign file's `engine`/`engines`: with several, a paired campaign (a block of columns
    /// per engine, and the statistics of each pair; docs/campaigns.md, "Paired campaigns").
    #[arg(long, value_delimiter = ',', value_parser = str::parse::<Engine>)]
    pub(crate) engines: Option<Vec<Engine>>,
    /// Also draw outcomes.png (every landing over the two dispersed inputs most correlated
    /// with a stable landing) and strokes.png (strokes against capacities) into --out, from
    /// the records there (matplotlib, in the project's Python environment); for a paired
    /// campaign, disagreement.png and differences.png of its first pair of engines.
    #[arg(long, requires = "out")]
    pub(crate) plot: bool,
    /// With a paired campaign: also write the K landings its first pair lists as disagreeing
    /// most as pages that play every engine side by side, --out/views/landing-N.html (as
    /// `touchdown view` writes them).
    #[arg(long, value_name = "K", requires = "out")]
    pub(crate) view: Option<usize>,
}

#[derive(Subcommand)]
pub(crate) enum CampaignAction {
    /// Join the folders of a campaign's shards into one, refusing parts of other campaigns,
    /// builds or base scenarios, and parts that overlap or leave landings out.
    Merge {
        /// The shards' folders.
        #[arg(required = true)]
        parts: Vec<PathBuf>,
        /// Folder of the merged campaign.
        #[arg(long, value_name = "DIR")]
        out: PathBuf,
        /// Output format (as for a campaign).
        #[arg(long, value_enum, default_value_t = Format::Text)]
        format: Format,
    },
    /// Estimate P(stable) on an expensive engine from a paired campaign of it with a cheap
    /// engine and a larger campaign of the same draws on the cheap engine alone: a
    /// multi-fidelity (control-variate) estimate with its interval (docs/campaigns.md,
    /// "Multi-fidelity estimate").
    Estimate {
        /// The paired campaign's folder (two engines, e.g. `--engines core,rapier`).
        #[arg(long, value_name = "DIR")]
        paired: PathBuf,
        /// The folder of the same campaign on the cheap engine alone (`--engines core`), with
        /// at least as many landings (`--add` more).
        #[arg(long, value_name = "DIR")]
        low: PathBuf,
        /// The cost of a landing on the expensive engine over one on the cheap engine, for the
        /// variance reduction at equal cost (docs/performance.md, "Paired campaigns").
        #[arg(long, value_name = "R")]
        cost_ratio: Option<f64>,
        /// Output format: text, or the estimate as JSON.
        #[arg(long, value_enum, default_value_t = Format::Text)]
        format: Format,
    },
}

impl Cli {
    /// The command line parsed, with one mistake clap cannot name caught first: `--set FIELD
    /// VALUE` (a space where the `=` goes), which clap would report as an unexpected argument
    /// with advice to write `-- -3`.
    pub(crate) fn parse_arguments() -> Cli {
        let args: Vec<std::ffi::OsString> = std::env::args_os().collect();
        if let Some(message) = set_split_in_two(&args) {
            use clap::CommandFactory;
            Cli::command()
                .error(clap::error::ErrorKind::ValueValidation, message)
                .exit();
        }
        Cli::parse_from(args)
    }
}

/// The message for `--set FIELD VALUE` written as two arguments, if `args` holds one.
fn set_split_in_two(args: &[std::ffi::OsString]) -> Option<String> {
    args.windows(3).find_map(|w| {
        let (flag, field, value) = (w[0].to_str()?, w[1].to_str()?, w[2].to_str()?);
        (flag == "--set" && !field.contains('=') && !value.starts_with("--")).then(|| {
            format!(
                "--set {field} {value}: the field and its value are one argument joined by '=': --set {field}={value}"
            )
        })
    })
}

/// `--set FIELD=VALUE`, on every command that takes a scenario.
#[derive(clap::Args)]
pub(crate) struct Overrides {
    /// Change one value of the scenario: a field path and a value in the scenario's own units,
    /// as in the file (`--set touchdown.vertical_velocity=-10.0`, `--set footpad.detached=rigid`,
    /// `--set 'touchdown.attitude[2]=45.0'`); repeatable.
    #[arg(long = "set", value_name = "FIELD=VALUE")]
    pub(crate) set: Vec<Set>,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum TableFormat {
    Text,
    Json,
    Csv,
}

/// A `--set FIELD=VALUE` override: a scenario field path and its value in the scenario's own
/// units, as TOML (a number, a boolean, a quoted or bare string).
#[derive(Debug, Clone)]
pub struct Set {
    pub(crate) field: String,
    pub(crate) value: toml::Value,
}

impl std::str::FromStr for Set {
    type Err = String;

    fn from_str(s: &str) -> Result<Set, String> {
        let (field, value) = s.split_once('=').ok_or_else(|| {
            format!("expected FIELD=VALUE (e.g. touchdown.vertical_velocity=-10.0), got {s:?}")
        })?;
        let field = field.trim();
        if field.is_empty() {
            return Err(format!("expected a field path before '=', got {s:?}"));
        }
        let value = value.trim();
        if value.contains('\n') {
            return Err(format!(
                "expected one value on one line after '=' (a TOML value, e.g. [0.0, 1.0]), got {value:?}"
            ));
        }
        // A TOML value as the file would hold it; a bare word (letters, digits, `_`, `-`, `.`)
        // is a string (surface.kind=soil). Anything else that is not TOML is refused with
        // TOML's reason: an unclosed quote or bracket is a typo, not a string.
        let bare_word = !value.is_empty()
            && value
                .chars()
                .all(|c| c.is_alphanumeric() || matches!(c, '_' | '-' | '.'));
        let parsed = toml::from_str::<toml::Table>(&format!("v = {value}"))
            .map_err(|e| e.message().to_string())
            .and_then(|mut t| t.remove("v").ok_or_else(|| "no value".to_string()));
        let value = match parsed {
            Ok(v) => v,
            // A number with a unit after it (`-3 m/s`, `5deg`): the file's units are implied.
            Err(_) if number_with_unit(value).is_some() => {
                return Err(format!(
                    "{field}: a value is in the scenario file's own units, written as the number alone: {field}={} (the file's [units] say which)",
                    number_with_unit(value).unwrap_or_default()
                ))
            }
            Err(_) if bare_word => toml::Value::String(value.to_string()),
            Err(reason) => {
                return Err(format!(
                    "{field}: expected a TOML value after '=' (a number, true or false, \"a string\", [a, list]) or a bare word, got {value:?}: {reason}"
                ))
            }
        };
        Ok(Set {
            field: field.to_string(),
            value,
        })
    }
}

/// The number at the start of `value` when a unit follows it (`-3 m/s` → `-3`).
fn number_with_unit(value: &str) -> Option<&str> {
    let end = value
        .find(|c: char| !(c.is_ascii_digit() || matches!(c, '-' | '+' | '.' | 'e' | 'E')))
        .filter(|&i| i > 0)?;
    let (number, rest) = value.split_at(end);
    (number.parse::<f64>().is_ok() && rest.trim_start().starts_with(|c: char| c.is_alphabetic()))
        .then_some(number)
}

impl std::fmt::Display for Set {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} = {}", self.field, self.value)
    }
}

/// The overrides of `--set`, as [`touchdown_scenario::ScenarioBase::with`] takes them.
pub fn overrides(set: &[Set]) -> Vec<(&str, toml::Value)> {
    set.iter()
        .map(|s| (s.field.as_str(), s.value.clone()))
        .collect()
}

/// The settings of a command's documents: the `--set` overrides, then its `options` (an
/// object, each name with its unit).
pub fn settings(set: &[Set], options: serde_json::Value) -> serde_json::Value {
    touchdown_record::document::settings(set.iter().map(|s| (s.field.as_str(), &s.value)), options)
}

/// The scenario file at `path` read once, and resolved with the `--set` overrides (an error
/// names the field, as for a file).
pub fn load(path: &Path, set: &[Set]) -> Result<(touchdown_scenario::ScenarioBase, Scenario)> {
    let base = touchdown_scenario::ScenarioBase::load(path)?;
    let sc = base.with(&overrides(set));
    let sc = if set.is_empty() {
        sc?
    } else {
        sc.with_context(|| format!("{} with --set", path.display()))?
    };
    Ok((base, sc))
}

/// The validation protocols of `touchdown validate`.
#[derive(Clone, Copy, ValueEnum)]
pub(crate) enum ValidationProtocol {
    /// Two calibration rows, six held out (reference/calibration-protocol.toml).
    TwoRow,
    /// Leave-one-out cross-validation (reference/cross-validation-protocol.toml).
    Cv,
}

/// `touchdown new`: the numbers a first vehicle and landing are drafted from.
#[derive(clap::Args)]
pub(crate) struct DraftArgs {
    /// Folder to write vehicle.toml and landing.toml into (created; existing files are
    /// never overwritten).
    #[arg(long, value_name = "DIR")]
    pub(crate) out: PathBuf,
    /// The vehicle's name.
    #[arg(long)]
    pub(crate) name: String,
    /// The unit system of every number given and of the files: si (m, kg, N, s) or
    /// ft-slug-lbf (ft, slug, lbf, s).
    #[arg(long, value_enum)]
    pub(crate) units: DraftUnits,
    /// Gear arrangement.
    #[arg(long, value_enum, default_value_t = DraftArrangement::Cantilever)]
    pub(crate) arrangement: DraftArrangement,
    /// Number of legs, evenly spaced.
    #[arg(long, default_value_t = 4)]
    pub(crate) legs: usize,
    /// Vehicle mass at touchdown, without the footpads; mass.
    #[arg(long, allow_hyphen_values = true)]
    pub(crate) mass: f64,
    /// Local gravity (1.62 m/s² on the Moon); length/time².
    #[arg(long, allow_hyphen_values = true)]
    pub(crate) gravity: f64,
    /// Principal moments of inertia about the centre of mass, XX,YY,ZZ; mass·length².
    #[arg(
        long,
        value_delimiter = ',',
        num_args = 1,
        required = true,
        allow_hyphen_values = true,
        value_name = "XX,YY,ZZ"
    )]
    pub(crate) inertia: Vec<f64>,
    /// Radius of the circle through the footpads, seen from above; length.
    #[arg(long, allow_hyphen_values = true)]
    pub(crate) footprint_radius: f64,
    /// Height of the centre of mass above the footpads, gear undeformed; length.
    #[arg(long, allow_hyphen_values = true)]
    pub(crate) centre_of_mass_height: f64,
    /// The primary strut's first crush load; force.
    #[arg(long, allow_hyphen_values = true)]
    pub(crate) crush_load: f64,
    /// The primary strut's stroke capacity; length.
    #[arg(long, allow_hyphen_values = true)]
    pub(crate) stroke: f64,
    /// Touchdown vertical velocity, negative down; length/time.
    #[arg(long, allow_hyphen_values = true)]
    pub(crate) vertical_velocity: f64,
    /// Touchdown horizontal velocity along +Y (downhill on a slope; toward leg 2 of four);
    /// length/time.
    #[arg(long, allow_hyphen_values = true, default_value_t = 0.0)]
    pub(crate) horizontal_velocity: f64,
    /// Surface slope about X, deg (+Y downhill).
    #[arg(long, allow_hyphen_values = true, default_value_t = 0.0)]
    pub(crate) slope: f64,
}

/// `touchdown new --units`.
#[derive(Clone, Copy, ValueEnum)]
pub(crate) enum DraftUnits {
    /// m, kg, N, s.
    Si,
    /// ft, slug, lbf, s.
    FtSlugLbf,
}

/// `touchdown new --arrangement`.
#[derive(Clone, Copy, ValueEnum)]
pub(crate) enum DraftArrangement {
    /// The LM's: secondaries attached to the primary at point 1.
    Cantilever,
    /// Inverted tripod: secondaries attached at the footpad.
    Tripod,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum Format {
    Text,
    Json,
}
