//! A video LUT: three 1-D tables (R, G, B) of `n ≥ 256` entries the graphics card applies to
//! every pixel before it reaches the display (what ArgyllCMS's `dispcal` computes and `dispwin`
//! loads). Entry `k` maps input `k / (n − 1)` to the output stored for each channel, all in
//! `[0, 1]`; between entries the map is linear.
//!
//! Files: ArgyllCMS's `.cal` (a CGATS file with one table `CAL`, fields `RGB_I RGB_R RGB_G
//! RGB_B`, keywords `DEVICE_CLASS "DISPLAY"`, `COLOR_REP "RGB"`), read with the project's
//! CGATS parser ([`specpoly_formats::cgats::parse`]) and written here; the same table ArgyllCMS's
//! `dispread -k/-K` appends to a `.ti3`. In a calibration file the LUT is the optional
//! `[video_lut]` table (`red`, `green`, `blue`: the outputs); in an ICC profile it is the
//! `vcgt` tag ([`crate::icc`]).

use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;
use std::path::Path;

/// The fewest entries a LUT has (an 8-bit card's table).
pub const MIN_ENTRIES: usize = 256;
/// The most entries a LUT may have (a 16-bit table).
pub const MAX_ENTRIES: usize = 65_536;

/// Three 1-D tables, one per channel, equally spaced inputs over `[0, 1]`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct VideoLut {
    /// Red's outputs.
    pub red: Vec<f64>,
    /// Green's outputs.
    pub green: Vec<f64>,
    /// Blue's outputs.
    pub blue: Vec<f64>,
}

impl VideoLut {
    /// The identity LUT of `n` entries.
    pub fn identity(n: usize) -> Self {
        let t: Vec<f64> = (0..n).map(|k| k as f64 / (n - 1) as f64).collect();
        Self {
            red: t.clone(),
            green: t.clone(),
            blue: t,
        }
    }

    /// From the three tables, checked ([`Self::check`]).
    pub fn new(red: Vec<f64>, green: Vec<f64>, blue: Vec<f64>) -> Result<Self> {
        let lut = Self { red, green, blue };
        lut.check()?;
        Ok(lut)
    }

    /// Checks the shape: the three tables have the same length, `MIN_ENTRIES..=MAX_ENTRIES`, and
    /// every value is a finite number in `[0, 1]`.
    pub fn check(&self) -> Result<()> {
        let n = self.red.len();
        if self.green.len() != n || self.blue.len() != n {
            return Err(Error::bad(
                "video LUT",
                format!(
                    "the channels have {}, {} and {} entries (they must be equal)",
                    n,
                    self.green.len(),
                    self.blue.len()
                ),
            ));
        }
        if !(MIN_ENTRIES..=MAX_ENTRIES).contains(&n) {
            return Err(Error::bad(
                "video LUT",
                format!("{n} entries per channel (need {MIN_ENTRIES}–{MAX_ENTRIES})"),
            ));
        }
        for (name, t) in ["red", "green", "blue"].iter().zip(self.tables()) {
            if let Some(k) = t
                .iter()
                .position(|v| !v.is_finite() || !(0.0..=1.0).contains(v))
            {
                return Err(Error::bad(
                    "video LUT",
                    format!("{name}[{k}] = {} is not a number in 0–1", t[k]),
                ));
            }
        }
        Ok(())
    }

    /// Entries per channel.
    pub fn len(&self) -> usize {
        self.red.len()
    }

    /// Whether the LUT has no entries (never true of a checked LUT).
    pub fn is_empty(&self) -> bool {
        self.red.is_empty()
    }

    /// The tables R, G, B.
    pub fn tables(&self) -> [&[f64]; 3] {
        [&self.red, &self.green, &self.blue]
    }

    /// The tables R, G, B, mutable.
    pub fn tables_mut(&mut self) -> [&mut Vec<f64>; 3] {
        [&mut self.red, &mut self.green, &mut self.blue]
    }

    /// The input of entry `k`.
    pub fn input(&self, k: usize) -> f64 {
        k as f64 / (self.len() - 1) as f64
    }

    /// Channel `c`'s output for input `v ∈ [0, 1]` (linear between entries).
    pub fn channel(&self, c: usize, v: f64) -> f64 {
        let t = self.tables()[c];
        let x = v.clamp(0.0, 1.0) * (t.len() - 1) as f64;
        let i = (x.floor() as usize).min(t.len() - 2);
        let f = x - i as f64;
        t[i] + f * (t[i + 1] - t[i])
    }

    /// The device values the display receives for `rgb`.
    pub fn apply(&self, rgb: [f64; 3]) -> [f64; 3] {
        [0, 1, 2].map(|c| self.channel(c, rgb[c]))
    }

    /// Whether every output is within `1/1000` of its input.
    pub fn is_identity(&self) -> bool {
        (0..self.len()).all(|k| {
            let x = self.input(k);
            self.tables().iter().all(|t| (t[k] - x).abs() <= 1e-3)
        })
    }

    /// From a CGATS `CAL` table's rows `[RGB_I, RGB_R, RGB_G, RGB_B]` (as
    /// [`specpoly_formats::cgats::Ti3::video_lut`] holds them): the inputs must be `k / (n − 1)`.
    pub fn from_rows(rows: &[[f64; 4]], source: &str) -> Result<Self> {
        let n = rows.len();
        if n < 2 {
            return Err(Error::invalid(
                "the CAL table",
                format!("has {n} rows (need {MIN_ENTRIES}–{MAX_ENTRIES})"),
            )
            .in_file(source));
        }
        for (k, r) in rows.iter().enumerate() {
            let want = k as f64 / (n - 1) as f64;
            if (r[0] - want).abs() > 1e-4 {
                return Err(Error::bad(
                    format!("CAL row {}", k + 1),
                    format!(
                        "RGB_I {} is not {want:.6} (the inputs must be equally spaced over 0–1)",
                        r[0]
                    ),
                )
                .in_file(source));
            }
        }
        let col = |c: usize| rows.iter().map(|r| r[c]).collect::<Vec<_>>();
        Self::new(col(1), col(2), col(3)).map_err(|e| e.in_file(source))
    }

    /// Reads an ArgyllCMS `.cal` text; `source` names it in errors.
    pub fn from_cal(text: &str, source: &str) -> Result<Self> {
        let tables = specpoly_formats::cgats::parse(text, source)?;
        let t = tables.iter().find(|t| t.kind == "CAL").ok_or_else(|| {
            Error::invalid("no CAL table", "(not an ArgyllCMS calibration file)").in_file(source)
        })?;
        if let Some(class) = t.keyword("DEVICE_CLASS") {
            if class != "DISPLAY" {
                return Err(Error::bad(
                    format!("DEVICE_CLASS \"{class}\""),
                    "not a display calibration",
                )
                .in_file(source));
            }
        }
        if let Some(rep) = t.keyword("COLOR_REP") {
            if rep != "RGB" {
                return Err(
                    Error::bad(format!("COLOR_REP \"{rep}\""), "not an RGB calibration")
                        .in_file(source),
                );
            }
        }
        let names = ["RGB_I", "RGB_R", "RGB_G", "RGB_B"];
        let mut cols = [0usize; 4];
        for (c, n) in cols.iter_mut().zip(names) {
            *c = t.field(n).ok_or_else(|| {
                Error::invalid(
                    "the CAL table",
                    format!("has no field {n} (need {})", names.join(" ")),
                )
                .in_file(source)
            })?;
        }
        let mut rows = Vec::with_capacity(t.rows.len());
        for (line, row) in &t.rows {
            let mut r = [0.0; 4];
            for k in 0..4 {
                r[k] = row[cols[k]]
                    .parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| Error::NotANumber {
                        file: source.to_string(),
                        line: *line,
                        field: names[k].to_string(),
                        text: row[cols[k]].clone(),
                    })?;
            }
            rows.push(r);
        }
        Self::from_rows(&rows, source)
    }

    /// Reads an ArgyllCMS `.cal` file.
    pub fn load(path: &Path) -> Result<Self> {
        let text = specpoly_formats::read::text(path)?;
        Self::from_cal(&text, &path.display().to_string())
    }

    /// The `.cal` text ArgyllCMS reads (`dispwin`, `applycal`, `dispread -k/-K`). `keywords` are
    /// extra `(NAME, value)` pairs (the target, e.g. `TARGET_WHITE_XYZ`) written as ArgyllCMS
    /// does, each declared with `KEYWORD`.
    pub fn to_cal(&self, originator: &str, keywords: &[(String, String)]) -> String {
        let mut s = String::from("CAL    \n\n");
        s.push_str("DESCRIPTOR \"Argyll Device Calibration State\"\n");
        let _ = writeln!(s, "ORIGINATOR \"{}\"", quote(originator));
        let _ = writeln!(s, "CREATED \"{}\"", crate::time::now_utc());
        s.push_str("KEYWORD \"DEVICE_CLASS\"\nDEVICE_CLASS \"DISPLAY\"\n");
        s.push_str("KEYWORD \"COLOR_REP\"\nCOLOR_REP \"RGB\"\n");
        s.push_str(
            "KEYWORD \"VIDEO_LUT_CALIBRATION_POSSIBLE\"\nVIDEO_LUT_CALIBRATION_POSSIBLE \"YES\"\n",
        );
        for (k, v) in keywords {
            let _ = writeln!(s, "KEYWORD \"{k}\"\n{k} \"{}\"", quote(v));
        }
        s.push_str(
            "\nNUMBER_OF_FIELDS 4\nBEGIN_DATA_FORMAT\nRGB_I RGB_R RGB_G RGB_B\nEND_DATA_FORMAT\n\n",
        );
        let _ = writeln!(s, "NUMBER_OF_SETS {}\nBEGIN_DATA", self.len());
        for k in 0..self.len() {
            let _ = writeln!(
                s,
                "{:.10} {:.10} {:.10} {:.10}",
                self.input(k),
                self.red[k],
                self.green[k],
                self.blue[k]
            );
        }
        s.push_str("END_DATA\n");
        s
    }

    /// Writes a `.cal` file atomically.
    pub fn save_cal(
        &self,
        path: &Path,
        originator: &str,
        keywords: &[(String, String)],
    ) -> Result<()> {
        Ok(specpoly_formats::atomic::write(
            path,
            self.to_cal(originator, keywords).as_bytes(),
        )?)
    }
}

/// A CGATS string value cannot hold `"` or a line break.
fn quote(s: &str) -> String {
    s.chars()
        .map(|c| if c == '"' || c.is_control() { '\'' } else { c })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cal_round_trip_and_errors() {
        let mut lut = VideoLut::identity(256);
        lut.red[10] = 0.5;
        let text = lut.to_cal("test", &[("TARGET_WHITE_XYZ".into(), "95 100 108".into())]);
        let back = VideoLut::from_cal(&text, "t.cal").unwrap();
        for c in 0..3 {
            for k in 0..256 {
                assert!((back.tables()[c][k] - lut.tables()[c][k]).abs() < 1e-9);
            }
        }
        assert!(!back.is_identity());
        assert!(VideoLut::identity(256).is_identity());
        assert!((lut.channel(0, 10.5 / 255.0) - (0.5 + 11.0 / 255.0) / 2.0).abs() < 1e-12);
        let short = text.replace("NUMBER_OF_SETS 256", "NUMBER_OF_SETS 255");
        assert!(VideoLut::from_cal(&short, "t.cal").is_err());
        assert!(VideoLut::from_cal(&text.replace(" 0.5000000000", " 1.5"), "t.cal").is_err());
        assert!(VideoLut::from_cal("CTI3\n", "t.cal").is_err());
        assert!(VideoLut::new(vec![0.0; 4], vec![0.0; 4], vec![0.0; 4]).is_err());
    }
}
