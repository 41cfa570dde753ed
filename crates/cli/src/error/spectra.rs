//! `specpoly_spectra::Error` → [`CliError`].

use super::CliError;
use specpoly_core::light::LightError;
use specpoly_spectra::Error;

impl From<Error> for CliError {
    fn from(e: Error) -> Self {
        match e {
            Error::Formats(e) => e.into(),
            Error::UnknownTable { .. }
            | Error::ColumnNeeded { .. }
            | Error::UnknownColumn { .. }
            | Error::UnknownLight(_)
            | Error::NotOneLight { .. }
            | Error::BadChannel { .. }
            | Error::BadScale(_)
            | Error::UnknownRepr(_)
            | Error::UnsupportedRepr { .. }
            | Error::NotPolynomial { .. }
            | Error::UnlistedLayout(_)
            | Error::UnknownObserver(_)
            | Error::Cie2006 { .. }
            | Error::ObserverTarget { .. }
            | Error::Mix(LightError::Channels(_) | LightError::BadTarget) => {
                CliError::Usage(e.to_string())
            }
            Error::Samples { .. }
            | Error::NotReflectance { .. }
            | Error::Overflow { .. }
            | Error::ImageOverflow { .. }
            | Error::Light { .. }
            | Error::ShortLight { .. }
            | Error::OutOfGamut { .. }
            | Error::BadObserver { .. }
            | Error::Mix(_) => CliError::Data(e.to_string()),
        }
    }
}
