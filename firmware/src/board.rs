//! What a board gives the application loop ([`crate::app::run`]): the UART, the PWM channels,
//! the settings and drive-table flashes, a millisecond clock and the RAM for the loop's large
//! state. One implementation per board in [`crate::boards`], where all the board's set-up and
//! `unsafe` live; the loop itself is the same on every board.

use crate::memory::Memory;
use specpoly_device::LedError;

/// A board the controller runs on.
pub trait Board {
    /// The error of a PWM channel (`Infallible` for timer channels).
    type PwmError;
    /// The settings flash (feature `settings`): a NOR flash whose whole capacity is the
    /// settings store's.
    #[cfg(feature = "settings")]
    type SettingsFlash: embedded_storage::nor_flash::NorFlash;

    /// The RAM of the loop's large state (line, controller, store buffer), in a static of the
    /// board's; lent once (a second call panics).
    fn memory(&mut self) -> &'static mut Memory;

    /// A byte received on the UART, if one is waiting.
    fn read(&mut self) -> Option<u8>;

    /// Sends `bytes` on the UART, waiting while the transmitter is full.
    fn write(&mut self, bytes: &[u8]);

    /// The full-scale duty shared by the PWM channels.
    fn max_duty(&self) -> u16;

    /// Drives the PWM channels: `duty[i]` on channel `i` (clamped to [`Board::max_duty`]), the
    /// channels past `duty.len()` off.
    fn set_duties(&mut self, duty: &[u16]) -> Result<(), LedError<Self::PwmError>>;

    /// The settings flash (feature `settings`), taken once at start.
    #[cfg(feature = "settings")]
    fn settings_flash(&mut self) -> Self::SettingsFlash;

    /// The drive table's flash region (feature `lut`), taken once at start.
    #[cfg(feature = "lut")]
    fn drive_table(&mut self) -> &'static mut dyn specpoly_device::lut::Region;

    /// Milliseconds since start, wrapping: the fades' clock.
    fn millis(&self) -> u32;

    /// Called when no byte is waiting: may sleep until the next interrupt (a received byte or
    /// a clock tick). The default returns at once (polling).
    fn idle(&mut self) {}

    /// The deepest stack use so far, in bytes, for the log; 0 where the board does not measure
    /// it.
    fn stack_high_water(&self) -> usize {
        0
    }
}
