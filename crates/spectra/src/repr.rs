//! Colour representations a user can pick (`--repr`, `--mode`), and the dispatch from that
//! runtime choice to the generic code, which is monomorphised per representation so every
//! mode runs the same code ([`specpoly_core::Shade`]).
//!
//! - `poly` — the project default, 8 uniform cubic spans ([`specpoly_core::DefaultSpectrum`]);
//! - `paper` — 2 cubic spans split at 550 nm ([`specpoly_core::PaperSpectrum`]);
//! - `poly:SxD` — `S` uniform spans of degree `D`;
//! - `sampled:N` — `N` point samples over 380–780 nm, the light and the colour matching
//!   functions point-sampled at the same wavelengths;
//! - `hero:N` — hero-wavelength sampling (`N` wavelengths drawn per path by the path tracer,
//!   as pbrt-v4 and Mitsuba 3; elsewhere `N` fixed wavelengths), [`crate::hero`] (its binding to a path in `specpoly-render`);
//! - `rgb` — linear sRGB triples (the paper's "RGB problem");
//! - `exact` — the 1 nm reference: 401 samples at 1 nm, identical to the 1 nm sum.

use crate::{Error, Result};
use specpoly_core::{
    DefaultSpectrum, Layout, Paper, PaperSpectrum, Rgb, Sampled, Shade, Spectrum, Uniform,
    DEFAULT_COEFFS, DEFAULT_SPANS,
};
use specpoly_simd::Wide;
use std::fmt;
use std::str::FromStr;

/// A representation of spectra for shading.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Repr {
    /// `S` uniform spans of `C` coefficients (degree `C − 1`). `poly` is the default preset.
    Poly {
        /// Number of spans.
        spans: usize,
        /// Coefficients per span.
        coeffs: usize,
    },
    /// The paper's 2 cubic spans split at 550 nm.
    Paper,
    /// Point samples.
    Sampled(usize),
    /// Hero-wavelength sampling with `N` wavelengths per path.
    Hero(usize),
    /// Linear sRGB.
    Rgb,
    /// The 1 nm reference.
    Exact,
}

impl Repr {
    /// The project default (`poly`).
    pub const DEFAULT: Repr = Repr::Poly {
        spans: DEFAULT_SPANS,
        coeffs: DEFAULT_COEFFS,
    };

    /// Whether the representation is a piecewise polynomial (`poly`, `paper`, `poly:SxD`).
    pub fn is_polynomial(&self) -> bool {
        matches!(self, Repr::Poly { .. } | Repr::Paper)
    }

    /// `self` if it is polynomial, else the usage error saying that `command` needs one.
    pub fn polynomial_for(self, command: &str) -> Result<Repr> {
        if self.is_polynomial() {
            Ok(self)
        } else {
            Err(Error::NotPolynomial {
                command: command.to_string(),
                repr: self,
            })
        }
    }

    /// Number of stored values per colour.
    pub fn size(&self) -> usize {
        match *self {
            Repr::Poly { spans, coeffs } => spans * coeffs,
            Repr::Paper => 8,
            Repr::Sampled(n) | Repr::Hero(n) => n,
            Repr::Rgb => 3,
            Repr::Exact => 401,
        }
    }
}

impl fmt::Display for Repr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            r if r == Repr::DEFAULT => write!(f, "poly"),
            Repr::Poly { spans, coeffs } => write!(f, "poly:{spans}x{}", coeffs - 1),
            Repr::Paper => write!(f, "paper"),
            Repr::Sampled(n) => write!(f, "sampled:{n}"),
            Repr::Hero(n) => write!(f, "hero:{n}"),
            Repr::Rgb => write!(f, "rgb"),
            Repr::Exact => write!(f, "exact"),
        }
    }
}

fn list(v: &[usize]) -> String {
    v.iter()
        .map(|x| x.to_string())
        .collect::<Vec<_>>()
        .join(", ")
}

impl FromStr for Repr {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        let bad = || Error::UnknownRepr(s.to_string());
        match s {
            "poly" => return Ok(Repr::DEFAULT),
            "paper" => return Ok(Repr::Paper),
            "rgb" => return Ok(Repr::Rgb),
            "exact" | "reference" => return Ok(Repr::Exact),
            "hero" => return Ok(Repr::Hero(4)),
            _ => {}
        }
        if let Some(rest) = s.strip_prefix("poly:") {
            let (a, b) = rest.split_once(['x', 'X']).ok_or_else(bad)?;
            let spans: usize = a.parse().map_err(|_| bad())?;
            let degree: usize = b.parse().map_err(|_| bad())?;
            if !POLY_SPANS.contains(&spans) || !POLY_DEGREES.contains(&degree) {
                return Err(Error::UnsupportedRepr {
                    text: s.to_string(),
                    what: "spans S are",
                    supported: format!(
                        "{} and degrees D are {}",
                        list(POLY_SPANS),
                        list(POLY_DEGREES)
                    ),
                });
            }
            return Ok(Repr::Poly {
                spans,
                coeffs: degree + 1,
            });
        }
        if let Some(rest) = s.strip_prefix("sampled:") {
            let n: usize = rest.parse().map_err(|_| bad())?;
            if !SAMPLED_N.contains(&n) {
                return Err(Error::UnsupportedRepr {
                    text: s.to_string(),
                    what: "sample counts N are",
                    supported: list(SAMPLED_N),
                });
            }
            return Ok(Repr::Sampled(n));
        }
        if let Some(rest) = s.strip_prefix("hero:") {
            let n: usize = rest.parse().map_err(|_| bad())?;
            if !HERO_N.contains(&n) {
                return Err(Error::UnsupportedRepr {
                    text: s.to_string(),
                    what: "wavelengths per path N are",
                    supported: list(HERO_N),
                });
            }
            return Ok(Repr::Hero(n));
        }
        Err(bad())
    }
}

/// Generic code run for one representation: `visit::<T>()`.
pub trait Visitor {
    /// What the visit returns.
    type Output;
    /// Runs with the representation's type `T`.
    fn visit<T: Shade>(self) -> Self::Output;
}

/// Generic code over the polynomial representations only (`poly`, `paper`, `poly:SxD`), for
/// what needs the `Spectrum` itself (coefficients, fit errors, evaluation for plots).
pub trait PolyVisitor {
    /// What the visit returns.
    type Output;
    /// Runs with `Spectrum<S, C, L>` (breakpoints `L::BREAKS`).
    fn visit<const S: usize, const C: usize, L: Layout<S>>(self) -> Self::Output;
}

/// Adapts a [`Visitor`] to a [`PolyVisitor`], so one table serves both dispatches.
struct AsShade<V>(V);

impl<V: Visitor> PolyVisitor for AsShade<V> {
    type Output = V::Output;
    fn visit<const S: usize, const C: usize, L: Layout<S>>(self) -> V::Output {
        self.0.visit::<Spectrum<S, C, L>>()
    }
}

/// The one list of supported layouts. From it come the parser's limits ([`POLY_SPANS`],
/// [`POLY_DEGREES`], [`SAMPLED_N`]) and both dispatches ([`dispatch`], [`dispatch_poly`]):
/// each listed layout is one monomorphised instance of the generic code.
macro_rules! representations {
    (spans: [$($s:literal),*]; coeffs: $cs:tt; sampled: [$($n:literal),*];) => {
        /// Span counts supported by `poly:SxD`.
        pub const POLY_SPANS: &[usize] = &[$($s),*];
        /// Degrees supported by `poly:SxD`.
        pub const POLY_DEGREES: &[usize] = &representations!(@degrees $cs);
        /// Sample counts supported by `sampled:N`.
        pub const SAMPLED_N: &[usize] = &[$($n),*];

        fn uniform_poly<V: PolyVisitor>(spans: usize, coeffs: usize, v: V) -> Option<V::Output> {
            match spans {
                $($s => representations!(@coeffs $s, coeffs, v, $cs),)*
                _ => None,
            }
        }

        fn sampled<V: Visitor>(n: usize, v: V) -> Option<V::Output> {
            match n {
                $($n => Some(v.visit::<Sampled<$n>>()),)*
                _ => None,
            }
        }
    };
    (@degrees [$($c:literal),*]) => { [$($c - 1),*] };
    (@coeffs $s:literal, $coeffs:expr, $v:expr, [$($c:literal),*]) => {
        match $coeffs {
            $($c => Some($v.visit::<$s, $c, Uniform>()),)*
            _ => None,
        }
    };
}

representations! {
    spans: [1, 2, 3, 4, 6, 8, 12, 16];
    coeffs: [2, 3, 4, 5, 6];
    sampled: [3, 4, 5, 8, 9, 11, 16, 21, 24, 32, 41, 48, 64, 81, 101, 201, 401];
}

/// Wavelengths per path supported by `hero:N` (pbrt-v4 and Mitsuba 3 use 4).
pub const HERO_N: &[usize] = &[4];

/// Runs `v` with the `Spectrum` type of a polynomial `repr`; a usage error naming `command`
/// for the others (sampled, RGB, exact).
pub fn dispatch_poly<V: PolyVisitor>(repr: Repr, command: &str, v: V) -> Result<V::Output> {
    let repr = repr.polynomial_for(command)?;
    poly(repr, v).ok_or(Error::UnlistedLayout(repr))
}

/// [`dispatch_poly`] without the message: `None` for a representation that is not polynomial
/// and for layouts outside the list (which [`Repr::from_str`] refuses).
fn poly<V: PolyVisitor>(repr: Repr, v: V) -> Option<V::Output> {
    match repr {
        Repr::Paper => Some(v.visit::<2, 4, Paper>()),
        Repr::Poly { spans, coeffs } => uniform_poly(spans, coeffs, v),
        Repr::Sampled(_) | Repr::Hero(_) | Repr::Rgb | Repr::Exact => None,
    }
}

/// Runs `v` with the type of `repr`.
///
/// # Panics
/// Never for a `Repr` from [`Repr::from_str`] or the constants: only a hand-built layout
/// outside the list could reach the panic.
pub fn dispatch<V: Visitor>(repr: Repr, v: V) -> V::Output {
    let out = match repr {
        Repr::Rgb => Some(v.visit::<Rgb>()),
        Repr::Exact => Some(v.visit::<Sampled<401>>()),
        // The presets' product and →XYZ through AVX2 + FMA kernels where the CPU has them
        // (specpoly-simd, chosen at run time; within its ULP_BOUND of the portable code).
        r if r == Repr::DEFAULT => Some(v.visit::<Wide<DefaultSpectrum>>()),
        Repr::Paper => Some(v.visit::<Wide<PaperSpectrum>>()),
        Repr::Sampled(81) => Some(v.visit::<Wide<Sampled<81>>>()),
        Repr::Sampled(n) => sampled(n, v),
        Repr::Hero(4) => Some(v.visit::<crate::hero::Hero<4>>()),
        Repr::Hero(_) => None,
        Repr::Poly { .. } => poly(repr, AsShade(v)),
    };
    match out {
        Some(o) => o,
        None => unreachable!("{repr}: not in the list of representations"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn parse_and_print() {
        for s in [
            "poly",
            "paper",
            "poly:4x5",
            "sampled:41",
            "hero:4",
            "rgb",
            "exact",
        ] {
            assert_eq!(s.parse::<Repr>().unwrap().to_string(), s);
        }
        assert_eq!("poly:8x3".parse::<Repr>().unwrap(), Repr::DEFAULT);
        assert!("poly:7x3".parse::<Repr>().is_err());
        assert!("sampled:7".parse::<Repr>().is_err());
        assert!("hero:3".parse::<Repr>().is_err());
        assert!("bogus".parse::<Repr>().is_err());
    }
}
