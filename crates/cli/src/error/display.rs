//! `specpoly_display::Error` → [`CliError`]: `--display` naming neither sRGB nor a file and
//! refused `--target` values or options are usage errors (exit 2); calibration files, display
//! TOML files, ICC profiles, video LUTs and models that are refused are data errors (exit 1);
//! an error about a named file takes the class of its cause; errors of the lower crates
//! (reading files, CGATS) pass through. The message is the display crate's.
//!
//! A meter's failure during a calibration to a target is the calibrate crate's error, mapped
//! as such.

use super::CliError;
use specpoly_display::Error;

impl From<Error> for CliError {
    fn from(e: Error) -> Self {
        let e = match e {
            Error::Formats(e) => return e.into(),
            Error::Meter(e) => {
                return match e.downcast::<specpoly_calibrate::Error>() {
                    Ok(e) => CliError::from(*e),
                    Err(e) => CliError::Data(e.to_string()),
                }
            }
            e => e,
        };
        if is_usage(&e) {
            CliError::Usage(e.to_string())
        } else {
            CliError::Data(e.to_string())
        }
    }
}

/// Whether the error is about the command line (an argument), not a file's contents.
fn is_usage(e: &Error) -> bool {
    match e {
        Error::NoSuchDisplay { .. } | Error::TargetValue { .. } | Error::TargetKey { .. } => true,
        Error::In { error, .. } => is_usage(error),
        Error::Formats(_) | Error::Meter(_) => false,
        Error::Toml { .. }
        | Error::WrongFormat { .. }
        | Error::NotACalibration { .. }
        | Error::Version { .. }
        | Error::NoVersion
        | Error::NotFinite { .. }
        | Error::BadValue { .. }
        | Error::Invalid { .. }
        | Error::NotANumber { .. }
        | Error::Model { .. }
        | Error::Core(_)
        | Error::Write { .. }
        | Error::Profile { .. }
        | Error::Unprofilable(_)
        | Error::ExportNeedsClip
        | Error::BlobNeedsMatrixModel
        | Error::BlobIsBinary => false,
    }
}

#[cfg(test)]
mod tests {
    use super::super::CliError;
    use specpoly_display::Error;

    fn code(e: Error) -> i32 {
        CliError::from(e).exit_code()
    }

    #[test]
    fn arguments_are_usage_errors_and_contents_data_errors() {
        assert_eq!(code(Error::NoSuchDisplay { spec: "x".into() }), 2);
        let target = || Error::TargetKey {
            spec: "foo=1".into(),
            key: "foo".into(),
        };
        assert_eq!(code(target()), 2);
        assert_eq!(
            CliError::from(target()).to_string(),
            "--target `foo=1`: unknown `foo` (white=D65|native|x,y, gamma=G|srgb|bt1886|lstar, luminance=N|native)"
        );
        assert_eq!(code(Error::NoVersion.in_file("a.toml")), 1);
        assert_eq!(
            CliError::from(Error::NoVersion.in_file("a.toml")).to_string(),
            "a.toml: no version"
        );
        assert_eq!(code(Error::ExportNeedsClip), 1);
        let missing = specpoly_formats::Error::missing("nosuch.toml");
        assert_eq!(code(Error::Formats(missing)), 2);
    }
}
