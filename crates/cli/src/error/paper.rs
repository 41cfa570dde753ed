//! `specpoly_paper::Error` → [`CliError`].

use super::CliError;
use specpoly_paper::Error;

impl From<Error> for CliError {
    fn from(e: Error) -> Self {
        match e {
            Error::Spectra(e) => e.into(),
            Error::Plot(e) => e.into(),
            Error::ProductNeedsTwo { .. } | Error::NotOneSpectrum { .. } => {
                CliError::Usage(e.to_string())
            }
            Error::Fit { .. } => CliError::Data(e.to_string()),
        }
    }
}
