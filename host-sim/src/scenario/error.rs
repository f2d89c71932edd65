//! The scenario layer's error type.

use std::fmt;
use std::path::PathBuf;

/// Everything that can go wrong while finding, reading, parsing or validating a scenario.
///
/// A bad file never yields a [`Scenario`](super::Scenario): loading stops at the first problem
/// and reports it as a [`Diagnostic`] naming the file, the line and column, the field path
/// (`groups[1].spawn.radius`) and what was wrong and expected.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ScenarioError {
    /// The scenario file could not be read.
    #[error("cannot read scenario file `{}`: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        #[source]
        source: std::io::Error,
    },
    /// The text is not valid TOML, does not have the scenario's shape (unknown field, wrong
    /// type, missing field) or breaks a rule of the scenario (a spawn region outside the world,
    /// an event naming a missing object, a bad controller parameter, ...).
    #[error("{0}")]
    Invalid(Box<Diagnostic>),
    /// `resolve` found neither a built-in scenario nor a file of that name.
    #[error(
        "no built-in scenario and no file named `{name}` (built-in scenarios: {})",
        super::builtin_names().join(", ")
    )]
    NotFound {
        /// The name or path asked for.
        name: String,
    },
}

impl ScenarioError {
    /// The diagnostic of an [`Invalid`](ScenarioError::Invalid) error.
    pub fn diagnostic(&self) -> Option<&Diagnostic> {
        match self {
            ScenarioError::Invalid(d) => Some(d),
            _ => None,
        }
    }
}

/// Which stage rejected a scenario.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum DiagnosticKind {
    /// Not valid TOML.
    Syntax,
    /// Valid TOML, but a field is unknown, missing or of the wrong type.
    Shape,
    /// Well-formed, but breaks a rule of the scenario (ranges, names, kinds, parameters).
    Rule,
    /// Not an error: the scenario runs, but probably not as meant (a
    /// [`ScenarioWarning`](super::ScenarioWarning)).
    Warning,
}

/// Where a scenario is wrong and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic {
    /// Which stage rejected the file.
    pub kind: DiagnosticKind,
    /// The file (or the origin name given to `Scenario::from_str`).
    pub file: String,
    /// 1-based line of the offending field; `None` for a scenario built in code.
    pub line: Option<usize>,
    /// 1-based column (in characters) of the offending field.
    pub column: Option<usize>,
    /// Path of the offending field, e.g. `groups[1].spawn.radius`; empty when the problem is
    /// not inside a field (some syntax errors).
    pub field: String,
    /// What was wrong and what was expected.
    pub message: String,
    /// The source line, for display.
    pub source_line: Option<String>,
}

impl fmt::Display for Diagnostic {
    /// `file:line:column: field `path`: message`, then the source line with a caret.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file)?;
        if let Some(line) = self.line {
            write!(f, ":{line}")?;
            if let Some(column) = self.column {
                write!(f, ":{column}")?;
            }
        }
        write!(f, ": ")?;
        match self.kind {
            DiagnosticKind::Syntax => write!(f, "TOML syntax error")?,
            DiagnosticKind::Shape | DiagnosticKind::Rule => write!(f, "invalid scenario")?,
            DiagnosticKind::Warning => write!(f, "warning")?,
        }
        if !self.field.is_empty() {
            write!(f, " in `{}`", self.field)?;
        }
        write!(f, ": {}", self.message)?;
        if let (Some(line), Some(text)) = (self.line, &self.source_line) {
            let gutter = line.to_string().len();
            write!(f, "\n {line} | {text}")?;
            if let Some(column) = self.column {
                write!(
                    f,
                    "\n {:gutter$} | {:>width$}",
                    "",
                    "^",
                    gutter = gutter,
                    width = column
                )?;
            }
        }
        Ok(())
    }
}

/// `Result` with a [`ScenarioError`].
pub type Result<T> = std::result::Result<T, ScenarioError>;
