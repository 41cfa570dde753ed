//! `--instrument serial:PORT[,options]`: a Photo Research PR-655 or PR-670 SpectraScan
//! spectroradiometer in *remote mode* over a serial port (the instruments' USB port is a
//! virtual COM port).
//!
//! The subset of the remote-mode protocol used (Photo Research, *PR-655/PR-670 SpectraScan
//! User Manual*, chapter "Remote Mode"; the same commands as PsychoPy's and Psychtoolbox's
//! PR-655 drivers):
//!
//! | sent | reply (one line, CR LF) | use |
//! |---|---|---|
//! | `PHOTO` (no terminator) | `REMOTE MODE` | enter remote mode, once after opening |
//! | `M1` CR | `qqqq,UUU,Y,x,y` | measure; status, units code, luminance Y and CIE 1931 x, y |
//! | `D2` CR | `qqqq,UUU,X,Y,Z` | CIE 1931 XYZ of the last measurement |
//! | `Q` CR | (none) | leave remote mode, when done |
//!
//! `qqqq` is the status: `0000` means success; any other value is an instrument error (the
//! manual's error-code table; 10 and 18 are "light too low"). The numbers may be written in C
//! exponent notation (`1.234e+002`). The instrument must be set to metric units, so Y is in
//! cd/m²; the units code is not interpreted.
//!
//! Each reading is `M1` then `D2`; the XYZ of `D2` is kept and its Y is checked against the Y
//! of `M1` (0.5 %), which catches a stale reply paired with the wrong command. Every command
//! has a timeout (`timeout`, default 5 s; `measure-timeout`, default 30 s, for `M1`, which
//! integrates longer at low light). A reply that does not come, does not parse or carries a
//! non-zero status is retried (`retries`, default 2, after discarding pending input); a port
//! that fails (unplugged, hung up) ends the run at once. Options: `baud` (default 9600).
//!
//! Real serial lines are not clean: an instrument set to echo sends each command back before
//! its reply, and a port opened mid-transmission or a USB-serial adapter waking up delivers
//! stray bytes. A line equal to the command is skipped, and so is any line with no reply in
//! it; a reply preceded by noise on its own line is found by [`find_reply`]. Only when the
//! deadline passes with nothing but noise does the exchange fail (and get retried). Ctrl-C
//! stops a wait within 100 ms; dropping the driver sends `Q` (back to local mode).

use crate::error::{InstrumentError, Result};
use crate::instrument::Instrument;
use crate::interrupt;
use serialport::{ClearBuffer, SerialPort};
use specpoly_formats::device_spec::DeviceSpec;
use std::io::{ErrorKind, Read, Write};
use std::time::{Duration, Instant};

pub use super::serial_failure::Failure;

/// One parsed data reply: status, units code, three numbers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reply {
    /// Status code (0: success).
    pub status: i64,
    /// Units code, as sent.
    pub units: i64,
    /// The three values.
    pub values: [f64; 3],
}

/// Parses `qqqq,UUU,a,b,c` (status, units, three numbers). A non-zero status with fewer
/// fields is accepted too (an error reply carries no data).
pub fn parse_reply(line: &str) -> Option<Reply> {
    let f: Vec<&str> = line.trim().split(',').map(str::trim).collect();
    let status: i64 = f.first()?.parse().ok()?;
    if status != 0 && f.len() < 5 {
        return Some(Reply {
            status,
            units: f.get(1).and_then(|u| u.parse().ok()).unwrap_or(0),
            values: [f64::NAN; 3],
        });
    }
    if f.len() != 5 {
        return None;
    }
    let units: i64 = f[1].parse().ok()?;
    let mut values = [0.0; 3];
    for (v, s) in values.iter_mut().zip(&f[2..]) {
        *v = s.parse().ok().filter(|x: &f64| x.is_finite())?;
    }
    Some(Reply {
        status,
        units,
        values,
    })
}

/// The reply in a line that may start with noise: the longest suffix that [`parse_reply`]
/// accepts and whose status is four digits (`0000`, `0018`, `-0001`).
pub fn find_reply(line: &str) -> Option<Reply> {
    let clean: String = line.chars().filter(|c| !c.is_control()).collect::<String>();
    clean
        .char_indices()
        .map(|(i, _)| &clean[i..])
        .filter(|s| {
            let status = s.split(',').next().unwrap_or("").trim();
            let digits = status.strip_prefix('-').unwrap_or(status);
            digits.len() == 4 && digits.bytes().all(|b| b.is_ascii_digit())
        })
        .find_map(parse_reply)
}

/// Options of the serial instrument.
#[derive(Clone, Debug, PartialEq)]
pub struct SerialOptions {
    /// Baud rate.
    pub baud: u32,
    /// Timeout of `PHOTO` and `D2`.
    pub timeout: Duration,
    /// Timeout of `M1`.
    pub measure_timeout: Duration,
    /// Retries after a timeout, a garbled reply or an error status.
    pub retries: u32,
}

impl Default for SerialOptions {
    fn default() -> Self {
        Self {
            baud: 9600,
            timeout: Duration::from_secs(5),
            measure_timeout: Duration::from_secs(30),
            retries: 2,
        }
    }
}

/// A PR-655/670 in remote mode.
pub struct Pr6xx {
    port: Box<dyn SerialPort>,
    name: String,
    options: SerialOptions,
    pending: Vec<u8>,
}

impl Pr6xx {
    /// Parses `PORT[,baud=N][,timeout=SECS][,measure-timeout=SECS][,retries=N]`, opens the
    /// port and enters remote mode.
    pub fn from_spec(spec: &DeviceSpec<'_>) -> Result<Self> {
        let path = spec.required_arg("a port", "serial:/dev/ttyACM0")?;
        let mut o = SerialOptions::default();
        for &(k, v) in &spec.options {
            match k {
                "baud" => o.baud = spec.integer(k, v)?,
                "timeout" => o.timeout = spec.seconds(k, v)?,
                "measure-timeout" => o.measure_timeout = spec.seconds(k, v)?,
                "retries" => o.retries = spec.integer(k, v)?,
                _ => {
                    return Err(spec
                        .unknown(k, "baud, timeout, measure-timeout, retries")
                        .into())
                }
            }
        }
        Ok(Self::open(path, o)?)
    }

    /// Opens `path` and enters remote mode.
    pub fn open(path: &str, options: SerialOptions) -> Result<Self, InstrumentError> {
        let port = serialport::new(path, options.baud)
            .timeout(Duration::from_millis(100))
            .open()
            .map_err(|source| InstrumentError::OpenPort {
                port: path.to_string(),
                source,
            })?;
        let mut me = Self {
            port,
            name: path.to_string(),
            options,
            pending: Vec::new(),
        };
        me.remote_mode()?;
        Ok(me)
    }

    fn err(&self, f: Failure) -> InstrumentError {
        InstrumentError::Serial {
            port: self.name.clone(),
            failure: f,
            attempts: None,
        }
    }

    fn send(&mut self, cmd: &str) -> std::result::Result<(), Failure> {
        self.port.write_all(cmd.as_bytes()).map_err(Failure::Gone)?;
        self.port.flush().map_err(Failure::Gone)
    }

    /// Reads one non-empty line (CR, LF or CR LF ended) before `timeout` runs out.
    fn read_line(
        &mut self,
        cmd: &'static str,
        timeout: Duration,
    ) -> std::result::Result<String, Failure> {
        let deadline = Instant::now() + timeout;
        loop {
            while let Some(i) = self.pending.iter().position(|b| *b == b'\n' || *b == b'\r') {
                let line: Vec<u8> = self.pending.drain(..=i).collect();
                let s = String::from_utf8_lossy(&line).trim().to_string();
                if !s.is_empty() {
                    return Ok(s);
                }
            }
            if interrupt::requested() {
                return Err(Failure::Interrupted);
            }
            let now = Instant::now();
            if now >= deadline {
                return Err(Failure::Timeout(cmd, timeout));
            }
            let wait = (deadline - now).min(Duration::from_millis(100));
            self.port
                .set_timeout(wait.max(Duration::from_millis(1)))
                .map_err(|e| Failure::Gone(e.into()))?;
            let mut buf = [0u8; 256];
            match self.port.read(&mut buf) {
                Ok(0) => {
                    return Err(Failure::Gone(std::io::Error::new(
                        ErrorKind::UnexpectedEof,
                        "end of file",
                    )))
                }
                Ok(n) => {
                    self.pending.extend_from_slice(&buf[..n]);
                    if self.pending.len() > 4096 {
                        let s = String::from_utf8_lossy(&self.pending[..64]).to_string();
                        self.pending.clear();
                        return Err(Failure::Garbled(cmd, format!("{s}… (no line end)")));
                    }
                }
                Err(e) if e.kind() == ErrorKind::TimedOut || e.kind() == ErrorKind::Interrupted => {
                }
                Err(e) => return Err(Failure::Gone(e)),
            }
        }
    }

    /// Discards pending input (after a failed exchange, so a late reply is not taken for the
    /// next one).
    fn drain(&mut self) -> std::result::Result<(), Failure> {
        self.pending.clear();
        std::thread::sleep(Duration::from_millis(50));
        self.port
            .clear(ClearBuffer::Input)
            .map_err(|e| Failure::Gone(e.into()))
    }

    fn try_remote_mode(&mut self) -> std::result::Result<(), Failure> {
        self.send("PHOTO")?;
        let timeout = self.options.timeout;
        let deadline = Instant::now() + timeout;
        let mut noise = None;
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            match self.read_line("PHOTO", left) {
                Ok(line) if line.to_ascii_uppercase().contains("REMOTE MODE") => return Ok(()),
                // an echo of the command or noise: keep reading until the deadline
                Ok(line) => noise = Some(line),
                Err(Failure::Timeout(..)) => {
                    return Err(match noise {
                        Some(n) => Failure::Garbled("PHOTO", n),
                        None => Failure::Timeout("PHOTO", timeout),
                    })
                }
                Err(f) => return Err(f),
            }
        }
    }

    fn remote_mode(&mut self) -> Result<(), InstrumentError> {
        let mut last = None;
        for _ in 0..=self.options.retries {
            match self.try_remote_mode() {
                Ok(()) => return Ok(()),
                Err(f @ (Failure::Gone(_) | Failure::Interrupted)) => return Err(self.err(f)),
                Err(f) => {
                    last = Some(f);
                    self.drain().map_err(|f| self.err(f))?;
                }
            }
        }
        match last {
            Some(Failure::Timeout(..)) => Err(InstrumentError::NoAnswer {
                port: self.name.clone(),
                seconds: self.options.timeout.as_secs_f64(),
                attempts: self.options.retries + 1,
            }),
            Some(f) => Err(self.err(f)),
            None => Err(InstrumentError::NoAttempt {
                port: self.name.clone(),
            }),
        }
    }

    fn exchange(
        &mut self,
        cmd: &'static str,
        timeout: Duration,
    ) -> std::result::Result<[f64; 3], Failure> {
        self.send(cmd)?;
        self.send("\r")?;
        let deadline = Instant::now() + timeout;
        let mut noise = None;
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            let line = match self.read_line(cmd, left) {
                Ok(l) => l,
                Err(Failure::Timeout(..)) => {
                    return Err(match noise {
                        Some(n) => Failure::Garbled(cmd, n),
                        None => Failure::Timeout(cmd, timeout),
                    })
                }
                Err(f) => return Err(f),
            };
            // the instrument echoing the command (a terminal setting), or noise on the line
            // before the reply (a port opened mid-transmission, a USB-serial adapter's
            // start-up bytes): skip it and keep reading until the deadline
            if line.eq_ignore_ascii_case(cmd) {
                continue;
            }
            match find_reply(&line) {
                Some(r) if r.status != 0 => return Err(Failure::Status(cmd, r.status)),
                Some(r) => return Ok(r.values),
                None => noise = Some(line),
            }
        }
    }

    fn try_measure(&mut self) -> std::result::Result<[f64; 3], Failure> {
        let yxy = self.exchange("M1", self.options.measure_timeout)?;
        let xyz = self.exchange("D2", self.options.timeout)?;
        let (y1, y2) = (yxy[0], xyz[1]);
        if (y1 - y2).abs() > 5e-3 * y1.abs().max(y2.abs()) + 1e-6 {
            return Err(Failure::Garbled(
                "D2",
                format!("Y = {y2} but `M1` measured Y = {y1}"),
            ));
        }
        Ok(xyz)
    }
}

impl Instrument for Pr6xx {
    fn describe(&self) -> String {
        format!("PR-655/670 (remote mode) on {}", self.name)
    }

    fn measure(&mut self) -> Result<[f64; 3], InstrumentError> {
        let mut last = None;
        let attempts = self.options.retries + 1;
        for _ in 0..attempts {
            match self.try_measure() {
                Ok(x) => return Ok(x),
                Err(f @ (Failure::Gone(_) | Failure::Interrupted)) => return Err(self.err(f)),
                Err(f) => {
                    last = Some(f);
                    self.drain().map_err(|f| self.err(f))?;
                }
            }
        }
        match last {
            Some(failure) => Err(InstrumentError::Serial {
                port: self.name.clone(),
                failure,
                attempts: Some(attempts),
            }),
            None => Err(InstrumentError::NoAttempt {
                port: self.name.clone(),
            }),
        }
    }
}

impl Drop for Pr6xx {
    fn drop(&mut self) {
        // leave remote mode; nothing to do if the port is gone
        let _ = self.send("Q\r");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_replies() {
        let r = parse_reply("0000,111,1.234e+002,0.3127,0.3290\r\n").unwrap();
        assert_eq!(r.status, 0);
        assert_eq!(r.units, 111);
        assert_eq!(r.values, [123.4, 0.3127, 0.3290]);
        assert_eq!(parse_reply(" 0018,111").unwrap().status, 18);
        assert!(parse_reply("0000,111,abc,0.3,0.3").is_none());
        assert!(parse_reply("0000,111,1,2").is_none());
        assert!(parse_reply("REMOTE MODE").is_none());
        assert!(parse_reply("0000,111,nan,1,1").is_none());
        assert!(parse_reply("").is_none());
    }

    #[test]
    fn finds_replies_after_noise() {
        let r = find_reply("\u{0}#!~0000,111,1.234e+002,0.3127,0.3290").unwrap();
        assert_eq!(r.values, [123.4, 0.3127, 0.3290]);
        assert_eq!(find_reply("xx0018").unwrap().status, 18);
        assert!(find_reply("7").is_none());
        assert!(find_reply("M1").is_none());
        assert!(find_reply("0000,111,#!x?,0.3,").is_none());
    }
}
