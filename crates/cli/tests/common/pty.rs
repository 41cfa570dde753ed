//! A fake serial device on a pseudo-terminal, for the tests of the host's serial links (the
//! LED controller, the PR-655): the pty pair, the device's thread until the fake is dropped,
//! reads that give up after 20 ms, and a line protocol's framing. Include it with
//! `#[path = "common/pty.rs"] mod pty;` (`pr655.rs` includes it itself).
#![allow(dead_code)]

use serialport::{SerialPort, TTYPort};
use specpoly_protocol::{LineReader, MAX_LINE};
use std::io::{ErrorKind, Read, Write};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::Duration;

/// A running fake device; stops (and joins its thread) when dropped.
pub struct FakePort {
    /// The port to open (`/dev/pts/N`).
    pub path: String,
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
    // held open so the pty stays up between the host's open and close
    _slave: TTYPort,
}

impl Drop for FakePort {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::SeqCst);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// Opens a pseudo-terminal pair and runs `serve(master, stop)` on a thread until the fake is
/// dropped (`stop` turns true). Returning from `serve` drops the master: the port hangs up.
pub fn spawn(serve: impl FnOnce(TTYPort, Arc<AtomicBool>) + Send + 'static) -> FakePort {
    let (master, slave) = TTYPort::pair().expect("a pseudo-terminal pair");
    // `pair` opens the master without close-on-exec: a `specpoly` started by the test would
    // inherit it and keep the pty up after the device "unplugs". The clone is close-on-exec
    // (F_DUPFD_CLOEXEC); the original is closed at once.
    let mut master = master.try_clone_native().expect("clone the master");
    master
        .set_timeout(Duration::from_millis(20))
        .expect("master timeout");
    let path = slave.name().expect("the slave's name");
    let stop = Arc::new(AtomicBool::new(false));
    let s = stop.clone();
    let thread = std::thread::spawn(move || serve(master, s));
    FakePort {
        path,
        stop,
        thread: Some(thread),
        _slave: slave,
    }
}

/// What arrived on the port within its 20 ms timeout (`None`: nothing; when nobody has the
/// slave open, after a 10 ms pause).
pub fn read_some<'a>(port: &mut TTYPort, buf: &'a mut [u8; 256]) -> Option<&'a [u8]> {
    match port.read(buf) {
        Ok(n) => Some(&buf[..n]),
        Err(e) if e.kind() == ErrorKind::TimedOut => None,
        Err(_) => {
            std::thread::sleep(Duration::from_millis(10));
            None
        }
    }
}

/// A line device's answer to one line.
pub enum Answer {
    /// Write this line (and CR LF).
    Line(String),
    /// Say nothing.
    Nothing,
    /// Write this line, then hang up.
    LineThenHangUp(String),
}

/// Serves a line protocol until `stop`: every line the protocol's framing (`LineReader`)
/// completes is passed to `answer`; malformed lines are dropped.
pub fn serve_lines(
    mut port: TTYPort,
    stop: Arc<AtomicBool>,
    mut answer: impl FnMut(&str) -> Answer,
) {
    let mut lines = LineReader::<MAX_LINE>::new();
    let mut buf = [0u8; 256];
    while !stop.load(Ordering::SeqCst) {
        let Some(bytes) = read_some(&mut port, &mut buf) else {
            continue;
        };
        for byte in bytes {
            let Some(Ok(line)) = lines.push(*byte).map(|l| l.map(str::to_owned)) else {
                continue;
            };
            let (out, hang_up) = match answer(&line) {
                Answer::Nothing => continue,
                Answer::Line(l) => (l, false),
                Answer::LineThenHangUp(l) => (l, true),
            };
            let _ = port.write_all(out.as_bytes());
            let _ = port.write_all(b"\r\n");
            let _ = port.flush();
            if hang_up {
                return;
            }
        }
    }
}
