//! `--instrument argyll[:OPTIONS]`: measure through ArgyllCMS's `dispread` (Debian package
//! `argyll`), which drives every instrument ArgyllCMS supports (i1Display Pro, ColorMunki,
//! Spyder, i1Pro, Klein K-10, JETI specbos, …) and shows the patches itself.
//!
//! **Why `dispread`, not `spotread`.** The patch set is handed to `dispread` as a `.ti1` and
//! its `.ti3` read back, in batches. `dispread` owns the patch window and the instrument for
//! the whole batch, so it applies what a colorimeter needs between patches (refresh-rate
//! sync, adaptive integration, display-type/CCSS corrections, drift compensation) at
//! ArgyllCMS's own speed; `spotread` measures whatever is on screen when a key arrives and
//! re-opens the instrument on each `-O` call. And only `dispread` has ArgyllCMS's fake
//! instrument (`-dfake`, reading `fake.icm`), so this path runs end to end against the real
//! binaries in the tests. See docs/calibration.md.
//!
//! **Never lose a measurement.** `dispread` writes its `.ti3` only when a batch is complete,
//! so the patches go in batches (`batch`, default 12): a failure or Ctrl-C loses at most the
//! batch in progress, and each finished batch is in `CAL.ti3` (atomically) before the next
//! starts. Each batch re-opens the instrument (about a second for an i1Display Pro).
//!
//! **A private working folder.** `dispread` reads its `.ti1` and writes its `.ti3` in a folder
//! of this run's own: created fresh in the system's temporary folder (`$TMPDIR`, else `/tmp`)
//! under a random name, mode 0700, never reused, removed when the run ends (the `tempfile`
//! crate's `TempDir`). No other user can plant a folder or a symlink there beforehand, so a
//! run never writes through someone else's link.
//!
//! **Never hang.** `dispread` runs with `-v` and must say something (a `patch k of n` line, a prompt, an error) at least every `timeout`
//! seconds (default 30), or it is killed and the run stops with one line. This also catches
//! ArgyllCMS's device scan blocking on a serial port with no instrument.
//!
//! `--display` names where `dispread` shows the patches: `argyll[:N]` (its own window on
//! display N, default 1), `argyll:web[:PORT]` (its web server, `-dweb`), `argyll:fake[:ICC]`
//! (ArgyllCMS's fake display and instrument; with an ICC profile it measures that profile's
//! colours, otherwise its built-in model), `argyll:dummy` (no window: the instrument reads
//! whatever is in front of it); options `scale=S` (the window's size relative to
//! ArgyllCMS's default, `-P 0.5,0.5,S`) and `fill` (black around the window, `-F`).
//!
//! OPTIONS (comma separated):
//!
//! | option | dispread flag | meaning |
//! |---|---|---|
//! | `c=N` | `-c N` | the instrument's number in ArgyllCMS's list (`spotread -?` prints it) |
//! | `y=X` | `-y X` | display type (a letter from the instrument's list, e.g. `l` LCD, `c` CRT; i1Display Pro: `e` and `b` for LED backlights …) |
//! | `x=FILE` | `-X FILE` | colorimeter correction: a `.ccss` (spectral samples) or `.ccmx` (matrix) |
//! | `q=OBS` | `-Q OBS` | observer for spectral data (`1931_2`, `1964_10`, …) |
//! | `fixed` | `-Y A` | non-adaptive (fixed) integration time |
//! | `rate=HZ` | `-Y R:HZ` | the display's refresh rate, instead of measuring it |
//! | `hires` | `-H` | high-resolution spectral mode |
//! | `drift=b\|w\|bw` | `-I X` | black/white drift compensation |
//! | `batch=N` | — | patches per `dispread` run (1–1000, default 12) |
//! | `timeout=SECS` | — | longest silence of `dispread` before it is stopped (default 30) |
//! | `arg=A` | `A` | any other `dispread` argument, one word per `arg=` |

use crate::error::{Error, InstrumentError, Result};
use crate::interrupt;
use specpoly_formats::device_spec::DeviceSpec;
use specpoly_formats::{cgats, ti1};
use std::io::{IsTerminal, Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// The Debian package with `dispread`.
pub const PACKAGE: &str = "argyll";

/// Where `dispread` shows the patches.
#[derive(Clone, Debug, PartialEq)]
pub enum ArgyllDisplay {
    /// Its own window on display `N` (1-based, ArgyllCMS's numbering).
    Screen(u32),
    /// Its web server on a port (default 8080).
    Web(Option<u16>),
    /// The fake display and instrument, optionally measuring an ICC profile.
    Fake(Option<PathBuf>),
    /// No window (`-d dummy`): the instrument reads whatever is in front of it.
    Dummy,
}

/// The `--display` for `dispread`.
#[derive(Clone, Debug, PartialEq)]
pub struct DisplayOptions {
    /// Where.
    pub display: ArgyllDisplay,
    /// Window scale (`-P 0.5,0.5,S`).
    pub scale: Option<f64>,
    /// Black around the window (`-F`).
    pub fill: bool,
}

/// Whether `spec` names the ArgyllCMS instrument.
pub fn is_argyll(spec: &str) -> bool {
    spec == "argyll" || spec.starts_with("argyll:")
}

impl DisplayOptions {
    /// Parses `argyll[:N|:web[:PORT]|:fake[:ICC]|:dummy][,scale=S][,fill]` (the project's
    /// one device-spec parser, [`DeviceSpec`]).
    pub fn parse(text: &str) -> Result<Self> {
        let spec = DeviceSpec::parse(text);
        let usage = || Error::ArgyllDisplay {
            spec: text.to_string(),
        };
        if spec.kind != "argyll" {
            return Err(usage());
        }
        let display = match spec.arg {
            None => ArgyllDisplay::Screen(1),
            Some("web") => ArgyllDisplay::Web(None),
            Some("fake") => ArgyllDisplay::Fake(None),
            Some("dummy") => ArgyllDisplay::Dummy,
            Some(r) if r.starts_with("web:") => {
                ArgyllDisplay::Web(Some(r[4..].parse().map_err(|_| usage())?))
            }
            Some(r) if r.starts_with("fake:") => {
                let p = PathBuf::from(&r[5..]);
                if !p.is_file() {
                    return Err(Error::NoProfile {
                        spec: text.to_string(),
                        file: p,
                    });
                }
                ArgyllDisplay::Fake(Some(p))
            }
            Some(r) => ArgyllDisplay::Screen(
                r.parse::<u32>()
                    .ok()
                    .filter(|n| *n >= 1)
                    .ok_or_else(usage)?,
            ),
        };
        let mut o = Self {
            display,
            scale: None,
            fill: false,
        };
        for &(k, v) in &spec.options {
            match k {
                "scale" => {
                    let x = spec.number(k, v)?;
                    if !(x > 0.0 && x <= 100.0) {
                        return Err(spec.bad(k, v, "expected a scale in (0, 100]").into());
                    }
                    o.scale = Some(x);
                }
                "fill" if v.is_empty() => o.fill = true,
                _ => return Err(spec.unknown(k, "scale=S, fill").into()),
            }
        }
        Ok(o)
    }

    fn args(&self) -> Vec<String> {
        let mut a = match &self.display {
            ArgyllDisplay::Screen(n) => vec!["-d".to_string(), n.to_string()],
            ArgyllDisplay::Web(None) => vec!["-dweb".to_string()],
            ArgyllDisplay::Web(Some(p)) => vec![format!("-dweb:{p}")],
            ArgyllDisplay::Fake(_) => vec!["-dfake".to_string()],
            ArgyllDisplay::Dummy => vec!["-d".to_string(), "dummy".to_string()],
        };
        if let Some(s) = self.scale {
            a.push("-P".into());
            a.push(format!("0.5,0.5,{s}"));
        }
        if self.fill {
            a.push("-F".into());
        }
        a
    }
}

/// The instrument options.
#[derive(Clone, Debug, PartialEq)]
pub struct ArgyllOptions {
    /// `dispread` arguments that choose and set up the instrument.
    pub args: Vec<String>,
    /// Patches per `dispread` run.
    pub batch: usize,
    /// Longest silence of `dispread`.
    pub timeout: Duration,
}

impl ArgyllOptions {
    /// Parses `argyll[:OPTION][,OPTION…]` (see the module docs) with the project's one
    /// device-spec parser, [`DeviceSpec`]: the first option may follow the `:`.
    pub fn parse(text: &str) -> Result<Self> {
        let spec = DeviceSpec::parse(text);
        if spec.kind != "argyll" {
            return Err(Error::ArgyllInstrument {
                spec: text.to_string(),
            });
        }
        let mut options: Vec<(&str, &str)> = Vec::new();
        if let Some(first) = spec.arg.filter(|a| !a.is_empty()) {
            options.push(first.split_once('=').unwrap_or((first, "")));
        }
        options.extend(spec.options.iter().copied());
        let mut o = Self {
            args: Vec::new(),
            batch: 12,
            timeout: Duration::from_secs(30),
        };
        for (k, v) in options {
            let word = |v: &str| {
                if v.is_empty() || v.contains(char::is_whitespace) {
                    Err(spec.bad(k, v, "expected one word"))
                } else {
                    Ok(v.to_string())
                }
            };
            match k {
                "c" => {
                    let n: u32 = spec.integer(k, v)?;
                    if n < 1 {
                        return Err(spec.bad(k, v, "instruments are numbered from 1").into());
                    }
                    o.args.extend(["-c".into(), n.to_string()]);
                }
                "y" => o.args.extend(["-y".into(), word(v)?]),
                "x" => {
                    let f = Path::new(v);
                    if !f.is_file() {
                        return Err(Error::NoCorrectionFile {
                            spec: text.to_string(),
                            file: v.to_string(),
                        });
                    }
                    let abs = std::fs::canonicalize(f).map_err(|e| Error::io(f, e))?;
                    o.args.extend(["-X".into(), abs.display().to_string()]);
                }
                "q" => o.args.extend(["-Q".into(), word(v)?]),
                "fixed" if v.is_empty() => o.args.extend(["-Y".into(), "A".into()]),
                "hires" if v.is_empty() => o.args.push("-H".into()),
                "rate" => {
                    let hz = spec.number(k, v)?;
                    if hz <= 0.0 {
                        return Err(spec.bad(k, v, "expected a refresh rate in Hz").into());
                    }
                    o.args.extend(["-Y".into(), format!("R:{hz}")]);
                }
                "drift" if matches!(v, "b" | "w" | "bw") => {
                    o.args.extend(["-I".into(), v.to_string()])
                }
                "batch" => {
                    o.batch = spec.integer(k, v)?;
                    if !(1..=1000).contains(&o.batch) {
                        return Err(spec.bad(k, v, "expected 1–1000 patches").into());
                    }
                }
                "timeout" => {
                    o.timeout = spec.seconds(k, v)?;
                    if o.timeout > Duration::from_secs(3600) {
                        return Err(spec.bad(k, v, "at most 3600 s").into());
                    }
                }
                "arg" => o.args.push(word(v)?),
                _ => {
                    return Err(spec.unknown(
                        k,
                        "c=N, y=X, x=FILE, q=OBS, fixed, rate=HZ, hires, drift=b|w|bw, batch=N, timeout=SECS, arg=A",
                    ).into())
                }
            }
        }
        Ok(o)
    }
}

/// Finds `name` on `PATH`.
pub fn find_program(name: &str) -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .map(|d| d.join(name))
        .find(|p| p.is_file())
}

/// `dispread` measuring batches of patches.
pub struct Dispread {
    program: PathBuf,
    display: DisplayOptions,
    options: ArgyllOptions,
    dir: tempfile::TempDir,
    settle: Option<Duration>,
    instrument_name: Option<String>,
    runs: usize,
}

/// Kills a child on drop (a run stopped by an error or Ctrl-C leaves no `dispread` behind).
struct Reaper(std::process::Child);

impl Drop for Reaper {
    fn drop(&mut self) {
        if let Ok(None) = self.0.try_wait() {
            let _ = self.0.kill();
        }
        let _ = self.0.wait();
    }
}

impl Dispread {
    /// Checks that `dispread` is installed, parses the options and makes the private working
    /// folder (see the module docs; removed when done). `settle` sets ArgyllCMS's minimum
    /// display update delay (`ARGYLL_MIN_DISPLAY_UPDATE_DELAY_MS`).
    pub fn open(instrument: &str, display: &str, settle: Option<Duration>) -> Result<Self> {
        use std::os::unix::fs::PermissionsExt;
        let options = ArgyllOptions::parse(instrument)?;
        let display = DisplayOptions::parse(display)?;
        let program =
            find_program("dispread").ok_or(InstrumentError::NotInstalled { package: PACKAGE })?;
        let tmp = std::env::temp_dir();
        let dir = tempfile::Builder::new()
            .prefix("specpoly-argyll-")
            .permissions(std::fs::Permissions::from_mode(0o700))
            .tempdir_in(&tmp)
            .map_err(|e| Error::io(&tmp, e))?;
        if let ArgyllDisplay::Fake(Some(icc)) = &display.display {
            // ArgyllCMS looks for `fake.icc` on Unix and macOS, `fake.icm` on Windows
            let to = dir.path().join(if cfg!(windows) {
                "fake.icm"
            } else {
                "fake.icc"
            });
            std::fs::copy(icc, &to).map_err(|e| Error::io(icc, e))?;
        }
        Ok(Self {
            program,
            display,
            options,
            dir,
            settle,
            instrument_name: None,
            runs: 0,
        })
    }

    /// One line: what measures and where the patches are.
    pub fn describe(&self) -> String {
        let what = self
            .instrument_name
            .clone()
            .unwrap_or_else(|| "the instrument".into());
        let args = self.options.args.join(" ");
        format!(
            "{what} via ArgyllCMS dispread{}{}",
            if args.is_empty() { "" } else { " " },
            args
        )
    }

    /// Where the patches are shown.
    pub fn describe_display(&self) -> String {
        match &self.display.display {
            ArgyllDisplay::Screen(n) => format!("ArgyllCMS's patch window on display {n}"),
            ArgyllDisplay::Web(p) => format!(
                "ArgyllCMS's web display: open http://<this machine>:{}/ in a browser, full screen",
                p.unwrap_or(8080)
            ),
            ArgyllDisplay::Fake(None) => "ArgyllCMS's fake display (built-in model)".into(),
            ArgyllDisplay::Dummy => "no patch window (ArgyllCMS's dummy display)".into(),
            ArgyllDisplay::Fake(Some(p)) => {
                format!("ArgyllCMS's fake display measuring {}", p.display())
            }
        }
    }

    /// The private working folder `dispread` runs in.
    pub fn work_dir(&self) -> &Path {
        self.dir.path()
    }

    /// Patches per `dispread` run.
    pub fn batch(&self) -> usize {
        self.options.batch
    }

    /// Whether this is ArgyllCMS's fake device (nothing to place on a screen).
    pub fn is_fake(&self) -> bool {
        matches!(self.display.display, ArgyllDisplay::Fake(_))
    }

    /// Measures `devices` (each in `[0, 1]`) in one `dispread` run: XYZ in cd/m², in order.
    pub fn measure(&mut self, devices: &[[f64; 3]]) -> Result<Vec<[f64; 3]>> {
        if interrupt::requested() {
            return Err(InstrumentError::Interrupted.into());
        }
        let ti1_path = self.dir.path().join("batch.ti1");
        let ti3_path = self.dir.path().join("batch.ti3");
        let _ = std::fs::remove_file(&ti3_path);
        std::fs::write(
            &ti1_path,
            ti1::write_ti1(devices, "specpoly calibrate run batch"),
        )
        .map_err(|e| Error::io(&ti1_path, e))?;
        let mut cmd = Command::new(&self.program);
        cmd.current_dir(self.dir.path())
            .arg("-v")
            .args(self.display.args())
            .args(&self.options.args)
            // absolute cd/m² (no normalisation to white), don't wait for the instrument to be
            // placed (the user placed it before the first run)
            .args(["-w", "-Y", "p"])
            .arg("batch")
            .stdout(Stdio::piped())
            .stderr(Stdio::piped());
        let interactive = std::io::stdin().is_terminal() && !self.is_fake();
        cmd.stdin(if interactive {
            Stdio::inherit()
        } else {
            Stdio::null()
        });
        if let Some(s) = self.settle {
            cmd.env(
                "ARGYLL_MIN_DISPLAY_UPDATE_DELAY_MS",
                s.as_millis().to_string(),
            );
        }
        let mut child = Reaper(cmd.spawn().map_err(|source| {
            if source.kind() == std::io::ErrorKind::NotFound {
                InstrumentError::NotInstalled { package: PACKAGE }
            } else {
                InstrumentError::Start {
                    program: self.program.clone(),
                    source,
                }
            }
        })?);
        self.runs += 1;
        let (tx, rx) = mpsc::channel::<(bool, Vec<u8>)>();
        let pipes: [(bool, Option<Box<dyn Read + Send>>); 2] = [
            (
                false,
                child
                    .0
                    .stdout
                    .take()
                    .map(|s| Box::new(s) as Box<dyn Read + Send>),
            ),
            (
                true,
                child
                    .0
                    .stderr
                    .take()
                    .map(|s| Box::new(s) as Box<dyn Read + Send>),
            ),
        ];
        for (is_err, pipe) in pipes {
            let Some(mut pipe) = pipe else { continue };
            let tx = tx.clone();
            std::thread::spawn(move || {
                let mut buf = [0u8; 4096];
                loop {
                    match pipe.read(&mut buf) {
                        Ok(0) | Err(_) => break,
                        Ok(n) => {
                            if tx.send((is_err, buf[..n].to_vec())).is_err() {
                                break;
                            }
                        }
                    }
                }
            });
        }
        drop(tx);
        let echo = std::io::stderr().is_terminal();
        let mut errors = String::new();
        let mut last = Instant::now();
        let mut open = true;
        let status = loop {
            match rx.recv_timeout(Duration::from_millis(100)) {
                Ok((is_err, bytes)) => {
                    last = Instant::now();
                    let text = String::from_utf8_lossy(&bytes);
                    if is_err {
                        errors.push_str(&text);
                        if errors.len() > 64 * 1024 {
                            errors.drain(..errors.len() - 32 * 1024);
                        }
                    }
                    if echo {
                        let _ = std::io::stderr().write_all(strip_noise(&text).as_bytes());
                    }
                }
                Err(mpsc::RecvTimeoutError::Disconnected) => open = false,
                Err(mpsc::RecvTimeoutError::Timeout) => {}
            }
            if interrupt::requested() {
                // dispread got the terminal's SIGINT too: give it a moment to release the
                // instrument before the reaper kills it
                let t = Instant::now();
                while t.elapsed() < Duration::from_secs(2) {
                    if let Ok(Some(_)) = child.0.try_wait() {
                        break;
                    }
                    std::thread::sleep(Duration::from_millis(50));
                }
                return Err(InstrumentError::Interrupted.into());
            }
            match child.0.try_wait() {
                Ok(Some(st)) if !open => break st,
                Ok(Some(st)) => {
                    // drain what is left in the pipes, briefly
                    if last.elapsed() > Duration::from_millis(500) {
                        break st;
                    }
                }
                Ok(None) => {}
                Err(e) => return Err(InstrumentError::Wait(e).into()),
            }
            if !open {
                std::thread::sleep(Duration::from_millis(20));
            }
            if last.elapsed() > self.options.timeout {
                return Err(InstrumentError::Silent {
                    seconds: self.options.timeout.as_secs_f64(),
                }
                .into());
            }
        };
        if !status.success() || !ti3_path.is_file() {
            return Err(dispread_failed(&errors, status.code()).into());
        }
        let text = std::fs::read_to_string(&ti3_path).map_err(|e| Error::io(&ti3_path, e))?;
        let t = cgats::read_ti3(&text, "dispread's batch.ti3")?;
        if self.instrument_name.is_none() {
            self.instrument_name = t.keyword("TARGET_INSTRUMENT").map(str::to_string);
        }
        let (m, absolute) = t.best_units();
        if !absolute {
            return Err(InstrumentError::Relative.into());
        }
        if m.len() != devices.len() {
            return Err(InstrumentError::Count {
                got: m.len(),
                asked: devices.len(),
            }
            .into());
        }
        for (k, (m, d)) in m.iter().zip(devices).enumerate() {
            // dispread writes the device values with about five significant digits
            if (0..3).any(|c| (m.device[c] - d[c]).abs() > 1e-4) {
                return Err(InstrumentError::WrongPatch {
                    number: k + 1,
                    got: m.device,
                    asked: *d,
                }
                .into());
            }
        }
        Ok(m.into_iter().map(|m| m.xyz).collect())
    }
}

/// `text` without ArgyllCMS's console warnings when stdin is not a terminal
/// (`poll_con_char: tcgetattr failed with '…' on stdin`, printed without a line end).
pub fn strip_noise(text: &str) -> String {
    const START: &str = "poll_con_char:";
    const END: &str = "on stdin";
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(i) = rest.find(START) {
        out.push_str(&rest[..i]);
        match rest[i..].find(END) {
            Some(j) => rest = &rest[i + j + END.len()..],
            None => {
                rest = "";
            }
        }
    }
    out.push_str(rest);
    out
}

/// One line from `dispread`'s stderr: its last `Error - …` message, with a hint for the
/// common ones.
pub fn argyll_error(stderr: &str, code: Option<i32>) -> String {
    dispread_failed(stderr, code).to_string()
}

/// The error of a failed `dispread` run from its stderr and exit code ([`argyll_error`]).
pub fn dispread_failed(stderr: &str, code: Option<i32>) -> InstrumentError {
    let cleaned = strip_noise(stderr);
    let msg = cleaned
        .lines()
        .rev()
        .find_map(|l| l.split_once("Error - ").map(|(_, m)| m.trim().to_string()))
        .or_else(|| {
            cleaned
                .lines()
                .map(str::trim)
                .rfind(|l| !l.is_empty())
                .map(str::to_string)
        })
        .unwrap_or_else(|| match code {
            Some(c) => format!("exit status {c}"),
            None => "killed by a signal".into(),
        });
    let hint = if msg.contains("Instrument Access Failed") || msg.contains("No ports") {
        " (no instrument found: is it plugged in? `spotread -?` lists the instruments ArgyllCMS sees)"
    } else {
        ""
    };
    InstrumentError::DispreadFailed { said: msg, hint }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_working_folder_is_private_fresh_and_never_a_planted_one() {
        use std::os::unix::fs::{MetadataExt, PermissionsExt};
        let out = tempfile::tempdir().unwrap();
        let profile = out.path().join("display.icc");
        std::fs::write(&profile, b"a profile").unwrap();
        // what another local user could plant where the folder used to be made: the old name
        // beside the readings (`.NAME.ti3.argyllPID`), a symlink to a folder of theirs
        let victim = out.path().join("victim");
        std::fs::create_dir(&victim).unwrap();
        let planted = out
            .path()
            .join(format!(".cal.ti3.argyll{}", std::process::id()));
        std::os::unix::fs::symlink(&victim, &planted).unwrap();
        let display = format!("argyll:fake:{}", profile.display());
        let a = Dispread::open("argyll", &display, None).unwrap();
        let b = Dispread::open("argyll", &display, None).unwrap();
        let dir = a.work_dir().to_path_buf();
        assert_ne!(dir, b.work_dir());
        assert!(!dir.starts_with(out.path()), "{}", dir.display());
        let meta = std::fs::symlink_metadata(&dir).unwrap();
        assert!(meta.is_dir());
        assert_eq!(meta.permissions().mode() & 0o777, 0o700);
        assert_eq!(meta.uid(), std::fs::metadata(out.path()).unwrap().uid());
        // the profile went into the private folder, nothing through the planted link
        assert_eq!(std::fs::read(dir.join("fake.icc")).unwrap(), b"a profile");
        assert_eq!(std::fs::read_dir(&victim).unwrap().count(), 0);
        drop(a);
        assert!(!dir.exists());
    }

    #[test]
    fn parses_options() {
        let o =
            ArgyllOptions::parse("argyll:c=2,y=e,fixed,rate=60,batch=5,timeout=3,arg=-Ib").unwrap();
        assert_eq!(
            o.args,
            ["-c", "2", "-y", "e", "-Y", "A", "-Y", "R:60", "-Ib"].map(String::from)
        );
        assert_eq!(o.batch, 5);
        assert_eq!(o.timeout, Duration::from_secs(3));
        assert_eq!(
            ArgyllOptions::parse("argyll").unwrap().args,
            Vec::<String>::new()
        );
        assert_eq!(ArgyllOptions::parse("argyll,hires").unwrap().args, ["-H"]);
        assert!(ArgyllOptions::parse("argyll:c=0").is_err());
        assert!(ArgyllOptions::parse("argyll:batch=0").is_err());
        assert!(ArgyllOptions::parse("argyll:x=/nonexistent.ccss").is_err());
        assert!(ArgyllOptions::parse("argyll:wat").is_err());
        assert!(ArgyllOptions::parse("serial:x").is_err());
        let d = DisplayOptions::parse("argyll:2,scale=0.5,fill").unwrap();
        assert_eq!(
            d.args(),
            ["-d", "2", "-P", "0.5,0.5,0.5", "-F"].map(String::from)
        );
        assert_eq!(
            DisplayOptions::parse("argyll:web:8081").unwrap().args(),
            ["-dweb:8081"]
        );
        assert_eq!(DisplayOptions::parse("argyll").unwrap().args(), ["-d", "1"]);
        assert!(DisplayOptions::parse("web").is_err());
        assert!(DisplayOptions::parse("argyll:0").is_err());
    }

    #[test]
    fn error_lines() {
        let e = argyll_error(
            "poll_con_char: tcgetattr failed with 'x' on stdindispread: Error - new_disprd failed with 'Instrument Access Failed'\n",
            Some(1),
        );
        assert!(
            e.starts_with("ArgyllCMS dispread failed: new_disprd failed with 'Instrument Access Failed' (no instrument"),
            "{e}"
        );
        assert_eq!(
            argyll_error("", None),
            "ArgyllCMS dispread failed: killed by a signal"
        );
    }
}
