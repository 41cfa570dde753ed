//! Assembling lines from a byte stream, bounded: a line is at most `N` bytes before its `\n`;
//! a longer one is discarded whole and reported once, at its end, as [`ErrorCode::TooLong`].
//! Printable ASCII and tab are kept, `\r` is dropped (so CRLF works), any other byte marks the
//! line [`ErrorCode::BadByte`].

use crate::{ErrorCode, Fault};

/// A fixed-capacity line assembler.
pub struct LineReader<const N: usize> {
    buf: [u8; N],
    len: usize,
    fault: Option<ErrorCode>,
    done: bool,
}

impl<const N: usize> Default for LineReader<N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: usize> LineReader<N> {
    /// An empty reader.
    pub const fn new() -> Self {
        Self {
            buf: [0; N],
            len: 0,
            fault: None,
            done: false,
        }
    }

    /// Takes one byte; at a `\n`, returns the line (without it) or why it was rejected.
    pub fn push(&mut self, b: u8) -> Option<Result<&str, Fault>> {
        if self.done {
            self.len = 0;
            self.fault = None;
            self.done = false;
        }
        match b {
            b'\n' => {
                self.done = true;
                if let Some(code) = self.fault {
                    return Some(Err(Fault::new(code)));
                }
                // only printable ASCII and tabs were stored
                match core::str::from_utf8(&self.buf[..self.len]) {
                    Ok(s) => Some(Ok(s)),
                    Err(_) => Some(Err(Fault::new(ErrorCode::BadByte))),
                }
            }
            b'\r' => None,
            b'\t' | 0x20..=0x7e => {
                if self.fault.is_none() {
                    if self.len < N {
                        self.buf[self.len] = b;
                        self.len += 1;
                    } else {
                        self.fault = Some(ErrorCode::TooLong);
                    }
                }
                None
            }
            _ => {
                if self.fault.is_none() {
                    self.fault = Some(ErrorCode::BadByte);
                }
                None
            }
        }
    }
}
