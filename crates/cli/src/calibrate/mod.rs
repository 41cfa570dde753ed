//! Monitor calibration: patch sets, where patches are shown, where readings come from, the
//! fit of Cowan's model, calibration files, ICC export and verification.

pub mod criteria;
pub mod export;
pub mod file;
pub mod fit;
pub mod icc;
pub mod icc_read;
pub mod instrument;
pub mod interrupt;
pub mod patch_display;
pub mod patches;
pub mod report_html;
pub mod run;
pub mod session;
pub mod sim;
pub mod target;
pub mod verify;
pub mod video_lut;

pub use crate::measurement::Measurement;
