//! The envelope of every JSON document the project writes (docs/outputs.md, "The convention"):
//! which document it is, what wrote it, the scenario it is about (its path and the SHA-256 of
//! the resolved scenario) and the settings it ran with, then the document's own fields. The
//! fields of a document are SI with the unit in the name; the settings echo what the user
//! gave, in the units the user gave it (a `--set` value in the scenario file's units).

use serde::Serialize;

/// The version of the project that wrote a document.
pub const TOUCHDOWN_VERSION: &str = env!("CARGO_PKG_VERSION");

/// Which scenario a document is about.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct ScenarioId {
    /// The scenario file as named on the command line (or `<scenario text>` for a scenario
    /// given as text).
    pub path: String,
    /// SHA-256 of the resolved scenario (every default written out), hex: two documents with
    /// the same hash ran the same landing whatever their files looked like.
    pub sha256: String,
}

impl ScenarioId {
    /// The scenario at `path` as resolved into `sc`.
    pub fn new(path: impl std::fmt::Display, sc: &touchdown_scenario::Scenario) -> ScenarioId {
        ScenarioId {
            path: path.to_string(),
            sha256: sc.sha256(),
        }
    }
}

/// A document: the envelope, then `body`'s fields (a struct or map serialising to an object).
#[derive(Debug, Clone, Serialize)]
pub struct Document<'a, T: Serialize> {
    /// Which document, and the version of its schema: `touchdown.run/1`, described by
    /// `docs/schemas/run.schema.json`.
    pub schema: String,
    /// The version of the project that wrote it.
    pub touchdown_version: &'static str,
    /// The scenario it is about (left out of documents about several scenarios, whose items
    /// each name theirs).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub scenario: Option<&'a ScenarioId>,
    /// The settings of the command that wrote it, as given.
    pub settings: &'a serde_json::Value,
    /// The document's own fields.
    #[serde(flatten)]
    pub body: &'a T,
}

impl<'a, T: Serialize> Document<'a, T> {
    /// The document `kind` (`run`, `compare`, ...) about `scenario`, written with `settings`.
    pub fn new(
        kind: &str,
        scenario: Option<&'a ScenarioId>,
        settings: &'a serde_json::Value,
        body: &'a T,
    ) -> Self {
        Document {
            schema: format!("touchdown.{kind}/1"),
            touchdown_version: TOUCHDOWN_VERSION,
            scenario,
            settings,
            body,
        }
    }

    /// The document as pretty JSON (a file, or a command's single document).
    pub fn pretty(&self) -> String {
        serde_json::to_string_pretty(self).expect("a document serialises: numbers and strings")
    }

    /// The document on one line (a line of JSON Lines).
    pub fn line(&self) -> String {
        serde_json::to_string(self).expect("a document serialises: numbers and strings")
    }
}

/// The settings of a command as its documents record them: `set`, the `--set FIELD=VALUE`
/// overrides as given (`[{"field": ..., "value": ...}]`, in the scenario file's units, in the
/// order given), then `options`, the command's own options (an object; each name with its unit).
pub fn settings<'v>(
    overrides: impl IntoIterator<Item = (&'v str, &'v toml::Value)>,
    options: serde_json::Value,
) -> serde_json::Value {
    let set: Vec<serde_json::Value> = overrides
        .into_iter()
        .map(|(field, value)| {
            let value = serde_json::to_value(value)
                .unwrap_or_else(|_| serde_json::Value::String(value.to_string()));
            serde_json::json!({ "field": field, "value": value })
        })
        .collect();
    let mut settings = serde_json::Map::new();
    settings.insert("set".into(), serde_json::Value::Array(set));
    if let serde_json::Value::Object(options) = options {
        settings.extend(options);
    }
    serde_json::Value::Object(settings)
}
