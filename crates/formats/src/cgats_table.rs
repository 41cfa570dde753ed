//! The CGATS text format itself (ANSI CGATS.17) as ArgyllCMS writes it: tables of keywords,
//! a field list and rows ([`parse`] → [`Table`]), below what the tables mean (`.ti3`
//! measurements in [`crate::cgats`], spectral fields in [`crate::spectral`], `.ccss`, `.ccmx`).
//! See [`crate::cgats`] for the layout of a file.

use crate::{Error, Result};

/// One CGATS table.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Table {
    /// The identifier on the table's first line (`CTI3`, `CAL`, …).
    pub kind: String,
    /// Keywords in file order, values unquoted; `BEGIN_X`…`END_X` blocks appear as `X` with the
    /// block's lines joined by newlines.
    pub keywords: Vec<(String, String)>,
    /// The field names.
    pub fields: Vec<String>,
    /// The rows, each with one value per field, and the 1-based line each came from.
    pub rows: Vec<(usize, Vec<String>)>,
    /// The 1-based line of the identifier, of each keyword (parallel to `keywords`), of
    /// `BEGIN_DATA_FORMAT` and of `END_DATA`, for messages about what is missing or wrong there.
    pub lines: TableLines,
}

/// Where the parts of a [`Table`] are in its file (1-based lines; 0 = not seen).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TableLines {
    /// The identifier line.
    pub identifier: usize,
    /// One per keyword.
    pub keywords: Vec<usize>,
    /// `BEGIN_DATA_FORMAT`.
    pub format: usize,
    /// `END_DATA`.
    pub end_data: usize,
}

/// An error at the declaring line unless a declared count `(count, line)` matches `got`.
fn check_count(
    source: &str,
    declared: Option<(usize, usize)>,
    got: usize,
    message: impl Fn(usize, usize) -> String,
) -> Result<()> {
    match declared {
        Some((k, at)) if k != got => Err(bad(source, at, message(k, got))),
        _ => Ok(()),
    }
}

/// The value of keyword `name` in `(keyword, value)` pairs.
pub(crate) fn keyword<'a>(keywords: &'a [(String, String)], name: &str) -> Option<&'a str> {
    keywords
        .iter()
        .find(|(k, _)| k == name)
        .map(|(_, v)| v.as_str())
}

impl Table {
    /// The value of a keyword.
    pub fn keyword(&self, name: &str) -> Option<&str> {
        keyword(&self.keywords, name)
    }

    /// The column of a field.
    pub fn field(&self, name: &str) -> Option<usize> {
        self.fields.iter().position(|f| f == name)
    }

    /// The line of keyword `name` (else the identifier's line).
    pub fn keyword_line(&self, name: &str) -> usize {
        self.keywords
            .iter()
            .position(|(k, _)| k == name)
            .and_then(|i| self.lines.keywords.get(i).copied())
            .unwrap_or(self.lines.identifier)
    }
}

/// Splits a line into whitespace-separated tokens, keeping `"quoted strings"` whole (unquoted).
fn tokens(line: &str, source: &str, n: usize) -> Result<Vec<String>> {
    let mut out = Vec::new();
    let mut chars = line.chars().peekable();
    loop {
        while chars.peek().is_some_and(|c| c.is_whitespace()) {
            chars.next();
        }
        let Some(&c) = chars.peek() else { break };
        if c == '#' {
            break;
        }
        let mut t = String::new();
        if c == '"' {
            chars.next();
            let mut closed = false;
            for c in chars.by_ref() {
                if c == '"' {
                    closed = true;
                    break;
                }
                t.push(c);
            }
            if !closed {
                return Err(bad(source, n, "unterminated quoted string"));
            }
        } else {
            while let Some(&c) = chars.peek() {
                if c.is_whitespace() {
                    break;
                }
                t.push(c);
                chars.next();
            }
        }
        out.push(t);
    }
    Ok(out)
}

/// [`Error::Cgats`] at `source:line`.
pub(crate) fn bad(source: &str, line: usize, why: impl Into<String>) -> Error {
    Error::Cgats {
        file: source.to_string(),
        line: Some(line),
        why: why.into(),
    }
}

fn count(v: &str, source: &str, n: usize, what: &str) -> Result<usize> {
    v.parse::<usize>()
        .map_err(|_| bad(source, n, format!("{what} `{v}` is not a whole number")))
}

/// Parses every table of a CGATS file. `source` names the file in error messages, which are
/// one line: `source:LINE: what is wrong`.
pub fn parse(text: &str, source: &str) -> Result<Vec<Table>> {
    #[derive(PartialEq)]
    enum State {
        Identifier,
        Header,
        Block(String),
        Format,
        Data,
    }
    let mut tables = Vec::new();
    let mut t = Table::default();
    let mut state = State::Identifier;
    let mut block = String::new();
    let mut n_fields: Option<(usize, usize)> = None;
    let mut n_sets: Option<(usize, usize)> = None;
    let mut last = 0;
    for (i, raw) in text.lines().enumerate() {
        let n = i + 1;
        last = n;
        if let State::Block(name) = &state {
            if raw.trim() == format!("END_{name}") {
                t.keywords.push((name.clone(), std::mem::take(&mut block)));
                t.lines.keywords.push(n);
                state = State::Header;
            } else {
                if !block.is_empty() {
                    block.push('\n');
                }
                block.push_str(raw.trim_end());
            }
            continue;
        }
        let tok = tokens(raw, source, n)?;
        if tok.is_empty() {
            continue;
        }
        match state {
            State::Identifier => {
                if tok.len() != 1 || tok[0].starts_with("BEGIN_") || tok[0].starts_with("END_") {
                    return Err(bad(
                        source,
                        n,
                        format!(
                            "expected a table identifier such as CTI3, found `{}`",
                            raw.trim()
                        ),
                    ));
                }
                t.kind = tok[0].clone();
                t.lines.identifier = n;
                state = State::Header;
            }
            State::Header => match tok[0].as_str() {
                "NUMBER_OF_FIELDS" => {
                    let v = tok
                        .get(1)
                        .ok_or_else(|| bad(source, n, "NUMBER_OF_FIELDS without a value"))?;
                    n_fields = Some((count(v, source, n, "NUMBER_OF_FIELDS")?, n));
                }
                "NUMBER_OF_SETS" => {
                    let v = tok
                        .get(1)
                        .ok_or_else(|| bad(source, n, "NUMBER_OF_SETS without a value"))?;
                    n_sets = Some((count(v, source, n, "NUMBER_OF_SETS")?, n));
                }
                "BEGIN_DATA_FORMAT" => {
                    if !t.fields.is_empty() {
                        return Err(bad(source, n, "a second BEGIN_DATA_FORMAT in one table"));
                    }
                    t.lines.format = n;
                    state = State::Format;
                }
                "BEGIN_DATA" => {
                    if t.fields.is_empty() {
                        return Err(bad(source, n, "BEGIN_DATA before BEGIN_DATA_FORMAT"));
                    }
                    check_count(source, n_fields, t.fields.len(), |k, got| {
                        format!("NUMBER_OF_FIELDS is {k} but the data format names {got} fields")
                    })?;
                    state = State::Data;
                }
                "END_DATA" | "END_DATA_FORMAT" => {
                    return Err(bad(source, n, format!("{} without its BEGIN", tok[0])));
                }
                k if k.starts_with("BEGIN_") && tok.len() == 1 => {
                    state = State::Block(k["BEGIN_".len()..].to_string());
                }
                _ => {
                    let value = tok[1..].join(" ");
                    t.keywords.push((tok[0].clone(), value));
                    t.lines.keywords.push(n);
                }
            },
            State::Format => {
                if tok[0] == "END_DATA_FORMAT" {
                    if t.fields.is_empty() {
                        return Err(bad(source, n, "empty data format"));
                    }
                    state = State::Header;
                } else {
                    t.fields.extend(tok);
                }
            }
            State::Data => {
                if tok[0] == "END_DATA" && tok.len() == 1 {
                    check_count(source, n_sets, t.rows.len(), |k, got| {
                        format!("NUMBER_OF_SETS is {k} but BEGIN_DATA…END_DATA holds {got} rows")
                    })?;
                    t.lines.end_data = n;
                    tables.push(std::mem::take(&mut t));
                    n_fields = None;
                    n_sets = None;
                    state = State::Identifier;
                } else {
                    if tok.len() != t.fields.len() {
                        return Err(bad(
                            source,
                            n,
                            format!(
                                "expected {} values ({}), found {}",
                                t.fields.len(),
                                t.fields.join(" "),
                                tok.len()
                            ),
                        ));
                    }
                    t.rows.push((n, tok));
                }
            }
            State::Block(_) => unreachable!("handled above"),
        }
    }
    match state {
        State::Identifier if !tables.is_empty() => Ok(tables),
        State::Identifier => Err(bad(source, last.max(1), "empty file: no CGATS table")),
        State::Header => Err(bad(
            source,
            last.max(1),
            "no BEGIN_DATA: the table has no data",
        )),
        State::Block(name) => Err(bad(
            source,
            last,
            format!("BEGIN_{name} without END_{name}"),
        )),
        State::Format => Err(bad(
            source,
            last,
            "BEGIN_DATA_FORMAT without END_DATA_FORMAT",
        )),
        State::Data => Err(bad(source, last, "BEGIN_DATA without END_DATA")),
    }
}

pub(crate) fn number(v: &str, source: &str, line: usize, field: &str) -> Result<f64> {
    match v.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(Error::CgatsNumber {
            file: source.to_string(),
            line,
            field: field.to_string(),
            value: v.to_string(),
            range: None,
        }),
    }
}
