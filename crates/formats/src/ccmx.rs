//! ArgyllCMS colorimeter correction matrices (`.ccmx`): the 3×3 matrix that turns one
//! colorimeter's XYZ on one display into a reference spectrometer's.
//!
//! The format is ArgyllCMS's (xicc/ccmx.c, `create_ccmx_cgats` / `read_ccmx_cgats`): a CGATS
//! file of type `CCMX` with one table; keywords `DESCRIPTOR`, `INSTRUMENT` (required),
//! `DISPLAY` and/or `TECHNOLOGY` (one is required), `DISPLAY_TYPE_BASE_ID`,
//! `DISPLAY_TYPE_REFRESH`, `REFERENCE`, `ORIGINATOR`, `CREATED`, `COLOR_REP "XYZ"`
//! (required); fields `XYZ_X XYZ_Y XYZ_Z` and exactly three rows, the matrix's rows:
//! `XYZ_ref = M · XYZ_colorimeter`.

use crate::cgats::{bad, number, parse};
use crate::{Error, Result};

/// A `.ccmx`.
#[derive(Clone, Debug, PartialEq)]
pub struct Ccmx {
    /// `DESCRIPTOR`.
    pub description: String,
    /// `INSTRUMENT`: the colorimeter.
    pub instrument: String,
    /// `DISPLAY`, if given.
    pub display: Option<String>,
    /// `TECHNOLOGY`: ArgyllCMS's display technology name.
    pub technology: String,
    /// `DISPLAY_TYPE_BASE_ID`: the colorimeter's calibration the readings were taken in.
    pub base_id: Option<u32>,
    /// `DISPLAY_TYPE_REFRESH`.
    pub refresh: Option<bool>,
    /// `REFERENCE`: the spectrometer.
    pub reference: Option<String>,
    /// `CREATED`, if known.
    pub created: Option<String>,
    /// The matrix, by rows.
    pub matrix: [[f64; 3]; 3],
}

fn quoted(v: &str) -> String {
    crate::escape::one_line(&v.replace('"', "'")).into_owned()
}

/// The `.ccmx` text; refused (nothing returned) for a matrix entry that is not finite or an
/// empty instrument or technology.
pub fn write(c: &Ccmx) -> Result<String> {
    use std::fmt::Write;
    if let Some(v) = c.matrix.iter().flatten().find(|v| !v.is_finite()) {
        return Err(Error::SpectralWrite {
            kind: ".ccmx",
            why: format!("the matrix has the non-finite entry {v}"),
        });
    }
    for (what, v) in [("instrument", &c.instrument), ("technology", &c.technology)] {
        if v.trim().is_empty() {
            return Err(Error::SpectralWrite {
                kind: ".ccmx",
                why: format!("no {what}"),
            });
        }
    }
    let mut s = String::from("CCMX   \n\n");
    let _ = writeln!(s, "DESCRIPTOR \"{}\"", quoted(&c.description));
    let _ = writeln!(s, "INSTRUMENT \"{}\"", quoted(&c.instrument));
    if let Some(d) = &c.display {
        let _ = writeln!(s, "DISPLAY \"{}\"", quoted(d));
    }
    let _ = writeln!(s, "TECHNOLOGY \"{}\"", quoted(&c.technology));
    if let Some(id) = c.base_id {
        let _ = writeln!(s, "DISPLAY_TYPE_BASE_ID \"{id}\"");
    }
    if let Some(r) = c.refresh {
        let _ = writeln!(
            s,
            "DISPLAY_TYPE_REFRESH \"{}\"",
            if r { "YES" } else { "NO" }
        );
    }
    if let Some(r) = &c.reference {
        let _ = writeln!(s, "REFERENCE \"{}\"", quoted(r));
    }
    let _ = writeln!(s, "ORIGINATOR \"specpoly\"");
    if let Some(t) = &c.created {
        let _ = writeln!(s, "CREATED \"{}\"", quoted(t));
    }
    let _ = writeln!(s, "COLOR_REP \"XYZ\"");
    let _ = writeln!(
        s,
        "\nNUMBER_OF_FIELDS 3\nBEGIN_DATA_FORMAT\nXYZ_X XYZ_Y XYZ_Z\nEND_DATA_FORMAT\n"
    );
    let _ = writeln!(s, "NUMBER_OF_SETS 3\nBEGIN_DATA");
    for r in &c.matrix {
        let _ = writeln!(s, "{:.6} {:.6} {:.6}", r[0], r[1], r[2]);
    }
    s.push_str("END_DATA\n");
    Ok(s)
}

/// Reads a `.ccmx`; one-line errors (`FILE:LINE: …`).
pub fn read(text: &str, source: &str) -> Result<Ccmx> {
    let tables = parse(text, source)?;
    let t = &tables[0];
    if t.kind != "CCMX" {
        return Err(bad(
            source,
            t.lines.identifier,
            format!("a `{}` file, not a CCMX", t.kind),
        ));
    }
    if t.keyword("COLOR_REP") != Some("XYZ") {
        return Err(bad(source, t.lines.identifier, "COLOR_REP is not \"XYZ\""));
    }
    let kw = |k: &str| t.keyword(k).map(str::to_string);
    let instrument =
        kw("INSTRUMENT").ok_or_else(|| bad(source, t.lines.identifier, "no INSTRUMENT keyword"))?;
    if kw("DISPLAY").is_none() && kw("TECHNOLOGY").is_none() {
        return Err(bad(
            source,
            t.lines.identifier,
            "neither DISPLAY nor TECHNOLOGY is given",
        ));
    }
    const F: [&str; 3] = ["XYZ_X", "XYZ_Y", "XYZ_Z"];
    let cols: Vec<usize> = F
        .iter()
        .map(|f| {
            t.field(f)
                .ok_or_else(|| bad(source, t.lines.format, format!("no field {f}")))
        })
        .collect::<Result<_>>()?;
    if t.rows.len() != 3 {
        return Err(bad(
            source,
            t.lines.end_data,
            format!("{} rows (a .ccmx has 3: the matrix's rows)", t.rows.len()),
        ));
    }
    let mut matrix = [[0.0; 3]; 3];
    for (r, (line, row)) in t.rows.iter().enumerate() {
        for k in 0..3 {
            matrix[r][k] = number(&row[cols[k]], source, *line, F[k])?;
        }
    }
    let base_id = match t.keyword("DISPLAY_TYPE_BASE_ID") {
        None => None,
        Some(v) => Some(v.trim().parse::<u32>().map_err(|_| {
            bad(
                source,
                t.keyword_line("DISPLAY_TYPE_BASE_ID"),
                format!("DISPLAY_TYPE_BASE_ID `{v}` is not a whole number"),
            )
        })?),
    };
    Ok(Ccmx {
        description: kw("DESCRIPTOR").unwrap_or_default(),
        instrument,
        display: kw("DISPLAY"),
        technology: kw("TECHNOLOGY").unwrap_or_default(),
        base_id,
        refresh: t
            .keyword("DISPLAY_TYPE_REFRESH")
            .map(|v| v.eq_ignore_ascii_case("YES")),
        reference: kw("REFERENCE"),
        created: kw("CREATED"),
        matrix,
    })
}
