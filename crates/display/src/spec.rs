//! The display description: what `--display` and `--calibration` name, sniffed once
//! ([`DisplaySpec::open`]) and then asked for the model a consumer needs.
//!
//! - `sRGB` (IEC 61966-2-1, any case);
//! - a calibration file written by `specpoly calibrate` (`format = "specpoly-calibration"`,
//!   docs/calibration.md; [`crate::calibration`]): the fitted model, its interaction lattice
//!   included;
//! - an ICC display profile (recognised by its `acsp` signature; [`crate::icc_read`]);
//! - a small TOML file giving a measured display's primaries (Cowan 1983):
//!
//! ```toml
//! primaries = [[0.640, 0.330], [0.300, 0.600], [0.150, 0.060]]  # x, y of red, green, blue
//! luminance = [21.3, 71.5, 7.2]      # Y (cd/m²) of each primary at full drive
//! gamma = 2.2                        # or: transfer = "srgb", or: transfer = [0.0, …, 1.0] (a table)
//! black = [0.2, 0.21, 0.25]          # optional: XYZ (cd/m²) at zero drive
//! ```

use crate::calibration::Calibration;
use crate::error::{Error, Result};
use serde::Deserialize;
use specpoly_core::display_model::FULL;
use specpoly_core::{Display, DisplayModel, Transfer, Xyz};
use std::path::{Path, PathBuf};

/// A display description, read once.
#[derive(Clone, Debug)]
pub enum DisplaySpec {
    /// sRGB (IEC 61966-2-1).
    Srgb,
    /// A display TOML of primaries, luminances and a transfer curve: the matrix model.
    Primaries(Box<Display>),
    /// A calibration file.
    Calibration {
        /// The file.
        path: PathBuf,
        /// Its calibration.
        calibration: Box<Calibration>,
    },
    /// An ICC display profile.
    Icc {
        /// The file.
        path: PathBuf,
        /// The profile as read.
        bytes: Vec<u8>,
        /// Its display model (with the interaction its table holds).
        model: Box<DisplayModel<FULL>>,
    },
}

impl DisplaySpec {
    /// `sRGB` (any case) or a file: a calibration, an ICC profile or a display TOML.
    pub fn open(spec: &str) -> Result<Self> {
        if spec.eq_ignore_ascii_case("srgb") {
            return Ok(Self::Srgb);
        }
        let path = Path::new(spec);
        if !path.exists() {
            return Err(Error::NoSuchDisplay {
                spec: spec.to_string(),
            });
        }
        if crate::icc_read::is_icc_file(path) {
            return Self::icc(path);
        }
        let text = specpoly_formats::read::text(path)?;
        if crate::calibration::is_calibration_text(&text) {
            let calibration = Calibration::from_toml(&text, &path.display().to_string())?;
            return Ok(Self::Calibration {
                path: path.to_path_buf(),
                calibration: Box::new(calibration),
            });
        }
        Ok(Self::Primaries(Box::new(parse(&text, spec)?)))
    }

    /// A measured display (`--calibration FILE`): a calibration file or an ICC display profile.
    pub fn open_measured(path: &Path) -> Result<Self> {
        if crate::icc_read::is_icc_file(path) {
            return Self::icc(path);
        }
        Ok(Self::Calibration {
            path: path.to_path_buf(),
            calibration: Box::new(crate::calibration::load(path)?),
        })
    }

    fn icc(path: &Path) -> Result<Self> {
        let bytes = specpoly_formats::read::bytes(path)?;
        let model = crate::icc_read::model(&bytes, &path.display().to_string())?;
        Ok(Self::Icc {
            path: path.to_path_buf(),
            bytes,
            model,
        })
    }

    /// The matrix model (Cowan 1983): primaries, black and per-channel curves.
    pub fn display(&self) -> Display {
        match self {
            Self::Srgb => Display::srgb(),
            Self::Primaries(d) => (**d).clone(),
            Self::Calibration { calibration, .. } => calibration.display(),
            Self::Icc { model, .. } => model.display().clone(),
        }
    }

    /// The full model: a calibration's or a LUT profile's with its interaction lattice, else the
    /// matrix model.
    pub fn model(&self) -> Box<DisplayModel<FULL>> {
        match self.interaction_model() {
            Some(m) => m,
            None => Box::new(DisplayModel::new(self.display(), None)),
        }
    }

    /// The full model when it has channel interaction; `None` for sRGB, display TOML files,
    /// matrix/TRC profiles and matrix-only calibrations.
    pub fn interaction_model(&self) -> Option<Box<DisplayModel<FULL>>> {
        match self {
            Self::Srgb | Self::Primaries(_) => None,
            Self::Calibration { calibration, .. } => calibration
                .has_interaction()
                .then(|| Box::new(calibration.model().clone())),
            Self::Icc { model, .. } => model.interaction().is_some().then(|| model.clone()),
        }
    }

    /// The calibration, when the description is one.
    pub fn calibration(&self) -> Option<&Calibration> {
        match self {
            Self::Calibration { calibration, .. } => Some(calibration),
            _ => None,
        }
    }

    /// The name errors give: the file, or `sRGB`.
    pub fn name(&self) -> String {
        match self.path() {
            Some(p) => p.display().to_string(),
            None => "sRGB".into(),
        }
    }

    /// The file, when the description is one.
    pub fn path(&self) -> Option<&Path> {
        match self {
            Self::Srgb | Self::Primaries(_) => None,
            Self::Calibration { path, .. } | Self::Icc { path, .. } => Some(path),
        }
    }
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

/// Parses a display TOML; `source` names it in errors.
pub fn parse(text: &str, source: &str) -> Result<Display> {
    let f: DisplayFile = toml::from_str(text).map_err(|e| Error::Toml {
        message: specpoly_formats::toml_error::one_line(&e, text, source),
    })?;
    let curve = match (f.gamma, f.transfer) {
        (Some(_), Some(_)) => {
            return Err(Error::invalid("give `gamma` or `transfer`,", "not both").in_file(source))
        }
        (Some(g), None) if g.is_finite() && g > 0.0 => Transfer::Gamma(g),
        (Some(g), None) => {
            return Err(Error::invalid(format!("gamma {g}"), "must be positive").in_file(source))
        }
        (None, None) => Transfer::Srgb,
        (None, Some(TransferSpec::Name(n))) => match n.to_ascii_lowercase().as_str() {
            "srgb" => Transfer::Srgb,
            "linear" => Transfer::Linear,
            _ => {
                return Err(Error::bad(
                    format!("transfer `{n}`"),
                    "use \"srgb\", \"linear\" or a table",
                )
                .in_file(source))
            }
        },
        (None, Some(TransferSpec::Table(t))) => Transfer::table(&t).map_err(|error| {
            Error::Model {
                what: "transfer table".into(),
                error,
                hint: String::new(),
            }
            .in_file(source)
        })?,
    };
    let black = f.black.map(Xyz::from_array).unwrap_or_default();
    if f.luminance.iter().any(|l| !(l.is_finite() && *l > 0.0)) {
        return Err(
            Error::invalid("every primary's luminance", "must be positive").in_file(source),
        );
    }
    Display::from_primaries(
        f.primaries,
        f.luminance,
        black,
        [curve.clone(), curve.clone(), curve],
    )
    .map_err(|e| Error::Core(e).in_file(source))
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
