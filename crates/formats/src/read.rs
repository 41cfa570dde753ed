//! Reading input files safely: only regular files (a path naming a device such as `/dev/zero`,
//! a FIFO or a directory is refused before it is opened, so nothing blocks or reads forever), and
//! at most [`MAX_INPUT_BYTES`] (the largest spectral table, scene or measurement file we expect
//! is a few megabytes; the limit bounds memory, it is not a format rule).

use crate::{Error, Result};
use std::io::Read;
use std::path::Path;

/// The largest input file read (64 MiB).
pub const MAX_INPUT_BYTES: u64 = 64 << 20;

/// The bytes of the regular file `path`, at most [`MAX_INPUT_BYTES`].
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
    let mut buf = Vec::new();
    file.take(MAX_INPUT_BYTES + 1)
        .read_to_end(&mut buf)
        .map_err(|e| Error::io(path, e))?;
    if buf.len() as u64 > MAX_INPUT_BYTES {
        return Err(Error::TooLarge {
            path: path.display().to_string(),
            limit_mib: MAX_INPUT_BYTES >> 20,
        });
    }
    Ok(buf)
}

/// The UTF-8 text of the regular file `path`, at most [`MAX_INPUT_BYTES`].
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
