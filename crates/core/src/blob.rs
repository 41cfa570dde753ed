//! The calibration blob: a display's model (Cowan's: primaries, black, a transfer curve per
//! channel; [`Display`]) as bytes, versioned and checksummed, for firmware that reads its
//! calibration from flash (the C library's `sp_calibration_load`; the host writes it with
//! `specpoly calibrate export --format c-blob`).
//!
//! Version 1, all fields little-endian:
//!
//! | Offset | Bytes | Field |
//! |---|---|---|
//! | 0 | 4 | magic `SPCB` |
//! | 4 | 2 | version, 1 |
//! | 6 | 2 | flags, 0 |
//! | 8 | 4 | length of the whole blob in bytes, checksum included |
//! | 12 | 24 | the primaries' CIE 1931 `x, y` (red, green, blue), f32 |
//! | 36 | 12 | the primaries' luminances at full drive, f32 |
//! | 48 | 12 | the black level's X, Y, Z, f32 |
//! | 60 | … | per channel: kind (u32: 0 linear, 1 sRGB, 2 power law, 3 table), points `n` (u32: the table's, else 0), then the exponent (f32) for a power law or `n` f32 for a table |
//! | length − 4 | 4 | CRC-32 of every byte before it (IEEE 802.3, reflected polynomial `0xEDB88320`, as zlib's `crc32`) |
//!
//! [`read`] never reads past the slice it is given, checks the magic, version and flags
//! ([`Error::BlobVersion`]), the length ([`Error::BlobTruncated`]; bytes after the blob are
//! allowed: a flash region larger than it), then the checksum ([`Error::BlobChecksum`]) before
//! it parses a field, and builds the display as [`Display::from_primaries`] does.

use crate::display::TABLE_MAX;
use crate::{Display, Error, Transfer, Xyz};

/// What a blob holds: the arguments of [`Display::from_primaries`].
#[derive(Clone, Debug, PartialEq)]
pub struct Parts {
    /// The primaries' CIE 1931 `[x, y]`, red, green, blue.
    pub primaries: [[f32; 2]; 3],
    /// Their luminances at full drive.
    pub luminance: [f32; 3],
    /// The black level.
    pub black: Xyz,
    /// Each channel's curve.
    pub transfer: [Transfer; 3],
}

impl Parts {
    /// The fields of `display` (its primaries as [`Display::primaries`] gives them back from
    /// its matrix).
    pub fn of(display: &Display) -> Self {
        let (primaries, luminance) = display.primaries();
        Self {
            primaries,
            luminance,
            black: display.black(),
            transfer: display.transfer().clone(),
        }
    }

    /// The display: [`Display::from_primaries`], once each primary's luminance is positive (an
    /// emitted light: [`Error::Negative`] with the field's index, 6–8, for one below zero,
    /// [`Error::Singular`] for zero). A blob of a negative luminance would load and not write
    /// back (its primaries, recovered from the matrix, are singular).
    pub fn display(self) -> Result<Display, Error> {
        for (i, &l) in self.luminance.iter().enumerate() {
            if !l.is_finite() {
                return Err(Error::NonFinite(6 + i));
            }
            if l < 0.0 {
                return Err(Error::Negative(6 + i));
            }
            if l == 0.0 {
                return Err(Error::Singular);
            }
        }
        Display::from_primaries(self.primaries, self.luminance, self.black, self.transfer)
    }
}

/// The blob's first four bytes.
pub const MAGIC: [u8; 4] = *b"SPCB";
/// The version [`write`] writes and [`read`] reads.
pub const VERSION: u16 = 1;
/// Bytes of the header (magic, version, flags, length).
pub const HEADER_BYTES: usize = 12;
/// The largest blob: three tables of [`TABLE_MAX`] points.
pub const MAX_BYTES: usize = HEADER_BYTES + 48 + 3 * (8 + 4 * TABLE_MAX) + 4;

/// CRC-32 (IEEE 802.3; reflected, initial and final XOR `0xFFFFFFFF`), bit by bit: no table
/// in flash, ≈ 8 shifts per byte, once per load.
pub fn crc32(bytes: &[u8]) -> u32 {
    let mut c = 0xFFFF_FFFFu32;
    for b in bytes {
        c ^= *b as u32;
        for _ in 0..8 {
            c = (c >> 1) ^ (0xEDB8_8320 & (c & 1).wrapping_neg());
        }
    }
    !c
}

/// A writer over a caller's buffer.
struct Out<'a> {
    buf: &'a mut [u8],
    at: usize,
}

impl Out<'_> {
    fn bytes(&mut self, b: &[u8]) -> Result<(), Error> {
        let end = self.at + b.len();
        self.buf
            .get_mut(self.at..end)
            .ok_or(Error::Capacity)?
            .copy_from_slice(b);
        self.at = end;
        Ok(())
    }
    fn u32(&mut self, v: u32) -> Result<(), Error> {
        self.bytes(&v.to_le_bytes())
    }
    fn f32(&mut self, v: f32) -> Result<(), Error> {
        self.bytes(&v.to_le_bytes())
    }
}

/// Writes `display` as a blob into `out` (its [`Parts::of`]); returns its length
/// (≤ [`MAX_BYTES`]). [`Error::Capacity`] when `out` is too short.
pub fn write(display: &Display, out: &mut [u8]) -> Result<usize, Error> {
    write_parts(&Parts::of(display), out)
}

/// Writes `parts` as a blob into `out`; returns its length (≤ [`MAX_BYTES`]).
/// [`Error::Capacity`] when `out` is too short.
pub fn write_parts(parts: &Parts, out: &mut [u8]) -> Result<usize, Error> {
    let mut o = Out { buf: out, at: 0 };
    o.bytes(&MAGIC)?;
    o.bytes(&VERSION.to_le_bytes())?;
    o.bytes(&0u16.to_le_bytes())?;
    o.u32(0)?; // the length, set below
    for v in parts
        .primaries
        .as_flattened()
        .iter()
        .chain(&parts.luminance)
    {
        o.f32(*v)?;
    }
    let k = parts.black;
    for v in [k.x, k.y, k.z] {
        o.f32(v)?;
    }
    for t in &parts.transfer {
        let (kind, values): (u32, &[f32]) = match t {
            Transfer::Linear => (0, &[]),
            Transfer::Srgb => (1, &[]),
            Transfer::Gamma(g) => (2, core::slice::from_ref(g)),
            Transfer::Table(v) => (3, v),
        };
        o.u32(kind)?;
        o.u32(if kind == 3 { values.len() as u32 } else { 0 })?;
        for x in values {
            o.f32(*x)?;
        }
    }
    let len = o.at + 4;
    o.buf
        .get_mut(8..12)
        .ok_or(Error::Capacity)?
        .copy_from_slice(&(len as u32).to_le_bytes());
    let crc = crc32(&o.buf[..o.at]);
    o.u32(crc)?;
    Ok(len)
}

/// A reader over the checked blob.
struct In<'a> {
    buf: &'a [u8],
    at: usize,
}

impl In<'_> {
    fn word(&mut self) -> Result<[u8; 4], Error> {
        let w = self
            .buf
            .get(self.at..self.at + 4)
            .ok_or(Error::BlobTruncated)?;
        self.at += 4;
        let mut b = [0u8; 4];
        b.copy_from_slice(w);
        Ok(b)
    }
    fn u32(&mut self) -> Result<u32, Error> {
        Ok(u32::from_le_bytes(self.word()?))
    }
    fn f32(&mut self) -> Result<f32, Error> {
        Ok(f32::from_le_bytes(self.word()?))
    }
}

/// The display a blob holds: [`parts`], then [`Parts::display`] (whose errors are the core's:
/// [`Error::NonFinite`], [`Error::Singular`]).
pub fn read(bytes: &[u8]) -> Result<Display, Error> {
    parts(bytes)?.display()
}

/// The fields of a blob, checked as the module docs say; a curve the core refuses gives its
/// error ([`Error::NonFinite`], [`Error::NotIncreasing`], [`Error::Capacity`]).
pub fn parts(bytes: &[u8]) -> Result<Parts, Error> {
    if bytes.len() < 8 || bytes[..4] != MAGIC {
        return Err(if MAGIC.starts_with(&bytes[..bytes.len().min(4)]) {
            Error::BlobTruncated
        } else {
            Error::BlobVersion
        });
    }
    if bytes[4..8] != [VERSION as u8, 0, 0, 0] {
        return Err(Error::BlobVersion);
    }
    let mut header = In { buf: bytes, at: 8 };
    let len = header.u32()? as usize;
    if len > bytes.len() {
        return Err(Error::BlobTruncated);
    }
    if !(HEADER_BYTES + 4..=MAX_BYTES).contains(&len) {
        return Err(Error::BlobVersion);
    }
    let body = &bytes[..len - 4];
    let mut crc = In {
        buf: bytes,
        at: len - 4,
    };
    if crc.u32()? != crc32(body) {
        return Err(Error::BlobChecksum);
    }
    let mut r = In {
        buf: body,
        at: HEADER_BYTES,
    };
    let mut v = [0.0f32; 12];
    for x in v.iter_mut() {
        *x = r.f32()?;
    }
    let xy = [[v[0], v[1]], [v[2], v[3]], [v[4], v[5]]];
    let lum = [v[6], v[7], v[8]];
    let black = Xyz::new(v[9], v[10], v[11]);
    let mut curves = [Transfer::Linear, Transfer::Linear, Transfer::Linear];
    for c in curves.iter_mut() {
        let (kind, n) = (r.u32()?, r.u32()? as usize);
        *c = match (kind, n) {
            (0, 0) => Transfer::Linear,
            (1, 0) => Transfer::Srgb,
            (2, 0) => match r.f32()? {
                g if g.is_finite() && g > 0.0 => Transfer::Gamma(g),
                g if !g.is_finite() => return Err(Error::NonFinite(0)),
                _ => return Err(Error::Capacity),
            },
            (3, 2..=TABLE_MAX) => {
                let mut t = [0.0f32; TABLE_MAX];
                for x in t[..n].iter_mut() {
                    *x = r.f32()?;
                }
                Transfer::table(&t[..n])?
            }
            (3, _) => return Err(Error::Capacity),
            _ => return Err(Error::BlobVersion),
        };
    }
    if r.at != body.len() {
        return Err(Error::BlobTruncated);
    }
    Ok(Parts {
        primaries: xy,
        luminance: lum,
        black,
        transfer: curves,
    })
}
