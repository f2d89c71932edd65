//! Loading: TOML text → checked [`Scenario`], with errors that name the file, line, column and
//! field.
//!
//! Three stages, each reporting the first problem it finds:
//! 1. TOML syntax (the parser's own position);
//! 2. shape: serde into the flat `raw` structs (unknown fields, wrong types, missing fields) and
//!    their conversion into the typed model (fields that do not fit an object's `kind`, ...);
//! 3. rules: the checks of `rules/` on the typed scenario.
//!
//! Stages 2 and 3 are `build.rs`'s [`build`].
//!
//! `locate.rs` places each problem in the text (file, line, column, field path).

use std::path::Path;

use super::build::build;
use super::diagnostic::DiagnosticKind;
use super::locate::{Document, invalid, unlocated};
use super::raw::RawScenario;
use super::rules::{steps_rule, validate};
use super::types::Scenario;
use super::warning::ScenarioWarning;
use crate::{Result, SimError};

impl Scenario {
    /// Reads and checks the scenario file at `path`. The scenario's `name` defaults to the
    /// file stem, and `source` is set to `path`. Its warnings: [`Scenario::warnings`], or
    /// [`Scenario::from_path_with_warnings`] for their lines.
    pub fn from_path(path: &Path) -> Result<Scenario> {
        Self::from_path_with_warnings(path).map(|(s, _)| s)
    }

    /// [`Scenario::from_path`], with the scenario's warnings (file, line, field, message).
    pub fn from_path_with_warnings(path: &Path) -> Result<(Scenario, Vec<ScenarioWarning>)> {
        let text = std::fs::read_to_string(path).map_err(|source| SimError::ScenarioRead {
            path: path.to_owned(),
            source,
        })?;
        load(&text, &path.display().to_string(), &stem(path), Some(path))
    }

    /// Parses and checks scenario text. `origin` names the text in error messages (a file name
    /// such as `scenarios/x.toml`); the scenario's `name` defaults to its stem.
    pub fn from_str(text: &str, origin: &str) -> Result<Scenario> {
        Self::from_str_with_warnings(text, origin).map(|(s, _)| s)
    }

    /// [`Scenario::from_str`], with the scenario's warnings (file, line, field, message).
    pub fn from_str_with_warnings(
        text: &str,
        origin: &str,
    ) -> Result<(Scenario, Vec<ScenarioWarning>)> {
        load(text, origin, &stem(Path::new(origin)), None)
    }

    /// Checks a scenario built or changed in code by the same rules as a loaded file (the
    /// diagnostic has no line: there is no file).
    pub fn validate(&self) -> Result<()> {
        validate(self)
            .map(drop)
            .map_err(|p| invalid(unlocated(self.file(), DiagnosticKind::Rule, p)))
    }

    /// The warnings of a valid scenario (none if it is invalid), without lines: they name the
    /// file (or the scenario) and the field. A loaded file's warnings with their lines come
    /// from [`Scenario::from_path_with_warnings`] and [`resolve_with_warnings`].
    ///
    /// [`resolve_with_warnings`]: super::resolve_with_warnings
    pub fn warnings(&self) -> Vec<ScenarioWarning> {
        validate(self)
            .unwrap_or_default()
            .into_iter()
            .map(|f| ScenarioWarning {
                kind: f.kind,
                diagnostic: unlocated(self.file(), DiagnosticKind::Warning, f.problem),
            })
            .collect()
    }

    /// What the diagnostics of a scenario without a text name: its file, or its name.
    fn file(&self) -> String {
        self.source
            .as_ref()
            .map_or_else(|| self.name.clone(), |s| s.display().to_string())
    }
}

/// Refuses a step count given on the command line (`--steps`) by the rule of a file's
/// `steps`, with the same message; `field` names the option.
pub fn check_steps(steps: u32, field: &str) -> Result<()> {
    steps_rule(steps, field).map_err(|p| {
        invalid(unlocated(
            "command line".to_owned(),
            DiagnosticKind::Rule,
            p,
        ))
    })
}

fn stem(path: &Path) -> String {
    path.file_stem().map_or_else(
        || "scenario".to_owned(),
        |s| s.to_string_lossy().into_owned(),
    )
}

/// Parses, converts and validates `text` (the file `source`, if any: the scenario's
/// `source`); errors and warnings name `origin`.
pub(crate) fn load(
    text: &str,
    origin: &str,
    default_name: &str,
    source: Option<&Path>,
) -> Result<(Scenario, Vec<ScenarioWarning>)> {
    let doc = Document::parse(text, origin)?;
    let raw: RawScenario = doc.deserialize()?;
    let (scenario, findings) =
        build(raw, default_name, source).map_err(|(kind, p)| invalid(doc.locate(kind, p)))?;
    let warnings = findings
        .into_iter()
        .map(|f| ScenarioWarning {
            kind: f.kind,
            diagnostic: doc.locate(DiagnosticKind::Warning, f.problem),
        })
        .collect();
    Ok((scenario, warnings))
}
