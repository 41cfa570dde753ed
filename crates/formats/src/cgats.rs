//! CGATS text files (ANSI CGATS.17) as ArgyllCMS writes them: `.ti3` display measurements.
//!
//! A file is one or more tables. Each table starts with an identifier line (`CTI3`, `CAL`, …),
//! then keyword lines (`KEYWORD "value"`), optional `BEGIN_<NAME>` … `END_<NAME>` blocks
//! (ArgyllCMS keeps program arguments there), the field list (`NUMBER_OF_FIELDS n`,
//! `BEGIN_DATA_FORMAT` … `END_DATA_FORMAT`) and the rows (`NUMBER_OF_SETS n`, `BEGIN_DATA` …
//! `END_DATA`). `#` starts a comment.
//!
//! A `.ti3` of a display has the fields `RGB_R RGB_G RGB_B` (device values 0–100) and
//! `XYZ_X XYZ_Y XYZ_Z`. ArgyllCMS's `dispread` normalises XYZ so the white patch has `Y = 100`
//! (`NORMALIZED_TO_Y_100 "YES"`) and writes the white's absolute XYZ in cd/m² as
//! `LUMINANCE_XYZ_CDM2`; a second table `CAL` holds the video-LUT calibration (256 entries per
//! channel) that was loaded while measuring.
//!
//! This is a small reader and writer of our own: the one CGATS crate on crates.io is
//! GPL-3.0, which this project's licence cannot take.

pub(crate) use crate::cgats_table::{bad, keyword, number};
pub use crate::cgats_table::{parse, Table, TableLines};
use crate::measurement::Measurement;
use crate::spectral::SpectralSet;
use crate::{Error, Result};

/// A display's measurements from a `.ti3`.
#[derive(Clone, Debug, PartialEq)]
pub struct Ti3 {
    /// Device values (0–1) and XYZ as written in the file (see [`Ti3::normalized`]).
    pub measurements: Vec<Measurement>,
    /// The 1-based line of each measurement (for messages).
    pub lines: Vec<usize>,
    /// The measurement table's keywords.
    pub keywords: Vec<(String, String)>,
    /// `NORMALIZED_TO_Y_100 "YES"`: XYZ are relative, the white patch has `Y = 100`.
    pub normalized: bool,
    /// `LUMINANCE_XYZ_CDM2`: the white's absolute XYZ in cd/m², if given.
    pub white_cdm2: Option<[f64; 3]>,
    /// The video-LUT calibration loaded while measuring (ArgyllCMS's `CAL` table): rows of
    /// `[input, R, G, B]`, all 0–1.
    pub video_lut: Option<Vec<[f64; 4]>>,
    /// Each measurement's spectrum, when measured with a spectrometer (`SPECTRAL_BANDS` and
    /// `SPEC_…` fields, [`crate::spectral`]), on the same scale as its XYZ.
    pub spectra: Option<SpectralSet>,
}

impl Ti3 {
    /// A keyword of the measurement table.
    pub fn keyword(&self, name: &str) -> Option<&str> {
        keyword(&self.keywords, name)
    }

    /// The factor that turns the file's XYZ into cd/m²: `Y_white / 100` for a normalised file
    /// with `LUMINANCE_XYZ_CDM2`, 1 for absolute data, `None` if a normalised file lacks the
    /// absolute white.
    pub fn absolute_scale(&self) -> Option<f64> {
        if self.normalized {
            self.white_cdm2.map(|w| w[1] / 100.0)
        } else {
            Some(1.0)
        }
    }

    /// The measurements in cd/m² when [`Self::absolute_scale`] is known, otherwise as in the
    /// file; and whether they are absolute.
    pub fn best_units(&self) -> (Vec<Measurement>, bool) {
        match self.absolute_scale() {
            Some(k) => (
                self.measurements
                    .iter()
                    .map(|m| Measurement {
                        device: m.device,
                        xyz: m.xyz.map(|v| v * k),
                    })
                    .collect(),
                true,
            ),
            None => (self.measurements.clone(), false),
        }
    }

    /// Whether the video LUT differs from identity by more than 1/1000 anywhere.
    pub fn video_lut_active(&self) -> bool {
        self.video_lut.as_ref().is_some_and(|rows| {
            rows.iter()
                .any(|r| (1..4).any(|c| (r[c] - r[0]).abs() > 1e-3))
        })
    }
}

/// Reads a display `.ti3`: the first table must have `RGB_R RGB_G RGB_B XYZ_X XYZ_Y XYZ_Z`.
/// Errors are one line with the file's line number.
pub fn read_ti3(text: &str, source: &str) -> Result<Ti3> {
    let tables = parse(text, source)?;
    let t = &tables[0];
    if t.kind == "CTI1" {
        return Err(bad(
            source,
            t.lines.identifier,
            format!("a CTI1 patch set (targets, not measurements; from targen or `calibrate patches`): measure it with `calibrate run --patches {source}` and use the .ti3 that writes"),
        ));
    }
    const NEED: [&str; 6] = ["RGB_R", "RGB_G", "RGB_B", "XYZ_X", "XYZ_Y", "XYZ_Z"];
    let mut col = [0usize; 6];
    for (c, name) in col.iter_mut().zip(NEED) {
        *c = t.field(name).ok_or_else(|| {
            bad(
                source,
                t.lines.format,
                format!(
                    "the first table has no field {name} (a display .ti3 needs {})",
                    NEED.join(" ")
                ),
            )
        })?;
    }
    if t.rows.is_empty() {
        return Err(bad(source, t.lines.end_data, "no measurements"));
    }
    let mut measurements = Vec::with_capacity(t.rows.len());
    let mut lines = Vec::with_capacity(t.rows.len());
    for (line, row) in &t.rows {
        let mut v = [0.0; 6];
        for k in 0..6 {
            v[k] = number(&row[col[k]], source, *line, NEED[k])?;
        }
        for k in 0..3 {
            if !(-1e-6..=100.0 + 1e-6).contains(&v[k]) {
                return Err(bad(
                    source,
                    *line,
                    format!("{} {} is outside 0–100", NEED[k], row[col[k]]),
                ));
            }
        }
        measurements.push(Measurement {
            device: [v[0], v[1], v[2]].map(|x| (x / 100.0).clamp(0.0, 1.0)),
            xyz: [v[3], v[4], v[5]],
        });
        lines.push(*line);
    }
    let normalized = t
        .keyword("NORMALIZED_TO_Y_100")
        .is_some_and(|v| v.eq_ignore_ascii_case("YES"));
    let white_cdm2 = match t.keyword("LUMINANCE_XYZ_CDM2") {
        None => None,
        Some(v) => {
            let parts: Vec<f64> = v
                .split_whitespace()
                .filter_map(|s| s.parse::<f64>().ok())
                .filter(|x| x.is_finite())
                .collect();
            if parts.len() != 3 || parts[1] <= 0.0 {
                return Err(bad(
                    source,
                    t.keyword_line("LUMINANCE_XYZ_CDM2"),
                    format!("LUMINANCE_XYZ_CDM2 `{v}` is not three numbers with Y > 0"),
                ));
            }
            Some([parts[0], parts[1], parts[2]])
        }
    };
    let mut video_lut = None;
    if let Some(cal) = tables.iter().skip(1).find(|t| t.kind == "CAL") {
        let names = ["RGB_I", "RGB_R", "RGB_G", "RGB_B"];
        let cols: Option<Vec<usize>> = names.iter().map(|n| cal.field(n)).collect();
        if let Some(cols) = cols {
            let mut rows = Vec::with_capacity(cal.rows.len());
            for (line, row) in &cal.rows {
                let mut r = [0.0; 4];
                for k in 0..4 {
                    r[k] = number(&row[cols[k]], source, *line, names[k])?;
                }
                rows.push(r);
            }
            video_lut = Some(rows);
        }
    }
    let spectra = crate::spectral::from_table(t, source)?;
    Ok(Ti3 {
        measurements,
        lines,
        keywords: t.keywords.clone(),
        normalized,
        white_cdm2,
        video_lut,
        spectra,
    })
}

/// What [`write_ti3`] writes besides the measurements.
#[derive(Clone, Debug, Default)]
pub struct Ti3Info {
    /// `DESCRIPTOR`.
    pub descriptor: String,
    /// `TARGET_INSTRUMENT`, if known.
    pub instrument: Option<String>,
    /// `CREATED` (any text; `specpoly_display::calibration::now_utc` gives an ISO 8601 time).
    pub created: Option<String>,
    /// Whether the measurements are in cd/m². If so and a white patch (device 1,1,1) is among
    /// them, the file is written as ArgyllCMS does: normalised to the white's `Y = 100`, the
    /// white's absolute XYZ in `LUMINANCE_XYZ_CDM2`. Otherwise XYZ is written as given.
    pub absolute: bool,
    /// More keywords written after the standard ones (name, value), e.g. the patch set a
    /// `calibrate run` measures (`SPECPOLY_PATCH_SET`).
    pub keywords: Vec<(String, String)>,
}

/// The white patch: the brightest measurement at device `(1, 1, 1)`, averaged over repeats.
pub fn white_patch(meas: &[Measurement]) -> Option<[f64; 3]> {
    let whites: Vec<&Measurement> = meas
        .iter()
        .filter(|m| m.device.iter().all(|v| *v >= 1.0 - 1e-9))
        .collect();
    if whites.is_empty() {
        return None;
    }
    let mut s = [0.0; 3];
    for m in &whites {
        for k in 0..3 {
            s[k] += m.xyz[k] / whites.len() as f64;
        }
    }
    Some(s)
}

/// Refuses (naming reading `n`, 1-based) a value that is not finite or a device value
/// outside 0–1: what no `.ti3` can hold so that it reads back.
fn check_reading(n: usize, m: &Measurement) -> Result<()> {
    if let Some(v) = m.device.iter().chain(&m.xyz).find(|v| !v.is_finite()) {
        return Err(Error::Ti3Write {
            why: format!(
                "reading {n} (device {}, XYZ {}) has the non-finite \
                 value {v}, which no .ti3 reader accepts",
                crate::stdout::values(&m.device),
                crate::stdout::values(&m.xyz)
            ),
        });
    }
    if let Some(v) = m.device.iter().find(|v| !(0.0..=1.0).contains(*v)) {
        return Err(Error::Ti3Write {
            why: format!(
                "reading {n} has the device value {v} outside 0–1 \
                 (device {})",
                crate::stdout::values(&m.device)
            ),
        });
    }
    Ok(())
}

/// The lines of a `.ti3` before its rows, through `BEGIN_DATA`: normalised to `white` (its
/// absolute XYZ in `LUMINANCE_XYZ_CDM2`) when given, else `NORMALIZED_TO_Y_100 "NO"`;
/// `NUMBER_OF_SETS` when `sets` is given (it is optional in CGATS).
fn head(
    info: &Ti3Info,
    white: Option<[f64; 3]>,
    sets: Option<usize>,
    bands: Option<&crate::spectral::Bands>,
) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let descriptor = if info.descriptor.is_empty() {
        "Argyll Calibration Target chart information 3"
    } else {
        info.descriptor.as_str()
    };
    let q = |v: &str| v.replace('"', "'");
    let _ = writeln!(s, "CTI3\n");
    let _ = writeln!(s, "DESCRIPTOR \"{}\"", q(descriptor));
    let _ = writeln!(s, "ORIGINATOR \"specpoly\"");
    if let Some(c) = &info.created {
        let _ = writeln!(s, "CREATED \"{}\"", q(c));
    }
    let _ = writeln!(s, "DEVICE_CLASS \"DISPLAY\"");
    let _ = writeln!(s, "COLOR_REP \"RGB_XYZ\"");
    if let Some(i) = &info.instrument {
        let _ = writeln!(s, "TARGET_INSTRUMENT \"{}\"", q(i));
    }
    match white {
        Some(w) => {
            let _ = writeln!(
                s,
                "LUMINANCE_XYZ_CDM2 \"{:.6} {:.6} {:.6}\"",
                w[0], w[1], w[2]
            );
            let _ = writeln!(s, "NORMALIZED_TO_Y_100 \"YES\"");
        }
        None => {
            let _ = writeln!(s, "NORMALIZED_TO_Y_100 \"NO\"");
        }
    }
    for (k, v) in &info.keywords {
        let _ = writeln!(s, "{k} \"{}\"", q(v));
    }
    let mut fields = "SAMPLE_ID RGB_R RGB_G RGB_B XYZ_X XYZ_Y XYZ_Z".to_string();
    let mut n_fields = 7;
    if let Some(b) = bands {
        s.push_str(&b.keyword_lines());
        for j in 0..b.count {
            fields.push(' ');
            fields.push_str(&b.field(j));
        }
        n_fields += b.count;
    }
    let _ = writeln!(s, "\nNUMBER_OF_FIELDS {n_fields}");
    let _ = writeln!(s, "BEGIN_DATA_FORMAT");
    let _ = writeln!(s, "{fields}");
    let _ = writeln!(s, "END_DATA_FORMAT\n");
    if let Some(n) = sets {
        let _ = writeln!(s, "NUMBER_OF_SETS {n}");
    }
    let _ = writeln!(s, "BEGIN_DATA");
    s
}

/// Row `n` (1-based, its `SAMPLE_ID`) of a `.ti3`, its XYZ times `scale`, with its newline;
/// refused when scaling overflows.
fn row(n: usize, m: &Measurement, scale: f64) -> Result<String> {
    let v = [
        m.device[0] * 100.0,
        m.device[1] * 100.0,
        m.device[2] * 100.0,
        m.xyz[0] * scale,
        m.xyz[1] * scale,
        m.xyz[2] * scale,
    ];
    // finite readings can still overflow when scaled (to percent, or to the white's Y = 100)
    if let Some(x) = v.iter().find(|x| !x.is_finite()) {
        return Err(Error::Ti3Write {
            why: format!(
                "reading {n} overflows to {x} when scaled (device {}, \
                 XYZ {})",
                crate::stdout::values(&m.device),
                crate::stdout::values(&m.xyz)
            ),
        });
    }
    Ok(format!(
        "{n} {:.5} {:.5} {:.5} {:.7} {:.7} {:.7}\n",
        v[0], v[1], v[2], v[3], v[4], v[5]
    ))
}

/// The line that ends a table's rows.
pub const END_DATA: &str = "END_DATA\n";

/// Writes measurements as a CGATS `.ti3` that ArgyllCMS (`colprof`) and DisplayCAL read.
/// Refuses (naming the reading) any value that is not finite, as written: [`read_ti3`] refuses
/// `inf` and `NaN`, so every file this writes reads back.
pub fn write_ti3(meas: &[Measurement], info: &Ti3Info) -> Result<String> {
    for (i, m) in meas.iter().enumerate() {
        check_reading(i + 1, m)?;
    }
    let white = if info.absolute {
        white_patch(meas)
    } else {
        None
    };
    let (white, scale) = match white {
        Some(w) if w.iter().any(|v| !v.is_finite()) => {
            return Err(Error::Ti3Write {
                why: format!(
                    "the white patch averages to the non-finite XYZ {}",
                    crate::stdout::values(&w)
                ),
            });
        }
        Some(w) if w[1] > 0.0 => (Some(w), 100.0 / w[1]),
        _ => (None, 1.0),
    };
    let mut s = head(info, white, Some(meas.len()), None);
    for (i, m) in meas.iter().enumerate() {
        s.push_str(&row(i + 1, m, scale)?);
    }
    s.push_str(END_DATA);
    Ok(s)
}

/// Writes measurements with their spectra as the `.ti3` ArgyllCMS's `dispread` writes with a
/// spectrometer: the fields of [`write_ti3`] then one `SPEC_nnn` per band, the bands in
/// `SPECTRAL_BANDS`, `SPECTRAL_START_NM`, `SPECTRAL_END_NM`. Normalised as [`write_ti3`]
/// normalises (spectra by the same factor as XYZ, as `dispread` does). `spectra` has one
/// spectrum per measurement; refused (nothing returned) when the counts differ or a value is
/// not finite.
pub fn write_spectral_ti3(
    meas: &[Measurement],
    spectra: &SpectralSet,
    info: &Ti3Info,
) -> Result<String> {
    const KIND: &str = "spectral .ti3";
    if spectra.samples.len() != meas.len() {
        return Err(Error::SpectralWrite {
            kind: KIND,
            why: format!(
                "{} spectra for {} readings",
                spectra.samples.len(),
                meas.len()
            ),
        });
    }
    spectra.check(KIND)?;
    for (i, m) in meas.iter().enumerate() {
        check_reading(i + 1, m)?;
    }
    let white = if info.absolute {
        white_patch(meas)
    } else {
        None
    };
    let (white, scale) = match white {
        Some(w) if w.iter().all(|v| v.is_finite()) && w[1] > 0.0 => (Some(w), 100.0 / w[1]),
        _ => (None, 1.0),
    };
    let mut s = head(info, white, Some(meas.len()), Some(&spectra.bands));
    for (i, (m, sp)) in meas.iter().zip(&spectra.samples).enumerate() {
        let r = row(i + 1, m, scale)?;
        s.push_str(r.trim_end());
        for v in sp {
            let x = v * scale;
            if !x.is_finite() {
                return Err(Error::SpectralWrite {
                    kind: KIND,
                    why: format!("reading {} overflows when scaled", i + 1),
                });
            }
            s.push(' ');
            s.push_str(&crate::spectral::value(x));
        }
        s.push('\n');
    }
    s.push_str(END_DATA);
    Ok(s)
}

/// The readings log form of a `.ti3` (what `calibrate run` appends to while it measures): the
/// head of [`write_ti3`] with XYZ as given (`NORMALIZED_TO_Y_100 "NO"`: no white is needed
/// before the first row) and no `NUMBER_OF_SETS`, through `BEGIN_DATA`. Rows
/// ([`ti3_log_row`]) follow, then [`END_DATA`]; every prefix that ends in a whole row plus
/// `END_DATA` is a `.ti3` that [`read_ti3`] reads.
pub fn ti3_log_head(info: &Ti3Info) -> String {
    head(info, None, None, None)
}

/// Row `n` (1-based) of the readings log ([`ti3_log_head`]), with its newline; refused as
/// [`write_ti3`] refuses a reading.
pub fn ti3_log_row(n: usize, m: &Measurement) -> Result<String> {
    check_reading(n, m)?;
    row(n, m, 1.0)
}

/// A readings log a run left open — stopped by `SIGKILL`, a crash or a full disk before it
/// wrote [`END_DATA`] after its last row — closed: the text with `END_DATA` appended, and the
/// last line, if it was torn (cut off without its newline, or not a whole row), dropped and
/// returned (control characters escaped). `None` when `text` is not an open log (no
/// `BEGIN_DATA`, or its rows end with `END_DATA`) or is not one even when closed.
pub fn close_open_log(text: &str, source: &str) -> Option<(String, Option<String>)> {
    let last = text.lines().rev().find(|l| !l.trim().is_empty())?;
    if last.trim() == "END_DATA" || !text.lines().any(|l| l.trim() == "BEGIN_DATA") {
        return None;
    }
    let closed = |body: &str| {
        let mut s = body.to_string();
        if !s.is_empty() && !s.ends_with('\n') {
            s.push('\n');
        }
        s.push_str(END_DATA);
        s
    };
    let drop_last = |t: &str| {
        let body = t.trim_end_matches('\n');
        let cut = body.rfind('\n').map_or(0, |i| i + 1);
        let torn = crate::escape::one_line(&body[cut..]).into_owned();
        (body[..cut].to_string(), torn)
    };
    let (body, torn) = if text.ends_with('\n') {
        let lines = text.lines().count();
        match read_ti3(&closed(text), source) {
            Ok(_) => return Some((closed(text), None)),
            // the last line is not a whole row
            Err(Error::Cgats { line: Some(l), .. }) | Err(Error::CgatsNumber { line: l, .. })
                if l == lines =>
            {
                let (b, t) = drop_last(text);
                (b, Some(t))
            }
            Err(_) => return None,
        }
    } else {
        let (b, t) = drop_last(text);
        (b, Some(t))
    };
    let fixed = closed(&body);
    read_ti3(&fixed, source).ok()?;
    Some((fixed, torn))
}

/// Reads a .ti3 file.
pub fn read_ti3_file(path: &std::path::Path) -> Result<Ti3> {
    let text = crate::read::text_or_latin1(path)?;
    read_ti3(&text, &path.display().to_string())
}

/// Writes the readings so far as a CGATS .ti3 (A's writer: ArgyllCMS's layout, normalised to
/// the white's `Y = 100` with its absolute XYZ in `LUMINANCE_XYZ_CDM2` once the white patch is
/// measured), atomically.
pub fn save_ti3(path: &std::path::Path, m: &[Measurement], info: &Ti3Info) -> Result<()> {
    crate::atomic::write(path, write_ti3(m, info)?.as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_the_shipped_ti3() {
        let t = read_ti3(
            include_str!("../../../data/ti3/acer-xb271hu-unit1_dispread_2068.ti3"),
            "acer.ti3",
        )
        .unwrap();
        assert_eq!(t.measurements.len(), 2068);
        assert!(t.normalized);
        assert!((t.white_cdm2.unwrap()[1] - 118.724927).abs() < 1e-9);
        assert_eq!(t.video_lut.as_ref().unwrap().len(), 256);
        assert!(t.video_lut_active());
        assert_eq!(t.measurements[0].device, [1.0; 3]);
        assert_eq!(t.lines[0], 38);
    }

    #[test]
    fn a_log_is_a_ti3_after_every_row_and_an_open_one_is_closed_without_its_torn_line() {
        let info = Ti3Info {
            absolute: true,
            ..Default::default()
        };
        let m = |k: f64| Measurement {
            device: [k / 4.0; 3],
            xyz: [k, k + 0.5, k + 0.25],
        };
        let mut text = ti3_log_head(&info);
        for n in 1..=3 {
            text.push_str(&ti3_log_row(n, &m(n as f64)).unwrap());
            let closed = format!("{text}{END_DATA}");
            let t = read_ti3(&closed, "log").unwrap();
            assert_eq!(t.measurements.len(), n);
            assert_eq!(t.measurements[n - 1], m(n as f64));
            // a whole file is not an open log
            assert_eq!(close_open_log(&closed, "log"), None);
        }
        // killed between rows: closed as it is
        let (closed, torn) = close_open_log(&text, "log").unwrap();
        assert_eq!(closed, format!("{text}{END_DATA}"));
        assert_eq!(torn, None);
        // killed inside a row, with and without its newline
        for cut in [
            "4 100.00000 10",
            "4 100.0DATA\n",
            "4 100.00000 100.00000 100.00000 1 2\n",
        ] {
            let (closed, torn) = close_open_log(&format!("{text}{cut}"), "log").unwrap();
            assert_eq!(closed, format!("{text}{END_DATA}"));
            assert_eq!(torn.as_deref(), Some(cut.trim_end()));
        }
        assert!(ti3_log_row(4, &m(f64::NAN)).is_err());
    }

    #[test]
    fn roundtrip() {
        let m = vec![
            Measurement {
                device: [1.0, 1.0, 1.0],
                xyz: [95.0, 100.0, 108.0],
            },
            Measurement {
                device: [0.5, 0.25, 0.0],
                xyz: [20.0, 15.0, 3.0],
            },
        ];
        let info = Ti3Info {
            absolute: true,
            ..Default::default()
        };
        let text = write_ti3(&m, &info).unwrap();
        let t = read_ti3(&text, "x").unwrap();
        let (back, abs) = t.best_units();
        assert!(abs);
        for (a, b) in m.iter().zip(&back) {
            for k in 0..3 {
                assert!((a.device[k] - b.device[k]).abs() < 1e-7);
                assert!((a.xyz[k] - b.xyz[k]).abs() < 1e-5);
            }
        }
    }

    #[test]
    fn errors_name_the_line() {
        let good = "CTI3\n\nNUMBER_OF_FIELDS 7\nBEGIN_DATA_FORMAT\nSAMPLE_ID RGB_R RGB_G RGB_B XYZ_X XYZ_Y XYZ_Z\nEND_DATA_FORMAT\nNUMBER_OF_SETS 1\nBEGIN_DATA\n1 100 100 100 95 100 108\nEND_DATA\n";
        assert!(read_ti3(good, "f").is_ok());
        let e = read_ti3(&good.replace("1 100 100 100 95", "1 100 100 x 95"), "f").unwrap_err();
        assert_eq!(e.to_string(), "f:9: RGB_B `x` is not a number");
        let e = read_ti3(&good.replace("SETS 1", "SETS 2"), "f").unwrap_err();
        assert!(e.to_string().starts_with("f:7: NUMBER_OF_SETS is 2"), "{e}");
        let e = read_ti3(&good.replace("FIELDS 7", "FIELDS 6"), "f").unwrap_err();
        assert!(e.to_string().starts_with("f:3: NUMBER_OF_FIELDS"), "{e}");
        let e = read_ti3(&good.replace(" XYZ_Z", " XYZ_W"), "f").unwrap_err();
        assert!(e.to_string().contains("XYZ_Z"), "{e}");
        let e = read_ti3(&good.replace("BEGIN_DATA\n", ""), "f").unwrap_err();
        assert!(e.to_string().starts_with("f:"), "{e}");
        let e = read_ti3(good.split("BEGIN_DATA\n").next().unwrap(), "f").unwrap_err();
        assert!(e.to_string().contains("no BEGIN_DATA"), "{e}");
        let e = read_ti3(&good.replace("95 100 108", "95 100"), "f").unwrap_err();
        assert!(e.to_string().starts_with("f:9: expected 7 values"), "{e}");
    }

    #[test]
    fn non_finite_readings_are_refused_and_no_file_is_written() {
        let dir = std::env::temp_dir().join(format!("specpoly-ti3-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("inf.ti3");
        let _ = std::fs::remove_file(&path);
        for (absolute, bad) in [
            (false, [f64::INFINITY, 1.0, 1.0]),
            (true, [1.0, f64::NAN, 1.0]),
        ] {
            let m = vec![
                Measurement {
                    device: [1.0; 3],
                    xyz: [95.0, 100.0, 108.0],
                },
                Measurement {
                    device: [0.5, 0.0, 0.0],
                    xyz: bad,
                },
            ];
            let info = Ti3Info {
                absolute,
                ..Default::default()
            };
            let e = write_ti3(&m, &info).unwrap_err().to_string();
            assert!(e.contains("reading 2"), "{e}");
            let e = save_ti3(&path, &m, &info).unwrap_err();
            assert!(e.to_string().contains("cannot write a .ti3"), "{e}");
            assert!(!path.exists(), "no file is written");
        }
        let m = vec![Measurement {
            device: [1.5, 0.0, 0.0],
            xyz: [1.0; 3],
        }];
        let e = write_ti3(&m, &Ti3Info::default()).unwrap_err().to_string();
        assert!(e.contains("outside 0–1"), "{e}");
        // a reading overflowing on the way to the white's Y = 100
        let m = vec![
            Measurement {
                device: [1.0; 3],
                xyz: [1e-300, 1e-300, 1e-300],
            },
            Measurement {
                device: [0.5, 0.0, 0.0],
                xyz: [1e300, 1.0, 1.0],
            },
        ];
        let info = Ti3Info {
            absolute: true,
            ..Default::default()
        };
        assert!(write_ti3(&m, &info)
            .unwrap_err()
            .to_string()
            .contains("overflows"));
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn every_written_value_reads_back() {
        // extremes that are finite as written: huge, tiny, negative, zero
        let vals = [
            0.0,
            -0.0,
            1e-300,
            -1e-12,
            0.5,
            1.0,
            123456.789,
            -1e15,
            1e300,
            f64::MAX / 100.0,
        ];
        for absolute in [false, true] {
            let mut m = vec![Measurement {
                device: [1.0; 3],
                xyz: [95.0, 100.0, 108.0],
            }];
            for (i, a) in vals.iter().enumerate() {
                let b = vals[(i + 3) % vals.len()];
                let d = vals[(i + 5) % vals.len()];
                m.push(Measurement {
                    device: [a.clamp(0.0, 1.0), 0.25, 1.0],
                    xyz: [*a, b, d],
                });
            }
            let info = Ti3Info {
                absolute,
                ..Default::default()
            };
            let text = write_ti3(&m, &info).unwrap();
            let t = read_ti3(&text, "x").unwrap_or_else(|e| panic!("{e}\n{text}"));
            assert_eq!(t.measurements.len(), m.len());
        }
    }
}
