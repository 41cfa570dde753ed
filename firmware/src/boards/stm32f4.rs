//! The STM32F401/F411 board (Cortex-M4F, feature `stm32f4`, binary `stm32f4`) with
//! `stm32f4xx-hal`: NUCLEO-F401RE and the "Black Pill" F401CE/F411CE (512 KiB parts).
//! [`Stm32f4`] is the application loop's [`Board`]:
//!
//! - clock: the 16 MHz HSI the chip starts on, no PLL. `Rcc::freeze` then waits on no ready
//!   flag (it spins only for HSE and PLL), so the same image also starts on QEMU's
//!   `netduinoplus2`, whose RCC is not modelled (its flags never set). 16 MHz computes a
//!   default-preset `refl` line in ≈ 10 ms;
//! - LED channels: six PWM channels at 1 kHz, full scale 16 000 ([`PINS`]): TIM3 CH1–4 on PA6,
//!   PA7, PB0, PB1 and TIM4 CH1–2 on PB6, PB7 (alternate function 2), each an
//!   [`embedded_hal::pwm::SetDutyCycle`]; the colour path drives the first three (red, green,
//!   blue), the mixer as many as were uploaded;
//! - millisecond clock: TIM5 (32 bits) counting at 1 kHz, free-running, read without
//!   interrupts (the fades' steps);
//! - line protocol: USART2 on PA2 (TX) / PA3 (RX), 115200 8N1 (the NUCLEO's ST-LINK virtual
//!   COM port; a 3.3 V USB-serial adapter on a Black Pill), polled;
//! - settings: flash sectors 6 and 7 (2 × 128 KiB at `0x0804_0000`), [`flash::SettingsFlash`];
//!   the drive table in sector 5 ([`flash::LutFlash`]);
//! - logs: defmt over RTT (`probe-rs run`, or `defmt-print` on a captured RTT stream);
//!   panics are logged and end in `udf`, which a debug probe reports.

#[cfg(any(feature = "settings", feature = "lut"))]
pub mod flash;

// the global defmt logger: RTT, read by the debug probe
use defmt_rtt as _;

use super::Slot;
use crate::board::Board;
use crate::memory::Memory;
use core::panic::PanicInfo;
use specpoly_device::led::CHANNELS;
use specpoly_device::{Led, LedError};
use stm32f4xx_hal::pac::{self, TIM3, TIM4, TIM5};
use stm32f4xx_hal::timer::{CounterMs, ErasedChannel};
use stm32f4xx_hal::{nb, prelude::*, rcc::Config, serial::Serial};

/// The LED channels' pins, in channel order (timer channel, MCU pin).
pub const PINS: [(&str, &str); CHANNELS] = [
    ("TIM3 CH1", "PA6"),
    ("TIM3 CH2", "PA7"),
    ("TIM3 CH3", "PB0"),
    ("TIM3 CH4", "PB1"),
    ("TIM4 CH1", "PB6"),
    ("TIM4 CH2", "PB7"),
];

/// PWM frequency.
const PWM_HZ: u32 = 1_000;

/// The application loop's RAM.
static MEMORY: Slot<Memory> = Slot::full(Memory::new());

/// The drive table's sector handle.
#[cfg(feature = "lut")]
static DRIVE_TABLE: Slot<flash::LutFlash> = Slot::empty();

/// A PWM channel of TIM3 or TIM4 (one type for the [`Led`]'s six).
pub enum Channel {
    /// TIM3 CH1–4.
    Tim3(ErasedChannel<TIM3>),
    /// TIM4 CH1–2.
    Tim4(ErasedChannel<TIM4>),
}

impl embedded_hal::pwm::ErrorType for Channel {
    type Error = core::convert::Infallible;
}

impl embedded_hal::pwm::SetDutyCycle for Channel {
    fn max_duty_cycle(&self) -> u16 {
        match self {
            Channel::Tim3(c) => c.max_duty_cycle(),
            Channel::Tim4(c) => c.max_duty_cycle(),
        }
    }

    fn set_duty_cycle(&mut self, duty: u16) -> Result<(), Self::Error> {
        match self {
            Channel::Tim3(c) => c.set_duty_cycle(duty),
            Channel::Tim4(c) => c.set_duty_cycle(duty),
        }
    }
}

/// An STM32F401/F411 board as the controller's board.
pub struct Stm32f4 {
    serial: Serial<pac::USART2, u8>,
    led: Led<Channel, CHANNELS>,
    clock: CounterMs<TIM5>,
    #[cfg(feature = "settings")]
    flash: Option<pac::FLASH>,
}

impl Stm32f4 {
    /// The board: HSI clock, USART2, the six PWM channels (off), TIM5 counting milliseconds.
    pub fn take() -> Self {
        let Some(dp) = pac::Peripherals::take() else {
            panic!("peripherals taken twice");
        };
        // HSI 16 MHz, no PLL: no spinning on clock-ready flags (see the module docs)
        let mut rcc = dp.RCC.freeze(Config::hsi());
        let gpioa = dp.GPIOA.split(&mut rcc);
        let gpiob = dp.GPIOB.split(&mut rcc);
        let serial = dp
            .USART2
            .serial((gpioa.pa2, gpioa.pa3), 115_200.bps(), &mut rcc);
        let Ok(serial) = serial else {
            panic!("USART2 configuration");
        };
        let (_, (t3c1, t3c2, t3c3, t3c4)) = dp.TIM3.pwm_hz(PWM_HZ.Hz(), &mut rcc);
        let (_, (t4c1, t4c2, ..)) = dp.TIM4.pwm_hz(PWM_HZ.Hz(), &mut rcc);
        let mut channels = [
            Channel::Tim3(t3c1.with(gpioa.pa6).erase()),
            Channel::Tim3(t3c2.with(gpioa.pa7).erase()),
            Channel::Tim3(t3c3.with(gpiob.pb0).erase()),
            Channel::Tim3(t3c4.with(gpiob.pb1).erase()),
            Channel::Tim4(t4c1.with(gpiob.pb6).erase()),
            Channel::Tim4(t4c2.with(gpiob.pb7).erase()),
        ];
        for c in &mut channels {
            match c {
                Channel::Tim3(c) => c.enable(),
                Channel::Tim4(c) => c.enable(),
            }
        }
        let Ok(led) = Led::new(channels) else {
            // two timers on the same bus clock at the same frequency: equal, non-zero maxima
            panic!("TIM3/TIM4 channels");
        };
        let mut clock = dp.TIM5.counter_ms(&mut rcc);
        if clock.start(u32::MAX.millis()).is_err() {
            panic!("TIM5 clock");
        }
        Self {
            serial,
            led,
            clock,
            #[cfg(feature = "settings")]
            flash: Some(dp.FLASH),
        }
    }
}

impl Board for Stm32f4 {
    type PwmError = core::convert::Infallible;
    #[cfg(feature = "settings")]
    type SettingsFlash = flash::SettingsFlash;

    fn memory(&mut self) -> &'static mut Memory {
        match MEMORY.take() {
            Some(m) => m,
            None => panic!("memory lent twice"),
        }
    }

    fn read(&mut self) -> Option<u8> {
        // nothing waiting, or an overrun or framing error: that byte is lost; the line
        // reader's checks catch the rest
        self.serial.read().ok()
    }

    fn write(&mut self, bytes: &[u8]) {
        for b in bytes {
            let _ = nb::block!(self.serial.write(*b));
        }
    }

    fn max_duty(&self) -> u16 {
        self.led.max()
    }

    fn set_duties(&mut self, duty: &[u16]) -> Result<(), LedError<Self::PwmError>> {
        self.led.set(duty)
    }

    #[cfg(feature = "settings")]
    fn settings_flash(&mut self) -> flash::SettingsFlash {
        match self.flash.take() {
            Some(f) => flash::SettingsFlash::new(f),
            None => panic!("settings flash taken twice"),
        }
    }

    #[cfg(feature = "lut")]
    fn drive_table(&mut self) -> &'static mut dyn specpoly_device::lut::Region {
        match DRIVE_TABLE.put(flash::LutFlash::take()) {
            Some(f) => f,
            None => panic!("drive table taken twice"),
        }
    }

    fn millis(&self) -> u32 {
        self.clock.now().ticks()
    }
}

/// Logs where through defmt, then stops in `udf` (the probe shows a HardFault at the panic).
/// Hand-written rather than `panic-probe` for the reason given in `boards::mps2`'s.
#[panic_handler]
fn panic(info: &PanicInfo) -> ! {
    match info.location() {
        Some(l) => defmt::error!("firmware panic at {=str}:{=u32}", l.file(), l.line()),
        None => defmt::error!("firmware panic"),
    }
    cortex_m::asm::udf()
}
