//! The settings flash on STM32F401/F411: sectors 6 and 7 (128 KiB each, `0x0804_0000`–
//! `0x0808_0000`) of a 512 KiB part, outside the image (`memory-stm32f4.x.in` ends FLASH at
//! sector 6). Programming and erasing go through the HAL's `UnlockedFlash` (sector erase,
//! byte programming, locked again after each call); reads are memory-mapped.
//!
//! Hand-written over the HAL's own `NorFlash` because that one declares a 128 KiB erase size
//! but erases whole sectors by address over the *entire* flash: here offsets are relative to
//! sector 6 and erasing can never reach the image.

use core::ptr::read_volatile;
use embedded_storage::nor_flash::{
    ErrorType, MultiwriteNorFlash, NorFlash, NorFlashErrorKind, ReadNorFlash,
};
use stm32f4xx_hal::{flash::FlashExt, pac::FLASH};

/// Flash base address.
const FLASH_BASE: usize = 0x0800_0000;
/// Offset of sector 6 from the flash base.
pub const OFFSET: usize = 0x4_0000;
/// Sector size (sectors 5–11 of the F4 are 128 KiB).
pub const SECTOR: usize = 128 * 1024;
/// The first settings sector's number.
pub const FIRST_SECTOR: u8 = 6;
/// Settings sectors.
pub const SECTORS: usize = 2;

/// Sectors 6–7 as a NOR flash; offsets relative to sector 6.
pub type SettingsFlash = SectorFlash<FIRST_SECTOR, SECTORS>;

/// The drive-correction table's sector (feature `lut`, `specpoly_device::lut`): sector 5, 128 KiB at
/// `0x0802_0000`, below the settings and outside the image (`memory-stm32f4.x.in` ends FLASH
/// at sector 5).
pub type LutFlash = SectorFlash<5, 1>;

/// `N` 128 KiB sectors from sector `FIRST` (5–7) as a NOR flash; offsets relative to sector
/// `FIRST`.
pub struct SectorFlash<const FIRST: u8, const N: usize> {
    flash: FLASH,
}

impl<const FIRST: u8, const N: usize> SectorFlash<FIRST, N> {
    /// Takes the flash interface.
    pub fn new(flash: FLASH) -> Self {
        Self { flash }
    }

    /// Offset of sector `FIRST` from the flash base (sector 5 is at 128 KiB).
    const OFFSET: usize = 0x2_0000 + (FIRST as usize - 5) * SECTOR;
}

impl LutFlash {
    /// The table's sector, through a second handle on the flash interface.
    pub fn take() -> Self {
        // SAFETY: the flash interface is shared with the settings' [`SettingsFlash`]; both
        // are used only from the main loop, one call at a time (a `lut` command or a `save`),
        // and every call leaves the interface locked, as it found it.
        Self::new(unsafe { stm32f4xx_hal::pac::Peripherals::steal() }.FLASH)
    }
}

fn check<const N: usize>(
    offset: u32,
    len: usize,
    align: usize,
) -> Result<usize, NorFlashErrorKind> {
    let offset = offset as usize;
    if !offset.is_multiple_of(align) || !len.is_multiple_of(align) {
        return Err(NorFlashErrorKind::NotAligned);
    }
    match offset.checked_add(len) {
        Some(end) if end <= SECTOR * N => Ok(offset),
        _ => Err(NorFlashErrorKind::OutOfBounds),
    }
}

impl<const FIRST: u8, const N: usize> ErrorType for SectorFlash<FIRST, N> {
    type Error = NorFlashErrorKind;
}

impl<const FIRST: u8, const N: usize> ReadNorFlash for SectorFlash<FIRST, N> {
    const READ_SIZE: usize = 1;

    fn read(&mut self, offset: u32, bytes: &mut [u8]) -> Result<(), Self::Error> {
        let at = FLASH_BASE + Self::OFFSET + check::<N>(offset, bytes.len(), 1)?;
        for (i, b) in bytes.iter_mut().enumerate() {
            // SAFETY: inside this region's sectors of the memory-mapped flash (bounds checked
            // above).
            *b = unsafe { read_volatile((at + i) as *const u8) };
        }
        Ok(())
    }

    fn capacity(&self) -> usize {
        SECTOR * N
    }
}

impl<const FIRST: u8, const N: usize> NorFlash for SectorFlash<FIRST, N> {
    const WRITE_SIZE: usize = 1;
    const ERASE_SIZE: usize = SECTOR;

    fn erase(&mut self, from: u32, to: u32) -> Result<(), Self::Error> {
        let len = (to as usize)
            .checked_sub(from as usize)
            .ok_or(NorFlashErrorKind::OutOfBounds)?;
        let first = check::<N>(from, len, SECTOR)? / SECTOR;
        let mut unlocked = self.flash.unlocked();
        for s in first..first + len / SECTOR {
            unlocked
                .erase(FIRST + s as u8)
                .map_err(|_| NorFlashErrorKind::Other)?;
        }
        Ok(())
    }

    fn write(&mut self, offset: u32, bytes: &[u8]) -> Result<(), Self::Error> {
        let at = Self::OFFSET + check::<N>(offset, bytes.len(), 1)?;
        self.flash
            .unlocked()
            .program(at, bytes.iter())
            .map_err(|_| NorFlashErrorKind::Other)
    }
}

/// The F4's flash has no ECC: programming a byte again only clears more bits.
impl<const FIRST: u8, const N: usize> MultiwriteNorFlash for SectorFlash<FIRST, N> {}
