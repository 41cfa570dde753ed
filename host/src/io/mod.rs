//! File formats and output: CSV spectra, atomic file writes.

pub mod atomic;
pub mod csv;
