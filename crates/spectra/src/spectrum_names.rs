//! Naming spectra on the command line: `FILE` (a CSV with one spectrum column), `FILE#COLUMN`,
//! `FILE#*` (every column), or the same with a built-in table (`colorchecker#red`) or a
//! built-in illuminant (`D65`). A file on disk wins over a built-in of the same name.

use crate::data::TABLES;
use crate::{Error, Result};
use specpoly_core::{Illuminant, Tabulated};
use specpoly_formats::csv::{self, Table};

/// A named spectrum with validated samples.
#[derive(Clone, Debug, PartialEq)]
pub struct Named {
    /// `SOURCE#COLUMN` or the illuminant's name.
    pub name: String,
    /// Wavelengths (nm), strictly increasing.
    pub wavelengths: Vec<f32>,
    /// Values.
    pub values: Vec<f32>,
}

impl Named {
    /// Checks the samples and builds a named spectrum.
    pub fn new(name: String, wavelengths: Vec<f32>, values: Vec<f32>) -> Result<Self> {
        if let Err(source) = Tabulated::new(&wavelengths, &values) {
            return Err(Error::Samples { name, source });
        }
        Ok(Self {
            name,
            wavelengths,
            values,
        })
    }

    /// The samples as core [`Tabulated`] data.
    pub fn tabulated(&self) -> Tabulated<'_> {
        match Tabulated::new(&self.wavelengths, &self.values) {
            Ok(t) => t,
            // `Named` is only built through `new`, which validated the same slices.
            Err(_) => unreachable!("validated in Named::new"),
        }
    }

    /// The short name (the column, without the file).
    pub fn short(&self) -> &str {
        self.name.rsplit('#').next().unwrap_or(&self.name)
    }
}

/// Loads a table from a file path, or a built-in table by name.
pub fn load_table(base: &str) -> Result<(String, Table)> {
    let path = std::path::Path::new(base);
    if path.exists() {
        let text = specpoly_formats::read::text_or_latin1(path)?;
        return Ok((base.to_string(), csv::parse(&text, base)?));
    }
    if let Some(t) = TABLES.iter().find(|t| t.name.eq_ignore_ascii_case(base)) {
        return Ok((t.name.to_string(), csv::parse(t.text, t.name)?));
    }
    Err(Error::UnknownTable {
        name: base.to_string(),
        builtins: builtin_names(),
    })
}

/// Names of the built-ins, for error messages.
pub fn builtin_names() -> String {
    let mut v: Vec<&str> = TABLES.iter().map(|t| t.name).collect();
    v.extend(Illuminant::ALL.iter().map(|i| i.name()));
    v.join(", ")
}

fn illuminant(name: &str) -> Option<Named> {
    let i = Illuminant::from_name(name)?;
    let t = i.tabulated();
    Some(Named {
        name: i.name().to_string(),
        wavelengths: t.wavelengths().to_vec(),
        values: t.values().to_vec(),
    })
}

/// Resolves one command-line spectrum name to one or more spectra (`FILE#*` gives all).
pub fn resolve(spec: &str) -> Result<Vec<Named>> {
    let (base, column) = match spec.split_once('#') {
        Some((b, c)) => (b, Some(c)),
        None => (spec, None),
    };
    if column.is_none() && !std::path::Path::new(base).exists() {
        if let Some(n) = illuminant(base) {
            return Ok(vec![n]);
        }
    }
    let (source, table) = load_table(base)?;
    let make = |(name, values): &(String, Vec<f32>)| {
        Named::new(
            format!("{source}#{name}"),
            table.wavelengths.clone(),
            values.clone(),
        )
    };
    match column {
        None if table.columns.len() == 1 => Ok(vec![make(&table.columns[0])?]),
        None => Err(Error::ColumnNeeded {
            spec: spec.to_string(),
            count: table.columns.len(),
            columns: column_list(&table),
        }),
        Some("*") => table.columns.iter().map(make).collect(),
        Some(c) => {
            let col = table
                .columns
                .iter()
                .find(|(n, _)| n == c)
                .or_else(|| {
                    table
                        .columns
                        .iter()
                        .find(|(n, _)| n.eq_ignore_ascii_case(c))
                })
                .or_else(|| unique_word_prefix(&table, c))
                .ok_or_else(|| Error::UnknownColumn {
                    table: source.clone(),
                    column: c.to_string(),
                    columns: column_list(&table),
                })?;
            Ok(vec![make(col)?])
        }
    }
}

/// The one column whose name starts with `c` followed by a space (case-insensitive), so
/// `colorchecker#white` names `white 9.5 (.05 D)`; `None` when none or several match.
fn unique_word_prefix<'t>(t: &'t Table, c: &str) -> Option<&'t (String, Vec<f32>)> {
    let c = c.to_ascii_lowercase();
    let mut hits = t.columns.iter().filter(|(n, _)| {
        let n = n.to_ascii_lowercase();
        n.strip_prefix(&c).is_some_and(|rest| rest.starts_with(' '))
    });
    let first = hits.next()?;
    hits.next().is_none().then_some(first)
}

fn column_list(t: &Table) -> String {
    t.columns
        .iter()
        .map(|(n, _)| n.as_str())
        .collect::<Vec<_>>()
        .join(", ")
}

/// Resolves many names, in order.
pub fn resolve_all<S: AsRef<str>>(specs: &[S]) -> Result<Vec<Named>> {
    let mut out = Vec::new();
    for s in specs {
        out.extend(resolve(s.as_ref())?);
    }
    Ok(out)
}

/// Resolves lights: `FILE#*` is every column of the file, anything else one light ([`light`]).
pub fn lights(spec: &str) -> Result<Vec<Named>> {
    if spec.ends_with("#*") {
        resolve(spec)
    } else {
        Ok(vec![light(spec)?])
    }
}

/// Resolves a light: a built-in illuminant name, or a file / `FILE#COLUMN` with one spectrum.
pub fn light(spec: &str) -> Result<Named> {
    if let Some(n) = illuminant(spec) {
        if !std::path::Path::new(spec).exists() {
            return Ok(n);
        }
    }
    let mut v = resolve(spec).map_err(|e| match e {
        Error::UnknownTable { .. }
        | Error::ColumnNeeded { .. }
        | Error::UnknownColumn { .. }
        | Error::Formats(specpoly_formats::Error::Missing { .. }) => {
            Error::UnknownLight(Box::new(e))
        }
        other => other,
    })?;
    if v.len() != 1 {
        return Err(Error::NotOneLight {
            spec: spec.to_string(),
            count: v.len(),
        });
    }
    Ok(v.remove(0))
}
