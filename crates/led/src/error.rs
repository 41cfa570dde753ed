//! The crate's errors: the link's and the controller's, and those of the lines built for it
//! (checked by the controller's own parser before anything is sent).

use specpoly_protocol::Fault;

/// The crate's result type.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// `--primaries: …` for a fault of the `cal` line: the failing number named by its position.
fn primaries_fault(f: &Fault) -> String {
    match f.at {
        Some(n) => format!("{} (number {n})", f.code.name()),
        None => f.to_string(),
    }
}

/// A failure of the link or of the controller, or a line that cannot be built.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The serial port could not be opened.
    #[error("{port}: cannot open the serial port: {source}")]
    Open {
        /// The port.
        port: String,
        /// Why.
        source: serialport::Error,
    },
    /// Reading or writing the port failed.
    #[error("{port}: {source}")]
    Io {
        /// The port.
        port: String,
        /// Why.
        source: std::io::Error,
    },
    /// No complete reply within the timeout.
    #[error("{port}: no reply to `{command}` within {ms} ms (is the controller running?)")]
    Timeout {
        /// The port.
        port: String,
        /// The command sent (first 40 bytes).
        command: String,
        /// The timeout.
        ms: u128,
    },
    /// The port closed (the device went away).
    #[error("{port}: the device closed the connection")]
    Closed {
        /// The port.
        port: String,
    },
    /// A reply that is not the protocol's.
    #[error(
        "{port}: unreadable reply to `{command}`: `{}`",
        specpoly_formats::escape::one_line(reply)
    )]
    BadReply {
        /// The port.
        port: String,
        /// The command sent (first 40 bytes).
        command: String,
        /// What came back (first 80 bytes).
        reply: String,
    },
    /// The controller answered `err`.
    #[error("the controller rejected `{command}`: {fault}")]
    Rejected {
        /// The command sent (first 40 bytes).
        command: String,
        /// Its answer.
        fault: Fault,
    },
    /// A controller of another protocol version.
    #[error("{port}: the controller speaks protocol {found}, this host speaks {expected}")]
    Version {
        /// The port.
        port: String,
        /// The device's version.
        found: u16,
        /// Ours.
        expected: u16,
    },
    /// A command longer than the protocol allows.
    #[error("command of {len} bytes exceeds the protocol's {max}-byte line")]
    TooLong {
        /// Its length.
        len: usize,
        /// The limit.
        max: usize,
    },
    /// A `--primaries` value that is not a number.
    #[error("--primaries: `{token}` is not a number")]
    PrimariesNotANumber {
        /// The text.
        token: String,
    },
    /// `--primaries` with other than nine numbers.
    #[error("--primaries takes 9 numbers (xr,yr,Yr,xg,yg,Yg,xb,yb,Yb), got {got}")]
    PrimariesCount {
        /// How many were given.
        got: usize,
    },
    /// `--primaries` the controller's parser rejects.
    #[error("--primaries: {}", primaries_fault(fault))]
    PrimariesRejected {
        /// The parser's answer.
        fault: Fault,
    },
    /// A calibration file's transfer curve longer than one protocol line.
    #[error("{name}: a curve does not fit one protocol line")]
    CurveTooLong {
        /// The calibration's name.
        name: String,
    },
    /// A calibration file's line the controller's parser rejects.
    #[error("{name}: not a usable LED calibration: {fault}")]
    NotLedCalibration {
        /// The calibration's name.
        name: String,
        /// The parser's answer.
        fault: Fault,
    },
    /// A calibration file whose primaries are degenerate.
    #[error("{name}: the primaries span no colour space")]
    NoColourSpace {
        /// The calibration's name.
        name: String,
    },
    /// A `refl` line with too few or too many reflectances.
    #[error("refl takes 1 to {max} reflectances, got {got}")]
    ReflectanceCount {
        /// How many were named.
        got: usize,
        /// The protocol's limit.
        max: usize,
    },
    /// A reflectance the preset cannot fit.
    #[error("{name}: cannot fit: {source}")]
    CannotFit {
        /// The reflectance.
        name: String,
        /// Why.
        source: specpoly_core::Error,
    },
    /// The `refl` line could not be written.
    #[error("cannot write the refl command")]
    ReflLine,
    /// Files and their formats (`specpoly-formats`).
    #[error(transparent)]
    Formats(#[from] specpoly_formats::Error),
    /// Named spectra (`specpoly-spectra`).
    #[error(transparent)]
    Spectra(#[from] specpoly_spectra::Error),
    /// Calibration files and ICC profiles (`specpoly-display`).
    #[error(transparent)]
    Display(#[from] specpoly_display::Error),
}
