//! Spectral CSV: a header row whose first cell names the wavelength column (`wavelength_nm`),
//! then one named spectrum per further column (colour-science's convention). Every malformed
//! input is rejected with one message naming `file:line:column` (column = the 1-based cell of
//! the row, as a spreadsheet counts them).
//!
//! The records come from the `csv` crate (RFC 4180: quoted cells, `""` inside quotes, CRLF);
//! the validation (finite values, strictly increasing wavelengths, the 380–780 nm domain) is
//! ours. What spreadsheets write is read as they write it:
//!
//! - the separator is `,`, `;` or a tab, whichever occurs most often (outside quotes) in the
//!   header line (LibreOffice and Excel in German, French … locales write `;`);
//! - with `;` or tab as separator, a decimal comma is read as a point (`0,125` is 0.125); a
//!   cell with both `.` and `,` (a thousands separator) is refused;
//! - a UTF-8 byte-order mark is skipped; files that are not UTF-8 are read as Latin-1
//!   (ISO 8859-1), the encoding of older exports ([`crate::read::text_or_latin1`]);
//! - blank lines, lines of empty cells (`;;;`), empty trailing columns and lines starting with
//!   `#` are skipped.
//!
//! A table holds at most [`MAX_COLUMNS`] spectra and [`MAX_ROWS`] wavelengths; a larger one is
//! refused at the header or at the first row past the limit, before the rest is parsed (with the
//! input size limit of [`crate::read`] this bounds the time and memory any file can take).

use crate::{Error, Result};

/// The most spectrum columns a table may have (10 000): far more than any measured set (a
/// colour checker has 24 patches, CIE 224's samples are 99, the largest reflectance sets in use a
/// few thousand); a file of more is refused, not read.
pub const MAX_COLUMNS: usize = 10_000;

/// The most wavelength rows a table may have (100 000: 380–780 nm every 0.004 nm).
pub const MAX_ROWS: usize = 100_000;

/// A parsed spectral table.
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    /// Wavelengths (nm), strictly increasing.
    pub wavelengths: Vec<f32>,
    /// `(name, values)` per spectrum column.
    pub columns: Vec<(String, Vec<f32>)>,
}

/// The separator a header line uses: the most frequent of `,` `;` tab outside quotes (`,` on a
/// tie or when there is none).
pub fn separator(header: &str) -> u8 {
    let mut counts = [0usize; 3];
    let mut quoted = false;
    for b in header.bytes() {
        match b {
            b'"' => quoted = !quoted,
            b',' if !quoted => counts[0] += 1,
            b';' if !quoted => counts[1] += 1,
            b'\t' if !quoted => counts[2] += 1,
            _ => {}
        }
    }
    let seps = [b',', b';', b'\t'];
    let mut best = 0;
    for i in 1..3 {
        if counts[i] > counts[best] {
            best = i;
        }
    }
    seps[best]
}

/// A cell or name as a message shows it: one line (control characters escaped) and at most
/// 40 characters.
fn shown(s: &str) -> String {
    let one = crate::escape::one_line(s);
    if one.chars().count() > 40 {
        format!("{}…", one.chars().take(39).collect::<String>())
    } else {
        one.into_owned()
    }
}

/// [`Error::Csv`] at `source`, optionally at a line and a column.
fn bad(source: &str, line: Option<u64>, column: Option<usize>, why: String) -> Error {
    Error::Csv {
        file: source.to_string(),
        line,
        column,
        why,
    }
}

fn is_skipped(line: &str) -> bool {
    let t = line.trim();
    t.is_empty() || t.starts_with('#')
}

/// Parses spectral CSV text; `source` names the input in error messages.
pub fn parse(text: &str, source: &str) -> Result<Table> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let header_line = text.lines().find(|l| !is_skipped(l)).unwrap_or("");
    let sep = separator(header_line);
    let mut reader = ::csv::ReaderBuilder::new()
        .delimiter(sep)
        .has_headers(false)
        .flexible(true)
        .comment(Some(b'#'))
        .from_reader(text.as_bytes());
    let mut records = reader.records();
    let at = |line: u64, col: usize, why: String| bad(source, Some(line), Some(col), why);
    // The line where a record starts, counted forward from the last one asked (records come
    // in order). The `csv` crate's own position of a record after a CRLF is the `\n` of that
    // CRLF, one line early, so line ends at the offset are skipped first.
    let bytes = text.as_bytes();
    let mut counted = (0usize, 1u64);
    let mut line_of = move |byte: u64| -> u64 {
        let mut to = (byte as usize).min(bytes.len());
        while to < bytes.len() && (bytes[to] == b'\n' || bytes[to] == b'\r') {
            to += 1;
        }
        if to >= counted.0 {
            counted.1 += bytes[counted.0..to].iter().filter(|&&b| b == b'\n').count() as u64;
            counted.0 = to;
        }
        counted.1
    };
    let mut next =
        |records: &mut ::csv::StringRecordsIter<&[u8]>| -> Result<Option<(u64, Vec<String>)>> {
            for r in records.by_ref() {
                let r = match r {
                    Ok(r) => r,
                    Err(e) => {
                        let line = e.position().map_or(0, |p| line_of(p.byte()));
                        return Err(bad(source, Some(line), None, e.to_string()));
                    }
                };
                let line = r.position().map_or(0, |p| line_of(p.byte()));
                if r.iter().all(|c| c.trim().is_empty()) {
                    continue;
                }
                return Ok(Some((
                    line,
                    r.iter().map(|c| c.trim().to_string()).collect(),
                )));
            }
            Ok(None)
        };
    let (hline, mut names) =
        next(&mut records)?.ok_or_else(|| bad(source, None, None, "empty file".into()))?;
    // Spreadsheets export empty columns to the right of the data.
    while names.len() > 1 && names.last().is_some_and(String::is_empty) {
        names.pop();
    }
    if number(&names[0], sep).is_some() {
        return Err(at(
            hline,
            1,
            "no header row (expected `wavelength_nm,NAME,...`)".into(),
        ));
    }
    if names.len() < 2 {
        return Err(at(
            hline,
            1,
            format!(
                "no spectrum columns after `{}` (separator `{}`; `,`, `;` and tab are read)",
                shown(&names[0]),
                (sep as char).escape_default()
            ),
        ));
    }
    if names.len() - 1 > MAX_COLUMNS {
        return Err(at(
            hline,
            MAX_COLUMNS + 2,
            format!(
                "{} spectrum columns; a table holds at most {MAX_COLUMNS} (split it into files)",
                names.len() - 1
            ),
        ));
    }
    let mut seen = std::collections::HashMap::with_capacity(names.len());
    for (i, n) in names.iter().enumerate().skip(1) {
        if n.is_empty() {
            return Err(at(
                hline,
                i + 1,
                format!("column {} has an empty name", i + 1),
            ));
        }
        if let Some(j) = seen.insert(n.as_str(), i) {
            return Err(at(
                hline,
                i + 1,
                format!("column name `{}` repeats column {}", shown(n), j + 1),
            ));
        }
    }
    let mut wavelengths: Vec<f32> = Vec::new();
    let mut values: Vec<Vec<f32>> = vec![Vec::new(); names.len() - 1];
    while let Some((ln, mut cells)) = next(&mut records)? {
        if wavelengths.len() == MAX_ROWS {
            return Err(at(
                ln,
                1,
                format!("more than {MAX_ROWS} wavelength rows; a table holds at most {MAX_ROWS}"),
            ));
        }
        if cells.len() > names.len() && cells[names.len()..].iter().all(String::is_empty) {
            cells.truncate(names.len());
        }
        if cells.len() != names.len() {
            return Err(at(
                ln,
                cells.len().min(names.len()) + 1,
                format!("{} cells, the header has {}", cells.len(), names.len()),
            ));
        }
        for (c, cell) in cells.iter().enumerate() {
            let col = shown(&names[c]);
            let here = |why: String| at(ln, c + 1, why);
            if cell.is_empty() {
                return Err(here(format!("empty cell in column `{col}`")));
            }
            let v = number(cell, sep).ok_or_else(|| {
                here(format!(
                    "`{}` in column `{col}` is not a number",
                    shown(cell)
                ))
            })?;
            if !v.is_finite() {
                return Err(here(format!(
                    "`{}` in column `{col}` is not finite (or beyond ±3.4e38)",
                    shown(cell)
                )));
            }
            if c == 0 {
                if let Some(prev) = wavelengths.last() {
                    if v <= *prev {
                        let what = if v == *prev {
                            "duplicate"
                        } else {
                            "decreasing"
                        };
                        return Err(here(format!("{what} wavelength {v} nm (after {prev} nm)")));
                    }
                }
                wavelengths.push(v);
            } else {
                values[c - 1].push(v);
            }
        }
    }
    if wavelengths.is_empty() {
        return Err(bad(source, None, None, "header but no data rows".into()));
    }
    let (first, last) = (wavelengths[0], wavelengths[wavelengths.len() - 1]);
    if last < specpoly_core::LAMBDA_MIN || first > specpoly_core::LAMBDA_MAX {
        return Err(bad(
            source,
            None,
            None,
            format!("data cover {first}-{last} nm, entirely outside 380-780 nm"),
        ));
    }
    Ok(Table {
        wavelengths,
        columns: names.into_iter().skip(1).zip(values).collect(),
    })
}

/// A cell as a number (f32, read directly so that what [`format`] writes reads back exactly);
/// with a separator other than `,`, a decimal comma counts as a point.
fn number(cell: &str, sep: u8) -> Option<f32> {
    if sep != b',' && cell.contains(',') {
        if cell.contains('.') || cell.matches(',').count() > 1 {
            return None;
        }
        return cell.replace(',', ".").parse().ok();
    }
    cell.parse().ok()
}

/// Formats a table as spectral CSV (`,`-separated; names quoted where RFC 4180 needs it).
pub fn format(t: &Table) -> String {
    // Names quoted (numbers not), so `;` or tabs in a name never decide the separator.
    let mut w = ::csv::WriterBuilder::new()
        .quote_style(::csv::QuoteStyle::NonNumeric)
        .from_writer(Vec::new());
    let mut row: Vec<String> = vec!["wavelength_nm".into()];
    row.extend(t.columns.iter().map(|(n, _)| n.clone()));
    // Writing into a Vec cannot fail.
    let _ = w.write_record(&row);
    for (i, wl) in t.wavelengths.iter().enumerate() {
        row.clear();
        row.push(format!("{wl}"));
        row.extend(t.columns.iter().map(|(_, v)| format!("{}", v[i])));
        let _ = w.write_record(&row);
    }
    let bytes = w.into_inner().unwrap_or_default();
    String::from_utf8(bytes).unwrap_or_default()
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
        assert!(err("wavelength_nm,a\n400,x\n").contains("t.csv:2:2: `x`"));
        assert!(err("wavelength_nm,a\n400,NaN\n").contains("not finite"));
        assert!(err("wavelength_nm,a\n400,1e39\n").contains("not finite"));
        assert!(err("wavelength_nm,a\n400,1\n400,1\n").contains("t.csv:3:1: duplicate"));
        assert!(err("wavelength_nm,a\n400,1\n390,1\n").contains("decreasing"));
        assert!(err("wavelength_nm,a\n400,\n").contains("empty cell"));
        assert!(err("wavelength_nm,a\n900,1\n910,1\n").contains("outside 380-780"));
        assert!(err("wavelength_nm,a\n").contains("no data rows"));
        assert!(err("wavelength_nm,a\n400,1,2\n").contains("3 cells"));
        assert!(err("wavelength_nm,a,a\n400,1,2\n").contains("repeats column 2"));
    }

    #[test]
    fn formatted_tables_read_back() {
        let t = Table {
            wavelengths: vec![400.0, 500.5],
            columns: vec![
                ("red, \"matte\"".into(), vec![0.25, 1e-7]),
                ("grün".into(), vec![0.0, 1.0]),
            ],
        };
        assert_eq!(parse(&format(&t), "t.csv").unwrap(), t);
    }
}
