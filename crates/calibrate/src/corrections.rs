//! Colorimeter corrections as ArgyllCMS makes them (`ccxxmake`): a `.ccss` of a display's
//! spectra, a `.ccmx` matrix from paired colorimeter and spectrometer readings; and a
//! simulated colorimeter to make such pairs from a simulated display.
//!
//! **The matrix** `M` (`XYZ_ref ≈ M · XYZ_colorimeter`) is ArgyllCMS's (xicc/ccmx.c,
//! `create_ccmx`): the minimum of the mean over the patches of a weighted CIE94 difference
//! squared, `(0.2·ΔL*)² + (ΔC*/S_C)² + (ΔH*/S_H)²` with `S_C = 1 + 0.048·C̄`,
//! `S_H = 1 + 0.014·C̄`, `C̄ = √(C*₁C*₂)` (lightness weighted down by 5), in CIELAB relative to the
//! reference's brightest patch (taken as the white, and weighted `n/4` times, a quarter of the
//! whole). ArgyllCMS minimises it with Powell's method from the identity; here BFGS with
//! central-difference gradients from the least-squares matrix, to a gradient below 1e-11 (the
//! hue term is written `ΔH* = 2√(C*₁C*₂)·sin(Δh/2)`, whose square is ArgyllCMS's
//! `ΔE² − ΔL² − ΔC²`) — the same minimum. (Gauss–Newton crawls here: `ΔC*` of the greys is a
//! cone at the neutral axis.)
//!
//! **The simulated colorimeter** has three filters shaped like the CIE 1931 functions as
//! Wyman, Sloan & Shirley fit them (JCGT 2(2), 2013: piecewise Gaussians, negative lobe of
//! x̄ dropped since a filter cannot transmit less than nothing) but each lobe's peak moved
//! (x̄'s long lobe +6 nm, ȳ +4 nm, z̄ −3 nm): a real colorimeter's filters miss the CIE functions
//! by about that much. Its factory matrix maps the raw responses to XYZ exactly on the
//! `broadband` display's primaries (a factory calibration on a wide-band reference), so it
//! reads broadband displays right and narrow-band ones wrong: what a `.ccmx` or `.ccss`
//! corrects.

use crate::error::{Error, Result};
use crate::sim::{spectrum_xyz, SimModel, KM};
use specpoly_core::Observer;

/// A simulated three-filter colorimeter.
#[derive(Clone, Debug, PartialEq)]
pub struct Colorimeter {
    /// The filters' responses at 380…780 nm (1 nm).
    pub filters: Vec<[f64; 3]>,
    /// The factory matrix: raw responses → XYZ.
    pub factory: [[f64; 3]; 3],
}

/// Wyman et al.'s asymmetric Gaussian.
fn g(nm: f64, mu: f64, s1: f64, s2: f64) -> f64 {
    let s = if nm < mu { s1 } else { s2 };
    (-0.5 * ((nm - mu) / s).powi(2)).exp()
}

fn mat_vec(m: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|r| (0..3).map(|c| m[r][c] * v[c]).sum())
}

impl Colorimeter {
    /// The simulated colorimeter (see the module docs).
    pub fn simulated() -> Self {
        let filters: Vec<[f64; 3]> = (380..=780)
            .map(|n| {
                let nm = n as f64;
                [
                    1.056 * g(nm, 599.8 + 6.0, 37.9, 31.0) + 0.362 * g(nm, 442.0, 16.0, 26.7),
                    0.821 * g(nm, 568.8 + 4.0, 46.9, 40.5) + 0.286 * g(nm, 530.9 + 4.0, 16.3, 31.1),
                    1.217 * g(nm, 437.0 - 3.0, 11.8, 36.0) + 0.681 * g(nm, 459.0 - 3.0, 26.0, 13.8),
                ]
            })
            .collect();
        let mut c = Self {
            filters,
            factory: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        };
        // factory calibration on the broadband primaries: factory · raw = XYZ for each
        let reference = SimModel::parse("broadband").expect("the built-in display parses");
        let raw = [0, 1, 2].map(|i| c.raw(&reference.spectra[i]));
        let xyz = [0, 1, 2].map(|i| spectrum_xyz(Observer::Cie1931, &reference.spectra[i]));
        // factory = XYZ_cols · raw_cols⁻¹
        let rc = specpoly_core::Mat3([0, 1, 2].map(|r| [raw[0][r], raw[1][r], raw[2][r]]));
        let inv = rc
            .inverse()
            .expect("the broadband primaries are independent")
            .0;
        let xc = [0, 1, 2].map(|r| [xyz[0][r], xyz[1][r], xyz[2][r]]);
        c.factory =
            [0, 1, 2].map(|r| [0, 1, 2].map(|k| (0..3).map(|j| xc[r][j] * inv[j][k]).sum()));
        c
    }

    /// The raw filter responses to a spectrum at 380…780 nm.
    pub fn raw(&self, s: &[f64]) -> [f64; 3] {
        let mut out = [0.0; 3];
        for (v, f) in s.iter().zip(&self.filters) {
            for k in 0..3 {
                out[k] += v * f[k];
            }
        }
        out.map(|v| v * KM)
    }

    /// The colorimeter's XYZ reading of a spectrum.
    pub fn read(&self, s: &[f64]) -> [f64; 3] {
        mat_vec(&self.factory, self.raw(s))
    }
}

/// ArgyllCMS's `icmXYZ2Lab` (CIELAB relative to `white`).
fn lab(xyz: [f64; 3], white: [f64; 3]) -> [f64; 3] {
    let f = |t: f64| {
        if t > 0.008856451586 {
            t.cbrt()
        } else {
            7.787036979 * t + 16.0 / 116.0
        }
    };
    let [fx, fy, fz] = [0, 1, 2].map(|k| f(xyz[k] / white[k]));
    [116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)]
}

/// The weighted CIE94 residuals of ArgyllCMS's fit (see the module docs).
fn residuals(p: &[f64; 3], q: &[f64; 3]) -> [f64; 3] {
    let dl = p[0] - q[0];
    let c1 = p[1].hypot(p[2]);
    let c2 = q[1].hypot(q[2]);
    let c12 = (c1 * c2).sqrt();
    let dc = c2 - c1;
    let mut dh_angle = q[2].atan2(q[1]) - p[2].atan2(p[1]);
    while dh_angle > std::f64::consts::PI {
        dh_angle -= std::f64::consts::TAU;
    }
    while dh_angle < -std::f64::consts::PI {
        dh_angle += std::f64::consts::TAU;
    }
    let dh = 2.0 * c12 * (dh_angle / 2.0).sin();
    [0.2 * dl, dc / (1.0 + 0.048 * c12), dh / (1.0 + 0.014 * c12)]
}

/// CIE94 ΔE (graphic arts, ArgyllCMS's `icmCIE94`).
fn cie94(p: [f64; 3], q: [f64; 3]) -> f64 {
    let dl = p[0] - q[0];
    let c1 = p[1].hypot(p[2]);
    let c2 = q[1].hypot(q[2]);
    let dc = c2 - c1;
    let de2 = dl * dl + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2);
    let dh2 = (de2 - dl * dl - dc * dc).max(0.0);
    let c12 = (c1 * c2).sqrt();
    let sc = 1.0 + 0.045 * c12;
    let sh = 1.0 + 0.015 * c12;
    (dl * dl + dc * dc / (sc * sc) + dh2 / (sh * sh)).sqrt()
}

/// A fitted correction matrix and its errors on the patches it was fitted to.
#[derive(Clone, Debug, PartialEq)]
pub struct CcmxFit {
    /// `XYZ_ref ≈ matrix · XYZ_colorimeter`, by rows.
    pub matrix: [[f64; 3]; 3],
    /// Mean CIE94 ΔE after correction.
    pub mean_de94: f64,
    /// Largest CIE94 ΔE after correction.
    pub max_de94: f64,
}

/// Solves the 9×9 (or any n×n) system `a·x = b` by Gaussian elimination with partial pivoting.
fn solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Option<Vec<f64>> {
    let n = b.len();
    for c in 0..n {
        let p = (c..n).max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))?;
        if !(a[p][c].abs() > 1e-300) {
            return None;
        }
        a.swap(c, p);
        b.swap(c, p);
        for r in c + 1..n {
            let f = a[r][c] / a[c][c];
            for k in c..n {
                a[r][k] -= f * a[c][k];
            }
            b[r] -= f * b[c];
        }
    }
    let mut x = vec![0.0; n];
    for r in (0..n).rev() {
        let s: f64 = (r + 1..n).map(|k| a[r][k] * x[k]).sum();
        x[r] = (b[r] - s) / a[r][r];
    }
    Some(x)
}

/// The central-difference gradient of `f` at `x`.
fn gradient(f: &dyn Fn(&[f64]) -> f64, x: &[f64]) -> Vec<f64> {
    (0..x.len())
        .map(|k| {
            let h = 1e-6 * x[k].abs().max(1e-2);
            let mut a = x.to_vec();
            let mut b = x.to_vec();
            a[k] += h;
            b[k] -= h;
            (f(&a) - f(&b)) / (2.0 * h)
        })
        .collect()
}

/// The minimum of `f` from `x` by BFGS with a backtracking (Armijo) line search, to a gradient
/// below 1e-11 or no further decrease (at most 5000 steps).
fn bfgs(f: &dyn Fn(&[f64]) -> f64, mut x: Vec<f64>) -> Vec<f64> {
    let n = x.len();
    let mut h: Vec<Vec<f64>> = (0..n)
        .map(|i| (0..n).map(|j| if i == j { 1.0 } else { 0.0 }).collect())
        .collect();
    let mut fx = f(&x);
    let mut g = gradient(f, &x);
    for _ in 0..5000 {
        if g.iter().map(|v| v.abs()).fold(0.0, f64::max) < 1e-11 {
            break;
        }
        let d: Vec<f64> = (0..n)
            .map(|i| -(0..n).map(|j| h[i][j] * g[j]).sum::<f64>())
            .collect();
        let mut slope: f64 = d.iter().zip(&g).map(|(a, b)| a * b).sum();
        let d = if slope < 0.0 {
            d
        } else {
            // not a descent direction: restart along the gradient
            for (i, row) in h.iter_mut().enumerate() {
                for (j, v) in row.iter_mut().enumerate() {
                    *v = if i == j { 1.0 } else { 0.0 };
                }
            }
            slope = -g.iter().map(|v| v * v).sum::<f64>();
            g.iter().map(|v| -v).collect()
        };
        let mut alpha = 1.0;
        let mut next = None;
        for _ in 0..60 {
            let xn: Vec<f64> = x.iter().zip(&d).map(|(a, b)| a + alpha * b).collect();
            let fn_ = f(&xn);
            if fn_.is_finite() && fn_ <= fx + 1e-4 * alpha * slope {
                next = Some((xn, fn_));
                break;
            }
            alpha *= 0.5;
        }
        let Some((xn, fn_)) = next else { break };
        let gn = gradient(f, &xn);
        let s: Vec<f64> = xn.iter().zip(&x).map(|(a, b)| a - b).collect();
        let y: Vec<f64> = gn.iter().zip(&g).map(|(a, b)| a - b).collect();
        let sy: f64 = s.iter().zip(&y).map(|(a, b)| a * b).sum();
        if sy > 1e-300 {
            // H ← (I − ρsyᵀ) H (I − ρysᵀ) + ρssᵀ
            let rho = 1.0 / sy;
            let hy: Vec<f64> = (0..n)
                .map(|i| (0..n).map(|j| h[i][j] * y[j]).sum())
                .collect();
            let yhy: f64 = y.iter().zip(&hy).map(|(a, b)| a * b).sum();
            for i in 0..n {
                for j in 0..n {
                    h[i][j] +=
                        rho * ((1.0 + rho * yhy) * s[i] * s[j] - hy[i] * s[j] - s[i] * hy[j]);
                }
            }
        }
        let done = fx - fn_ <= 1e-16 * fx.abs();
        x = xn;
        fx = fn_;
        g = gn;
        if done {
            break;
        }
    }
    x
}

/// Paired readings checked, with what the objective needs.
struct Problem<'a> {
    cols: &'a [[f64; 3]],
    targets: Vec<[f64; 3]>,
    white: [f64; 3],
    wix: usize,
}

impl<'a> Problem<'a> {
    fn new(refs: &[[f64; 3]], cols: &'a [[f64; 3]]) -> Result<Self> {
        let bad = |why: String| Error::Correction { why };
        if refs.len() != cols.len() {
            return Err(bad(format!(
                "{} reference readings for {} colorimeter readings (the same patches, in the same order)",
                refs.len(),
                cols.len()
            )));
        }
        if refs.len() < 3 {
            return Err(bad(format!(
                "{} patches (3 at least: white and the primaries)",
                refs.len()
            )));
        }
        if let Some(v) = refs.iter().chain(cols).flatten().find(|v| !v.is_finite()) {
            return Err(bad(format!("a reading has the non-finite value {v}")));
        }
        let wix = (0..refs.len())
            .max_by(|&a, &b| refs[a][1].total_cmp(&refs[b][1]))
            .unwrap_or(0);
        let white = refs[wix];
        if !white.iter().all(|v| *v > 0.0) {
            return Err(bad(
                "the brightest reference patch has no positive XYZ".into()
            ));
        }
        Ok(Self {
            cols,
            targets: refs.iter().map(|r| lab(*r, white)).collect(),
            white,
            wix,
        })
    }

    /// ArgyllCMS's objective at the matrix `m` (by rows, 9 entries).
    fn objective(&self, m: &[f64]) -> f64 {
        let n = self.cols.len();
        let mm = [[m[0], m[1], m[2]], [m[3], m[4], m[5]], [m[6], m[7], m[8]]];
        (0..n)
            .map(|i| {
                let q = lab(mat_vec(&mm, self.cols[i]), self.white);
                let w = if i == self.wix { n as f64 / 4.0 } else { 1.0 };
                w * residuals(&self.targets[i], &q)
                    .iter()
                    .map(|v| v * v)
                    .sum::<f64>()
            })
            .sum::<f64>()
            / n as f64
    }
}

/// ArgyllCMS's fit objective (see the module docs) of `matrix` on paired readings: what
/// [`fit_ccmx`] minimises, to compare a matrix made elsewhere (`ccxxmake`'s) with ours.
pub fn ccmx_objective(refs: &[[f64; 3]], cols: &[[f64; 3]], matrix: &[[f64; 3]; 3]) -> Result<f64> {
    let p = Problem::new(refs, cols)?;
    Ok(p.objective(&matrix.concat()))
}

/// The correction matrix of paired readings (see the module docs): `refs[i]` the reference
/// (spectrometer) XYZ of patch `i`, `cols[i]` the colorimeter's, both in the same units.
pub fn fit_ccmx(refs: &[[f64; 3]], cols: &[[f64; 3]]) -> Result<CcmxFit> {
    let problem = Problem::new(refs, cols)?;
    let n = refs.len();
    let objective = |m: &[f64]| problem.objective(m);
    // start: the least-squares matrix in XYZ (each row: Σ cols·colsᵀ m_r = Σ cols·ref_r)
    let mut ata = vec![vec![0.0; 3]; 3];
    let mut atb = [[0.0; 3]; 3];
    for (c, r) in cols.iter().zip(refs) {
        for j in 0..3 {
            for k in 0..3 {
                ata[j][k] += c[j] * c[k];
            }
            for row in 0..3 {
                atb[row][j] += c[j] * r[row];
            }
        }
    }
    let mut p = vec![1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
    let mut ls = Vec::new();
    for row in atb {
        match solve(ata.clone(), row.to_vec()) {
            Some(x) => ls.extend(x),
            None => break,
        }
    }
    if ls.len() == 9 && ls.iter().all(|v| v.is_finite()) && objective(&ls) < objective(&p) {
        p = ls;
    }
    let p = bfgs(&objective, p);
    let matrix = [[p[0], p[1], p[2]], [p[3], p[4], p[5]], [p[6], p[7], p[8]]];
    let des: Vec<f64> = (0..n)
        .map(|i| {
            cie94(
                problem.targets[i],
                lab(mat_vec(&matrix, cols[i]), problem.white),
            )
        })
        .collect();
    Ok(CcmxFit {
        matrix,
        mean_de94: des.iter().sum::<f64>() / n as f64,
        max_de94: des.iter().copied().fold(0.0, f64::max),
    })
}

/// The matrix `XYZ_ref = M · XYZ_col` applied.
pub fn apply(m: &[[f64; 3]; 3], xyz: [f64; 3]) -> [f64; 3] {
    mat_vec(m, xyz)
}
