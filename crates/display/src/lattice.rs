//! The channel-interaction correction: a `g × g × g` lattice of XYZ offsets over device RGB,
//! trilinearly interpolated and added to the shaper/matrix model,
//!
//! `XYZ(rgb) = M · (t_R(r), t_G(g), t_B(b)) + k + L(rgb)`.
//!
//! A matrix with per-channel curves assumes that channels add (Cowan 1983); LCD and TN panels
//! break that (crosstalk between neighbouring subpixels, a backlight that sags with the load),
//! and ArgyllCMS answers with a colour lookup table (`colprof -qm`). `L` is that idea kept
//! small: offsets on a coarse lattice (`g ≤` [`MAX_GRID`]) on top of the matrix model, fitted by
//! weighted least squares with a second-difference (thin-plate-like) penalty along each axis,
//! so that nodes no patch touches follow their neighbours. With `g = 2` the correction is
//! multilinear: a constant, `r`, `g`, `b`, `rg`, `rb`, `gb` and `rgb` terms.
//!
//! The normal equations are banded (a node couples only with nodes at most `2g²` apart in
//! index), so they are solved by a banded Cholesky factorisation: `O(n·(2g²)²)` instead of
//! `O(n³)`. It is twenty lines of our own: the general crates that have one (nalgebra,
//! faer) are large for this one call.

use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// The largest lattice side the calibration file accepts.
pub const MAX_GRID: usize = 17;

/// The interaction lattice of a calibration: `values[(i·g + j)·g + k]` is the XYZ offset at
/// device `(i, j, k) / (g − 1)`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Lattice {
    /// Nodes per side (2–[`MAX_GRID`]).
    pub grid: usize,
    /// `grid³` XYZ offsets, red slowest, blue fastest (the calibration's units).
    pub values: Vec<[f64; 3]>,
}

/// The eight lattice nodes around `rgb` (clamped to `[0, 1]`) and their trilinear weights.
pub fn corners(grid: usize, rgb: [f64; 3]) -> [(usize, f64); 8] {
    let g = grid;
    let mut j = [0usize; 3];
    let mut f = [0.0; 3];
    for c in 0..3 {
        let v = rgb[c];
        // NaN → 0
        let x = if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) } * (g - 1) as f64;
        j[c] = (x as usize).min(g - 2);
        f[c] = x - j[c] as f64;
    }
    let mut out = [(0usize, 0.0f64); 8];
    let mut n = 0;
    for a in 0..2 {
        for b in 0..2 {
            for d in 0..2 {
                let idx = ((j[0] + a) * g + j[1] + b) * g + j[2] + d;
                let w = [a, b, d]
                    .iter()
                    .zip(f)
                    .map(|(s, f)| if *s == 1 { f } else { 1.0 - f })
                    .product();
                out[n] = (idx, w);
                n += 1;
            }
        }
    }
    out
}

impl Lattice {
    /// The offset at `rgb`.
    pub fn eval(&self, rgb: [f64; 3]) -> [f64; 3] {
        let mut s = [0.0; 3];
        for (i, w) in corners(self.grid, rgb) {
            for (r, v) in s.iter_mut().enumerate() {
                *v += w * self.values[i][r];
            }
        }
        s
    }

    /// A one-line check: side 2–[`MAX_GRID`], `grid³` finite values.
    pub fn check(&self) -> Result<()> {
        if !(2..=MAX_GRID).contains(&self.grid) {
            return Err(Error::invalid(
                format!("interaction.grid = {}", self.grid),
                format!("must be 2–{MAX_GRID}"),
            ));
        }
        let n = self.grid.pow(3);
        if self.values.len() != n {
            return Err(Error::invalid(
                "interaction.values",
                format!(
                    "has {} entries, grid {} needs {n}",
                    self.values.len(),
                    self.grid
                ),
            ));
        }
        if let Some(i) = self
            .values
            .iter()
            .position(|v| v.iter().any(|x| !x.is_finite()))
        {
            return Err(Error::invalid(
                format!("interaction.values[{i}]"),
                "is not finite",
            ));
        }
        Ok(())
    }
}

/// One patch of the lattice fit: device values, the residual XYZ to explain, and each
/// component's weight.
pub struct Sample {
    /// Device RGB.
    pub device: [f64; 3],
    /// What the lattice should add (measured minus the matrix model).
    pub residual: [f64; 3],
    /// Weights of the X, Y, Z errors.
    pub weight: [f64; 3],
}

/// The relative strength of the smoothness penalty (times the mean diagonal of the data's
/// normal matrix); chosen on the shipped displays' held-out error (docs/calibration.md).
pub const SMOOTHING: f64 = 0.01;

/// Fits a `grid`-sided lattice to the samples by weighted least squares with the
/// second-difference penalty; `None` if the system cannot be solved.
pub fn fit(grid: usize, samples: &[Sample]) -> Option<Lattice> {
    let g = grid;
    let n = g * g * g;
    let bw = (2 * g * g).max(g * g + g + 1);
    let mut values = vec![[0.0; 3]; n];
    for r in 0..3 {
        let mut band = Band::new(n, bw);
        let mut b = vec![0.0; n];
        for s in samples {
            let c = corners(g, s.device);
            let w = s.weight[r];
            for &(i, wi) in &c {
                b[i] += w * wi * s.residual[r];
                for &(j, wj) in &c {
                    band.add(i, j, w * wi * wj);
                }
            }
        }
        let scale = (0..n).map(|i| band.get(i, i)).sum::<f64>() / n as f64;
        if !(scale.is_finite() && scale > 0.0) {
            return None;
        }
        let lambda = SMOOTHING * scale;
        for i in 0..g {
            for j in 0..g {
                for k in 0..g {
                    let p = [i, j, k];
                    for axis in 0..3 {
                        if p[axis] == 0 || p[axis] == g - 1 {
                            continue;
                        }
                        let node = |d: isize| {
                            let mut q = p;
                            q[axis] = (q[axis] as isize + d) as usize;
                            (q[0] * g + q[1]) * g + q[2]
                        };
                        let t = [(node(-1), 1.0), (node(0), -2.0), (node(1), 1.0)];
                        for &(a, wa) in &t {
                            for &(c, wc) in &t {
                                band.add(a, c, lambda * wa * wc);
                            }
                        }
                    }
                }
            }
        }
        for i in 0..n {
            band.add(i, i, 1e-9 * scale);
        }
        let x = band.solve(b)?;
        for i in 0..n {
            values[i][r] = x[i];
        }
    }
    Some(Lattice { grid, values })
}

/// A symmetric positive-definite band matrix: the lower band, `bw` below the diagonal.
struct Band {
    n: usize,
    bw: usize,
    // row i holds columns i − bw ..= i at offsets 0..=bw
    a: Vec<f64>,
}

impl Band {
    fn new(n: usize, bw: usize) -> Band {
        let bw = bw.min(n.saturating_sub(1));
        Band {
            n,
            bw,
            a: vec![0.0; n * (bw + 1)],
        }
    }

    fn at(&self, i: usize, j: usize) -> usize {
        // j ≤ i, i − j ≤ bw
        i * (self.bw + 1) + (self.bw + j - i)
    }

    /// Adds `v` to `A[i][j]` for `i ≥ j`; calls with `i < j` are ignored, so that loops over
    /// both orders of a symmetric term add it once.
    fn add(&mut self, i: usize, j: usize, v: f64) {
        if i >= j {
            let k = self.at(i, j);
            self.a[k] += v;
        }
    }

    fn get(&self, i: usize, j: usize) -> f64 {
        let (i, j) = if i >= j { (i, j) } else { (j, i) };
        self.a[self.at(i, j)]
    }

    /// Cholesky `A = L Lᵀ` in place, then the two triangular solves; `None` if not
    /// positive definite or not finite.
    fn solve(mut self, mut b: Vec<f64>) -> Option<Vec<f64>> {
        let (n, bw) = (self.n, self.bw);
        let w = bw + 1;
        for i in 0..n {
            let j0 = i.saturating_sub(bw);
            for j in j0..=i {
                // Σ_k L[i][k]·L[j][k], k = j0..j: contiguous in both rows
                let ri = i * w + bw - i;
                let rj = j * w + bw - j;
                let dot: f64 = self.a[ri + j0..ri + j]
                    .iter()
                    .zip(&self.a[rj + j0..rj + j])
                    .map(|(p, q)| p * q)
                    .sum();
                let s = self.a[ri + j] - dot;
                if i == j {
                    if !(s > 0.0) {
                        return None;
                    }
                    self.a[ri + j] = s.sqrt();
                } else {
                    self.a[ri + j] = s / self.a[rj + j];
                }
            }
        }
        for i in 0..n {
            let mut s = b[i];
            for k in i.saturating_sub(bw)..i {
                s -= self.get(i, k) * b[k];
            }
            b[i] = s / self.get(i, i);
        }
        for i in (0..n).rev() {
            let mut s = b[i];
            for k in i + 1..(i + bw + 1).min(n) {
                s -= self.get(k, i) * b[k];
            }
            b[i] = s / self.get(i, i);
        }
        b.iter().all(|v| v.is_finite()).then_some(b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The banded solve against the core's dense Gaussian elimination on a random SPD band.
    #[test]
    fn band_solve_matches_dense() {
        let (n, bw) = (30, 5);
        let mut band = Band::new(n, bw);
        let mut dense = vec![0.0; n * n];
        let mut seed = 1u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for i in 0..n {
            for j in i.saturating_sub(bw)..i {
                let v = rnd();
                band.add(i, j, v);
                dense[i * n + j] = v;
                dense[j * n + i] = v;
            }
            band.add(i, i, 4.0);
            dense[i * n + i] = 4.0;
        }
        let b: Vec<f64> = (0..n).map(|_| rnd()).collect();
        let x = band.solve(b.clone()).unwrap();
        let mut y = b;
        specpoly_core::solve::solve(&mut dense, &mut y).unwrap();
        for (a, c) in x.iter().zip(&y) {
            assert!((a - c).abs() < 1e-12, "{a} {c}");
        }
    }

    /// A multilinear function is reproduced exactly by any lattice (trilinear interpolation
    /// and the second-difference penalty both vanish on it).
    #[test]
    fn reproduces_multilinear() {
        let f = |d: [f64; 3]| {
            [
                d[0] * d[1],
                0.5 * d[1] * d[2] - 0.1,
                d[0] * d[1] * d[2] + d[2],
            ]
        };
        let mut samples = Vec::new();
        for i in 0..6 {
            for j in 0..6 {
                for k in 0..6 {
                    let d = [i as f64 / 5.0, j as f64 / 5.0, k as f64 / 5.0];
                    samples.push(Sample {
                        device: d,
                        residual: f(d),
                        weight: [1.0; 3],
                    });
                }
            }
        }
        for g in [2, 3, 5] {
            let l = fit(g, &samples).unwrap();
            l.check().unwrap();
            let d = [0.31, 0.77, 0.52];
            let (a, b) = (l.eval(d), f(d));
            for r in 0..3 {
                assert!((a[r] - b[r]).abs() < 1e-6, "g {g}: {a:?} {b:?}");
            }
        }
    }
}
