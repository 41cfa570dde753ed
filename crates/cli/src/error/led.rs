//! `specpoly_led::Error` → [`CliError`]: `--primaries` and `refl` arguments the controller's
//! parser rejects are usage errors (exit 2); the link, the controller and calibration files
//! are data errors (exit 1). The message is the error's.

use super::CliError;
use specpoly_led::Error;

/// The CLI's error for an error of `specpoly-led` (`.map_err(from_led)?`).
pub fn from_led(e: Error) -> CliError {
    match e {
        Error::Lower(e) => e,
        Error::PrimariesNotANumber { .. }
        | Error::PrimariesCount { .. }
        | Error::PrimariesRejected { .. }
        | Error::ReflectanceCount { .. }
        | Error::ReflLine => CliError::Usage(e.to_string()),
        Error::Open { .. }
        | Error::Io { .. }
        | Error::Timeout { .. }
        | Error::Closed { .. }
        | Error::BadReply { .. }
        | Error::Rejected { .. }
        | Error::Version { .. }
        | Error::TooLong { .. }
        | Error::CurveTooLong { .. }
        | Error::NotLedCalibration { .. }
        | Error::NoColourSpace { .. }
        | Error::CannotFit { .. } => CliError::Data(e.to_string()),
    }
}
