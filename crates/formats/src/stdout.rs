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

/// Whether stdout was closed when the process started (`specpoly … -o - >&-`). The Rust
/// runtime then puts `/dev/null` on descriptor 1, opened read-write, so whatever is written
/// there would vanish while the command says it succeeded. On Linux that state shows in
/// `/proc/self/fd/1` (→ `/dev/null`) and `/proc/self/fdinfo/1` (access mode `O_RDWR`); a
/// shell's `>/dev/null` opens it write-only, which is a stdout like any other. (A parent
/// that hands over `/dev/null` opened read-write, as `1<>/dev/null` does, looks the same.)
/// Elsewhere: `false`. Checked once per process.
pub fn closed_at_start() -> bool {
    static CLOSED: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *CLOSED.get_or_init(|| {
        let null = std::fs::read_link("/proc/self/fd/1")
            .is_ok_and(|p| p == std::path::Path::new("/dev/null"));
        null && std::fs::read_to_string("/proc/self/fdinfo/1").is_ok_and(|info| {
            info.lines()
                .find_map(|l| l.strip_prefix("flags:"))
                .and_then(|f| u32::from_str_radix(f.trim(), 8).ok())
                // O_ACCMODE = 3, O_RDWR = 2
                .is_some_and(|flags| flags & 3 == 2)
        })
    })
}

/// An error when stdout was closed at start ([`closed_at_start`]): for output that is the
/// command's product (`-o -`), which must not vanish with exit 0.
pub fn check_open() -> Result<()> {
    if closed_at_start() {
        return Err(Error::io(
            "stdout",
            std::io::Error::other("it is closed (`>&-`), so the output would be lost"),
        ));
    }
    Ok(())
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
