//! The readings file of `calibrate run` (`CAL.ti3`) kept like a database transaction log:
//! a measurement, once taken, is never lost.
//!
//! - Every reading is committed at once, in time linear in the number of readings:
//!   - the first write of a run writes the whole file through the project's atomic writer
//!     (temporary file, `fsync`, rename) in the log form ([`cgats::ti3_log_head`]: XYZ in
//!     cd/m² as read, no `NUMBER_OF_SETS`), with every reading so far and `END_DATA`;
//!   - every later reading is appended in place: one `write` of its row followed by
//!     `END_DATA` over the old `END_DATA`, then `fdatasync`. A process stopped at any instant
//!     (Ctrl-C, an instrument error, `SIGKILL`) leaves the file before or after that write,
//!     both complete `.ti3` files;
//!   - when measuring ends (done, failed or interrupted) the file is rewritten once,
//!     atomically, in ArgyllCMS's layout ([`cgats::write_ti3`]: patch order, normalised to
//!     the white's `Y = 100` with `LUMINANCE_XYZ_CDM2`, `NUMBER_OF_SETS`).
//!
//!   A write the system cut short (a full disk, a crash of the machine) can leave a torn last
//!   line and no `END_DATA`. A failed append is undone at once (the file is cut back to its
//!   last whole row); what a crash left is repaired by `--resume`, which ignores the torn
//!   line with a warning ([`cgats::close_open_log`]) and measures that patch again.
//! - The file names its patch set: the keyword `SPECPOLY_PATCH_SET` holds the number of
//!   patches and a 64-bit FNV-1a hash of their device values (as written, 0–100 with five
//!   decimals).
//! - An existing `.ti3` is never overwritten silently. [`Existing::Refuse`] (the default) stops
//!   with a message; [`Existing::Resume`] reads it back, checks that it was measured with the
//!   same patch set (refuses otherwise) and measures only the patches it lacks;
//!   [`Existing::Force`] first renames it to the first free `CAL.ti3.1`, `CAL.ti3.2`, ….
//!
//! FNV-1a (Fowler–Noll–Vo, 64-bit offset basis and prime) is written out here: eight lines,
//! and a checksum crate would pin a hash this file format must keep stable anyway.

use crate::error::{Error, Result};
use crate::patches::Patch;
use specpoly_formats::cgats::{self, Ti3Info};
use specpoly_formats::measurement::Measurement;
use std::fs::File;
use std::os::unix::fs::FileExt;
use std::path::{Path, PathBuf};

/// What to do when the `.ti3` already exists.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Existing {
    /// Stop with a message.
    Refuse,
    /// Measure only the patches it lacks (same patch set only).
    Resume,
    /// Keep it as a numbered backup and start over.
    Force,
}

/// The keyword naming the patch set.
pub const PATCH_SET_KEYWORD: &str = "SPECPOLY_PATCH_SET";

/// A device value as written in a `.ti3` (percent, five decimals), as an integer.
fn grid(v: f64) -> i64 {
    (v * 100.0 * 1e5).round() as i64
}

/// `N patches, fnv1a64 HEX`: the patch set's fingerprint.
pub fn fingerprint(devices: &[[f64; 3]]) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for d in devices {
        for v in d {
            for b in grid(*v).to_le_bytes() {
                h ^= u64::from(b);
                h = h.wrapping_mul(0x0000_0100_0000_01b3);
            }
        }
    }
    format!("{} patches, fnv1a64 {h:016x}", devices.len())
}

/// The SHA-256 of `bytes`, lower-case hex (FIPS 180-4, the `sha2` crate): what a calibration
/// records of the readings file it was fitted from (`sha256sum FILE` prints the same).
pub fn sha256_hex(bytes: &[u8]) -> String {
    use sha2::{Digest, Sha256};
    Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// [`sha256_hex`] of the file at `path` (a regular file, read whole: at most
/// [`specpoly_formats::read::MAX_INPUT_BYTES`]).
pub fn sha256_file(path: &Path) -> Result<String> {
    Ok(sha256_hex(&specpoly_formats::read::bytes(path)?))
}

/// The first free backup name `PATH.1`, `PATH.2`, ….
pub fn backup_name(path: &Path) -> PathBuf {
    let mut n = 1;
    loop {
        let mut s = path.as_os_str().to_os_string();
        s.push(format!(".{n}"));
        let p = PathBuf::from(s);
        if !p.exists() {
            return p;
        }
        n += 1;
    }
}

/// A measuring session: the patch set, the readings taken (old and new) and their file.
#[derive(Debug)]
pub struct Session {
    path: PathBuf,
    devices: Vec<[f64; 3]>,
    readings: Vec<Option<[f64; 3]>>,
    info: Ti3Info,
    log: Option<Log>,
}

/// The readings file open for appending (see the module docs).
#[derive(Debug)]
struct Log {
    file: File,
    /// Where `END_DATA` starts: the next row goes here.
    end: u64,
    /// Rows in the file (the next row's `SAMPLE_ID` is one more).
    rows: usize,
}

impl Log {
    /// Appends `rows` (whole lines) before `END_DATA` and syncs; on failure, cuts the file
    /// back to its last whole row and `END_DATA` (as far as the system lets it) and keeps the
    /// old end.
    fn append(&mut self, rows: &str) -> std::io::Result<()> {
        let mut bytes = Vec::with_capacity(rows.len() + cgats::END_DATA.len());
        bytes.extend_from_slice(rows.as_bytes());
        bytes.extend_from_slice(cgats::END_DATA.as_bytes());
        let written = self
            .file
            .write_all_at(&bytes, self.end)
            .and_then(|()| self.file.sync_data());
        if let Err(e) = written {
            let end = cgats::END_DATA.as_bytes();
            let _ = self
                .file
                .set_len(self.end)
                .and_then(|()| self.file.write_all_at(end, self.end))
                .and_then(|()| self.file.sync_data());
            return Err(e);
        }
        self.end += rows.len() as u64;
        Ok(())
    }
}

impl Session {
    /// Opens the session for `patches` writing to `path`; `existing` says what to do with a
    /// `.ti3` already there. Returns the session and a note for the user (a backup made, the
    /// readings resumed), if any.
    pub fn open(
        path: &Path,
        patches: &[Patch],
        existing: Existing,
        mut info: Ti3Info,
    ) -> Result<(Self, Option<String>)> {
        let devices: Vec<[f64; 3]> = patches.iter().map(|p| p.device).collect();
        let fp = fingerprint(&devices);
        info.keywords
            .retain(|(k, _)| k.as_str() != PATCH_SET_KEYWORD);
        info.keywords
            .push((PATCH_SET_KEYWORD.to_string(), fp.clone()));
        let mut me = Self {
            path: path.to_path_buf(),
            readings: vec![None; devices.len()],
            devices,
            info,
            log: None,
        };
        if !path.exists() {
            let note = (existing == Existing::Resume)
                .then(|| format!("nothing to resume: {} does not exist yet", path.display()));
            return Ok((me, note));
        }
        let shown = path.display();
        let file = || path.to_path_buf();
        match existing {
            Existing::Refuse => Err(Error::ReadingsExist {
                file: file(),
                backup: backup_name(path),
            }),
            Existing::Force => {
                let b = backup_name(path);
                std::fs::rename(path, &b).map_err(|e| Error::io(path, e))?;
                Ok((me, Some(format!("kept the old {shown} as {}", b.display()))))
            }
            Existing::Resume => {
                let text = specpoly_formats::read::text_or_latin1(path)
                    .map_err(Error::ResumeUnreadable)?;
                let source = shown.to_string();
                let mut torn = None;
                let t = match cgats::read_ti3(&text, &source) {
                    Ok(t) => t,
                    Err(e) => {
                        // a log a killed run left open: close it, without a torn last line
                        let (closed, cut) = cgats::close_open_log(&text, &source)
                            .ok_or(Error::ResumeUnreadable(e))?;
                        torn = cut;
                        cgats::read_ti3(&closed, &source).map_err(Error::ResumeUnreadable)?
                    }
                };
                match t.keyword(PATCH_SET_KEYWORD) {
                    Some(v) if v == fp => {}
                    Some(v) => {
                        return Err(Error::ResumeOtherSet {
                            file: file(),
                            found: v.to_string(),
                            expected: fp,
                        })
                    }
                    None => {
                        return Err(Error::ResumeNoPatchSet {
                            file: file(),
                            keyword: PATCH_SET_KEYWORD,
                        })
                    }
                }
                let (m, absolute) = t.best_units();
                if !absolute {
                    return Err(Error::ResumeRelative { file: file() });
                }
                for (m, line) in m.iter().zip(&t.lines) {
                    let g = m.device.map(grid);
                    let slot = (0..me.devices.len()).find(|&i| {
                        me.readings[i].is_none()
                            && me.devices[i]
                                .iter()
                                .zip(&g)
                                .all(|(d, g)| (grid(*d) - g).abs() <= 1)
                    });
                    match slot {
                        Some(i) => me.readings[i] = Some(m.xyz),
                        None => {
                            return Err(Error::ResumeStrayPatch {
                                file: file(),
                                line: *line,
                                rgb: m.device.map(|v| v * 100.0),
                            })
                        }
                    }
                }
                let n = me.taken();
                let torn = torn.map_or(String::new(), |l| {
                    let l: String = l.chars().take(60).collect();
                    format!(
                        " (its last line `{l}` was cut off when the run writing it was stopped: ignored, that patch is measured again)"
                    )
                });
                Ok((
                    me,
                    Some(format!(
                        "resuming {shown}: {n} of {} patches measured, {} to go{torn}",
                        patches.len(),
                        patches.len() - n
                    )),
                ))
            }
        }
    }

    /// Sets the instrument named in the file.
    pub fn set_instrument(&mut self, name: String) {
        self.info.instrument = Some(name);
    }

    /// The file's metadata.
    pub fn info(&self) -> &Ti3Info {
        &self.info
    }

    /// The indices of the patches not measured yet, in order.
    pub fn missing(&self) -> Vec<usize> {
        (0..self.readings.len())
            .filter(|&i| self.readings[i].is_none())
            .collect()
    }

    /// How many patches are measured.
    pub fn taken(&self) -> usize {
        self.readings.iter().filter(|r| r.is_some()).count()
    }

    /// `error`, stopping a run of this session, with what the session kept: how many readings
    /// are in its file and how many patches `--resume` would measure ([`Error::Stopped`], the
    /// one place the "readings kept" message comes from).
    pub fn stopped(&self, error: Error) -> Error {
        let kept = self.taken();
        Error::Stopped {
            source: Box::new(error),
            kept,
            file: self.path.clone(),
            remaining: self.readings.len() - kept,
        }
    }

    /// Records the reading of patch `i` and commits it to the file (see the module docs). A
    /// reading whose write fails is not kept: the session holds what the file holds.
    pub fn record(&mut self, i: usize, xyz: [f64; 3]) -> Result<()> {
        self.record_all(&[(i, xyz)])
    }

    /// Records several readings (patch index, XYZ) with one write; none of them is kept if the
    /// write fails.
    pub fn record_all(&mut self, r: &[(usize, [f64; 3])]) -> Result<()> {
        let Some(log) = self.log.as_mut() else {
            // the run's first write: the whole file, atomically, then open it for appending
            let before: Vec<Option<[f64; 3]>> = r.iter().map(|(i, _)| self.readings[*i]).collect();
            for (i, x) in r {
                self.readings[*i] = Some(*x);
            }
            let opened = self.open_log();
            if opened.is_err() {
                for ((i, _), b) in r.iter().zip(before).rev() {
                    self.readings[*i] = b;
                }
            }
            return opened;
        };
        let mut rows = String::new();
        for (k, (i, x)) in r.iter().enumerate() {
            let m = Measurement {
                device: self.devices[*i],
                xyz: *x,
            };
            rows.push_str(&cgats::ti3_log_row(log.rows + k + 1, &m)?);
        }
        log.append(&rows).map_err(|e| Error::io(&self.path, e))?;
        log.rows += r.len();
        for (i, x) in r {
            self.readings[*i] = Some(*x);
        }
        Ok(())
    }

    /// Writes the readings so far as the log ([`cgats::ti3_log_head`], atomically) and opens it
    /// for appending.
    fn open_log(&mut self) -> Result<()> {
        let m = self.measurements();
        let mut text = cgats::ti3_log_head(&self.info);
        for (k, m) in m.iter().enumerate() {
            text.push_str(&cgats::ti3_log_row(k + 1, m)?);
        }
        let end = text.len() as u64;
        text.push_str(cgats::END_DATA);
        specpoly_formats::atomic::write(&self.path, text.as_bytes())?;
        let file = std::fs::OpenOptions::new()
            .write(true)
            .open(&self.path)
            .map_err(|e| Error::io(&self.path, e))?;
        self.log = Some(Log {
            file,
            end,
            rows: m.len(),
        });
        Ok(())
    }

    /// Ends the run's writing: rewrites the file once in ArgyllCMS's layout (patch order,
    /// normalised to the white; atomically) and closes the log. Nothing to do if nothing was
    /// written.
    pub fn close(&mut self) -> Result<()> {
        if self.log.take().is_none() {
            return Ok(());
        }
        self.save()
    }

    /// The readings taken, in patch order.
    pub fn measurements(&self) -> Vec<Measurement> {
        self.devices
            .iter()
            .zip(&self.readings)
            .filter_map(|(d, r)| r.map(|xyz| Measurement { device: *d, xyz }))
            .collect()
    }

    /// The reading of every patch, if all are measured.
    pub fn complete(&self) -> Option<Vec<[f64; 3]>> {
        self.readings.iter().copied().collect()
    }

    fn save(&self) -> Result<()> {
        Ok(specpoly_formats::atomic::write(
            &self.path,
            cgats::write_ti3(&self.measurements(), &self.info)?.as_bytes(),
        )?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn info() -> Ti3Info {
        Ti3Info {
            absolute: true,
            ..Ti3Info::default()
        }
    }

    fn set(n: usize) -> Vec<Patch> {
        let devices: Vec<[f64; 3]> = (0..n).map(|k| [k as f64 / n as f64; 3]).collect();
        crate::patches::from_devices(&devices).unwrap()
    }

    /// The readings in the file at `path`.
    fn on_disk(path: &Path) -> usize {
        let text = std::fs::read_to_string(path).unwrap();
        cgats::read_ti3(&text, "t").unwrap().measurements.len()
    }

    #[test]
    fn a_reading_whose_write_fails_is_not_counted_as_kept() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("c.ti3");
        let (mut s, _) = Session::open(&path, &set(4), Existing::Refuse, info()).unwrap();
        s.record(0, [1.0, 2.0, 3.0]).unwrap();
        s.record(1, [2.0, 3.0, 4.0]).unwrap();
        // a reading the file cannot take (the .ti3 writer refuses non-finite values)
        let e = s.record(2, [f64::INFINITY, 1.0, 1.0]).unwrap_err();
        assert_eq!(s.taken(), 2);
        assert_eq!(on_disk(&path), 2);
        assert_eq!(s.missing(), [2, 3]);
        let stopped = s.stopped(e).to_string();
        assert!(stopped.contains("2 readings kept"), "{stopped}");
        // a batch fails whole
        let e = s.record_all(&[(2, [1.0; 3]), (3, [f64::NAN; 3])]);
        assert!(e.is_err());
        assert_eq!(s.taken(), 2);
        assert_eq!(on_disk(&path), 2);
    }

    #[test]
    fn readings_are_appended_in_place_and_the_closed_file_has_argylls_layout() {
        use std::os::unix::fs::MetadataExt;
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("c.ti3");
        let patches = crate::patches::from_devices(&[[0.0; 3], [1.0; 3], [0.5, 0.0, 0.0]]).unwrap();
        let (mut s, _) = Session::open(&path, &patches, Existing::Refuse, info()).unwrap();
        let readings = [[0.2, 0.3, 0.4], [95.0, 100.0, 108.0], [20.0, 10.0, 1.0]];
        s.record(0, readings[0]).unwrap();
        let inode = std::fs::metadata(&path).unwrap().ino();
        let mut before = std::fs::read_to_string(&path).unwrap();
        for (i, x) in readings.iter().enumerate().skip(1) {
            s.record(i, *x).unwrap();
            // the same file, grown: what was there stays, less its END_DATA
            assert_eq!(std::fs::metadata(&path).unwrap().ino(), inode);
            let now = std::fs::read_to_string(&path).unwrap();
            let kept = before.strip_suffix("END_DATA\n").unwrap();
            assert!(now.starts_with(kept), "{before}\n---\n{now}");
            // a whole .ti3 after every reading, in cd/m² as read
            let t = cgats::read_ti3(&now, "c.ti3").unwrap();
            assert_eq!(t.measurements.len(), i + 1);
            assert!(!t.normalized);
            assert_eq!(t.measurements[i].xyz, *x);
            before = now;
        }
        s.close().unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(text.contains("NUMBER_OF_SETS 3\n"), "{text}");
        let t = cgats::read_ti3(&text, "c.ti3").unwrap();
        assert!(t.normalized);
        assert_eq!(t.white_cdm2, Some(readings[1]));
        let (m, absolute) = t.best_units();
        assert!(absolute);
        for (m, x) in m.iter().zip(&readings) {
            for k in 0..3 {
                assert!((m.xyz[k] - x[k]).abs() < 1e-6, "{m:?} vs {x:?}");
            }
        }
    }

    #[test]
    fn resume_ignores_a_torn_last_line_and_measures_that_patch_again() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("c.ti3");
        let patches = set(5);
        let (mut s, _) = Session::open(&path, &patches, Existing::Refuse, info()).unwrap();
        for i in 0..3 {
            s.record(i, [1.0 + i as f64; 3]).unwrap();
        }
        // the machine went down in the middle of appending the fourth row: the first bytes of
        // the row over the old END_DATA, with or without the rest of END_DATA after them
        let whole = std::fs::read_to_string(&path).unwrap();
        let head = whole.strip_suffix("END_DATA\n").unwrap();
        drop(s);
        for torn in ["4 60.00000 60.0", "4 60.0DATA\n"] {
            std::fs::write(&path, format!("{head}{torn}")).unwrap();
            let (mut s, note) = Session::open(&path, &patches, Existing::Resume, info()).unwrap();
            let note = note.unwrap();
            assert!(note.contains("3 of 5 patches measured"), "{note}");
            assert!(note.contains("was cut off"), "{note}");
            assert!(note.contains(torn.trim_end()), "{note}");
            assert_eq!(s.missing(), [3, 4]);
            s.record(3, [4.0; 3]).unwrap();
            s.record(4, [5.0; 3]).unwrap();
            s.close().unwrap();
            let t = cgats::read_ti3(&std::fs::read_to_string(&path).unwrap(), "c").unwrap();
            let (m, _) = t.best_units();
            let y: Vec<f64> = m.iter().map(|m| (m.xyz[1] * 1e6).round() / 1e6).collect();
            assert_eq!(y, [1.0, 2.0, 3.0, 4.0, 5.0]);
        }
    }

    #[test]
    fn fingerprint_follows_the_values() {
        let a = fingerprint(&[[0.0; 3], [1.0, 0.5, 0.25]]);
        assert_eq!(a, fingerprint(&[[0.0; 3], [1.0, 0.5, 0.25]]));
        assert_ne!(a, fingerprint(&[[0.0; 3], [1.0, 0.5, 0.26]]));
        assert_ne!(a, fingerprint(&[[1.0, 0.5, 0.25], [0.0; 3]]));
        assert!(a.starts_with("2 patches, fnv1a64 "), "{a}");
    }
}
