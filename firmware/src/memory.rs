//! The RAM of the application loop's large state ([`Memory`]), which a board lends from a static
//! of its own ([`crate::board::Board::memory`]).

use core::mem::MaybeUninit;
#[cfg(feature = "settings")]
use specpoly_device::store::Buffer;
use specpoly_device::Controller;
use specpoly_protocol::{LineReader, MAX_LINE};

/// The loop's large state, in a static of the board's sized by the types: the line being read,
/// the controller (its calibrated display) and the store's work buffer. `MaybeUninit` keeps
/// them in `.bss`: a reader's `None` fault and a controller's niche would otherwise put their
/// whole initial images in `.data`, i.e. in flash too (2 KiB).
pub struct Memory {
    pub(crate) lines: MaybeUninit<LineReader<MAX_LINE>>,
    pub(crate) controller: MaybeUninit<Controller>,
    #[cfg(feature = "settings")]
    pub(crate) buffer: Buffer,
}

impl Memory {
    /// Uninitialised (zeroed) memory, for a static.
    pub const fn new() -> Self {
        Self {
            lines: MaybeUninit::uninit(),
            controller: MaybeUninit::uninit(),
            #[cfg(feature = "settings")]
            buffer: Buffer::new(),
        }
    }
}

impl Default for Memory {
    fn default() -> Self {
        Self::new()
    }
}
