//! Spectral CSV: a header row whose first cell names the wavelength column (`wavelength_nm`),
//! then one named spectrum per further column (colour-science's convention). Every malformed
//! input is rejected with the file, line and column in one message.
//!
//! Hand-written (≈100 lines) rather than the `csv` crate: the format is plain numbers and the
//! validation (finite, strictly increasing wavelengths, the 380–780 nm domain) is the real work.

use crate::error::{CliError, Result};

/// A parsed spectral table.
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    /// Wavelengths (nm), strictly increasing.
    pub wavelengths: Vec<f32>,
    /// `(name, values)` per spectrum column.
    pub columns: Vec<(String, Vec<f32>)>,
}

/// Parses spectral CSV text; `source` names the input in error messages.
pub fn parse(text: &str, source: &str) -> Result<Table> {
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
    let (hline, header) = lines
        .next()
        .ok_or_else(|| CliError::data(format!("{source}: empty file")))?;
    let names: Vec<String> = header.split(',').map(|c| c.trim().to_string()).collect();
    if names[0].parse::<f64>().is_ok() {
        return Err(CliError::data(format!(
            "{source}:{}: no header row (expected `wavelength_nm,NAME,...`)",
            hline + 1
        )));
    }
    if names.len() < 2 {
        return Err(CliError::data(format!(
            "{source}:{}: no spectrum columns after `{}`",
            hline + 1,
            names[0]
        )));
    }
    for (i, n) in names.iter().enumerate().skip(1) {
        if n.is_empty() {
            return Err(CliError::data(format!(
                "{source}:{}: column {} has an empty name",
                hline + 1,
                i + 1
            )));
        }
    }
    let mut wavelengths = Vec::new();
    let mut values: Vec<Vec<f32>> = vec![Vec::new(); names.len() - 1];
    for (ln, line) in lines {
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        if cells.len() != names.len() {
            return Err(CliError::data(format!(
                "{source}:{}: {} cells, the header has {}",
                ln + 1,
                cells.len(),
                names.len()
            )));
        }
        for (c, cell) in cells.iter().enumerate() {
            let col = &names[c];
            if cell.is_empty() {
                return Err(CliError::data(format!(
                    "{source}:{}: empty cell in column `{col}`",
                    ln + 1
                )));
            }
            let v: f64 = cell.parse().map_err(|_| {
                CliError::data(format!(
                    "{source}:{}: `{cell}` in column `{col}` is not a number",
                    ln + 1
                ))
            })?;
            if !v.is_finite() {
                return Err(CliError::data(format!(
                    "{source}:{}: `{cell}` in column `{col}` is not finite",
                    ln + 1
                )));
            }
            if c == 0 {
                if let Some(prev) = wavelengths.last() {
                    if v as f32 <= *prev {
                        let what = if v as f32 == *prev {
                            "duplicate"
                        } else {
                            "decreasing"
                        };
                        return Err(CliError::data(format!(
                            "{source}:{}: {what} wavelength {v} nm (after {prev} nm)",
                            ln + 1
                        )));
                    }
                }
                wavelengths.push(v as f32);
            } else {
                values[c - 1].push(v as f32);
            }
        }
    }
    if wavelengths.is_empty() {
        return Err(CliError::data(format!("{source}: header but no data rows")));
    }
    let (first, last) = (wavelengths[0], wavelengths[wavelengths.len() - 1]);
    if last < specpoly_core::LAMBDA_MIN || first > specpoly_core::LAMBDA_MAX {
        return Err(CliError::data(format!(
            "{source}: data cover {first}-{last} nm, entirely outside 380-780 nm"
        )));
    }
    Ok(Table {
        wavelengths,
        columns: names.into_iter().skip(1).zip(values).collect(),
    })
}

/// Formats a table as spectral CSV.
pub fn format(t: &Table) -> String {
    let mut s = String::from("wavelength_nm");
    for (n, _) in &t.columns {
        s.push(',');
        s.push_str(n);
    }
    s.push('\n');
    for (i, w) in t.wavelengths.iter().enumerate() {
        s.push_str(&format!("{w}"));
        for (_, v) in &t.columns {
            s.push_str(&format!(",{}", v[i]));
        }
        s.push('\n');
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> String {
        parse(text, "t.csv").unwrap_err().to_string()
    }

    #[test]
    fn parses_and_rejects() {
        let t = parse("wavelength_nm,a,b\n400,0.1,0.2\n410,0.3,0.4\n", "t.csv").unwrap();
        assert_eq!(t.wavelengths, vec![400.0, 410.0]);
        assert_eq!(t.columns[1], ("b".into(), vec![0.2, 0.4]));
        assert!(err("400,0.1\n").contains("no header"));
        assert!(err("wavelength_nm,a\n400,x\n").contains("not a number"));
        assert!(err("wavelength_nm,a\n400,NaN\n").contains("not finite"));
        assert!(err("wavelength_nm,a\n400,1\n400,1\n").contains("duplicate"));
        assert!(err("wavelength_nm,a\n400,1\n390,1\n").contains("decreasing"));
        assert!(err("wavelength_nm,a\n400,\n").contains("empty cell"));
        assert!(err("wavelength_nm,a\n900,1\n910,1\n").contains("outside 380-780"));
        assert!(err("wavelength_nm,a\n").contains("no data rows"));
        assert!(err("wavelength_nm,a\n400,1,2\n").contains("3 cells"));
    }
}
