//! User data on a terminal: a name or file content that reaches stdout or stderr has its control
//! characters (ESC, CR, BEL, …) written as escapes (`\u{1b}`), so a CSV column name cannot move
//! the cursor, recolour the terminal or forge a line of output.

use std::borrow::Cow;

/// `s` with every control character except newline and tab escaped (`\u{1b}`); `s` itself when
/// it has none.
pub fn control(s: &str) -> Cow<'_, str> {
    escape_if(s, |c| c.is_control() && c != '\n' && c != '\t')
}

/// `s` on one line: every control character escaped, newlines and tabs included.
pub fn one_line(s: &str) -> Cow<'_, str> {
    escape_if(s, char::is_control)
}

/// `s` for HTML, SVG and XML text and attribute values: `& < > " '` as character references,
/// and every control character but the newline written visibly as an escape (`\u{1b}`): XML
/// 1.0 cannot hold those, not even as character references, so the page stays well-formed.
pub fn markup(s: &str) -> String {
    let mut o = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => o.push_str("&#38;"),
            '<' => o.push_str("&#60;"),
            '>' => o.push_str("&#62;"),
            '"' => o.push_str("&#34;"),
            '\'' => o.push_str("&#39;"),
            c if c.is_control() && c != '\n' => o.extend(c.escape_default()),
            c => o.push(c),
        }
    }
    o
}

fn escape_if(s: &str, bad: impl Fn(char) -> bool) -> Cow<'_, str> {
    if !s.chars().any(&bad) {
        return Cow::Borrowed(s);
    }
    let mut out = String::with_capacity(s.len() + 8);
    for c in s.chars() {
        if bad(c) {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    Cow::Owned(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escapes_control_characters_only() {
        assert_eq!(control("red"), "red");
        assert_eq!(control("a\u{1b}[31mb\n"), "a\\u{1b}[31mb\n");
        assert_eq!(one_line("a\r\nb\u{7}"), "a\\r\\nb\\u{7}");
        assert_eq!(one_line("Grün"), "Grün");
    }
}
