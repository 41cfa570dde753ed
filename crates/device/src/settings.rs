//! The controller's settings as one versioned flash record: calibration (primaries'
//! chromaticities and luminances), the three transfer curves, the gamut map and the observer.
//!
//! The multi-channel mixer's settings are a second record of their own ([`crate::mix`], map
//! key 2), so this format stays 1 and the store's work buffer, sized by this record, does not
//! grow.
//!
//! Record format [`FORMAT`] = 1, little-endian, at most [`RECORD_MAX`] bytes:
//!
//! | bytes | field |
//! |---|---|
//! | 1 | format version (`1`) |
//! | 9 × 4 | `x y Y` of red, green, blue (f32) |
//! | 3 × (1 + …) | per channel a curve tag: `0` linear, `1` sRGB, `2` gamma + f32 γ, `3` table + n (u8) + n × f32 |
//! | 1 | gamut map: `0` clip, `1` desaturate |
//! | 1 | observer: `0` CIE 1931, `1` CIE 1964 |
//!
//! [`read`] checks every field with the same limits as the protocol's parser (`cal`, `trc`
//! ranges; tables through [`Transfer::table`]); anything else is a [`RecordError`], so a record
//! of another format, or bytes that are not a record, are never applied. The record is written
//! from a borrowed [`Record`] and read field by field into the controller's own storage: no
//! copy of the (up to 3 × 64-point) curves on the stack. Integrity against
//! interrupted writes and bit errors is the storage's (`sequential-storage`: CRC-32 per item).

use specpoly_core::{display::TABLE_MAX, GamutMap, Observer, Transfer};

/// The record format written by this firmware.
pub const FORMAT: u8 = 1;

/// Largest record: three 64-point tables.
pub const RECORD_MAX: usize = 1 + 9 * 4 + 3 * (2 + TABLE_MAX * 4) + 2;

/// The settings a record holds, borrowed from the controller to be written
/// ([`crate::Controller::record`]): the curves are not copied.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Record<'a> {
    /// `[x, y]` of red, green, blue at full drive.
    pub xy: [[f32; 2]; 3],
    /// Luminance `Y` of each primary at full drive.
    pub luminance: [f32; 3],
    /// Per-channel transfer curves.
    pub trc: &'a [Transfer; 3],
    /// The gamut mapping.
    pub map: GamutMap,
    /// The observer for reflectances.
    pub observer: Observer,
}

/// A record's fields other than its curves, as [`read`] returns them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Header {
    /// `[x, y]` of red, green, blue at full drive.
    pub xy: [[f32; 2]; 3],
    /// Luminance `Y` of each primary at full drive.
    pub luminance: [f32; 3],
    /// The gamut mapping.
    pub map: GamutMap,
    /// The observer for reflectances.
    pub observer: Observer,
}

/// Why bytes are not a record of this firmware.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RecordError {
    /// Another format version (an older or newer firmware wrote it).
    Format(u8),
    /// Too short, too long, or a field out of range: not a record.
    Invalid,
}

impl Record<'_> {
    /// Writes the record into `out`; returns its length, or `None` when `out` is too short
    /// ([`RECORD_MAX`] bytes always suffice).
    pub fn encode(&self, out: &mut [u8]) -> Option<usize> {
        let mut w = Writer { out, at: 0 };
        w.u8(FORMAT);
        for i in 0..3 {
            w.f32(self.xy[i][0]);
            w.f32(self.xy[i][1]);
            w.f32(self.luminance[i]);
        }
        for t in self.trc {
            match t {
                Transfer::Linear => w.u8(0),
                Transfer::Srgb => w.u8(1),
                Transfer::Gamma(g) => {
                    w.u8(2);
                    w.f32(*g);
                }
                Transfer::Table(v) => {
                    w.u8(3);
                    w.u8(v.len() as u8);
                    for x in v {
                        w.f32(*x);
                    }
                }
            }
        }
        w.u8(match self.map {
            GamutMap::Clip => 0,
            GamutMap::Desaturate => 1,
        });
        // the controller takes only the observers it carries moments for (1931, 1964)
        w.u8(match self.observer {
            Observer::Cie1964 => 1,
            _ => 0,
        });
        (w.at <= w.out.len()).then_some(w.at)
    }
}

/// Reads a record of format [`FORMAT`] written by [`Record::encode`], checking every field.
/// With `curves`, its three curves are stored there (only curve by curve, so on an error some
/// may have been replaced: pass storage to be discarded, or check first with `None`).
pub fn read(bytes: &[u8], mut curves: Option<&mut [Transfer; 3]>) -> Result<Header, RecordError> {
    let mut r = Reader { bytes, at: 0 };
    let format = r.u8()?;
    if format != FORMAT {
        return Err(RecordError::Format(format));
    }
    let mut xy = [[0.0; 2]; 3];
    let mut luminance = [0.0; 3];
    for i in 0..3 {
        let (x, y, big_y) = (r.f32()?, r.f32()?, r.f32()?);
        // the `cal` command's ranges
        let ok =
            (0.0..=1.0).contains(&x) && y > 0.0 && y <= 1.0 && big_y > 0.0 && big_y.is_finite();
        if !ok {
            return Err(RecordError::Invalid);
        }
        xy[i] = [x, y];
        luminance[i] = big_y;
    }
    for i in 0..3 {
        let t = match r.u8()? {
            0 => Transfer::Linear,
            1 => Transfer::Srgb,
            2 => {
                let g = r.f32()?;
                if !(0.1..=10.0).contains(&g) {
                    return Err(RecordError::Invalid);
                }
                Transfer::Gamma(g)
            }
            3 => {
                let n = r.u8()? as usize;
                let values = r
                    .bytes
                    .get(r.at..r.at + 4 * n)
                    .ok_or(RecordError::Invalid)?;
                r.at += 4 * n;
                let floats = values
                    .chunks_exact(4)
                    .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]));
                // checked where it lies, then read straight into the controller's curve: no
                // 64-point copy on the stack (the deepest path is a `load` of such a record)
                Transfer::check_table(floats.clone()).map_err(|_| RecordError::Invalid)?;
                if let Some(c) = curves.as_deref_mut() {
                    c[i] = Transfer::Table(heapless::Vec::new());
                    if let Transfer::Table(v) = &mut c[i] {
                        for x in floats {
                            // at most TABLE_MAX, checked above
                            let _ = v.push(x);
                        }
                    }
                }
                continue;
            }
            _ => return Err(RecordError::Invalid),
        };
        if let Some(c) = curves.as_deref_mut() {
            c[i] = t;
        }
    }
    let map = match r.u8()? {
        0 => GamutMap::Clip,
        1 => GamutMap::Desaturate,
        _ => return Err(RecordError::Invalid),
    };
    let observer = match r.u8()? {
        0 => Observer::Cie1931,
        1 => Observer::Cie1964,
        _ => return Err(RecordError::Invalid),
    };
    if r.at != bytes.len() {
        return Err(RecordError::Invalid);
    }
    Ok(Header {
        xy,
        luminance,
        map,
        observer,
    })
}

/// Counts every byte; stores those that fit (the caller checks the count).
struct Writer<'a> {
    out: &'a mut [u8],
    at: usize,
}

impl Writer<'_> {
    fn u8(&mut self, v: u8) {
        if let Some(b) = self.out.get_mut(self.at) {
            *b = v;
        }
        self.at += 1;
    }
    fn f32(&mut self, v: f32) {
        for b in v.to_le_bytes() {
            self.u8(b);
        }
    }
}

struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    fn u8(&mut self) -> Result<u8, RecordError> {
        let b = *self.bytes.get(self.at).ok_or(RecordError::Invalid)?;
        self.at += 1;
        Ok(b)
    }
    fn f32(&mut self) -> Result<f32, RecordError> {
        let mut b = [0u8; 4];
        for x in b.iter_mut() {
            *x = self.u8()?;
        }
        Ok(f32::from_le_bytes(b))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn curves() -> [Transfer; 3] {
        let table: [f32; TABLE_MAX] = core::array::from_fn(|i| (i as f32 / 63.0).powf(2.2));
        [
            Transfer::table(&table).unwrap(),
            Transfer::Gamma(2.2),
            Transfer::Srgb,
        ]
    }

    fn record(trc: &[Transfer; 3]) -> Record<'_> {
        Record {
            xy: [[0.7, 0.29], [0.17, 0.7], [0.135, 0.04]],
            luminance: [2.5, 7.25, 1.0],
            trc,
            map: GamutMap::Desaturate,
            observer: Observer::Cie1964,
        }
    }

    fn header(r: &Record) -> Header {
        Header {
            xy: r.xy,
            luminance: r.luminance,
            map: r.map,
            observer: r.observer,
        }
    }

    #[test]
    fn a_record_reads_back_as_written() {
        let mut buf = [0u8; RECORD_MAX];
        let trc = curves();
        let r = record(&trc);
        let n = r.encode(&mut buf).unwrap();
        let mut back = [Transfer::Linear, Transfer::Linear, Transfer::Linear];
        assert_eq!(read(&buf[..n], None), Ok(header(&r)));
        assert_eq!(read(&buf[..n], Some(&mut back)), Ok(header(&r)));
        assert_eq!(back, trc);
        assert_eq!(r.encode(&mut buf[..n - 1]), None);
        let three: [Transfer; 3] = core::array::from_fn(|_| curves()[0].clone());
        assert_eq!(
            record(&three).encode(&mut buf),
            Some(RECORD_MAX),
            "the largest fills RECORD_MAX"
        );
    }

    #[test]
    fn other_formats_and_damaged_records_are_refused() {
        let mut buf = [0u8; RECORD_MAX];
        let trc = curves();
        let n = record(&trc).encode(&mut buf).unwrap();
        let mut old = buf;
        old[0] = 0;
        assert_eq!(read(&old[..n], None), Err(RecordError::Format(0)));
        assert_eq!(read(&buf[..n - 1], None), Err(RecordError::Invalid));
        assert_eq!(read(&buf[..0], None), Err(RecordError::Invalid));
        let mut long = [0u8; RECORD_MAX + 1];
        long[..n].copy_from_slice(&buf[..n]);
        assert_eq!(read(&long[..n + 1], None), Err(RecordError::Invalid));
        // a luminance of NaN (bytes ff ff ff ff) and an unknown curve tag
        let mut nan = buf;
        nan[9..13].copy_from_slice(&[0xff; 4]);
        assert_eq!(read(&nan[..n], None), Err(RecordError::Invalid));
        let mut tag = buf;
        tag[37] = 9;
        assert_eq!(read(&tag[..n], None), Err(RecordError::Invalid));
        // a table that decreases (its second point set above the third)
        let mut dip = buf;
        dip[43..47].copy_from_slice(&1.0f32.to_le_bytes());
        assert_eq!(read(&dip[..n], None), Err(RecordError::Invalid));
    }
}
