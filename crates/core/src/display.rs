//! A display (monitor or RGB LED) as three additive primaries: Cowan's model (Cowan 1983, the
//! paper's §7.3). With the primaries' chromaticities `(xᵢ, yᵢ)` and luminances `Yᵢ` at full drive,
//! the primary's XYZ is `Yᵢ · (xᵢ/yᵢ, 1, (1 − xᵢ − yᵢ)/yᵢ)`, and for linear drive `rgb ∈ [0, 1]³`
//!
//! `XYZ = M · rgb + black`, with the columns of `M` the primaries' XYZ.
//!
//! Device values pass through a per-channel transfer curve (sRGB's IEC 61966-2-1 curve, a pure
//! gamma, or a measured table). Colours outside the gamut are either clipped per channel (the
//! paper's clamp) or desaturated toward the grey of the same luminance, which keeps the dominant
//! wavelength (the mixture with white lies on the line to the white point) and the luminance.

use crate::{math, Error, Mat3, Xyz};
use heapless::Vec;

/// Largest number of points of a tabulated transfer curve.
pub const TABLE_MAX: usize = 64;

// `Table` is much larger than the other variants; with no heap in `no_std` it stays inline.
#[allow(clippy::large_enum_variant)]
/// A channel's transfer curve between device value `v ∈ [0, 1]` and linear light `l ∈ [0, 1]`.
#[derive(Clone, Debug, PartialEq)]
pub enum Transfer {
    /// No curve: `l = v`.
    Linear,
    /// The sRGB curve of IEC 61966-2-1 (linear toe below 0.04045).
    Srgb,
    /// A pure power law `l = v^γ`.
    Gamma(f32),
    /// Measured linear output at evenly spaced device values `0, 1/(n−1), …, 1`, increasing.
    Table(Vec<f32, TABLE_MAX>),
}

impl Transfer {
    /// Whether `values` make a table ([`Transfer::table`]'s conditions), read as they come: a
    /// device checks a stored table without a copy of it.
    pub fn check_table(values: impl IntoIterator<Item = f32>) -> Result<(), Error> {
        let mut n = 0;
        let mut last = f32::NEG_INFINITY;
        for v in values {
            if n == TABLE_MAX {
                return Err(Error::Capacity);
            }
            if !v.is_finite() {
                return Err(Error::NonFinite(n));
            }
            if v < last {
                return Err(Error::NotIncreasing(n));
            }
            (last, n) = (v, n + 1);
        }
        if n < 2 {
            return Err(Error::Capacity);
        }
        Ok(())
    }

    /// A tabulated curve; values must be finite and non-decreasing, 2 ≤ n ≤ [`TABLE_MAX`].
    pub fn table(values: &[f32]) -> Result<Self, Error> {
        Self::check_table(values.iter().copied())?;
        let mut t = Vec::new();
        // capacity checked above
        let _ = t.extend_from_slice(values);
        Ok(Transfer::Table(t))
    }

    /// Device value → linear light.
    #[inline]
    pub fn decode(&self, v: f32) -> f32 {
        let v = v.clamp(0.0, 1.0);
        // the power laws share one call of `pow_unit`, so that it is inlined once (flash)
        let (x, p) = match self {
            Transfer::Linear => return v,
            Transfer::Srgb if v <= 0.04045 => return v / 12.92,
            Transfer::Srgb => ((v + 0.055) / 1.055, 2.4),
            Transfer::Gamma(g) => (v, *g),
            Transfer::Table(t) => {
                let x = v * (t.len() - 1) as f32;
                let i = (x as usize).min(t.len() - 2);
                let f = x - i as f32;
                return t[i] + (t[i + 1] - t[i]) * f;
            }
        };
        math::pow_unit(x, p)
    }

    /// The curve's slope `dl/dv` at `v` (clamped to `[0, 1]`): the derivative on the right of
    /// `v` (on the left at `v = 1`); 0 where the curve is flat. A power law below 1, whose
    /// slope at 0 is infinite, gives the secant to the first table step, `1/(TABLE_MAX − 1)`.
    pub fn slope(&self, v: f32) -> f32 {
        let v = if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
        match self {
            Transfer::Linear => 1.0,
            Transfer::Srgb => {
                if v <= 0.04045 {
                    1.0 / 12.92
                } else {
                    2.4 / 1.055 * math::powf((v + 0.055) / 1.055, 1.4)
                }
            }
            Transfer::Gamma(g) => {
                let d = *g * math::powf(v, *g - 1.0);
                if d.is_finite() {
                    d
                } else {
                    Self::secant_up(|x| math::powf(x, *g), v)
                }
            }
            Transfer::Table(t) => {
                let n = t.len();
                let top = (n - 1) as f32;
                let i = ((v * top) as usize).min(n - 2);
                (t[i + 1] - t[i]) * top
            }
        }
    }

    /// [`Self::slope`], except where the curve is flat at `v` (a table's flat foot, a power
    /// law's zero slope at 0): there the secant from `v` to the first point where it rises,
    /// the slope a solver needs to leave the flat part. 0 only for a curve flat to its end.
    pub fn rise(&self, v: f32) -> f32 {
        let s = self.slope(v);
        let v = if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
        if s > 0.0 || v >= 1.0 {
            return s.max(0.0);
        }
        match self {
            Transfer::Table(t) => {
                let top = (t.len() - 1) as f32;
                let here = self.decode(v);
                match t.iter().position(|y| *y > here) {
                    Some(k) => (t[k] - here) / (k as f32 / top - v),
                    None => 0.0,
                }
            }
            _ => Self::secant_up(|x| self.decode(x), v),
        }
    }

    /// The secant of `f` from `v` to `v + 1/(TABLE_MAX − 1)` (or 1).
    fn secant_up(f: impl Fn(f32) -> f32, v: f32) -> f32 {
        let h = (1.0 / (TABLE_MAX - 1) as f32).min(1.0 - v);
        if h > 0.0 {
            (f(v + h) - f(v)) / h
        } else {
            0.0
        }
    }

    /// Linear light → device value (the inverse of [`Self::decode`]; clamps to `[0, 1]`).
    #[inline]
    pub fn encode(&self, l: f32) -> f32 {
        let l = l.clamp(0.0, 1.0);
        // `a · l^p + b`: one call of `pow_unit` for both power laws (inlined once: flash);
        // `1 · x + 0` is `x` exactly
        let (p, a, b) = match self {
            Transfer::Linear => return l,
            Transfer::Srgb if l <= 0.003_130_8 => return 12.92 * l,
            Transfer::Srgb => (1.0 / 2.4, 1.055, -0.055),
            Transfer::Gamma(g) => (1.0 / *g, 1.0, 0.0),
            Transfer::Table(t) => return table_inverse(t, l),
        };
        a * math::pow_unit(l, p) + b
    }
}

/// Where a non-decreasing curve sampled at `n ≥ 2` evenly spaced points `0, 1/(n−1), …, 1`
/// reaches `l`: the linear interpolant's inverse (the first crossing on a flat step; 0 below
/// the curve, 1 above). [`Transfer::encode`] of a table, and the host's ICC writer on its
/// longer curves.
#[inline]
pub fn table_inverse(t: &[f32], l: f32) -> f32 {
    let n = t.len();
    if n < 2 || l <= t[0] {
        return 0.0;
    }
    if l >= t[n - 1] {
        return 1.0;
    }
    let i = t.partition_point(|x| *x <= l).clamp(1, n - 1);
    let (a, b) = (t[i - 1], t[i]);
    let f = if b > a { (l - a) / (b - a) } else { 0.0 };
    ((i - 1) as f32 + f) / (n - 1) as f32
}

/// How to bring a colour outside the display's gamut inside it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum GamutMap {
    /// Clamp each channel to `[0, 1]` (the paper, §7.3). Shifts hue.
    #[default]
    Clip,
    /// Mix with the grey of equal luminance until in gamut (luminance clipped to the white's
    /// first): keeps the dominant wavelength.
    Desaturate,
}

/// A display: primaries, black level and per-channel transfer curves.
#[derive(Clone, Debug, PartialEq)]
pub struct Display {
    to_xyz: Mat3,
    from_xyz: Mat3,
    black: Xyz,
    transfer: [Transfer; 3],
}

/// The result of encoding a colour for a display.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Encoded {
    /// Device values in `[0, 1]`.
    pub device: [f32; 3],
    /// Linear drive after gamut mapping, in `[0, 1]`.
    pub linear: [f32; 3],
    /// Whether the colour was outside the gamut (and was mapped).
    pub out_of_gamut: bool,
}

/// Cowan's matrices (RGB → XYZ and its inverse) from the primaries' chromaticities `[x, y]`
/// and luminances at full drive: column `i` is primary `i`'s XYZ.
fn matrices(xy: [[f32; 2]; 3], luminance: [f32; 3]) -> Result<(Mat3, Mat3), Error> {
    let mut m = [[0.0f32; 3]; 3];
    for (i, (c, l)) in xy.iter().zip(luminance).enumerate() {
        if !(c[0].is_finite() && c[1].is_finite() && l.is_finite()) {
            return Err(Error::NonFinite(i));
        }
        if c[1] <= 0.0 {
            return Err(Error::Singular);
        }
        let p = Xyy {
            x: c[0],
            y: c[1],
            big_y: l,
        }
        .to_xyz();
        m[0][i] = p.x;
        m[1][i] = p.y;
        m[2][i] = p.z;
    }
    let to_xyz = Mat3(m);
    let from_xyz = to_xyz.inverse()?;
    Ok((to_xyz, from_xyz))
}

impl Display {
    /// Cowan's model from the primaries' chromaticities `[x, y]` and luminances at full drive.
    pub fn from_primaries(
        xy: [[f32; 2]; 3],
        luminance: [f32; 3],
        black: Xyz,
        transfer: [Transfer; 3],
    ) -> Result<Self, Error> {
        let (to_xyz, from_xyz) = matrices(xy, luminance)?;
        Ok(Self {
            to_xyz,
            from_xyz,
            black,
            transfer,
        })
    }

    /// New primaries for this display, its curves and black kept ([`Display::from_primaries`]
    /// in place: no second display, whose curves would be copied, is built). On an error the
    /// display is unchanged.
    pub fn set_primaries(&mut self, xy: [[f32; 2]; 3], luminance: [f32; 3]) -> Result<(), Error> {
        (self.to_xyz, self.from_xyz) = matrices(xy, luminance)?;
        Ok(())
    }

    /// Cowan's model from the primaries' chromaticities and the white's chromaticity and
    /// luminance: the primaries' luminances are solved so that full drive gives that white.
    pub fn from_primaries_white(
        xy: [[f32; 2]; 3],
        white_xy: [f32; 2],
        white_luminance: f32,
        transfer: [Transfer; 3],
    ) -> Result<Self, Error> {
        let (_, unit_from_xyz) = matrices(xy, [1.0; 3])?;
        let w = Xyy {
            x: white_xy[0],
            y: white_xy[1],
            big_y: white_luminance,
        }
        .to_xyz();
        let lum = unit_from_xyz.apply(w.to_array());
        Self::from_primaries(xy, lum, Xyz::default(), transfer)
    }

    /// sRGB (IEC 61966-2-1): Rec. 709 primaries, D65 white of luminance 1, the sRGB curve.
    pub fn srgb() -> Self {
        let t = [Transfer::Srgb, Transfer::Srgb, Transfer::Srgb];
        match Self::from_primaries_white(SRGB_PRIMARIES, D65_XY, 1.0, t) {
            Ok(d) => d,
            // constant, non-singular input (unit-tested)
            Err(_) => unreachable!("sRGB primaries are valid"),
        }
    }

    /// Linear RGB → XYZ matrix (columns: primaries at full drive).
    pub fn rgb_to_xyz(&self) -> &Mat3 {
        &self.to_xyz
    }

    /// XYZ → linear RGB matrix.
    pub fn xyz_to_rgb(&self) -> &Mat3 {
        &self.from_xyz
    }

    /// The black level (XYZ at zero drive).
    pub fn black(&self) -> Xyz {
        self.black
    }

    /// The channels' transfer curves.
    pub fn transfer(&self) -> &[Transfer; 3] {
        &self.transfer
    }

    /// The channels' transfer curves, to change in place: the curves are independent of the
    /// primaries' matrices, so no other field depends on them (the LED controller sets one
    /// curve without copying the others).
    pub fn transfer_mut(&mut self) -> &mut [Transfer; 3] {
        &mut self.transfer
    }

    /// The primaries' chromaticities and luminances.
    pub fn primaries(&self) -> ([[f32; 2]; 3], [f32; 3]) {
        let mut xy = [[0.0; 2]; 3];
        let mut lum = [0.0; 3];
        for i in 0..3 {
            let p = Xyz::new(
                self.to_xyz.0[0][i],
                self.to_xyz.0[1][i],
                self.to_xyz.0[2][i],
            );
            let c = Xyy::from_xyz(p, Xyz::default());
            xy[i] = [c.x, c.y];
            lum[i] = p.y;
        }
        (xy, lum)
    }

    /// XYZ at full drive of all three channels, black included.
    #[inline]
    pub fn white(&self) -> Xyz {
        Xyz::from_array(self.to_xyz.apply([1.0; 3])) + self.black
    }

    /// Predicted XYZ for device values `rgb ∈ [0, 1]³` (in the display's luminance units).
    #[inline]
    pub fn device_to_xyz(&self, rgb: [f32; 3]) -> Xyz {
        let lin = [
            self.transfer[0].decode(rgb[0]),
            self.transfer[1].decode(rgb[1]),
            self.transfer[2].decode(rgb[2]),
        ];
        Xyz::from_array(self.to_xyz.apply(lin)) + self.black
    }

    /// Linear drive (unclipped) for an absolute XYZ in the display's units.
    #[inline]
    pub fn xyz_to_linear(&self, xyz: Xyz) -> [f32; 3] {
        let b = self.black;
        self.from_xyz.apply([xyz.x - b.x, xyz.y - b.y, xyz.z - b.z])
    }

    /// Encodes an absolute XYZ (display units) into device values, mapping out-of-gamut colours.
    #[inline]
    pub fn encode(&self, xyz: Xyz, map: GamutMap) -> Encoded {
        let lin = self.xyz_to_linear(xyz);
        let (linear, out_of_gamut) = map_gamut(lin, self.luminance_weights(), map);
        let device = [
            self.transfer[0].encode(linear[0]),
            self.transfer[1].encode(linear[1]),
            self.transfer[2].encode(linear[2]),
        ];
        Encoded {
            device,
            linear,
            out_of_gamut,
        }
    }

    /// Encodes a colour given relative to a white of `Y = 100` (the project's XYZ convention)
    /// by scaling it to the display's white luminance.
    #[inline]
    pub fn encode_relative(&self, xyz: Xyz, map: GamutMap) -> Encoded {
        let k = (self.white().y - self.black.y) / 100.0;
        self.encode(xyz.scale(k), map)
    }

    /// Each channel's share of the white's luminance (row Y of `M`, normalised).
    #[inline]
    pub fn luminance_weights(&self) -> [f32; 3] {
        let r = self.to_xyz.0[1];
        let s = r[0] + r[1] + r[2];
        if s > 0.0 {
            [r[0] / s, r[1] / s, r[2] / s]
        } else {
            [1.0 / 3.0; 3]
        }
    }
}

use crate::Xyy;

/// Rec. 709 / sRGB primaries (IEC 61966-2-1).
pub const SRGB_PRIMARIES: [[f32; 2]; 3] = [[0.64, 0.33], [0.30, 0.60], [0.15, 0.06]];
/// The chromaticity of D65 as IEC 61966-2-1 writes it.
pub const D65_XY: [f32; 2] = [0.3127, 0.3290];

/// Brings linear drive into `[0, 1]³`. Returns the mapped drive and whether it was outside.
#[inline]
pub fn map_gamut(lin: [f32; 3], weights: [f32; 3], map: GamutMap) -> ([f32; 3], bool) {
    const EPS: f32 = 1e-6;
    let outside = lin
        .iter()
        .any(|v| !(-EPS..=1.0 + EPS).contains(v) || v.is_nan());
    if !outside {
        return (lin.map(|v| v.clamp(0.0, 1.0)), false);
    }
    let lin = lin.map(|v| if v.is_nan() { 0.0 } else { v });
    match map {
        GamutMap::Clip => (lin.map(|v| v.clamp(0.0, 1.0)), true),
        GamutMap::Desaturate => {
            let y =
                (weights[0] * lin[0] + weights[1] * lin[1] + weights[2] * lin[2]).clamp(0.0, 1.0);
            // largest t ∈ [0, 1] with y + t (c − y) ∈ [0, 1] for every channel
            let mut t = 1.0f32;
            for c in lin {
                let d = c - y;
                if c > 1.0 && d > 0.0 {
                    t = t.min((1.0 - y) / d);
                } else if c < 0.0 && d < 0.0 {
                    t = t.min(-y / d);
                }
            }
            let t = t.clamp(0.0, 1.0);
            (lin.map(|c| (y + t * (c - y)).clamp(0.0, 1.0)), true)
        }
    }
}

/// Quantises a device value in `[0, 1]` to a level `0 ..= max`: `round(v · max)`, half up;
/// `v` is clamped to `[0, 1]` and NaN gives 0.
#[inline]
pub fn quantize(v: f32, max: u16) -> u16 {
    let v = if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
    (v * max as f32 + 0.5) as u16
}

/// Quantises a device value in `[0, 1]` to 8 bits: [`quantize`] with `max = 255` (the paper's
/// ×256 would overflow at 1.0).
pub fn quantize8(v: f32) -> u8 {
    quantize(v, 255) as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn transfer_roundtrips() {
        let curves = [
            Transfer::Linear,
            Transfer::Srgb,
            Transfer::Gamma(2.2),
            Transfer::table(&[0.0, 0.05, 0.2, 0.5, 1.0]).unwrap(),
        ];
        for c in curves {
            for i in 0..=20 {
                let v = i as f32 / 20.0;
                assert!((c.encode(c.decode(v)) - v).abs() < 1e-4, "{c:?} {v}");
            }
        }
        assert_eq!(
            Transfer::table(&[0.0, 0.5, 0.4]),
            Err(Error::NotIncreasing(2))
        );
        assert_eq!(Transfer::table(&[0.0]), Err(Error::Capacity));
    }

    #[test]
    fn desaturate_keeps_luminance_and_dominant_direction() {
        let w = [0.2126, 0.7152, 0.0722];
        let (m, out) = map_gamut([1.4, 0.2, -0.1], w, GamutMap::Desaturate);
        assert!(out);
        let y0 = 0.2126 * 1.4 + 0.7152 * 0.2 - 0.0722 * 0.1;
        let y1 = w[0] * m[0] + w[1] * m[1] + w[2] * m[2];
        assert!((y0 - y1).abs() < 1e-5);
        // colinear with grey: (m − y) ∥ (c − y)
        let d0 = [1.4 - y0, 0.2 - y0, -0.1 - y0];
        let d1 = [m[0] - y1, m[1] - y1, m[2] - y1];
        let k = d1[0] / d0[0];
        assert!((d1[1] - k * d0[1]).abs() < 1e-5 && (d1[2] - k * d0[2]).abs() < 1e-5);
        assert!(m.iter().all(|v| (0.0..=1.0).contains(v)));
        let (c, out) = map_gamut([1.4, 0.2, -0.1], w, GamutMap::Clip);
        assert!(out);
        assert_eq!(c, [1.0, 0.2, 0.0]);
    }

    #[test]
    fn quantisation() {
        assert_eq!(quantize8(1.0), 255);
        assert_eq!(quantize8(0.5), 128);
        assert_eq!(quantize8(f32::NAN), 0);
        assert_eq!(quantize(1.0, 65535), 65535);
        assert_eq!(quantize(0.5, 1000), 500);
        assert_eq!(quantize(-3.0, 255), 0);
    }
}
