//! The integration tests of `calibrate`: one test binary, a module per area.

mod common;
mod corrections;
mod display_inverse;
mod displays;
mod icc;
mod icc_lut;
mod locus;
mod lut3d;
mod model;
mod ti3;
