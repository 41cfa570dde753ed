//! # specpoly (host)
//!
//! The `specpoly` command-line tool on top of `specpoly-core`: spectra in, calibrated colours
//! out; a spectral ray tracer; a monitor-calibration workflow; the LED controller's host side.
//! The library target exists so tests and benchmarks can call the same code as the binary.
#![forbid(unsafe_code)]

pub mod accuracy;
pub mod calibrate;
pub mod cli;
pub mod colour;
pub mod data;
pub mod error;
pub mod figures;
pub mod fit_report;
pub mod io;
pub mod led;
pub mod measurement;
pub mod plot;
pub mod render;
pub mod repr;
pub mod size;
pub mod spectrum_names;
pub mod stats;
pub mod table1;
