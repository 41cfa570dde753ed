//! Board support for QEMU `mps2-an386` (Cortex-M4F): the CMSDK UART, a PWM stand-in whose
//! duties are reported (QEMU emulates no PWM), stack painting, an instruction counter, and the
//! panic handler. The only `unsafe` of the project is here: memory-mapped registers and the
//! stack region, each block with its reason.

pub mod icount;
pub mod pwm;
pub mod stack;
pub mod uart;
pub mod vectors;

use core::fmt::Write as _;
use core::panic::PanicInfo;
use cortex_m_semihosting::{debug, hio};
use heapless::String;
use specpoly_protocol::number::write_int;

/// Writes a line to the host's standard output through semihosting. Built with the protocol's
/// own integer writer rather than `core::fmt`'s, which would cost ≈ 2 KiB of flash.
pub fn host_line(parts: &[&str], numbers: &[(&str, i64)]) {
    let mut s: String<160> = String::new();
    for p in parts {
        let _ = s.push_str(p);
    }
    for (k, v) in numbers {
        let _ = s.push_str(k);
        let _ = write_int(&mut s, *v);
    }
    let _ = s.push('\n');
    if let Ok(mut out) = hio::hstdout() {
        let _ = out.write_str(&s);
    }
}

/// Any panic is a bug (input never panics: the parser is fuzzed on the host and on target):
/// report where through semihosting and exit QEMU with a failure code.
#[panic_handler]
fn panic(info: &PanicInfo) -> ! {
    match info.location() {
        Some(l) => host_line(&["firmware panic at ", l.file()], &[(":", l.line() as i64)]),
        None => host_line(&["firmware panic"], &[]),
    }
    debug::exit(debug::EXIT_FAILURE);
    loop {
        cortex_m::asm::wfi();
    }
}
