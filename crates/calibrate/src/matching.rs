//! Matching two displays' whites for an observer: the white target (and video LUT) that makes
//! display B's white look like display A's to a chosen observer, and how far apart the two
//! whites are under other observers.
//!
//! Two displays set to the same white under the CIE 1931 observer do not look alike when
//! their spectra differ (a QD-OLED's narrow primaries against a WLED LCD's broad ones): the
//! match holds for the 1931 observer only. With both displays modelled by their spectra
//! ([`crate::spectral_display`]) the match can be made for any observer `o`:
//!
//! 1. A's white `W = XYZ_o(A, 1, 1, 1)`; B's primaries `Pᵢ = XYZ_o(Pᵢ^B)` and black `K`.
//! 2. B's channel light `s(t) = P⁻¹(t·W − K)`: the mix of B's primaries with A's white's
//!    chromaticity under `o` at `t` times its luminance. `t` is the largest with every
//!    `sᵢ ≤ 1`, at most 1 (B no brighter than A); a chromaticity B cannot mix (`sᵢ < 0`) is
//!    refused.
//! 3. The video LUT: channel `i`'s entry for input `v` is `encode(sᵢ · decode(v))` (B's
//!    transfer curve), 16 bits (`round(65535·x)`), so full input gives the new white; what B
//!    then shows is computed from the quantised white entries.
//!
//! The report compares A's white with B's matched white under each observer: Δu′v′ (CIE
//! 1976 UCS) and ΔE00 with both whites at `Y = 100` and A's as the reference white (the
//! chromatic difference; the luminance ratio is reported apart).

use crate::error::{Error, Result};
use crate::spectral_display::SpectralDisplay;
use specpoly_core::{Observer, Transfer};

/// Entries per channel of the video LUT.
pub const LUT_ENTRIES: usize = 256;

/// `l = decode(v)` in f64 for the power laws, through core's curve otherwise.
fn decode(t: &Transfer, v: f64) -> f64 {
    match t {
        Transfer::Linear => v,
        Transfer::Gamma(g) => v.max(0.0).powf(*g as f64),
        _ => t.decode(v as f32) as f64,
    }
}

/// The inverse of [`decode`].
fn encode(t: &Transfer, l: f64) -> f64 {
    match t {
        Transfer::Linear => l,
        Transfer::Gamma(g) => l.max(0.0).powf(1.0 / *g as f64),
        _ => t.encode(l as f32) as f64,
    }
}

/// `(u′, v′)` of an XYZ.
pub fn uv(xyz: [f64; 3]) -> [f64; 2] {
    let d = xyz[0] + 15.0 * xyz[1] + 3.0 * xyz[2];
    [4.0 * xyz[0] / d, 9.0 * xyz[1] / d]
}

/// Δu′v′ of two XYZ.
pub fn delta_uv(a: [f64; 3], b: [f64; 3]) -> f64 {
    let (p, q) = (uv(a), uv(b));
    (p[0] - q[0]).hypot(p[1] - q[1])
}

/// B matched to A for an observer.
#[derive(Clone, Debug, PartialEq)]
pub struct Matched {
    /// The observer the whites match under.
    pub observer: Observer,
    /// B's channel light at the new white (0–1 of full drive), exact.
    pub light: [f64; 3],
    /// The new white's device values on B (its transfer curve's inverse of `light`).
    pub white_codes: [f64; 3],
    /// The video LUT's full-input entries, 16-bit.
    pub white_lut16: [u16; 3],
    /// B's channel light after the 16-bit quantisation.
    pub light_quantised: [f64; 3],
    /// The video LUT: `LUT_ENTRIES` rows of 16-bit `[R, G, B]` for inputs `k / 255`.
    pub lut: Vec<[u16; 3]>,
    /// B's white luminance over A's under the observer (`t`).
    pub luminance_ratio: f64,
}

/// Makes B's white match A's under `observer` (see the module docs).
pub fn match_white(
    a: &SpectralDisplay,
    b: &SpectralDisplay,
    observer: Observer,
) -> Result<Matched> {
    let w = a.xyz([1.0; 3], observer);
    let p = b.primaries_xyz(observer);
    let k = b.black_xyz(observer);
    let m = specpoly_core::Mat3([0, 1, 2].map(|r| [p[0][r], p[1][r], p[2][r]]));
    let inv = m
        .inverse()
        .map_err(|_| Error::Match {
            why: format!("{}'s primaries are not independent", b.name),
        })?
        .0;
    let mul = |v: [f64; 3]| [0, 1, 2].map(|r| (0..3).map(|c| inv[r][c] * v[c]).sum::<f64>());
    let (sw, sk) = (mul(w), mul(k));
    // s(t) = t·sw − sk
    if let Some(i) = (0..3).find(|&i| !(sw[i] > 0.0)) {
        return Err(Error::Match {
            why: format!(
                "{}'s white under the {} observer is outside {}'s gamut (channel {i} would be negative)",
                a.name,
                observer.name(),
                b.name
            ),
        });
    }
    let t = (0..3).map(|i| (1.0 + sk[i]) / sw[i]).fold(1.0f64, f64::min);
    let light = [0, 1, 2].map(|i| (t * sw[i] - sk[i]).clamp(0.0, 1.0));
    let white_codes = light.map(|l| encode(&b.transfer, l));
    let q = |x: f64| (x.clamp(0.0, 1.0) * 65535.0).round() as u16;
    let white_lut16 = white_codes.map(q);
    let light_quantised = white_lut16.map(|c| decode(&b.transfer, c as f64 / 65535.0));
    let lut = (0..LUT_ENTRIES)
        .map(|e| {
            let v = e as f64 / (LUT_ENTRIES - 1) as f64;
            let d = decode(&b.transfer, v);
            [0, 1, 2].map(|i| q(encode(&b.transfer, light[i] * d)))
        })
        .collect();
    Ok(Matched {
        observer,
        light,
        white_codes,
        white_lut16,
        light_quantised,
        lut,
        luminance_ratio: t,
    })
}

/// One observer's row of the report.
#[derive(Clone, Debug, PartialEq)]
pub struct Mismatch {
    /// The observer.
    pub observer: Observer,
    /// A's white, `(u′, v′)`.
    pub a_uv: [f64; 2],
    /// B's matched white (after quantisation), `(u′, v′)`.
    pub b_uv: [f64; 2],
    /// Δu′v′.
    pub delta_uv: f64,
    /// ΔE00, both at `Y = 100`, A's white the reference.
    pub delta_e00: f64,
}

/// A's white against B's matched white under `observer`.
pub fn mismatch(
    a: &SpectralDisplay,
    b: &SpectralDisplay,
    matched: &Matched,
    observer: Observer,
) -> Mismatch {
    let wa = a.xyz([1.0; 3], observer);
    let wb = b.xyz_linear(matched.light_quantised, observer);
    let norm = |x: [f64; 3]| x.map(|v| v * 100.0 / x[1]);
    Mismatch {
        observer,
        a_uv: uv(wa),
        b_uv: uv(wb),
        delta_uv: delta_uv(wa, wb),
        delta_e00: specpoly_core::delta_e2000_xyz(norm(wb), norm(wa), norm(wa)),
    }
}
