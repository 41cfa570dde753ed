//! The video LUT loaded into a real graphics stack: a headless X server (Xvfb) whose RandR CRTC
//! has a 256-entry gamma ramp, loaded and read back by ArgyllCMS's `dispwin` (the loader
//! `dispcal`/DisplayCAL use), never by our code. `calibrate run --target` calibrates a
//! simulated display whose native white is far from D65 (so the LUT is far from the
//! identity); `dispwin` loads the `.cal` we write, then the `vcgt` of the profile
//! `calibrate icc` writes, and `dispwin -s` saves the ramp the server holds; each equals the
//! calibration's `[video_lut]` within [`QUANT`]. `dispwin -c` then leaves the identity ramp.
//! Without Xvfb or ArgyllCMS this test fails (never skips): `apt-get install xvfb argyll`.
//!
//! Two things about the server, found while writing this test:
//! - Xvfb must run with `-noreset`. An X server resets when its last client disconnects (each
//!   `dispwin` is one client), and the reset re-creates the RandR CRTC, whose ramp
//!   `RRCrtcGammaSetSize` allocates with `malloc` and never initialises. The block is usually
//!   the one just freed, so the previous ramp survives except its first 32 bytes (red entries
//!   0–15), where glibc's allocator has written its free-list pointers (the "garbage" values
//!   are Xvfb's own heap and libc addresses). Neither ArgyllCMS nor the `.cal` is at fault.
//! - The display number comes from `-displayfd 1` (Xvfb picks a free one and writes it on its
//!   standard output), Xvfb runs under `timeout` (it cannot outlive the test by more than
//!   [`XVFB_LIFE`]), and a guard ends its process group on every path out of the test.

use crate::common::calibrate_run as common;

use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// The largest difference between a ramp entry read back and our LUT's: the server holds
/// 16-bit entries (`dispwin` stores `⌊v·65535 + ½⌋`, and our `vcgt` holds the same 16-bit
/// codes), at most half a step off, 1/131 070; `dispwin -s` prints six significant digits
/// (`%g`), at most 5·10⁻⁷ off in `[0, 1]`; plus 10⁻⁹ for the f64 arithmetic.
const QUANT: f64 = 0.5 / 65535.0 + 0.5e-6 + 1e-9;
/// How long the Xvfb may live at most (`timeout`), whatever happens to the test.
const XVFB_LIFE: &str = "300";
/// Each `dispwin` call's limit (`timeout`).
const DISPWIN_LIFE: &str = "30";

/// A headless X server, ended (its whole process group) when dropped.
struct Xvfb {
    /// `timeout`, the leader of the process group Xvfb runs in.
    child: Child,
    /// `:N`.
    display: String,
}

impl Xvfb {
    fn start() -> Self {
        let mut child = Command::new("timeout")
            .args([
                XVFB_LIFE,
                "Xvfb",
                "-displayfd",
                "1",
                "-noreset",
                "-nolisten",
            ])
            .args(["tcp", "-screen", "0", "640x480x24"])
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("start Xvfb (apt-get install xvfb)");
        let out = child.stdout.take().unwrap();
        let mut err = child.stderr.take().unwrap();
        let (tx, rx) = mpsc::channel();
        std::thread::spawn(move || {
            let mut line = String::new();
            let _ = BufReader::new(out).read_line(&mut line);
            let _ = tx.send(line);
        });
        let log = std::thread::spawn(move || {
            let mut s = String::new();
            let _ = err.read_to_string(&mut s);
            s
        });
        // the guard exists before anything can fail
        let mut x = Xvfb {
            child,
            display: String::new(),
        };
        match rx.recv_timeout(Duration::from_secs(30)) {
            Ok(n) if n.trim().parse::<u32>().is_ok() => x.display = format!(":{}", n.trim()),
            got => {
                drop(x);
                panic!(
                    "Xvfb gave no display number within 30 s ({got:?}); its log: {}",
                    log.join().unwrap_or_default()
                );
            }
        }
        x
    }

    /// `timeout 30 dispwin -d1 ARGS` on this server; its stdout (the call must succeed).
    fn dispwin(&self, args: &[&str]) -> String {
        let out = Command::new("timeout")
            .args([DISPWIN_LIFE, "dispwin", "-d1"])
            .args(args)
            .env("DISPLAY", &self.display)
            .stdin(Stdio::null())
            .output()
            .expect("run dispwin (apt-get install argyll)");
        let text = |b: &[u8]| String::from_utf8_lossy(b).into_owned();
        assert!(
            out.status.success(),
            "dispwin {args:?}: {:?}\n{}\n{}",
            out.status,
            text(&out.stdout),
            text(&out.stderr)
        );
        text(&out.stdout) + &text(&out.stderr)
    }

    /// The ramp the server holds now (`dispwin -s`), as three tables.
    fn ramp(&self, dir: &Path, name: &str) -> [Vec<f64>; 3] {
        let file = dir.join(name);
        self.dispwin(&["-s", file.to_str().unwrap()]);
        read_ramp(&file)
    }
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        // `timeout` leads the group and passes TERM on to Xvfb; KILL if they are still there
        let group = format!("-{}", self.child.id());
        let _ = Command::new("kill").args(["-TERM", "--", &group]).status();
        let deadline = Instant::now() + Duration::from_secs(5);
        while Instant::now() < deadline {
            if let Ok(Some(_)) = self.child.try_wait() {
                return;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        let _ = Command::new("kill").args(["-KILL", "--", &group]).status();
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// The `RGB_R RGB_G RGB_B` columns of the `.cal` `dispwin -s` writes (read here, not with the
/// project's CGATS reader: this file is the oracle's answer).
fn read_ramp(path: &Path) -> [Vec<f64>; 3] {
    let text = std::fs::read_to_string(path).unwrap();
    let format = text
        .split("BEGIN_DATA_FORMAT")
        .nth(1)
        .and_then(|s| s.split("END_DATA_FORMAT").next())
        .expect("a data format");
    let fields: Vec<&str> = format.split_whitespace().collect();
    let col = |name: &str| fields.iter().position(|f| *f == name).unwrap();
    let cols = [col("RGB_R"), col("RGB_G"), col("RGB_B")];
    let data = text
        .split("\nBEGIN_DATA\n")
        .nth(1)
        .and_then(|s| s.split("END_DATA").next())
        .expect("a data block");
    let mut ramp: [Vec<f64>; 3] = Default::default();
    for row in data.lines().filter(|l| !l.trim().is_empty()) {
        let v: Vec<f64> = row.split_whitespace().map(|x| x.parse().unwrap()).collect();
        for (t, &c) in ramp.iter_mut().zip(&cols) {
            t.push(v[c]);
        }
    }
    ramp
}

/// The largest difference between a ramp read back and `want`.
fn worst(ramp: &[Vec<f64>; 3], want: [&[f64]; 3]) -> f64 {
    let mut w = 0.0f64;
    for (got, want) in ramp.iter().zip(want) {
        assert_eq!(got.len(), want.len(), "ramp size");
        for (g, x) in got.iter().zip(want) {
            w = w.max((g - x).abs());
        }
    }
    w
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn the_cal_and_the_profile_vcgt_load_into_the_x_server_ramp() {
    let dir = tempfile::tempdir().unwrap();
    let cal: PathBuf = dir.path().join("cool.toml");
    // native white x 0.28, y 0.29: Δxy 0.05 from D65, so every channel's LUT moves
    let spec = "sim:crt,white_xy=0.28:0.29,gamma=2.4,black=0.3,noise=0.001,seed=5";
    let done = common::calibrate(
        spec,
        "sim",
        &["--target", "white=D65,gamma=2.2"],
        s(&cal),
        Duration::from_secs(120),
    );
    assert_eq!(done.code, Some(0), "{done:?}");
    let icc = dir.path().join("cool.icc");
    let made = common::cli::run(&["calibrate", "icc", s(&cal), "-o", s(&icc)]);
    assert_eq!(made.code, 0, "{made:?}");
    let c = specpoly_display::calibration::load(&cal).unwrap();
    let lut = c
        .video_lut()
        .expect("the calibration holds the LUT")
        .clone();
    assert_eq!(
        lut.len(),
        256,
        "the LUT matches the server's 256-entry ramp"
    );
    let identity: Vec<f64> = (0..256).map(|k| k as f64 / 255.0).collect();
    let id = [&identity[..]; 3];
    let moved = worst(&[lut.red.clone(), lut.green.clone(), lut.blue.clone()], id);
    assert!(moved > 0.05, "the LUT is nearly the identity ({moved})");

    let x = Xvfb::start();
    // the `.cal` calibrate run wrote
    x.dispwin(&[s(&dir.path().join("cool.cal"))]);
    let w = worst(&x.ramp(dir.path(), "after_cal.cal"), lut.tables());
    println!("the .cal: ramp read back against the LUT: max {w:.2e} (bound {QUANT:.2e})");
    assert!(w <= QUANT, "the .cal loaded: {w} > {QUANT}");
    // `-c` clears it
    x.dispwin(&["-c"]);
    let w = worst(&x.ramp(dir.path(), "cleared.cal"), id);
    println!("dispwin -c: ramp against the identity: max {w:.2e}");
    assert!(w <= QUANT, "dispwin -c left {w} from the identity");
    let v = x.dispwin(&["-V", s(&icc)]);
    assert!(v.contains("is NOT loaded"), "{v}");
    // the profile's vcgt
    x.dispwin(&[s(&icc)]);
    let w = worst(&x.ramp(dir.path(), "after_icc.cal"), lut.tables());
    println!("the profile's vcgt: ramp read back against the LUT: max {w:.2e}");
    assert!(w <= QUANT, "the vcgt loaded: {w} > {QUANT}");
    let v = x.dispwin(&["-V", s(&icc)]);
    assert!(v.contains("IS loaded"), "{v}");
    x.dispwin(&["-c"]);
    let w = worst(&x.ramp(dir.path(), "cleared2.cal"), id);
    assert!(w <= QUANT, "dispwin -c left {w} from the identity");
}
