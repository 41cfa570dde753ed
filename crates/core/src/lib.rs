//! # specpoly-core
//!
//! Spectral shading with piecewise polynomials and calibrated colour output, after
//! M. G. Raso and A. Fournier, "A Piecewise Polynomial Approach to Shading Using Spectral
//! Distributions", Graphics Interface 1991. `no_std`, no allocation: the same code runs on the
//! desktop and on a Cortex-M microcontroller.
//!
//! One flow:
//!
//! ```text
//! tabulated data ─fit─▶ Spectrum<S, C, L> ─mul (+reduce)─▶ Spectrum<S, C, L> ─· Moments─▶ Xyz ─Display─▶ device RGB
//! ```
//!
//! ```
//! use specpoly_core::{DefaultSpectrum, Illuminant, Lab, Moments, Observer, Tabulated, delta_e2000};
//!
//! // A reflectance tabulated at 10 nm (a made-up red paint).
//! let nm: Vec<f32> = (0..41).map(|i| 380.0 + 10.0 * i as f32).collect();
//! let red: Vec<f32> = nm.iter().map(|w| 0.05 + 0.8 / (1.0 + ((600.0 - w) / 15.0).exp())).collect();
//! let data = Tabulated::new(&nm, &red)?;
//!
//! let r = DefaultSpectrum::fit(&data)?;                   // 8 uniform cubic spans
//! let light = Moments::new(Observer::Cie1964, &Illuminant::D65.tabulated());
//! let twice = r.mul(&r);                                  // an inter-reflection, reduced to cubics
//! let xyz = light.xyz(&twice);
//! let lab = Lab::from_xyz(xyz, light.white());
//! assert!(lab.a > 40.0);                                  // a saturated red
//! # let _ = delta_e2000(lab, lab);
//! # Ok::<(), specpoly_core::Error>(())
//! ```
//!
//! ## Component types
//!
//! - **f32 in the kernels**: spectra and their products, moments, [`Xyz`]/[`Xyy`] values,
//!   the display model ([`Display`], [`Mat3`]) and the drive step — everything a pixel or the
//!   firmware computes. 24 bits are far beyond the data (measured reflectances carry 3–4
//!   digits), f32 is what a Cortex-M4F does in hardware, and twice as many lanes vectorise.
//! - **f64 at the edges**: sums over many terms (moments over 401 wavelengths, fits' normal
//!   equations, the 1 nm reference [`exact_xyz`]), linear algebra ([`solve`]), the paper's
//!   raw-λ monomials, CIELAB/CIEDE2000 ([`Lab`], differences of nearly equal numbers),
//!   CIECAM02, the host's ICC profiles, and every figure the host reports.
//! - **One type at both**: [`Mat3<T>`](Mat3) and [`Xyz<T>`](Xyz) are generic over [`Real`]
//!   (`f32`, the default, or `f64`), and so is [`bradford`]: one Bradford, one 3×3 product,
//!   one inverse per component type. The f32 inverse stays in f32 (the adjugate refined by a
//!   Newton step summed with its rounding errors: no soft f64 on the firmware); the f64 one is
//!   the adjugate. Literals with nothing else to fix their type are f64 (Rust's fallback):
//!   write `Xyz::<f32>::new(…)` where an f32 value is meant.
//! - Crossing: f32 → f64 by widening (`<[f64; 3]>::from(xyz)`, [`Lab::from_xyz`] takes both);
//!   f64 → f32 once, when a kernel value is made (a fit, a moment, a matrix).
//!
//! ## One implementation of each step
//!
//! `duplicates --repo core` lists one pair, kept: `Transfer::decode` and `Transfer::encode`
//! share the shape of a `match` over the curves, but each is the other's inverse, not a copy.
//! Also kept, same shape only: the test of `light::samples` checking the CES99 and TCS14 tables
//! (two tables, two tolerances); the two writers of `pixel::export` (a C header and a Rust
//! source: the same tables in two languages); the documented constants and result structs of
//! `light::cct` and `light::tm30` (one doc line per item); the tests of `pixel::transform`
//! (one `Options` literal and one `PanelTransform` each). `light::channels` inverts 3×3 systems
//! in f32 by the adjugate alone and solves 2×2 ones by Cramer's rule rather than calling
//! [`solve`] (f64) or [`Mat3::inverse`] (refined): on the Cortex-M4F f64 is soft float and a six-channel mix
//! takes 20 inverses and 240 2×2 solves per fade step (docs/leds.md).
#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod blob;
pub mod cheb;
pub mod colorimetry;
pub mod display;
pub mod display_model;
pub mod drive;
pub mod drive_table;
pub mod error;
pub mod fit;
pub mod illuminant;
pub mod interaction;
pub mod layout;
pub mod light;
mod math;
pub mod matrix;
pub mod moments;
pub mod observer;
pub mod paper;
pub mod pixel;
pub mod shade;
pub mod solve;
pub mod spectrum;
pub mod tabulated;

pub use cheb::Cheb;
pub use colorimetry::{
    bradford, chromaticity, de2000_terms, delta_e2000, delta_e2000_xyz, De2000Terms, Lab, Xyy, Xyz,
};
pub use display::{quantize, quantize8, Display, Encoded, GamutMap, Transfer};
pub use display_model::{DisplayModel, InverseOptions, Solution};
pub use drive::Drive;
pub use error::Error;
pub use fit::FitErrors;
pub use illuminant::Illuminant;
pub use interaction::Interaction;
pub use layout::{Breaks, Layout, Paper, Uniform, PAPER_BREAKS};
pub use matrix::{Mat3, Real};
pub use moments::{exact_xyz, Moments};
pub use observer::{CmfTable, Observer};
pub use shade::{Rgb, RgbLight, Sampled, SampledLight, Shade};
pub use spectrum::{DefaultSpectrum, PaperSpectrum, Spectrum, DEFAULT_COEFFS, DEFAULT_SPANS};
pub use tabulated::Tabulated;

/// Short end of the domain (nm), as in the paper.
pub const LAMBDA_MIN: f32 = 380.0;
/// Long end of the domain (nm).
pub const LAMBDA_MAX: f32 = 780.0;
