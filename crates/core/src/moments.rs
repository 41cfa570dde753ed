//! Moments of the basis functions against a light and an observer, so that the XYZ of any
//! spectrum on the same breakpoints is three dot products.
//!
//! For span `s = [a, b]` and basis function `Tₖ(t(λ))`,
//!
//! `Mₓ[k][s] = K · Σ_λ w(λ) Tₖ(t(λ)) S(λ) x̄(λ)`, and likewise for ȳ, z̄,
//!
//! summed at 1 nm over 380–780 nm, with `S` the light's tabulated power linearly interpolated
//! (never a polynomial fit: §7.1 of the paper), `w = ½` on interior breakpoints (each side takes
//! half) and 1 elsewhere, and `K = 100 / Σ_λ S(λ) ȳ(λ)` so a perfect white has `Y = 100`.
//! Then `X = Σₖ Σₛ Mₓ[k][s] · coef[k][s]` is *exactly* the 1 nm sum of the polynomial spectrum
//! times the light and observer: the only error left is the polynomial's own.
//!
//! The paper instead fitted x̄, ȳ, z̄ by cubics and integrated the degree-6 product analytically
//! (eq. 7); [`crate::paper`] keeps that path for reproduction.

use crate::{cheb::basis_f64, Layout, Observer, Spectrum, Tabulated, Uniform, Xyz};
use core::marker::PhantomData;

/// Precomputed moments for one (observer, light) on the spans of layout `L`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Moments<const S: usize, const C: usize, L: Layout<S> = Uniform> {
    /// `m[axis][k][s]`, axis 0..3 = X, Y, Z.
    m: [[[f32; S]; C]; 3],
    white: Xyz,
    layout: PhantomData<L>,
}

impl<const S: usize, const C: usize, L: Layout<S>> Moments<S, C, L> {
    /// Computes the moments (f64 accumulation, 401 wavelengths).
    pub fn new(observer: Observer, light: &Tabulated<'_>) -> Self {
        Self::from_fn(observer, |nm| light.at(nm))
    }

    /// Computes the moments of a light given as a function of wavelength (nm), sampled at the
    /// same 401 wavelengths: for computed spectra such as a Planckian radiator or CIE daylight.
    pub fn from_fn(observer: Observer, light: impl Fn(f64) -> f64) -> Self {
        let mut acc = [[[0.0f64; S]; C]; 3];
        let mut white = [0.0f64; 3];
        let mut t_k = [0.0f64; C];
        let table = observer.table();
        for (i, cmf) in table.iter().enumerate() {
            let nm = 380.0 + i as f64;
            let power = light(nm);
            let sw = [
                power * cmf[0] as f64,
                power * cmf[1] as f64,
                power * cmf[2] as f64,
            ];
            for (w, v) in white.iter_mut().zip(sw) {
                *w += v;
            }
            for s in 0..S {
                let (a, b) = L::BREAKS.span(s);
                let (a, b) = (a as f64, b as f64);
                if nm < a || nm > b {
                    continue;
                }
                let interior_edge = (nm == a && s > 0) || (nm == b && s + 1 < S);
                let w = if interior_edge { 0.5 } else { 1.0 };
                let t = (2.0 * nm - (a + b)) / (b - a);
                basis_f64(t, &mut t_k);
                for axis in 0..3 {
                    for k in 0..C {
                        acc[axis][k][s] += w * t_k[k] * sw[axis];
                    }
                }
            }
        }
        let norm = if white[1] > 0.0 {
            100.0 / white[1]
        } else {
            0.0
        };
        let mut m = [[[0.0f32; S]; C]; 3];
        for axis in 0..3 {
            for k in 0..C {
                for s in 0..S {
                    m[axis][k][s] = (acc[axis][k][s] * norm) as f32;
                }
            }
        }
        Self::from_parts(
            m,
            Xyz::new((white[0] * norm) as f32, 100.0, (white[2] * norm) as f32),
        )
    }

    /// Moments from their values: `m[axis][k][s]` (axis 0..3 = X, Y, Z) and the XYZ of the
    /// perfect reflector. For tables computed ahead of time (the firmware's `build.rs` writes
    /// the output of [`Self::new`] as `const` calls of this).
    pub const fn from_parts(m: [[[f32; S]; C]; 3], white: Xyz) -> Self {
        Self {
            m,
            white,
            layout: PhantomData,
        }
    }

    /// The moments, `m[axis][k][s]`, axis 0..3 = X, Y, Z.
    pub const fn moments(&self) -> &[[[f32; S]; C]; 3] {
        &self.m
    }

    /// XYZ of the perfect reflector under this light (`Y = 100`).
    pub const fn white(&self) -> Xyz {
        self.white
    }

    /// The weighted sum `Σ wᵢ·Mᵢ` of moments (and of their whites).
    ///
    /// Moments are linear in the light, so for lights `Sᵢ` with unnormalised luminous sums
    /// `Yᵢ = Σ_λ Sᵢ ȳ` and weights `wᵢ = dᵢ·Yᵢ / Σⱼ dⱼ·Yⱼ` this is exactly the normalised moments of
    /// the mixture `Σ dᵢ·Sᵢ` (used for multi-channel LED mixing, `crate::light::mix`).
    pub fn blend(parts: &[(f32, &Self)]) -> Self {
        let mut m = [[[0.0f32; S]; C]; 3];
        let mut white = [0.0f32; 3];
        for (w, p) in parts {
            for axis in 0..3 {
                for k in 0..C {
                    for s in 0..S {
                        m[axis][k][s] += w * p.m[axis][k][s];
                    }
                }
            }
            for (o, v) in white.iter_mut().zip(p.white.to_array()) {
                *o += w * v;
            }
        }
        Self::from_parts(m, Xyz::from_array(white))
    }

    /// XYZ of `r` as a reflectance under the light: three dot products of length `S·C`.
    ///
    /// Each axis sums span lanes: lane `s` is `Σₖ M[k][s]·c[k][s]` in order of `k` from zero.
    /// The span loop is the outer one, so a lane's three axes stay in registers even where the
    /// loops are not unrolled (built for size, 2 016 → 1 085 instructions on the Cortex-M4;
    /// built at `opt-level = 3` in `specpoly-kernels`, 350); the x86-64 compiler vectorises
    /// across the lanes either way (SSE2: 24 `mulps` + 24 `addps`). The lanes are then summed
    /// pairwise: folded in halves down to 4 per axis (one SSE register), then each axis's last
    /// lanes with index loops — no closure, which a large caller would leave out of line
    /// (docs/performance.md, "Kernels at the floor"); for the paper's 2 spans the same sum as
    /// in order. One loop for both targets: 7.6 ns per call on x86-64 (SSE2), 350 instructions
    /// on the Cortex-M4 for the default preset.
    #[inline]
    pub fn xyz(&self, r: &Spectrum<S, C, L>) -> Xyz {
        let c = r.coefficients();
        let m = &self.m;
        // S lane accumulators per axis from zero. Starting them at the k = 0 products instead
        // (no `0.0 + p`) was measured 1.7× slower for 8 spans on x86-64: the loop no longer
        // vectorises (docs/performance.md, "Breakpoints in the type").
        let mut lanes = [[0.0f32; S]; 3];
        for s in 0..S {
            let (mut x, mut y, mut z) = (0.0f32, 0.0f32, 0.0f32);
            for k in 0..C {
                let v = c[k][s];
                x += m[0][k][s] * v;
                y += m[1][k][s] * v;
                z += m[2][k][s] * v;
            }
            lanes[0][s] = x;
            lanes[1][s] = y;
            lanes[2][s] = z;
        }
        let mut n = S;
        while n > 4 && n % 2 == 0 {
            n /= 2;
            for acc in lanes.iter_mut() {
                for l in 0..n {
                    acc[l] += acc[l + n];
                }
            }
        }
        // The last lanes, per axis, with plain index loops: an iterator `sum` or an array
        // `map` is a closure call, and in a large caller (the renderer, the bench) the
        // compiler leaves such closures out of line — three calls per →XYZ, measured 2×
        // slower (docs/performance.md, "Kernels at the floor"). `-0.0 + p` is exactly `p`.
        let mut out = [0.0f32; 3];
        for axis in 0..3 {
            let p = &mut lanes[axis];
            let mut n = n;
            while n > 1 && n % 2 == 0 {
                n /= 2;
                for l in 0..n {
                    p[l] += p[l + n];
                }
            }
            let mut t = -0.0f32;
            for l in 0..n {
                t += p[l];
            }
            out[axis] = t;
        }
        Xyz::new(out[0], out[1], out[2])
    }
}

/// The colour reference: XYZ of reflectance `r` under `light` as a 1 nm f64 sum over 380–780 nm
/// of the linear interpolants, normalised so the perfect white has `Y = 100`.
/// Returns `(XYZ of r, XYZ of the white)`.
pub fn exact_xyz(
    observer: Observer,
    light: &Tabulated<'_>,
    r: impl Fn(f64) -> f64,
) -> ([f64; 3], [f64; 3]) {
    let mut xyz = [0.0f64; 3];
    let mut white = [0.0f64; 3];
    for (i, cmf) in observer.table().iter().enumerate() {
        let nm = 380.0 + i as f64;
        let p = light.at(nm);
        let rv = r(nm);
        for k in 0..3 {
            white[k] += p * cmf[k] as f64;
            xyz[k] += rv * p * cmf[k] as f64;
        }
    }
    let norm = 100.0 / white[1];
    for k in 0..3 {
        xyz[k] *= norm;
        white[k] *= norm;
    }
    (xyz, white)
}
