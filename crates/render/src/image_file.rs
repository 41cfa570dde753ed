//! Image files: the format follows the extension of the output path; `-` writes a PNG to
//! stdout.
//!
//! - `.png`, 8 bits per channel (default) or 16 (`bits = 16`): display-encoded values (the
//!   display's transfer curve, gamut-mapped), with the colour metadata of the display: an `sRGB`
//!   chunk for the sRGB display, or the display's ICC profile in an `iCCP` chunk when rendering
//!   for a calibrated display (a calibration file; the profile is the one
//!   `specpoly calibrate icc` writes). A plain display TOML has no profile and gets no chunk.
//! - `.exr` (OpenEXR, 32-bit float, `exr` crate): **linear** values, unclipped, in `R G B`
//!   channels with a `chromaticities` attribute, either the display's RGB (its primaries; the
//!   scene white, after white balance, at `(1, 1, 1)`) or CIE XYZ (OpenEXR's XYZ convention:
//!   X, Y, Z in `R G B`, chromaticities red `(1, 0)`, green `(0, 1)`, blue `(0, 0)`, white
//!   `(⅓, ⅓)`; the scene white at `Y = 1`), so every EXR reader knows what the values are.
//!
//! Every file is written whole or not at all (the project's atomic writer).

use super::{Image, Output};
use crate::error::{Error, Result};
use rayon::prelude::*;
use specpoly_core::{quantize, quantize8, Xyz};
use specpoly_display::spec::DisplaySpec;
use std::borrow::Cow;
use std::path::Path;

/// An output file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// PNG, 8 bits per channel.
    Png8,
    /// PNG, 16 bits per channel.
    Png16,
    /// OpenEXR, linear 32-bit float.
    Exr,
}

/// What linear values an EXR holds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ExrSpace {
    /// The display's linear RGB.
    #[default]
    Rgb,
    /// CIE XYZ.
    Xyz,
}

impl std::str::FromStr for ExrSpace {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        match s.to_ascii_lowercase().as_str() {
            "rgb" => Ok(ExrSpace::Rgb),
            "xyz" => Ok(ExrSpace::Xyz),
            _ => Err(Error::ExrSpace {
                given: s.to_string(),
            }),
        }
    }
}

/// Colour metadata for a PNG.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum ColourTag {
    /// No colour chunk.
    #[default]
    None,
    /// An `sRGB` chunk (perceptual intent).
    Srgb,
    /// An `iCCP` chunk holding this ICC profile.
    Icc(Vec<u8>),
}

/// The format for `path` from its extension; `bits` (8 or 16) applies to PNG. `-` (stdout)
/// is PNG, the format a pipe can carry (OpenEXR's writer seeks).
pub fn format_for(path: &Path, bits: u8) -> Result<Format> {
    let ext = if path == Path::new("-") {
        "png".to_string()
    } else {
        path.extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase())
            .unwrap_or_default()
    };
    match (ext.as_str(), bits) {
        ("png", 8) => Ok(Format::Png8),
        ("png", 16) => Ok(Format::Png16),
        ("png", bits) => Err(Error::PngBits { bits }),
        ("exr", _) => Ok(Format::Exr),
        ("", _) => Err(Error::ImageFormat {
            path: path.to_path_buf(),
            ext: None,
        }),
        (e, _) => Err(Error::ImageFormat {
            path: path.to_path_buf(),
            ext: Some(e.to_string()),
        }),
    }
}

impl Output {
    /// XYZ after exposure and white balance (relative, white `Y = 100`).
    #[inline]
    fn adapted(&self, xyz: Xyz) -> Xyz {
        Xyz::from_array(self.adapt.apply(xyz.scale(self.exposure).to_array()))
    }

    /// One pixel's linear display RGB, unclipped, the display white at `(1, 1, 1)`.
    #[inline]
    pub fn linear(&self, xyz: Xyz) -> [f32; 3] {
        let d = &self.display;
        let k = (d.white().y - d.black().y) / 100.0;
        d.xyz_to_linear(self.adapted(xyz).scale(k) + d.black())
    }
}

/// Writes `img` to `path` in `format`.
pub fn write(
    path: &Path,
    img: &Image,
    out: &Output,
    format: Format,
    tag: &ColourTag,
    space: ExrSpace,
) -> Result<()> {
    match format {
        Format::Png8 => {
            let px: Vec<u8> = img
                .xyz
                .par_iter()
                .flat_map_iter(|x| out.device(*x).map(quantize8))
                .collect();
            write_png(path, img.width, img.height, &px, png::BitDepth::Eight, tag)
        }
        Format::Png16 => {
            let px: Vec<u8> = img
                .xyz
                .par_iter()
                .flat_map_iter(|x| {
                    let d = out.device(*x).map(|v| quantize(v, u16::MAX));
                    [d[0].to_be_bytes(), d[1].to_be_bytes(), d[2].to_be_bytes()]
                        .into_iter()
                        .flatten()
                })
                .collect();
            write_png(
                path,
                img.width,
                img.height,
                &px,
                png::BitDepth::Sixteen,
                tag,
            )
        }
        Format::Exr => write_exr(path, img, out, space),
    }
}

/// Writes RGB samples (8-bit, or 16-bit big-endian) as a PNG with its colour chunk. No time
/// stamp: the same pixels give the same bytes.
pub fn write_png(
    path: &Path,
    width: u32,
    height: u32,
    px: &[u8],
    depth: png::BitDepth,
    tag: &ColourTag,
) -> Result<()> {
    Ok(specpoly_formats::atomic::write_with(path, |w| {
        let mut info = png::Info::with_size(width, height);
        info.color_type = png::ColorType::Rgb;
        info.bit_depth = depth;
        if let ColourTag::Icc(p) = tag {
            info.icc_profile = Some(Cow::Borrowed(p));
        }
        let mut enc = png::Encoder::with_info(w, info).map_err(std::io::Error::other)?;
        if *tag == ColourTag::Srgb {
            enc.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
        }
        let mut wr = enc.write_header().map_err(std::io::Error::other)?;
        wr.write_image_data(px).map_err(std::io::Error::other)?;
        wr.finish().map_err(std::io::Error::other)
    })?)
}

/// The EXR `chromaticities` attribute (OpenEXR's `ImfChromaticities`): the xy of the RGB
/// channels' primaries and of `R = G = B`. Display RGB: the display's primaries and the
/// chromaticity of their sum (the linear values are `M⁻¹·XYZ`, black excluded, so `(1, 1, 1)`
/// is `M·1`). XYZ: OpenEXR's convention for CIE XYZ in `R G B` channels, red `(1, 0)`,
/// green `(0, 1)`, blue `(0, 0)`, white `(⅓, ⅓)`, which readers turn back into XYZ exactly.
pub fn exr_chromaticities(out: &Output, space: ExrSpace) -> [[f32; 2]; 4] {
    match space {
        ExrSpace::Xyz => [[1.0, 0.0], [0.0, 1.0], [0.0, 0.0], [1.0 / 3.0, 1.0 / 3.0]],
        ExrSpace::Rgb => {
            let d = &out.display;
            let (xy, _) = d.primaries();
            let w = d.white() - d.black();
            let sum = w.x + w.y + w.z;
            [xy[0], xy[1], xy[2], [w.x / sum, w.y / sum]]
        }
    }
}

fn write_exr(path: &Path, img: &Image, out: &Output, space: ExrSpace) -> Result<()> {
    use exr::prelude::*;
    let w = img.width as usize;
    let px: Vec<[f32; 3]> = match space {
        ExrSpace::Rgb => img.xyz.par_iter().map(|x| out.linear(*x)).collect(),
        ExrSpace::Xyz => img
            .xyz
            .par_iter()
            .map(|x| x.scale(out.exposure / 100.0).to_array())
            .collect(),
    };
    let channels = SpecificChannels::build()
        .with_channel("R")
        .with_channel("G")
        .with_channel("B")
        .with_pixel_fn(|p: Vec2<usize>| {
            let v = px[p.y() * w + p.x()];
            (v[0], v[1], v[2])
        });
    let mut image = Image::from_channels((img.width as usize, img.height as usize), channels);
    let [r, g, b, white] = exr_chromaticities(out, space);
    image.attributes.chromaticities = Some(exr::meta::attribute::Chromaticities {
        red: Vec2(r[0], r[1]),
        green: Vec2(g[0], g[1]),
        blue: Vec2(b[0], b[1]),
        white: Vec2(white[0], white[1]),
    });
    Ok(specpoly_formats::atomic::write_with(path, |f| {
        image
            .write()
            .to_buffered(f)
            .map_err(|e| std::io::Error::other(e.to_string()))
    })?)
}

/// The colour tag for a display: `sRGB` gets the `sRGB` chunk, a calibration file its ICC
/// profile, an ICC profile itself, a plain display TOML nothing.
pub fn colour_tag(spec: &DisplaySpec) -> Result<ColourTag> {
    Ok(match spec {
        DisplaySpec::Srgb => ColourTag::Srgb,
        DisplaySpec::Icc { bytes, .. } => ColourTag::Icc(bytes.clone()),
        DisplaySpec::Primaries(_) => ColourTag::None,
        DisplaySpec::Calibration { path, calibration } => {
            // the description `specpoly calibrate icc` gives
            let desc = specpoly_display::icc::description(calibration, path);
            let opts = specpoly_display::icc::IccOptions::for_calibration(calibration);
            ColourTag::Icc(specpoly_display::icc::build(calibration, &desc, &opts)?)
        }
    })
}
