//! Board support for STM32F401/F411 (Cortex-M4F) with `stm32f4xx-hal`: NUCLEO-F401RE and the
//! "Black Pill" F401CE/F411CE (512 KiB parts). Feature `stm32f4`, binary `stm32f4`.
//!
//! - clock: the 16 MHz HSI the chip starts on, no PLL. `Rcc::freeze` then waits on no ready
//!   flag (it spins only for HSE and PLL), so the same image also starts on QEMU's
//!   `netduinoplus2`, whose RCC is not modelled (its flags never set). 16 MHz computes a
//!   default-preset `refl` line in ≈ 10 ms;
//! - LED: TIM3 channels 1–3 on PA6, PA7, PB0 at 1 kHz, [`embedded_hal::pwm::SetDutyCycle`];
//! - line protocol: USART2 on PA2 (TX) / PA3 (RX), 115200 8N1 (the NUCLEO's ST-LINK virtual
//!   COM port; a 3.3 V USB-serial adapter on a Black Pill);
//! - settings: flash sectors 6 and 7 (2 × 128 KiB at `0x0804_0000`), [`flash::SettingsFlash`];
//! - logs: defmt over RTT (`probe-rs run`, or `defmt-print` on a captured RTT stream);
//!   panics are logged and end in `udf`, which a debug probe reports.

#[cfg(any(feature = "settings", feature = "lut"))]
pub mod flash;

// the global defmt logger: RTT, read by the debug probe
use defmt_rtt as _;

use core::panic::PanicInfo;

/// Logs where through defmt, then stops in `udf` (the probe shows a HardFault at the panic).
/// Hand-written rather than `panic-probe` for the reason given in `board::panic` (mps2).
#[panic_handler]
fn panic(info: &PanicInfo) -> ! {
    match info.location() {
        Some(l) => defmt::error!("firmware panic at {=str}:{=u32}", l.file(), l.line()),
        None => defmt::error!("firmware panic"),
    }
    cortex_m::asm::udf()
}
