//! One measuring run per output: `calibrate run -o CAL.toml` holds an exclusive lock on
//! `CAL.toml.lock` from before it touches the readings (`CAL.ti3`, `CAL.native.ti3`, a
//! `--force` backup) until its calibration is written. A second run on the same output stops
//! at once with one line naming the holder; without the lock both would write the same
//! readings file and one run's readings would be lost, or the calibration fitted from one
//! run's readings would sit beside the other's.
//!
//! - The lock is the operating system's advisory file lock (`flock(2)` on Linux, through
//!   std's [`File::try_lock`]): it belongs to the open file, so it ends with the process however
//!   the process ends (exit, Ctrl-C, a panic, `SIGKILL`, a crash). Nothing a killed run leaves
//!   can block the next one.
//! - The file holds one line naming the holder (`pid N, started TIME`), which the refused run
//!   prints. A run that ends normally removes the file (while still holding the lock). A run
//!   that finds the file with a holder line but takes the lock knows that holder ended without
//!   releasing it (killed, or the machine went down) and says so.
//! - Removal races are closed the usual way: after taking the lock, a run checks that the path
//!   still names the file it locked (same device and inode); if the holder removed it in
//!   between, the run opens the new one and tries again.

use crate::error::{Error, Result};
use std::fs::{File, OpenOptions, TryLockError};
use std::io::{Read, Seek, SeekFrom, Write};
use std::os::unix::fs::MetadataExt;
use std::path::{Path, PathBuf};

/// The lock file of an output: `CAL.toml` → `CAL.toml.lock`.
pub fn lock_path(output: &Path) -> PathBuf {
    let mut s = output.as_os_str().to_os_string();
    s.push(".lock");
    PathBuf::from(s)
}

/// The most bytes of a holder line read back (a lock file is one short line).
const MAX_HOLDER: u64 = 256;

/// Times the lock is re-tried when its file was removed between opening and locking it.
const ATTEMPTS: usize = 8;

/// An exclusive lock on an output, held until dropped.
#[derive(Debug)]
pub struct RunLock {
    file: File,
    path: PathBuf,
}

/// The holder line in a lock file, if any (trimmed, control characters escaped).
fn holder(file: &mut File) -> Option<String> {
    let mut text = String::new();
    file.seek(SeekFrom::Start(0)).ok()?;
    file.take(MAX_HOLDER).read_to_string(&mut text).ok()?;
    let line = text.lines().next()?.trim();
    (!line.is_empty()).then(|| specpoly_formats::escape::one_line(line).into_owned())
}

/// Whether `file` is the file `path` names now.
fn still_there(file: &File, path: &Path) -> bool {
    match (file.metadata(), std::fs::metadata(path)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

impl RunLock {
    /// Takes the lock of `output` ([`lock_path`]) for this process, or fails at once with
    /// [`Error::Locked`] naming the run that holds it. `started` is written into the lock
    /// file. Returns the lock and a note when it was taken over from a run that ended
    /// without releasing it.
    pub fn acquire(output: &Path, started: &str) -> Result<(RunLock, Option<String>)> {
        let path = lock_path(output);
        for _ in 0..ATTEMPTS {
            let mut file = OpenOptions::new()
                .read(true)
                .write(true)
                .create(true)
                .truncate(false)
                .open(&path)
                .map_err(|e| Error::io(&path, e))?;
            match file.try_lock() {
                Ok(()) => {}
                Err(TryLockError::WouldBlock) => {
                    return Err(Error::Locked {
                        output: output.to_path_buf(),
                        lock: path.clone(),
                        holder: holder(&mut file).unwrap_or_else(|| "pid unknown".into()),
                    })
                }
                Err(TryLockError::Error(e)) => return Err(Error::io(&path, e)),
            }
            if !still_there(&file, &path) {
                // the holder finished and removed it after we opened it: lock the new one
                continue;
            }
            let stale = holder(&mut file);
            let line = format!("pid {}, started {started}\n", std::process::id());
            file.set_len(0)
                .and_then(|()| file.seek(SeekFrom::Start(0)))
                .and_then(|_| file.write_all(line.as_bytes()))
                .and_then(|()| file.flush())
                .map_err(|e| Error::io(&path, e))?;
            let note = stale.map(|h| {
                format!(
                    "{}: the run that held it ({h}) ended without releasing it (killed, or the machine went down); taken over",
                    path.display()
                )
            });
            return Ok((RunLock { file, path }, note));
        }
        Err(Error::io(
            &path,
            std::io::Error::other("the lock file kept being replaced; is another run starting?"),
        ))
    }

    /// The lock file.
    pub fn path(&self) -> &Path {
        &self.path
    }
}

impl Drop for RunLock {
    /// Removes the lock file while still holding the lock (a run that opened it meanwhile
    /// sees it gone and opens the next one), then releases the lock by closing the file.
    fn drop(&mut self) {
        if still_there(&self.file, &self.path) {
            let _ = std::fs::remove_file(&self.path);
        }
        let _ = self.file.unlock();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_second_lock_is_refused_naming_the_holder_and_free_after_release() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("c.toml");
        let (lock, note) = RunLock::acquire(&out, "T0").unwrap();
        assert!(note.is_none());
        assert_eq!(lock.path(), dir.path().join("c.toml.lock"));
        let e = RunLock::acquire(&out, "T1").unwrap_err().to_string();
        assert!(
            e.contains(&format!("pid {}, started T0", std::process::id())),
            "{e}"
        );
        drop(lock);
        assert!(!dir.path().join("c.toml.lock").exists());
        let (again, note) = RunLock::acquire(&out, "T2").unwrap();
        assert!(note.is_none());
        drop(again);
    }

    #[test]
    fn a_left_lock_file_without_a_holder_is_taken_over_with_a_note() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("c.toml");
        std::fs::write(lock_path(&out), "pid 4242, started T0\n").unwrap();
        let (lock, note) = RunLock::acquire(&out, "T1").unwrap();
        let note = note.unwrap();
        assert!(note.contains("pid 4242, started T0"), "{note}");
        assert!(note.contains("ended without releasing it"), "{note}");
        let text = std::fs::read_to_string(lock.path()).unwrap();
        assert_eq!(text, format!("pid {}, started T1\n", std::process::id()));
    }
}
