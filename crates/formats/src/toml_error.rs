//! TOML errors on one line: `FILE:LINE:COLUMN: message`, as compilers write them. The `toml`
//! crate's own `Display` spreads an error over several lines (a source excerpt with a caret);
//! every TOML file the CLI reads (scenes, display files, calibrations) reports through
//! [`error`] ([`crate::Error::Toml`]) or [`one_line`] instead.

use crate::Error;

/// `source:line:column: message` for an error in `text` (the file's contents); the message's
/// own lines are joined with `, `. Without a position (an error found after parsing, e.g. a
/// missing field): `source: message`. The text of [`error`].
pub fn one_line(e: &toml::de::Error, text: &str, source: &str) -> String {
    error(e, text, source).to_string()
}

/// The error [`Error::Toml`] for `e` in `text` (the file's contents), with its line and column
/// (1-based, the column in characters) when `e` has a position; the message's own lines are
/// joined with `, `.
pub fn error(e: &toml::de::Error, text: &str, source: &str) -> Error {
    let msg = e
        .message()
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join(", ");
    let (line, column) = match e.span() {
        Some(span) => {
            let at = span.start.min(text.len());
            // a span inside a multi-byte character would not be a char boundary
            let at = (0..=at)
                .rev()
                .find(|&i| text.is_char_boundary(i))
                .unwrap_or(0);
            let before = &text[..at];
            let line = before.matches('\n').count() + 1;
            let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
            (Some(line), Some(column))
        }
        None => (None, None),
    };
    Error::Toml {
        file: source.to_string(),
        line,
        column,
        message: msg,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn position_and_one_line() {
        let text = "a = 1\nb = [\n";
        let e = text.parse::<toml::Table>().unwrap_err();
        let s = one_line(&e, text, "f.toml");
        assert!(s.starts_with("f.toml:"), "{s}");
        assert!(!s.contains('\n'), "{s}");
        let text = "x = 1\ny = \"é\" z\n";
        let e = text.parse::<toml::Table>().unwrap_err();
        let s = one_line(&e, text, "g.toml");
        assert!(s.starts_with("g.toml:2:"), "{s}");
    }
}
