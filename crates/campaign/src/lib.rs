//! Monte Carlo touchdown campaigns (docs/campaigns.md): thousands of landings of one base
//! scenario with dispersed touchdown conditions, run in parallel on any engine, each landing
//! drawn from its own counter-based stream so that the results are the same whatever the
//! threads, shards or order; per-landing records as JSON Lines and Parquet; the probability of
//! a stable landing with its lower confidence bound.
//!
//! | module | content |
//! |---|---|
//! | [`boundary`] | the stability boundary of the base configuration over the campaign's speeds, for its outcomes plot |
//! | [`accuracy`] | the accuracy the campaign's integrator settings give: its first landings against runs refined eightfold |
//! | [`spec`] | the campaign file: base scenario, dispersions and their units, correlations, landings, seed, engine, records |
//! | [`distribution`] | the distributions' quantile functions and each landing's random stream |
//! | [`record`] | a landing's record: the values applied (read back), its outcome and failure mode, its strokes, loads and margins |
//! | [`statistics`] | P(stable) with its Clopper-Pearson lower bound, the zero-failure sizes, counts, percentiles |
//! | [`fidelity`] | a multi-fidelity (control-variate) estimate of a probability on an expensive engine from a paired campaign and a larger one on a cheap engine |
//! | [`paired`] | a paired campaign's statistics: each engine's, and between engines the disagreement rate, McNemar's test, paired differences, the worst landings |
//! | [`store`] | the campaign's files, read and written: the manifest, `landings.jsonl`, `landings.parquet`, `statistics.json` |
//! | [`analysis`] | the statistics of the stored records, and the landings they name written as scenarios |
//! | [`folder`] | the campaign's folder: built beside `--out`, locked, exchanged when complete |
//! | [`landing`] | one landing: drawn, resolved, read back, landed on each engine; its record |
//! | [`run`] | landings in parallel, shards, merges and extensions |

pub mod accuracy;
pub mod analysis;
pub mod boundary;
pub mod distribution;
pub mod fidelity;
pub mod folder;
pub mod landing;
pub mod paired;
pub mod record;
pub mod run;
pub mod spec;
pub mod statistics;
pub mod store;

pub use paired::Report;
pub use run::{add, merge, Shard};
pub use spec::Campaign;
pub use statistics::Statistics;

/// What stops a campaign (a landing that fails is a record, not an error).
#[derive(Debug, thiserror::Error)]
pub enum CampaignError {
    /// The campaign file cannot be read (missing, not a file, too large, not TOML).
    #[error("{file}: cannot read the campaign file: {message}")]
    File {
        /// The file.
        file: String,
        /// What went wrong.
        message: String,
    },
    /// A field of the campaign file is missing, unknown, of the wrong type or invalid.
    #[error("{file}: field `{field}`: {message}")]
    Field {
        /// The campaign file.
        file: String,
        /// The field path, e.g. `dispersion[1].std_dev`.
        field: String,
        /// What a valid value is.
        message: String,
    },
    /// The engine cannot be set up (its runtime missing): no landing can run.
    #[error(transparent)]
    Engine(Box<touchdown_registry::EngineFailure>),
    /// A dispersed value is not what the resolved scenario holds (a fault of this program,
    /// never of the input: the records would not say what ran).
    #[error("landing {landing}: the resolved scenario has no value at `{field}` to read back")]
    NotApplied {
        /// The landing.
        landing: u64,
        /// The field.
        field: String,
    },
    /// Reading or writing a campaign's files.
    #[error("{path}: {message}")]
    Store {
        /// The file or folder.
        path: String,
        /// What went wrong.
        message: String,
    },
    /// Parts that are not of one campaign, or do not hold each landing once.
    #[error("{0}")]
    Mismatch(String),
    /// The stability boundary of the base configuration (for the outcomes plot) cannot be
    /// searched.
    #[error("the base configuration's stability boundary: {0}")]
    Boundary(#[from] touchdown_validation::ValidationError),
    /// The thread pool cannot be built.
    #[error("cannot start the landing threads: {0}")]
    Threads(String),
}

impl CampaignError {
    /// What went wrong (`e`) reading or writing the file or folder at `path`.
    pub fn store(path: &std::path::Path, e: impl std::fmt::Display) -> Self {
        CampaignError::Store {
            path: path.display().to_string(),
            message: e.to_string(),
        }
    }

    /// A field error of the campaign file `file`.
    pub fn field(file: &str, field: impl Into<String>, message: impl Into<String>) -> Self {
        CampaignError::Field {
            file: file.to_string(),
            field: field.into(),
            message: message.into(),
        }
    }

    /// A campaign file that cannot be read, from the reader's error.
    pub fn file(e: &touchdown_scenario::ScenarioError) -> Self {
        use touchdown_scenario::ScenarioError as S;
        let (file, message) = match e {
            S::Io { file, cause } => (file, cause.to_string()),
            S::TooLarge { file, bytes, most } => (
                file,
                format!(
                    "the file is {bytes} bytes; a campaign file is at most {most} bytes ({} MiB)",
                    most >> 20
                ),
            ),
            S::NotAFile { file, kind } => (file, format!("not a regular file ({kind})")),
            S::Empty { file } => (
                file,
                "empty file: expected a campaign (docs/campaigns.md)".into(),
            ),
            S::Syntax { file, message } => (file, format!("not valid TOML: {message}")),
            S::NotALanding { file } | S::Field { file, .. } => (file, e.to_string()),
        };
        CampaignError::File {
            file: file.clone(),
            message,
        }
    }
}

/// SHA-256 of `bytes`, hex.
pub(crate) fn sha256_hex(bytes: &[u8]) -> String {
    use sha2::{Digest, Sha256};
    format!("{:x}", Sha256::digest(bytes))
}
