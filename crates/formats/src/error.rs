//! The errors of specpoly's files ([`Error`]).
//!
//! [`Error`] says what went wrong with which file, and where: a missing input file
//! ([`Error::Missing`]), an I/O error with its path ([`Error::Io`]), a file that is not one this
//! tool reads (a device, a folder, too large, not UTF-8), a spectral CSV, CGATS or `.ti1` error
//! with its file, line and column or field, a TOML error with its position
//! ([`crate::toml_error`]), a device string `KIND:ARG,key=value` that is wrong
//! ([`crate::device_spec`]), a `.ti3` that cannot be written. Every message is one line, and
//! names the file first (`FILE:LINE[:COLUMN]: what is wrong`) where there is one. Which of these
//! is the user's mistake (exit 2) and which bad data (exit 1) is decided by the CLI, not here.

use std::fmt;
use std::path::Path;

/// An error reading, parsing or writing one of specpoly's files.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// An input file, named on the command line or in a file it names, that does not exist.
    #[error("{path}: no such file")]
    Missing {
        /// The file.
        path: String,
    },
    /// A file (or `stdout`) could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// The file, or `stdout`.
        path: String,
        /// What went wrong.
        source: std::io::Error,
    },
    /// An input path that names a device, FIFO or folder instead of a regular file.
    #[error("{path}: not a regular file (give a file, not a device, pipe or folder)")]
    NotRegular {
        /// The path.
        path: String,
    },
    /// An input file larger than [`crate::read::max_input_bytes`].
    #[error("{path}: larger than the input limit of {} (--max-input-size raises it)", crate::read::size_text(*.limit))]
    TooLarge {
        /// The file.
        path: String,
        /// The limit, bytes.
        limit: u64,
    },
    /// A text file that is not UTF-8.
    #[error("{path}: not UTF-8 text (invalid byte at offset {offset})")]
    NotUtf8 {
        /// The file.
        path: String,
        /// The offset of the first invalid byte.
        offset: usize,
    },
    /// An output path that is a folder.
    #[error("{path}: is a folder, not a file")]
    OutputIsFolder {
        /// The path.
        path: String,
    },
    /// An output path through more symbolic links than are followed.
    #[error("{path}: more than {max} symbolic links")]
    TooManyLinks {
        /// The path.
        path: String,
        /// The most links followed.
        max: usize,
    },
    /// A malformed spectral CSV ([`crate::csv`]): `FILE[:LINE[:COLUMN]]: why`.
    #[error("{}: {why}", Position(.file, *.line, *.column))]
    Csv {
        /// The file (as the caller named it).
        file: String,
        /// The 1-based line, if the error has one.
        line: Option<u64>,
        /// The 1-based cell of the row (as a spreadsheet counts), if the error has one.
        column: Option<usize>,
        /// What is wrong.
        why: String,
    },
    /// A malformed CGATS file ([`crate::cgats`]) or a `.ti3` or `.ti1` table that is not
    /// what it must be: `FILE[:LINE]: why`.
    #[error("{}: {why}", Position(.file, .line.map(|l| l as u64), None))]
    Cgats {
        /// The file (as the caller named it).
        file: String,
        /// The 1-based line, if the error has one.
        line: Option<usize>,
        /// What is wrong.
        why: String,
    },
    /// A CGATS value that is not a number (or not one in its range): `FILE:LINE: FIELD
    /// `VALUE` is not a number[ in RANGE]`.
    #[error("{file}:{line}: {field} `{value}` is not a number{}", .range.map(|r| format!(" in {r}")).unwrap_or_default())]
    CgatsNumber {
        /// The file.
        file: String,
        /// The 1-based line.
        line: usize,
        /// The field (`RGB_R`, `XYZ_Y`, …).
        field: String,
        /// The value as written.
        value: String,
        /// The range it must be in, if the message names one (`0–100`).
        range: Option<&'static str>,
    },
    /// A TOML error ([`crate::toml_error`]): `FILE[:LINE:COLUMN]: message`, one line.
    #[error("{}: {message}", Position(.file, .line.map(|l| l as u64), *.column))]
    Toml {
        /// The file.
        file: String,
        /// The 1-based line, if the error has a position.
        line: Option<usize>,
        /// The 1-based column (characters), if the error has a position.
        column: Option<usize>,
        /// The message, its lines joined by `, `.
        message: String,
    },
    /// Measurements that cannot be written as a `.ti3`.
    #[error("cannot write a .ti3: {why}")]
    Ti3Write {
        /// Why (names the reading).
        why: String,
    },
    /// Spectral data (a spectral `.ti3`, a `.ccss`) or a correction matrix (`.ccmx`) that
    /// cannot be written: `cannot write a KIND: why`.
    #[error("cannot write a {kind}: {why}")]
    SpectralWrite {
        /// `.ccss`, `.ccmx` or `spectral .ti3`.
        kind: &'static str,
        /// Why (names the sample or value).
        why: String,
    },
    /// A device string without the argument its kind needs ([`crate::device_spec`]).
    #[error("`{spec}` needs {what}: `{example}`")]
    DeviceArgument {
        /// The whole device string.
        spec: String,
        /// What the argument is (`a port`).
        what: String,
        /// An example (`led:/dev/ttyACM0`).
        example: String,
    },
    /// A device option with a bad value.
    #[error("`{spec}`: `{key}={value}`: {why}")]
    DeviceOption {
        /// The whole device string.
        spec: String,
        /// The option.
        key: String,
        /// Its value.
        value: String,
        /// What it should be.
        why: String,
    },
    /// A device option the device does not know.
    #[error("`{spec}`: unknown option `{key}` ({known})")]
    UnknownDeviceOption {
        /// The whole device string.
        spec: String,
        /// The option.
        key: String,
        /// The options the device knows.
        known: String,
    },
    /// A value that cannot be written as JSON.
    #[error("JSON: {0}")]
    Json(#[source] serde_json::Error),
}

impl Error {
    /// An I/O error on `path`. An input file that does not exist is [`Error::Missing`]
    /// instead ([`crate::read`] does this).
    pub fn io(path: impl AsRef<Path>, source: std::io::Error) -> Self {
        Error::Io {
            path: path.as_ref().display().to_string(),
            source,
        }
    }

    /// An input file that does not exist.
    pub fn missing(path: impl AsRef<Path>) -> Self {
        Error::Missing {
            path: path.as_ref().display().to_string(),
        }
    }
}

/// `FILE`, `FILE:LINE` or `FILE:LINE:COLUMN`, as messages start.
struct Position<'a>(&'a str, Option<u64>, Option<usize>);

impl fmt::Display for Position<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.0)?;
        if let Some(line) = self.1 {
            write!(f, ":{line}")?;
            if let Some(column) = self.2 {
                write!(f, ":{column}")?;
            }
        }
        Ok(())
    }
}

/// The result type of this crate's functions.
pub type Result<T, E = Error> = std::result::Result<T, E>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn positions() {
        let csv = |line, column| Error::Csv {
            file: "t.csv".into(),
            line,
            column,
            why: "bad".into(),
        };
        assert_eq!(csv(None, None).to_string(), "t.csv: bad");
        assert_eq!(csv(Some(3), None).to_string(), "t.csv:3: bad");
        assert_eq!(csv(Some(3), Some(2)).to_string(), "t.csv:3:2: bad");
        let missing = Error::missing("nosuch.csv");
        assert_eq!(missing.to_string(), "nosuch.csv: no such file");
    }
}
