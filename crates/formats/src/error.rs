//! The CLI's one error type. Every failure is one line on stderr and an exit code, the same in
//! every command:
//!
//! | code | meaning |
//! |---|---|
//! | 0 | done (`calibrate verify`: every criterion met) |
//! | 1 | bad data, a failed device or computation, a file that exists but cannot be read or written, a failed tolerance (`calibrate verify`, `led --check`) |
//! | 2 | the command line is wrong: unknown option or value, unknown built-in name, or an input file that does not exist, named on the command line or in a file it names (clap's own errors included) |
//!
//! A missing input file counts as a usage error because something names a file that is not
//! there, exactly like an unknown built-in name (`xyz nosuch.csv` and `xyz nosuch` fail alike). Errors are one line: TOML's ([`crate::toml_error`]) are folded to one.

use std::path::Path;

/// A CLI failure.
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
    /// [`CliError::missing`] instead ([`crate::read`] does this).
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
