//! Diagnostics: where a scenario is wrong (file, line, column, field path) and why; the
//! payload of [`SimError::InvalidScenario`](crate::SimError::InvalidScenario) and of each
//! [`ScenarioWarning`](super::ScenarioWarning).

use std::fmt;

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
