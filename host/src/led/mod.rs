//! The host side of the RGB-LED controller (`specpoly-firmware`): a serial [`link::Link`] that
//! speaks the shared line protocol ([`specpoly_protocol`], `firmware/PROTOCOL.md`), and the
//! host's own computation of what the controller must answer ([`model::Model`]), with the same
//! `specpoly-core`, so `specpoly led --check` (and the QEMU tests) can verify the device.

pub mod error;
pub mod lines;
pub mod link;
pub mod model;

pub use error::LedError;
pub use link::Link;
pub use model::Model;
