//! # specpoly (host)
//!
//! The `specpoly` command-line tool on top of `specpoly-core`: spectra in, calibrated colours
//! out; a spectral ray tracer; a monitor-calibration workflow; the LED controller's host side.
//! The library target exists so tests and benchmarks can call the same code as the binary.
#![forbid(unsafe_code)]

pub mod calibrate;
pub mod cli;
pub mod colour;
pub mod data;
pub mod error;
pub mod io;
pub mod led;
pub mod light;
pub mod plot;
pub mod render;
pub mod repr;
pub mod spectra;
