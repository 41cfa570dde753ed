//! `specpoly_formats::Error` → [`CliError`].

use super::CliError;

/// Which file errors are the user's mistake.
/// A missing input file and a wrong device string are usage errors (exit 2: something names a
/// file that is not there, or a device option that does not exist, like an unknown built-in
/// name); I/O errors keep their path and source (exit 1); everything else is bad data (exit 1).
/// The message is kept.
impl From<specpoly_formats::Error> for CliError {
    fn from(e: specpoly_formats::Error) -> Self {
        match e {
            specpoly_formats::Error::Io { path, source } => CliError::Io { path, source },
            specpoly_formats::Error::Missing { .. }
            | specpoly_formats::Error::DeviceArgument { .. }
            | specpoly_formats::Error::DeviceOption { .. }
            | specpoly_formats::Error::UnknownDeviceOption { .. } => CliError::Usage(e.to_string()),
            specpoly_formats::Error::NotRegular { .. }
            | specpoly_formats::Error::TooLarge { .. }
            | specpoly_formats::Error::NotUtf8 { .. }
            | specpoly_formats::Error::OutputIsFolder { .. }
            | specpoly_formats::Error::TooManyLinks { .. }
            | specpoly_formats::Error::Csv { .. }
            | specpoly_formats::Error::Cgats { .. }
            | specpoly_formats::Error::CgatsNumber { .. }
            | specpoly_formats::Error::Toml { .. }
            | specpoly_formats::Error::Ti3Write { .. }
            | specpoly_formats::Error::SpectralWrite { .. }
            | specpoly_formats::Error::Json(_) => CliError::Data(e.to_string()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::CliError;
    use specpoly_formats::Error;

    #[test]
    fn a_missing_file_is_a_usage_error_and_io_keeps_its_path() {
        assert_eq!(CliError::from(Error::missing("nosuch.csv")).exit_code(), 2);
        let csv = Error::Csv {
            file: "t.csv".into(),
            line: None,
            column: None,
            why: "bad".into(),
        };
        assert_eq!(CliError::from(csv).exit_code(), 1);
        let io = Error::io("f", std::io::Error::other("denied"));
        assert!(matches!(CliError::from(io), CliError::Io { ref path, .. } if path == "f"));
    }
}
