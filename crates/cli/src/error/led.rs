//! `specpoly_led::Error` → [`CliError`]: `--primaries` and `refl` arguments the controller's
//! parser rejects are usage errors (exit 2); the link, the controller and calibration files
//! are data errors (exit 1). The message is the error's.

use super::CliError;
use specpoly_led::Error;

impl From<Error> for CliError {
    fn from(e: Error) -> CliError {
        match e {
            Error::Formats(e) => e.into(),
            Error::Spectra(e) => e.into(),
            Error::Display(e) => e.into(),
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
}
