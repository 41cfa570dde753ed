//! Reading input files safely: only regular files (a path naming a device such as `/dev/zero`,
//! a FIFO or a directory is refused before it is opened, so nothing blocks or reads forever), and
//! at most [`max_input_bytes`] (by default [`MAX_INPUT_BYTES`]: the largest spectral table,
//! scene or measurement file we expect is a few megabytes; the limit bounds memory, it is not a
//! format rule). A program that reads larger inputs on purpose (a mesh of millions of
//! triangles) raises it once at start with [`set_max_input_bytes`] (the CLI's
//! `--max-input-size`).

use crate::{Error, Result};
use std::io::Read;
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};

/// The largest input file read by default (64 MiB).
pub const MAX_INPUT_BYTES: u64 = 64 << 20;

/// The process's input limit: one setting for every reader, as a process has one memory.
static LIMIT: AtomicU64 = AtomicU64::new(MAX_INPUT_BYTES);

/// The largest input file read now, bytes.
pub fn max_input_bytes() -> u64 {
    LIMIT.load(Ordering::Relaxed)
}

/// Sets the largest input file read, bytes (at least 1).
pub fn set_max_input_bytes(limit: u64) {
    LIMIT.store(limit.max(1), Ordering::Relaxed);
}

/// The bytes of the regular file `path`, at most [`max_input_bytes`].
/// A file that does not exist is [`Error::Missing`] (the CLI counts it a usage error, as in
/// every command).
pub fn bytes(path: &Path) -> Result<Vec<u8>> {
    let meta = std::fs::metadata(path).map_err(|e| match e.kind() {
        std::io::ErrorKind::NotFound => Error::missing(path),
        _ => Error::io(path, e),
    })?;
    if !meta.is_file() {
        return Err(Error::NotRegular {
            path: path.display().to_string(),
        });
    }
    let file = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
    let limit = max_input_bytes();
    if meta.len() > limit {
        return Err(Error::TooLarge {
            path: path.display().to_string(),
            limit,
        });
    }
    let mut buf = Vec::new();
    file.take(limit.saturating_add(1))
        .read_to_end(&mut buf)
        .map_err(|e| Error::io(path, e))?;
    if buf.len() as u64 > limit {
        return Err(Error::TooLarge {
            path: path.display().to_string(),
            limit,
        });
    }
    Ok(buf)
}

/// A byte count as people write it: `64 MiB`, `2 KiB`, `100 bytes` (the largest binary unit
/// that divides it).
pub fn size_text(bytes: u64) -> String {
    match bytes {
        b if b >= 1 << 30 && b % (1 << 30) == 0 => format!("{} GiB", b >> 30),
        b if b >= 1 << 20 && b % (1 << 20) == 0 => format!("{} MiB", b >> 20),
        b if b >= 1 << 10 && b % (1 << 10) == 0 => format!("{} KiB", b >> 10),
        b => format!("{b} bytes"),
    }
}

/// The UTF-8 text of the regular file `path`, at most [`max_input_bytes`].
pub fn text(path: &Path) -> Result<String> {
    String::from_utf8(bytes(path)?).map_err(|e| Error::NotUtf8 {
        path: path.display().to_string(),
        offset: e.utf8_error().valid_up_to(),
    })
}

/// The text of a file's bytes: UTF-8 without its byte-order mark, or else Latin-1 (ISO 8859-1:
/// every byte is the character of the same number, so this never fails). For formats that
/// older tools and spreadsheets write in Latin-1: CSV spectra and CGATS.
pub fn decode(bytes: Vec<u8>) -> String {
    let body = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(&bytes[..]);
    match std::str::from_utf8(body) {
        Ok(s) => s.to_string(),
        Err(_) => body.iter().map(|&b| b as char).collect(),
    }
}

/// The text of the regular file `path` ([`bytes`]), decoded by [`decode`].
pub fn text_or_latin1(path: &Path) -> Result<String> {
    bytes(path).map(decode)
}
