//! The crate's errors: [`Error`] for everything it does, with the failures of the devices in
//! [`InstrumentError`] (what reads the patches: the PR-655/670 on a serial port, ArgyllCMS's
//! `dispread`) and [`PatchDisplayError`] (what shows them: the web page, the manual prompt,
//! the LED controller).

use crate::instrument::serial_failure::Failure;
use crate::interrupt;
use std::path::PathBuf;

/// The crate's result type.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// A failure of the crate: a bad patch set or device spec, a fit that cannot be made, a
/// readings file that cannot be resumed, a device that failed, a run that stopped.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// `--ramp-steps` out of range.
    #[error("--ramp-steps {0}: expected 2–256")]
    RampSteps(usize),
    /// `--verify` too large.
    #[error("--verify {0}: at most 10000")]
    VerifyCount(usize),
    /// A patch set (`.ti1`) without patches.
    #[error("the patch set is empty")]
    EmptyPatchSet,

    /// A transfer table size out of range.
    #[error("table points {points} must be 2–{max}")]
    TablePoints {
        /// The size asked for.
        points: usize,
        /// The largest.
        max: usize,
    },
    /// A measurement (1-based) with a value that is not finite.
    #[error("measurement {index} is not finite")]
    NotFinite {
        /// Which, 1-based.
        index: usize,
    },
    /// A measurement (1-based) beyond [`crate::readings::MAX_READING`].
    #[error(
        "measurement {index}: XYZ {:.4e} {:.4e} {:.4e} is beyond ±{:e} cd/m² (not a display reading)",
        xyz[0],
        xyz[1],
        xyz[2],
        max
    )]
    BeyondRange {
        /// Which, 1-based.
        index: usize,
        /// Its XYZ.
        xyz: [f64; 3],
        /// The limit ([`crate::readings::MAX_READING`]).
        max: f64,
    },
    /// No reading of device black.
    #[error("no black patch (device 0 0 0): Cowan's model needs the black level")]
    NoBlack,
    /// No reading of a primary at full drive.
    #[error(
        "no full-drive {channel} patch (device {} {} {})",
        device[0],
        device[1],
        device[2]
    )]
    NoFullDrive {
        /// `red`, `green` or `blue`.
        channel: &'static str,
        /// The device values looked for.
        device: [f64; 3],
    },
    /// A primary at full drive that is not brighter than black.
    #[error("the full-drive {channel} patch is not brighter than black")]
    DarkPrimary {
        /// `red`, `green` or `blue`.
        channel: &'static str,
    },
    /// The least-squares matrix fit without three independent channels.
    #[error("least-squares matrix: the fit patches do not span three channels")]
    NoSpan,
    /// An absolute `.ti3` against a relative calibration, and nothing to normalise by.
    #[error(
        "the .ti3 is absolute, the calibration relative, and the .ti3 has no white patch to normalise by"
    )]
    NoWhitePatch,

    /// A `--display` of no known kind.
    #[error(
        "--display `{spec}`: expected `web[:PORT]`, `led:PORT`, `manual` or `sim:SPD[,options]`"
    )]
    UnknownDisplay {
        /// The spec given.
        spec: String,
    },
    /// An `--instrument` of no known kind.
    #[error(
        "--instrument `{spec}`: expected `serial:PORT[,options]`, `argyll[:options]`, `sim` or `sim:SPD[,options]`"
    )]
    UnknownInstrument {
        /// The spec given.
        spec: String,
    },
    /// `--display web:X` with `X` not a port.
    #[error("--display `{spec}`: expected `web` or `web:PORT`")]
    WebPort {
        /// The spec given.
        spec: String,
    },
    /// A `--display` that is not ArgyllCMS's, with `--instrument argyll`.
    #[error(
        "--display `{spec}`: with --instrument argyll, ArgyllCMS shows the patches: `argyll[:N]` (its window on display N), `argyll:web[:PORT]`, `argyll:fake[:PROFILE.icc]` or `argyll:dummy`, options `scale=S`, `fill`"
    )]
    ArgyllDisplay {
        /// The spec given.
        spec: String,
    },
    /// An instrument spec that is not `argyll[:options]` where one must be.
    #[error("--instrument `{spec}`: expected `argyll[:options]`")]
    ArgyllInstrument {
        /// The spec given.
        spec: String,
    },
    /// `--display argyll:fake:ICC` with no such file.
    #[error("--display {spec}: no profile {}", file.display())]
    NoProfile {
        /// The spec given.
        spec: String,
        /// The profile named.
        file: PathBuf,
    },
    /// `--instrument argyll:x=FILE` with no such file.
    #[error("--instrument {spec}: correction file `{file}` not found")]
    NoCorrectionFile {
        /// The spec given.
        spec: String,
        /// The file named.
        file: String,
    },
    /// `--instrument sim` without a simulated display.
    #[error(
        "--instrument sim reads a simulated display: use it with --display sim:SPD, or name the spectra (--instrument sim:crt) to simulate what --display shows"
    )]
    SimNeedsSimDisplay,
    /// `--instrument sim:SPD` with `--display sim:…`.
    #[error("--display is already simulated: use --instrument sim to read it")]
    AlreadySimulated,
    /// `--instrument argyll` without `--display argyll…`.
    #[error(
        "--instrument argyll measures with ArgyllCMS's dispread, which shows the patches itself: use it with --display argyll[:N]"
    )]
    ArgyllNeedsArgyllDisplay,
    /// `--display argyll…` without `--instrument argyll`.
    #[error(
        "--display argyll is ArgyllCMS's own patch window: use it with --instrument argyll[:options]"
    )]
    ArgyllDisplayNeedsArgyll,

    /// A simulated display's channel spectrum that is not a spectrum.
    #[error("{spectra}: channel {channel}: {error}")]
    SimChannel {
        /// Where the spectra come from.
        spectra: String,
        /// The channel (0 red, 1 green, 2 blue).
        channel: usize,
        /// Why.
        error: specpoly_core::Error,
    },
    /// A simulated display's `white_xy` its primaries cannot mix.
    #[error("{spectra}: white_xy={x}:{y} is outside the primaries' gamut")]
    SimWhiteOutside {
        /// Where the spectra come from.
        spectra: String,
        /// The white's x.
        x: f64,
        /// The white's y.
        y: f64,
    },
    /// A simulated display whose primaries have no luminance.
    #[error("{spectra}: the primaries have no luminance")]
    SimNoLuminance {
        /// Where the spectra come from.
        spectra: String,
    },
    /// A simulated display's table without the three channels.
    #[error(
        "{spectra}: a display's spectra need columns `red`, `green`, `blue` (or exactly three columns); it has {columns}"
    )]
    SimColumns {
        /// Where the spectra come from.
        spectra: String,
        /// Its columns, comma-separated.
        columns: String,
    },

    /// The patch display failed.
    #[error(transparent)]
    Display(#[from] PatchDisplayError),
    /// The instrument failed.
    #[error(transparent)]
    Instrument(#[from] InstrumentError),
    /// Ctrl-C during a run.
    #[error("{}", interrupt::MESSAGE)]
    Interrupted,
    /// A failure at one patch of a run.
    #[error(
        "patch {number} of {total} ({kind} {:.3} {:.3} {:.3}): {source}",
        device[0],
        device[1],
        device[2]
    )]
    AtPatch {
        /// The patch, 1-based.
        number: usize,
        /// Patches in the run.
        total: usize,
        /// The patch's kind ([`crate::patches::PatchKind::name`]).
        kind: &'static str,
        /// Its device values.
        device: [f64; 3],
        /// What failed.
        source: Box<Error>,
    },
    /// A failure in one batch of a run (ArgyllCMS's `dispread` measures in batches).
    #[error("patches {first}–{last} of {total}: {source}")]
    AtBatch {
        /// The batch's first patch, 1-based.
        first: usize,
        /// Its last.
        last: usize,
        /// Patches in the set.
        total: usize,
        /// What failed.
        source: Box<Error>,
    },
    /// A measuring run that stopped: why, and the readings it kept
    /// ([`crate::session::Session::stopped`] builds it).
    #[error("{source}; {}", kept_text(*kept, file, *remaining))]
    Stopped {
        /// Why it stopped.
        source: Box<Error>,
        /// Readings in the file.
        kept: usize,
        /// The readings file.
        file: PathBuf,
        /// Patches still to measure.
        remaining: usize,
    },

    /// The readings file exists and neither `--resume` nor `--force` was given.
    #[error(
        "{} already exists: add --resume to measure only the patches it lacks, or --force to start over (the old file is kept as {})",
        file.display(),
        backup.display()
    )]
    ReadingsExist {
        /// The readings file.
        file: PathBuf,
        /// Where `--force` would keep it.
        backup: PathBuf,
    },
    /// Another run holds the output's lock ([`crate::lock::RunLock`]).
    #[error(
        "{} is being measured by another run ({holder}; lock {}): wait for it to end, or use another -o",
        output.display(),
        lock.display()
    )]
    Locked {
        /// The output (`-o`).
        output: PathBuf,
        /// The lock file.
        lock: PathBuf,
        /// The holder's line in the lock file (`pid N, started TIME`).
        holder: String,
    },
    /// `--resume` of a readings file that cannot be read.
    #[error("cannot resume: {0} (use --force to start over; the file is kept as a backup)")]
    ResumeUnreadable(specpoly_formats::Error),
    /// `--resume` of readings of another patch set.
    #[error(
        "cannot resume {}: it was measured with another patch set ({found}; this run has {expected}): give the same --ramp-steps, --verify or --patches, or --force to start over",
        file.display()
    )]
    ResumeOtherSet {
        /// The readings file.
        file: PathBuf,
        /// Its patch set's fingerprint.
        found: String,
        /// This run's.
        expected: String,
    },
    /// `--resume` of a file without the patch-set keyword.
    #[error(
        "cannot resume {}: it has no {} (not written by `calibrate run`): use --force to start over, or another -o",
        file.display(),
        keyword
    )]
    ResumeNoPatchSet {
        /// The readings file.
        file: PathBuf,
        /// The keyword `calibrate run` writes ([`crate::session::PATCH_SET_KEYWORD`]).
        keyword: &'static str,
    },
    /// `--resume` of normalised readings.
    #[error(
        "cannot resume {}: normalised readings without LUMINANCE_XYZ_CDM2",
        file.display()
    )]
    ResumeRelative {
        /// The readings file.
        file: PathBuf,
    },
    /// `--resume` of a file with a reading of no patch of the set.
    #[error(
        "cannot resume {}:{line}: RGB {:.5} {:.5} {:.5} is not a patch of the set (or is there twice)",
        file.display(),
        rgb[0],
        rgb[1],
        rgb[2]
    )]
    ResumeStrayPatch {
        /// The readings file.
        file: PathBuf,
        /// The line.
        line: usize,
        /// Its RGB, percent.
        rgb: [f64; 3],
    },

    /// A file (or stdin) that cannot be read or written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// Files and their formats (`specpoly-formats`).
    #[error(transparent)]
    Formats(#[from] specpoly_formats::Error),
    /// Named spectra (`specpoly-spectra`).
    #[error(transparent)]
    Spectra(Box<specpoly_spectra::Error>),
    /// Calibration files, ICC profiles, video LUTs and targets (`specpoly-display`).
    #[error(transparent)]
    DisplayFile(Box<specpoly_display::Error>),
    /// The LED controller's link (`specpoly-led`).
    #[error(transparent)]
    Led(Box<specpoly_led::Error>),
}

/// The tail of [`Error::Stopped`]'s message.
fn kept_text(kept: usize, file: &std::path::Path, remaining: usize) -> String {
    if kept == 0 {
        "no readings taken".to_string()
    } else {
        format!(
            "{kept} readings kept in {} (run again with --resume to measure the other {remaining})",
            file.display()
        )
    }
}

impl Error {
    /// An I/O error on `path`.
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Error::Io {
            path: path.into(),
            source,
        }
    }
}

/// A failure of an instrument ([`crate::instrument::Instrument`]) or of ArgyllCMS's
/// `dispread`.
#[derive(Debug, thiserror::Error)]
pub enum InstrumentError {
    /// The serial port could not be opened.
    #[error("cannot open serial port {port}: {source}")]
    OpenPort {
        /// The port.
        port: String,
        /// Why.
        source: serialport::Error,
    },
    /// An exchange with the PR-655/670 failed (and is not retried: the port failed, Ctrl-C),
    /// or failed on every attempt (`attempts`).
    #[error(
        "instrument on {port}: {failure}{}",
        attempts.map(|n| format!(" ({n} attempts)")).unwrap_or_default()
    )]
    Serial {
        /// The port.
        port: String,
        /// What went wrong.
        failure: Failure,
        /// The attempts made, when every one failed.
        attempts: Option<u32>,
    },
    /// Nothing answered `PHOTO` on the port.
    #[error(
        "no instrument answered on {port}: sent `PHOTO`, no `REMOTE MODE` within {seconds:.1} s ({attempts} attempts; is a PR-655/670 connected and switched on?)"
    )]
    NoAnswer {
        /// The port.
        port: String,
        /// The timeout.
        seconds: f64,
        /// The attempts made.
        attempts: u32,
    },
    /// No attempt at all (zero attempts).
    #[error("{port}: no attempt made")]
    NoAttempt {
        /// The port.
        port: String,
    },
    /// `dispread` is not on `PATH`.
    #[error(
        "ArgyllCMS is not installed (no `dispread` on PATH): install the Debian/Ubuntu package `{package}` (apt install {package})",
        package = package
    )]
    NotInstalled {
        /// The package that installs it ([`crate::instrument::argyll::PACKAGE`]).
        package: &'static str,
    },
    /// `dispread` could not be started.
    #[error("cannot start {}: {source}", program.display())]
    Start {
        /// The program.
        program: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// Waiting for `dispread` failed.
    #[error("dispread: {0}")]
    Wait(std::io::Error),
    /// `dispread` fell silent.
    #[error(
        "ArgyllCMS dispread said nothing for {seconds:.0} s and was stopped: no instrument found, or one that does not answer (is it plugged in? `spotread -?` lists what ArgyllCMS sees; raise timeout= for long prompts)"
    )]
    Silent {
        /// The timeout.
        seconds: f64,
    },
    /// `dispread` failed: its last error line, and a hint.
    #[error("ArgyllCMS dispread failed: {said}{hint}")]
    DispreadFailed {
        /// What it said.
        said: String,
        /// A hint for a known failure (empty if none).
        hint: &'static str,
    },
    /// `dispread`'s readings are normalised.
    #[error("dispread's .ti3 is normalised and gives no absolute luminance")]
    Relative,
    /// `dispread` returned another number of readings.
    #[error("dispread measured {got} patches of {asked}")]
    Count {
        /// Readings returned.
        got: usize,
        /// Patches asked for.
        asked: usize,
    },
    /// `dispread` measured another patch than asked.
    #[error("dispread's patch {number} is RGB {got:?}, not the {asked:?} asked for")]
    WrongPatch {
        /// The patch, 1-based.
        number: usize,
        /// What it measured.
        got: [f64; 3],
        /// What was asked.
        asked: [f64; 3],
    },
    /// Ctrl-C.
    #[error("{}", interrupt::MESSAGE)]
    Interrupted,
}

/// A failure of a patch display ([`crate::patch_display::PatchDisplay`]).
#[derive(Debug, thiserror::Error)]
pub enum PatchDisplayError {
    /// The web display cannot listen on its port.
    #[error("web display: cannot listen on 127.0.0.1:{port}: {source}")]
    Listen {
        /// The port.
        port: u16,
        /// Why.
        source: std::io::Error,
    },
    /// The web display's socket failed.
    #[error("web display: {0}")]
    Socket(std::io::Error),
    /// The web display's server thread did not start.
    #[error("web display: cannot start the server: {0}")]
    Server(std::io::Error),
    /// No browser showed the patch in time.
    #[error(
        "web display: no browser showed patch {seq} ({css}) within {seconds:.0} s — is {url} open and visible?"
    )]
    NotShown {
        /// The patch's sequence number.
        seq: u64,
        /// Its colour, `rgb(R,G,B)`.
        css: String,
        /// How long it waited.
        seconds: f64,
        /// The page.
        url: String,
    },
    /// A second client presented the web display's one-time key: someone else may drive the
    /// run, so it stops.
    #[error(
        "web display: the run's one-time link was opened by a second client (another local process may have read it); stopped — run again and open the new link only in the display's browser"
    )]
    KeyReused,
    /// Reading the manual display's confirmation failed.
    #[error("manual display: reading stdin: {0}")]
    Stdin(std::io::Error),
    /// Stdin ended before the patch was confirmed.
    #[error("manual display: stdin closed before the patch was confirmed")]
    StdinClosed,
    /// The user typed `q`.
    #[error("manual display: stopped by the user")]
    StoppedByUser,
    /// The LED controller or its link failed.
    #[error("LED display: {0}")]
    Led(#[from] specpoly_led::Error),
    /// The LED display's neutral model could not be built.
    #[error("LED display: {0}")]
    LedModel(specpoly_core::Error),
    /// The LED controller answered `xyz` with something else than a colour.
    #[error("LED display: {port}: unexpected reply to `xyz`: `{reply}`")]
    LedReply {
        /// The port.
        port: String,
        /// The reply.
        reply: String,
    },
    /// The LED controller drove other duties than the patch's.
    #[error(
        "LED display: {port}: drove duties {duty} for device {device}, expected {expected} (of {max})"
    )]
    LedDuty {
        /// The port.
        port: String,
        /// The duties driven.
        duty: String,
        /// The patch's device values.
        device: String,
        /// The duties expected.
        expected: String,
        /// Duty steps per channel.
        max: u16,
    },
}

impl From<specpoly_spectra::Error> for Error {
    fn from(e: specpoly_spectra::Error) -> Self {
        Error::Spectra(Box::new(e))
    }
}

impl From<specpoly_display::Error> for Error {
    fn from(e: specpoly_display::Error) -> Self {
        Error::DisplayFile(Box::new(e))
    }
}

impl From<specpoly_led::Error> for Error {
    fn from(e: specpoly_led::Error) -> Self {
        Error::Led(Box::new(e))
    }
}
