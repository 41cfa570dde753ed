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

use crate::{cheb::Cheb, Error, LAMBDA_MAX, LAMBDA_MIN};

/// Span breakpoints: span `s` covers `[edges[s], edges[s+1]]`, `edges[S] = end`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Breaks<const S: usize> {
    lo: [f32; S],
    end: f32,
}

impl<const S: usize> Breaks<S> {
    /// `S` equal spans over 380–780 nm.
    pub const fn uniform() -> Self {
        const { assert!(S > 0) };
        let mut lo = [0.0; S];
        let mut s = 0;
        while s < S {
            lo[s] = LAMBDA_MIN + (LAMBDA_MAX - LAMBDA_MIN) * s as f32 / S as f32;
            s += 1;
        }
        Self {
            lo,
            end: LAMBDA_MAX,
        }
    }

    /// Breakpoints from the `S` span starts (the first must be 380 nm), ending at 780 nm.
    pub fn from_starts(lo: [f32; S]) -> Result<Self, Error> {
        if S == 0 {
            return Err(Error::Empty);
        }
        if lo[0] != LAMBDA_MIN {
            return Err(Error::OutOfRange);
        }
        for s in 0..S {
            if !lo[s].is_finite() {
                return Err(Error::NonFinite(s));
            }
            let next = if s + 1 < S { lo[s + 1] } else { LAMBDA_MAX };
            if next <= lo[s] {
                return Err(Error::NotIncreasing(s + 1));
            }
        }
        Ok(Self {
            lo,
            end: LAMBDA_MAX,
        })
    }

    /// The interval `[a, b]` of span `s`.
    #[inline]
    pub fn span(&self, s: usize) -> (f32, f32) {
        let b = if s + 1 < S { self.lo[s + 1] } else { self.end };
        (self.lo[s], b)
    }

    /// All `S + 1` breakpoints, in an iterator.
    pub fn points(&self) -> impl Iterator<Item = f32> + '_ {
        self.lo.iter().copied().chain(core::iter::once(self.end))
    }

    /// The span holding `nm` (clamped to the domain) and the local variable `t ∈ [-1, 1]`.
    #[inline]
    pub fn locate(&self, nm: f32) -> (usize, f32) {
        let nm = nm.clamp(LAMBDA_MIN, LAMBDA_MAX);
        let mut s = 0;
        while s + 1 < S && nm >= self.lo[s + 1] {
            s += 1;
        }
        let (a, b) = self.span(s);
        (s, ((2.0 * nm - (a + b)) / (b - a)).clamp(-1.0, 1.0))
    }
}

/// The paper's breakpoints: 380–550–780 nm (§5.2).
pub const PAPER_BREAKS: Breaks<2> = Breaks {
    lo: [380.0, 550.0],
    end: LAMBDA_MAX,
};

/// The paper's representation: 2 cubic spans split at 550 nm.
pub type PaperSpectrum = Spectrum<2, 4>;
/// Number of spans of the project default.
pub const DEFAULT_SPANS: usize = 8;
/// Number of coefficients per span of the project default (cubic).
pub const DEFAULT_COEFFS: usize = 4;
/// The project default: 8 uniform cubic spans (see `docs/accuracy.md` for the choice).
pub type DefaultSpectrum = Spectrum<DEFAULT_SPANS, DEFAULT_COEFFS>;

/// A piecewise polynomial spectrum: `S` spans of `C` Chebyshev coefficients each.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spectrum<const S: usize, const C: usize> {
    breaks: Breaks<S>,
    /// `coef[k][s]`: coefficient of `Tₖ` in span `s`.
    coef: [[f32; S]; C],
}

impl PaperSpectrum {
    /// The paper's layout (2 cubic spans split at 550 nm), zero everywhere.
    pub const fn paper_zero() -> Self {
        Self::zero(PAPER_BREAKS)
    }
}

impl<const S: usize, const C: usize> Spectrum<S, C> {
    /// The zero spectrum on `breaks`.
    pub const fn zero(breaks: Breaks<S>) -> Self {
        Self {
            breaks,
            coef: [[0.0; S]; C],
        }
    }

    /// The constant spectrum `v` on `breaks`.
    pub const fn constant(breaks: Breaks<S>, v: f32) -> Self {
        let mut coef = [[0.0; S]; C];
        let mut s = 0;
        while s < S {
            coef[0][s] = v;
            s += 1;
        }
        Self { breaks, coef }
    }

    /// Builds a spectrum from per-span Chebyshev series.
    pub fn from_spans(breaks: Breaks<S>, spans: [Cheb<C>; S]) -> Self {
        let mut coef = [[0.0; S]; C];
        for (s, p) in spans.iter().enumerate() {
            for k in 0..C {
                coef[k][s] = p.c[k];
            }
        }
        Self { breaks, coef }
    }

    /// The breakpoints.
    pub fn breaks(&self) -> &Breaks<S> {
        &self.breaks
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
    pub fn coefficients(&self) -> &[[f32; S]; C] {
        &self.coef
    }

    /// Mutable raw coefficients, `[k][s]` (used by [`crate::Moments`] and deserialisers).
    pub fn coefficients_mut(&mut self) -> &mut [[f32; S]; C] {
        &mut self.coef
    }

    /// Evaluates at `nm`. Outside 380–780 nm the end values are held; exactly on an interior
    /// breakpoint the mean of the two spans' values is returned (the same convention the
    /// moments use, so a 1 nm sum of `eval` equals [`crate::Moments::xyz`]).
    pub fn eval(&self, nm: f32) -> f32 {
        let (s, t) = self.breaks.locate(nm);
        let v = self.span(s).eval(t);
        if s > 0 && nm == self.breaks.span(s).0 && nm > LAMBDA_MIN {
            0.5 * (v + self.span(s - 1).eval(1.0))
        } else {
            v
        }
    }

    /// Sum (breakpoints must match; checked in debug builds, see [`Self::try_add`]).
    #[inline]
    pub fn add(&self, o: &Self) -> Self {
        debug_assert!(self.breaks == o.breaks, "spectra on different breakpoints");
        let mut r = *self;
        for k in 0..C {
            for s in 0..S {
                r.coef[k][s] += o.coef[k][s];
            }
        }
        r
    }

    /// Sum, checking that the breakpoints match.
    pub fn try_add(&self, o: &Self) -> Result<Self, Error> {
        if self.breaks != o.breaks {
            return Err(Error::BreaksMismatch);
        }
        Ok(self.add(o))
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
        debug_assert!(self.breaks == o.breaks, "spectra on different breakpoints");
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
            let mut cc = [0.0f32; C];
            for i in 0..C {
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
        Self {
            breaks: self.breaks,
            coef: c,
        }
    }

    /// Product, checking that the breakpoints match.
    pub fn try_mul(&self, o: &Self) -> Result<Self, Error> {
        if self.breaks != o.breaks {
            return Err(Error::BreaksMismatch);
        }
        Ok(self.mul(o))
    }

    /// The exact product, with `M ≥ 2C − 1` coefficients per span (checked at compile time).
    pub fn mul_exact<const M: usize>(&self, o: &Self) -> Spectrum<S, M> {
        let mut out = Spectrum::<S, M>::zero(self.breaks);
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
    pub fn truncate<const K: usize>(&self) -> Spectrum<S, K> {
        let mut out = Spectrum::<S, K>::zero(self.breaks);
        for k in 0..K.min(C) {
            out.coef[k] = self.coef[k];
        }
        out
    }

    /// `∫₃₈₀⁷⁸⁰ p(λ) dλ`, exactly: each span contributes `(b − a)/2 · ∫₋₁¹ p(t) dt`.
    pub fn integral(&self) -> f32 {
        (0..S)
            .map(|s| {
                let (a, b) = self.breaks.span(s);
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
    fn uniform_breaks_cover_the_domain() {
        let b = Breaks::<8>::uniform();
        assert_eq!(b.span(0), (380.0, 430.0));
        assert_eq!(b.span(7), (730.0, 780.0));
        assert_eq!(b.locate(780.0), (7, 1.0));
        assert_eq!(b.locate(405.0), (0, 0.0));
    }

    #[test]
    fn bad_breaks_are_rejected() {
        assert_eq!(
            Breaks::<2>::from_starts([380.0, 380.0]),
            Err(Error::NotIncreasing(1))
        );
        assert_eq!(
            Breaks::<2>::from_starts([300.0, 500.0]),
            Err(Error::OutOfRange)
        );
        assert_eq!(
            Breaks::<2>::from_starts([380.0, f32::NAN]),
            Err(Error::NonFinite(1))
        );
    }

    #[test]
    fn integral_of_a_line() {
        // p(λ) on 2 spans equal to t in each span integrates to 0; constant 1 gives 400.
        let one = Spectrum::<2, 4>::constant(PAPER_BREAKS, 1.0);
        assert!((one.integral() - 400.0).abs() < 1e-3);
    }

    #[test]
    fn mismatched_breaks_are_an_error() {
        let a = Spectrum::<2, 4>::constant(PAPER_BREAKS, 1.0);
        let b = Spectrum::<2, 4>::constant(Breaks::uniform(), 1.0);
        assert_eq!(a.try_mul(&b), Err(Error::BreaksMismatch));
        assert_eq!(a.try_add(&b), Err(Error::BreaksMismatch));
    }
}
