//! The Touchdown scenario format: a TOML file with a `schema_version`, an explicit `[units]`
//! table and strict fields (unknown fields are errors), resolved into SI.
//!
//! * [`schema`]: the file as written, in its own units (each field documents its dimension);
//! * [`units`]: the unit systems a file may declare;
//! * [`model`]: the resolved, validated scenario in SI ([`Scenario`]);
//! * [`frames`]: the report's frames and initial state (eqs. 1-4, 19), shared by every engine.
//!
//! A file may `extends = "other.toml"`: tables are merged key by key, the extending file
//! winning. Errors name the file that holds the offending field.

pub mod error;
pub mod frames;
mod load;
mod mechanisms;
pub mod model;
pub mod schema;
pub mod units;

pub use error::ScenarioError;
pub use load::{merged_table, set_field};
pub use model::Scenario;
