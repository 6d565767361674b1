//! The Touchdown scenario format: a TOML file with a `schema_version`, an explicit `[units]`
//! table and strict fields (unknown fields are errors), resolved into SI.
//!
//! * [`schema`]: the file as written, in its own units (each field documents its dimension);
//! * [`dimension`]: the powers of length, mass, force, angle and time of a unit, read alike
//!   from the Ranges table, a campaign's units and the fields table's dimension column;
//! * [`units`]: the unit systems a file may declare, and [`units::short`], the short notation
//!   every number in a message is printed in;
//! * [`ranges`]: the range of physical plausibility of every number, checked on load in SI;
//! * [`model`]: the resolved, validated scenario in SI ([`Scenario`]), with the
//!   [`Scenario::warnings`] of values legal but outside their usual range;
//! * [`draft`]: a first vehicle and landing drafted from a handful of numbers (`touchdown new`);
//! * [`initial`]: the state a landing starts from (eq. 19), shared by every engine;
//! * [`scales`]: the vehicle's own length, velocity, time and acceleration scales, which
//!   judgements that must not depend on its size or units are ratios of;
//! * [`mirror`]: the mirror image, and the legs' images under which a landing is its own.
//!
//! A file may `extends = "other.toml"`: tables are merged key by key, the extending file
//! winning; it may not change the `[units]` of the file it extends. Errors name the file that
//! holds the offending field. Only regular files are read (a FIFO or a device is refused before
//! it is opened), and a table of the schema is read only from a TOML table (never from an
//! array, which serde's derived structs would otherwise accept field by field).

mod check;
pub mod dimension;
pub mod draft;
pub mod error;
pub mod initial;
mod load;
mod mechanisms;
pub mod mirror;
pub mod model;
mod overrides;
pub mod ranges;
mod read;
mod resolve;
pub mod scales;
pub mod schema;
mod strict;
#[cfg(test)]
mod tests;
pub mod units;

pub use error::{ScenarioError, Warning};
pub use load::ScenarioBase;
pub use model::Scenario;
pub use overrides::set_field;
pub use read::{merged_table, read_toml};
pub use resolve::{read_strict, SchemaMismatch};
