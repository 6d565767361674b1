//! Scenario errors: every one names the file and, where there is one, the field.

/// An error in a scenario file.
#[derive(Debug, thiserror::Error)]
pub enum ScenarioError {
    /// The file could not be read.
    #[error("{file}: cannot read the scenario file: {message}")]
    Io { file: String, message: String },
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
