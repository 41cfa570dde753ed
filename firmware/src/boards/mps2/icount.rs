//! Instruction counts under QEMU. QEMU's `-icount shift=0` makes virtual time advance exactly
//! 1 ns per executed instruction; SysTick, clocked by the 25 MHz system clock of mps2-an386,
//! then ticks once every 40 instructions. A measurement repeats the work `n` times and divides,
//! so the ±40 instruction resolution becomes ±40/n. (DWT CYCCNT is not emulated by QEMU.)
//!
//! On hardware the same counter gives cycles at 25 MHz instead.

use cortex_m::peripheral::{syst::SystClkSource, SYST};

/// Instructions per SysTick tick under `-icount shift=0` (1 GHz virtual / 25 MHz).
pub const INSNS_PER_TICK: u64 = 40;
const RELOAD: u32 = 0x00FF_FFFF;

/// A free-running 24-bit SysTick, extended in software (read at least every 400 M insns).
pub struct Counter {
    syst: SYST,
}

impl Counter {
    /// Starts SysTick free-running on the core clock, no interrupt.
    pub fn new(mut syst: SYST) -> Self {
        syst.disable_interrupt();
        syst.set_clock_source(SystClkSource::Core);
        syst.set_reload(RELOAD);
        syst.clear_current();
        syst.enable_counter();
        Self { syst }
    }

    /// Ticks elapsed while running `f` `n` times, as instructions per call (rounded).
    pub fn insns_per_call(&mut self, n: u32, mut f: impl FnMut()) -> u64 {
        let _ = self.syst.has_wrapped();
        let start = SYST::get_current();
        let mut wraps = 0u64;
        for _ in 0..n {
            f();
            if self.syst.has_wrapped() {
                wraps += 1;
            }
        }
        let end = SYST::get_current();
        if self.syst.has_wrapped() {
            wraps += 1;
        }
        // SysTick counts down
        let ticks = wraps * (RELOAD as u64 + 1) + start as u64 - end as u64;
        (ticks * INSNS_PER_TICK + n as u64 / 2) / n as u64
    }
}
