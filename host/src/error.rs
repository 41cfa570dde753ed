//! The CLI's one error type. Every failure is one line on stderr and an exit code:
//! 2 for usage errors (bad arguments, unknown names), 1 for data and I/O errors.

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

    /// An I/O error on `path`.
    pub fn io(path: impl AsRef<Path>, source: std::io::Error) -> Self {
        CliError::Io {
            path: path.as_ref().display().to_string(),
            source,
        }
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
