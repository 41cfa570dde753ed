//! Output files are written whole or not at all, and only where the user pointed:
//!
//! - `-` writes to stdout (refused when stdout was closed at start:
//!   [`crate::stdout::check_open`]);
//! - a FIFO, character device or socket (e.g. `/dev/stdout`, `/dev/null`, a named pipe) is
//!   written directly: it cannot be replaced, only written;
//! - a symlink is followed (the link stays, its target gets the bytes);
//! - a regular file (or a new one) gets its bytes through a temporary file created exclusively
//!   (`O_EXCL`, a random name, never following a planted link) in the target's folder, renamed
//!   over the target only after a complete, synced write: a failure leaves no partial file.
//!
//! Temporary files are `.NAME.XXXXXX.specpoly-tmp`; one a killed run left (unmodified for
//! [`STALE_AFTER`]) is removed by the next write to the same folder. The exclusive random temp
//! file is the `tempfile` crate's `NamedTempFile` (hand-writing `O_EXCL` + random names + cleanup
//! would repeat a well-kept crate).

use crate::{Error, Result};
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::time::Duration;

/// The suffix of our temporary files.
const SUFFIX: &str = ".specpoly-tmp";

/// A temporary file of ours untouched this long belongs to a run that was killed.
pub const STALE_AFTER: Duration = Duration::from_secs(600);

/// The most symlinks followed from an output path (as Linux's `ELOOP` limit).
const MAX_LINKS: usize = 40;

/// Writes `bytes` to `path` (see the module docs).
pub fn write(path: &Path, bytes: &[u8]) -> Result<()> {
    write_with(path, |w| w.write_all(bytes))
}

/// Writes through `f` to `path`: stdout for `-`, directly into a FIFO or device, else whole
/// or not at all through an exclusive temporary file and a rename.
pub fn write_with(
    path: &Path,
    f: impl FnOnce(&mut BufWriter<File>) -> std::io::Result<()>,
) -> Result<()> {
    if path == Path::new("-") {
        crate::stdout::check_open()?;
        return stream(stdout_file().map_err(|e| Error::io("stdout", e))?, f)
            .map_err(|e| Error::io("stdout", e));
    }
    let target = resolve_links(path)?;
    match std::fs::metadata(&target) {
        Ok(m) if m.is_dir() => Err(Error::OutputIsFolder {
            path: path.display().to_string(),
        }),
        Ok(m) if !m.is_file() => {
            let file = std::fs::OpenOptions::new()
                .write(true)
                .open(&target)
                .map_err(|e| Error::io(path, e))?;
            stream(file, f).map_err(|e| Error::io(path, e))
        }
        _ => replace(&target, f).map_err(|e| Error::io(path, e)),
    }
}

/// A `File` on a duplicate of the stdout descriptor (so the same writer type serves both).
fn stdout_file() -> std::io::Result<File> {
    use std::os::fd::AsFd;
    Ok(File::from(std::io::stdout().as_fd().try_clone_to_owned()?))
}

/// Writes into an open stream (stdout, FIFO, device) and flushes.
fn stream(
    file: File,
    f: impl FnOnce(&mut BufWriter<File>) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let mut w = BufWriter::new(file);
    f(&mut w)?;
    w.flush()
}

/// `path` with every symlink along its last component followed (a dangling link resolves to
/// where it points, so the file is created there).
fn resolve_links(path: &Path) -> Result<PathBuf> {
    let mut p = path.to_path_buf();
    for _ in 0..MAX_LINKS {
        match std::fs::symlink_metadata(&p) {
            Ok(m) if m.file_type().is_symlink() => {
                let to = std::fs::read_link(&p).map_err(|e| Error::io(path, e))?;
                p = match p.parent() {
                    Some(dir) if to.is_relative() => dir.join(to),
                    _ => to,
                };
            }
            _ => return Ok(p),
        }
    }
    Err(Error::TooManyLinks {
        path: path.display().to_string(),
        max: MAX_LINKS,
    })
}

/// Writes a regular file whole or not at all: exclusive temporary file, sync, rename.
fn replace(
    target: &Path,
    f: impl FnOnce(&mut BufWriter<File>) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let name = target
        .file_name()
        .ok_or_else(|| std::io::Error::other("not a file path"))?
        .to_string_lossy()
        .into_owned();
    remove_stale(&dir, &name);
    // a new file gets the usual 0666 less the umask; a replaced one keeps its permissions
    let permissions = match std::fs::metadata(target) {
        Ok(m) => m.permissions(),
        Err(_) => {
            use std::os::unix::fs::PermissionsExt;
            std::fs::Permissions::from_mode(0o666)
        }
    };
    let tmp = tempfile::Builder::new()
        .prefix(&format!(".{name}."))
        .suffix(SUFFIX)
        .permissions(permissions)
        .tempfile_in(&dir)?;
    // the path half deletes the temporary file when dropped on an error
    let (file, tmp_path) = tmp.into_parts();
    let mut w = BufWriter::new(file);
    f(&mut w)?;
    let file = w.into_inner().map_err(|e| e.into_error())?;
    file.sync_all()?;
    tmp_path.persist(target).map_err(|e| e.error)?;
    Ok(())
}

/// Removes our temporary files for `name` in `dir` that a killed run left behind.
fn remove_stale(dir: &Path, name: &str) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let prefix = format!(".{name}.");
    for e in entries.flatten() {
        let file_name = e.file_name();
        let n = file_name.to_string_lossy();
        if !(n.starts_with(&prefix) && n.ends_with(SUFFIX)) {
            continue;
        }
        let stale = e
            .metadata()
            .ok()
            .filter(|m| m.is_file())
            .and_then(|m| m.modified().ok())
            .and_then(|t| t.elapsed().ok())
            .is_some_and(|age| age >= STALE_AFTER);
        if stale {
            let _ = std::fs::remove_file(e.path());
        }
    }
}
