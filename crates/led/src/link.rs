//! A line-protocol link to the controller over any byte stream (a serial port, or a
//! pseudo-terminal in tests): one command line out, one reply line back.

use crate::Error;
use specpoly_protocol::{Reply, MAX_LINE, MAX_REPLY, PROTOCOL_VERSION};
use std::io::{ErrorKind, Read, Write};
use std::time::{Duration, Instant};

/// The controller at the other end of `port`.
pub struct Link<P> {
    port: P,
    name: String,
    timeout: Duration,
    pending: Vec<u8>,
}

impl Link<Box<dyn serialport::SerialPort>> {
    /// Opens a serial port (115200 8N1; a pseudo-terminal ignores the rate).
    pub fn open(path: &str, timeout: Duration) -> Result<Self, Error> {
        let port = serialport::new(path, 115_200)
            .timeout(Duration::from_millis(20))
            .open()
            .map_err(|source| Error::Open {
                port: path.to_owned(),
                source,
            })?;
        Ok(Self::new(port, path, timeout))
    }
}

/// EIO (a pseudo-terminal whose other end has gone) and a broken pipe mean the device left.
/// serialport reports a `poll` that returned `POLLERR` (a pseudo-terminal or USB serial device
/// whose other end went away, racing with `POLLHUP`) as `ErrorKind::Other` carrying EIO's text
/// and no OS code (`serialport` 4, `posix/poll.rs` `wait_fd`): that is a hang-up too.
fn is_hang_up(e: &std::io::Error) -> bool {
    e.kind() == ErrorKind::BrokenPipe
        || e.raw_os_error() == Some(5)
        || (e.kind() == ErrorKind::Other
            && e.raw_os_error().is_none()
            && e.to_string() == "I/O error")
}

fn clip(s: &str, n: usize) -> String {
    s.chars().take(n).collect()
}

impl<P: Read + Write> Link<P> {
    /// A link over an open stream; `name` is used in messages.
    pub fn new(port: P, name: &str, timeout: Duration) -> Self {
        Self {
            port,
            name: name.to_owned(),
            timeout,
            pending: Vec::new(),
        }
    }

    /// Sends one command line and returns the controller's reply; an `err` reply is
    /// [`Error::Rejected`].
    pub fn send(&mut self, command: &str) -> Result<Reply, Error> {
        let line = self.exchange(command)?;
        match Reply::parse(&line) {
            Ok(Reply::Error(fault)) => Err(Error::Rejected {
                command: clip(command, 40),
                fault,
            }),
            Ok(r) => Ok(r),
            Err(_) => Err(Error::BadReply {
                port: self.name.clone(),
                command: clip(command, 40),
                reply: clip(&line, 80),
            }),
        }
    }

    /// `hello`, checking the protocol version; returns the full-scale duty.
    pub fn hello(&mut self) -> Result<u16, Error> {
        match self.send("hello")? {
            Reply::Hello { protocol, max, .. } if protocol == PROTOCOL_VERSION => Ok(max),
            Reply::Hello { protocol, .. } => Err(Error::Version {
                port: self.name.clone(),
                found: protocol,
                expected: PROTOCOL_VERSION,
            }),
            other => Err(Error::BadReply {
                port: self.name.clone(),
                command: "hello".into(),
                reply: clip(&crate::lines::reply_line(&other), 80),
            }),
        }
    }

    fn io_error(&self, source: std::io::Error) -> Error {
        if is_hang_up(&source) {
            Error::Closed {
                port: self.name.clone(),
            }
        } else {
            Error::Io {
                port: self.name.clone(),
                source,
            }
        }
    }

    /// Writes `command` and a newline, and reads the reply line (without its newline).
    pub fn exchange(&mut self, command: &str) -> Result<String, Error> {
        if command.len() > MAX_LINE {
            return Err(Error::TooLong {
                len: command.len(),
                max: MAX_LINE,
            });
        }
        self.exchange_unchecked(command)
    }

    /// As [`Self::exchange`] without the host's length check, to test the controller's own
    /// limits.
    pub fn exchange_unchecked(&mut self, command: &str) -> Result<String, Error> {
        let mut out = Vec::with_capacity(command.len() + 1);
        out.extend_from_slice(command.as_bytes());
        out.push(b'\n');
        // no flush: on a tty it is tcdrain, which only waits for the bytes to leave, and
        // reports a hang-up as an opaque "flush failed"
        if let Err(e) = self.port.write_all(&out) {
            return Err(self.io_error(e));
        }
        let deadline = Instant::now() + self.timeout;
        let mut chunk = [0u8; 256];
        loop {
            if let Some(i) = self.pending.iter().position(|b| *b == b'\n') {
                let line: Vec<u8> = self.pending.drain(..=i).collect();
                let text = String::from_utf8_lossy(&line[..i]);
                return Ok(text.trim_end_matches('\r').to_owned());
            }
            if self.pending.len() > 4 * MAX_REPLY {
                return Err(Error::BadReply {
                    port: self.name.clone(),
                    command: clip(command, 40),
                    reply: clip(&String::from_utf8_lossy(&self.pending), 80),
                });
            }
            if Instant::now() >= deadline {
                return Err(Error::Timeout {
                    port: self.name.clone(),
                    command: clip(command, 40),
                    ms: self.timeout.as_millis(),
                });
            }
            match self.port.read(&mut chunk) {
                Ok(0) => {
                    return Err(Error::Closed {
                        port: self.name.clone(),
                    })
                }
                Ok(n) => self.pending.extend_from_slice(&chunk[..n]),
                Err(e) if matches!(e.kind(), ErrorKind::TimedOut | ErrorKind::WouldBlock) => {}
                Err(e) if e.kind() == ErrorKind::Interrupted => {}
                Err(e) => return Err(self.io_error(e)),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::is_hang_up;
    use std::io::{Error, ErrorKind};

    /// The three ways a departed device shows up, and two that are not a hang-up.
    #[test]
    fn hang_ups() {
        assert!(is_hang_up(&Error::from(ErrorKind::BrokenPipe)));
        assert!(is_hang_up(&Error::from_raw_os_error(5)));
        assert!(is_hang_up(&Error::other("I/O error")));
        assert!(!is_hang_up(&Error::other("something else")));
        assert!(!is_hang_up(&Error::from(ErrorKind::PermissionDenied)));
    }
}
