//! The integration tests of `spectra`: one test binary, a module per area.

mod cie2006_luxpy;
mod grid_weights;
mod observer_csv;
