//! The inverse of a calibration's model: device RGB for a wanted XYZ.
//!
//! The forward model `f(rgb) = M · t(rgb) + k + L(rgb)` (see [`super::lattice`]) is evaluated
//! in f64 from the file's values. Its inverse has no closed form once `L` is present, so it
//! is solved: start from the matrix model's inverse (`t⁻¹(M⁻¹ (XYZ − k))`, each channel
//! clamped to `[0, 1]`), then Levenberg–Marquardt steps on `‖f(rgb) − XYZ‖²` (errors scaled
//! by the white's luminance), each step kept inside the cube `[0, 1]³`, with a central-
//! difference Jacobian (`h = 10⁻⁶`; the curves are piecewise linear, the lattice trilinear).
//! Inside the gamut it converges to `f(rgb) = XYZ` within 10⁻¹⁰ of the white's luminance;
//! outside, to the nearest prediction the cube allows.

use super::super::file::{Calibration, TransferKind};

/// The forward model in f64.
pub struct Forward<'a> {
    cal: &'a Calibration,
    m: [[f64; 3]; 3],
}

impl<'a> Forward<'a> {
    /// The model of `cal`.
    pub fn new(cal: &'a Calibration) -> Self {
        Forward {
            cal,
            m: cal.matrix(),
        }
    }

    /// Each channel's linear light (f64; the same curve the calibration's display uses).
    pub fn linear(&self, rgb: [f64; 3]) -> [f64; 3] {
        let t = &self.cal.data().transfer;
        [0, 1, 2].map(|c| {
            let v = if rgb[c].is_nan() {
                0.0
            } else {
                rgb[c].clamp(0.0, 1.0)
            };
            match t.kind {
                TransferKind::Gamma => v.powf(t.gamma[c]),
                TransferKind::Table => {
                    let tab = t.tables()[c];
                    let n = tab.len();
                    let x = v * (n - 1) as f64;
                    let i = (x as usize).min(n - 2);
                    let f = x - i as f64;
                    tab[i] + (tab[i + 1] - tab[i]) * f
                }
            }
        })
    }

    /// Predicted XYZ.
    pub fn xyz(&self, rgb: [f64; 3]) -> [f64; 3] {
        let t = self.linear(rgb);
        let d = self.cal.data();
        let l = d.interaction.as_ref().map(|l| l.eval(rgb));
        [0, 1, 2].map(|r| {
            self.m[r][0] * t[0]
                + self.m[r][1] * t[1]
                + self.m[r][2] * t[2]
                + d.black[r]
                + l.map_or(0.0, |l| l[r])
        })
    }
}

/// Device RGB whose predicted XYZ is `xyz` (see the module docs).
pub fn inverse(cal: &Calibration, xyz: [f64; 3]) -> [f64; 3] {
    let f = Forward::new(cal);
    let scale = cal.data().white[1].abs().max(f64::MIN_POSITIVE);
    // the matrix model's inverse as the start
    let d = cal.display();
    let k = cal.data().black;
    let lin = d.xyz_to_linear(specpoly_core::Xyz::new(
        (xyz[0] - k[0]) as f32,
        (xyz[1] - k[1]) as f32,
        (xyz[2] - k[2]) as f32,
    ));
    let mut x = [0, 1, 2].map(|c| {
        let v = d.transfer()[c].encode(lin[c]) as f64;
        if v.is_finite() {
            v
        } else {
            0.5
        }
    });
    let resid = |x: [f64; 3]| -> [f64; 3] {
        let p = f.xyz(x);
        [0, 1, 2].map(|r| (p[r] - xyz[r]) / scale)
    };
    let norm = |r: [f64; 3]| r.iter().map(|v| v * v).sum::<f64>();
    let mut r = resid(x);
    let mut cost = norm(r);
    let mut mu = 1e-3;
    const H: f64 = 1e-6;
    for _ in 0..200 {
        if !(cost > 1e-20) {
            break;
        }
        // central-difference Jacobian, one-sided at the cube's faces
        let mut j = [[0.0; 3]; 3];
        for c in 0..3 {
            let (mut lo, mut hi) = (x, x);
            lo[c] = (x[c] - H).max(0.0);
            hi[c] = (x[c] + H).min(1.0);
            let (a, b) = (resid(lo), resid(hi));
            let h = hi[c] - lo[c];
            for row in 0..3 {
                j[row][c] = (b[row] - a[row]) / h;
            }
        }
        // (JᵀJ + μ·diag(JᵀJ) + ε) δ = −Jᵀ r
        let mut a = [[0.0; 3]; 3];
        let mut g = [0.0; 3];
        for p in 0..3 {
            for q in 0..3 {
                a[p][q] = (0..3).map(|row| j[row][p] * j[row][q]).sum();
            }
            g[p] = -(0..3).map(|row| j[row][p] * r[row]).sum::<f64>();
        }
        let mut improved = false;
        for _ in 0..30 {
            let mut m = a;
            for p in 0..3 {
                m[p][p] += mu * a[p][p].max(1e-12) + 1e-15;
            }
            let mut step = g;
            if specpoly_core::solve::solve(m.as_flattened_mut(), &mut step).is_err() {
                mu *= 10.0;
                continue;
            }
            let xn = [0, 1, 2].map(|c| (x[c] + step[c]).clamp(0.0, 1.0));
            let rn = resid(xn);
            let cn = norm(rn);
            if cn < cost {
                let moved = (0..3).map(|c| (xn[c] - x[c]).abs()).fold(0.0, f64::max);
                x = xn;
                r = rn;
                cost = cn;
                mu = (mu / 3.0).max(1e-12);
                improved = moved > 1e-15;
                break;
            }
            mu *= 4.0;
        }
        if !improved {
            break;
        }
    }
    x
}
