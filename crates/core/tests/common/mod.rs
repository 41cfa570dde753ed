//! Helpers the test modules share.

pub mod light_data;
pub mod reference_1nm;
