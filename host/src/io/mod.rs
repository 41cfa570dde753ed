//! File formats and output: CSV spectra, atomic file writes.

pub mod atomic;
pub mod cgats;
pub mod csv;
pub mod stdout;
pub mod ti1;
