//! The core's one error enum (plain, `no_std`).

use core::fmt;

/// Everything that can go wrong in `specpoly-core`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Error {
    /// Fewer samples than needed (at least one for data, two breakpoints for spans).
    Empty,
    /// Wavelength and value slices differ in length.
    LengthMismatch,
    /// A NaN or infinite wavelength or value, at this index.
    NonFinite(usize),
    /// Wavelengths (or breakpoints) not strictly increasing, at this index.
    NotIncreasing(usize),
    /// The data lie entirely outside 380–780 nm, or a breakpoint falls outside it.
    OutOfRange,
    /// A singular matrix (a degenerate display primary set or fit).
    Singular,
    /// A table (transfer curve) holds too many or too few points for its capacity.
    Capacity,
    /// Not a calibration blob, or one of a version (or with a curve kind) this build does
    /// not read.
    BlobVersion,
    /// A calibration blob whose checksum does not match its bytes.
    BlobChecksum,
    /// A calibration blob shorter than its header says, or whose fields do not fill it.
    BlobTruncated,
    /// A negative value where only non-negative ones make sense (a sensitivity), at this index.
    Negative(usize),
    /// One of three channels (sensitivities) is zero everywhere: channel 0, 1 or 2.
    ZeroChannel(usize),
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Empty => write!(f, "no data"),
            Error::LengthMismatch => write!(f, "wavelengths and values differ in length"),
            Error::NonFinite(i) => write!(f, "non-finite number (NaN or infinity) at sample {i}"),
            Error::NotIncreasing(i) => {
                write!(f, "wavelengths must be strictly increasing (sample {i})")
            }
            Error::OutOfRange => write!(f, "data lie outside 380-780 nm"),
            Error::Singular => write!(f, "singular matrix"),
            Error::Capacity => write!(f, "table size outside its capacity"),
            Error::BlobVersion => write!(f, "not a calibration blob of a version this build reads"),
            Error::BlobChecksum => write!(f, "calibration blob checksum mismatch (corrupted)"),
            Error::BlobTruncated => write!(f, "calibration blob cut short"),
            Error::Negative(i) => write!(f, "negative value at sample {i}"),
            Error::ZeroChannel(k) => write!(f, "channel {} is zero everywhere", k + 1),
        }
    }
}

impl core::error::Error for Error {}
