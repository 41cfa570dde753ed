//! Correlated colour temperature and Duv ↔ CIE 1931 `xy`.
//!
//! - [`sp_cct_to_xy`] is the device's locus ([`specpoly_core::light::locus`]: a 25-node cubic
//!   Hermite table in mired, f32, within 2.4·10⁻⁶ of Planck's law in `u′v′` over 1000–25 000 K;
//!   Duv along the locus normal, ANSI C78.377), the one the LED mixer uses for CCT targets;
//! - [`sp_xy_to_cct`] is the exact definition ([`specpoly_core::light::cct::cct_duv`], f64:
//!   the nearest point of the Planckian locus in CIE 1960 `uv`, CIE 015:2018 §9.5, from Planck's
//!   law summed at 1 nm). It is the costly one (soft f64 on a Cortex-M4F; docs/performance.md).

use crate::status::{finite, of, Status};
use crate::{ptr, SpStatus};
use specpoly_core::light::{cct, channels::Goal};

/// CIE 1931 chromaticity.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SpXy {
    /// x.
    pub x: f32,
    /// y.
    pub y: f32,
}

/// A correlated colour temperature and Duv.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SpCct {
    /// Correlated colour temperature, K.
    pub cct: f64,
    /// Signed distance from the Planckian locus in CIE 1960 `uv`, positive above (greener).
    pub duv: f64,
}

/// The chromaticity of `cct` K moved `duv` from the Planckian locus along its normal.
///
/// Returns `SP_STATUS_OK`; `SP_STATUS_NULL_POINTER` (`out` NULL); `SP_STATUS_NOT_FINITE`
/// (`cct` or `duv` NaN or infinite); `SP_STATUS_DOMAIN` (`cct` outside 1000–25 000 K or
/// |`duv`| > 0.05, or a point that is no chromaticity: not `x, y > 0`, `x + y < 1`, as
/// 1000 K at Duv +0.05).
///
/// # Safety
/// `out` is NULL or points to a writable `SpXy`.
#[no_mangle]
pub unsafe extern "C" fn sp_cct_to_xy(cct: f32, duv: f32, out: *mut SpXy) -> SpStatus {
    // SAFETY: forwarded contract.
    of(unsafe { ptr::get_mut(out) }.and_then(|out| {
        *out = cct_to_xy(cct, duv)?;
        Ok(())
    }))
}

fn cct_to_xy(cct: f32, duv: f32) -> Status<SpXy> {
    finite(&[cct, duv])?;
    let p = Goal::Cct { cct, duv, lum: 1.0 }
        .point()
        .ok_or(SpStatus::Domain)?;
    let [x, y] = p.xy();
    // far above the locus at its red end the normal leaves the chromaticity diagram
    if !(x > 0.0 && y > 0.0 && x + y < 1.0) {
        return Err(SpStatus::Domain);
    }
    Ok(SpXy { x, y })
}

/// The CCT and Duv of chromaticity `(x, y)`.
///
/// Returns `SP_STATUS_OK`; `SP_STATUS_NULL_POINTER` (`out` NULL); `SP_STATUS_NOT_FINITE` (`x`
/// or `y` NaN or infinite); `SP_STATUS_DOMAIN` (not `x > 0`, `y > 0`, `x + y < 1`);
/// `SP_STATUS_NO_CCT` (farther than 0.05 from the locus, or outside 1000–100 000 K).
///
/// # Safety
/// `out` is NULL or points to a writable `SpCct`.
#[no_mangle]
pub unsafe extern "C" fn sp_xy_to_cct(x: f64, y: f64, out: *mut SpCct) -> SpStatus {
    // SAFETY: forwarded contract.
    of(unsafe { ptr::get_mut(out) }.and_then(|out| {
        *out = xy_to_cct(x, y)?;
        Ok(())
    }))
}

fn xy_to_cct(x: f64, y: f64) -> Status<SpCct> {
    if !(x.is_finite() && y.is_finite()) {
        return Err(SpStatus::NotFinite);
    }
    if !(x > 0.0 && y > 0.0 && x + y < 1.0) {
        return Err(SpStatus::Domain);
    }
    let c = cct::cct_duv(cct::xy_to_uv([x, y])).map_err(|_| SpStatus::NoCct)?;
    Ok(SpCct {
        cct: c.cct,
        duv: c.duv,
    })
}
