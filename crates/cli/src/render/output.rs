//! How XYZ pixels become a display's values ([`Output`], [`to_rgb8`]), and the display an
//! image is encoded for ([`load`]): `sRGB` (IEC 61966-2-1), or a small TOML file giving a
//! measured display's primaries (Cowan 1983):
//!
//! ```toml
//! primaries = [[0.640, 0.330], [0.300, 0.600], [0.150, 0.060]]  # x, y of red, green, blue
//! luminance = [21.3, 71.5, 7.2]      # Y (cd/m²) of each primary at full drive
//! gamma = 2.2                        # or: transfer = "srgb", or: transfer = [0.0, …, 1.0] (a table)
//! black = [0.2, 0.21, 0.25]          # optional: XYZ (cd/m²) at zero drive
//! ```
//!
//! A calibration file written by `specpoly calibrate` (`format = "specpoly-calibration"`, see
//! docs/calibration.md) or an ICC display profile is also accepted: its display model is used
//! ([`crate::calibrate::file::load_display`]).

use super::scene::Scene;
use super::{scene_white, Image};
use crate::error::{CliError, Result};
use rayon::prelude::*;
use serde::Deserialize;
use specpoly_core::display_model::FULL;
use specpoly_core::{bradford, quantize8, Display, DisplayModel, GamutMap, Mat3, Transfer, Xyz};
use std::sync::Arc;

/// How XYZ pixels become display values.
#[derive(Clone, Debug)]
pub struct Output {
    /// The display.
    pub display: Display,
    /// Gamut mapping.
    pub gamut: GamutMap,
    /// XYZ multiplier before display.
    pub exposure: f32,
    /// Chromatic adaptation applied before display (Bradford, scene white → display white).
    pub adapt: Mat3,
    /// A calibration's full model when it has channel interaction (`calibrate fit`'s
    /// lattice): device values then come from the core's [`DisplayModel::encode_relative`]
    /// (the matrix model's gamut mapping, then the full model's exact inverse), so the full
    /// model emits what the matrix model [`Self::display`] maps the colour to. `None`: the
    /// matrix model alone.
    pub model: Option<Arc<DisplayModel<FULL>>>,
}

impl Output {
    /// The output for `scene` on `display`: its exposure, and its white adapted to the display's
    /// white when the scene asks for white balance.
    pub fn new(scene: &Scene, display: Display, gamut: GamutMap) -> Self {
        let adapt = if scene.render.white_balance {
            let dw = display.white();
            let dw = dw.scale(100.0 / dw.y);
            bradford(scene_white(scene), dw)
        } else {
            Mat3::IDENTITY
        };
        Self {
            display,
            gamut,
            exposure: scene.render.exposure,
            adapt,
            model: None,
        }
    }

    /// The output with a full model (see [`Self::model`]; a model without interaction is the
    /// matrix model and is dropped).
    pub fn with_model(mut self, model: Option<Box<DisplayModel<FULL>>>) -> Self {
        self.model = model.filter(|m| m.interaction().is_some()).map(Arc::from);
        self
    }

    /// One pixel's display device values in `[0, 1]`, before quantisation (8- and 16-bit PNG).
    #[inline]
    pub fn device(&self, xyz: Xyz) -> [f32; 3] {
        let a = Xyz::from_array(self.adapt.apply(xyz.scale(self.exposure).to_array()));
        match &self.model {
            Some(m) => m.encode_relative(a, self.gamut).device,
            None => self.display.encode_relative(a, self.gamut).device,
        }
    }

    /// One pixel's 8-bit device values.
    pub fn encode(&self, xyz: Xyz) -> [u8; 3] {
        self.device(xyz).map(quantize8)
    }
}

/// The image as 8-bit RGB, row-major (in parallel: the transfer curve's powers cost about as
/// much as tracing a simple scene).
pub fn to_rgb8(img: &Image, out: &Output) -> Vec<u8> {
    let mut rgb = vec![0u8; img.xyz.len() * 3];
    rgb.par_chunks_mut(3)
        .zip(img.xyz.par_iter())
        .for_each(|(px, xyz)| px.copy_from_slice(&out.encode(*xyz)));
    rgb
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct DisplayFile {
    primaries: [[f32; 2]; 3],
    luminance: [f32; 3],
    gamma: Option<f32>,
    transfer: Option<TransferSpec>,
    black: Option<[f32; 3]>,
}

#[derive(Debug, Deserialize)]
#[serde(untagged)]
enum TransferSpec {
    Name(String),
    Table(Vec<f32>),
}

/// `sRGB` (any case) or a display TOML file.
pub fn load(spec: &str) -> Result<Display> {
    if spec.eq_ignore_ascii_case("srgb") {
        return Ok(Display::srgb());
    }
    let path = std::path::Path::new(spec);
    if !path.exists() {
        return Err(CliError::usage(format!(
            "--display `{spec}`: not `sRGB` and no such file"
        )));
    }
    if crate::calibrate::icc_read::is_icc_file(path) {
        return crate::calibrate::file::load_display(path);
    }
    let text = crate::io::read::text(std::path::Path::new(path))?;
    let is_calibration = crate::calibrate::file::is_calibration_text(&text);
    if is_calibration {
        return crate::calibrate::file::load_display(path);
    }
    parse(&text, spec)
}

/// The full model behind `--display SPEC` (`xyz --display`): a calibration's or a LUT ICC
/// profile's (its interaction lattice included), or the matrix model of sRGB, a display TOML
/// file or a matrix/TRC profile.
pub fn load_model(spec: &str) -> Result<Box<DisplayModel<FULL>>> {
    match interaction_model(spec)? {
        Some(m) => Ok(m),
        None => Ok(Box::new(DisplayModel::new(load(spec)?, None))),
    }
}

/// The full model behind `--display SPEC` when it has channel interaction (for
/// [`Output::with_model`]): a calibration with an interaction lattice, or a LUT ICC profile
/// whose table holds interaction; `None` for sRGB, display TOML files, matrix/TRC profiles and
/// matrix-only calibrations.
pub fn interaction_model(spec: &str) -> Result<Option<Box<DisplayModel<FULL>>>> {
    let path = std::path::Path::new(spec);
    if spec.eq_ignore_ascii_case("srgb") || !path.is_file() {
        return Ok(None);
    }
    if crate::calibrate::icc_read::is_icc_file(path) {
        let m = crate::calibrate::icc_read::load_model(path)?;
        return Ok(m.interaction().is_some().then_some(m));
    }
    let text = crate::io::read::text(path)?;
    if !crate::calibrate::file::is_calibration_text(&text) {
        return Ok(None);
    }
    let cal = crate::calibrate::file::load(path)?;
    Ok(cal.has_interaction().then(|| Box::new(cal.model().clone())))
}

/// Parses a display TOML; `source` names it in errors.
pub fn parse(text: &str, source: &str) -> Result<Display> {
    let f: DisplayFile = toml::from_str(text)
        .map_err(|e| CliError::data(crate::io::toml_error::one_line(&e, text, source)))?;
    let curve = match (f.gamma, f.transfer) {
        (Some(_), Some(_)) => {
            return Err(CliError::data(format!(
                "{source}: give `gamma` or `transfer`, not both"
            )))
        }
        (Some(g), None) if g.is_finite() && g > 0.0 => Transfer::Gamma(g),
        (Some(g), None) => {
            return Err(CliError::data(format!(
                "{source}: gamma {g} must be positive"
            )))
        }
        (None, None) => Transfer::Srgb,
        (None, Some(TransferSpec::Name(n))) => match n.to_ascii_lowercase().as_str() {
            "srgb" => Transfer::Srgb,
            "linear" => Transfer::Linear,
            _ => {
                return Err(CliError::data(format!(
                    "{source}: transfer `{n}`: use \"srgb\", \"linear\" or a table"
                )))
            }
        },
        (None, Some(TransferSpec::Table(t))) => Transfer::table(&t)
            .map_err(|e| CliError::data(format!("{source}: transfer table: {e}")))?,
    };
    let black = f.black.map(Xyz::from_array).unwrap_or_default();
    if f.luminance.iter().any(|l| !(l.is_finite() && *l > 0.0)) {
        return Err(CliError::data(format!(
            "{source}: every primary's luminance must be positive"
        )));
    }
    Display::from_primaries(
        f.primaries,
        f.luminance,
        black,
        [curve.clone(), curve.clone(), curve],
    )
    .map_err(|e| CliError::data(format!("{source}: {e}")))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_a_display() {
        let d = parse(
            "primaries = [[0.64, 0.33], [0.30, 0.60], [0.15, 0.06]]\nluminance = [21.26, 71.52, 7.22]\ngamma = 2.2\n",
            "d.toml",
        )
        .unwrap();
        assert!((d.white().y - 100.0).abs() < 0.01);
        assert!(parse("primaries = 1", "d.toml").is_err());
        assert!(parse(
            "primaries = [[0.64, 0.33], [0.30, 0.60], [0.15, 0.06]]\nluminance = [1, 1, -1]\n",
            "d.toml"
        )
        .is_err());
    }
}
