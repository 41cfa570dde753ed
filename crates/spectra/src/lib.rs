//! # specpoly-spectra
//!
//! The core's spectra on the host: built-in reference data ([`data`]), spectra named on a
//! command line or in a file ([`spectrum_names`]), refusing data that cannot be a reflectance
//! ([`plausible`]), the representations a user picks and the dispatch from that runtime choice
//! to monomorphised code ([`repr`], [`hero`]), the colours of chains of reflectances
//! ([`colour`]) and of many reflectances on one grid as one matrix
//! ([`grid_weights`]), observers given as data — CSV sensitivities and the CIE 2006 model for an
//! age and field size ([`observer`], [`cie2006`]) — and the light-metric and LED-mixing reports ([`light`], TM-30 in full:
//! [`light_tm30`]).
//!
//! `duplicates` pairs kept: the `light` and `mix` reports ([`light::LightReport`],
//! [`light::MixReport`]): different key sets in a different order, which a shared flattened
//! struct would reorder; their documented fields (one doc line each, like `specpoly-render`'s
//! `Scene`); the `match` arms of [`repr`]'s parser (one per representation).
#![forbid(unsafe_code)]

pub mod cie2006;
pub mod colour;
pub mod data;
pub mod error;
pub mod grid_weights;
pub mod hero;
pub mod light;
pub mod light_checks;
pub mod light_tm30;
pub mod observer;
pub mod plausible;
pub mod repr;
pub mod spectrum_names;

pub use error::{Error, Result};
