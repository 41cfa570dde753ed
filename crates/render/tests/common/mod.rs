//! Helpers the test modules share.

pub mod displays;
pub mod scenes;
