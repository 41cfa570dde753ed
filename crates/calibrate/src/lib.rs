//! # specpoly-calibrate
//!
//! Measuring a display: patch sets ([`patches`]), where patches are shown ([`patch_display`]),
//! where readings come from ([`instrument`]), the readings log ([`session`]), one run per
//! output ([`lock`]), the measuring loop ([`run`]), the fit of the display model ([`fit`]), drift between repeated readings ([`drift`]),
//! verification ([`verify`], [`criteria`]) and its report ([`report_html`]). The calibration file and its exports are in `specpoly-display`.
#![forbid(unsafe_code)]

pub mod criteria;
pub mod drift;
pub mod error;
pub mod fit;
pub mod instrument;
pub mod interrupt;
pub mod lock;
pub mod patch_display;
pub mod patches;
pub mod progress;
pub mod readings;
pub mod report_html;
pub mod run;
pub mod session;
pub mod sim;
pub mod verify;

pub use error::{Error, InstrumentError, PatchDisplayError, Result};
pub use specpoly_formats::measurement::Measurement;
