//! # specpoly-paper
//!
//! M. G. Raso and A. Fournier, *A Piecewise Polynomial Approach to Shading Using Spectral
//! Distributions* (Graphics Interface 1991), reproduced on our data: the accuracy report of every
//! representation against the 1 nm reference ([`accuracy`], `docs/accuracy.md`), the paper's
//! Table 1 ([`table1`]), the fit of a spectrum and what it costs ([`fit_report`]) and Figures 4
//! and 5 ([`figures`]).
#![forbid(unsafe_code)]

pub mod accuracy;
pub mod error;
pub mod figures;
pub mod fit_report;
pub mod table1;

pub use error::{Error, Result};
