//! The CLI's errors: the library crates' errors, and clap's folded to one line
//! ([`clap_error_line`]); `main` prints one line and exits with the error's code. Every failure
//! is one line on stderr and an exit code, the same in every command:
//!
//! | code | meaning |
//! |---|---|
//! | 0 | done (`calibrate verify`: every criterion met) |
//! | 1 | bad data, a failed device or computation, a file that exists but cannot be read or written, a failed tolerance (`calibrate verify`, `led --check`) |
//! | 2 | the command line is wrong: unknown option or value, unknown built-in name, or an input file that does not exist, named on the command line or in a file it names (clap's own errors included) |
//!
//! A missing input file counts as a usage error because something names a file that is not
//! there, exactly like an unknown built-in name (`xyz nosuch.csv` and `xyz nosuch` fail alike).
//! Errors are one line: TOML's (`specpoly_formats::toml_error`) are folded to one.
//!
//! The library crates return their own error enums; [`CliError`] is where their variants
//! become these codes: one `From` impl per crate, in the submodules of this module.

use std::path::Path;

/// A CLI failure: one line and an exit code. The library crates' errors become one through
/// `From` (one file per crate below), which decides the exit code; the message is theirs.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// Bad arguments or an unknown name (exit code 2).
    #[error("{0}")]
    Usage(String),
    /// Bad input data, a failed device or a failed computation (exit code 1).
    #[error("{0}")]
    Data(String),
    /// A file could not be read or written (exit code 1).
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// What went wrong.
        source: std::io::Error,
    },
}

impl CliError {
    /// The process exit code for this error.
    pub fn exit_code(&self) -> i32 {
        match self {
            CliError::Usage(_) => 2,
            CliError::Data(_) | CliError::Io { .. } => 1,
        }
    }

    /// An I/O error on `path` (exit 1). An input file that does not exist is
    /// [`CliError::missing`] instead.
    pub fn io(path: impl AsRef<Path>, source: std::io::Error) -> Self {
        CliError::Io {
            path: path.as_ref().display().to_string(),
            source,
        }
    }

    /// An input file named on the command line that does not exist (exit 2).
    pub fn missing(path: impl AsRef<Path>) -> Self {
        CliError::Usage(format!("{}: no such file", path.as_ref().display()))
    }

    /// A usage error.
    pub fn usage(msg: impl Into<String>) -> Self {
        CliError::Usage(msg.into())
    }

    /// A data error.
    pub fn data(msg: impl Into<String>) -> Self {
        CliError::Data(msg.into())
    }
}

/// The CLI's result type.
pub type Result<T, E = CliError> = std::result::Result<T, E>;

// The library crates' errors mapped to the CLI's: one file per crate.
mod calibrate;
mod display;
mod formats;
mod led;
mod paper;
mod plot;
mod render;
mod spectra;

/// A clap error as one line (`unexpected argument '--x' found (tip: …); usage: specpoly …`), or
/// `None` for `--help` and `--version`, which clap prints itself.
pub fn clap_error_line(e: &clap::Error) -> Option<String> {
    use clap::error::ErrorKind;
    if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) {
        return None;
    }
    let text = e.render().to_string();
    let usage = text
        .lines()
        .find_map(|l| l.trim().strip_prefix("Usage: "))
        .map(str::trim);
    if e.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
        return Some(format!(
            "a command is missing; usage: {}; `--help` lists the commands",
            usage.unwrap_or("specpoly <COMMAND>")
        ));
    }
    let mut main: Option<&str> = None;
    let mut extra = Vec::new();
    let mut tips = Vec::new();
    for l in text.lines().map(str::trim).filter(|l| !l.is_empty()) {
        if let Some(m) = l.strip_prefix("error: ") {
            if main.is_none() {
                main = Some(m.trim_end_matches(':'));
                continue;
            }
        }
        let boilerplate = l.starts_with("Usage: ") || l.starts_with("For more information");
        if let Some(t) = l.strip_prefix("tip: ") {
            tips.push(t);
        } else if !boilerplate && main.is_some() {
            extra.push(l);
        }
    }
    let mut s = main.unwrap_or("bad command line").to_string();
    if !extra.is_empty() {
        s.push_str(": ");
        s.push_str(&extra.join(", "));
    }
    if !tips.is_empty() {
        s.push_str(&format!(" (tip: {})", tips.join("; ")));
    }
    if let Some(u) = usage {
        s.push_str(&format!("; usage: {u}"));
    }
    Some(s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    fn line(args: &[&str]) -> Option<String> {
        let e = crate::cli::Cli::try_parse_from(args).expect_err("an error");
        clap_error_line(&e)
    }

    #[test]
    fn clap_errors_fold_to_one_line() {
        let l = line(&["specpoly", "xyz", "colorchecker#red", "--bogus"]).unwrap();
        assert!(
            l.contains("--bogus") && l.contains("usage: specpoly xyz"),
            "{l}"
        );
        assert!(!l.contains('\n'), "{l}");
        let l = line(&["specpoly", "plot", "colorchecker#red"]).unwrap();
        assert!(l.contains("--output"), "{l}");
        let l = line(&["specpoly", "calibrate"]).unwrap();
        assert!(l.contains("usage: specpoly calibrate"), "{l}");
        assert_eq!(line(&["specpoly", "--help"]), None);
        assert_eq!(line(&["specpoly", "--version"]), None);
    }
}
