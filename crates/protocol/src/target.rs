//! What a colour command may ask for: the one check the controller (`specpoly-device`) and
//! the host's model of it (`specpoly-led`) both make before a target reaches gamut mapping.

use crate::fault::ErrorCode;
use specpoly_core::Xyz;

/// The largest X, Y or Z a colour command may ask for (white `Y = 100`): a hundred times the
/// LED's white. No LED comes near it; a larger number is a mistake, not a colour.
pub const MAX_TARGET: f32 = 1e4;

/// How far below zero X, Y or Z may be and still count as zero (rounding, as in the XYZ of a
/// reflectance near black): 10⁻⁵ of the white's `Y = 100`.
pub const NEGATIVE_TOLERANCE: f32 = 1e-3;

/// Whether `t` can be a colour: finite ([`ErrorCode::NotFinite`] if not), and X, Y, Z each in
/// [−[`NEGATIVE_TOLERANCE`], [`MAX_TARGET`]] ([`ErrorCode::OutOfRange`] if not). Every real
/// light has non-negative tristimulus values (the CIE colour-matching functions are
/// non-negative), so a negative one names no colour: gamut mapping must not be asked to
/// show it (desaturating `xyz -1e30 1 1` toward the grey of its luminance lit the LED at its
/// full white, a hundred times the target's `Y`).
pub fn check_target(t: Xyz) -> Result<(), ErrorCode> {
    let v = [t.x, t.y, t.z];
    if v.iter().any(|c| !c.is_finite()) {
        return Err(ErrorCode::NotFinite);
    }
    if v.iter()
        .any(|c| !(-NEGATIVE_TOLERANCE..=MAX_TARGET).contains(c))
    {
        return Err(ErrorCode::OutOfRange);
    }
    Ok(())
}
