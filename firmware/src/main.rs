//! The RGB-LED colour controller on QEMU mps2-an386: wiring only. At start the settings saved
//! in flash are loaded (or the defaults kept, with the reason logged). Lines from UART0 go
//! through the shared protocol parser to the [`Controller`] (`save`/`load` to the settings
//! [`Store`]); the reply goes back on the UART and the duties to the LED, and (QEMU has no PWM)
//! to the defmt log: `duty R G B max=M stack=BYTES`.
#![no_std]
#![no_main]

use core::fmt::Write as _;
use cortex_m_rt::{entry, exception};
use heapless::String;
use specpoly_firmware::board::{
    flash::{RamFlash, PAGE, PAGES},
    pwm::ReportedPwm,
    stack,
    uart::Uart,
};
use specpoly_firmware::store::{self, Blocking, Buffer, LoadError, Store};
use specpoly_firmware::{Controller, RgbLed};
use specpoly_protocol::{Command, LineReader, Reply, MAX_LINE, MAX_REPLY};

/// SysTick period: the core sleeps in `wfi` and wakes on a UART byte or after 1 ms at most.
const TICK: u32 = 25_000;

#[entry]
fn main() -> ! {
    stack::paint();
    let mut uart = Uart::uart0();
    if let Some(mut p) = cortex_m::Peripherals::take() {
        p.SYST
            .set_clock_source(cortex_m::peripheral::syst::SystClkSource::Core);
        p.SYST.set_reload(TICK - 1);
        p.SYST.clear_current();
        p.SYST.enable_interrupt();
        p.SYST.enable_counter();
    }
    let mut led = match RgbLed::new(
        ReportedPwm::default(),
        ReportedPwm::default(),
        ReportedPwm::default(),
    ) {
        Ok(l) => l,
        // equal, non-zero maxima by construction
        Err(_) => panic!("PWM stand-in"),
    };
    let mut controller = Controller::new(led.max());
    let mut buffer = Buffer::new();
    let Ok(mut store) = Store::new(Blocking(RamFlash::take()), 0..(PAGE * PAGES) as u32) else {
        // whole pages, at least two, by the constants
        panic!("settings range");
    };
    match store.load(&mut buffer) {
        Ok(s) => match controller.apply(&s) {
            Ok(()) => defmt::info!("settings loaded from flash"),
            Err(_) => defmt::warn!("saved settings not applicable: defaults used"),
        },
        Err(LoadError::NotSaved) => defmt::info!("no saved settings: defaults used"),
        Err(e) => defmt::warn!("saved settings ignored ({=str}): defaults used", e.name()),
    }
    let mut lines = LineReader::<MAX_LINE>::new();
    let mut out: String<MAX_REPLY> = String::new();
    defmt::info!("specpoly-led ready");
    loop {
        let Some(byte) = uart.read() else {
            cortex_m::asm::wfi();
            continue;
        };
        let Some(line) = lines.push(byte) else {
            continue;
        };
        let reply = match line {
            Ok(l) if l.trim_ascii().is_empty() => continue,
            Ok(l) => store::handle(&mut controller, &mut store, &mut buffer, Command::parse(l)),
            Err(f) => Reply::Error(f),
        };
        out.clear();
        if reply.write(&mut out).is_err() {
            // a reply longer than MAX_REPLY (bounded by the protocol's tests): say so
            out.clear();
            let _ = out.push_str("err too-long");
        }
        let _ = uart.write_str(&out);
        uart.write_byte(b'\n');
        let duty = controller.duty();
        if led.set(duty).is_ok() {
            defmt::info!(
                "duty {=u16} {=u16} {=u16} max={=u16} stack={=usize}",
                duty[0],
                duty[1],
                duty[2],
                led.max(),
                stack::high_water()
            );
        }
    }
}

#[exception]
fn SysTick() {}
