//! The host side of the RGB-LED controller (`specpoly-firmware`): a serial [`link::Link`] that
//! speaks the shared line protocol ([`specpoly_protocol`], `firmware/PROTOCOL.md`); the
//! controller modelled with the same core calls ([`model::Model`], for playing a controller in
//! tests; [`model::MixModel`] for the multi-channel mixer, the firmware's own calls); and the
//! independent f64 references with their tolerance tables ([`check`] for colours,
//! [`mix_check`] for mixes, from the channels' spectra) that `specpoly led --check` and the
//! QEMU tests verify a controller against.
#![forbid(unsafe_code)]

pub mod check;
pub mod error;
pub mod lines;
pub mod link;
pub mod mix_check;
pub mod model;
pub mod table;

pub use check::Oracle;
pub use error::{Error, Result};
pub use link::Link;
pub use model::{MixModel, Model};
pub use table::DriveTable;
