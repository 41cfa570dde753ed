//! The 3-D table path: a `G × G × G` grid over the source code values holding panel levels,
//! interpolated tetrahedrally (Kasson, Nin, Plouffe & Hafner, "Performing color space
//! conversions with three-dimensional linear interpolation", J. Electronic Imaging 4 (1995);
//! the scheme of ICC `mAB` look-ups and Little CMS). For panels whose model is not additive (an
//! interaction term between channels), where no 3×3 and per-channel curves can be exact: the grid
//! is sampled from any function, in f64, once.
//!
//! Each cube cell is split into six tetrahedra along its grey diagonal; the one holding the
//! point is chosen by the order of the fractional coordinates `fx, fy, fz`, and the result is
//! `c₀₀₀ + Σ` of three edge differences weighted by them (four look-ups, three multiplies per
//! channel, weights in Q12). Tetrahedral interpolation reproduces any function affine in the source codes
//! exactly and keeps the grey diagonal exact at grid nodes.
//!
//! Entries are device code values in Q8 of a level (`d · (2^bits − 1) · 256`), so the output
//! dithers like [`PixelTransform`](super::PixelTransform)'s (here the fraction is linear in
//! code value, not light).

use super::source::linear_matrix;
use super::transform::Options;
use crate::display::{map_gamut, Display};
use crate::Error;

/// A tetrahedrally interpolated `G³` table: source codes → panel levels (Q8). `2 ≤ G ≤ 256`
/// (checked at compile time); `G = 17` holds 29 KiB, `G = 9` 4.3 KiB.
#[derive(Clone, Debug, PartialEq)]
pub struct CubeTransform<const G: usize> {
    grid: [[[[u16; 3]; G]; G]; G],
    bits: [u8; 3],
}

impl<const G: usize> CubeTransform<G> {
    const SIZE_OK: () = assert!(G >= 2 && G <= 256, "CubeTransform<G>: 2 ≤ G ≤ 256");
    /// Bytes of the grid.
    pub const TABLE_BYTES: usize = G * G * G * 6;

    /// Samples `device(source)` on the grid: `f` takes source code values in `[0, 1]³` (node
    /// `i` at `i/(G − 1)`) and returns panel device values in `[0, 1]³` (clamped; NaN → 0).
    pub fn from_fn(bits: [u8; 3], mut f: impl FnMut([f64; 3]) -> [f64; 3]) -> Result<Self, Error> {
        let () = Self::SIZE_OK;
        if bits.iter().any(|b| !(1..=8).contains(b)) {
            return Err(Error::Capacity);
        }
        let scale = bits.map(|b| ((1u32 << b) - 1) as f64 * 256.0);
        let mut grid = [[[[0u16; 3]; G]; G]; G];
        let n = (G - 1) as f64;
        for (i, plane) in grid.iter_mut().enumerate() {
            for (j, row) in plane.iter_mut().enumerate() {
                for (k, e) in row.iter_mut().enumerate() {
                    let d = f([i as f64 / n, j as f64 / n, k as f64 / n]);
                    for c in 0..3 {
                        let v = if d[c].is_nan() {
                            0.0
                        } else {
                            d[c].clamp(0.0, 1.0)
                        };
                        e[c] = libm::round(v * scale[c]) as u16;
                    }
                }
            }
        }
        Ok(Self { grid, bits })
    }

    /// The grid for an additive panel (Cowan's model), as [`PixelTransform`](super::PixelTransform)
    /// computes it but in f32 per node: decode, `T`, the core's gamut map, the panel's curve.
    pub fn from_display(panel: &Display, opts: Options) -> Result<Self, Error> {
        let t = linear_matrix(panel, opts.source, opts.white)?;
        let w = panel.luminance_weights();
        let curves = panel.transfer();
        Self::from_fn(opts.bits, |c| {
            let lin = c.map(|v| opts.source.decode(v as f32));
            let (l, _) = map_gamut(t.apply(lin), w, opts.map);
            [0, 1, 2].map(|i| curves[i].encode(l[i]) as f64)
        })
    }

    /// The panel's bits per channel.
    pub fn bits(&self) -> [u8; 3] {
        self.bits
    }

    /// The grid node `[r][g][b]` (Q8 levels).
    pub fn node(&self, r: usize, g: usize, b: usize) -> [u16; 3] {
        self.grid[r][g][b]
    }

    /// The panel levels (Q8) for a source pixel.
    #[inline]
    pub fn levels(&self, rgb: [u8; 3]) -> [u16; 3] {
        // position in cells, Q12 (rounded): c · (G − 1) / 255
        let cell = |c: u8| {
            let p = (c as u32 * (G as u32 - 1) * 4096 + 127) / 255;
            let i = (p >> 12).min(G as u32 - 2);
            (i as usize, (p - (i << 12)) as i32)
        };
        let (i, fx) = cell(rgb[0]);
        let (j, fy) = cell(rgb[1]);
        let (k, fz) = cell(rgb[2]);
        let g = &self.grid;
        let at = |a: usize, b: usize, c: usize| g[i + a][j + b][k + c];
        let c000 = at(0, 0, 0);
        let c111 = at(1, 1, 1);
        // the tetrahedron: three edges from c000 to c111, in order of decreasing fraction
        let (p1, p2, w1, w2, w3) = if fx >= fy {
            if fy >= fz {
                (at(1, 0, 0), at(1, 1, 0), fx, fy, fz)
            } else if fx >= fz {
                (at(1, 0, 0), at(1, 0, 1), fx, fz, fy)
            } else {
                (at(0, 0, 1), at(1, 0, 1), fz, fx, fy)
            }
        } else if fz >= fy {
            (at(0, 0, 1), at(0, 1, 1), fz, fy, fx)
        } else if fz >= fx {
            (at(0, 1, 0), at(0, 1, 1), fy, fz, fx)
        } else {
            (at(0, 1, 0), at(1, 1, 0), fy, fx, fz)
        };
        [0, 1, 2].map(|c| {
            let (a, b, d, e) = (c000[c] as i32, p1[c] as i32, p2[c] as i32, c111[c] as i32);
            // a convex combination of u16 values in Q12: below 2^28, no overflow
            let v = (a << 12) + w1 * (b - a) + w2 * (d - b) + w3 * (e - d) + 2048;
            (v >> 12).clamp(0, u16::MAX as i32) as u16
        })
    }

    /// The panel code values with a dither threshold in `0..256`.
    #[inline]
    pub fn apply(&self, rgb: [u8; 3], threshold: u16) -> [u8; 3] {
        self.levels(rgb)
            .map(|l| ((l as u32 + threshold as u32) >> 8) as u8)
    }
}
