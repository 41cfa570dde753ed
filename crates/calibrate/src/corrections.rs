//! Colorimeter corrections as ArgyllCMS makes them (`ccxxmake`): a `.ccss` of a display's
//! spectra, a `.ccmx` matrix from paired colorimeter and spectrometer readings; and a
//! simulated colorimeter to make such pairs from a simulated display.
//!
//! **The matrix** `M` (`XYZ_ref ≈ M · XYZ_colorimeter`) is ArgyllCMS's (xicc/ccmx.c,
//! `create_ccmx`): the minimum of the mean over the patches of a weighted CIE94 difference
//! squared, `(0.2·ΔL*)² + (ΔC*/S_C)² + (ΔH*/S_H)²` with `S_C = 1 + 0.048·C̄`,
//! `S_H = 1 + 0.014·C̄`, `C̄ = √(C*₁C*₂)` (lightness weighted down by 5), in CIELAB relative to the
//! reference's brightest patch (taken as the white, and weighted `n/4` times, a quarter of the
//! whole). ArgyllCMS minimises it with Powell's method from the identity; here
//! Levenberg–Marquardt on the residuals `(0.2ΔL*, ΔC*/S_C, ΔH*/S_H)` with the signed hue
//! difference `ΔH* = 2√(C*₁C*₂)·sin(Δh/2)` (whose square is ArgyllCMS's `ΔE² − ΔL² − ΔC²`),
//! started from the least-squares matrix, to a relative change of the sum below 1e-14 —
//! the same minimum.
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
        let inv = rc.inverse().expect("the broadband primaries are independent").0;
        let xc = [0, 1, 2].map(|r| [xyz[0][r], xyz[1][r], xyz[2][r]]);
        c.factory = [0, 1, 2].map(|r| [0, 1, 2].map(|k| (0..3).map(|j| xc[r][j] * inv[j][k]).sum()));
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

/// The correction matrix of paired readings (see the module docs): `refs[i]` the reference
/// (spectrometer) XYZ of patch `i`, `cols[i]` the colorimeter's, both in the same units.
pub fn fit_ccmx(refs: &[[f64; 3]], cols: &[[f64; 3]]) -> Result<CcmxFit> {
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
    let n = refs.len();
    let wix = (0..n)
        .max_by(|&a, &b| refs[a][1].total_cmp(&refs[b][1]))
        .unwrap_or(0);
    let white = refs[wix];
    if !white.iter().all(|v| *v > 0.0) {
        return Err(bad("the brightest reference patch has no positive XYZ".into()));
    }
    let targets: Vec<[f64; 3]> = refs.iter().map(|r| lab(*r, white)).collect();
    let weight = |i: usize| if i == wix { (n as f64 / 4.0).sqrt() } else { 1.0 };
    let resid = |m: &[f64]| -> Vec<f64> {
        let mut r = Vec::with_capacity(3 * n);
        for i in 0..n {
            let mm = [[m[0], m[1], m[2]], [m[3], m[4], m[5]], [m[6], m[7], m[8]]];
            let q = lab(mat_vec(&mm, cols[i]), white);
            let w = weight(i);
            r.extend(residuals(&targets[i], &q).map(|v| v * w));
        }
        r
    };
    let cost = |r: &[f64]| r.iter().map(|v| v * v).sum::<f64>();
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
    for row in 0..3 {
        match solve(ata.clone(), atb[row].to_vec()) {
            Some(x) => ls.extend(x),
            None => break,
        }
    }
    if ls.len() == 9 && ls.iter().all(|v| v.is_finite()) {
        p = ls;
    }
    let mut r = resid(&p);
    let mut c0 = cost(&r);
    let mut mu = 1e-3;
    for _ in 0..500 {
        // forward-difference Jacobian
        let mut jac = vec![vec![0.0; 9]; r.len()];
        for k in 0..9 {
            let h = 1e-7 * p[k].abs().max(1e-3);
            let mut q = p.clone();
            q[k] += h;
            let rq = resid(&q);
            for (row, (a, b)) in jac.iter_mut().zip(rq.iter().zip(&r)) {
                row[k] = (a - b) / h;
            }
        }
        let mut jtj = vec![vec![0.0; 9]; 9];
        let mut jtr = vec![0.0; 9];
        for (row, ri) in jac.iter().zip(&r) {
            for a in 0..9 {
                jtr[a] -= row[a] * ri;
                for b in 0..9 {
                    jtj[a][b] += row[a] * row[b];
                }
            }
        }
        let mut improved = false;
        for _ in 0..30 {
            let mut a = jtj.clone();
            for d in 0..9 {
                a[d][d] += mu * jtj[d][d].max(1e-12);
            }
            let Some(step) = solve(a, jtr.clone()) else {
                mu *= 10.0;
                continue;
            };
            let q: Vec<f64> = p.iter().zip(&step).map(|(a, b)| a + b).collect();
            let rq = resid(&q);
            let c1 = cost(&rq);
            if c1.is_finite() && c1 <= c0 {
                let rel = (c0 - c1) / c0.max(1e-300);
                p = q;
                r = rq;
                c0 = c1;
                mu = (mu / 10.0).max(1e-12);
                improved = rel > 1e-14;
                break;
            }
            mu *= 10.0;
        }
        if !improved {
            break;
        }
    }
    let matrix = [[p[0], p[1], p[2]], [p[3], p[4], p[5]], [p[6], p[7], p[8]]];
    let des: Vec<f64> = (0..n)
        .map(|i| cie94(targets[i], lab(mat_vec(&matrix, cols[i]), white)))
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
