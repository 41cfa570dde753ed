//! The calibration file: a versioned TOML file holding a fitted display model (Cowan 1983:
//! `XYZ = M · (t_R(r), t_G(g), t_B(b)) + black`) and where it came from.
//!
//! ```toml
//! format = "specpoly-calibration"
//! version = 1
//! units = "cd/m2"            # or "relative" (white Y = 100)
//! black = [0.11, 0.11, 0.20] # XYZ at device (0, 0, 0)
//! white = [112.7, 118.7, 129.1] # measured XYZ at device (1, 1, 1)
//! [primaries.red]            # chromaticity and luminance at full drive, black excluded
//! x = 0.68
//! y = 0.31
//! Y = 25.0
//! …
//! [transfer]
//! kind = "table"             # or "gamma"
//! gamma = [2.2, 2.2, 2.2]    # the best pure power law per channel (always present)
//! red = […]                  # linear light at device 0, 1/(n−1), …, 1 (n ≤ 64)
//! …
//! [interaction]              # optional: the channel-interaction lattice (fit/lattice.rs)
//! grid = 9
//! values = [[…], …]          # grid³ XYZ offsets
//! [fit]                      # model chosen, residuals, outliers, additivity
//! [provenance]               # source file, dates, instrument, patch counts
//! [video_lut]                # optional: the video LUT loaded while the model holds
//! red = […]                  # ≥ 256 outputs per channel for inputs 0, 1/(n−1), …, 1
//! …
//! ```
//!
//! The model is `XYZ = M · t(rgb) + black + L(rgb)`, `L` the interaction lattice when present
//! (files without `[interaction]`, all version-1 files before it, are the matrix model).
//!
//! Every key is described in docs/calibration.md. Loading checks the format name, the
//! version, and that every number is finite and the model is usable.

use crate::error::{Error, Result};
pub use crate::lattice::Lattice;
pub use crate::time::{now_utc, utc_parts};
use serde::{Deserialize, Serialize};
use specpoly_core::display_model::FULL;
use specpoly_core::{Display, DisplayModel, Interaction, Transfer, Xyz};
use specpoly_formats::toml_error::one_line;
use std::path::Path;

/// The `format` value of a calibration file.
pub const FORMAT: &str = "specpoly-calibration";
/// The calibration-file version this build reads and writes.
pub const VERSION: u32 = 1;

/// A primary at full drive, black excluded.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Primary {
    /// Chromaticity x.
    pub x: f64,
    /// Chromaticity y.
    pub y: f64,
    /// Luminance (the calibration's units).
    #[serde(rename = "Y")]
    pub luminance: f64,
}

impl Primary {
    /// The primary's XYZ.
    pub fn xyz(&self) -> [f64; 3] {
        let k = self.luminance / self.y;
        [self.x * k, self.luminance, (1.0 - self.x - self.y) * k]
    }

    /// From XYZ.
    pub fn from_xyz(p: [f64; 3]) -> Primary {
        let s = p[0] + p[1] + p[2];
        Primary {
            x: p[0] / s,
            y: p[1] / s,
            luminance: p[1],
        }
    }
}

/// The three primaries.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Primaries {
    /// Red.
    pub red: Primary,
    /// Green.
    pub green: Primary,
    /// Blue.
    pub blue: Primary,
}

impl Primaries {
    /// As an array R, G, B.
    pub fn array(&self) -> [Primary; 3] {
        [self.red, self.green, self.blue]
    }
}

/// Which transfer curve the model uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum TransferKind {
    /// The measured ramp, resampled to at most 64 evenly spaced points.
    #[default]
    Table,
    /// A pure power law `l = v^γ` per channel.
    Gamma,
}

/// The per-channel transfer curves.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TransferCurves {
    /// Which curve the model uses.
    pub kind: TransferKind,
    /// The best-fitting power law per channel (least squares on the ramp).
    pub gamma: [f64; 3],
    /// Red's table: linear light at device values `0, 1/(n−1), …, 1`.
    pub red: Vec<f64>,
    /// Green's table.
    pub green: Vec<f64>,
    /// Blue's table.
    pub blue: Vec<f64>,
}

impl TransferCurves {
    /// The tables R, G, B.
    pub fn tables(&self) -> [&[f64]; 3] {
        [&self.red, &self.green, &self.blue]
    }
}

/// ΔE00 statistics over a set of patches (`patches`, `mean`, `p95`, `max` in the file).
pub use specpoly_formats::stats::Stats;

/// How well the model fits.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct FitReport {
    /// How the matrix was found: `"cowan"` (the full-drive primaries minus black) or
    /// `"least-squares"` (over the fit patches, see docs/calibration.md).
    pub matrix: String,
    /// ΔE00 of the model on the patches it was fitted on.
    pub residual: Stats,
    /// ΔE00 on held-out patches, if any were given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub verification: Option<Stats>,
    /// Additivity: ΔE00 between the measured white and `R + G + B − 2·black` (measured);
    /// absent without a white patch.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub additivity_delta_e00: Option<f64>,
    /// Additivity: `(Y_R + Y_G + Y_B − 2·Y_black) / Y_white − 1`, in percent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub additivity_luminance_percent: Option<f64>,
    /// The model the fit chose: `"shaper-matrix"` or `"shaper-matrix + lattice N"` (absent in
    /// files written before the interaction correction).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub model: String,
    /// The candidate models and their cross-validated ΔE00 on the fit patches (how `model`
    /// was chosen).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub candidates: Vec<Candidate>,
    /// Patches left out of the fit as bad readings.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub outliers: Vec<Outlier>,
    /// Primaries the fit had to constrain to the chromaticity triangle (`x ≥ 0`, `y > 0`,
    /// `x + y ≤ 1`) or to the spectral locus (CIE 1931, `fit/locus.rs`), one sentence each.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub constrained: Vec<String>,
}

/// A candidate model of the fit and its cross-validated error.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Candidate {
    /// The model, as in [`FitReport::model`].
    pub model: String,
    /// Mean ΔE00 on each fold's held-out patches, pooled over the folds.
    pub cv_mean: f64,
}

/// A measurement the fit dropped.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Outlier {
    /// Its position among the measurements given to the fit (1-based).
    pub patch: usize,
    /// Its device values (0–1).
    pub device: [f64; 3],
    /// Its ΔE00 against the model fitted with it (the statistic of the test).
    pub delta_e00: f64,
    /// Why it was dropped.
    pub reason: String,
}

/// Where a calibration came from.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Provenance {
    /// The measurements' file.
    pub source: String,
    /// The SHA-256 of the measurements' file as it was when fitted (lower-case hex; absent in
    /// files written before it was recorded): `sha256sum SOURCE` tells whether these readings
    /// are the ones this calibration was fitted from.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub readings_sha256: String,
    /// When the calibration was fitted (UTC, ISO 8601).
    pub created: String,
    /// When the measurements were taken (as the source says), if known.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub measured: String,
    /// The instrument, if known.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub instrument: String,
    /// Patches in the source.
    pub patches_total: usize,
    /// Patches the model was fitted on.
    pub patches_fit: usize,
    /// Held-out patches verified.
    pub patches_verify: usize,
    /// Notes: normalisation, video LUT.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<String>,
}

/// The calibration file's contents.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CalibrationData {
    /// Always [`FORMAT`].
    pub format: String,
    /// Always [`VERSION`].
    pub version: u32,
    /// `"cd/m2"` (absolute) or `"relative"` (white `Y = 100`).
    pub units: String,
    /// XYZ at device `(0, 0, 0)`.
    pub black: [f64; 3],
    /// Measured XYZ at device `(1, 1, 1)` (the model's own white if none was measured).
    pub white: [f64; 3],
    /// The primaries at full drive, black excluded.
    pub primaries: Primaries,
    /// The transfer curves.
    pub transfer: TransferCurves,
    /// The channel-interaction correction, if the fit chose one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub interaction: Option<Lattice>,
    /// Fit quality.
    pub fit: FitReport,
    /// Provenance.
    pub provenance: Provenance,
}

/// Whether `text` is a calibration file (a TOML table with a `format` key), as opposed to
/// another TOML file given where a display is expected (a display file of primaries).
pub fn is_calibration_text(text: &str) -> bool {
    text.parse::<toml::Table>()
        .map(|t| t.contains_key("format"))
        .unwrap_or(false)
}

/// A validated calibration: its file contents and the display model built from them (the
/// core's [`DisplayModel`]: the matrix model and the interaction lattice, in f32).
#[derive(Clone, Debug, PartialEq)]
pub struct Calibration {
    data: CalibrationData,
    model: Box<DisplayModel<FULL>>,
    /// The video LUT loaded while the display was measured (the model describes the display
    /// with it loaded): the file's optional `[video_lut]`.
    video_lut: Option<crate::video_lut::VideoLut>,
}

fn finite(name: &str, v: &[f64]) -> Result<()> {
    match v.iter().position(|x| !x.is_finite()) {
        Some(i) => Err(Error::NotFinite {
            field: name.to_string(),
            index: i,
        }),
        None => Ok(()),
    }
}

impl Calibration {
    /// Checks the contents and builds the display model.
    pub fn new(data: CalibrationData) -> Result<Self> {
        if data.format != FORMAT {
            return Err(Error::WrongFormat {
                found: data.format.clone(),
                expected: FORMAT,
            });
        }
        if data.version != VERSION {
            return Err(Error::Version {
                found: data.version.into(),
                supported: VERSION,
            });
        }
        if data.units != "cd/m2" && data.units != "relative" {
            return Err(Error::invalid(
                format!("units \"{}\"", data.units),
                "must be \"cd/m2\" or \"relative\"",
            ));
        }
        finite("black", &data.black)?;
        finite("white", &data.white)?;
        if data.white[1] <= 0.0 {
            return Err(Error::invalid("white Y", "must be positive"));
        }
        for (name, p) in ["red", "green", "blue"].iter().zip(data.primaries.array()) {
            finite(&format!("primaries.{name}"), &[p.x, p.y, p.luminance])?;
            if p.y <= 0.0 || p.x < 0.0 || p.x + p.y > 1.0 + 1e-9 || p.luminance <= 0.0 {
                return Err(Error::bad(
                    format!("primaries.{name}"),
                    format!(
                        "x = {}, y = {}, Y = {} is not a valid primary (need y > 0, x + y ≤ 1, Y > 0)",
                        p.x, p.y, p.luminance
                    ),
                ));
            }
        }
        let t = &data.transfer;
        let mut curves = [Transfer::Linear, Transfer::Linear, Transfer::Linear];
        for (c, name) in ["red", "green", "blue"].iter().enumerate() {
            finite("transfer.gamma", &t.gamma)?;
            if !(0.1..=10.0).contains(&t.gamma[c]) {
                return Err(Error::invalid(
                    format!("transfer.gamma[{c}] = {}", t.gamma[c]),
                    "is outside 0.1–10",
                ));
            }
            let table = t.tables()[c];
            finite(&format!("transfer.{name}"), table)?;
            let f: Vec<f32> = table.iter().map(|v| *v as f32).collect();
            let tab = Transfer::table(&f).map_err(|error| Error::Model {
                what: format!("transfer.{name}"),
                error,
                hint: format!(
                    " (need 2–{} non-decreasing values)",
                    specpoly_core::display::TABLE_MAX
                ),
            })?;
            // the controller's rule for `trc table` (firmware/PROTOCOL.md): off is 0, full is 1
            if t.kind == TransferKind::Table
                && (table.first() != Some(&0.0) || table.last() != Some(&1.0))
            {
                return Err(Error::bad(
                    format!("transfer.{name}"),
                    format!(
                        "a table must start at 0 and end at 1 (linear light at device 0 and 1), \
                         not {} … {}",
                        table.first().copied().unwrap_or(f64::NAN),
                        table.last().copied().unwrap_or(f64::NAN)
                    ),
                ));
            }
            curves[c] = match t.kind {
                TransferKind::Table => tab,
                TransferKind::Gamma => Transfer::Gamma(t.gamma[c] as f32),
            };
        }
        let interaction = match &data.interaction {
            Some(l) => {
                l.check()?;
                let v = l.values.iter().map(|v| v.map(|x| x as f32));
                Some(Interaction::new(l.grid, v).map_err(|error| Error::Model {
                    what: "interaction".into(),
                    error,
                    hint: " (an offset beyond f32?)".into(),
                })?)
            }
            None => None,
        };
        let p = data.primaries.array();
        let display = Display::from_primaries(
            p.map(|p| [p.x as f32, p.y as f32]),
            p.map(|p| p.luminance as f32),
            Xyz::new(
                data.black[0] as f32,
                data.black[1] as f32,
                data.black[2] as f32,
            ),
            curves,
        )
        .map_err(|error| Error::Model {
            what: "the primaries do not make a display".into(),
            error,
            hint: String::new(),
        })?;
        Ok(Calibration {
            data,
            model: Box::new(DisplayModel::new(display, interaction)),
            video_lut: None,
        })
    }

    /// The video LUT the model holds with, if any (see [`crate::video_lut`]).
    pub fn video_lut(&self) -> Option<&crate::video_lut::VideoLut> {
        self.video_lut.as_ref()
    }

    /// Sets the video LUT the model holds with (checked; an identity LUT is kept too).
    pub fn set_video_lut(&mut self, lut: Option<crate::video_lut::VideoLut>) -> Result<()> {
        if let Some(l) = &lut {
            l.check()?;
        }
        self.video_lut = lut;
        Ok(())
    }

    /// The file's contents.
    pub fn data(&self) -> &CalibrationData {
        &self.data
    }

    /// Mutable provenance and fit report (the model itself stays as validated).
    pub fn report_mut(&mut self) -> (&mut FitReport, &mut Provenance) {
        (&mut self.data.fit, &mut self.data.provenance)
    }

    /// The matrix model (Cowan's model with the fitted curves) for `specpoly-core`.
    pub fn display(&self) -> Display {
        self.model.display().clone()
    }

    /// The full model (matrix model and interaction lattice): the core's evaluation and
    /// inverse, which [`Self::predict`] and [`Self::inverse`] call.
    pub fn model(&self) -> &DisplayModel<FULL> {
        &self.model
    }

    /// Whether XYZ is in cd/m² (else relative to a white of `Y = 100`).
    pub fn absolute(&self) -> bool {
        self.data.units == "cd/m2"
    }

    /// Predicted XYZ for device values in `[0, 1]` (the calibration's units): the matrix
    /// model of [`Self::display`] plus the interaction lattice, if any (the core's
    /// [`DisplayModel::device_to_xyz`], f32, widened).
    pub fn predict(&self, rgb: [f64; 3]) -> [f64; 3] {
        <[f64; 3]>::from(self.model.device_to_xyz(rgb.map(|v| v as f32)))
    }

    /// Whether the model has a channel-interaction correction (then [`Self::display`], the
    /// matrix model alone, is an approximation of [`Self::predict`]).
    pub fn has_interaction(&self) -> bool {
        self.data.interaction.is_some()
    }

    /// Device RGB in `[0, 1]³` whose [`Self::predict`] is `xyz` (the calibration's units): the
    /// core's [`DisplayModel::inverse`], exact (ΔE00 ≤ 0.005) inside the gamut; outside it the
    /// nearest prediction within the cube in least squares.
    pub fn inverse(&self, xyz: [f64; 3]) -> [f64; 3] {
        let x = xyz.map(|v| v as f32);
        self.model.inverse(Xyz::from_array(x)).device.map(f64::from)
    }

    /// The linear light of each channel for device values in `[0, 1]`.
    pub fn linearise(&self, rgb: [f64; 3]) -> [f64; 3] {
        let t = self.model.display().transfer();
        [0, 1, 2].map(|c| t[c].decode(rgb[c] as f32) as f64)
    }

    /// The model's `M` (columns: primaries' XYZ) in f64.
    pub fn matrix(&self) -> [[f64; 3]; 3] {
        let p = self.data.primaries.array().map(|p| p.xyz());
        [0, 1, 2].map(|r| [p[0][r], p[1][r], p[2][r]])
    }

    /// The TOML text of the file.
    pub fn to_toml(&self) -> Result<String> {
        let body = toml::to_string(&self.data).map_err(|error| Error::Write {
            what: "the calibration",
            error,
        })?;
        // the optional table goes last, after every table of the model
        let lut = match &self.video_lut {
            None => String::new(),
            Some(l) => {
                #[derive(Serialize)]
                struct Lut<'a> {
                    video_lut: &'a crate::video_lut::VideoLut,
                }
                let t = toml::to_string(&Lut { video_lut: l }).map_err(|error| Error::Write {
                    what: "the calibration's video LUT",
                    error,
                })?;
                format!("\n{t}")
            }
        };
        Ok(format!(
            "# specpoly display calibration (Cowan's model); keys: docs/calibration.md\n{body}{lut}"
        ))
    }

    /// Parses a calibration file's text; `source` names it in errors.
    pub fn from_toml(text: &str, source: &str) -> Result<Self> {
        let value: toml::Value = text.parse().map_err(|e: toml::de::Error| Error::Toml {
            message: one_line(&e, text, source),
        })?;
        match value.get("format").and_then(|v| v.as_str()) {
            Some(FORMAT) => {}
            Some(f) => {
                // the file's own text, shown on one line (found by fuzzing)
                let f = specpoly_formats::escape::one_line(f);
                return Err(Error::WrongFormat {
                    found: f.into_owned(),
                    expected: FORMAT,
                }
                .in_file(source));
            }
            None => return Err(Error::NotACalibration { expected: FORMAT }.in_file(source)),
        }
        match value.get("version").and_then(|v| v.as_integer()) {
            Some(v) if v == VERSION as i64 => {}
            Some(v) => {
                return Err(Error::Version {
                    found: v,
                    supported: VERSION,
                }
                .in_file(source))
            }
            None => return Err(Error::NoVersion.in_file(source)),
        }
        let lut =
            match value.get("video_lut") {
                None => None,
                Some(v) => Some(v.clone().try_into::<crate::video_lut::VideoLut>().map_err(
                    |e| Error::Toml {
                        message: one_line(&e, text, &format!("{source}: video_lut")),
                    },
                )?),
            };
        let data: CalibrationData = value.try_into().map_err(|e: toml::de::Error| Error::Toml {
            message: one_line(&e, text, source),
        })?;
        let mut cal = Calibration::new(data).map_err(|e| e.in_file(source))?;
        cal.set_video_lut(lut).map_err(|e| e.in_file(source))?;
        Ok(cal)
    }

    /// Writes the file atomically.
    pub fn save(&self, path: &Path) -> Result<()> {
        Ok(specpoly_formats::atomic::write(
            path,
            self.to_toml()?.as_bytes(),
        )?)
    }
}

/// Loads a calibration file.
pub fn load(path: &Path) -> Result<Calibration> {
    let text = specpoly_formats::read::text(path)?;
    Calibration::from_toml(&text, &path.display().to_string())
}
