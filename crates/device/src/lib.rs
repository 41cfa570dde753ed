//! # specpoly-device
//!
//! The LED controller's logic, independent of any board: what both firmware boards run
//! (`firmware/`) and what the host can use as its model of the device. `no_std`, no heap, no
//! `unsafe`; unit-tested on the host (`cargo test -p specpoly-device`).
//!
//! An RGB LED is a three-primary display, so its colour is controlled with the same
//! mathematics as a monitor (`specpoly-core`: Cowan's model, the paper's §7.3). Commands arrive
//! as lines ([`specpoly_protocol`], `firmware/PROTOCOL.md`); the [`controller`] answers them and
//! computes PWM duties; [`output`] says which duties the channels show; the [`led`] driver sets
//! up to six `embedded-hal` PWM channels.
//!
//! | module | holds |
//! |---|---|
//! | [`controller`] | commands → replies and duties (calibration, curves, gamut map, observer, mixer, drive table) |
//! | [`output`] | which path the channels show: the colour path's three duties or the mixer's |
//! | [`led`] | [`Led`]: `N` `embedded_hal::pwm::SetDutyCycle` channels of one full scale; [`led::Duties`] |
//! | [`lights`] | the built-in lights' moments, computed at build time by the core (`build.rs`) |
//! | [`settings`] | the settings record (format 1): encode, decode with range checks |
//! | [`mix`] | the mixer's settings record (channels, curves, fade time) |
//! | `store` | feature `settings`: the records in a `sequential-storage` map over `embedded-storage` NOR flash; `save`/`load`/restore |
//! | `lut` | feature `lut`: the drive-correction table in a flash region of its own |
//! | [`fade`] | [`fade::Pacer`]: one fade step every 10 ms of a millisecond clock |
//! | [`fuzz`] | the command handler's fuzz target (bytes as they arrive on the UART) |
//!
//! Features (the firmware forwards its own): `settings`, `mixing` (3–6 LED channels: `channel`,
//! `xy`, `cct`, `fade`), `lut` (default `full` = all three); `observer-1964` (the 10°
//! observer's moments), `fast-math` (micromath's `powf` in the transfer curves). Without
//! `settings`, `mixing` and `lut` the controller fits a 32 KiB part (firmware/README.md).
#![cfg_attr(not(test), no_std)]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod controller;
pub mod fade;
pub mod fuzz;
pub mod led;
pub mod lights;
#[cfg(feature = "lut")]
pub mod lut;
pub mod mix;
pub mod output;
pub mod settings;
#[cfg(feature = "settings")]
pub mod store;

pub use controller::Controller;
pub use led::{Duties, Led, LedError};
pub use output::Output;
