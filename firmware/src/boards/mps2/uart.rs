//! The CMSDK APB UART of the MPS2 boards (ARM DDI 0479C, §4.6), UART0 at `0x4000_4000`:
//! DATA `0x0`, STATE `0x4` (bit 0 TX full, bit 1 RX full), CTRL `0x8` (bit 0 TX enable, bit 1 RX
//! enable, bit 3 RX interrupt enable), INTSTATUS `0xC` (bit 1 RX, write 1 to clear),
//! BAUDDIV `0x10`. Polled, with the RX interrupt (IRQ 0) used only to wake the core from `wfi`.

use core::ptr::{read_volatile, write_volatile};

const UART0: usize = 0x4000_4000;
const DATA: usize = 0x0;
const STATE: usize = 0x4;
const CTRL: usize = 0x8;
const INTSTATUS: usize = 0xC;
const BAUDDIV: usize = 0x10;
const TX_FULL: u32 = 1 << 0;
const RX_FULL: u32 = 1 << 1;
/// NVIC interrupt set-enable register 0 (ARMv7-M ARM, B3.4.4); UART0 RX is IRQ 0 on MPS2.
const NVIC_ISER0: usize = 0xE000_E100;

/// UART0, owned once (see [`Uart::uart0`]).
pub struct Uart {
    base: usize,
}

fn read(addr: usize) -> u32 {
    // SAFETY: `addr` is one of UART0's word-aligned registers, which are always mapped on
    // mps2-an386; a volatile read has no other effect than the device's own.
    unsafe { read_volatile(addr as *const u32) }
}

fn write(addr: usize, v: u32) {
    // SAFETY: as in `read`: a mapped, word-aligned device register.
    unsafe { write_volatile(addr as *mut u32, v) }
}

impl Uart {
    /// Enables UART0 (TX, RX and the RX interrupt, so `wfi` wakes on a byte). Call once, from
    /// `main`: two `Uart`s would interleave bytes.
    pub fn uart0() -> Self {
        write(UART0 + BAUDDIV, 16);
        write(UART0 + CTRL, 0b1011);
        write(NVIC_ISER0, 1);
        Self { base: UART0 }
    }

    /// A received byte, if one is waiting.
    pub fn read(&mut self) -> Option<u8> {
        if read(self.base + STATE) & RX_FULL != 0 {
            Some(read(self.base + DATA) as u8)
        } else {
            None
        }
    }

    /// Clears the RX interrupt (from its handler).
    pub fn clear_rx_interrupt() {
        write(UART0 + INTSTATUS, RX_FULL);
    }

    /// Sends one byte, waiting while the transmitter is full.
    pub fn write_byte(&mut self, b: u8) {
        while read(self.base + STATE) & TX_FULL != 0 {}
        write(self.base + DATA, b as u32);
    }
}

impl core::fmt::Write for Uart {
    fn write_str(&mut self, s: &str) -> core::fmt::Result {
        for b in s.bytes() {
            self.write_byte(b);
        }
        Ok(())
    }
}
