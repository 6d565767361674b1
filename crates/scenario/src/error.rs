//! Scenario errors and warnings: every one names the file and, where there is one, the field.
//! Numbers in their messages are in short notation ([`crate::units::short`]).

/// An error in a scenario file.
#[derive(Debug, thiserror::Error)]
pub enum ScenarioError {
    /// The file could not be read.
    /// (`cause` is part of the message, not a chained source, so that it reads once.)
    #[error("{file}: cannot read the scenario file: {cause}")]
    Io { file: String, cause: std::io::Error },
    /// The file is larger than any scenario file: `bytes` over the limit `most`.
    #[error("{file}: cannot read the scenario file: the file is {bytes} bytes; a scenario file is at most {most} bytes ({} MiB)", most >> 20)]
    TooLarge { file: String, bytes: u64, most: u64 },
    /// The path is not a regular file (a directory, a FIFO, a device, a socket): refused before
    /// it is opened, so that a FIFO cannot block the reader.
    #[error("{file}: not a regular file ({kind}): expected a scenario file (TOML)")]
    NotAFile { file: String, kind: String },
    /// The file holds no TOML key at all (an empty or comment-only file, `/dev/null` copied).
    #[error("{file}: empty file: expected a scenario (schema_version, name, [units], [vehicle], [gear], [primary_strut], [secondary_strut], [footpad], [surface], [touchdown], [integrator]; docs/scenario-format.md)")]
    Empty { file: String },
    /// A vehicle description (a file with neither `[surface]` nor `[touchdown]`, such as
    /// `scenarios/vehicles/lm-1-6.toml`) loaded as a landing.
    #[error("{file}: a vehicle description, not a landing (it has no [surface] and no [touchdown]): it is meant to be extended by a landing file, one with `extends = \"<path to this file>\"` that adds [surface] and [touchdown], as the landings in scenarios/ extend scenarios/vehicles/lm-1-6.toml")]
    NotALanding { file: String },
    /// The file is not valid TOML.
    #[error("{file}: not valid TOML: {message}")]
    Syntax { file: String, message: String },
    /// A field is missing, unknown, of the wrong type, or has an invalid value.
    #[error("{file}: field `{field}`: {message}")]
    Field {
        file: String,
        field: String,
        message: String,
    },
}

impl ScenarioError {
    /// A field error: `expected` says what a valid value is.
    pub fn field(file: &str, field: impl Into<String>, message: impl Into<String>) -> Self {
        ScenarioError::Field {
            file: file.to_string(),
            field: field.into(),
            message: message.into(),
        }
    }
}

/// A value the loader accepts but that lies outside the usual range of its field
/// (docs/scenario-format.md, "Ranges"): legal, and possibly meant, but worth a look. A loaded
/// scenario lists them in [`crate::Scenario::warnings`]; callers print them.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Warning {
    /// The file of the `extends` chain that sets the field.
    pub file: String,
    /// The field path, e.g. `touchdown.vertical_velocity`.
    pub field: String,
    /// What is unusual about the value, with the usual range.
    pub message: String,
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}: field `{}`: warning: {}",
            self.file, self.field, self.message
        )
    }
}
