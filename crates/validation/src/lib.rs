//! Validation of the report-faithful core against the 1/6-scale LM drop tests of NASA TN D-7045
//! (docs/validation.md): Table I with calibration rows and held-out rows, the sensitivity of every stroke to
//! the estimated parameters, the facts the text states about the figure 25-26 landing, and the
//! report's automatic stability-boundary search.
//!
//! The reference data and the protocol are files under `reference/` (each with provenance); the
//! landings are the scenarios under `scenarios/`.

pub mod boundary;
pub mod calibrate;
pub mod checkpoint;
pub mod cross_validation;
pub mod estimate;
pub mod facts;
pub mod reference;
pub mod sensitivity;
pub mod si;
pub mod table;

/// Errors of the validation tools.
#[derive(Debug, thiserror::Error)]
pub enum ValidationError {
    /// A reference file is missing or malformed.
    #[error("reference data: {0}")]
    Reference(String),
    /// A scenario failed to load.
    #[error(transparent)]
    Scenario(#[from] touchdown_scenario::ScenarioError),
    /// A landing did not complete (the cause follows in the error chain).
    #[error("{scenario}")]
    Run {
        /// The scenario.
        scenario: String,
        /// What became of it.
        source: touchdown_record::RunError,
    },
    /// A point of a search that the scenario cannot take: a speed outside its field's range.
    #[error("{scenario} at vertical velocity {vv}, horizontal speed {vh} (the file's units, from the speeds asked for)")]
    Point {
        /// The scenario.
        scenario: String,
        /// The vertical velocity, in the file's units, negative down.
        vv: String,
        /// The horizontal speed, in the file's units.
        vh: String,
        /// What the scenario says of it (boxed: the rare path, kept out of every result's size).
        source: Box<touchdown_scenario::ScenarioError>,
    },
    /// The optimiser failed.
    #[error("calibration: {0}")]
    Calibration(String),
    /// A table could not be written (the stability-boundary search's CSV).
    #[error("CSV: {0}")]
    Csv(#[from] csv::Error),
    /// A setting is out of its range (the stability-boundary search's, for one).
    #[error("{argument}: expected {expected}, got {got}")]
    Setting {
        /// The command-line argument that carries the setting, e.g. `--vh-step`.
        argument: &'static str,
        /// What it must be.
        expected: String,
        /// The value given.
        got: String,
    },
}
