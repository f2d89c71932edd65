//! Whole-or-nothing file writes.
//!
//! Every output file goes through [`AtomicFile`]: the bytes go to a temporary file in the same
//! folder (named `.<final name>.<random>`), which is flushed, synced to disk and then renamed over
//! the final name. A reader therefore sees either the previous file (or none) or the complete new
//! one, never a half-written file; on any error, or when the writer is dropped without
//! [`AtomicFile::commit`], the temporary file is removed and the final name is left untouched.

use std::ffi::OsString;
use std::fs::File;
use std::io::{self, BufWriter, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

use tempfile::NamedTempFile;

use crate::{Result, SimError};

/// Buffer size of the writer handed to callers.
const BUF_SIZE: usize = 256 * 1024;

/// A file being written atomically: write through [`AtomicFile::writer`], then
/// [`commit`](AtomicFile::commit). Dropping it uncommitted removes the temporary file.
pub struct AtomicFile {
    path: PathBuf,
    out: BufWriter<NamedTempFile>,
}

impl std::fmt::Debug for AtomicFile {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("AtomicFile")
            .field("path", &self.path)
            .field("temp", &self.out.get_ref().path())
            .finish()
    }
}

impl AtomicFile {
    /// Starts writing `path`: creates the temporary file beside it (the folder must exist).
    pub fn create(path: impl AsRef<Path>) -> Result<Self> {
        let path = path.as_ref().to_path_buf();
        let dir = match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let name = path
            .file_name()
            .ok_or_else(|| SimError::NoFileName { path: path.clone() })?;
        let mut prefix = OsString::from(".");
        prefix.push(name);
        prefix.push(".");
        let mut builder = tempfile::Builder::new();
        builder.prefix(&prefix).suffix(".tmp");
        #[cfg(unix)]
        {
            // The usual mode of a new file (the umask still applies), not tempfile's 0600.
            use std::os::unix::fs::PermissionsExt;
            builder.permissions(std::fs::Permissions::from_mode(0o666));
        }
        let tmp = builder
            .tempfile_in(&dir)
            .map_err(|e| SimError::io("creating a temporary file for", &path, e))?;
        Ok(Self {
            path,
            out: BufWriter::with_capacity(BUF_SIZE, tmp),
        })
    }

    /// The final path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The buffered writer into the temporary file.
    pub fn writer(&mut self) -> &mut BufWriter<NamedTempFile> {
        &mut self.out
    }

    /// Flushes the buffer and overwrites `len` bytes at `offset` (e.g. a header whose numbers are
    /// only known at the end), then returns to the end of the file.
    pub fn patch(&mut self, offset: u64, bytes: &[u8]) -> Result<()> {
        let path = self.path.clone();
        let io = |e| SimError::io("writing", &path, e);
        self.out.flush().map_err(io)?;
        let f = self.out.get_mut();
        f.seek(SeekFrom::Start(offset)).map_err(io)?;
        f.write_all(bytes).map_err(io)?;
        f.seek(SeekFrom::End(0)).map_err(io)?;
        Ok(())
    }

    /// Flushes, syncs and renames the temporary file over the final path.
    pub fn commit(self) -> Result<()> {
        let Self { path, out } = self;
        let tmp = out
            .into_inner()
            .map_err(|e| SimError::io("writing", &path, e.into_error()))?;
        tmp.as_file()
            .sync_all()
            .map_err(|e| SimError::io("syncing", &path, e))?;
        tmp.persist(&path)
            .map_err(|e| SimError::io("renaming the temporary file to", &path, e.error))?;
        sync_parent(&path);
        Ok(())
    }
}

/// Removes the temporary files that writers of `path` killed earlier left beside it
/// (`.<file name>.<random>.tmp`); returns how many. A writer of `path` running at the same time
/// would lose its temporary file and fail, leaving `path` as it was. Best effort.
pub fn remove_stale_temps(path: impl AsRef<Path>) -> usize {
    let path = path.as_ref();
    let (Some(dir), Some(name)) = (path.parent(), path.file_name().and_then(|n| n.to_str())) else {
        return 0;
    };
    let dir = if dir.as_os_str().is_empty() {
        Path::new(".")
    } else {
        dir
    };
    let prefix = format!(".{name}.");
    let Ok(entries) = std::fs::read_dir(dir) else {
        return 0;
    };
    entries
        .flatten()
        .filter(|e| {
            e.file_name().to_str().is_some_and(|n| {
                n.strip_prefix(&prefix)
                    .and_then(|r| r.strip_suffix(".tmp"))
                    .is_some_and(|random| !random.is_empty() && !random.contains('.'))
            }) && e.file_type().is_ok_and(|t| t.is_file())
        })
        .filter(|e| std::fs::remove_file(e.path()).is_ok())
        .count()
}

/// Syncs the folder holding `path` so the rename itself is durable (best effort: not every
/// platform or file system allows syncing a folder).
fn sync_parent(path: &Path) {
    #[cfg(unix)]
    if let Some(dir) = path.parent() {
        let dir = if dir.as_os_str().is_empty() {
            Path::new(".")
        } else {
            dir
        };
        if let Ok(d) = File::open(dir) {
            let _ = d.sync_all();
        }
    }
    #[cfg(not(unix))]
    let _ = path;
}

/// Writes `path` whole or not at all: `write` gets a buffered writer into a temporary file in the
/// same folder, which replaces `path` only if `write` returns `Ok`. An error from `write` is
/// reported as a write error on `path` and leaves no file behind.
pub fn write_atomic<F>(path: impl AsRef<Path>, write: F) -> Result<()>
where
    F: FnOnce(&mut dyn Write) -> io::Result<()>,
{
    let mut file = AtomicFile::create(path)?;
    if let Err(e) = write(file.writer()) {
        return Err(SimError::io("writing", file.path(), e));
    }
    file.commit()
}

/// Writes `bytes` to `path` whole or not at all.
pub fn write_atomic_bytes(path: impl AsRef<Path>, bytes: &[u8]) -> Result<()> {
    write_atomic(path, |w| w.write_all(bytes))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::testing::{entries, temp_path};

    /// `p` holds `contents` and is the only file in its folder.
    fn assert_alone_with(p: &Path, contents: &[u8]) {
        assert_eq!(std::fs::read(p).unwrap(), contents);
        let name = p.file_name().unwrap().to_string_lossy();
        assert_eq!(entries(p.parent().unwrap()), vec![name]);
    }

    /// [`write_atomic`] with a closure that writes `bytes` and then fails with `why`.
    fn write_then_fail(p: &Path, bytes: &[u8], why: &str) -> Result<()> {
        write_atomic(p, |w| {
            w.write_all(bytes)?;
            Err(io::Error::other(why))
        })
    }

    #[test]
    fn writes_whole_file() {
        let (_dir, p) = temp_path("a.txt");
        write_atomic(&p, |w| w.write_all(b"hello\n")).unwrap();
        assert_alone_with(&p, b"hello\n");
        // Overwrite.
        write_atomic_bytes(&p, b"bye").unwrap();
        assert_alone_with(&p, b"bye");
    }

    #[test]
    fn failing_closure_leaves_no_file() {
        let (dir, p) = temp_path("b.csv");
        let msg = write_then_fail(&p, &[b'x'; 1_000_000], "boom")
            .unwrap_err()
            .to_string();
        assert!(msg.contains("b.csv") && msg.contains("boom"), "{msg}");
        assert!(!p.exists());
        assert!(entries(dir.path()).is_empty(), "{:?}", entries(dir.path()));
    }

    #[test]
    fn failing_closure_keeps_previous_file() {
        let (_dir, p) = temp_path("c.json");
        write_atomic_bytes(&p, b"old").unwrap();
        assert!(write_then_fail(&p, b"new but broken", "nope").is_err());
        assert_alone_with(&p, b"old");
    }

    #[test]
    fn dropped_uncommitted_leaves_nothing() {
        let (dir, p) = temp_path("d.npy");
        {
            let mut f = AtomicFile::create(&p).unwrap();
            f.writer().write_all(b"partial").unwrap();
        }
        assert!(entries(dir.path()).is_empty());
    }

    #[test]
    fn stale_temporary_files_of_one_name_are_removed() {
        let (dir, p) = temp_path("run.gif");
        for n in [
            ".run.gif.aB3xYz.tmp",
            ".run.gif.q.tmp",
            ".run.gif.a.b.tmp",
            ".snapshot.png.x.tmp",
            "keep.tmp",
        ] {
            std::fs::write(dir.path().join(n), b"x").unwrap();
        }
        assert_eq!(remove_stale_temps(&p), 2);
        assert_eq!(
            entries(dir.path()),
            vec![".run.gif.a.b.tmp", ".snapshot.png.x.tmp", "keep.tmp"]
        );
    }

    #[test]
    fn patch_rewrites_header() {
        let (_dir, p) = temp_path("e.bin");
        let mut f = AtomicFile::create(&p).unwrap();
        f.writer().write_all(b"????-body").unwrap();
        f.patch(0, b"HEAD").unwrap();
        f.writer().write_all(b"-tail").unwrap();
        f.commit().unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), b"HEAD-body-tail");
    }

    #[test]
    fn missing_folder_names_the_path() {
        let (_dir, p) = temp_path("no/such/dir/f.txt");
        let msg = write_atomic_bytes(&p, b"x").unwrap_err().to_string();
        assert!(msg.contains("f.txt"), "{msg}");
    }

    #[cfg(unix)]
    #[test]
    fn file_mode_is_not_private() {
        use std::os::unix::fs::PermissionsExt;
        let (dir, p) = temp_path("m.txt");
        write_atomic_bytes(&p, b"x").unwrap();
        let mode = std::fs::metadata(&p).unwrap().permissions().mode() & 0o777;
        // Whatever the umask, group/other get at least what a plain File::create gives them.
        let q = dir.path().join("plain.txt");
        std::fs::write(&q, b"x").unwrap();
        let plain = std::fs::metadata(&q).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode, plain);
    }
}
