//! # specpoly-display
//!
//! The display description, specpoly's central file: the calibration file ([`calibration`],
//! a fitted display model in TOML), one loader that sniffs a display file once ([`spec`]), ICC
//! profiles written from a calibration ([`icc`]) and read back ([`icc_read`]), the
//! channel-interaction lattice ([`lattice`]), video LUTs ([`video_lut`]), calibration targets
//! ([`target`]) and framebuffer tables baked from a calibration ([`export`]).
#![forbid(unsafe_code)]

pub mod calibration;
pub mod export;
pub mod icc;
pub mod icc_read;
pub mod lattice;
pub mod spec;
pub mod target;
pub mod time;
pub mod video_lut;
