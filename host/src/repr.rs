//! Colour representations a user can pick (`--repr`, `--mode`), and the dispatch from that
//! runtime choice to the generic code, which is monomorphised per representation so every
//! mode runs the same code ([`specpoly_core::Shade`]).
//!
//! - `poly` — the project default, 8 uniform cubic spans ([`DefaultSpectrum`]);
//! - `paper` — 2 cubic spans split at 550 nm ([`PaperSpectrum`]);
//! - `poly:SxD` — `S` uniform spans of degree `D`;
//! - `sampled:N` — `N` point samples over 380–780 nm, the light and the colour matching
//!   functions point-sampled at the same wavelengths;
//! - `rgb` — linear sRGB triples (the paper's "RGB problem");
//! - `exact` — the 1 nm reference: 401 samples at 1 nm, identical to the 1 nm sum.

use crate::error::{CliError, Result};
use specpoly_core::{
    DefaultSpectrum, PaperSpectrum, Rgb, Sampled, Shade, Spectrum, DEFAULT_COEFFS, DEFAULT_SPANS,
};
use std::fmt;
use std::str::FromStr;

/// Span counts supported by `poly:SxD`.
pub const POLY_SPANS: &[usize] = &[1, 2, 3, 4, 6, 8, 12, 16];
/// Degrees supported by `poly:SxD`.
pub const POLY_DEGREES: &[usize] = &[1, 2, 3, 4, 5];
/// Sample counts supported by `sampled:N`.
pub const SAMPLED_N: &[usize] = &[
    3, 4, 5, 8, 9, 11, 16, 21, 24, 32, 41, 48, 64, 81, 101, 201, 401,
];

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

    /// Number of stored values per colour.
    pub fn size(&self) -> usize {
        match *self {
            Repr::Poly { spans, coeffs } => spans * coeffs,
            Repr::Paper => 8,
            Repr::Sampled(n) => n,
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
    type Err = CliError;
    fn from_str(s: &str) -> Result<Self> {
        let bad = || {
            CliError::usage(format!(
                "unknown representation `{s}` (poly, paper, poly:SxD, sampled:N, rgb, exact)"
            ))
        };
        match s {
            "poly" => return Ok(Repr::DEFAULT),
            "paper" => return Ok(Repr::Paper),
            "rgb" => return Ok(Repr::Rgb),
            "exact" | "reference" => return Ok(Repr::Exact),
            _ => {}
        }
        if let Some(rest) = s.strip_prefix("poly:") {
            let (a, b) = rest.split_once(['x', 'X']).ok_or_else(bad)?;
            let spans: usize = a.parse().map_err(|_| bad())?;
            let degree: usize = b.parse().map_err(|_| bad())?;
            if !POLY_SPANS.contains(&spans) || !POLY_DEGREES.contains(&degree) {
                return Err(CliError::usage(format!(
                    "`{s}`: supported spans S are {} and degrees D are {}",
                    list(POLY_SPANS),
                    list(POLY_DEGREES)
                )));
            }
            return Ok(Repr::Poly {
                spans,
                coeffs: degree + 1,
            });
        }
        if let Some(rest) = s.strip_prefix("sampled:") {
            let n: usize = rest.parse().map_err(|_| bad())?;
            if !SAMPLED_N.contains(&n) {
                return Err(CliError::usage(format!(
                    "`{s}`: supported sample counts N are {}",
                    list(SAMPLED_N)
                )));
            }
            return Ok(Repr::Sampled(n));
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

macro_rules! by_coeffs {
    ($s:literal, $c:expr, $v:expr) => {
        match $c {
            2 => $v.visit::<Spectrum<$s, 2>>(),
            3 => $v.visit::<Spectrum<$s, 3>>(),
            4 => $v.visit::<Spectrum<$s, 4>>(),
            5 => $v.visit::<Spectrum<$s, 5>>(),
            _ => $v.visit::<Spectrum<$s, 6>>(),
        }
    };
}

macro_rules! by_n {
    ($n:expr, $v:expr; $($lit:literal),*) => {
        match $n {
            $($lit => $v.visit::<Sampled<$lit>>(),)*
            _ => $v.visit::<Sampled<401>>(),
        }
    };
}

/// Runs `v` with the type of `repr` (which [`Repr::from_str`] has validated).
pub fn dispatch<V: Visitor>(repr: Repr, v: V) -> V::Output {
    match repr {
        Repr::Paper => v.visit::<PaperSpectrum>(),
        r if r == Repr::DEFAULT => v.visit::<DefaultSpectrum>(),
        Repr::Poly { spans, coeffs } => match spans {
            1 => by_coeffs!(1, coeffs, v),
            2 => by_coeffs!(2, coeffs, v),
            3 => by_coeffs!(3, coeffs, v),
            4 => by_coeffs!(4, coeffs, v),
            6 => by_coeffs!(6, coeffs, v),
            8 => by_coeffs!(8, coeffs, v),
            12 => by_coeffs!(12, coeffs, v),
            _ => by_coeffs!(16, coeffs, v),
        },
        Repr::Sampled(n) => {
            by_n!(n, v; 3, 4, 5, 8, 9, 11, 16, 21, 24, 32, 41, 48, 64, 81, 101, 201)
        }
        Repr::Rgb => v.visit::<Rgb>(),
        Repr::Exact => v.visit::<Sampled<401>>(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn parse_and_print() {
        for s in ["poly", "paper", "poly:4x5", "sampled:41", "rgb", "exact"] {
            assert_eq!(s.parse::<Repr>().unwrap().to_string(), s);
        }
        assert_eq!("poly:8x3".parse::<Repr>().unwrap(), Repr::DEFAULT);
        assert!("poly:7x3".parse::<Repr>().is_err());
        assert!("sampled:7".parse::<Repr>().is_err());
        assert!("bogus".parse::<Repr>().is_err());
    }
}
