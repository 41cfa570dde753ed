//! Input and output: CSV spectra, CGATS measurements, atomic file writes, device strings
//! (`KIND[:ARG][,KEY=VALUE...]`), stdout and the progress bar.

pub mod atomic;
pub mod cgats;
pub mod csv;
pub mod device_spec;
pub mod escape;
pub mod progress;
pub mod read;
pub mod stdout;
pub mod ti1;
pub mod toml_error;
