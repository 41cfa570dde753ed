//! The device part of the vector table: one entry, IRQ 0 = UART0 RX on mps2-an386, instead of
//! cortex-m-rt's default 240 entries (0.9 KiB of flash). No other interrupt is ever enabled.

use super::uart::Uart;

/// UART0 RX: clear the interrupt; `main` reads the byte after `wfi` returns.
extern "C" fn uart0_rx() {
    Uart::clear_rx_interrupt();
}

/// Placed right after the 16 system exceptions by cortex-m-rt's link.x.
#[link_section = ".vector_table.interrupts"]
#[no_mangle]
#[used]
pub static __INTERRUPTS: [extern "C" fn(); 1] = [uart0_rx];
