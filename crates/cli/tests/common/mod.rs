//! Helpers the test modules share.

pub mod calibrate_run;
pub mod cli;
/// The shipped displays' fits (one copy, in the calibrate crate's tests).
#[path = "../../../calibrate/tests/common/displays.rs"]
pub mod displays;
pub mod pr655;
pub mod pr655_rig;
pub mod pty;
