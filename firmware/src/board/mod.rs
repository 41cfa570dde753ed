//! Board support for QEMU `mps2-an386` (Cortex-M4F): the CMSDK UART, a PWM stand-in whose
//! duties are reported (QEMU emulates no PWM), stack painting, an instruction counter, the
//! defmt logger (semihosting), the panic handler and the framebuffer demo's RGB565 kernel in
//! assembly. The only `unsafe` of the project is here: memory-mapped registers, the stack region
//! and the call into the assembly kernel, each block with its reason.

#[cfg(any(feature = "settings", feature = "lut"))]
pub mod flash;
pub mod icount;
pub mod pwm;
pub mod rgb565;
pub mod rgb888;
pub mod stack;
mod transform_asm;
pub mod uart;
pub mod vectors;

// the global defmt logger: frames go to QEMU's standard output through semihosting
use defmt_semihosting as _;

use core::panic::PanicInfo;
use cortex_m_semihosting::debug;

/// Any panic is a bug (input never panics: the parser is fuzzed on the host and on target):
/// log where through defmt and exit QEMU with a failure code. Hand-written rather than
/// `panic-probe`: its `print-defmt` formats the message with `core::fmt`, which the firmware
/// otherwise keeps out of flash, and it stops in `udf`, which leaves QEMU running instead of
/// exiting with a failure.
#[panic_handler]
fn panic(info: &PanicInfo) -> ! {
    match info.location() {
        Some(l) => defmt::error!("firmware panic at {=str}:{=u32}", l.file(), l.line()),
        None => defmt::error!("firmware panic"),
    }
    debug::exit(debug::EXIT_FAILURE);
    loop {
        cortex_m::asm::wfi();
    }
}
