//! # specpoly-firmware
//!
//! The LED colour controller's firmware for Cortex-M4F (`thumbv7em-none-eabihf`): one
//! application loop ([`app::run`]) over a [`board::Board`], and the boards it runs on
//! ([`boards`]: QEMU `mps2-an386`, STM32F401/F411). The controller logic itself — commands,
//! replies, duties, settings records and their store, the drive table, fades — is the
//! target-independent `specpoly-device` crate (crates/device), unit-tested on the host.
//!
//! | module | holds |
//! |---|---|
//! | [`app`] | the loop: UART bytes → line → controller/store → reply → PWM channels; restore at start; fade steps on the clock |
//! | [`board`] | the [`board::Board`] trait: UART, PWM channels, flashes, millisecond clock, RAM |
//! | [`boards`] | `mps2` and `stm32f4`: board assembly, peripherals, defmt logger, panic handler; the only `unsafe` |
//!
//! No heap. `unsafe` is denied everywhere but in [`boards`].
//!
//! `duplicates` pairs kept: the `NorFlash` impls of `boards/mps2/flash.rs` and
//! `boards/stm32f4/flash.rs` (the trait's shape over two memories); the two boards' `Board` impls
//! (the trait's methods over different peripherals); the RGB565 and RGB888 kernels and the
//! stages of `transform_asm.rs` (one instruction sequence per channel, unrolled for the M4's
//! cycle budget); the bins' few lines (one per board and demo).
#![no_std]
#![deny(unsafe_code)]
#![warn(missing_docs)]

#[cfg(all(target_arch = "arm", target_os = "none"))]
pub mod app;
#[cfg(all(target_arch = "arm", target_os = "none"))]
pub mod board;
#[cfg(all(target_arch = "arm", target_os = "none"))]
#[allow(unsafe_code)]
pub mod boards;
#[cfg(all(target_arch = "arm", target_os = "none"))]
pub mod memory;

#[cfg(all(
    target_arch = "arm",
    target_os = "none",
    feature = "mps2",
    feature = "stm32f4"
))]
compile_error!("one board at a time: --no-default-features --features stm32f4,full");
