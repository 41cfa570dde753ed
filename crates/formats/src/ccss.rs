//! ArgyllCMS colorimeter calibration spectral samples (`.ccss`): a display's spectra, from
//! which a colorimeter whose filters' sensitivities are known (i1Display Pro, Spyder 4/5)
//! computes its own correction for that display.
//!
//! The format is ArgyllCMS's (xicc/ccss.c, `create_ccss_cgats` / `read_ccss_cgats`): a CGATS
//! file of type `CCSS` with one table; keywords `DESCRIPTOR`, `ORIGINATOR`, `CREATED`,
//! `DISPLAY` and/or `TECHNOLOGY` (one is required), `DISPLAY_TYPE_REFRESH` (`YES`/`NO`),
//! `REFERENCE` (the spectrometer), the bands ([`crate::spectral`]) and `SPECTRAL_NORM`; fields
//! `SAMPLE_ID` and `SPEC_nnn`; at least three samples. `ccxxmake -S` scales the samples
//! together so the largest value is 100 ([`Ccss::from_spectra`] does the same).

use crate::cgats::{bad, parse};
use crate::spectral::{self, SpectralSet};
use crate::{Error, Result};

/// A `.ccss`.
#[derive(Clone, Debug, PartialEq)]
pub struct Ccss {
    /// `DESCRIPTOR`.
    pub description: String,
    /// `DISPLAY`: the display's make and model, if given.
    pub display: Option<String>,
    /// `TECHNOLOGY`: ArgyllCMS's display technology name (`LCD White LED`, `OLED`, …).
    pub technology: String,
    /// `DISPLAY_TYPE_REFRESH`: whether the display refreshes (CRT, plasma, some OLED).
    pub refresh: bool,
    /// `REFERENCE`: the spectrometer that measured the samples, if known.
    pub reference: Option<String>,
    /// `CREATED`, if known.
    pub created: Option<String>,
    /// The samples.
    pub samples: SpectralSet,
}

/// The fewest samples ArgyllCMS reads.
pub const MIN_SAMPLES: usize = 3;

impl Ccss {
    /// The samples of `spectra` scaled together so the largest value is 100, as `ccxxmake -S`
    /// makes them.
    pub fn normalise(spectra: &SpectralSet) -> Result<SpectralSet> {
        spectra.check(".ccss")?;
        let big = spectra
            .samples
            .iter()
            .flatten()
            .fold(f64::NEG_INFINITY, |m, v| m.max(*v));
        if !(big > 0.0) {
            return Err(Error::SpectralWrite {
                kind: ".ccss",
                why: "no sample has a positive value".into(),
            });
        }
        Ok(SpectralSet {
            bands: spectra.bands,
            samples: spectra
                .samples
                .iter()
                .map(|s| s.iter().map(|v| v * 100.0 / big).collect())
                .collect(),
        })
    }
}

/// Escapes a keyword value (CGATS has no escape for `"`).
fn quoted(v: &str) -> String {
    crate::escape::one_line(&v.replace('"', "'")).into_owned()
}

/// The `.ccss` text; refused (nothing returned) with fewer than [`MIN_SAMPLES`] samples, an
/// empty technology or a value that is not finite.
pub fn write(c: &Ccss) -> Result<String> {
    use std::fmt::Write;
    c.samples.check(".ccss")?;
    if c.samples.samples.len() < MIN_SAMPLES {
        return Err(Error::SpectralWrite {
            kind: ".ccss",
            why: format!(
                "{} samples (ArgyllCMS reads {MIN_SAMPLES} or more: white and the primaries at least)",
                c.samples.samples.len()
            ),
        });
    }
    if c.technology.trim().is_empty() {
        return Err(Error::SpectralWrite {
            kind: ".ccss",
            why: "no display technology".into(),
        });
    }
    let b = &c.samples.bands;
    let mut s = String::from("CCSS   \n\n");
    let _ = writeln!(s, "DESCRIPTOR \"{}\"", quoted(&c.description));
    let _ = writeln!(s, "ORIGINATOR \"specpoly\"");
    if let Some(t) = &c.created {
        let _ = writeln!(s, "CREATED \"{}\"", quoted(t));
    }
    if let Some(d) = &c.display {
        let _ = writeln!(s, "DISPLAY \"{}\"", quoted(d));
    }
    let _ = writeln!(s, "TECHNOLOGY \"{}\"", quoted(&c.technology));
    let _ = writeln!(
        s,
        "DISPLAY_TYPE_REFRESH \"{}\"",
        if c.refresh { "YES" } else { "NO" }
    );
    if let Some(r) = &c.reference {
        let _ = writeln!(s, "REFERENCE \"{}\"", quoted(r));
    }
    s.push_str(&b.keyword_lines());
    let _ = writeln!(s, "SPECTRAL_NORM \"1.000000\"");
    let _ = writeln!(s, "\nNUMBER_OF_FIELDS {}", b.count + 1);
    let _ = writeln!(s, "BEGIN_DATA_FORMAT");
    s.push_str("SAMPLE_ID");
    for j in 0..b.count {
        s.push(' ');
        s.push_str(&b.field(j));
    }
    let _ = writeln!(s, "\nEND_DATA_FORMAT\n");
    let _ = writeln!(s, "NUMBER_OF_SETS {}", c.samples.samples.len());
    let _ = writeln!(s, "BEGIN_DATA");
    for (i, sample) in c.samples.samples.iter().enumerate() {
        let _ = write!(s, "{}", i + 1);
        for v in sample {
            s.push(' ');
            s.push_str(&spectral::value(*v));
        }
        s.push('\n');
    }
    s.push_str("END_DATA\n");
    Ok(s)
}

/// Reads a `.ccss`; one-line errors (`FILE:LINE: …`).
pub fn read(text: &str, source: &str) -> Result<Ccss> {
    let tables = parse(text, source)?;
    let t = &tables[0];
    if t.kind != "CCSS" {
        return Err(bad(
            source,
            t.lines.identifier,
            format!("a `{}` file, not a CCSS", t.kind),
        ));
    }
    let samples = spectral::from_table(t, source)?.ok_or_else(|| {
        bad(
            source,
            t.lines.format,
            "no spectral samples (SPECTRAL_BANDS and SPEC_… fields)",
        )
    })?;
    if samples.samples.len() < MIN_SAMPLES {
        return Err(bad(
            source,
            t.lines.end_data,
            format!(
                "{} samples (a .ccss has {MIN_SAMPLES} or more)",
                samples.samples.len()
            ),
        ));
    }
    let kw = |k: &str| t.keyword(k).map(str::to_string);
    if kw("DISPLAY").is_none() && kw("TECHNOLOGY").is_none() {
        return Err(bad(
            source,
            t.lines.identifier,
            "neither DISPLAY nor TECHNOLOGY is given",
        ));
    }
    Ok(Ccss {
        description: kw("DESCRIPTOR").unwrap_or_default(),
        display: kw("DISPLAY"),
        technology: kw("TECHNOLOGY").unwrap_or_default(),
        refresh: t
            .keyword("DISPLAY_TYPE_REFRESH")
            .is_some_and(|v| v.eq_ignore_ascii_case("YES")),
        reference: kw("REFERENCE"),
        created: kw("CREATED"),
        samples,
    })
}
