//! The display drive step ([`specpoly_core::drive`], Cowan 1983): a target XYZ (white `Y = 100`)
//! → linear drive (gamut mapped) → the transfer curves' inverse → integer levels `0..=max` →
//! the XYZ emitted at those levels.
//!
//! The display is given as its model's parameters ([`SpDisplay`]: the primaries' chromaticities
//! and luminances, the black level and a curve per channel: a power law, the sRGB curve or a
//! measured table), filled by the caller or read from a calibration blob
//! ([`sp_calibration_load`]: `specpoly calibrate export --format c-blob` on the host,
//! [`specpoly_core::blob`]). Each call builds the core's [`Display`] (the 3×3 inverse included)
//! and runs its drive step, or its forward model (device values → XYZ, [`sp_display_forward`])
//! or its inverse (XYZ → device values, [`sp_display_inverse`]).

use crate::status::{self, finite, of, Status};
use crate::{ptr, SpStatus};
use specpoly_core::display::TABLE_MAX;
use specpoly_core::{blob, Display, Error, GamutMap, Transfer, Xyz};

/// The most points of a tabulated transfer curve.
pub const SP_DISPLAY_TABLE_MAX: usize = 64;
const _: () = assert!(SP_DISPLAY_TABLE_MAX == TABLE_MAX);

/// How a colour outside the gamut is brought inside (the `map` argument).
#[repr(i32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpGamutMap {
    /// Clamp each channel to [0, 1].
    Clip = 0,
    /// Mix with the grey of equal luminance until inside (keeps the dominant wavelength).
    Desaturate = 1,
}

/// A display (or RGB LED) as three additive primaries.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpDisplay {
    /// The primaries' CIE 1931 `[x, y]` (red, green, blue), `y > 0`.
    pub primaries: [[f32; 2]; 3],
    /// The primaries' luminances at full drive (any unit).
    pub luminance: [f32; 3],
    /// The black level's X, Y, Z (same unit; zeros for none).
    pub black: [f32; 3],
    /// Each channel's curve, device value → light: 1 linear, 0 the sRGB curve, else
    /// `l = v^gamma` (> 0); used where `table_len` is 0.
    pub gamma: [f32; 3],
    /// Points of each channel's tabulated curve: 0 for none (`gamma` is used), else 2 to
    /// `SP_DISPLAY_TABLE_MAX`.
    pub table_len: [u32; 3],
    /// Each channel's tabulated curve: the linear output at `table_len` evenly spaced device
    /// values `0, 1/(n−1), …, 1`, non-decreasing.
    pub table: [[f32; SP_DISPLAY_TABLE_MAX]; 3],
}

impl Default for SpDisplay {
    fn default() -> Self {
        Self {
            primaries: [[0.0; 2]; 3],
            luminance: [0.0; 3],
            black: [0.0; 3],
            gamma: [1.0; 3],
            table_len: [0; 3],
            table: [[0.0; SP_DISPLAY_TABLE_MAX]; 3],
        }
    }
}

/// CIE 1931 tristimulus values.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SpXyz {
    /// X.
    pub x: f32,
    /// Y.
    pub y: f32,
    /// Z.
    pub z: f32,
}

/// What the display shows for a target.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SpDrive {
    /// Linear drive after gamut mapping, in [0, 1].
    pub linear: [f32; 3],
    /// Integer levels `round(v · max)` of the device values.
    pub level: [u16; 3],
    /// The XYZ emitted at those levels, relative to the display's white at `Y = 100`.
    pub emitted: SpXyz,
    /// 1 when the target was outside the gamut (and was mapped), else 0.
    pub out_of_gamut: i32,
}

impl From<Xyz> for SpXyz {
    fn from(v: Xyz) -> Self {
        Self {
            x: v.x,
            y: v.y,
            z: v.z,
        }
    }
}

/// Channel `c`'s curve, written in place (a `Transfer` is 264 bytes: built where it stays,
/// not returned through `Result`s, it costs no copies on the stack).
fn curve(d: &SpDisplay, c: usize, out: &mut Transfer) -> Status<()> {
    let n = d.table_len[c] as usize;
    if n > 0 {
        let t = d.table[c].get(..n).ok_or(SpStatus::Size)?;
        Transfer::check_table(t.iter().copied()).map_err(|e| match e {
            Error::NonFinite(_) => SpStatus::NotFinite,
            Error::NotIncreasing(_) => SpStatus::Domain,
            _ => SpStatus::Size,
        })?;
        *out = Transfer::Table(Default::default());
        if let Transfer::Table(v) = out {
            // checked above: n ≤ SP_DISPLAY_TABLE_MAX
            v.extend_from_slice(t).map_err(|_| SpStatus::Size)?;
        }
        return Ok(());
    }
    *out = match d.gamma[c] {
        0.0 => Transfer::Srgb,
        1.0 => Transfer::Linear,
        g if g > 0.0 => Transfer::Gamma(g),
        _ => return Err(SpStatus::Domain),
    };
    Ok(())
}

/// The core's display from the caller's description, every field checked. Inlined into each
/// function: built in its caller's frame, the display (≈ 850 bytes) is not copied out of a
/// return slot (measured on the M4F: 1 500 instructions and 1.5 KiB of stack more per call
/// when out of line).
#[inline(always)]
fn display(d: &SpDisplay) -> Status<Display> {
    finite(d.primaries.as_flattened())?;
    finite(&d.luminance)?;
    finite(&d.black)?;
    finite(&d.gamma)?;
    let mut t = [Transfer::Linear, Transfer::Linear, Transfer::Linear];
    for (c, t) in t.iter_mut().enumerate() {
        curve(d, c, t)?;
    }
    let [x, y, z] = d.black;
    Display::from_primaries(d.primaries, d.luminance, Xyz::new(x, y, z), t).map_err(|e| match e {
        Error::NonFinite(_) => SpStatus::NotFinite,
        _ => SpStatus::Singular,
    })
}

fn gamut_map(map: i32) -> Status<GamutMap> {
    match map {
        0 => Ok(GamutMap::Clip),
        1 => Ok(GamutMap::Desaturate),
        _ => Err(SpStatus::Domain),
    }
}

fn drive(d: &SpDisplay, t: &SpXyz, map: i32, max: u16) -> Status<SpDrive> {
    finite(&[t.x, t.y, t.z])?;
    let map = gamut_map(map)?;
    let r = display(d)?.drive(Xyz::new(t.x, t.y, t.z), map, max);
    let e = r.emitted;
    Ok(SpDrive {
        linear: r.linear,
        level: r.level,
        emitted: SpXyz {
            x: e.x,
            y: e.y,
            z: e.z,
        },
        out_of_gamut: r.out_of_gamut as i32,
    })
}

/// The drive step for `target` (CIE XYZ relative to the display's white at `Y = 100`) with
/// gamut map `map` (`SpGamutMap`) on levels `0..=max`.
///
/// Returns `SP_STATUS_OK`; `SP_STATUS_NULL_POINTER` (`display`, `target` or `out` NULL);
/// `SP_STATUS_NOT_FINITE` (a NaN or infinite target or display field); `SP_STATUS_DOMAIN` (an
/// unknown `map`, a negative gamma, a decreasing table); `SP_STATUS_SIZE` (a `table_len` of 1
/// or over `SP_DISPLAY_TABLE_MAX`); `SP_STATUS_SINGULAR` (a primary with `y ≤ 0`, or primaries
/// that do not span XYZ).
///
/// # Safety
/// `display` and `target` are NULL or point to a valid `SpDisplay` and `SpXyz`; `out` is NULL
/// or points to a writable `SpDrive`.
#[no_mangle]
pub unsafe extern "C" fn sp_display_drive(
    display: *const SpDisplay,
    target: *const SpXyz,
    map: i32,
    max: u16,
    out: *mut SpDrive,
) -> SpStatus {
    // SAFETY: forwarded contract.
    let args = unsafe { (ptr::get(display), ptr::get(target), ptr::get_mut(out)) };
    let (Ok(d), Ok(t), Ok(out)) = args else {
        return SpStatus::NullPointer;
    };
    of(drive(d, t, map, max).map(|r| *out = r))
}

/// A colour encoded for the display.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SpEncoded {
    /// Device values in [0, 1] (the curves' inverse of `linear`).
    pub device: [f32; 3],
    /// Linear drive after gamut mapping, in [0, 1].
    pub linear: [f32; 3],
    /// 1 when the colour was outside the gamut (and was mapped), else 0.
    pub out_of_gamut: i32,
}

/// The display model forward: the XYZ (in the display's units, black included) the display
/// emits at device values `rgb[0..3]` in [0, 1] (the core's `Display::device_to_xyz`:
/// `XYZ = M · decode(rgb) + black`).
///
/// Returns `SP_STATUS_OK`; `SP_STATUS_NULL_POINTER` (`display`, `rgb` or `out` NULL);
/// `SP_STATUS_NOT_FINITE`; `SP_STATUS_DOMAIN` (a device value outside [0, 1], or a display
/// field as for `sp_display_drive`); `SP_STATUS_SIZE`, `SP_STATUS_SINGULAR` as for
/// `sp_display_drive`.
///
/// # Safety
/// `display` is NULL or points to a valid `SpDisplay`; `rgb` is NULL or points to 3 floats;
/// `out` is NULL or points to a writable `SpXyz`.
#[no_mangle]
pub unsafe extern "C" fn sp_display_forward(
    display: *const SpDisplay,
    rgb: *const f32,
    out: *mut SpXyz,
) -> SpStatus {
    // SAFETY: forwarded contract.
    let args = unsafe { (ptr::get(display), ptr::slice(rgb, 3), ptr::get_mut(out)) };
    let (Ok(d), Ok(rgb), Ok(out)) = args else {
        return SpStatus::NullPointer;
    };
    of(forward(d, rgb).map(|v| *out = v))
}

fn forward(d: &SpDisplay, rgb: &[f32]) -> Status<SpXyz> {
    finite(rgb)?;
    if !rgb.iter().all(|v| (0.0..=1.0).contains(v)) {
        return Err(SpStatus::Domain);
    }
    let v = display(d)?.device_to_xyz([rgb[0], rgb[1], rgb[2]]);
    finite(&[v.x, v.y, v.z])?;
    Ok(SpXyz::from(v))
}

/// The display model inverse: the device values that make `xyz` (in the display's units,
/// black included), the linear drive brought into the gamut by `map` (`SpGamutMap`) first (the
/// core's `Display::encode`).
///
/// Returns `SP_STATUS_OK`; `SP_STATUS_NULL_POINTER` (`display`, `xyz` or `out` NULL);
/// `SP_STATUS_NOT_FINITE`; `SP_STATUS_DOMAIN` (an unknown `map`, or a display field as for
/// `sp_display_drive`); `SP_STATUS_SIZE`, `SP_STATUS_SINGULAR` as for `sp_display_drive`.
///
/// # Safety
/// `display` and `xyz` are NULL or point to a valid `SpDisplay` and `SpXyz`; `out` is NULL or
/// points to a writable `SpEncoded`.
#[no_mangle]
pub unsafe extern "C" fn sp_display_inverse(
    display: *const SpDisplay,
    xyz: *const SpXyz,
    map: i32,
    out: *mut SpEncoded,
) -> SpStatus {
    // SAFETY: forwarded contract.
    let args = unsafe { (ptr::get(display), ptr::get(xyz), ptr::get_mut(out)) };
    let (Ok(d), Ok(t), Ok(out)) = args else {
        return SpStatus::NullPointer;
    };
    of(inverse(d, t, map).map(|v| *out = v))
}

fn inverse(d: &SpDisplay, t: &SpXyz, map: i32) -> Status<SpEncoded> {
    finite(&[t.x, t.y, t.z])?;
    let map = gamut_map(map)?;
    let e = display(d)?.encode(Xyz::new(t.x, t.y, t.z), map);
    finite(&e.device)?;
    finite(&e.linear)?;
    Ok(SpEncoded {
        device: e.device,
        linear: e.linear,
        out_of_gamut: e.out_of_gamut as i32,
    })
}

/// Reads a calibration blob (`specpoly calibrate export --format c-blob`: magic `SPCB`,
/// version 1, length, the display's fields, CRC-32; docs/c.md) from `blob[0..len]` into
/// `out`. Nothing past `blob[len − 1]` is read; bytes after the blob's own length are ignored
/// (a flash region larger than it). The display is checked as `sp_display_drive` checks it.
///
/// Returns `SP_STATUS_OK`; `SP_STATUS_NULL_POINTER` (`blob` or `out` NULL);
/// `SP_STATUS_BLOB_VERSION` (not a blob, or of another version); `SP_STATUS_BLOB_TRUNCATED`
/// (shorter than its length field); `SP_STATUS_BLOB_CHECKSUM` (corrupted);
/// `SP_STATUS_NOT_FINITE`, `SP_STATUS_DOMAIN`, `SP_STATUS_SIZE`, `SP_STATUS_SINGULAR` (a
/// well-formed blob of a display the model refuses).
///
/// # Safety
/// `blob` is NULL or points to `len` readable bytes; `out` is NULL or points to a writable
/// `SpDisplay`.
#[no_mangle]
pub unsafe extern "C" fn sp_calibration_load(
    blob: *const u8,
    len: usize,
    out: *mut SpDisplay,
) -> SpStatus {
    if len > isize::MAX as usize {
        return SpStatus::Size;
    }
    // SAFETY: forwarded contract.
    let args = unsafe { (ptr::slice(blob, len), ptr::get_mut(out)) };
    let (Ok(bytes), Ok(out)) = args else {
        return SpStatus::NullPointer;
    };
    of(load(bytes).map(|d| *out = d))
}

fn load(bytes: &[u8]) -> Status<SpDisplay> {
    let p = blob::parts(bytes).map_err(status::core)?;
    let mut d = SpDisplay {
        primaries: p.primaries,
        luminance: p.luminance,
        black: p.black.to_array(),
        ..SpDisplay::default()
    };
    for (c, t) in p.transfer.iter().enumerate() {
        match t {
            Transfer::Linear => d.gamma[c] = 1.0,
            Transfer::Srgb => d.gamma[c] = 0.0,
            // > 0 (the blob's rule); an exponent of exactly 1 is the linear curve here
            Transfer::Gamma(g) => d.gamma[c] = *g,
            Transfer::Table(v) => {
                d.table_len[c] = v.len() as u32;
                d.table[c][..v.len()].copy_from_slice(v);
            }
        }
    }
    display(&d)?;
    Ok(d)
}
