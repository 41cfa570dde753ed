//! `--instrument argyll`: `specpoly calibrate run` against the real ArgyllCMS binaries
//! (Debian package `argyll`, installed by test.sh): the fake device end to end (the command
//! docs/calibration.md gives an i1Display Pro user, with `--display argyll:fake`), a `targen`
//! patch set, our `.ti1` read by `dispread`, ArgyllCMS not installed, no instrument, and an
//! instrument error mid-run followed by `--resume`.
//!
//! The oracle for the fake device is ArgyllCMS's own model of it (spectro/dispsup.c,
//! `disprd_fake_read`): colorants red (0.41, 0.21, 0.02), green (0.30, 0.55, 0.15), blue
//! (0.15, 0.10, 0.97) scaled so they add up to a white of Y = 120 cd/m², input offsets
//! (−0.03, 0.07, −0.08, negative ones cut to 0) before a power of 2.5, an XYZ offset, and
//! uniform noise of at most 0.02, 0.01, 0.04 cd/m² on X, Y, Z. So the readings' primaries
//! (full channel minus black) must have those colorants' chromaticities within [`XY_TOL`],
//! and their luminances, like white minus black, must add up to 120 less green's share at
//! the offset (120 − G·0.07^2.5) within [`Y_TOL`].
//!
//! **Headless machines.** ArgyllCMS looks for USB instruments in `/dev/bus/usb`, then
//! `/proc/bus/usb`, then — if neither has an entry — reads every device node in `/dev`,
//! and blocks forever on a serial port with no carrier (`/dev/ttyS0` in a container). A
//! desktop has `/dev/bus/usb/001…`. Where it is missing, these tests run `specpoly` (and
//! with it `dispread`) in a private mount namespace with an empty `/proc/bus/usb/001`
//! (`unshare -m`, root): what a machine with a USB bus and no instrument on it looks like.
//! Without that, `dispread` hangs — which `no_instrument_…_within_30_s` uses on purpose.

use crate::common::cli;

use specpoly_formats::{cgats, ti1};
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

/// Chromaticity tolerance of the fake device's primaries (its noise is ≤ 0.04 cd/m² on
/// readings of 9–82 cd/m²).
const XY_TOL: f64 = 0.002;
/// Luminance tolerance of the primaries' sum, cd/m² (six readings' noise of ≤ 0.01 each).
const Y_TOL: f64 = 0.1;

struct Done {
    code: Option<i32>,
    stdout: String,
    stderr: String,
    took: Duration,
}

impl std::fmt::Debug for Done {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "exit {:?} after {:.1} s\n--- stdout\n{}--- stderr\n{}",
            self.code,
            self.took.as_secs_f64(),
            self.stdout,
            self.stderr
        )
    }
}

/// Whether ArgyllCMS's USB scan stops at a bus directory on this machine.
fn usb_bus_present() -> bool {
    ["/dev/bus/usb", "/proc/bus/usb"].iter().any(|d| {
        std::fs::read_dir(d)
            .map(|mut r| r.next().is_some())
            .unwrap_or(false)
    })
}

/// A command running `program args` where ArgyllCMS's device scan cannot hang (see the module
/// docs); `fakebus` is a directory to build the stand-in `/proc/bus` in.
fn contained(program: &Path, fakebus: &Path) -> Command {
    if usb_bus_present() {
        return Command::new(program);
    }
    std::fs::create_dir_all(fakebus.join("usb/001")).unwrap();
    let mut c = Command::new("unshare");
    c.args([
        "-m",
        "sh",
        "-c",
        "mount --bind \"$0\" /proc/bus && exec \"$@\"",
    ])
    .arg(fakebus)
    .arg(program);
    c
}

/// Runs `cmd` in `dir` with a deadline, collecting its output.
fn run(mut cmd: Command, dir: &Path, timeout: Duration) -> Done {
    let t = Instant::now();
    let mut child = cli::spawn_piped(cmd.current_dir(dir));
    drop(child.stdin.take());
    let mut out = child.stdout.take().unwrap();
    let mut err = child.stderr.take().unwrap();
    let o = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = out.read_to_string(&mut s);
        s
    });
    let e = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = err.read_to_string(&mut s);
        s
    });
    let code = loop {
        if let Some(st) = child.try_wait().unwrap() {
            break st.code();
        }
        if t.elapsed() > timeout {
            let _ = child.kill();
            let _ = child.wait();
            break None;
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    Done {
        code,
        stdout: o.join().unwrap(),
        stderr: e.join().unwrap(),
        took: t.elapsed(),
    }
}

/// `program ARGS`, not contained.
fn command(program: impl AsRef<std::ffi::OsStr>, args: &[&str]) -> Command {
    let mut c = Command::new(program);
    c.args(args);
    c
}

fn specpoly() -> PathBuf {
    PathBuf::from(env!("CARGO_BIN_EXE_specpoly"))
}

/// `specpoly ARGS` in `dir`, contained.
fn specpoly_run(dir: &Path, args: &[&str], timeout: Duration) -> Done {
    let mut c = contained(&specpoly(), &dir.join("fakebus"));
    c.args(args);
    run(c, dir, timeout)
}

/// A reading: device values (0–1) and XYZ (cd/m²).
type Reading = ([f64; 3], [f64; 3]);

/// The readings of a .ti3 in cd/m².
fn readings(path: &Path) -> (cgats::Ti3, Vec<Reading>) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let t = cgats::read_ti3(&text, &path.display().to_string()).unwrap();
    let (m, absolute) = t.best_units();
    assert!(absolute, "{}: not absolute", path.display());
    let r = m.iter().map(|m| (m.device, m.xyz)).collect();
    (t, r)
}

fn find(r: &[Reading], d: [f64; 3]) -> [f64; 3] {
    r.iter()
        .find(|(dev, _)| dev.iter().zip(&d).all(|(a, b)| (a - b).abs() < 1e-9))
        .unwrap_or_else(|| panic!("no reading of {d:?}"))
        .1
}

fn xy(v: [f64; 3]) -> [f64; 2] {
    let s = v[0] + v[1] + v[2];
    [v[0] / s, v[1] / s]
}

#[test]
fn fake_device_end_to_end() {
    let dir = tempfile::tempdir().unwrap();
    // the command of docs/calibration.md, with ArgyllCMS's fake device for the display
    let done = specpoly_run(
        dir.path(),
        &cli::calibrate_run("argyll:fake", "argyll", &[], "fake.toml"),
        Duration::from_secs(120),
    );
    assert_eq!(done.code, Some(0), "{done:?}");
    assert!(dir.path().join("fake.toml").is_file());
    let (t, r) = readings(&dir.path().join("fake.ti3"));
    assert_eq!(r.len(), 49, "{done:?}");
    assert!(
        t.keyword("TARGET_INSTRUMENT").unwrap().starts_with("Fake"),
        "{:?}",
        t.keyword("TARGET_INSTRUMENT")
    );
    // no working directory left behind
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .filter(|n| n.contains("argyll"))
        .collect();
    assert!(left.is_empty(), "{left:?}");
    // ArgyllCMS's fake display model (dispsup.c)
    let black = find(&r, [0.0; 3]);
    let white = find(&r, [1.0; 3]);
    let colorants = [[0.41, 0.21, 0.02], [0.30, 0.55, 0.15], [0.15, 0.10, 0.97]];
    for (ch, c) in colorants.iter().enumerate() {
        let mut d = [0.0; 3];
        d[ch] = 1.0;
        let full = find(&r, d);
        let p = xy([0, 1, 2].map(|k| full[k] - black[k]));
        let want = xy(*c);
        for k in 0..2 {
            assert!(
                (p[k] - want[k]).abs() < XY_TOL,
                "channel {ch}: xy {p:?} vs ArgyllCMS's {want:?}"
            );
        }
    }
    // the colorants are scaled to add up to the white, Y = 120 cd/m²; black is the green
    // colorant at its input offset 0.07 (red's and blue's are negative, cut to 0), to the
    // power 2.5, so full green minus black lacks that much of green
    let g = 0.07f64.powf(2.5);
    let prim: Vec<f64> = (0..3)
        .map(|ch| {
            let mut d = [0.0; 3];
            d[ch] = 1.0;
            find(&r, d)[1] - black[1]
        })
        .collect();
    let want = 120.0 - prim[1] / (1.0 - g) * g;
    let sum: f64 = prim.iter().sum();
    assert!(
        (sum - want).abs() < Y_TOL,
        "R + G + B − 3·black: Y = {sum}, model {want}"
    );
    let wk = white[1] - black[1];
    assert!(
        (wk - want).abs() < Y_TOL,
        "white − black: Y = {wk}, model {want}"
    );
    // the fit says the same
    let cal = specpoly_display::calibration::load(&dir.path().join("fake.toml")).unwrap();
    let red = cal.data().primaries.red;
    assert!((red.x - 0.41 / 0.64).abs() < XY_TOL, "{red:?}");
    // running again refuses to overwrite the readings
    let again = specpoly_run(
        dir.path(),
        &cli::calibrate_run("argyll:fake", "argyll", &[], "fake.toml"),
        Duration::from_secs(60),
    );
    assert_eq!(again.code, Some(2), "{again:?}");
    assert!(again.stderr.contains("already exists"), "{again:?}");
}

#[test]
fn targen_patch_set_measured_through_dispread() {
    let dir = tempfile::tempdir().unwrap();
    let g = run(
        command("targen", &["-d3", "-f24", "set"]),
        dir.path(),
        Duration::from_secs(60),
    );
    assert_eq!(g.code, Some(0), "{g:?}");
    let set = ti1::read_ti1(
        &std::fs::read_to_string(dir.path().join("set.ti1")).unwrap(),
        "set.ti1",
    )
    .unwrap();
    assert_eq!(set.len(), 24);
    let done = specpoly_run(
        dir.path(),
        &cli::calibrate_run(
            "argyll:fake",
            "argyll:batch=5",
            &["--patches", "set.ti1"],
            "t.toml",
        ),
        Duration::from_secs(120),
    );
    assert_eq!(done.code, Some(0), "{done:?}");
    let (_, r) = readings(&dir.path().join("t.ti3"));
    assert_eq!(r.len(), 24);
    for ((d, _), want) in r.iter().zip(&set) {
        for k in 0..3 {
            assert!((d[k] - want[k]).abs() < 1e-6, "{d:?} vs {want:?}");
        }
    }
    // a CTI1 given as measurements is refused
    let fit = run(
        command(
            specpoly(),
            &["calibrate", "fit", "--ti3", "set.ti1", "-o", "x.toml"],
        ),
        dir.path(),
        Duration::from_secs(30),
    );
    assert_eq!(fit.code, Some(1), "{fit:?}");
    assert!(fit.stderr.contains("CTI1 patch set"), "{fit:?}");
    assert_eq!(fit.stderr.trim().lines().count(), 1, "{fit:?}");
    assert!(!dir.path().join("x.toml").exists());
}

#[test]
fn our_ti1_is_read_by_dispread() {
    let dir = tempfile::tempdir().unwrap();
    let w = run(
        command(
            specpoly(),
            &[
                "calibrate",
                "patches",
                "--ramp-steps",
                "3",
                "--verify",
                "2",
                "-o",
                "ours.ti1",
            ],
        ),
        dir.path(),
        Duration::from_secs(30),
    );
    assert_eq!(w.code, Some(0), "{w:?}");
    assert!(w.stderr.contains("wrote ours.ti1"), "{w:?}");
    let n = specpoly_calibrate::patches::standard(3, 2).unwrap().len();
    let mut c = contained(Path::new("/usr/bin/dispread"), &dir.path().join("fakebus"));
    c.args(["-w", "-dfake", "ours"]);
    let d = run(c, dir.path(), Duration::from_secs(60));
    assert_eq!(d.code, Some(0), "{d:?}");
    let (_, r) = readings(&dir.path().join("ours.ti3"));
    assert_eq!(r.len(), n);
}

#[test]
fn argyll_not_installed_is_one_line_naming_the_package() {
    let dir = tempfile::tempdir().unwrap();
    let mut c = command(
        specpoly(),
        &cli::calibrate_run("argyll:fake", "argyll", &[], "x.toml"),
    );
    c.env("PATH", dir.path());
    let done = run(c, dir.path(), Duration::from_secs(30));
    assert_eq!(done.code, Some(1), "{done:?}");
    let e = done.stderr.trim();
    assert_eq!(e.lines().count(), 1, "{e}");
    assert!(e.contains("apt install argyll"), "{e}");
    assert!(!dir.path().join("x.ti3").exists());
}

#[test]
fn no_instrument_is_a_clear_error_within_30_s() {
    // not contained: on a machine without a USB bus ArgyllCMS's scan blocks on a serial
    // port, and the watchdog stops it; elsewhere dispread finds no instrument and says so
    let dir = tempfile::tempdir().unwrap();
    let c = command(
        specpoly(),
        &cli::calibrate_run("argyll:dummy", "argyll:timeout=5", &[], "x.toml"),
    );
    let done = run(c, dir.path(), Duration::from_secs(60));
    assert_eq!(done.code, Some(1), "{done:?}");
    assert!(done.took < Duration::from_secs(30), "{done:?}");
    let e = done.stderr.trim();
    assert_eq!(e.lines().count(), 1, "{e}");
    assert!(
        e.contains("said nothing for 5 s") || e.contains("no instrument found"),
        "{e}"
    );
    assert!(e.contains("no readings taken"), "{e}");
}

#[test]
fn no_instrument_contained_is_argylls_own_error() {
    // contained: the scan finishes, dispread tries the serial ports and gives up
    let dir = tempfile::tempdir().unwrap();
    let done = specpoly_run(
        dir.path(),
        &cli::calibrate_run("argyll:dummy", "argyll:timeout=25", &[], "x.toml"),
        Duration::from_secs(60),
    );
    assert_eq!(done.code, Some(1), "{done:?}");
    assert!(done.took < Duration::from_secs(30), "{done:?}");
    let e = done.stderr.trim();
    assert_eq!(e.lines().count(), 1, "{e}");
    assert!(
        e.contains("Instrument Access Failed") || e.contains("said nothing for 25 s"),
        "{e}"
    );
}

/// A measuring command for `dispread -M` (ArgyllCMS's external-instrument callout): XYZ of
/// a gamma-2.2 display with fixed primaries, written to `SCRIPT.meas`; it fails (exit 1) on
/// call number `limit` and later, counting calls in `SCRIPT.count`.
fn callout(dir: &Path, limit: usize) -> PathBuf {
    let p = dir.join("meter.sh");
    let script = format!(
        r#"#!/bin/sh
n=$(cat "$0.count" 2>/dev/null || echo 0)
n=$((n + 1))
echo $n > "$0.count"
[ $n -ge {limit} ] && exit 1
awk -v r="$4" -v g="$5" -v b="$6" 'BEGIN {{
  R = r ^ 2.2; G = g ^ 2.2; B = b ^ 2.2
  printf "%.6f %.6f %.6f\n", 41.24*R + 35.76*G + 18.05*B + 0.2, 21.26*R + 71.52*G + 7.22*B + 0.2, 1.93*R + 11.92*G + 95.05*B + 0.2
}}' > "$0.meas"
"#
    );
    std::fs::write(&p, script).unwrap();
    let _ = std::fs::remove_file(dir.join("meter.sh.count"));
    assert!(Command::new("chmod")
        .arg("+x")
        .arg(&p)
        .status()
        .unwrap()
        .success());
    p
}

fn meter_xyz(d: [f64; 3]) -> [f64; 3] {
    let l = d.map(|v| v.powf(2.2));
    [
        41.24 * l[0] + 35.76 * l[1] + 18.05 * l[2] + 0.2,
        21.26 * l[0] + 71.52 * l[1] + 7.22 * l[2] + 0.2,
        1.93 * l[0] + 11.92 * l[1] + 95.05 * l[2] + 0.2,
    ]
}

#[test]
fn instrument_error_mid_run_keeps_finished_batches_and_resume_completes() {
    let dir = tempfile::tempdir().unwrap();
    let meter = callout(dir.path(), 11);
    let inst = format!("argyll:batch=4,arg=-M,arg={}", meter.display());
    let args = cli::calibrate_run("argyll:fake", &inst, &[], "m.toml");
    let done = specpoly_run(dir.path(), &args, Duration::from_secs(120));
    assert_eq!(done.code, Some(1), "{done:?}");
    let e = done.stderr.trim();
    assert_eq!(e.lines().count(), 1, "{e}");
    assert!(e.contains("patches 9–12 of 49"), "{e}");
    assert!(e.contains("ArgyllCMS dispread failed"), "{e}");
    assert!(e.contains("8 readings kept in m.ti3"), "{e}");
    let (_, first) = readings(&dir.path().join("m.ti3"));
    assert_eq!(first.len(), 8);
    // the instrument works again: --resume measures the other 41
    callout(dir.path(), 1000);
    let mut resumed = args.to_vec();
    resumed.push("--resume");
    let done = specpoly_run(dir.path(), &resumed, Duration::from_secs(120));
    assert_eq!(done.code, Some(0), "{done:?}");
    assert!(done.stderr.contains("8 of 49 patches measured"), "{done:?}");
    let (_, all) = readings(&dir.path().join("m.ti3"));
    assert_eq!(all.len(), 49);
    let set = specpoly_calibrate::patches::standard(9, 16).unwrap();
    for ((d, x), p) in all.iter().zip(&set) {
        // device values as the .ti3 writes them (0–100, five decimals)
        for k in 0..3 {
            assert!((d[k] - p.device[k]).abs() < 1e-7, "{d:?} vs {:?}", p.device);
        }
        // the meter's own XYZ, to its six decimals (and the .ti3's seven digits)
        let want = meter_xyz(*d);
        for k in 0..3 {
            assert!(
                (x[k] - want[k]).abs() < 1e-5 * want[k].max(1.0),
                "{d:?}: {x:?} vs {want:?}"
            );
        }
    }
    for (a, b) in first.iter().zip(&all) {
        assert_eq!(a.0, b.0);
    }
}

#[test]
fn dispread_reads_our_ccss_and_ccmx() {
    // ArgyllCMS reads a correction with `-X` before it opens the instrument, and refuses one
    // its reader (xicc/ccss.c, xicc/ccmx.c) cannot parse: with the fake device the run then
    // completes, with a file it cannot read it stops with "Reading CCMX/CCSS File … failed"
    let dir = tempfile::tempdir().unwrap();
    for args in [
        vec![
            "calibrate",
            "simulate",
            "--display",
            "sim:qdoled",
            "-o",
            "ref.ti3",
        ],
        vec![
            "calibrate",
            "simulate",
            "--display",
            "sim:qdoled",
            "--instrument",
            "colorimeter",
            "-o",
            "col.ti3",
        ],
        vec![
            "calibrate",
            "ccss",
            "--ti3",
            "ref.ti3",
            "--technology",
            "OLED",
            "-o",
            "ours.ccss",
        ],
        vec![
            "calibrate",
            "ccmx",
            "--reference",
            "ref.ti3",
            "--colorimeter",
            "col.ti3",
            "-o",
            "ours.ccmx",
        ],
        vec![
            "calibrate",
            "patches",
            "--ramp-steps",
            "2",
            "--verify",
            "0",
            "-o",
            "p.ti1",
        ],
    ] {
        let w = run(
            command(specpoly(), &args),
            dir.path(),
            Duration::from_secs(30),
        );
        assert_eq!(w.code, Some(0), "{args:?}: {w:?}");
    }
    std::fs::write(dir.path().join("bad.ccmx"), "CCMX\n\nDESCRIPTOR \"x\"\n").unwrap();
    for (file, ok) in [
        ("ours.ccss", true),
        ("ours.ccmx", true),
        ("bad.ccmx", false),
    ] {
        let name = format!("run_{}", file.replace('.', "_"));
        std::fs::copy(
            dir.path().join("p.ti1"),
            dir.path().join(format!("{name}.ti1")),
        )
        .unwrap();
        let mut c = contained(Path::new("/usr/bin/dispread"), &dir.path().join("fakebus"));
        c.args(["-w", "-dfake", "-X", file, &name]);
        let d = run(c, dir.path(), Duration::from_secs(60));
        if ok {
            assert_eq!(d.code, Some(0), "{file}: {d:?}");
            assert!(dir.path().join(format!("{name}.ti3")).exists(), "{d:?}");
        } else {
            assert_ne!(d.code, Some(0), "{d:?}");
            assert!(d.stderr.contains("Reading CCMX/CCSS File"), "{d:?}");
        }
    }
}
