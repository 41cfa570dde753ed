//! The application loop every board runs ([`run`]): UART bytes → [`LineReader`] → the
//! [`Controller`] (`save`/`load` with the settings store) → the reply on the UART → the PWM
//! channels ([`Output`]: the colour path's three duties or the mixer's up to six), with fade
//! steps on the board's millisecond clock ([`Pacer`]). At start the drive table's region is
//! attached and the saved settings (calibration, then the mixer's) are restored.
//!
//! The log (defmt) is the tests' window on the device: `duty R G B max=M stack=BYTES` after
//! every line answered (the colour path's duties), `mix duty [..]` when a mix target is shown
//! at once, `fade K/N duty [..] stack=BYTES` for every fade step.

use crate::board::Board;
use crate::memory::Memory;
use core::fmt;
#[cfg(feature = "mixing")]
use specpoly_device::fade::Pacer;
#[cfg(feature = "settings")]
use specpoly_device::store::{self, Blocking, Buffer, LoadError, Store};
use specpoly_device::{Controller, Duties, LedError, Output};
use specpoly_protocol::{Fault, LineReader, Reply};

/// The settings store on the board's flash (feature `settings`); nothing without it.
struct Storage<B: Board> {
    #[cfg(feature = "settings")]
    store: Store<Blocking<B::SettingsFlash>>,
    #[cfg(feature = "settings")]
    buffer: &'static mut Buffer,
    #[cfg(not(feature = "settings"))]
    board: core::marker::PhantomData<B>,
}

/// What answering a line did.
enum Answer {
    /// An empty line: no reply.
    Empty,
    /// A reply; the channels stay as they are.
    Kept,
    /// A reply, and the channels are to show these duties.
    Drive(Duties),
    /// A reply that started a fade: its steps drive the channels.
    Fade,
}

/// The UART as a `fmt::Write`: replies go out as they are formatted (no reply buffer).
struct Uart<'a, B>(&'a mut B);

impl<B: Board> fmt::Write for Uart<'_, B> {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        self.0.write(s.as_bytes());
        Ok(())
    }
}

/// Runs the controller on `board` for ever.
pub fn run<B: Board>(mut board: B) -> ! {
    let Memory {
        lines,
        controller,
        #[cfg(feature = "settings")]
        buffer,
    } = board.memory();
    let controller = Controller::init(controller, board.max_duty());
    // the drive table's region, before the settings are restored
    #[cfg(feature = "lut")]
    controller.attach_lut(board.drive_table());
    let lines = lines.write(LineReader::new());
    #[cfg(feature = "settings")]
    let mut storage = restore(&mut board, controller, buffer);
    #[cfg(not(feature = "settings"))]
    let mut storage = Storage::<B> {
        board: core::marker::PhantomData,
    };
    defmt::info!("specpoly-led ready");
    let mut output = Output::default();
    #[cfg(feature = "mixing")]
    let mut pacer = Pacer::new(0);
    loop {
        #[cfg(feature = "mixing")]
        if controller.mixer.fading() && pacer.due(board.millis()) {
            fade_step(&mut board, controller, &mut output);
        }
        let Some(byte) = board.read() else {
            board.idle();
            continue;
        };
        let Some(line) = lines.push(byte) else {
            continue;
        };
        match answer(line, controller, &mut storage, &mut board, &mut output) {
            Answer::Empty => continue,
            Answer::Kept => {}
            Answer::Drive(d) => {
                drive(&mut board, &d);
                #[cfg(feature = "mixing")]
                if output.mixing() {
                    defmt::info!("mix duty {=[?]}", d.lit());
                }
            }
            // a new fade: its first step one period from now
            #[cfg(feature = "mixing")]
            Answer::Fade => pacer = Pacer::new(board.millis()),
            #[cfg(not(feature = "mixing"))]
            Answer::Fade => {}
        }
        let duty = controller.duty();
        defmt::info!(
            "duty {=u16} {=u16} {=u16} max={=u16} stack={=usize}",
            duty[0],
            duty[1],
            duty[2],
            board.max_duty(),
            board.stack_high_water()
        );
    }
}

/// Sets the channels; a channel's refusal is logged (the controller's state stands).
fn drive<B: Board>(board: &mut B, d: &Duties) {
    if let Err(LedError::Channel(i, _)) = board.set_duties(d.lit()) {
        defmt::warn!("PWM channel {=usize} refused its duty", i);
    }
}

/// Answers one line (or its fault) on the UART; [`Answer::Empty`] for an empty line, which gets
/// no reply. Not inlined: the parsed command and the reply live only while a line is answered,
/// not in [`run`]'s frame for ever.
#[inline(never)]
fn answer<B: Board>(
    line: Result<&str, Fault>,
    controller: &mut Controller,
    storage: &mut Storage<B>,
    board: &mut B,
    output: &mut Output,
) -> Answer {
    let reply = match line {
        Ok(l) if l.trim_ascii().is_empty() => return Answer::Empty,
        #[cfg(feature = "settings")]
        Ok(l) => store::handle(controller, &mut storage.store, storage.buffer, l),
        #[cfg(not(feature = "settings"))]
        Ok(l) => {
            let _ = &storage;
            controller.handle(specpoly_device::controller::parse(l))
        }
        Err(f) => Reply::Error(f),
    };
    // the UART never refuses a byte
    let _ = reply.write(&mut Uart(board));
    board.write(b"\n");
    match output.after(&reply, controller) {
        Some(d) => Answer::Drive(d),
        None if matches!(reply, Reply::Mix(_)) => Answer::Fade,
        None => Answer::Kept,
    }
}

/// One fade step, driven and logged (`fade K/N duty [..] stack=BYTES`). Not inlined: the solve
/// behind it is not wanted in [`run`]'s frame, which lives for ever.
#[cfg(feature = "mixing")]
#[inline(never)]
fn fade_step<B: Board>(board: &mut B, controller: &mut Controller, output: &mut Output) {
    if let Some((k, n, duty)) = controller.fade_step() {
        let channels = controller.mixer.channels.list().len();
        let d = output.step(&duty[..channels]);
        drive(board, &d);
        defmt::info!(
            "fade {=u16}/{=u16} duty {=[?]} stack={=usize}",
            k,
            n,
            d.lit(),
            board.stack_high_water()
        );
    }
}

/// The settings store on the board's flash, and the saved settings applied (or the defaults
/// kept, with the reason logged): the calibration record, then the mixer's.
#[cfg(feature = "settings")]
fn restore<B: Board>(
    board: &mut B,
    controller: &mut Controller,
    buffer: &'static mut Buffer,
) -> Storage<B> {
    use embedded_storage::nor_flash::ReadNorFlash;
    let flash = board.settings_flash();
    let capacity = flash.capacity() as u32;
    let Ok(mut store) = Store::new(Blocking(flash), 0..capacity) else {
        // whole pages, at least two, by the board's constants
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
    Storage { store, buffer }
}
