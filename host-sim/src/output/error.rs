//! The one error type of the output layer.

use std::io;
use std::path::PathBuf;

/// Everything that can go wrong while writing or reading a run's output files.
///
/// Every message names the file (or folder) and what failed, so it can be shown to a user as is.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum OutputError {
    /// An I/O operation on `path` failed (`op` says which: "creating", "writing", "reading", ...).
    #[error("{op} {}: {source}", path.display())]
    Io {
        /// What was being done.
        op: &'static str,
        /// The file or folder.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: io::Error,
    },
    /// A JSON file could not be written or parsed.
    #[error("{op} {}: {source}", path.display())]
    Json {
        /// "writing" or "parsing".
        op: &'static str,
        /// The file.
        path: PathBuf,
        /// The underlying error (its message carries line and column when parsing).
        #[source]
        source: serde_json::Error,
    },
    /// A required file of a run folder is missing.
    #[error("run folder {} has no {file} ({hint})", dir.display())]
    Missing {
        /// The run folder.
        dir: PathBuf,
        /// The missing file name (or names).
        file: String,
        /// What it is needed for.
        hint: &'static str,
    },
    /// A data file is malformed: `line` is 1-based for text files, 0 when not applicable.
    #[error("{}{}: {msg}", path.display(), if *line > 0 { format!(":{line}") } else { String::new() })]
    Format {
        /// The file.
        path: PathBuf,
        /// 1-based line number in a text file, 0 when the error has no line.
        line: usize,
        /// What is wrong.
        msg: String,
    },
    /// An existing output folder holds something no run writes (a run replaces its folder
    /// whole, so it refuses to delete what may be a user's file).
    #[error(
        "{} holds `{entry}`, which no run writes; a run replaces its output folder whole, so \
         choose another output folder (`--out`) or move `{entry}` away",
        dir.display()
    )]
    NotARunFolder {
        /// The folder.
        dir: PathBuf,
        /// The first entry that is not a run file.
        entry: String,
    },
    /// The data handed to a writer is inconsistent (frames of different agents, a bad scene...).
    #[error("cannot write {}: {msg}", path.display())]
    Invalid {
        /// The file that was to be written.
        path: PathBuf,
        /// What is wrong with the data.
        msg: String,
    },
}

impl OutputError {
    /// An I/O error on `path`.
    pub fn io(op: &'static str, path: impl Into<PathBuf>, source: io::Error) -> Self {
        Self::Io {
            op,
            path: path.into(),
            source,
        }
    }

    /// A malformed-file error.
    pub fn format(path: impl Into<PathBuf>, line: usize, msg: impl Into<String>) -> Self {
        Self::Format {
            path: path.into(),
            line,
            msg: msg.into(),
        }
    }

    /// An inconsistent-data error.
    pub fn invalid(path: impl Into<PathBuf>, msg: impl Into<String>) -> Self {
        Self::Invalid {
            path: path.into(),
            msg: msg.into(),
        }
    }
}

/// Result of the output layer.
pub type Result<T> = std::result::Result<T, OutputError>;
