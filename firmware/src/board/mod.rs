//! Board support for QEMU `mps2-an386` (Cortex-M4F): the CMSDK UART, a PWM stand-in whose
//! duties are reported (QEMU emulates no PWM), stack painting, an instruction counter, and the
//! panic handler. The only `unsafe` of the project is here: memory-mapped registers and the
//! stack region, each block with its reason.

pub mod icount;
pub mod pwm;
pub mod stack;
pub mod uart;

use core::panic::PanicInfo;
use cortex_m_semihosting::{debug, hprintln};

/// Any panic is a bug (input never panics: the parser is fuzzed on the host and on target):
/// print it through semihosting and exit QEMU with a failure code.
#[panic_handler]
fn panic(info: &PanicInfo) -> ! {
    hprintln!("firmware panic: {}", info);
    debug::exit(debug::EXIT_FAILURE);
    loop {
        cortex_m::asm::wfi();
    }
}
