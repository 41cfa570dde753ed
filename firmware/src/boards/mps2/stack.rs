//! Stack use by painting: the free RAM below the stack is filled with a pattern at start-up;
//! the lowest word no longer holding it marks the deepest the stack has grown.
//!
//! cortex-m-rt places `.data`/`.bss` at the bottom of RAM (ending at `__sheap`) and the stack at
//! the top (`_stack_start`), growing down. Only the [`PAINTED`] bytes below the current stack
//! pointer are painted, which bounds the scan.

use core::ptr::{addr_of, read_volatile, write_volatile};

/// Bytes painted below the stack pointer at [`paint`].
pub const PAINTED: usize = 32 * 1024;
const PATTERN: u32 = 0x5EED_C0DE;

extern "C" {
    static _stack_start: u32;
    static __sheap: u32;
}

fn top() -> usize {
    // a linker symbol: only its address is taken, never read
    addr_of!(_stack_start) as usize
}

fn floor() -> usize {
    let heap = addr_of!(__sheap) as usize;
    heap.max(top() - PAINTED - 256)
}

/// Paints the free stack region below the caller's stack pointer (less a 64-byte margin for
/// this function's own frame). Call once, first thing in `main`.
#[inline(never)]
pub fn paint() {
    let sp = cortex_m::register::msp::read() as usize - 64;
    let mut a = floor();
    while a < sp {
        // SAFETY: [floor, sp − 64) is RAM between the end of `.bss` and the live stack, which
        // nothing else uses (no heap); word-aligned since both ends are.
        unsafe { write_volatile(a as *mut u32, PATTERN) };
        a += 4;
    }
}

/// The deepest stack use so far, in bytes below `_stack_start`.
pub fn high_water() -> usize {
    let mut a = floor();
    let t = top();
    // SAFETY: reads of the painted RAM region, word-aligned.
    while a < t && unsafe { read_volatile(a as *const u32) } == PATTERN {
        a += 4;
    }
    t - a
}
