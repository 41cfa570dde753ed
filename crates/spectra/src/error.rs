//! What can go wrong naming, checking and mixing spectra: a name that resolves to nothing
//! (or to more than one spectrum where one is needed), samples the core refuses, data that
//! cannot be a reflectance, a representation that is not supported, a mix that cannot be made,
//! and the files behind the names ([`specpoly_formats::Error`]). Messages are one line; which
//! errors are the user's mistake (exit 2) is decided by the CLI.

use crate::repr::Repr;
use specpoly_core::light::LightError;

/// An error of `specpoly-spectra`.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// Reading or parsing the file a name points to.
    #[error(transparent)]
    Formats(#[from] specpoly_formats::Error),
    /// Samples the core refuses (not increasing, non-finite, outside 380–780 nm, …).
    #[error("{name}: {source}")]
    Samples {
        /// The spectrum's name.
        name: String,
        /// What the core says.
        source: specpoly_core::Error,
    },
    /// A name that is neither a file nor a built-in table.
    #[error("`{name}`: no such file, and not a built-in table ({builtins})")]
    UnknownTable {
        /// The name.
        name: String,
        /// The built-in names.
        builtins: String,
    },
    /// A table of several columns named without a column.
    #[error("`{spec}` has {count} columns: name one as `{spec}#COLUMN` (or `{spec}#*` for all): {columns}")]
    ColumnNeeded {
        /// The name as given.
        spec: String,
        /// How many columns the table has.
        count: usize,
        /// Their names.
        columns: String,
    },
    /// A column the table does not have.
    #[error("`{table}` has no column `{column}`; it has: {columns}")]
    UnknownColumn {
        /// The table (file or built-in).
        table: String,
        /// The column asked for.
        column: String,
        /// The columns it has.
        columns: String,
    },
    /// A light whose name does not resolve (the reason inside: [`Error::UnknownTable`],
    /// [`Error::ColumnNeeded`], [`Error::UnknownColumn`] or a missing file).
    #[error("unknown illuminant {0} (built-in: A, D50, D65, E, FL2, FL7, FL11)")]
    UnknownLight(#[source] Box<Error>),
    /// A light named by something that holds several spectra.
    #[error("`{spec}` names {count} spectra; a light is one")]
    NotOneLight {
        /// The name as given.
        spec: String,
        /// How many spectra it names.
        count: usize,
    },
    /// A channel argument that is not `NAME=FILE.csv[#COLUMN]`.
    #[error("`{text}`: {why}")]
    BadChannel {
        /// The argument.
        text: String,
        /// What is wrong.
        why: &'static str,
    },
    /// `--scale` not finite and > 0.
    #[error("--scale {0}: must be > 0")]
    BadScale(f64),
    /// Data that cannot be a reflectance ([`crate::plausible`]); `why` carries the hint.
    #[error("{name}: {why}")]
    NotReflectance {
        /// The spectrum's name.
        name: String,
        /// What is wrong, and the fix.
        why: String,
    },
    /// A result that overflowed.
    #[error("{name}: the result overflowed (not finite); check the input's scale")]
    Overflow {
        /// What was computed.
        name: String,
    },
    /// An image with a non-finite pixel.
    #[error("{what}: the image overflowed (not finite); check the lights' spectra and scales")]
    ImageOverflow {
        /// The image.
        what: String,
    },
    /// A representation that is not one of the list.
    #[error("unknown representation `{0}` (poly, paper, poly:SxD, sampled:N, hero:N, rgb, exact)")]
    UnknownRepr(String),
    /// A representation of the right form with unsupported parameters (`poly:5x9`).
    #[error("`{text}`: supported {what} {supported}")]
    UnsupportedRepr {
        /// The representation as given.
        text: String,
        /// What is limited (`sample counts N are`).
        what: &'static str,
        /// The supported values.
        supported: String,
    },
    /// A command that needs a polynomial representation given another.
    #[error("`{command}` needs a polynomial representation (poly, paper, poly:SxD), not `{repr}`")]
    NotPolynomial {
        /// The command.
        command: String,
        /// The representation given.
        repr: Repr,
    },
    /// A polynomial layout outside the dispatch list.
    #[error("`{0}`: not a listed layout")]
    UnlistedLayout(Repr),
    /// A light's metrics (its name, and what the core says).
    #[error("{name}: {source}")]
    Light {
        /// The light's name.
        name: String,
        /// What the core says.
        source: LightError,
    },
    /// A light tabulated over less than the 380–780 nm the metrics sum over.
    #[error(
        "{name}: tabulated over {lo}-{hi} nm; the metrics need 380-780 nm \
         (--extrapolate holds the end values, as CIE 015:2018 allows)"
    )]
    ShortLight {
        /// The light's name.
        name: String,
        /// First tabulated wavelength, nm.
        lo: f64,
        /// Last tabulated wavelength, nm.
        hi: f64,
    },
    /// A mix target outside the gamut of the channels.
    #[error("target {target} is outside the gamut of the channels {channels}")]
    OutOfGamut {
        /// The target ([`crate::light::describe`]).
        target: String,
        /// The channels' names.
        channels: String,
    },
    /// An observer named on the command line that is neither built in nor a readable table.
    #[error(
        "unknown observer `{0}` (1931, 1964, 2015-2, 2015-10, cie2006:age=A,field=F, \
         or a CSV file of three sensitivities)"
    )]
    UnknownObserver(String),
    /// A sensitivity table (observer CSV) that cannot be an observer.
    #[error("{name}: {why}")]
    BadObserver {
        /// The file.
        name: String,
        /// What is wrong.
        why: String,
    },
    /// A CIE 2006 observer outside the model's range, or written wrong.
    #[error("`{spec}`: {why}")]
    Cie2006 {
        /// The observer as given.
        spec: String,
        /// What is wrong.
        why: String,
    },
    /// A mix target that has no meaning under the chosen observer: a Duv off the Planckian
    /// locus is defined on the CIE 1931 (u, v) diagram only.
    #[error(
        "--target {target}: a Duv is defined on the CIE 1931 diagram only; under the {observer} \
         observer give xy:X,Y or cct:K (the Planckian radiator's chromaticity under it)"
    )]
    ObserverTarget {
        /// The target as described.
        target: String,
        /// The observer's name.
        observer: String,
    },
    /// A mix the core cannot solve or drive (a wrong channel count or target, a dark channel,
    /// …).
    #[error("{0}")]
    Mix(LightError),
}

/// The result type of this crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;
