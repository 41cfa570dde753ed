//! # specpoly-display
//!
//! The display description, specpoly's central file: the calibration file ([`calibration`],
//! a fitted display model in TOML), one loader that sniffs a display file once ([`spec`]), ICC
//! profiles written from a calibration ([`icc`]) and read back ([`icc_read`]), the
//! channel-interaction lattice ([`lattice`]), video LUTs ([`video_lut`]), calibration targets
//! ([`target`]), framebuffer tables baked from a calibration ([`export`]) and 3D LUTs ([`lut3d`]).
//!
//! Layers, each module depending only on those before it in this list (no module cycles):
//! [`error`] and [`time`] (the UTC stamps); [`lattice`]; [`video_lut`]; [`calibration`];
//! [`target`] and [`export`] on a calibration; [`icc`] (its B2A0 table solved by the core's
//! inverse, as everything else); [`icc_read`]; [`spec`], the one loader over all the readers; [`lut3d`], 3D LUTs
//! from a source colour space to any display model (the core's `DisplayModel`, as [`spec`]
//! gives it), and their files.
//!
//! The colour maths is the core's: Bradford, 3×3 products and inverses are
//! `specpoly_core::Mat3<f64>`/`Xyz<f64>` and `specpoly_core::bradford` (the ICC writer and
//! reader have no matrix code of their own); the PCS white is
//! `specpoly_core::colorimetry::ICC_D50`.
//!
//! Errors are [`Error`] (what is wrong, with its data); the CLI gives them their exit codes.
//! No command-line parsing here: the CLI's value enums convert to [`calibration::TransferKind`],
//! [`icc::IccVersion`] and the [`export`] options.
#![forbid(unsafe_code)]

pub mod calibration;
pub mod error;
pub mod export;
pub mod icc;
pub mod icc_read;
pub mod lattice;
pub mod lut3d;
pub mod spec;
pub mod target;
pub mod time;
pub mod video_lut;

pub use error::{Error, Result};
