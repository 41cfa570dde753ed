//! The readings file of `calibrate run` (`CAL.ti3`) kept like a database transaction log:
//! a measurement, once taken, is never lost.
//!
//! - Every reading is written at once: the whole `.ti3` (all readings so far, in patch order)
//!   is rewritten through the project's atomic writer (temporary file, `fsync`, rename), so a
//!   run stopped at any instant — Ctrl-C, an instrument error, an unplugged port, `SIGKILL` in
//!   the middle of a write — leaves either the previous or the new complete file, never a torn
//!   one.
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
                let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
                let source = shown.to_string();
                let t = cgats::read_ti3(&text, &source).map_err(Error::ResumeUnreadable)?;
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
                Ok((
                    me,
                    Some(format!(
                        "resuming {shown}: {n} of {} patches measured, {} to go",
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

    /// Records the reading of patch `i` and rewrites the file atomically. A reading whose
    /// write fails is not kept: the session holds what the file holds.
    pub fn record(&mut self, i: usize, xyz: [f64; 3]) -> Result<()> {
        self.record_all(&[(i, xyz)])
    }

    /// Records several readings (patch index, XYZ) with one write; none of them is kept if the
    /// write fails.
    pub fn record_all(&mut self, r: &[(usize, [f64; 3])]) -> Result<()> {
        let before: Vec<Option<[f64; 3]>> = r.iter().map(|(i, _)| self.readings[*i]).collect();
        for (i, x) in r {
            self.readings[*i] = Some(*x);
        }
        let saved = self.save();
        if saved.is_err() {
            for ((i, _), b) in r.iter().zip(before).rev() {
                self.readings[*i] = b;
            }
        }
        saved
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
    fn fingerprint_follows_the_values() {
        let a = fingerprint(&[[0.0; 3], [1.0, 0.5, 0.25]]);
        assert_eq!(a, fingerprint(&[[0.0; 3], [1.0, 0.5, 0.25]]));
        assert_ne!(a, fingerprint(&[[0.0; 3], [1.0, 0.5, 0.26]]));
        assert_ne!(a, fingerprint(&[[1.0, 0.5, 0.25], [0.0; 3]]));
        assert!(a.starts_with("2 patches, fnv1a64 "), "{a}");
    }
}
