//! `Spectrum<S, C>`: a piecewise polynomial over 380–780 nm with `S` spans, each a Chebyshev
//! series with `C` coefficients (degree `C − 1`) in the span's local variable
//! `t = (2λ − (a + b)) / (b − a) ∈ [-1, 1]`.
//!
//! This is the representation of Raso & Fournier (1991, §5): the paper uses `S = 2` cubic spans
//! split at 550 nm ([`PaperSpectrum`]); the project default ([`DefaultSpectrum`]) is 8 uniform
//! cubic spans, chosen from the accuracy/cost table in `docs/accuracy.md`.
//!
//! Storage is coefficient-major (`coef[k][s]` is the `Tₖ` coefficient of span `s`), so the
//! multiply, add and dot products run over spans in lanes that the compiler vectorises.

use crate::{cheb::Cheb, Breaks, Layout, Paper, Uniform, LAMBDA_MIN};
use core::marker::PhantomData;

/// The paper's representation: 2 cubic spans split at 550 nm.
pub type PaperSpectrum = Spectrum<2, 4, Paper>;
/// Number of spans of the project default.
pub const DEFAULT_SPANS: usize = 8;
/// Number of coefficients per span of the project default (cubic).
pub const DEFAULT_COEFFS: usize = 4;
/// The project default: 8 uniform cubic spans (see `docs/accuracy.md` for the choice);
/// 128 bytes, `8 × 4` f32.
pub type DefaultSpectrum = Spectrum<DEFAULT_SPANS, DEFAULT_COEFFS, Uniform>;

/// A piecewise polynomial spectrum: `S` spans of `C` Chebyshev coefficients each, on the
/// breakpoints of layout `L` ([`Uniform`] unless named).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spectrum<const S: usize, const C: usize, L: Layout<S> = Uniform> {
    /// `coef[k][s]`: coefficient of `Tₖ` in span `s`.
    coef: [[f32; S]; C],
    layout: PhantomData<L>,
}

impl<const S: usize, const C: usize, L: Layout<S>> Default for Spectrum<S, C, L> {
    fn default() -> Self {
        Self::ZERO
    }
}

impl<const S: usize, const C: usize, L: Layout<S>> Spectrum<S, C, L> {
    /// The breakpoints of this layout.
    pub const BREAKS: Breaks<S> = L::BREAKS;

    /// The zero spectrum.
    pub const ZERO: Self = Self::from_coefficients([[0.0; S]; C]);

    /// The constant spectrum `v`.
    pub const fn constant(v: f32) -> Self {
        let mut coef = [[0.0; S]; C];
        if C > 0 {
            coef[0] = [v; S];
        }
        Self::from_coefficients(coef)
    }

    /// From raw coefficients, `coef[k][s]` the `Tₖ` coefficient of span `s`.
    pub const fn from_coefficients(coef: [[f32; S]; C]) -> Self {
        Self {
            coef,
            layout: PhantomData,
        }
    }

    /// Builds a spectrum from per-span Chebyshev series.
    pub fn from_spans(spans: [Cheb<C>; S]) -> Self {
        let mut coef = [[0.0; S]; C];
        for (s, p) in spans.iter().enumerate() {
            for k in 0..C {
                coef[k][s] = p.c[k];
            }
        }
        Self::from_coefficients(coef)
    }

    /// The breakpoints (the layout's, [`Self::BREAKS`]).
    pub const fn breaks(&self) -> Breaks<S> {
        L::BREAKS
    }

    /// The series of span `s`.
    pub fn span(&self, s: usize) -> Cheb<C> {
        let mut c = [0.0; C];
        for (k, v) in c.iter_mut().enumerate() {
            *v = self.coef[k][s];
        }
        Cheb { c }
    }

    /// The raw coefficients, `[k][s]`.
    pub const fn coefficients(&self) -> &[[f32; S]; C] {
        &self.coef
    }

    /// Mutable raw coefficients, `[k][s]` (used by fitting and deserialisers).
    pub fn coefficients_mut(&mut self) -> &mut [[f32; S]; C] {
        &mut self.coef
    }

    /// Evaluates at `nm`. Outside 380–780 nm the end values are held; exactly on an interior
    /// breakpoint the mean of the two spans' values is returned (the same convention the
    /// moments use, so a 1 nm sum of `eval` equals [`crate::Moments::xyz`]).
    pub fn eval(&self, nm: f32) -> f32 {
        let (s, t) = L::BREAKS.locate(nm);
        let v = self.span(s).eval(t);
        if s > 0 && nm == L::BREAKS.span(s).0 && nm > LAMBDA_MIN {
            0.5 * (v + self.span(s - 1).eval(1.0))
        } else {
            v
        }
    }

    /// Sum.
    #[inline]
    pub fn add(&self, o: &Self) -> Self {
        let mut r = *self;
        for k in 0..C {
            for s in 0..S {
                r.coef[k][s] += o.coef[k][s];
            }
        }
        r
    }

    /// Scalar multiple.
    #[inline]
    pub fn scale(&self, f: f32) -> Self {
        let mut r = *self;
        for row in r.coef.iter_mut() {
            for v in row.iter_mut() {
                *v *= f;
            }
        }
        r
    }

    /// Product reduced back to degree `C − 1` in every span: the paper's eq. 6, which in the
    /// Chebyshev basis is the exact product with the coefficients of degree ≥ `C` dropped.
    /// The error is at most the sum of the dropped coefficients' magnitudes
    /// (see [`Self::mul_exact`] and [`Cheb::tail_bound`]).
    #[inline]
    pub fn mul(&self, o: &Self) -> Self {
        const { assert!(C > 0) };
        let a = &self.coef;
        let b = &o.coef;
        let mut c = [[0.0f32; S]; C];
        // Tᵢ·Tⱼ = ½(Tᵢ₊ⱼ + T|ᵢ₋ⱼ|), span by span. The i, j loops have constant trip counts
        // and unroll completely; the span loop then vectorises over the coefficient-major
        // storage (measured: 3.7× faster than a symmetric i < j form, docs/performance.md).
        for s in 0..S {
            let mut ac = [0.0f32; C];
            let mut bc = [0.0f32; C];
            for k in 0..C {
                ac[k] = a[k][s];
                bc[k] = b[k][s];
            }
            // Row i = 0 first, assigned rather than added to zero: T₀·Tⱼ puts a₀bⱼ twice on
            // Tⱼ. (`0.0 + p` cannot be folded in IEEE arithmetic, −0 + 0 being +0.)
            let mut cc = [0.0f32; C];
            for j in 0..C {
                let p = ac[0] * bc[j];
                cc[j] = p + p;
            }
            for i in 1..C {
                for j in 0..C {
                    let p = ac[i] * bc[j];
                    if i + j < C {
                        cc[i + j] += p;
                    }
                    cc[i.abs_diff(j)] += p;
                }
            }
            for k in 0..C {
                c[k][s] = 0.5 * cc[k];
            }
        }
        Self::from_coefficients(c)
    }

    /// The exact product, with `M ≥ 2C − 1` coefficients per span (checked at compile time).
    pub fn mul_exact<const M: usize>(&self, o: &Self) -> Spectrum<S, M, L> {
        let mut out = Spectrum::<S, M, L>::ZERO;
        for s in 0..S {
            let p = self.span(s).mul_exact::<M>(&o.span(s));
            for k in 0..M {
                out.coef[k][s] = p.c[k];
            }
        }
        out
    }

    /// Keeps the first `K` coefficients of each span (a plain Chebyshev truncation when
    /// `K < C`, zero padding when `K > C`).
    pub fn truncate<const K: usize>(&self) -> Spectrum<S, K, L> {
        let mut out = Spectrum::<S, K, L>::ZERO;
        for k in 0..K.min(C) {
            out.coef[k] = self.coef[k];
        }
        out
    }

    /// `∫₃₈₀⁷⁸⁰ p(λ) dλ`, exactly: each span contributes `(b − a)/2 · ∫₋₁¹ p(t) dt`.
    pub fn integral(&self) -> f32 {
        (0..S)
            .map(|s| {
                let (a, b) = L::BREAKS.span(s);
                0.5 * (b - a) * self.span(s).integral()
            })
            .sum()
    }

    /// Total number of coefficients (`S · C`): the representation's size.
    pub const fn len() -> usize {
        S * C
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integral_of_a_line() {
        // constant 1 on the paper's 2 spans integrates to 400.
        let one = PaperSpectrum::constant(1.0);
        assert!((one.integral() - 400.0).abs() < 1e-3);
    }

    #[test]
    fn the_default_is_its_coefficients_only() {
        assert_eq!(core::mem::size_of::<DefaultSpectrum>(), 128);
        assert_eq!(core::mem::size_of::<PaperSpectrum>(), 32);
    }
}
