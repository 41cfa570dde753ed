//! # specpoly-formats
//!
//! The files specpoly reads and writes, below every other host crate: spectral CSV ([`csv`]),
//! CGATS `.ti3` readings ([`cgats`]) and ArgyllCMS `.ti1` patch sets ([`ti1`]), bounded reads of
//! regular files ([`read`]), output files written whole or not at all ([`atomic`]), control
//! characters escaped for a terminal ([`escape`]), device strings `KIND:ARG,key=value`
//! ([`device_spec`]), TOML errors on one line ([`toml_error`]), whole outputs to stdout
//! ([`stdout`]), one measured patch ([`measurement`]), spectral samples in CGATS
//! ([`spectral`]) and ArgyllCMS's colorimeter corrections ([`ccss`], [`ccmx`]).
//!
//! Its functions return [`Error`] ([`error`]): what went wrong with which file, and where
//! (`FILE:LINE[:COLUMN]: …`), as data; which errors are usage errors and which exit codes they
//! give is the CLI's decision (`crates/cli/src/error/formats.rs`).
//!
//! Hand-written where a crate exists: the `KIND:ARG,key=value` device strings (clap parses one
//! value, not sub-options, and no small crate reads this grammar) and the CGATS reader (the
//! ArgyllCMS dialect with its keywords; no maintained crate reads it).
#![forbid(unsafe_code)]

pub mod atomic;
pub mod ccmx;
pub mod ccss;
pub mod cgats;
pub mod cgats_table;
pub mod csv;
pub mod device_spec;
pub mod error;
pub mod escape;
pub mod measurement;
pub mod read;
pub mod spectral;
pub mod stats;
pub mod stdout;
pub mod ti1;
pub mod toml_error;

pub use error::Error;

/// The result type of this crate's functions.
pub type Result<T, E = Error> = std::result::Result<T, E>;
