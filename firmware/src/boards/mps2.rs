//! The QEMU `mps2-an386` board (Cortex-M4F, feature `mps2`): [`Mps2`], the application loop's
//! [`Board`] — the CMSDK UART0 (polled, its RX interrupt waking the core from `wfi`), six PWM
//! stand-ins whose duties are reported in the log (QEMU emulates no PWM), RAM-backed settings
//! and drive-table flashes, SysTick as the millisecond clock, the painted stack's high-water
//! mark. Also here for the other binaries: an instruction counter, the defmt logger
//! (semihosting), the panic handler and the framebuffer demo's RGB565 and RGB888 kernels in
//! assembly. `unsafe` is confined to these files: memory-mapped registers, the stack region and
//! the calls into the assembly kernels, each block with its reason.

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

use super::Slot;
use crate::board::Board;
use crate::memory::Memory;
use core::panic::PanicInfo;
use core::sync::atomic::{AtomicU32, Ordering};
use cortex_m::peripheral::syst::SystClkSource;
use cortex_m_rt::exception;
use cortex_m_semihosting::debug;
use pwm::ReportedPwm;
use specpoly_device::led::CHANNELS;
use specpoly_device::{Led, LedError};
use uart::Uart;

/// SysTick period: the core (25 MHz) sleeps in `wfi` and wakes on a UART byte or after 1 ms at
/// most.
const TICK: u32 = 25_000;

/// Milliseconds since start (SysTick).
static MILLIS: AtomicU32 = AtomicU32::new(0);

/// The application loop's RAM.
static MEMORY: Slot<Memory> = Slot::full(Memory::new());

/// The drive table's region (zero-sized: the region is at a fixed address).
#[cfg(feature = "lut")]
static DRIVE_TABLE: Slot<flash::LutFlash> = Slot::empty();

/// QEMU mps2-an386 as the controller's board.
pub struct Mps2 {
    uart: Uart,
    led: Led<ReportedPwm, CHANNELS>,
}

impl Mps2 {
    /// The board: stack painted (first: the high-water mark counts from here), UART0 enabled,
    /// SysTick ticking every millisecond, the PWM stand-ins off.
    pub fn take() -> Self {
        stack::paint();
        let uart = Uart::uart0();
        if let Some(mut p) = cortex_m::Peripherals::take() {
            p.SYST.set_clock_source(SystClkSource::Core);
            p.SYST.set_reload(TICK - 1);
            p.SYST.clear_current();
            p.SYST.enable_interrupt();
            p.SYST.enable_counter();
        }
        let Ok(led) = Led::new(core::array::from_fn(|_| ReportedPwm::default())) else {
            // equal, non-zero maxima by construction
            panic!("PWM stand-in");
        };
        Self { uart, led }
    }

    /// The duties the stand-ins hold.
    pub fn duties(&self) -> [u16; CHANNELS] {
        self.led.duty()
    }
}

impl Board for Mps2 {
    type PwmError = core::convert::Infallible;
    #[cfg(feature = "settings")]
    type SettingsFlash = flash::RamFlash;

    fn memory(&mut self) -> &'static mut Memory {
        match MEMORY.take() {
            Some(m) => m,
            None => panic!("memory lent twice"),
        }
    }

    fn read(&mut self) -> Option<u8> {
        self.uart.read()
    }

    fn write(&mut self, bytes: &[u8]) {
        for b in bytes {
            self.uart.write_byte(*b);
        }
    }

    fn max_duty(&self) -> u16 {
        self.led.max()
    }

    fn set_duties(&mut self, duty: &[u16]) -> Result<(), LedError<Self::PwmError>> {
        self.led.set(duty)
    }

    #[cfg(feature = "settings")]
    fn settings_flash(&mut self) -> flash::RamFlash {
        flash::RamFlash::take()
    }

    #[cfg(feature = "lut")]
    fn drive_table(&mut self) -> &'static mut dyn specpoly_device::lut::Region {
        match DRIVE_TABLE.put(flash::LutFlash::take()) {
            Some(f) => f,
            None => panic!("drive table taken twice"),
        }
    }

    fn millis(&self) -> u32 {
        MILLIS.load(Ordering::Relaxed)
    }

    fn idle(&mut self) {
        cortex_m::asm::wfi();
    }

    fn stack_high_water(&self) -> usize {
        stack::high_water()
    }
}

#[exception]
fn SysTick() {
    MILLIS.fetch_add(1, Ordering::Relaxed);
}

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
