//! A problem at a field path: what every check of the scenario layer reports, before it is
//! located in the file (see `locate.rs`).

use std::fmt;

/// A problem at a field path (`groups[1].spawn.radius`, or relative while converting): what
/// every rule reports, the loader then places it in the file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Problem {
    /// Path of the field; empty for the value itself.
    pub path: String,
    /// What was wrong and what was expected.
    pub message: String,
}

impl Problem {
    /// A problem at `path` saying `message`.
    pub fn new(path: impl Into<String>, message: impl Into<String>) -> Self {
        Problem {
            path: path.into(),
            message: message.into(),
        }
    }

    /// The same problem seen from the parent: `prefix` is prepended to the path.
    pub(crate) fn under(mut self, prefix: &str) -> Self {
        self.path = join(prefix, &self.path);
        self
    }
}

/// `prefix` + `path` with a dot where needed (`a` + `b` = `a.b`, `a` + `[1]` = `a[1]`).
pub(crate) fn join(prefix: &str, path: &str) -> String {
    if prefix.is_empty() {
        path.to_owned()
    } else if path.is_empty() {
        prefix.to_owned()
    } else if path.starts_with('[') {
        format!("{prefix}{path}")
    } else {
        format!("{prefix}.{path}")
    }
}

impl fmt::Display for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.path.is_empty() {
            write!(f, "{}", self.message)
        } else {
            write!(f, "`{}`: {}", self.path, self.message)
        }
    }
}
