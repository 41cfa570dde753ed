//! # specpoly-simd
//!
//! The shading kernels — the reduced product ([`Shade::mul`]; for spectra `Spectrum::mul`, the
//! paper's eq. 6) and the integral to XYZ ([`Shade::xyz`]; for spectra `Moments::xyz`) — as
//! AVX2 + FMA kernels chosen at run time, for the host (which has `std` to ask the CPU). The
//! core stays `no_std` and portable: built for the x86-64 baseline its loops vectorise for
//! SSE2, on a Cortex-M they stay scalar; this crate adds a second path beside them.
//!
//! Kernels exist for the presets the renderer and `xyz` use: the default
//! (`Spectrum<8, 4>`, one span per 256-bit lane), the paper's (`Spectrum<2, 4, Paper>`) and,
//! so the speed comparison stays honest, `Sampled<81>` (whose product per call stays the
//! inlined portable one: an element-wise product has nothing to fuse, and returning 324 bytes
//! from an out-of-line kernel costs more than AVX2 saves). They are written with `core::arch`
//! intrinsics because recompiling the core's own code for AVX2 (a `#[target_feature]` wrapper
//! around the inlined portable kernel) was measured 1.7–3× slower per call: the compiler's
//! reductions shuffle lane by lane, and the portable kernels are not always inlined
//! (`docs/performance.md`, "Kernels at the floor").
//!
//! Each also has the product and its integral fused ([`Shade::mul_xyz`], `xyz(a·b, L)`, the
//! renderer's most frequent pair): the product stays in registers, one call instead of two, and
//! the result is bit-identical to the two calls (the same operations).
//!
//! **Accuracy.** Fused multiply-adds and a pairwise horizontal sum round differently from the
//! portable code, so results are not bit-for-bit: each output differs from the portable one by
//! at most [`ULP_BOUND`] units of 2⁻²⁴ times the sum of the magnitudes of the terms that form it
//! (for a product coefficient `Σ|aᵢbⱼ|`/2, for X `Σ|Mₖₛcₖₛ|`), checked by proptest over random
//! spectra in `tests/paths.rs`, which also checks both paths against independent f64 oracles.
//!
//! **Choosing the path.** [`Avx2Fma::detect`] asks the CPU once (`is_x86_feature_detected!`)
//! and caches the answer; [`Wide<T>`] is a [`Shade`] that calls the AVX2 kernel when the CPU has
//! it and `T`'s portable code otherwise, so generic code (the ray tracer, `xyz --repr`) gets the
//! fast path by naming `Wide<DefaultSpectrum>` instead of `DefaultSpectrum`. The environment
//! variable `SPECPOLY_KERNELS=portable` forces the portable path (to measure both in one build).
//! Never build with `-C target-cpu=native`: on Zen 4 it made →XYZ 3.5× slower (AVX-512
//! gathers).
//!
//! **Why `unsafe`, and only in one module.** Calling a `#[target_feature]` function from code
//! compiled without those features is `unsafe` (the caller promises the CPU has them), and so
//! are the intrinsics' loads and stores through pointers. Both are in the private module `x86`:
//! the promise is made through the token [`Avx2Fma`], which exists only after detection
//! succeeded (the pattern of `pulp`'s `V3`); loads and stores take whole `[f32; 8]` arrays. The
//! crate is otherwise `deny(unsafe_code)`. Why by hand rather than `pulp` or `multiversion`:
//! `multiversion` recompiles portable code per target, which is the approach measured too slow
//! above; `pulp`'s safe vector types would carry the same kernels behind a dependency and a
//! generic `Simd` layer, for three kernels of twenty lines.
#![deny(unsafe_code)]
#![deny(unsafe_op_in_unsafe_fn)]
#![warn(missing_docs)]

use specpoly_core::{Error, Observer, Shade, Tabulated, Xyz};

#[cfg(target_arch = "x86_64")]
mod x86;
#[cfg(target_arch = "x86_64")]
pub use x86::Avx2Fma;

#[cfg(not(target_arch = "x86_64"))]
mod other;
#[cfg(not(target_arch = "x86_64"))]
pub use other::Avx2Fma;

/// Bound on the difference between the AVX2 and the portable kernels, in units of 2⁻²⁴ (the
/// f32 unit roundoff, half an ulp at 1) times the sum of the magnitudes of the terms of each
/// output (crate docs). Each path's worst-case rounding error is `n·2⁻²⁴` of that sum for `n`
/// roundings in a chain (Higham 2002, §4.2): at most 7 + 6 for the product, 11 + 7 for the
/// default's →XYZ and 19 + 10 for sampled-81's, so 32 holds for every kernel.
pub const ULP_BOUND: f64 = 32.0;

/// A representation with AVX2 + FMA kernels, called through the proof [`Avx2Fma`] that the CPU
/// has them.
pub trait Kernels: Shade {
    /// `a · b` ([`Shade::mul`]), one call. For `Sampled<81>` this is the portable product
    /// inlined (the same bits): its 324-byte result costs more to return from an AVX2 call
    /// than the AVX2 arithmetic saves (docs/performance.md, "Kernels at the floor").
    fn mul_with(k: Avx2Fma, a: &Self, b: &Self) -> Self;
    /// XYZ of `a` under `light` ([`Shade::xyz`]).
    fn xyz_with(k: Avx2Fma, a: &Self, light: &Self::Light) -> Xyz;
    /// `xyz(a · b, light)` in one call ([`Shade::mul_xyz`]): the product stays in registers,
    /// bit-identical to [`Self::mul_with`] then [`Self::xyz_with`].
    fn mul_xyz_with(k: Avx2Fma, a: &Self, b: &Self, light: &Self::Light) -> Xyz;
    /// `out[i] = a[i] · b[i]` over the shortest of the three, in one AVX2 loop (the kernel
    /// inlined; one check for the batch).
    fn mul_each(k: Avx2Fma, a: &[Self], b: &[Self], out: &mut [Self]);
    /// `out[i] = xyz(a[i], light)` over the shorter of the two, in one AVX2 loop.
    fn xyz_each(k: Avx2Fma, a: &[Self], light: &Self::Light, out: &mut [Xyz]);
}

/// A [`Shade`] value whose product and →XYZ run the AVX2 + FMA kernels when the CPU has them
/// ([`Avx2Fma::detect`]) and `T`'s portable code otherwise (within [`ULP_BOUND`] of each
/// other). Everything else (fits, sums, scaling) is `T`'s own.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(transparent)]
pub struct Wide<T>(pub T);

// `inline(always)`: the renderer calls these in deep generic code where the compiler otherwise
// keeps them out of line, and every call then copies a 128-byte value once more.
impl<T: Kernels> Shade for Wide<T> {
    type Light = T::Light;
    fn light(observer: Observer, light: &Tabulated<'_>) -> Self::Light {
        T::light(observer, light)
    }
    #[inline(always)]
    fn constant(v: f32, light: &Self::Light) -> Self {
        Wide(T::constant(v, light))
    }
    #[inline(always)]
    fn mul(&self, o: &Self) -> Self {
        Wide(match Avx2Fma::detect() {
            Some(k) => T::mul_with(k, &self.0, &o.0),
            None => self.0.mul(&o.0),
        })
    }
    #[inline(always)]
    fn add(&self, o: &Self) -> Self {
        Wide(self.0.add(&o.0))
    }
    #[inline(always)]
    fn scale(&self, k: f32) -> Self {
        Wide(self.0.scale(k))
    }
    #[inline(always)]
    fn xyz(&self, light: &Self::Light) -> Xyz {
        match Avx2Fma::detect() {
            Some(k) => T::xyz_with(k, &self.0, light),
            None => self.0.xyz(light),
        }
    }
    #[inline(always)]
    fn mul_xyz(&self, o: &Self, light: &Self::Light) -> Xyz {
        match Avx2Fma::detect() {
            Some(k) => T::mul_xyz_with(k, &self.0, &o.0, light),
            None => self.0.mul_xyz(&o.0, light),
        }
    }
    fn from_reflectance(r: &Tabulated<'_>, light: &Self::Light) -> Result<Self, Error> {
        T::from_reflectance(r, light).map(Wide)
    }
    fn size() -> usize {
        T::size()
    }
}
