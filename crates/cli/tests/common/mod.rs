//! Helpers the test modules share.

pub mod calibrate_run;
pub mod cli;
pub mod displays;
pub mod pr655;
pub mod pr655_rig;
pub mod pty;
