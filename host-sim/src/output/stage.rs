//! A run's output folder holds exactly one run: its files appear together or not at all.
//!
//! A run writes into a *staging folder* beside its target, a hidden sibling named
//! `.<target>.staging-<pid>-<random>`. Only when every file is complete is it swapped into
//! place: on Linux with one atomic `renameat2(RENAME_EXCHANGE)` (at every instant the target is
//! the old run or the new one), elsewhere, or where the file system cannot exchange, by renaming
//! the old folder aside to `.<target>.old-<pid>-<random>` and the staging folder in. The old run
//! is then removed. A new target is simply the staging folder renamed.
//!
//! What a kill (SIGKILL, power loss) leaves behind, at each point:
//!
//! | killed ...                          | the target is   | left beside it                      |
//! |-------------------------------------|-----------------|-------------------------------------|
//! | while the run writes                | the old run     | the staging folder (partial)        |
//! | after the exchange                  | the new run     | the old run under the staging name  |
//! | between the two fallback renames    | missing         | the old run as `.<target>.old-...`  |
//!
//! Temporary files of the atomic writers live inside the staging folder and go with it. Every
//! run first cleans up what dead processes left in the folder it writes into ([`clean_stale`]):
//! staging and failed folders are removed, and an `old` folder whose target is missing is put
//! back. Only folders whose name has that pattern, whose process is gone and which hold nothing
//! but run files are touched: user files are never deleted. For the same reason a run refuses
//! to replace an existing folder that holds anything a run does not write.
//!
//! A run that fails (a full disk, a controller error) keeps only its `run.log`, with the error
//! at its end, in `.<target>.failed-<pid>-<random>/` ([`Staging::abandon`]); the target is left
//! untouched and the next run into that folder removes the failed one.

use std::ffi::OsStr;
use std::fs;
use std::io;
use std::path::{Path, PathBuf};

use tempfile::TempDir;

use super::{
    ATTITUDE_NPY, POSITIONS_NPY, RUN_GIF, RUN_LOG, SCENE_JSON, SNAPSHOT_PNG, SUMMARY_JSON,
    TRAJECTORIES_CSV,
};
use crate::{Result, SimError};

/// Every file a run writes into its folder. A new output file must be listed here: a run
/// refuses to replace a folder holding a file not listed (the tests that identify whole run
/// folders, `host-sim/tests/common`, fail when a run writes an unlisted file).
pub const RUN_FILES: &[&str] = &[
    SCENE_JSON,
    TRAJECTORIES_CSV,
    POSITIONS_NPY,
    ATTITUDE_NPY,
    SUMMARY_JSON,
    SNAPSHOT_PNG,
    RUN_GIF,
    RUN_LOG,
];

/// Folders of a dead process younger than this are left alone where liveness cannot be asked
/// of the system (no `/proc`).
#[cfg(not(target_os = "linux"))]
const STALE_AFTER: std::time::Duration = std::time::Duration::from_secs(24 * 3600);

/// What a hidden sibling of a run folder is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Sibling {
    /// A run being written.
    Staging,
    /// The previous run, moved aside during a fallback swap.
    Old,
    /// The log of a failed run.
    Failed,
}

impl Sibling {
    const ALL: [Sibling; 3] = [Sibling::Staging, Sibling::Old, Sibling::Failed];

    fn tag(self) -> &'static str {
        match self {
            Sibling::Staging => "staging",
            Sibling::Old => "old",
            Sibling::Failed => "failed",
        }
    }

    /// `.<target>.<tag>-<pid>-` (tempfile adds the random part).
    fn prefix(self, target: &str) -> String {
        format!(".{target}.{}-{}-", self.tag(), std::process::id())
    }
}

/// Length of the random part of a sibling's name.
const RANDOM_LEN: usize = 8;

/// `.<target>.<tag>-<pid>-<random>` → (target, kind, pid).
fn parse_sibling(name: &str) -> Option<(&str, Sibling, u32)> {
    let rest = name.strip_prefix('.')?;
    let (rest, random) = rest.rsplit_once('-')?;
    if random.len() != RANDOM_LEN || !random.bytes().all(|b| b.is_ascii_alphanumeric()) {
        return None;
    }
    let (rest, pid) = rest.rsplit_once('-')?;
    let pid: u32 = pid.parse().ok()?;
    let (target, tag) = rest.rsplit_once('.')?;
    let kind = Sibling::ALL.into_iter().find(|k| k.tag() == tag)?;
    (!target.is_empty()).then_some((target, kind, pid))
}

/// Whether `name` is a file a run writes, or the temporary file of one
/// (`.<run file>.<random>.tmp`, see [`AtomicFile`](super::AtomicFile)).
pub fn is_run_file_name(name: &str) -> bool {
    if RUN_FILES.contains(&name) {
        return true;
    }
    let Some(inner) = name.strip_prefix('.').and_then(|n| n.strip_suffix(".tmp")) else {
        return false;
    };
    RUN_FILES.iter().any(|f| {
        inner
            .strip_prefix(f)
            .is_some_and(|r| r.starts_with('.') && r.len() > 1)
    })
}

/// The first entry of folder `dir` that a run does not write (a sub-folder, a link, a file of
/// another name); `None` when the folder holds only run files.
fn foreign_entry(dir: &Path) -> io::Result<Option<String>> {
    for entry in fs::read_dir(dir)? {
        let entry = entry?;
        let name = entry.file_name().to_string_lossy().into_owned();
        if !entry.file_type()?.is_file() || !is_run_file_name(&name) {
            return Ok(Some(name));
        }
    }
    Ok(None)
}

/// Whether process `pid` may still be running.
#[cfg(target_os = "linux")]
fn alive(pid: u32, _dir: &Path) -> bool {
    pid == std::process::id() || Path::new("/proc").join(pid.to_string()).exists()
}

/// Whether process `pid` may still be running (without `/proc`: whether the folder is recent).
#[cfg(not(target_os = "linux"))]
fn alive(pid: u32, dir: &Path) -> bool {
    pid == std::process::id()
        || fs::symlink_metadata(dir)
            .and_then(|m| m.modified())
            .ok()
            .and_then(|t| t.elapsed().ok())
            .is_none_or(|age| age < STALE_AFTER)
}

/// Removes (or, for an `old` folder whose target is missing, puts back) what runs killed
/// earlier left in `parent`: hidden staging, old and failed folders of dead processes that hold
/// only run files. Best effort: what cannot be cleaned stays, and the run goes on. Returns the
/// folders removed or restored.
pub fn clean_stale(parent: &Path) -> Vec<PathBuf> {
    let mut done = Vec::new();
    let Ok(entries) = fs::read_dir(parent) else {
        return done;
    };
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some((target, kind, pid)) = name.to_str().and_then(parse_sibling) else {
            continue;
        };
        let path = entry.path();
        let is_dir = entry.file_type().is_ok_and(|t| t.is_dir());
        if !is_dir || alive(pid, &path) || !matches!(foreign_entry(&path), Ok(None)) {
            continue;
        }
        let target = parent.join(target);
        let cleaned = if kind == Sibling::Old && fs::symlink_metadata(&target).is_err() {
            fs::rename(&path, &target).is_ok()
        } else {
            fs::remove_dir_all(&path).is_ok()
        };
        if cleaned {
            done.push(path);
        }
    }
    done
}

/// A run being written: the staging folder beside its target (see the module docs).
///
/// Dropped without [`commit`](Staging::commit) or [`abandon`](Staging::abandon), it removes the
/// staging folder.
#[derive(Debug)]
pub struct Staging {
    /// The run folder to replace.
    target: PathBuf,
    /// Its parent.
    parent: PathBuf,
    /// Its file name.
    name: String,
    /// The staging folder.
    dir: TempDir,
}

impl Staging {
    /// Prepares a run into `target`: creates its parent, cleans what killed runs left there,
    /// checks that an existing `target` is a run folder (a folder holding only run files), and
    /// creates the staging folder. Nothing in `target` changes.
    pub fn begin(target: impl AsRef<Path>) -> Result<Self> {
        let target = resolve(target.as_ref())?;
        let (parent, name) = split(&target)?;
        fs::create_dir_all(&parent).map_err(|e| SimError::io("creating the folder", &parent, e))?;
        clean_stale(&parent);
        match fs::symlink_metadata(&target) {
            Ok(m) if m.is_dir() => {
                let foreign = foreign_entry(&target)
                    .map_err(|e| SimError::io("reading the folder", &target, e))?;
                if let Some(entry) = foreign {
                    return Err(SimError::NotARunFolder { dir: target, entry });
                }
            }
            Ok(_) => {
                return Err(SimError::io(
                    "writing the run folder",
                    &target,
                    io::Error::other("a file of that name exists and is not a folder"),
                ));
            }
            Err(e) if e.kind() == io::ErrorKind::NotFound => {}
            Err(e) => return Err(SimError::io("reading", &target, e)),
        }
        let dir = sibling(&parent, &name, Sibling::Staging)
            .map_err(|e| SimError::io("creating a staging folder beside", &target, e))?;
        Ok(Self {
            target,
            parent,
            name,
            dir,
        })
    }

    /// The staging folder: write every file of the run here.
    pub fn path(&self) -> &Path {
        self.dir.path()
    }

    /// The run folder this run replaces (symbolic links resolved).
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// Swaps the staging folder in as the target and removes the previous run. On an error the
    /// target is as it was and the staging folder, handed back, still holds the new run.
    pub fn commit(self) -> std::result::Result<(), Box<(Self, SimError)>> {
        sync_dir(self.dir.path());
        let exists = fs::symlink_metadata(&self.target).is_ok();
        let swapped = if !exists {
            fs::rename(self.dir.path(), &self.target)
        } else {
            match exchange(self.dir.path(), &self.target) {
                Ok(()) => Ok(()),
                Err(_) => self.swap_by_renames(),
            }
        };
        if let Err(e) = swapped {
            let err = SimError::io("moving the finished run into", &self.target, e);
            return Err(Box::new((self, err)));
        }
        sync_dir(&self.parent);
        // After an exchange the staging path holds the previous run, which dropping the
        // `TempDir` removes; after a rename it holds nothing.
        drop(self.dir);
        Ok(())
    }

    /// The fallback swap: the target aside to an `old` folder, the staging folder in, the old
    /// folder removed (on the way out of this function).
    fn swap_by_renames(&self) -> io::Result<()> {
        let old = sibling(&self.parent, &self.name, Sibling::Old)?;
        // Renaming a folder over an empty folder replaces it.
        fs::rename(&self.target, old.path())?;
        if let Err(e) = fs::rename(self.dir.path(), &self.target) {
            if fs::rename(old.path(), &self.target).is_err() {
                // The target is missing: keep the previous run where the next run puts it back.
                let _ = old.keep();
            }
            return Err(e);
        }
        Ok(())
    }

    /// Gives the run up after an error: keeps only its `run.log` (which should end with the
    /// error), moved to a `failed` folder beside the target, and returns that log's path; the
    /// target is untouched. `None` if the log could not be kept (the staging folder is then
    /// removed whole).
    pub fn abandon(self) -> Option<PathBuf> {
        if let Ok(entries) = fs::read_dir(self.dir.path()) {
            for entry in entries.flatten() {
                if entry.file_name() != OsStr::new(RUN_LOG) {
                    let _ = fs::remove_file(entry.path());
                }
            }
        }
        self.dir.path().join(RUN_LOG).is_file().then_some(())?;
        let failed = sibling(&self.parent, &self.name, Sibling::Failed).ok()?;
        fs::rename(self.dir.path(), failed.path()).ok()?;
        let _ = self.dir.keep();
        Some(failed.keep().join(RUN_LOG))
    }
}

/// `target` with a symbolic link (at its last component) resolved, and `.`/`..` made into a
/// named folder.
fn resolve(target: &Path) -> Result<PathBuf> {
    let is_link = fs::symlink_metadata(target).is_ok_and(|m| m.file_type().is_symlink());
    if is_link || target.file_name().is_none() {
        return fs::canonicalize(target).map_err(|e| SimError::io("resolving", target, e));
    }
    Ok(target.to_path_buf())
}

/// Parent folder and file name of a target.
fn split(target: &Path) -> Result<(PathBuf, String)> {
    let name = target
        .file_name()
        .and_then(OsStr::to_str)
        .ok_or_else(|| SimError::OutputFolderName {
            path: target.to_path_buf(),
        })?
        .to_owned();
    let parent = match target.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    Ok((parent, name))
}

/// A new empty hidden sibling folder of `kind` for target `name` in `parent` (removed when
/// dropped unless kept).
fn sibling(parent: &Path, name: &str, kind: Sibling) -> io::Result<TempDir> {
    let prefix = kind.prefix(name);
    let mut b = tempfile::Builder::new();
    b.prefix(&prefix).rand_bytes(RANDOM_LEN);
    #[cfg(unix)]
    {
        // The usual mode of a new folder (the umask still applies), not tempfile's 0700.
        use std::os::unix::fs::PermissionsExt;
        b.permissions(fs::Permissions::from_mode(0o777));
    }
    b.tempdir_in(parent)
}

/// Swaps two paths atomically (Linux `renameat2(RENAME_EXCHANGE)`).
#[cfg(target_os = "linux")]
fn exchange(a: &Path, b: &Path) -> io::Result<()> {
    use rustix::fs::{CWD, RenameFlags, renameat_with};
    renameat_with(CWD, a, CWD, b, RenameFlags::EXCHANGE).map_err(io::Error::from)
}

/// No atomic exchange here: the caller falls back to two renames.
#[cfg(not(target_os = "linux"))]
fn exchange(_a: &Path, _b: &Path) -> io::Result<()> {
    Err(io::Error::from(io::ErrorKind::Unsupported))
}

/// Syncs a folder so renames in it are durable (best effort).
fn sync_dir(dir: &Path) {
    #[cfg(unix)]
    if let Ok(d) = fs::File::open(dir) {
        let _ = d.sync_all();
    }
    #[cfg(not(unix))]
    let _ = dir;
}

#[cfg(test)]
mod tests;
