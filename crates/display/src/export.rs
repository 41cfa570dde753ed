//! `calibrate export`: a calibration baked into a framebuffer pixel transform
//! (`specpoly_core::pixel::PanelTransform`: decode table, 3×3 in fixed point, panel
//! inverse-curve tables, 7.3 KiB) and written as C or Rust source for firmware
//! (docs/calibration.md, "Framebuffer export"), or its display model written as a calibration
//! blob for the C library (`specpoly_core::blob`, docs/c.md).

use crate::calibration::Calibration;
use crate::error::{Error, Result};
use specpoly_core::pixel::{export, Options, PanelTransform, Source, White};
use specpoly_core::{blob as core_blob, GamutMap};

/// The source colour space of the firmware's UI.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SourceArg {
    /// sRGB (IEC 61966-2-1).
    #[default]
    Srgb,
    /// Display P3.
    P3,
    /// Linear-light sRGB.
    Linear,
}

impl From<SourceArg> for Source {
    fn from(s: SourceArg) -> Source {
        match s {
            SourceArg::Srgb => Source::Srgb,
            SourceArg::P3 => Source::DisplayP3,
            SourceArg::Linear => Source::LinearSrgb,
        }
    }
}

/// What to write.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// A C99 header: tables and `NAME_levels`, `NAME_codes`, `NAME_rgb565`.
    CTable,
    /// Rust: `pub static NAME: specpoly_core::pixel::PixelTransform`.
    Rust,
    /// The calibration blob (`specpoly_core::blob`: the display model, versioned and
    /// checksummed) that the C library's `sp_calibration_load` reads: bytes, [`blob`].
    CBlob,
}

/// The panel's bits per channel.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Bits {
    /// 5-6-5.
    #[default]
    Rgb565,
    /// 6-6-6.
    Rgb666,
    /// 8-8-8.
    Rgb888,
}

impl Bits {
    fn array(self) -> [u8; 3] {
        match self {
            Bits::Rgb565 => Options::RGB565,
            Bits::Rgb666 => Options::RGB666,
            Bits::Rgb888 => Options::RGB888,
        }
    }
}

/// How the source white is reproduced.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum WhiteArg {
    /// Adapted (Bradford) to the panel's white: source white → full drive.
    #[default]
    Adapt,
    /// D65 kept (clips at the source white on a panel whose white is not D65).
    Absolute,
}

impl From<WhiteArg> for White {
    fn from(w: WhiteArg) -> White {
        match w {
            WhiteArg::Adapt => White::Adapt,
            WhiteArg::Absolute => White::Absolute,
        }
    }
}

/// A C and Rust identifier: ASCII letter or `_`, then letters, digits, `_`; at most 64.
pub fn identifier(s: &str) -> std::result::Result<String, String> {
    let ok = !s.is_empty()
        && s.len() <= 64
        && s.chars()
            .next()
            .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    if ok {
        Ok(s.to_owned())
    } else {
        Err(format!(
            "\"{s}\" is not an identifier (a letter or _, then letters, digits, _; ≤ 64)"
        ))
    }
}

/// The transform for a calibration (clip gamut map: what the C export implements).
pub fn transform(
    cal: &Calibration,
    source: SourceArg,
    white: WhiteArg,
    bits: Bits,
) -> Result<PanelTransform> {
    let opts = Options {
        source: source.into(),
        white: white.into(),
        map: GamutMap::Clip,
        bits: bits.array(),
    };
    PanelTransform::new(&cal.display(), opts).map_err(|error| Error::Model {
        what: "cannot build the pixel transform".into(),
        error,
        hint: String::new(),
    })
}

/// The source text of `p` in `format`, named `name`; `origin` is said in its leading comment.
pub fn source_text(p: &PanelTransform, format: Format, name: &str, origin: &str) -> Result<String> {
    let mut out = String::new();
    let written = match format {
        Format::CTable => export::write_c(p, name, origin, &mut out),
        Format::Rust => export::write_rust(p, &name.to_ascii_uppercase(), origin, &mut out),
        Format::CBlob => return Err(Error::BlobIsBinary),
    };
    written.map_err(|_| Error::ExportNeedsClip)?;
    Ok(out)
}

/// The calibration blob of `cal` (`specpoly_core::blob`, at most `blob::MAX_BYTES`): its
/// matrix model, Cowan's primaries, black and curves. A calibration with a channel-interaction
/// lattice is refused ([`Error::BlobNeedsMatrixModel`]): the device would compute other colours
/// than the model predicts.
pub fn blob(cal: &Calibration) -> Result<Vec<u8>> {
    if cal.has_interaction() {
        return Err(Error::BlobNeedsMatrixModel);
    }
    let mut buf = [0u8; core_blob::MAX_BYTES];
    let n = core_blob::write(&cal.display(), &mut buf).map_err(|error| Error::Model {
        what: "cannot write the calibration blob".into(),
        error,
        hint: String::new(),
    })?;
    Ok(buf[..n].to_vec())
}
