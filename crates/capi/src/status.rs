//! The status every function returns.

/// What a call did: 0 success, 1 a finished fade (not an error), negative an error. Outputs
/// are written only on `SP_STATUS_OK` (and `SP_STATUS_FADE_DONE` where documented).
#[repr(i32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpStatus {
    /// Success.
    Ok = 0,
    /// `sp_mix_step`: no fade step is pending (the target is shown).
    FadeDone = 1,
    /// A pointer argument is NULL.
    NullPointer = -1,
    /// An input number is NaN or infinite.
    NotFinite = -2,
    /// An input is outside its documented domain (CCT, Duv, chromaticity, luminance, a curve's
    /// gamma, a gamut-map code, a wavelength, an observer or illuminant code).
    Domain = -3,
    /// The chromaticity is more than 0.05 from the Planckian locus or outside 1000–100 000 K:
    /// it has no CCT (CIE 015:2018 §9.5).
    NoCct = -4,
    /// A channel count outside 3 to `SP_MAX_CHANNELS`.
    Channels = -5,
    /// The channels cannot make the target chromaticity.
    OutOfGamut = -6,
    /// The display's primaries give a singular matrix (or a primary with `y ≤ 0`).
    Singular = -7,
    /// A length outside its range: no samples, a table of 1 or more than
    /// `SP_DISPLAY_TABLE_MAX` points, a buffer too large to address.
    Size = -8,
    /// Not a calibration blob of a version this library reads (its magic or version).
    BlobVersion = -9,
    /// A calibration blob whose checksum does not match its bytes (corrupted).
    BlobChecksum = -10,
    /// A calibration blob shorter than its header says (cut off), or with bytes past it.
    BlobTruncated = -11,
}

/// A `Result` whose error is a status.
pub(crate) type Status<T> = Result<T, SpStatus>;

/// The status of a result.
pub(crate) fn of(r: Status<()>) -> SpStatus {
    match r {
        Ok(()) => SpStatus::Ok,
        Err(s) => s,
    }
}

/// [`SpStatus::NotFinite`] unless every value is finite.
pub(crate) fn finite(values: &[f32]) -> Status<()> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(SpStatus::NotFinite)
    }
}

/// The status of a core error.
pub(crate) fn core(e: specpoly_core::Error) -> SpStatus {
    use specpoly_core::Error;
    match e {
        Error::Empty | Error::Capacity | Error::LengthMismatch => SpStatus::Size,
        Error::NonFinite(_) => SpStatus::NotFinite,
        Error::NotIncreasing(_)
        | Error::OutOfRange
        | Error::Negative(_)
        | Error::ZeroChannel(_) => SpStatus::Domain,
        Error::Singular => SpStatus::Singular,
        Error::BlobVersion => SpStatus::BlobVersion,
        Error::BlobChecksum => SpStatus::BlobChecksum,
        Error::BlobTruncated => SpStatus::BlobTruncated,
    }
}
