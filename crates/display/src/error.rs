//! The display crate's errors: what is wrong with a calibration file, a display TOML, an ICC
//! profile, a video LUT or a `--target`/`--display` argument, with the data each message
//! needs. The CLI maps them to exit codes (`crates/cli/src/error/display.rs`).

/// A meter's failure during a calibration to a target: the measuring crate's own error,
/// boxed (this crate does not know it; the caller can downcast it back).
pub type MeterError = Box<dyn std::error::Error + Send + Sync>;

/// Everything that can go wrong in `specpoly-display`.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// An error about a named file (or value): `FILE: …`.
    #[error("{file}: {error}")]
    In {
        /// The file, as the user named it.
        file: String,
        /// What is wrong in it.
        error: Box<Error>,
    },
    /// A TOML file that does not parse or does not have the expected shape (the message names
    /// the file and the line).
    #[error("{message}")]
    Toml {
        /// The parser's message on one line, with the file and line.
        message: String,
    },
    /// A file is not of the expected format: `format is "…", expected "…"`.
    #[error("format is \"{found}\", expected \"{expected}\"")]
    WrongFormat {
        /// The file's `format`.
        found: String,
        /// The format read.
        expected: &'static str,
    },
    /// A TOML file without the calibration's `format` key.
    #[error("not a specpoly calibration (no format = \"{expected}\")")]
    NotACalibration {
        /// The format read.
        expected: &'static str,
    },
    /// A calibration file of another version.
    #[error("calibration version {found} is not supported (this build reads version {supported})")]
    Version {
        /// The file's version.
        found: i64,
        /// The version this build reads.
        supported: u32,
    },
    /// A calibration file without a version.
    #[error("no version")]
    NoVersion,
    /// A NaN or infinite number in a list of the file.
    #[error("{field}[{index}] is not a finite number")]
    NotFinite {
        /// The list (`black`, `primaries.red`, …).
        field: String,
        /// The index in it.
        index: usize,
    },
    /// A value outside what it may be, said as `WHAT: WHY` (`primaries.red: x = …`,
    /// `video LUT: 3 entries per channel (…)`).
    #[error("{what}: {why}")]
    BadValue {
        /// The value (a key, a table).
        what: String,
        /// What is wrong with it.
        why: String,
    },
    /// A value outside what it may be, said as one sentence `WHAT WHY` (`white Y must be
    /// positive`, `target white x … y … is outside the display's gamut`).
    #[error("{what} {why}")]
    Invalid {
        /// The value.
        what: String,
        /// What it must be, or what is wrong.
        why: String,
    },
    /// A number word that does not read as one: `FILE:LINE: FIELD `TEXT` is not a number`.
    #[error("{file}:{line}: {field} `{text}` is not a number")]
    NotANumber {
        /// The file.
        file: String,
        /// The line.
        line: usize,
        /// The field.
        field: String,
        /// The word.
        text: String,
    },
    /// The core refused a model, a table or a transform: `WHAT: ERROR[HINT]`.
    #[error("{what}: {error}{hint}")]
    Model {
        /// What was being built.
        what: String,
        /// The core's error.
        error: specpoly_core::Error,
        /// A parenthesised hint after the error, or nothing.
        hint: String,
    },
    /// The core refused a display model (the message is the core's).
    #[error(transparent)]
    Core(#[from] specpoly_core::Error),
    /// TOML text could not be written.
    #[error("cannot write {what}: {error}")]
    Write {
        /// What was being written.
        what: &'static str,
        /// The serialiser's error.
        error: toml::ser::Error,
    },
    /// An ICC profile is not one this crate reads: `FILE: WHY`.
    #[error("{file}: {why}")]
    Profile {
        /// The profile.
        file: String,
        /// Why it cannot be read (Little CMS's message included).
        why: String,
    },
    /// A profile cannot be written for this calibration (a white without luminance, singular
    /// primaries).
    #[error("{0}")]
    Unprofilable(&'static str),
    /// The C tables need the clip gamut map.
    #[error("cannot write the tables (the C export needs the clip map)")]
    ExportNeedsClip,
    /// The calibration blob holds the matrix model only (Cowan's: primaries, black, curves).
    #[error(
        "the calibration has a channel-interaction lattice, which a c-blob cannot hold \
         (refit with --interaction none for an additive model)"
    )]
    BlobNeedsMatrixModel,
    /// `c-blob` is bytes, not source text.
    #[error("the c-blob format is binary: write it with export::blob")]
    BlobIsBinary,
    /// `--display SPEC` names neither sRGB nor a file.
    #[error("--display `{spec}`: not `sRGB` and no such file")]
    NoSuchDisplay {
        /// The argument.
        spec: String,
    },
    /// A `--target` option with a bad value.
    #[error("--target `{spec}`: `{key}={value}`: {why}")]
    TargetValue {
        /// The whole argument.
        spec: String,
        /// The option.
        key: String,
        /// Its value.
        value: String,
        /// What it must be.
        why: &'static str,
    },
    /// A `--target` option that does not exist.
    #[error("--target `{spec}`: unknown `{key}` (white=D65|native|x,y, gamma=G|srgb|bt1886|lstar, luminance=N|native)")]
    TargetKey {
        /// The whole argument.
        spec: String,
        /// The option.
        key: String,
    },
    /// Reading or writing a file, CGATS and TOML syntax (`specpoly-formats`).
    #[error(transparent)]
    Formats(#[from] specpoly_formats::Error),
    /// The meter of a calibration to a target failed (its own error, boxed: see
    /// [`crate::target::Meter`]).
    #[error("{0}")]
    Meter(MeterError),
}

impl Error {
    /// This error about `file`: `FILE: …`.
    pub fn in_file(self, file: &str) -> Error {
        Error::In {
            file: file.to_string(),
            error: Box::new(self),
        }
    }

    /// A [`Error::BadValue`].
    pub(crate) fn bad(what: impl Into<String>, why: impl Into<String>) -> Error {
        Error::BadValue {
            what: what.into(),
            why: why.into(),
        }
    }

    /// An [`Error::Invalid`].
    pub(crate) fn invalid(what: impl Into<String>, why: impl Into<String>) -> Error {
        Error::Invalid {
            what: what.into(),
            why: why.into(),
        }
    }
}

/// The crate's result.
pub type Result<T, E = Error> = std::result::Result<T, E>;
