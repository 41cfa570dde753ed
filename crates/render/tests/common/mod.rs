//! Helpers the test modules share.

/// The shipped displays' fits (one copy, in the calibrate crate's tests).
#[path = "../../../calibrate/tests/common/displays.rs"]
pub mod displays;
pub mod scenes;
