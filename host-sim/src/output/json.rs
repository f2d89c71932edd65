//! JSON files of a run (`summary.json`, `scene.json`): written pretty with a final newline, whole
//! or not at all, and read back with errors that name the file.

use std::path::Path;

use serde::Serialize;
use serde::de::DeserializeOwned;

use super::atomic::write_atomic;
use crate::{Result, SimError};

/// Writes `value` as pretty JSON with a final newline to `path`, whole or not at all.
pub(crate) fn write_json<T: Serialize>(path: &Path, value: &T) -> Result<()> {
    let text = serde_json::to_string_pretty(value).map_err(|source| SimError::Json {
        op: "serialising",
        path: path.to_path_buf(),
        source,
    })?;
    write_atomic(path, |w| {
        w.write_all(text.as_bytes())?;
        w.write_all(b"\n")
    })
}

/// Reads the JSON file `path`.
pub(crate) fn read_json<T: DeserializeOwned>(path: &Path) -> Result<T> {
    let text = std::fs::read_to_string(path).map_err(|e| SimError::io("reading", path, e))?;
    serde_json::from_str(&text).map_err(|source| SimError::Json {
        op: "parsing",
        path: path.to_path_buf(),
        source,
    })
}
