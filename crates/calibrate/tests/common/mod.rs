//! Helpers the test modules share.

pub mod displays;
pub mod lut3d_consumers;
