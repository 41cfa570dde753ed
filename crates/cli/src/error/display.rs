//! `specpoly_display::Error` → [`CliError`]: `--display` naming neither sRGB nor a file and
//! refused `--target` values or options are usage errors (exit 2); calibration files, display
//! TOML files, ICC profiles, video LUTs and models that are refused are data errors (exit 1);
//! an error about a named file takes the class of its cause; errors of the lower crates
//! (reading files, CGATS) pass through. The message is the display crate's.
//!
//! The `From` impl itself is beside the error in `specpoly-display` (`error.rs`): Rust's
//! orphan rule does not let this crate implement `From<specpoly_display::Error>` for
//! `CliError` (both foreign here), and `specpoly-calibrate`, not converted yet, needs the same
//! `?`. These tests pin the mapping the CLI relies on.

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
        let lower = CliError::usage("lower");
        assert_eq!(code(Error::Lower(lower)), 2);
    }
}
