//! Reading an ICC display profile as a [`Display`] (Cowan's model), for `render --display`,
//! `led --calibration` and `xyz --display` ([`crate::calibration::load_display`], the one loader
//! they share). Little CMS (the `lcms2` crate) parses the profile.
//!
//! A file is taken for an ICC profile when bytes 36–39 hold the signature `acsp`
//! ([`is_icc`]). It must be an RGB display (`mntr`) profile.
//!
//! - **Matrix/TRC profiles** (`rXYZ gXYZ bXYZ`, `rTRC gTRC bTRC`): the colorants are PCS
//!   values (adapted to D50, white `Y = 1`); the display's own XYZ is `chad⁻¹ · PCS` (the
//!   profile's `chad`; a v2 profile without one: Bradford from D50 to its `wtpt`; a v4 profile
//!   without one: D50), times the `lumi` luminance (cd/m²; without `lumi`, a white of
//!   `Y = 100`). A curve that is a pure power law within 1/2000 becomes `Transfer::Gamma`,
//!   any other is sampled at [`specpoly_core::display::TABLE_MAX`] points. A curve that does
//!   not start at 0 (black folded into the curves, as [`crate::icc`] writes it) gives the
//!   display its black, and the curves are renormalised to run from 0 to 1.
//! - **LUT profiles** (an `A2B0` and no colorants): the same model sampled through Little
//!   CMS's relative-colorimetric transform: the primaries at full drive, black, and each
//!   channel's ramp for its curve. Channel interaction in the table is carried by the core's
//!   interaction lattice ([`load_model`]): the table sampled on a 17³ grid less the matrix
//!   model (exact at the nodes, trilinear between them, as Little CMS interpolates a 17³
//!   table); `render --display` and `xyz --display` use it, `led` the matrix model.

use crate::error::{Error, Result};
use lcms2::{
    ColorSpaceSignature, Intent, PixelFormat, Profile, ProfileClassSignature, Tag, TagSignature,
    Transform,
};
use specpoly_core::display_model::FULL;
use specpoly_core::{Display, DisplayModel, Interaction, Transfer, Xyz};
use std::path::Path;

use specpoly_core::colorimetry::ICC_D50;
use specpoly_core::{bradford, Mat3};

/// Whether `bytes` start like an ICC profile (`acsp` at offset 36).
pub fn is_icc(bytes: &[u8]) -> bool {
    bytes.len() >= 128 && &bytes[36..40] == b"acsp"
}

/// Whether the file at `path` is an ICC profile (reads its first 40 bytes; false if it cannot).
pub fn is_icc_file(path: &Path) -> bool {
    use std::io::Read;
    let Ok(meta) = std::fs::metadata(path) else {
        return false;
    };
    if !meta.is_file() || meta.len() < 128 {
        return false;
    }
    let mut head = [0u8; 40];
    std::fs::File::open(path)
        .and_then(|mut f| f.read_exact(&mut head))
        .is_ok()
        && &head[36..40] == b"acsp"
}

/// The display an ICC profile file describes.
pub fn load(path: &Path) -> Result<Display> {
    let bytes = specpoly_formats::read::bytes(path)?;
    display(&bytes, &path.display().to_string())
}

/// The display an ICC profile's bytes describe (its matrix model); `source` names it in errors.
pub fn display(bytes: &[u8], source: &str) -> Result<Display> {
    Ok(model(bytes, source)?.display().clone())
}

/// The full model of an ICC profile file: its matrix model and, for a LUT profile whose table
/// holds channel interaction, the lattice that carries it ([`LATTICE_GRID`]).
pub fn load_model(path: &Path) -> Result<Box<DisplayModel<FULL>>> {
    let bytes = specpoly_formats::read::bytes(path)?;
    model(&bytes, &path.display().to_string())
}

/// Nodes a side of the lattice sampled from a LUT profile's `A2B0` (17, the grid our own
/// profiles' tables have).
pub const LATTICE_GRID: usize = 17;

/// Offsets below this share of the white's luminance everywhere mean the table holds no
/// interaction worth a lattice: a LUT profile of a matrix display differs from its sampled
/// matrix model only by the table's own sampling (16-bit XYZ, a 17³ grid: 0.04 % of the white
/// on the Acer's), the Surface's interaction reaches several percent.
pub const LATTICE_FLOOR: f64 = 1e-3;

/// The model an ICC profile's bytes describe.
pub fn model(bytes: &[u8], source: &str) -> Result<Box<DisplayModel<FULL>>> {
    let bad = |why: String| Error::Profile {
        file: source.to_string(),
        why,
    };
    if !is_icc(bytes) {
        return Err(bad("not an ICC profile (no `acsp` signature)".into()));
    }
    let declared = u32::from_be_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]) as usize;
    if declared != bytes.len() {
        return Err(bad(format!(
            "a broken ICC profile: its header gives {declared} bytes, the file has {}",
            bytes.len()
        )));
    }
    let p = Profile::new_icc(bytes)
        .map_err(|e| bad(format!("a broken ICC profile (Little CMS: {e})")))?;
    if p.device_class() != ProfileClassSignature::DisplayClass {
        return Err(bad(format!(
            "an ICC profile of class `{}`, not a display (`mntr`) profile",
            String::from_utf8_lossy(&bytes[12..16])
        )));
    }
    if p.color_space() != ColorSpaceSignature::RgbData {
        return Err(bad(format!(
            "an ICC display profile of colour space `{}`, not RGB",
            String::from_utf8_lossy(&bytes[16..20])
        )));
    }
    let luminance = match p.read_tag(TagSignature::LuminanceTag) {
        Tag::CIEXYZ(v) if v.Y.is_finite() && v.Y > 0.0 => v.Y,
        _ => 100.0,
    };
    // PCS (D50) → the display's own white
    let chad = match p.read_tag(TagSignature::ChromaticAdaptationTag) {
        Tag::CIExyYTRIPLE(t) => Some([
            [t.Red.x, t.Red.y, t.Red.Y],
            [t.Green.x, t.Green.y, t.Green.Y],
            [t.Blue.x, t.Blue.y, t.Blue.Y],
        ]),
        _ => None,
    };
    let to_display = match chad {
        Some(c) => Mat3(c)
            .inverse()
            .map_err(|_| bad("its `chad` matrix is singular".into()))?,
        None if p.version() < 4.0 => match p.read_tag(TagSignature::MediaWhitePointTag) {
            Tag::CIEXYZ(w) if w.Y > 0.0 => bradford(ICC_D50, Xyz::new(w.X / w.Y, 1.0, w.Z / w.Y)),
            _ => bradford(ICC_D50, ICC_D50),
        },
        None => bradford(ICC_D50, ICC_D50),
    };
    let colorants = [
        TagSignature::RedColorantTag,
        TagSignature::GreenColorantTag,
        TagSignature::BlueColorantTag,
    ];
    let trcs = [
        TagSignature::RedTRCTag,
        TagSignature::GreenTRCTag,
        TagSignature::BlueTRCTag,
    ];
    let n = specpoly_core::display::TABLE_MAX;
    let mut lut = false;
    // primaries (PCS, white Y = 1) and curves sampled at n points (linear light, 0–1)
    let (pcs, curves, black_pcs): ([[f64; 3]; 3], [Vec<f64>; 3], [f64; 3]) =
        if colorants.iter().chain(&trcs).all(|s| p.has_tag(*s)) {
            let mut pcs = [[0.0; 3]; 3];
            for (c, sig) in colorants.iter().enumerate() {
                match p.read_tag(*sig) {
                    Tag::CIEXYZ(v) => pcs[c] = [v.X, v.Y, v.Z],
                    _ => return Err(bad("a colorant tag is not an XYZ".into())),
                }
            }
            let mut curves: [Vec<f64>; 3] = Default::default();
            for (c, sig) in trcs.iter().enumerate() {
                match p.read_tag(*sig) {
                    Tag::ToneCurve(t) => {
                        curves[c] = (0..n)
                            .map(|k| t.eval((k as f64 / (n - 1) as f64) as f32) as f64)
                            .collect()
                    }
                    _ => return Err(bad("a TRC tag is not a curve".into())),
                }
            }
            (pcs, curves, [0.0; 3])
        } else if p.has_tag(TagSignature::AToB0Tag) {
            lut = true;
            sample_lut(&p).map_err(bad)?
        } else {
            return Err(bad(
                "an RGB display profile with neither colorants and curves nor an A2B0 table".into(),
            ));
        };
    // black: what the curves give at 0, through the colorants
    let k: [f64; 3] = [0, 1, 2].map(|c| curves[c][0]);
    let mut black = to_display.apply(black_pcs).map(|v| v * luminance);
    let mut prim = [[0.0; 3]; 3];
    let mut trc = [Transfer::Linear, Transfer::Linear, Transfer::Linear];
    for c in 0..3 {
        let span = curves[c][n - 1] - k[c];
        if !(span.is_finite() && span > 0.0) {
            return Err(bad(format!(
                "channel {c}'s curve does not rise (from {} to {})",
                k[c],
                curves[c][n - 1]
            )));
        }
        let xyz = to_display.apply(pcs[c]).map(|v| v * luminance);
        for j in 0..3 {
            black[j] += k[c] * xyz[j];
            prim[c][j] = span * xyz[j];
        }
        let norm: Vec<f64> = curves[c]
            .iter()
            .map(|v| ((v - k[c]) / span).clamp(0.0, 1.0))
            .collect();
        trc[c] = curve(&norm).map_err(|e| bad(format!("channel {c}'s curve: {e}")))?;
    }
    let mut xy = [[0.0f32; 2]; 3];
    let mut lum = [0.0f32; 3];
    for c in 0..3 {
        let s = prim[c][0] + prim[c][1] + prim[c][2];
        if !(s.is_finite() && s > 0.0 && prim[c][1] > 0.0) {
            return Err(bad(format!(
                "primary {c} has XYZ {:?}: not a display primary",
                prim[c]
            )));
        }
        xy[c] = [(prim[c][0] / s) as f32, (prim[c][1] / s) as f32];
        lum[c] = prim[c][1] as f32;
    }
    let display = Display::from_primaries(
        xy,
        lum,
        Xyz::new(black[0] as f32, black[1] as f32, black[2] as f32),
        trc,
    )
    .map_err(|e| bad(format!("its primaries do not make a display: {e}")))?;
    let lattice = if lut {
        sample_lattice(&p, &display, |pcs| {
            to_display.apply(pcs).map(|v| v * luminance)
        })
        .map_err(bad)?
    } else {
        None
    };
    Ok(Box::new(DisplayModel::new(display, lattice)))
}

/// A LUT profile's channel interaction as a lattice: at each node of a [`LATTICE_GRID`]³ grid
/// of device values, the table's XYZ (Little CMS, relative colorimetric, through `to_display`)
/// less the matrix model's; `None` when every offset is below [`LATTICE_FLOOR`] of the white.
fn sample_lattice(
    p: &Profile,
    display: &Display,
    to_display: impl Fn([f64; 3]) -> [f64; 3],
) -> std::result::Result<Option<Interaction<FULL>>, String> {
    let t = to_pcs(p)?;
    let g = LATTICE_GRID;
    let src: Vec<[f64; 3]> = (0..g * g * g)
        .map(|i| [i / (g * g), i / g % g, i % g].map(|n| n as f64 / (g - 1) as f64))
        .collect();
    let mut dst = vec![[0.0; 3]; src.len()];
    t.transform_pixels(&src, &mut dst);
    let white = display.white().y as f64;
    let mut largest = 0.0f64;
    let offsets: Vec<[f32; 3]> = src
        .iter()
        .zip(&dst)
        .map(|(d, pcs)| {
            let want = to_display(*pcs);
            let base = display.device_to_xyz(d.map(|v| v as f32)).to_array();
            let o = [0, 1, 2].map(|r| want[r] - base[r] as f64);
            largest = o.iter().fold(largest, |m, v| m.max(v.abs()));
            o.map(|v| v as f32)
        })
        .collect();
    if !(largest.is_finite()) {
        return Err("its A2B0 table gives a non-finite XYZ".into());
    }
    if largest <= LATTICE_FLOOR * white {
        return Ok(None);
    }
    Interaction::new(g, offsets)
        .map(Some)
        .map_err(|e| format!("its A2B0 table as a lattice: {e}"))
}

/// A pure power law when one fits every sample within 1/2000, else the table.
fn curve(t: &[f64]) -> std::result::Result<Transfer, String> {
    let n = t.len();
    let mid = t[n / 2];
    let x = (n / 2) as f64 / (n - 1) as f64;
    if mid > 0.0 && mid < 1.0 {
        let g = mid.ln() / x.ln();
        let fits = (0..n).all(|k| {
            let x = k as f64 / (n - 1) as f64;
            (x.powf(g) - t[k]).abs() <= 5e-4
        });
        if fits && (0.1..=10.0).contains(&g) {
            return Ok(Transfer::Gamma(g as f32));
        }
    }
    let f: Vec<f32> = t.iter().map(|v| *v as f32).collect();
    Transfer::table(&f).map_err(|e| e.to_string())
}

/// Little CMS's relative-colorimetric transform from the profile's device RGB to PCS XYZ.
fn to_pcs(p: &Profile) -> std::result::Result<Transform<[f64; 3], [f64; 3]>, String> {
    let xyz = Profile::new_xyz();
    Transform::new(
        p,
        PixelFormat::RGB_DBL,
        &xyz,
        PixelFormat::XYZ_DBL,
        Intent::RelativeColorimetric,
    )
    .map_err(|e| format!("Little CMS cannot use its A2B0 table: {e}"))
}

/// What [`sample_lut`] measures: primaries (PCS, black excluded), curves (0 to 1), black (PCS).
type Sampled = ([[f64; 3]; 3], [Vec<f64>; 3], [f64; 3]);

/// Samples a LUT profile through Little CMS: full-drive primaries and black (PCS) and each
/// channel's curve (its luminance over its ramp, black subtracted, normalised).
fn sample_lut(p: &Profile) -> std::result::Result<Sampled, String> {
    let t = to_pcs(p)?;
    let n = specpoly_core::display::TABLE_MAX;
    let mut src = vec![[0.0; 3]];
    for c in 0..3 {
        for k in 0..n {
            let mut rgb = [0.0; 3];
            rgb[c] = k as f64 / (n - 1) as f64;
            src.push(rgb);
        }
    }
    let mut dst = vec![[0.0; 3]; src.len()];
    t.transform_pixels(&src, &mut dst);
    let black = dst[0];
    let mut pcs = [[0.0; 3]; 3];
    let mut curves: [Vec<f64>; 3] = Default::default();
    for c in 0..3 {
        let ramp = &dst[1 + c * n..1 + (c + 1) * n];
        let full = ramp[n - 1];
        pcs[c] = [0, 1, 2].map(|j| full[j] - black[j]);
        let y = pcs[c][1];
        if !(y.is_finite() && y > 0.0) {
            return Err(format!(
                "channel {c} has no luminance through its A2B0 table"
            ));
        }
        curves[c] = ramp
            .iter()
            .map(|v| ((v[1] - black[1]) / y).clamp(0.0, 1.0))
            .collect();
        curves[c][0] = 0.0;
        for k in 1..n {
            curves[c][k] = curves[c][k].max(curves[c][k - 1]);
        }
    }
    Ok((pcs, curves, black))
}
