//! Observers named on a command line or in a file: the built-in CIE observers, the CIE 2006
//! physiological observer for an age and field size ([`crate::cie2006`]), and any CSV of three
//! spectral sensitivities (a camera's, a colorimeter's filters).
//!
//! ## `--observer` syntax ([`parse`])
//!
//! | value | observer |
//! |---|---|
//! | `1931` (`2`), `1964` (`10`) | CIE 1931 2°, CIE 1964 10° |
//! | `2015-2`, `2015-10` | CIE 2015 2°, 10° (CIE 170-2) |
//! | `cie2006:age=A,field=F` | CIE 170-1 for age A (20–80 years), field F (2–10°) |
//! | `FILE.csv` | three sensitivities read from the file ([`from_csv`]) |
//!
//! ## Sensitivity CSV rules ([`from_csv`])
//!
//! The project's spectral CSV (`wavelength_nm` then named columns, `specpoly_formats::csv`)
//! with exactly three columns, in the roles x̄ ȳ z̄ (the second sets the white's `Y = 100`).
//! Refused, with one line naming the file (and line/column where there is one): a missing or
//! non-numeric cell, a negative value, wavelengths not strictly increasing, data not covering
//! 400–700 nm, a column that is zero everywhere. Between samples the table is interpolated
//! linearly; outside the data it is zero (a sensitivity is not extended as a reflectance is).

use crate::{Error, Result};
use specpoly_core::{observer::CMF_LEN, CmfTable, Observer, Tabulated};
use std::path::Path;
use std::sync::Mutex;

/// The range a sensitivity table must cover, nm.
pub const REQUIRED_NM: (f32, f32) = (400.0, 700.0);

/// Keeps `table` for the rest of the process and returns it as an [`Observer`].
///
/// The core's `Observer` is `Copy` and borrows a runtime table for `'static`; a process makes
/// a handful (one per `--observer`), so each distinct table is kept once: asking again for an
/// equal table returns the one already kept (memory is bounded by the distinct tables asked).
pub fn intern(table: CmfTable) -> Observer {
    static KEPT: Mutex<Vec<&'static CmfTable>> = Mutex::new(Vec::new());
    let mut kept = KEPT.lock().unwrap_or_else(|p| p.into_inner());
    if let Some(t) = kept.iter().find(|t| ***t == table) {
        return Observer::Table(t);
    }
    let t: &'static CmfTable = Box::leak(Box::new(table));
    kept.push(t);
    Observer::Table(t)
}

/// Parses an observer: a built-in name, `cie2006:age=A,field=F`, or a CSV file (see the module
/// docs). A value that is none of these is [`Error::UnknownObserver`].
pub fn parse(spec: &str) -> Result<Observer> {
    if let Some(o) = Observer::from_name(spec) {
        return Ok(o);
    }
    if let Some(params) = spec
        .strip_prefix("cie2006:")
        .or_else(|| spec.strip_prefix("CIE2006:"))
    {
        let (age, field) = crate::cie2006::parse_params(spec, params)?;
        return Ok(intern(crate::cie2006::table(age, field)?));
    }
    let path = Path::new(spec);
    if path.is_file() {
        return Ok(intern(from_csv(path)?));
    }
    Err(Error::UnknownObserver(spec.to_string()))
}

/// Reads three sensitivities from a CSV file onto the 1 nm grid (see the module docs).
pub fn from_csv(path: &Path) -> Result<CmfTable> {
    let text = specpoly_formats::read::text_or_latin1(path)?;
    from_csv_text(&text, &path.display().to_string())
}

/// [`from_csv`] of text already read; `source` names it in messages.
pub fn from_csv_text(text: &str, source: &str) -> Result<CmfTable> {
    let bad = |why: String| Error::BadObserver {
        name: source.to_string(),
        why,
    };
    let t = specpoly_formats::csv::parse(text, source)?;
    if t.columns.len() != 3 {
        return Err(bad(format!(
            "{} sensitivity columns; an observer has 3 (x̄ ȳ z̄, or a camera's R G B)",
            t.columns.len()
        )));
    }
    let (lo, hi) = (t.wavelengths[0], t.wavelengths[t.wavelengths.len() - 1]);
    if lo > REQUIRED_NM.0 || hi < REQUIRED_NM.1 {
        return Err(bad(format!(
            "data cover {lo}-{hi} nm; an observer needs at least {}-{} nm",
            REQUIRED_NM.0, REQUIRED_NM.1
        )));
    }
    let mut values = [[0.0f32; 3]; CMF_LEN];
    for (k, (name, col)) in t.columns.iter().enumerate() {
        if let Some(i) = col.iter().position(|v| *v < 0.0) {
            return Err(bad(format!(
                "negative sensitivity {} in column `{name}` at {} nm",
                col[i], t.wavelengths[i]
            )));
        }
        let tab = Tabulated::new(&t.wavelengths, col).map_err(|e| bad(e.to_string()))?;
        for (i, v) in values.iter_mut().enumerate() {
            let nm = 380.0 + i as f64;
            if nm >= lo as f64 && nm <= hi as f64 {
                v[k] = tab.at(nm) as f32;
            }
        }
    }
    let name = format!("file:{source}");
    CmfTable::new(&name, values).map_err(|e| match e {
        specpoly_core::Error::ZeroChannel(k) => bad(format!(
            "column `{}` is zero everywhere in 380-780 nm",
            t.columns[k].0
        )),
        e => bad(e.to_string()),
    })
}
