//! # specpoly (host)
//!
//! The `specpoly` command-line tool on top of `specpoly-core`: spectra in, calibrated colours
//! out; a spectral ray tracer; a monitor-calibration workflow; the LED controller's host side.
//! The library target exists so tests and benchmarks can call the same code as the binary.
//!
//! Layout: `cli/` only parses (shared typed arguments in [`cli::args`]), calls and prints; the
//! work is in the library modules — [`colour`] and [`repr`] (the colour of spectra in any
//! representation, dispatched from the one list of layouts), [`accuracy`], [`table1`],
//! [`fit_report`] and [`figures`] (the paper's tables and figures), [`render`], [`calibrate`],
//! [`led`] (the controller's host side), [`spectrum_names`] (command-line spectrum names),
//! [`stats`], [`size`], [`measurement`], [`io`] (files, device strings, stdout, progress).
//!
//! Hand-written where a crate exists: the `KIND:ARG,key=value` device strings
//! ([`io::device_spec`]; clap parses one value, not sub-options, and no small crate reads this
//! grammar) and the nearest-rank percentile ([`stats`]; one line, no dependency).
//! Repetition `duplicates` still reports, kept on purpose: the entries of the built-in file lists
//! (`data::TABLES`, `render::builtin::SCENES`: data, one struct literal each) and the serde
//! structs of the scene file's `[[sphere]]`/`[[plane]]`/`[[box]]` sections (one per TOML table).
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
