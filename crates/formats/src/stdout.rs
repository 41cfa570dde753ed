//! Printing a command's whole output at once (text, or `--json`), with control characters from
//! user data escaped ([`crate::escape::control`]). A closed pipe (`specpoly … | head`) is not an
//! error: the reader has what it wanted, so the command ends quietly instead of panicking.

use crate::{Error, Result};
use std::io::Write;

/// Writes `text` to stdout; a broken pipe counts as success.
pub fn print(text: &str) -> Result<()> {
    let text = crate::escape::control(text);
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(Error::io("stdout", e)),
        _ => Ok(()),
    }
}

/// Writes `value` as pretty JSON and a newline to stdout (`--json`).
pub fn print_json<T: serde::Serialize + ?Sized>(value: &T) -> Result<()> {
    let s = serde_json::to_string_pretty(value).map_err(Error::Json)?;
    print(&format!("{s}\n"))
}

/// Values separated by spaces (`0.5 0.25 1`), as messages show a triple: never Rust's `Debug`
/// form (`[0.5, 0.25, 1.0]`).
pub fn values<T: std::fmt::Display>(v: &[T]) -> String {
    v.iter().map(T::to_string).collect::<Vec<_>>().join(" ")
}
