//! The `wrote FILE` line every command prints on stderr for each file it writes, made in one
//! place: the file name on one line with its control characters escaped
//! ([`specpoly_formats::escape::one_line`]: a name holding an OSC or CSI sequence cannot
//! retitle, recolour or clear the terminal, nor forge a line), and `-` shown as `stdout`.

use std::path::Path;

/// `wrote NAME{detail}`.
pub fn line(path: &Path, detail: &str) -> String {
    let name = if path == Path::new("-") {
        "stdout".to_string()
    } else {
        specpoly_formats::escape::one_line(&path.display().to_string()).into_owned()
    };
    format!("wrote {name}{detail}")
}

/// Prints [`line`] on stderr.
pub fn wrote(path: &Path, detail: &str) {
    eprintln!("{}", line(path, detail));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_one_line_and_escaped() {
        assert_eq!(
            line(Path::new("a\u{1b}]0;x\u{7}\nb.png"), " (2 bytes)"),
            "wrote a\\u{1b}]0;x\\u{7}\\nb.png (2 bytes)"
        );
        assert_eq!(line(Path::new("-"), ""), "wrote stdout");
        assert_eq!(line(Path::new("Grün.svg"), ""), "wrote Grün.svg");
    }
}
