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
//! structs of the scene file's `[[sphere]]`/`[[plane]]`/`[[box]]` sections (one per TOML table);
//! the `light` and `mix` reports ([`light::LightReport`], [`light::MixReport`]) and their
//! tables in `cli/light.rs`, `cli/mix.rs`: the issue fixes different key sets in a different
//! order (`light` has X, Y, Z and R9 before Rf), which a shared flattened struct would reorder;
//! the documented fields of [`render::scene::Scene`] and [`light::LightReport`] (one doc line per
//! field); the "format / patch set does not match" checks of `calibrate::file` and
//! `calibrate::session` (one `match` each, different keys and errors); the two primaries tables
//! of `calibrate run` (measured and simulated, one `format!` each); the CGATS headers of
//! `io::cgats` and `io::ti1` (the fixed keywords of two different files); the signatures of
//! the point- and area-light weight helpers of `render::tracer` (one per kind of light).
#![forbid(unsafe_code)]

pub mod accuracy;
pub mod calibrate;
pub mod cli;
pub mod colour;
pub mod data;
pub mod error;
pub mod figures;
pub mod fit_report;
pub mod fuzz;
pub mod io;
pub mod led;
pub mod light;
pub mod measurement;
pub mod plausible;
pub mod plot;
pub mod render;
pub mod repr;
pub mod size;
pub mod spectrum_names;
pub mod stats;
pub mod table1;
