//! Spectral samples in CGATS files, as ArgyllCMS writes them: a `.ti3` measured with a
//! spectrometer (`dispread`), a `.ccss` (`ccxxmake -S`).
//!
//! The bands are evenly spaced: the keywords `SPECTRAL_BANDS` (count, ≥ 2),
//! `SPECTRAL_START_NM` and `SPECTRAL_END_NM` give them, and band `j` is at
//! `start + j·(end − start)/(bands − 1)` nm. Its field is named after that wavelength rounded
//! to the nearest nanometre, three digits at least: `SPEC_380` … (ArgyllCMS, spectro/dispread.c
//! and xicc/ccss.c: `SPEC_%03d` of `(int)(nm + 0.5)`). CGATS files of other programs name the
//! same fields `SPECTRAL_NM_380`, `SPECTRAL_NM380` or `nm380`; those are read too.
//!
//! The values are spectral radiance (ArgyllCMS: mW·m⁻²·sr⁻¹·nm⁻¹ for a display; a `.ccss`
//! is normalised so its largest value is 100). Negative values are allowed (a spectrometer's
//! noise in the dark bands), values that are not finite are not.

use crate::cgats_table::{bad, number, Table};
use crate::{Error, Result};

/// The most bands read: ArgyllCMS's own limit (`XSPECT_MAX_BANDS`, spectro/xspect.h).
pub const MAX_BANDS: usize = 601;

/// The field-name prefixes read, the first one written.
const PREFIXES: [&str; 4] = ["SPEC_", "SPECTRAL_NM_", "SPECTRAL_NM", "nm"];

/// Evenly spaced bands.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bands {
    /// The first band, nm.
    pub start_nm: f64,
    /// The last band, nm.
    pub end_nm: f64,
    /// How many (≥ 2).
    pub count: usize,
}

impl Bands {
    /// Checked bands: 2–[`MAX_BANDS`] of them, finite wavelengths with `start < end`.
    pub fn new(start_nm: f64, end_nm: f64, count: usize) -> std::result::Result<Self, String> {
        if !(2..=MAX_BANDS).contains(&count) {
            return Err(format!("{count} bands (2–{MAX_BANDS} are read)"));
        }
        if !(start_nm.is_finite() && end_nm.is_finite() && start_nm > 0.0 && start_nm < end_nm) {
            return Err(format!(
                "bands from {start_nm} to {end_nm} nm (need 0 < start < end)"
            ));
        }
        Ok(Self {
            start_nm,
            end_nm,
            count,
        })
    }

    /// 1 nm bands over 380–780 nm (401).
    pub fn visible_1nm() -> Self {
        Self {
            start_nm: 380.0,
            end_nm: 780.0,
            count: 401,
        }
    }

    /// The wavelength of band `j`, nm.
    pub fn nm(&self, j: usize) -> f64 {
        self.start_nm + j as f64 * (self.end_nm - self.start_nm) / (self.count - 1) as f64
    }

    /// The band spacing, nm.
    pub fn step(&self) -> f64 {
        (self.end_nm - self.start_nm) / (self.count - 1) as f64
    }

    /// The field name of band `j` (`SPEC_380`).
    pub fn field(&self, j: usize) -> String {
        format!("SPEC_{:03}", (self.nm(j) + 0.5).floor() as i64)
    }

    /// The keyword lines that declare the bands (`SPECTRAL_BANDS "401"` …), as ArgyllCMS
    /// writes them.
    pub fn keyword_lines(&self) -> String {
        format!(
            "SPECTRAL_BANDS \"{}\"\nSPECTRAL_START_NM \"{:.6}\"\nSPECTRAL_END_NM \"{:.6}\"\n",
            self.count, self.start_nm, self.end_nm
        )
    }
}

/// Spectral samples on common bands.
#[derive(Clone, Debug, PartialEq)]
pub struct SpectralSet {
    /// The bands.
    pub bands: Bands,
    /// One spectrum per sample, `bands.count` values each.
    pub samples: Vec<Vec<f64>>,
}

impl SpectralSet {
    /// Linear interpolation of sample `i` at `nm` (0 outside the bands).
    pub fn at(&self, i: usize, nm: f64) -> f64 {
        let b = &self.bands;
        let s = &self.samples[i];
        if nm < b.start_nm || nm > b.end_nm {
            return 0.0;
        }
        let x = (nm - b.start_nm) / b.step();
        let j = (x.floor() as usize).min(b.count - 2);
        let f = x - j as f64;
        s[j] * (1.0 - f) + s[j + 1] * f
    }

    /// Refuses (naming the sample, 1-based) a spectrum with the wrong number of values or a
    /// value that is not finite.
    pub fn check(&self, kind: &'static str) -> Result<()> {
        for (i, s) in self.samples.iter().enumerate() {
            if s.len() != self.bands.count {
                return Err(Error::SpectralWrite {
                    kind,
                    why: format!(
                        "sample {} has {} values for {} bands",
                        i + 1,
                        s.len(),
                        self.bands.count
                    ),
                });
            }
            if let Some((j, v)) = s.iter().enumerate().find(|(_, v)| !v.is_finite()) {
                return Err(Error::SpectralWrite {
                    kind,
                    why: format!(
                        "sample {} has the non-finite value {v} at {} nm",
                        i + 1,
                        self.bands.nm(j)
                    ),
                });
            }
        }
        Ok(())
    }
}

/// Whether a field name is a spectral band's (`SPEC_380`, `SPECTRAL_NM_380`, `nm380`, …).
fn is_band_field(name: &str) -> bool {
    PREFIXES.iter().any(|p| {
        name.strip_prefix(p)
            .is_some_and(|r| !r.is_empty() && r.bytes().all(|b| b.is_ascii_digit()))
    })
}

/// The column of band `nm` (rounded), under any of the prefixes.
fn band_column(t: &Table, nm: i64) -> Option<usize> {
    t.fields.iter().position(|f| {
        PREFIXES.iter().any(|p| {
            f.strip_prefix(p)
                .filter(|r| !r.is_empty() && r.bytes().all(|b| b.is_ascii_digit()))
                .and_then(|r| r.parse::<i64>().ok())
                == Some(nm)
        })
    })
}

/// A keyword's number, or a one-line error at its line.
fn keyword_number(t: &Table, name: &str, source: &str) -> Result<f64> {
    let line = t.keyword_line(name);
    let v = t.keyword(name).ok_or_else(|| {
        bad(
            source,
            t.lines.identifier,
            format!("spectral fields without the keyword {name}"),
        )
    })?;
    match v.trim().parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(bad(source, line, format!("{name} `{v}` is not a number"))),
    }
}

/// The spectral samples of a table (one per row), or `None` when it has no spectral keywords
/// or fields. One-line errors (`FILE:LINE: …`) for a keyword that is missing or not a number,
/// a band count that does not match the fields, a band whose field is missing, a value that
/// is not a finite number.
pub fn from_table(t: &Table, source: &str) -> Result<Option<SpectralSet>> {
    let n_fields = t.fields.iter().filter(|f| is_band_field(f)).count();
    if t.keyword("SPECTRAL_BANDS").is_none() && n_fields == 0 {
        return Ok(None);
    }
    let count_text = t.keyword("SPECTRAL_BANDS").ok_or_else(|| {
        bad(
            source,
            t.lines.format,
            "spectral fields (SPEC_…) without the keyword SPECTRAL_BANDS",
        )
    })?;
    let count_line = t.keyword_line("SPECTRAL_BANDS");
    let count: usize = count_text.trim().parse().map_err(|_| {
        bad(
            source,
            count_line,
            format!("SPECTRAL_BANDS `{count_text}` is not a whole number"),
        )
    })?;
    let start = keyword_number(t, "SPECTRAL_START_NM", source)?;
    let end = keyword_number(t, "SPECTRAL_END_NM", source)?;
    let bands = Bands::new(start, end, count).map_err(|why| bad(source, count_line, why))?;
    if n_fields != count {
        return Err(bad(
            source,
            t.lines.format,
            format!("SPECTRAL_BANDS is {count} but the data format has {n_fields} spectral fields"),
        ));
    }
    let mut cols = Vec::with_capacity(count);
    for j in 0..count {
        let nm = (bands.nm(j) + 0.5).floor() as i64;
        let c = band_column(t, nm).ok_or_else(|| {
            bad(
                source,
                t.lines.format,
                format!(
                    "no field {} for band {} of {count} ({start}–{end} nm)",
                    bands.field(j),
                    j + 1
                ),
            )
        })?;
        cols.push(c);
    }
    let mut samples = Vec::with_capacity(t.rows.len());
    for (line, row) in &t.rows {
        let mut s = Vec::with_capacity(count);
        for &c in &cols {
            s.push(number(&row[c], source, *line, &t.fields[c])?);
        }
        samples.push(s);
    }
    Ok(Some(SpectralSet { bands, samples }))
}

/// A number as CGATS holds it, 7 significant digits (ArgyllCMS writes 6–7).
pub fn value(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    if (1e-4..1e7).contains(&a) {
        let digits = (6 - a.log10().floor() as i32).clamp(0, 10) as usize;
        let s = format!("{v:.digits$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    } else {
        format!("{v:.6e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cgats_table::parse;

    const GOOD: &str = "CTI3\n\nSPECTRAL_BANDS \"3\"\nSPECTRAL_START_NM \"400.000000\"\nSPECTRAL_END_NM \"700.000000\"\nNUMBER_OF_FIELDS 4\nBEGIN_DATA_FORMAT\nSAMPLE_ID SPEC_400 SPEC_550 SPEC_700\nEND_DATA_FORMAT\nNUMBER_OF_SETS 2\nBEGIN_DATA\n1 1 2 3\n2 -0.5 0 1e-3\nEND_DATA\n";

    fn read(text: &str) -> Result<Option<SpectralSet>> {
        from_table(&parse(text, "f")?[0], "f")
    }

    #[test]
    fn reads_bands_and_values_under_any_prefix() {
        let s = read(GOOD).unwrap().unwrap();
        assert_eq!(s.bands, Bands::new(400.0, 700.0, 3).unwrap());
        assert_eq!(s.samples, vec![vec![1.0, 2.0, 3.0], vec![-0.5, 0.0, 1e-3]]);
        assert!((s.at(0, 475.0) - 1.5).abs() < 1e-12);
        for p in ["SPECTRAL_NM_", "SPECTRAL_NM", "nm"] {
            let t = GOOD.replace("SPEC_", p);
            assert_eq!(read(&t).unwrap().unwrap(), s, "{p}");
        }
        assert_eq!(
            read(
                &GOOD
                    .replace("SPEC_", "X_")
                    .replace("SPECTRAL_BANDS \"3\"\n", "")
            )
            .unwrap(),
            None
        );
    }

    #[test]
    fn bad_spectral_fields_are_one_line_errors() {
        let cases = [
            (
                GOOD.replace("BANDS \"3\"", "BANDS \"4\""),
                "f:7: SPECTRAL_BANDS is 4 but the data format has 3 spectral fields",
            ),
            (
                GOOD.replace("BANDS \"3\"", "BANDS \"x\""),
                "f:3: SPECTRAL_BANDS `x` is not a whole number",
            ),
            (
                GOOD.replace("START_NM \"400.000000\"", "START_NM \"nan\""),
                "f:4: SPECTRAL_START_NM `nan` is not a number",
            ),
            (
                GOOD.replace("SPEC_550", "SPEC_551"),
                "f:7: no field SPEC_550 for band 2 of 3 (400–700 nm)",
            ),
            (
                GOOD.replace("2 -0.5", "2 NaN"),
                "f:13: SPEC_400 `NaN` is not a number",
            ),
            (
                GOOD.replace("SPECTRAL_BANDS \"3\"\n", ""),
                "f:6: spectral fields (SPEC_…) without the keyword SPECTRAL_BANDS",
            ),
            (
                GOOD.replace("END_NM \"700.000000\"", "END_NM \"300\""),
                "f:3: bands from 400 to 300 nm (need 0 < start < end)",
            ),
        ];
        for (text, want) in cases {
            let e = read(&text).unwrap_err().to_string();
            assert_eq!(e, want);
            assert_eq!(e.lines().count(), 1);
        }
    }

    #[test]
    fn values_keep_seven_digits() {
        assert_eq!(value(100.0), "100");
        assert_eq!(value(0.1234567891), "0.1234568");
        assert_eq!(value(-12.5), "-12.5");
        assert_eq!(value(1.5e-9), "1.500000e-9");
        assert_eq!(value(0.0), "0");
        assert_eq!(Bands::new(380.0, 780.0, 81).unwrap().field(1), "SPEC_385");
    }
}
