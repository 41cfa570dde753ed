//! The RGB-LED colour controller on QEMU mps2-an386: wiring only. At start the settings saved
//! in flash are loaded (or the defaults kept, with the reason logged). Lines from UART0 go
//! through the shared protocol parser to the [`Controller`] (`save`/`load` to the settings
//! [`Store`]); the reply goes back on the UART and the duties to the LED, and (QEMU has no PWM)
//! to the defmt log: `duty R G B max=M stack=BYTES`. Mixed channels (`channel`, `xy`, `cct`)
//! are logged as `mix duty [..]`, fade steps as `fade K/N duty [..] stack=BYTES`, one every
//! 10 ms of SysTick time.
#![no_std]
#![no_main]

use core::mem::MaybeUninit;
use core::sync::atomic::{AtomicU32, Ordering};
use cortex_m_rt::{entry, exception};
#[cfg(feature = "lut")]
use specpoly_firmware::board::flash::LutFlash;
#[cfg(feature = "settings")]
use specpoly_firmware::board::flash::{RamFlash, PAGE, PAGES};
use specpoly_firmware::board::{pwm::ReportedPwm, stack, uart::Uart};
#[cfg(feature = "mixing")]
use specpoly_firmware::fade::Pacer;
#[cfg(feature = "settings")]
use specpoly_firmware::store::{self, Blocking, Buffer, LoadError, Store};
use specpoly_firmware::{Controller, RgbLed};
use specpoly_protocol::{Fault, LineReader, Reply, MAX_LINE};

/// The settings store in RAM-backed flash (feature `settings`); nothing without it.
#[cfg(feature = "settings")]
type Storage = (Store<Blocking<RamFlash>>, &'static mut Buffer);
#[cfg(not(feature = "settings"))]
type Storage = ();

/// SysTick period: the core sleeps in `wfi` and wakes on a UART byte or after 1 ms at most.
const TICK: u32 = 25_000;

/// Milliseconds since start (SysTick), for fade steps.
static MILLIS: AtomicU32 = AtomicU32::new(0);

#[entry]
fn main() -> ! {
    // The large state lives in statics sized by their types, not in `main`'s frame
    // (cortex-m-rt makes each a `&'static mut`): the line being read, the reply, the
    // store's work buffer and the controller (its calibrated display).
    // `MaybeUninit` keeps them in `.bss`: a reader's `None` fault and a controller's niche
    // would otherwise put their whole initial images in `.data`, i.e. in flash too (2 KiB)
    static mut LINES: MaybeUninit<LineReader<MAX_LINE>> = MaybeUninit::uninit();
    #[cfg(feature = "settings")]
    static mut BUFFER: Buffer = Buffer::new();
    static mut CONTROLLER: MaybeUninit<Controller> = MaybeUninit::uninit();
    // the drive table's flash region (zero-sized: the region is at a fixed address)
    #[cfg(feature = "lut")]
    static mut LUT_FLASH: MaybeUninit<LutFlash> = MaybeUninit::uninit();
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
    let controller = Controller::init(CONTROLLER, led.max());
    #[cfg(feature = "lut")]
    controller.attach_lut(LUT_FLASH.write(LutFlash::take()));
    let lines = LINES.write(LineReader::new());
    #[cfg(feature = "settings")]
    let mut storage: Storage = {
        let buffer = BUFFER;
        let Ok(mut store) = Store::new(Blocking(RamFlash::take()), 0..(PAGE * PAGES) as u32) else {
            // whole pages, at least two, by the constants
            panic!("settings range");
        };
        match store::restore(controller, &mut store, buffer) {
            Ok(()) => defmt::info!("settings loaded from flash"),
            Err(LoadError::NotSaved) => defmt::info!("no saved settings: defaults used"),
            Err(e) => defmt::warn!("saved settings ignored ({=str}): defaults used", e.name()),
        }
        #[cfg(feature = "mixing")]
        match store::restore_mix(controller, &mut store, buffer) {
            Ok(()) => defmt::info!("mix settings loaded from flash"),
            Err(LoadError::NotSaved) => {}
            Err(e) => defmt::warn!("saved mix settings ignored ({=str})", e.name()),
        }
        (store, buffer)
    };
    #[cfg(not(feature = "settings"))]
    let mut storage: Storage = ();
    defmt::info!("specpoly-led ready");
    #[cfg(feature = "mixing")]
    let mut pacer = Pacer::new(0);
    loop {
        #[cfg(feature = "mixing")]
        if controller.mixer.fading() && pacer.due(MILLIS.load(Ordering::Relaxed)) {
            fade_step(controller);
        }
        let Some(byte) = uart.read() else {
            cortex_m::asm::wfi();
            continue;
        };
        let Some(line) = lines.push(byte) else {
            continue;
        };
        if !answer(line, controller, &mut storage, &mut uart) {
            continue;
        }
        #[cfg(feature = "mixing")]
        if controller.mixer.fading() {
            // a new fade: its first step one period from now
            pacer = Pacer::new(MILLIS.load(Ordering::Relaxed));
        } else if controller.mixer.shown().is_some() {
            log_mix(controller);
        }
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

/// Answers one line (or its fault) on the UART; `false` for an empty line, which gets no
/// reply. The reply is written straight to the UART (no reply buffer: at most `MAX_REPLY`
/// bytes, the protocol's tests bound it). Not inlined: the parsed command and the reply live
/// only while a line is answered, not in `main`'s frame for ever.
#[inline(never)]
fn answer(
    line: Result<&str, Fault>,
    controller: &mut Controller,
    storage: &mut Storage,
    uart: &mut Uart,
) -> bool {
    let reply = match line {
        Ok(l) if l.trim_ascii().is_empty() => return false,
        #[cfg(feature = "settings")]
        Ok(l) => store::handle(controller, &mut storage.0, storage.1, l),
        #[cfg(not(feature = "settings"))]
        Ok(l) => {
            let () = *storage;
            controller.handle(specpoly_firmware::controller::parse(l))
        }
        Err(f) => Reply::Error(f),
    };
    // the UART never refuses a byte
    let _ = reply.write(uart);
    uart.write_byte(b'\n');
    true
}

/// The mixed channels' duties (QEMU has no PWM for them): `mix duty [..]`. Not inlined: the
/// solve behind them is not wanted in `main`'s frame, which lives for ever.
#[cfg(feature = "mixing")]
#[inline(never)]
fn log_mix(controller: &Controller) {
    let n = controller.mixer.channels.list().len();
    defmt::info!("mix duty {=[?]}", controller.mix_duty()[..n]);
}

/// One fade step, its duties logged (`fade K/N duty [..] stack=BYTES`).
#[cfg(feature = "mixing")]
#[inline(never)]
fn fade_step(controller: &mut Controller) {
    if let Some((k, n, duty)) = controller.fade_step() {
        let channels = controller.mixer.channels.list().len();
        defmt::info!(
            "fade {=u16}/{=u16} duty {=[?]} stack={=usize}",
            k,
            n,
            duty[..channels],
            stack::high_water()
        );
    }
}

#[exception]
fn SysTick() {
    MILLIS.fetch_add(1, Ordering::Relaxed);
}
