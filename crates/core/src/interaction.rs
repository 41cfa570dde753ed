//! Channel interaction: a `g × g × g` lattice of XYZ offsets over device RGB, trilinearly
//! interpolated and added to Cowan's model (Cowan 1983, the paper's §7.3),
//!
//! `XYZ(rgb) = M · (t_R(r), t_G(g), t_B(b)) + black + L(rgb)`.
//!
//! Cowan's model assumes the channels add; LCD and TN panels break that (crosstalk between
//! neighbouring subpixels, a backlight that sags with the load). `L` is the correction the
//! host's fit finds (`specpoly::calibrate::fit::lattice`): node `(i, j, k)` sits at device
//! `(i, j, k) / (g − 1)`, stored red slowest, blue fastest. With `g = 2` the correction is
//! multilinear (a constant and the `r, g, b, rg, rb, gb, rgb` terms).
//!
//! The capacity (nodes) is in the type: `Interaction<{ 17 * 17 * 17 }>` holds any lattice the
//! calibration file accepts, a microcontroller picks a smaller one. Offsets are f32, the
//! kernel type of the display model.

use crate::Error;
use heapless::Vec;

/// The largest lattice side: the calibration file's limit.
pub const GRID_MAX: usize = 17;

/// Nodes of a lattice of side `grid`.
pub const fn nodes(grid: usize) -> usize {
    grid * grid * grid
}

/// A lattice of XYZ offsets over device RGB, at most `CAP` nodes.
#[derive(Clone, Debug, PartialEq)]
pub struct Interaction<const CAP: usize> {
    grid: usize,
    values: Vec<[f32; 3], CAP>,
}

/// The lattice cell around a device colour: the lower corner's node index per axis and the
/// fractions within the cell.
fn cell(grid: usize, rgb: [f32; 3]) -> ([usize; 3], [f32; 3]) {
    let mut j = [0usize; 3];
    let mut f = [0.0f32; 3];
    let top = (grid - 1) as f32;
    for c in 0..3 {
        // NaN → 0
        let v = if rgb[c].is_nan() {
            0.0
        } else {
            rgb[c].clamp(0.0, 1.0)
        };
        let x = v * top;
        j[c] = (x as usize).min(grid - 2);
        f[c] = x - j[c] as f32;
    }
    (j, f)
}

impl<const CAP: usize> Interaction<CAP> {
    /// A lattice of side `grid` (2–[`GRID_MAX`]) from its `grid³` offsets, red slowest: an
    /// [`Error::Capacity`] for another side or count or more than `CAP` nodes, an
    /// [`Error::NonFinite`] (node index) for a NaN or infinite offset.
    pub fn new(grid: usize, values: impl IntoIterator<Item = [f32; 3]>) -> Result<Self, Error> {
        if !(2..=GRID_MAX).contains(&grid) || nodes(grid) > CAP {
            return Err(Error::Capacity);
        }
        let mut v = Vec::new();
        for (i, x) in values.into_iter().enumerate() {
            if x.iter().any(|c| !c.is_finite()) {
                return Err(Error::NonFinite(i));
            }
            v.push(x).map_err(|_| Error::Capacity)?;
        }
        if v.len() != nodes(grid) {
            return Err(Error::Capacity);
        }
        Ok(Self { grid, values: v })
    }

    /// Nodes per side.
    pub fn grid(&self) -> usize {
        self.grid
    }

    /// The offsets, red slowest, blue fastest.
    pub fn values(&self) -> &[[f32; 3]] {
        &self.values
    }

    /// The offset at `rgb` (clamped to `[0, 1]³`; NaN reads as 0).
    pub fn eval(&self, rgb: [f32; 3]) -> [f32; 3] {
        self.eval_with_slope(rgb).0
    }

    /// The offset at `rgb` and its derivatives: `slope[c]` is `∂L/∂rgb[c]` (XYZ), the slope
    /// of the trilinear interpolant inside the cell (at a node, the cell above it; at the top
    /// face, the cell below).
    pub fn eval_with_slope(&self, rgb: [f32; 3]) -> ([f32; 3], [[f32; 3]; 3]) {
        let g = self.grid;
        let (j, f) = cell(g, rgb);
        let top = (g - 1) as f32;
        let mut value = [0.0f32; 3];
        let mut slope = [[0.0f32; 3]; 3];
        for corner in 0..8usize {
            let s = [corner >> 2 & 1, corner >> 1 & 1, corner & 1];
            let idx = ((j[0] + s[0]) * g + j[1] + s[1]) * g + j[2] + s[2];
            let node = self.values[idx];
            // the weight along each axis, and its derivative in device units
            let w = [0, 1, 2].map(|c| if s[c] == 1 { f[c] } else { 1.0 - f[c] });
            let dw = [0, 1, 2].map(|c| if s[c] == 1 { top } else { -top });
            let weight = w[0] * w[1] * w[2];
            let d = [
                dw[0] * w[1] * w[2],
                w[0] * dw[1] * w[2],
                w[0] * w[1] * dw[2],
            ];
            for r in 0..3 {
                value[r] += weight * node[r];
                for c in 0..3 {
                    slope[c][r] += d[c] * node[r];
                }
            }
        }
        (value, slope)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A multilinear function sampled at the nodes is reproduced everywhere (trilinear
    /// interpolation is exact on it), and its slopes are the analytic derivatives.
    #[test]
    fn reproduces_a_multilinear_function_and_its_slopes() {
        let f = |d: [f32; 3]| {
            [
                d[0] * d[1],
                0.5 * d[1] * d[2] - 0.1,
                d[0] * d[1] * d[2] + d[2],
            ]
        };
        let df = |d: [f32; 3]| {
            [
                [d[1], 0.0, d[1] * d[2]],
                [d[0], 0.5 * d[2], d[0] * d[2]],
                [0.0, 0.5 * d[1], d[0] * d[1] + 1.0],
            ]
        };
        for g in [2usize, 3, 5] {
            let vals = (0..nodes(g)).map(|i| {
                let (a, b, c) = (i / (g * g), i / g % g, i % g);
                f([a, b, c].map(|k| k as f32 / (g - 1) as f32))
            });
            let l = Interaction::<125>::new(g, vals).unwrap();
            let d = [0.31, 0.77, 0.52];
            let (v, s) = l.eval_with_slope(d);
            for r in 0..3 {
                assert!((v[r] - f(d)[r]).abs() < 1e-6, "g {g}");
                for c in 0..3 {
                    assert!((s[c][r] - df(d)[c][r]).abs() < 1e-5, "g {g} ∂{c} {r}");
                }
            }
        }
    }

    #[test]
    fn refuses_wrong_sizes_and_non_finite_offsets() {
        assert_eq!(
            Interaction::<8>::new(3, [[0.0; 3]; 27]),
            Err(Error::Capacity)
        );
        assert_eq!(
            Interaction::<27>::new(3, [[0.0; 3]; 26]),
            Err(Error::Capacity)
        );
        assert_eq!(Interaction::<8>::new(1, [[0.0; 3]]), Err(Error::Capacity));
        let mut v = [[0.0f32; 3]; 8];
        v[5][1] = f32::NAN;
        assert_eq!(Interaction::<8>::new(2, v), Err(Error::NonFinite(5)));
        // NaN device values read as 0
        let l = Interaction::<8>::new(2, (0..8).map(|i| [i as f32; 3])).unwrap();
        assert_eq!(l.eval([f32::NAN; 3]), [0.0; 3]);
        assert_eq!(l.eval([1.0; 3]), [7.0; 3]);
    }
}
