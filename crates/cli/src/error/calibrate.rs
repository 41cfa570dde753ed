//! `specpoly_calibrate::Error` → [`CliError`]: bad arguments (ramp steps, patch counts, table
//! size, device specs and which display goes with which instrument, a readings file that
//! exists or belongs to another patch set) are usage errors (exit 2); the fit's data, the
//! devices, Ctrl-C, unreadable readings and an output another run holds are data errors
//! (exit 1); I/O errors stay I/O errors. An error at a patch, at a batch or stopping a run
//! takes the exit code of its cause and the whole message.

use super::CliError;
use specpoly_calibrate::Error;

impl From<Error> for CliError {
    fn from(e: Error) -> CliError {
        let message = e.to_string();
        match e {
            Error::Formats(e) => e.into(),
            Error::Spectra(e) => (*e).into(),
            Error::DisplayFile(e) => (*e).into(),
            Error::Led(e) => (*e).into(),
            Error::Io { path, source } => CliError::io(path, source),
            Error::AtPatch { source, .. }
            | Error::AtBatch { source, .. }
            | Error::Stopped { source, .. } => match CliError::from(*source) {
                CliError::Usage(_) => CliError::Usage(message),
                _ => CliError::Data(message),
            },
            Error::RampSteps(_)
            | Error::VerifyCount(_)
            | Error::TablePoints { .. }
            | Error::UnknownDisplay { .. }
            | Error::UnknownInstrument { .. }
            | Error::WebPort { .. }
            | Error::ArgyllDisplay { .. }
            | Error::ArgyllInstrument { .. }
            | Error::SimNeedsSimDisplay
            | Error::AlreadySimulated
            | Error::ArgyllNeedsArgyllDisplay
            | Error::ArgyllDisplayNeedsArgyll
            | Error::SimWhiteOutside { .. }
            | Error::ReadingsExist { .. }
            | Error::ResumeOtherSet { .. }
            | Error::ResumeNoPatchSet { .. } => CliError::Usage(message),
            Error::EmptyPatchSet
            | Error::NotFinite { .. }
            | Error::BeyondRange { .. }
            | Error::NoBlack
            | Error::NoFullDrive { .. }
            | Error::DarkPrimary { .. }
            | Error::NoSpan
            | Error::NoWhitePatch
            | Error::NoProfile { .. }
            | Error::NoCorrectionFile { .. }
            | Error::SimChannel { .. }
            | Error::SimNoLuminance { .. }
            | Error::SimColumns { .. }
            | Error::SpectralTi3 { .. }
            | Error::Correction { .. }
            | Error::Match { .. }
            | Error::Display(_)
            | Error::Instrument(_)
            | Error::Interrupted
            | Error::Locked { .. }
            | Error::ResumeUnreadable(_)
            | Error::ResumeRelative { .. }
            | Error::ResumeStrayPatch { .. } => CliError::Data(message),
        }
    }
}
