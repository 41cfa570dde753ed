//! Where a spectrum's spans break: [`Breaks`] (the values) and [`Layout`] (a marker type that
//! carries them at compile time).
//!
//! Every layout the project uses is a compile-time constant, so the breakpoints live in the type
//! (as palette puts a colour space's white point in the type): `Spectrum<S, C, L>` stores only
//! its `S · C` coefficients, spectra on different layouts are different types (combining them is
//! a compile error, not a run-time check), and the compiler sees the breakpoints as constants.
//! Measured gain and the decision: `docs/performance.md` ("Breakpoints in the type").
//!
//! A new layout is a marker type with a `const` [`Breaks`]:
//!
//! ```
//! use specpoly_core::{Breaks, Layout, Spectrum};
//!
//! #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
//! struct Visible3;
//! impl Layout<3> for Visible3 {
//!     const BREAKS: Breaks<3> = Breaks::from_starts_or_panic([380.0, 480.0, 600.0]);
//! }
//! let one = Spectrum::<3, 4, Visible3>::constant(1.0);
//! assert!((one.integral() - 400.0).abs() < 1e-3);
//! ```

use crate::{Error, LAMBDA_MAX, LAMBDA_MIN};
use core::fmt::Debug;

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
    pub const fn from_starts(lo: [f32; S]) -> Result<Self, Error> {
        if S == 0 {
            return Err(Error::Empty);
        }
        if lo[0] != LAMBDA_MIN {
            return Err(Error::OutOfRange);
        }
        let mut s = 0;
        while s < S {
            if !lo[s].is_finite() {
                return Err(Error::NonFinite(s));
            }
            let next = if s + 1 < S { lo[s + 1] } else { LAMBDA_MAX };
            if next <= lo[s] {
                return Err(Error::NotIncreasing(s + 1));
            }
            s += 1;
        }
        Ok(Self {
            lo,
            end: LAMBDA_MAX,
        })
    }

    /// [`Self::from_starts`] for a [`Layout::BREAKS`] constant: bad breakpoints stop the build.
    pub const fn from_starts_or_panic(lo: [f32; S]) -> Self {
        match Self::from_starts(lo) {
            Ok(b) => b,
            Err(_) => panic!("span starts must begin at 380 nm and increase below 780 nm"),
        }
    }

    /// The interval `[a, b]` of span `s`.
    #[inline]
    pub const fn span(&self, s: usize) -> (f32, f32) {
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
pub const PAPER_BREAKS: Breaks<2> = Breaks::from_starts_or_panic([380.0, 550.0]);

/// A spectrum layout known at compile time: a marker type naming `S` spans' breakpoints.
pub trait Layout<const S: usize>:
    Copy + Default + Debug + PartialEq + Eq + Send + Sync + 'static
{
    /// The breakpoints.
    const BREAKS: Breaks<S>;
}

/// `S` equal spans over 380–780 nm (the project default uses 8).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Uniform;

impl<const S: usize> Layout<S> for Uniform {
    const BREAKS: Breaks<S> = Breaks::uniform();
}

/// The paper's two spans, split at 550 nm ([`PAPER_BREAKS`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Paper;

impl Layout<2> for Paper {
    const BREAKS: Breaks<2> = PAPER_BREAKS;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_breaks_cover_the_domain() {
        let b = <Uniform as Layout<8>>::BREAKS;
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
        assert_eq!(PAPER_BREAKS.span(1), (550.0, 780.0));
    }
}
