//! Light-source metrics and multi-channel LED mixing.
//!
//! A light is kept as its *exact tabulated* spectral power distribution, summarised once as
//! moments ([`Source`]); the test samples of the colour-rendering standards are reflectances,
//! fitted once with the project's polynomials ([`Samples`]). The colour of every sample under
//! any light is then three dot products, and because moments are linear in the light, a mix of
//! LED channels `Σ dᵢ·Sᵢ` has moments `Σ wᵢ·Mᵢ` ([`crate::Moments::blend`]): that is what lets the
//! metrics run inside an optimiser (and later on the microcontroller).
//!
//! - [`cct`]: CIE 1960 UCS, correlated colour temperature and Duv (nearest point on the
//!   Planckian locus, found directly; CIE 015:2018 §9.5);
//! - [`reference`](mod@reference): Planckian radiators and CIE daylight, the reference illuminants;
//! - [`spd`]: a light on its own 1 nm or 5 nm grid over 380–780 nm, as the standards sum it
//!   (the metrics of one measured light; [`sprague`] takes the 5 nm test samples to 1 nm);
//! - [`cri`]: CIE 13.3-1995 general colour rendering index Ra and the special indices (R9);
//! - [`cam02`]: CIECAM02 and CAM02-UCS (CIE 159:2004; Luo, Cui & Li 2006);
//! - [`tm30`]: CIE 224:2017 / ANSI-IES TM-30 fidelity Rf and gamut index Rg, the hue bins and
//!   the 99 samples' fidelities, the colour vector graphic's points;
//! - [`design_intent`]: ANSI/IES TM-30-20 Annex E priority levels (preference, vividness,
//!   fidelity);
//! - [`mix`]: duties of 3–6 channels for a chromaticity or CCT target, the freedom spent on Rf,
//!   Ra, luminous efficacy or least drive.
//! - [`mix_limits`]: the same with lower limits on Ra, R9, Rf, Rg (mixing to a specification);
//! - [`locus`]: the Planckian locus as a 25-node table (f32, cubic Hermite in mired), for
//!   devices;
//! - [`spectral`]: peak wavelength, FWHM, dominant wavelength and excitation purity;
//! - [`alpha_opic`]: CIE S 026:2018 α-opic irradiances, ELR, DER and EDI;
//! - [`ansi_c78377`]: ANSI C78.377-2017 nominal CCTs and their quadrangles;
//! - [`ja8`]: California Title 24 JA8's colour clauses;
//! - [`channels`]: the device's mixer (f32): 3–`M` channels' XYZ, `xy`/CCT targets, the least
//!   weighted drive, fades.

pub mod alpha_opic;
pub mod ansi_c78377;
pub mod cam02;
pub mod cct;
pub mod channels;
pub mod cri;
pub mod design_intent;
pub mod ja8;
pub mod locus;
pub mod mix;
pub mod mix_limits;
pub mod reference;
pub mod samples;
pub mod source;
pub mod spd;
pub mod spectral;
pub mod sprague;
pub mod tm30;

pub use cct::Cct;
pub use cri::Cri;
pub use mix::{Driven, Mix, Objective, Target};
pub use samples::Samples;
pub use source::Source;
pub use spd::Spd;
pub use tm30::Tm30;

use core::fmt;

/// Everything that can go wrong in light metrics and mixing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightError {
    /// The light has no luminous power (or a non-finite one).
    Dark,
    /// The light is too far from the Planckian locus (|Duv| > 0.05) or outside 1000–100 000 K:
    /// CCT and the colour-rendering metrics are not defined (CIE 015:2018 §9.5).
    NoCct {
        /// The CIE 1960 u of the light.
        u: f64,
        /// The CIE 1960 v of the light.
        v: f64,
    },
    /// The target chromaticity cannot be made by the channels at non-negative drive.
    OutOfGamut,
    /// Channel count outside 3–6.
    Channels(usize),
    /// A target outside its domain (chromaticity, CCT, Duv or luminance), or non-finite.
    BadTarget,
    /// The light is tabulated over less than 380–780 nm, the range the metrics sum over.
    Range {
        /// First tabulated wavelength, nm.
        lo: f64,
        /// Last tabulated wavelength, nm.
        hi: f64,
    },
    /// A tabulated value below −[`spd::NEGATIVE_NOISE`] × the light's peak: not measurement
    /// noise around zero but a light emitting negative power, which no metric is defined for.
    Negative {
        /// Wavelength of the most negative value, nm.
        nm: f64,
        /// The most negative value.
        value: f64,
        /// The light's largest value.
        peak: f64,
    },
    /// An error from the core (mismatched breakpoints, singular matrices).
    Core(crate::Error),
}

impl From<crate::Error> for LightError {
    fn from(e: crate::Error) -> Self {
        LightError::Core(e)
    }
}

impl fmt::Display for LightError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LightError::Dark => write!(f, "the light has no luminous power"),
            LightError::NoCct { u, v } => write!(
                f,
                "no correlated colour temperature: u,v = {u:.4},{v:.4} is more than 0.05 from the \
                 Planckian locus or outside 1000-100000 K"
            ),
            LightError::OutOfGamut => {
                write!(f, "the target is outside the channels' gamut")
            }
            LightError::Channels(n) => write!(f, "{n} channels: a mix takes 3 to 6"),
            LightError::BadTarget => write!(f, "target outside its domain"),
            LightError::Range { lo, hi } => write!(
                f,
                "the light is tabulated over {lo}-{hi} nm; the colour metrics need 380-780 nm \
                 (or the end values held, as CIE 015:2018 allows)"
            ),
            LightError::Negative { nm, value, peak } => write!(
                f,
                "negative spectral power {value} at {nm} nm, below -{}% of the peak {peak}: a \
                 light cannot emit negative power (subtract less dark signal, or clip the noise)",
                spd::NEGATIVE_NOISE * 100.0
            ),
            LightError::Core(e) => write!(f, "{e}"),
        }
    }
}

impl core::error::Error for LightError {}
