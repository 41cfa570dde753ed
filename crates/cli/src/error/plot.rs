//! `specpoly_plot::Error` → [`CliError`].

use super::CliError;
use specpoly_plot::Error;

impl From<Error> for CliError {
    fn from(e: Error) -> Self {
        match e {
            Error::BadSize { .. } | Error::SizeOutOfRange { .. } | Error::LegendTooBig { .. } => {
                CliError::Usage(e.to_string())
            }
            Error::Draw(_) | Error::Text(_) | Error::Png(_) => CliError::Data(e.to_string()),
        }
    }
}
