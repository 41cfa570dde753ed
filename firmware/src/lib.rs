//! # specpoly-firmware
//!
//! An RGB-LED colour controller on `specpoly-core`: an RGB LED is a three-primary display, so
//! its colour is controlled with the same mathematics as a monitor (Cowan's model, the paper's
//! §7.3). Commands arrive as lines on the UART ([`specpoly_protocol`], `PROTOCOL.md`); the
//! [`controller`] computes XYZ and duties; the [`led`] driver sets three PWM channels.
//!
//! With 3–6 LED channels uploaded (`channel`), the controller also solves `xy` and `cct` targets
//! on the device and fades between them ([`mix`], [`fade`]; `specpoly_core::light::channels`).
//!
//! Settings survive resets in flash ([`settings`]: the record, `store`: `sequential-storage`).
//! Both are Cargo features, `settings` and `mixing` (default `full`): without them the
//! controller fits a 32 KiB part (README.md).
//! The controller, the driver and the store are target-independent and unit-tested on the host
//! (the store against `sequential-storage`'s mock flash); the board
//! support ([`board`]: UART, a PWM stand-in, stack painting, an instruction counter) exists only
//! for `thumbv7em-none-eabihf` (QEMU `mps2-an386`). No heap.
//!
//! `duplicates --repo firmware` lists two same-shape pairs, kept: the `NorFlash` impls of
//! `board::flash` (SSRAM stand-in) and `stm32f4::flash` (the real sector), the trait's required
//! shape over different memories; the main loops of `main.rs` and `bin/stm32f4.rs` (one per
//! board: different peripherals around the same controller calls and `defmt` line).
#![cfg_attr(not(test), no_std)]
#![warn(missing_docs)]

pub mod controller;
pub mod fade;
pub mod fuzz;
pub mod led;
pub mod lights;
#[cfg(feature = "lut")]
pub mod lut;
pub mod mix;
pub mod settings;
#[cfg(feature = "settings")]
pub mod store;

#[cfg(all(target_arch = "arm", target_os = "none", feature = "mps2"))]
pub mod board;

#[cfg(all(target_arch = "arm", target_os = "none", feature = "stm32f4"))]
pub mod stm32f4;

#[cfg(all(
    target_arch = "arm",
    target_os = "none",
    feature = "mps2",
    feature = "stm32f4"
))]
compile_error!("one board at a time: --no-default-features --features stm32f4,full");

pub use controller::Controller;
pub use led::{LedError, RgbLed};
