//! The boards ([`crate::board::Board`] implementations), one file each, for
//! `thumbv7em-none-eabihf`: [`mps2`] (QEMU `mps2-an386`, feature `mps2`) and [`stm32f4`]
//! (STM32F401/F411, feature `stm32f4`). Board assembly and every `unsafe` of the firmware
//! live here.

#[cfg(feature = "mps2")]
pub mod mps2;
#[cfg(feature = "stm32f4")]
pub mod stm32f4;

use core::cell::UnsafeCell;
use core::mem::MaybeUninit;
use core::sync::atomic::{AtomicBool, Ordering};

/// A static holding one `T`, lent out once as `&'static mut T` (the loop's [`Memory`] and
/// the drive table's flash handle).
///
/// [`Memory`]: crate::memory::Memory
pub struct Slot<T> {
    value: UnsafeCell<MaybeUninit<T>>,
    /// Whether `value` was left uninitialised by [`Slot::empty`] (`false` for a full slot,
    /// so that a full slot of zeroed or uninitialised memory stays in `.bss`).
    empty: bool,
    lent: AtomicBool,
}

// SAFETY: the value is reachable only through the one `&'static mut` that `take`/`put` hand
// out (guarded by `lent`), so it is never shared between contexts.
unsafe impl<T> Sync for Slot<T> {}

impl<T> Slot<T> {
    /// A slot holding `value` from the start (a `const` value: no copy at run time).
    pub const fn full(value: T) -> Self {
        Self {
            value: UnsafeCell::new(MaybeUninit::new(value)),
            empty: false,
            lent: AtomicBool::new(false),
        }
    }

    /// An empty slot, for [`Slot::put`].
    pub const fn empty() -> Self {
        Self {
            value: UnsafeCell::new(MaybeUninit::uninit()),
            empty: true,
            lent: AtomicBool::new(false),
        }
    }

    /// The value of a [`Slot::full`] slot; `None` once lent, or for an empty slot.
    #[allow(clippy::mut_from_ref)] // the one `&mut` ever made, guarded by `lent`
    pub fn take(&'static self) -> Option<&'static mut T> {
        if self.empty || self.lent.swap(true, Ordering::AcqRel) {
            return None;
        }
        // SAFETY: initialised by `full` (checked), and `lent` makes this the only reference ever made.
        Some(unsafe { (*self.value.get()).assume_init_mut() })
    }

    /// Stores `value` in an [`Slot::empty`] slot and lends it; `None` once lent, or for a full
    /// slot (its value is kept).
    #[allow(clippy::mut_from_ref)] // the one `&mut` ever made, guarded by `lent`
    pub fn put(&'static self, value: T) -> Option<&'static mut T> {
        if !self.empty || self.lent.swap(true, Ordering::AcqRel) {
            return None;
        }
        // SAFETY: `lent` makes this the only reference ever made; the slot held nothing.
        Some(unsafe { (*self.value.get()).write(value) })
    }
}
