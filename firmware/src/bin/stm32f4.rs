//! The RGB-LED colour controller on an STM32F401/F411 board (feature `stm32f4`): wiring only,
//! as `src/main.rs` on QEMU. USART2 lines → protocol → [`Controller`] (`save`/`load` to the
//! settings [`Store`] in flash sectors 6–7) → reply on USART2, duties on TIM3 CH1–3. Pins,
//! clock and wiring: `specpoly_firmware::stm32f4` and firmware/README.md.
#![no_std]
#![no_main]

use cortex_m_rt::entry;
use heapless::String;
#[cfg(feature = "lut")]
use specpoly_firmware::stm32f4::flash::LutFlash;
use specpoly_firmware::stm32f4::flash::{SettingsFlash, SECTOR, SECTORS};
use specpoly_firmware::store::{self, Blocking, Buffer, LoadError, Store};
use specpoly_firmware::{Controller, RgbLed};
use specpoly_protocol::{LineReader, Reply, MAX_LINE, MAX_REPLY};
use stm32f4xx_hal::{block, nb, pac, prelude::*, rcc::Config, serial::Serial};

#[entry]
fn main() -> ! {
    // the drive table's flash handle (cortex-m-rt makes it a `&'static mut`)
    #[cfg(feature = "lut")]
    static mut LUT_FLASH: core::mem::MaybeUninit<LutFlash> = core::mem::MaybeUninit::uninit();
    let Some(dp) = pac::Peripherals::take() else {
        panic!("peripherals taken twice");
    };
    // HSI 16 MHz, no PLL: no spinning on clock-ready flags (see the module docs)
    let mut rcc = dp.RCC.freeze(Config::hsi());
    let gpioa = dp.GPIOA.split(&mut rcc);
    let gpiob = dp.GPIOB.split(&mut rcc);
    let serial: Result<Serial<pac::USART2, u8>, _> =
        dp.USART2
            .serial((gpioa.pa2, gpioa.pa3), 115_200.bps(), &mut rcc);
    let Ok(mut serial) = serial else {
        panic!("USART2 configuration");
    };
    let (_, (c1, c2, c3, ..)) = dp.TIM3.pwm_hz(1.kHz(), &mut rcc);
    let (mut r, mut g, mut b) = (c1.with(gpioa.pa6), c2.with(gpioa.pa7), c3.with(gpiob.pb0));
    r.enable();
    g.enable();
    b.enable();
    let Ok(mut led) = RgbLed::new(r, g, b) else {
        // one timer: equal, non-zero maxima
        panic!("TIM3 channels");
    };
    let mut controller = Controller::new(led.max());
    // the drive table's sector (feature `lut`), before the settings are restored
    #[cfg(feature = "lut")]
    controller.attach_lut(LUT_FLASH.write(LutFlash::take()));
    let mut buffer = Buffer::new();
    let flash = Blocking(SettingsFlash::new(dp.FLASH));
    let Ok(mut store) = Store::new(flash, 0..(SECTOR * SECTORS) as u32) else {
        panic!("settings range");
    };
    match store::restore(&mut controller, &mut store, &mut buffer) {
        Ok(()) => defmt::info!("settings loaded from flash"),
        Err(LoadError::NotSaved) => defmt::info!("no saved settings: defaults used"),
        Err(e) => defmt::warn!("saved settings ignored ({=str}): defaults used", e.name()),
    }
    let mut lines = LineReader::<MAX_LINE>::new();
    let mut out: String<MAX_REPLY> = String::new();
    defmt::info!("specpoly-led ready, PWM max={=u16}", led.max());
    loop {
        let byte = match serial.read() {
            Ok(b) => b,
            Err(nb::Error::WouldBlock) => continue,
            // overrun or framing: the byte is lost; the line reader's checks catch the rest
            Err(nb::Error::Other(_)) => continue,
        };
        let Some(line) = lines.push(byte) else {
            continue;
        };
        let reply = match line {
            Ok(l) if l.trim_ascii().is_empty() => continue,
            Ok(l) => store::handle(&mut controller, &mut store, &mut buffer, l),
            Err(f) => Reply::Error(f),
        };
        out.clear();
        if reply.write(&mut out).is_err() {
            out.clear();
            let _ = out.push_str("err too-long");
        }
        for &c in out.as_bytes().iter().chain(b"\n") {
            let _ = block!(serial.write(c));
        }
        let duty = controller.duty();
        if led.set(duty).is_ok() {
            defmt::info!(
                "duty {=u16} {=u16} {=u16} max={=u16}",
                duty[0],
                duty[1],
                duty[2],
                led.max()
            );
        }
    }
}
