//! The settings "flash" on QEMU `mps2-an386`: the board has no flash controller (its 4 MiB at
//! `0x0000_0000` are SSRAM that QEMU loads the image into), so the top 16 KiB of that region,
//! which `memory.x` keeps out of the image, act as a NOR flash: erase sets 4 KiB pages to
//! `0xFF`, a write can only clear bits (`old & new`), as on a real NOR part. QEMU leaves this
//! RAM alone on `system_reset`, so saved settings survive a reset (not a restart of QEMU).
//! On a real board the same store runs on the MCU's flash sectors (`boards::stm32f4`).
//!
//! The drive-correction table (feature `lut`, `specpoly_device::lut`) has a region of its own below
//! it: [`LUT_PAGES`] pages at [`LUT_BASE`], the same kind of stand-in ([`LutFlash`]).

use core::ptr::{read_volatile, write_volatile};
use embedded_storage::nor_flash::{
    ErrorType, MultiwriteNorFlash, NorFlash, NorFlashErrorKind, ReadNorFlash,
};

/// First byte of the region (`memory.x`: FLASH ends here).
pub const BASE: usize = 0x003F_C000;
/// Erase page.
pub const PAGE: usize = 4096;
/// Pages (sequential-storage keeps one free; the others take records in turn).
pub const PAGES: usize = 4;

/// First byte of the drive table's region (`memory.x`: FLASH ends here).
pub const LUT_BASE: usize = BASE - PAGE * LUT_PAGES;
/// The drive table's pages: a 13³ table (13 536 B) fits.
pub const LUT_PAGES: usize = 4;

/// A RAM-backed NOR flash of `N` pages at `AT`; offsets are relative to it.
pub struct RamFlash<const AT: usize = BASE, const N: usize = PAGES>(());

/// The drive table's region.
pub type LutFlash = RamFlash<LUT_BASE, LUT_PAGES>;

impl<const AT: usize, const N: usize> RamFlash<AT, N> {
    /// The region. Call once: two handles would interleave writes.
    ///
    /// QEMU powers SSRAM up as zeros, where a new NOR part reads erased (`0xFF`): a region of
    /// nothing but zeros is such a fresh start (sequential-storage never leaves one) and is
    /// erased here, so the first start finds "nothing saved" rather than a damaged store.
    pub fn take() -> Self {
        let mut f = Self(());
        let zeros = (AT..AT + PAGE * N)
            .step_by(4)
            // SAFETY: as in `read`: the region, word-aligned.
            .all(|a| unsafe { read_volatile(a as *const u32) } == 0);
        if zeros {
            let _ = f.erase(0, (PAGE * N) as u32);
        }
        f
    }
}

/// The address of `len` bytes at `offset` in the region of `pages` pages at `base`.
fn check(
    (base, pages): (usize, usize),
    offset: u32,
    len: usize,
    align: usize,
) -> Result<usize, NorFlashErrorKind> {
    let offset = offset as usize;
    if !offset.is_multiple_of(align) || !len.is_multiple_of(align) {
        return Err(NorFlashErrorKind::NotAligned);
    }
    match offset.checked_add(len) {
        Some(end) if end <= PAGE * pages => Ok(base + offset),
        _ => Err(NorFlashErrorKind::OutOfBounds),
    }
}

impl<const AT: usize, const N: usize> ErrorType for RamFlash<AT, N> {
    type Error = NorFlashErrorKind;
}

impl<const AT: usize, const N: usize> ReadNorFlash for RamFlash<AT, N> {
    const READ_SIZE: usize = 1;

    fn read(&mut self, offset: u32, bytes: &mut [u8]) -> Result<(), Self::Error> {
        let at = check((AT, N), offset, bytes.len(), 1)?;
        for (i, b) in bytes.iter_mut().enumerate() {
            // SAFETY: [LUT_BASE, BASE + 16 KiB) is SSRAM outside the image and the stack
            // (memory.x), used by nothing else; bounds checked above (the two regions do not
            // overlap, and each is taken once).
            *b = unsafe { read_volatile((at + i) as *const u8) };
        }
        Ok(())
    }

    fn capacity(&self) -> usize {
        PAGE * N
    }
}

impl<const AT: usize, const N: usize> NorFlash for RamFlash<AT, N> {
    const WRITE_SIZE: usize = 4;
    const ERASE_SIZE: usize = PAGE;

    fn erase(&mut self, from: u32, to: u32) -> Result<(), Self::Error> {
        let len = (to as usize)
            .checked_sub(from as usize)
            .ok_or(NorFlashErrorKind::OutOfBounds)?;
        let at = check((AT, N), from, len, PAGE)?;
        for a in (at..at + len).step_by(4) {
            // SAFETY: as in `read`; word-aligned since BASE and PAGE are.
            unsafe { write_volatile(a as *mut u32, u32::MAX) };
        }
        Ok(())
    }

    fn write(&mut self, offset: u32, bytes: &[u8]) -> Result<(), Self::Error> {
        let at = check((AT, N), offset, bytes.len(), 4)?;
        for (i, b) in bytes.iter().enumerate() {
            let p = (at + i) as *mut u8;
            // SAFETY: as in `read`. NOR programming clears bits only.
            unsafe { write_volatile(p, read_volatile(p) & *b) };
        }
        Ok(())
    }
}

/// Writing a word twice only clears more bits, as on NOR flash without ECC.
impl<const AT: usize, const N: usize> MultiwriteNorFlash for RamFlash<AT, N> {}
