//! # specpoly
//!
//! The `specpoly` command-line tool over the library crates (`specpoly-core`, `-formats`,
//! `-spectra`, `-paper`, `-plot`, `-display`, `-calibrate`, `-render`, `-led`): [`cli`] parses
//! (one file per command, the arguments several commands share in [`cli::args`]), calls the
//! libraries and prints; [`error`] turns every failure into one line and an exit code. The
//! library target exists so tests can run a command in-process; [`fuzz`] holds the parsers'
//! fuzz targets (`fuzz/`, replayed in `cargo test`).
//!
//! `duplicates` pairs kept: the `From` impls in [`error`]'s submodules share their shape (one
//! `match` over each library crate's error enum: that crate's exit codes).
#![forbid(unsafe_code)]

pub mod cli;
pub mod error;
pub mod fuzz;
