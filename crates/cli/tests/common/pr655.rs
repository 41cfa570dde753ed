//! An emulated Photo Research PR-655 in remote mode on a pseudo-terminal, for the tests of
//! `--instrument serial:PORT`. It speaks the subset the driver uses (`PHOTO`, `M1`, `D2`,
//! `Q`, see crates/calibrate/src/instrument/serial.rs) and measures whatever `source` returns
//! (the XYZ of the patch on screen). Faults make it misbehave on given measurements.
#![allow(dead_code)]

use super::pty;

use pty::FakePort;
use serialport::TTYPort;
use std::io::Write;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::Duration;

/// How the emulator misbehaves. Measurement numbers count `M1` commands from 1 (a retry is a
/// new `M1`).
#[derive(Clone, Debug, Default)]
pub struct Faults {
    /// Never answer anything (a port with no instrument).
    pub silent: bool,
    /// Answer these `M1`s with garbage.
    pub garbage_on: Vec<usize>,
    /// Answer every `M1` from this one on with garbage.
    pub garbage_from: Option<usize>,
    /// Answer these `M1`s after a delay.
    pub slow_on: Vec<(usize, Duration)>,
    /// Answer these `M1`s with an error status.
    pub status_on: Vec<(usize, i64)>,
    /// Close the port when this `M1` arrives (the instrument is unplugged).
    pub vanish_on: Option<usize>,
    /// Integration time of every measurement.
    pub integration: Duration,
    /// Echo every command back (its bytes, then CR LF) before answering, as an instrument
    /// whose serial line is set to echo does.
    pub echo: bool,
    /// Send a line of noise before every reply and stray bytes at the start of the reply's
    /// line (a port opened mid-transmission, a USB-serial adapter waking up).
    pub noise: bool,
}

/// A running emulator; stops when dropped.
pub struct Emulator {
    /// The port to open (`/dev/pts/N`).
    pub path: String,
    /// `M1` commands received so far.
    pub measurements: Arc<AtomicUsize>,
    /// `Q` commands (back to local mode) received so far.
    pub quits: Arc<AtomicUsize>,
    _port: FakePort,
}

impl Emulator {
    /// `M1` commands received so far.
    pub fn measured(&self) -> usize {
        self.measurements.load(Ordering::SeqCst)
    }

    /// `Q` commands received so far.
    pub fn quitted(&self) -> usize {
        self.quits.load(Ordering::SeqCst)
    }
}

/// C's `%.3e`: `1.234e+002`, the PR-655's number format.
pub fn c_exp(v: f64) -> String {
    let s = format!("{v:.3e}");
    let (m, e) = s.split_once('e').unwrap();
    let e: i32 = e.parse().unwrap();
    format!("{m}e{}{:03}", if e < 0 { '-' } else { '+' }, e.abs())
}

/// Starts an emulator measuring `source`.
pub fn spawn(source: impl Fn() -> [f64; 3] + Send + 'static, faults: Faults) -> Emulator {
    let count = Arc::new(AtomicUsize::new(0));
    let quits = Arc::new(AtomicUsize::new(0));
    let (c, q) = (count.clone(), quits.clone());
    let port = pty::spawn(move |master, stop| run(master, source, faults, stop, c, q));
    Emulator {
        path: port.path.clone(),
        measurements: count,
        quits,
        _port: port,
    }
}

fn run(
    mut port: TTYPort,
    source: impl Fn() -> [f64; 3],
    f: Faults,
    stop: Arc<AtomicBool>,
    count: Arc<AtomicUsize>,
    quits: Arc<AtomicUsize>,
) {
    let mut buf: Vec<u8> = Vec::new();
    let mut last = [0.0f64; 3];
    let mut b = [0u8; 256];
    let noise = f.noise;
    let echo = f.echo;
    let echo_back = |port: &mut TTYPort, cmd: &[u8]| {
        if echo {
            let _ = port.write_all(cmd);
            let _ = port.write_all(b"\r\n");
            let _ = port.flush();
        }
    };
    let reply = |port: &mut TTYPort, s: &str| {
        if noise {
            let _ = port.write_all(b"\x00\xff#~ line noise ~#\r\n\x11@@");
        }
        let _ = port.write_all(s.as_bytes());
        let _ = port.write_all(b"\r\n");
        let _ = port.flush();
    };
    while !stop.load(Ordering::SeqCst) {
        match pty::read_some(&mut port, &mut b) {
            Some(bytes) => buf.extend_from_slice(bytes),
            None => continue,
        }
        if f.silent {
            buf.clear();
            continue;
        }
        loop {
            // PHOTO comes without a line end
            if let Some(i) = find(&buf, b"PHOTO") {
                buf.drain(..i + 5);
                echo_back(&mut port, b"PHOTO");
                reply(&mut port, " REMOTE MODE");
                continue;
            }
            let Some(i) = buf.iter().position(|b| *b == b'\r' || *b == b'\n') else {
                break;
            };
            let line: Vec<u8> = buf.drain(..=i).collect();
            let cmd = String::from_utf8_lossy(&line).trim().to_string();
            if !cmd.is_empty() {
                echo_back(&mut port, cmd.as_bytes());
            }
            match cmd.as_str() {
                "" => {}
                "Q" => {
                    quits.fetch_add(1, Ordering::SeqCst);
                }
                "M1" => {
                    let n = count.fetch_add(1, Ordering::SeqCst) + 1;
                    if f.vanish_on == Some(n) {
                        return; // drops the master: the port hangs up
                    }
                    if !f.integration.is_zero() {
                        std::thread::sleep(f.integration);
                    }
                    if let Some((_, d)) = f.slow_on.iter().find(|(k, _)| *k == n) {
                        std::thread::sleep(*d);
                    }
                    if f.garbage_on.contains(&n) || f.garbage_from.is_some_and(|k| n >= k) {
                        reply(&mut port, "0000,111,#!x?,0.3,");
                        continue;
                    }
                    if let Some((_, s)) = f.status_on.iter().find(|(k, _)| *k == n) {
                        reply(&mut port, &format!("{s:04}"));
                        continue;
                    }
                    last = source();
                    let sum = last[0] + last[1] + last[2];
                    let (x, y) = if sum > 0.0 {
                        (last[0] / sum, last[1] / sum)
                    } else {
                        (0.0, 0.0)
                    };
                    reply(
                        &mut port,
                        &format!("0000,111,{},{x:.4},{y:.4}", c_exp(last[1])),
                    );
                }
                "D2" => reply(
                    &mut port,
                    &format!(
                        "0000,111,{},{},{}",
                        c_exp(last[0]),
                        c_exp(last[1]),
                        c_exp(last[2])
                    ),
                ),
                _ => reply(&mut port, "-0001"),
            }
        }
    }
}

fn find(h: &[u8], n: &[u8]) -> Option<usize> {
    h.windows(n.len()).position(|w| w == n)
}
