//! The AVX2 + FMA kernels, and the one place that promises the CPU has them.
//!
//! Everything `unsafe` in the crate is here: calls of `#[target_feature]` functions from code
//! compiled without those features (made only through an [`Avx2Fma`], which exists only after
//! detection succeeded) and unaligned vector loads and stores of whole `[f32; 8]` / `[f32; 4]`
//! arrays. The arithmetic intrinsics themselves are safe inside `#[target_feature]` functions.
#![allow(unsafe_code)]

use crate::Kernels;
use core::arch::x86_64::{
    __m128, __m256, _mm256_add_ps, _mm256_castps256_ps128, _mm256_extractf128_ps, _mm256_fmadd_ps,
    _mm256_hadd_ps, _mm256_loadu_ps, _mm256_mul_ps, _mm256_set1_ps, _mm256_setzero_ps, _mm_add_ps,
    _mm_fmadd_ps, _mm_loadu_ps, _mm_mul_ps, _mm_set1_ps, _mm_storeu_ps,
};
use specpoly_core::{
    DefaultSpectrum, Moments, Paper, PaperSpectrum, Sampled, SampledLight, Shade, Uniform, Xyz,
};
use std::sync::atomic::{AtomicU8, Ordering};

/// Proof that this CPU has AVX2 and FMA: only [`Avx2Fma::detect`] makes one, so the kernels
/// behind it are safe to call.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Avx2Fma(());

const UNKNOWN: u8 = 0;
const ABSENT: u8 = 1;
const PRESENT: u8 = 2;

/// The cached answer of [`Avx2Fma::detect`].
static DETECTED: AtomicU8 = AtomicU8::new(UNKNOWN);

#[cold]
fn ask_the_cpu() -> u8 {
    let forced_portable = std::env::var_os("SPECPOLY_KERNELS").is_some_and(|v| v == "portable");
    let has = std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma");
    let answer = if has && !forced_portable {
        PRESENT
    } else {
        ABSENT
    };
    DETECTED.store(answer, Ordering::Relaxed);
    answer
}

impl Avx2Fma {
    /// `Some` if this CPU has AVX2 and FMA (and `SPECPOLY_KERNELS=portable` is not set); asked
    /// once, then a cached load.
    #[inline]
    pub fn detect() -> Option<Self> {
        let answer = match DETECTED.load(Ordering::Relaxed) {
            UNKNOWN => ask_the_cpu(),
            a => a,
        };
        (answer == PRESENT).then_some(Avx2Fma(()))
    }
}

// ---- loads and stores of whole arrays ----

#[inline]
#[target_feature(enable = "avx2,fma")]
fn load8(p: &[f32; 8]) -> __m256 {
    // SAFETY: reads exactly the 8 f32 of `p` (unaligned load).
    unsafe { _mm256_loadu_ps(p.as_ptr()) }
}

/// `v` as an array, written as two 128-bit halves: the portable (SSE2) code that receives a
/// kernel's result copies it 16 bytes at a time, and a 16-byte load forwards from a 16-byte
/// store but stalls on half of a 32-byte one (measured: the run-time path's product went from
/// 10.9 to 5.7 ns, docs/performance.md).
#[inline]
#[target_feature(enable = "avx2,fma")]
fn store8(v: __m256) -> [f32; 8] {
    let mut o = [0.0f32; 8];
    // SAFETY: writes exactly the 8 f32 of `o`, 4 at a time (unaligned stores).
    unsafe {
        _mm_storeu_ps(o.as_mut_ptr(), _mm256_castps256_ps128(v));
        _mm_storeu_ps(o.as_mut_ptr().add(4), _mm256_extractf128_ps::<1>(v));
    }
    o
}

#[inline]
#[target_feature(enable = "avx2,fma")]
fn load4(p: &[f32; 4]) -> __m128 {
    // SAFETY: reads exactly the 4 f32 of `p` (unaligned load).
    unsafe { _mm_loadu_ps(p.as_ptr()) }
}

#[inline]
#[target_feature(enable = "avx2,fma")]
fn store4(v: __m128) -> [f32; 4] {
    let mut o = [0.0f32; 4];
    // SAFETY: writes exactly the 4 f32 of `o` (unaligned store).
    unsafe { _mm_storeu_ps(o.as_mut_ptr(), v) };
    o
}

// ---- the reduced product of two cubic spans, lane-wise ----

/// `Tᵢ·Tⱼ = ½(Tᵢ₊ⱼ + T|ᵢ₋ⱼ|)` for cubics, the degree ≥ 4 terms dropped (the paper's eq. 6 in
/// the Chebyshev basis), per lane:
///
/// `c₀ = a₀b₀ + ½(a₁b₁ + a₂b₂ + a₃b₃)`, `c₁ = a₀b₁ + a₁b₀ + ½(a₁b₂ + a₂b₁ + a₂b₃ + a₃b₂)`,
/// `c₂ = a₀b₂ + a₂b₀ + ½(a₁b₁ + a₁b₃ + a₃b₁)`, `c₃ = a₀b₃ + a₃b₀ + ½(a₁b₂ + a₂b₁)`:
/// 16 products, 20 of them in fused multiply-adds, 4 halvings.
macro_rules! cubic_product {
    ($a:expr, $b:expr, $fma:ident, $mul:ident, $splat:ident) => {{
        let [a0, a1, a2, a3] = $a;
        let [b0, b1, b2, b3] = $b;
        let half = $splat(0.5);
        let h0 = $fma(a1, b1, $fma(a2, b2, $mul(a3, b3)));
        let h1 = $fma(a1, b2, $fma(a2, b1, $fma(a2, b3, $mul(a3, b2))));
        let h2 = $fma(a1, b1, $fma(a1, b3, $mul(a3, b1)));
        let h3 = $fma(a1, b2, $mul(a2, b1));
        [
            $fma(a0, b0, $mul(half, h0)),
            $fma(a0, b1, $fma(a1, b0, $mul(half, h1))),
            $fma(a0, b2, $fma(a2, b0, $mul(half, h2))),
            $fma(a0, b3, $fma(a3, b0, $mul(half, h3))),
        ]
    }};
}

/// The sums of the 8 lanes of `x`, `y` and `z`: `[Σx, Σy, Σz]`, each as
/// `((x₀+x₁)+(x₂+x₃)) + ((x₄+x₅)+(x₆+x₇))`.
#[inline]
#[target_feature(enable = "avx2,fma")]
fn sum_lanes3(x: __m256, y: __m256, z: __m256) -> [f32; 3] {
    let h = _mm256_hadd_ps(_mm256_hadd_ps(x, y), _mm256_hadd_ps(z, z));
    let s = store4(_mm_add_ps(
        _mm256_castps256_ps128(h),
        _mm256_extractf128_ps::<1>(h),
    ));
    [s[0], s[1], s[2]]
}

// ---- the default preset: 8 uniform cubic spans, one span per lane ----

/// The reduced product's four coefficient rows, in registers.
#[inline]
#[target_feature(enable = "avx2,fma")]
fn product_default(a: &DefaultSpectrum, b: &DefaultSpectrum) -> [__m256; 4] {
    let (a, b) = (a.coefficients(), b.coefficients());
    cubic_product!(
        a.each_ref().map(|r| load8(r)),
        b.each_ref().map(|r| load8(r)),
        _mm256_fmadd_ps,
        _mm256_mul_ps,
        _mm256_set1_ps
    )
}

#[inline]
#[target_feature(enable = "avx2,fma")]
fn mul_default(a: &DefaultSpectrum, b: &DefaultSpectrum) -> DefaultSpectrum {
    DefaultSpectrum::from_coefficients(product_default(a, b).map(|v| store8(v)))
}

#[inline]
#[target_feature(enable = "avx2,fma")]
fn xyz_default(r: &DefaultSpectrum, light: &Moments<8, 4, Uniform>) -> Xyz {
    xyz_rows_default(r.coefficients().each_ref().map(|r| load8(r)), light)
}

/// `xyz(a · b)` with the product kept in registers: the same operations, hence the same bits,
/// as [`mul_default`] then [`xyz_default`].
#[inline]
#[target_feature(enable = "avx2,fma")]
fn mul_xyz_default(
    a: &DefaultSpectrum,
    b: &DefaultSpectrum,
    light: &Moments<8, 4, Uniform>,
) -> Xyz {
    xyz_rows_default(product_default(a, b), light)
}

/// →XYZ of the coefficient rows `c` (one span per lane).
#[inline]
#[target_feature(enable = "avx2,fma")]
fn xyz_rows_default(c: [__m256; 4], light: &Moments<8, 4, Uniform>) -> Xyz {
    let dot = |m: &[[f32; 8]; 4]| {
        let mut acc = _mm256_mul_ps(load8(&m[0]), c[0]);
        for k in 1..4 {
            acc = _mm256_fmadd_ps(load8(&m[k]), c[k], acc);
        }
        acc
    };
    let m = light.moments();
    Xyz::from_array(sum_lanes3(dot(&m[0]), dot(&m[1]), dot(&m[2])))
}

// ---- the paper's preset: 2 cubic spans, 8 coefficients in all ----

/// `[[f32; 2]; 4]` (coefficient-major) as the one `[f32; 8]` it is in memory.
#[inline(always)]
fn flat8(c: &[[f32; 2]; 4]) -> &[f32; 8] {
    c.as_flattened().try_into().unwrap_or(&[0.0; 8])
}

#[inline]
#[target_feature(enable = "avx2,fma")]
fn mul_paper(a: &PaperSpectrum, b: &PaperSpectrum) -> PaperSpectrum {
    // one 128-bit register per coefficient, the two spans in lanes 0 and 1
    let rows = |c: &[[f32; 2]; 4]| c.map(|[x, y]| load4(&[x, y, 0.0, 0.0]));
    let c = cubic_product!(
        rows(a.coefficients()),
        rows(b.coefficients()),
        _mm_fmadd_ps,
        _mm_mul_ps,
        _mm_set1_ps
    );
    PaperSpectrum::from_coefficients(c.map(|v| {
        let [x, y, _, _] = store4(v);
        [x, y]
    }))
}

#[inline]
#[target_feature(enable = "avx2,fma")]
fn xyz_paper(r: &PaperSpectrum, light: &Moments<2, 4, Paper>) -> Xyz {
    let c = load8(flat8(r.coefficients()));
    let m = light.moments();
    let dot = |axis: usize| _mm256_mul_ps(load8(flat8(&m[axis])), c);
    Xyz::from_array(sum_lanes3(dot(0), dot(1), dot(2)))
}

// ---- sampled, 81 wavelengths: ten registers and one sample ----

/// `v` as ten `[f32; 8]` and the last sample.
#[inline(always)]
fn chunks81(v: &[f32; 81]) -> ([&[f32; 8]; 10], f32) {
    (
        core::array::from_fn(|i| v[8 * i..8 * i + 8].try_into().unwrap_or(&[0.0; 8])),
        v[80],
    )
}

#[inline]
#[target_feature(enable = "avx2,fma")]
fn mul_sampled81(a: &Sampled<81>, b: &Sampled<81>) -> Sampled<81> {
    let ((ac, at), (bc, bt)) = (chunks81(&a.0), chunks81(&b.0));
    let mut out = [0.0f32; 81];
    for i in 0..10 {
        out[8 * i..8 * i + 8].copy_from_slice(&store8(_mm256_mul_ps(load8(ac[i]), load8(bc[i]))));
    }
    out[80] = at * bt;
    Sampled(out)
}

#[inline]
#[target_feature(enable = "avx2,fma")]
fn xyz_sampled81(v: &Sampled<81>, light: &SampledLight<81>) -> Xyz {
    let (vc, vt) = chunks81(&v.0);
    let w = light.weights();
    let dot = |w: &[f32; 81]| {
        let (wc, _) = chunks81(w);
        // two chains, so the fused multiply-adds' latency overlaps
        let (mut even, mut odd) = (_mm256_setzero_ps(), _mm256_setzero_ps());
        for i in (0..10).step_by(2) {
            even = _mm256_fmadd_ps(load8(wc[i]), load8(vc[i]), even);
            odd = _mm256_fmadd_ps(load8(wc[i + 1]), load8(vc[i + 1]), odd);
        }
        _mm256_add_ps(even, odd)
    };
    let xyz = sum_lanes3(dot(&w[0]), dot(&w[1]), dot(&w[2]));
    Xyz::from_array(core::array::from_fn(|axis| xyz[axis] + w[axis][80] * vt))
}

#[inline]
#[target_feature(enable = "avx2,fma")]
fn mul_xyz_paper(a: &PaperSpectrum, b: &PaperSpectrum, light: &Moments<2, 4, Paper>) -> Xyz {
    xyz_paper(&mul_paper(a, b), light)
}

#[inline]
#[target_feature(enable = "avx2,fma")]
fn mul_xyz_sampled81(a: &Sampled<81>, b: &Sampled<81>, light: &SampledLight<81>) -> Xyz {
    xyz_sampled81(&mul_sampled81(a, b), light)
}

// ---- the kernels behind the token ----

/// `kernels!(T, mul, xyz, mul_xyz)` implements [`Kernels`] for `T` with these AVX2 kernels;
/// `kernels!(T, mul, xyz, mul_xyz, per_call_product = portable)` keeps `T`'s own (inlined)
/// product for `mul_with` and uses `mul` only inside AVX2 loops (`mul_each`).
macro_rules! kernels {
    ($t:ty, $mul:ident, $xyz:ident, $mul_xyz:ident) => {
        kernels!(@impl $t, $mul, $xyz, $mul_xyz, |a, b| {
            // SAFETY: an `Avx2Fma` exists only if `detect` found AVX2 and FMA on this CPU.
            unsafe { $mul(a, b) }
        });
    };
    ($t:ty, $mul:ident, $xyz:ident, $mul_xyz:ident, per_call_product = portable) => {
        kernels!(@impl $t, $mul, $xyz, $mul_xyz, |a, b| Shade::mul(a, b));
    };
    (@impl $t:ty, $mul:ident, $xyz:ident, $mul_xyz:ident, |$a:ident, $b:ident| $per_call:expr) => {
        impl Kernels for $t {
            #[inline(always)]
            fn mul_with(_: Avx2Fma, $a: &Self, $b: &Self) -> Self {
                $per_call
            }
            #[inline(always)]
            fn xyz_with(_: Avx2Fma, a: &Self, light: &Self::Light) -> Xyz {
                // SAFETY: an `Avx2Fma` exists only if `detect` found AVX2 and FMA on this CPU.
                unsafe { $xyz(a, light) }
            }
            #[inline(always)]
            fn mul_xyz_with(_: Avx2Fma, a: &Self, b: &Self, light: &Self::Light) -> Xyz {
                // SAFETY: an `Avx2Fma` exists only if `detect` found AVX2 and FMA on this CPU.
                unsafe { $mul_xyz(a, b, light) }
            }
            fn mul_each(_: Avx2Fma, a: &[Self], b: &[Self], out: &mut [Self]) {
                #[target_feature(enable = "avx2,fma")]
                fn each(a: &[$t], b: &[$t], out: &mut [$t]) {
                    for ((o, a), b) in out.iter_mut().zip(a).zip(b) {
                        *o = $mul(a, b);
                    }
                }
                // SAFETY: an `Avx2Fma` exists only if `detect` found AVX2 and FMA on this CPU.
                unsafe { each(a, b, out) }
            }
            fn xyz_each(_: Avx2Fma, a: &[Self], light: &Self::Light, out: &mut [Xyz]) {
                #[target_feature(enable = "avx2,fma")]
                fn each(a: &[$t], light: &<$t as Shade>::Light, out: &mut [Xyz]) {
                    for (o, a) in out.iter_mut().zip(a) {
                        *o = $xyz(a, light);
                    }
                }
                // SAFETY: an `Avx2Fma` exists only if `detect` found AVX2 and FMA on this CPU.
                unsafe { each(a, light, out) }
            }
        }
    };
}

kernels!(DefaultSpectrum, mul_default, xyz_default, mul_xyz_default);
kernels!(PaperSpectrum, mul_paper, xyz_paper, mul_xyz_paper);
// Sampled-81's product per call is the portable one, inlined: one multiplication per sample,
// so the same bits, and its 324-byte result returned from an out-of-line AVX2 kernel is copied
// again by the caller (`memcpy`; the compiler cannot build it in place in a slice element):
// through `Wide` 37 ns against 12.8 ns inlined (docs/performance.md, "Kernels at the floor").
// Inside AVX2 loops (`mul_each`) and fused with →XYZ (`mul_xyz_with`) the kernel is used.
kernels!(
    Sampled<81>,
    mul_sampled81,
    xyz_sampled81,
    mul_xyz_sampled81,
    per_call_product = portable
);
