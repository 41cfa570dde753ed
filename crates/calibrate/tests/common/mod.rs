//! Helpers the test modules share.

pub mod displays;
