//! The display drive step ([`specpoly_core::drive`], Cowan 1983): a target XYZ (white `Y = 100`)
//! → linear drive (gamut mapped) → the transfer curves' inverse → integer levels `0..=max` →
//! the XYZ emitted at those levels.
//!
//! The display is given as its model's parameters ([`SpDisplay`]: the primaries' chromaticities
//! and luminances, the black level and a curve per channel), the same numbers the LED firmware's
//! `cal`/`trc` commands set; `calibrate export` writes C source for the framebuffer's pixel
//! transform, not this model, so there is no binary calibration blob to read. Each call builds
//! the core's [`Display`] (the 3×3 inverse included) and runs its drive step.

use crate::status::{finite, of, Status};
use crate::{ptr, SpStatus};
use specpoly_core::{Display, Error, GamutMap, Transfer, Xyz};

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
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SpDisplay {
    /// The primaries' CIE 1931 `[x, y]` (red, green, blue), `y > 0`.
    pub primaries: [[f32; 2]; 3],
    /// The primaries' luminances at full drive (any unit).
    pub luminance: [f32; 3],
    /// The black level's X, Y, Z (same unit; zeros for none).
    pub black: [f32; 3],
    /// Each channel's curve, device value → light: 1 linear, 0 the sRGB curve, else
    /// `l = v^gamma` (> 0).
    pub gamma: [f32; 3],
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

fn curve(g: f32) -> Status<Transfer> {
    Ok(match g {
        0.0 => Transfer::Srgb,
        1.0 => Transfer::Linear,
        g if g > 0.0 => Transfer::Gamma(g),
        _ => return Err(SpStatus::Domain),
    })
}

/// The core's display from the caller's description, every field checked.
fn display(d: &SpDisplay) -> Status<Display> {
    finite(d.primaries.as_flattened())?;
    finite(&d.luminance)?;
    finite(&d.black)?;
    finite(&d.gamma)?;
    let t = [curve(d.gamma[0])?, curve(d.gamma[1])?, curve(d.gamma[2])?];
    let [x, y, z] = d.black;
    Display::from_primaries(d.primaries, d.luminance, Xyz::new(x, y, z), t).map_err(|e| match e {
        Error::NonFinite(_) => SpStatus::NotFinite,
        _ => SpStatus::Singular,
    })
}

fn drive(d: &SpDisplay, t: &SpXyz, map: i32, max: u16) -> Status<SpDrive> {
    finite(&[t.x, t.y, t.z])?;
    let map = match map {
        0 => GamutMap::Clip,
        1 => GamutMap::Desaturate,
        _ => return Err(SpStatus::Domain),
    };
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
/// unknown `map`, a negative gamma); `SP_STATUS_SINGULAR` (a primary with `y ≤ 0`, or primaries
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
