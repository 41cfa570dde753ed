//! # specpoly-c
//!
//! A C ABI over [`specpoly_core`] for LED and display firmware written in C: CCT/Duv ↔ `xy`,
//! mixing 3–6 LED channels to an `xy` or CCT/Duv target with the fade stepper, the display
//! model (the drive step: target XYZ → device levels → emitted XYZ; forward and inverse) read
//! from a versioned, checksummed calibration blob, and spectra (fit, evaluate, multiply, → XYZ
//! under the built-in lights and observers). `include/specpoly.hpp` wraps it for C++. The
//! header `include/specpoly.h` is generated from this crate by `cbindgen` (`cbindgen.toml`);
//! `docs/c.md` shows how to link it.
//!
//! Rules of the ABI:
//!
//! - **caller-owned, fixed-size `#[repr(C)]` structs**, no allocation, no global state;
//! - **every function is total**: it checks its pointers (NULL), its numbers (NaN, ±∞, ranges)
//!   and counts before it calls the core, and returns an [`SpStatus`] (`int32_t`); outputs are
//!   written only on [`SpStatus::Ok`] (and [`SpStatus::FadeDone`] for the fade step);
//! - the results are the core's own functions' results, bit for bit (the tests compare a C
//!   program's output with the Rust API on the host, and under QEMU on a Cortex-M4F and an
//!   RV32IMC).
//!
//! `unsafe` is allowed in this crate only, and only where a C pointer is turned into a
//! reference (the `ptr` module); every other line is safe Rust. On a target without an operating
//! system the crate is `no_std` with a panic handler that parks the core (no function here
//! panics on any input; the handler is a backstop); on a host it links `std` for its panic
//! runtime only.

#![no_std]
#![deny(unsafe_op_in_unsafe_fn)]

#[cfg(not(target_os = "none"))]
extern crate std;

pub mod cct;
pub mod display;
mod lights;
pub mod mix;
mod ptr;
pub mod spectrum;
pub mod status;

pub use status::SpStatus;

/// A panic never crosses the ABI: on a device it stops here.
#[cfg(target_os = "none")]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {
        core::hint::spin_loop();
    }
}
