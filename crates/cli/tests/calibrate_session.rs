//! Never lose a measurement: `calibrate run` refuses to overwrite a `.ti3`, `--force` keeps
//! it as a numbered backup, `--resume` measures only what is missing (and refuses another
//! patch set), and a run stopped by Ctrl-C or `SIGKILL` — at any instant, also in the middle
//! of rewriting the file — leaves a valid `.ti3` that `--resume` completes. The oracle is an
//! uninterrupted run of the same noiseless simulated display: the completed file must hold
//! the same readings.

use crate::common::calibrate_run as common;

use specpoly_formats::cgats;
use std::path::Path;
use std::time::{Duration, Instant};

/// The same reading after a write and a read back: the .ti3 keeps seven decimals of
/// XYZ normalised to white Y = 100.
const TOL: f64 = 1e-6;

fn rows(path: &Path) -> Vec<([f64; 3], [f64; 3])> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let t = cgats::read_ti3(&text, &path.display().to_string())
        .unwrap_or_else(|e| panic!("a torn .ti3: {e}\n{text}"));
    let (m, abs) = t.best_units();
    assert!(abs);
    m.iter().map(|m| (m.device, m.xyz)).collect()
}

fn args<'a>(cal: &'a str, extra: &[&'a str]) -> Vec<&'a str> {
    let mut v = vec![
        "calibrate",
        "run",
        "--display",
        "sim:crt,black=0.3",
        "--instrument",
        "sim",
        "-o",
        cal,
    ];
    v.extend_from_slice(extra);
    v
}

fn signal(pid: u32, sig: &str) {
    let ok = std::process::Command::new("kill")
        .args([sig, &pid.to_string()])
        .status()
        .unwrap()
        .success();
    assert!(ok, "kill {sig} {pid}");
}

fn same(a: &[([f64; 3], [f64; 3])], b: &[([f64; 3], [f64; 3])]) {
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(b) {
        assert_eq!(x.0, y.0);
        for k in 0..3 {
            assert!(
                (x.1[k] - y.1[k]).abs() <= TOL * y.1[k].abs().max(1.0),
                "{x:?} vs {y:?}"
            );
        }
    }
}

#[test]
fn refuse_then_force_keeps_numbered_backups() {
    let dir = tempfile::tempdir().unwrap();
    let cal = dir.path().join("c.toml");
    let c = cal.to_str().unwrap();
    let quick = ["--ramp-steps", "3", "--verify", "1"];
    let done = common::run(&args(c, &quick), Duration::from_secs(60));
    assert_eq!(done.code, Some(0), "{done:?}");
    let ti3 = dir.path().join("c.ti3");
    let before = std::fs::read(&ti3).unwrap();
    let done = common::run(&args(c, &quick), Duration::from_secs(60));
    assert_eq!(done.code, Some(2), "{done:?}");
    assert!(done.stderr.contains("already exists"), "{done:?}");
    assert!(done.stderr.contains("--resume"), "{done:?}");
    assert_eq!(std::fs::read(&ti3).unwrap(), before);
    for n in 1..=2 {
        let done = common::run(
            &args(c, &[&quick[..], &["--force"]].concat()),
            Duration::from_secs(60),
        );
        assert_eq!(done.code, Some(0), "{done:?}");
        assert!(done.stderr.contains(&format!("c.ti3.{n}")), "{done:?}");
    }
    assert_eq!(std::fs::read(dir.path().join("c.ti3.1")).unwrap(), before);
    assert!(dir.path().join("c.ti3.2").is_file());
    // --resume and --force together are a usage error
    let done = common::run(&args(c, &["--resume", "--force"]), Duration::from_secs(60));
    assert_eq!(done.code, Some(2), "{done:?}");
}

#[test]
fn ctrl_c_keeps_the_readings_and_resume_completes_them() {
    let dir = tempfile::tempdir().unwrap();
    // the oracle: an uninterrupted run
    let clean = dir.path().join("clean.toml");
    let done = common::run(&args(clean.to_str().unwrap(), &[]), Duration::from_secs(60));
    assert_eq!(done.code, Some(0), "{done:?}");
    let want = rows(&dir.path().join("clean.ti3"));

    let cal = dir.path().join("c.toml");
    let c = cal.to_str().unwrap();
    let run = common::start(&args(c, &["--settle", "40"]));
    std::thread::sleep(Duration::from_millis(600));
    signal(run.pid(), "-INT");
    let done = run.finish(Duration::from_secs(30));
    let e = done.one_line_error(1);
    assert!(e.contains("interrupted (Ctrl-C)"), "{e}");
    assert!(e.contains("--resume"), "{e}");
    assert!(!cal.exists());
    let part = rows(&dir.path().join("c.ti3"));
    assert!(
        !part.is_empty() && part.len() < want.len(),
        "{}",
        part.len()
    );
    same(&part, &want[..part.len()]);

    // another patch set is refused
    let done = common::run(
        &args(c, &["--resume", "--ramp-steps", "5"]),
        Duration::from_secs(60),
    );
    assert_eq!(done.code, Some(2), "{done:?}");
    assert!(done.stderr.contains("another patch set"), "{done:?}");

    let done = common::run(&args(c, &["--resume"]), Duration::from_secs(60));
    assert_eq!(done.code, Some(0), "{done:?}");
    assert!(
        done.stderr.contains(&format!(
            "{} of {} patches measured",
            part.len(),
            want.len()
        )),
        "{done:?}"
    );
    same(&rows(&dir.path().join("c.ti3")), &want);
    assert!(cal.is_file());
}

#[test]
fn sigkill_at_any_instant_leaves_a_valid_ti3() {
    let dir = tempfile::tempdir().unwrap();
    // many patches, each followed by a whole-file rewrite: kills land in the middle of writes
    let extra = ["--ramp-steps", "48", "--verify", "40", "--settle", "3"];
    let clean = dir.path().join("clean.toml");
    let done = common::run(
        &args(clean.to_str().unwrap(), &extra),
        Duration::from_secs(120),
    );
    assert_eq!(done.code, Some(0), "{done:?}");
    let want = rows(&dir.path().join("clean.ti3"));

    let cal = dir.path().join("k.toml");
    let c = cal.to_str().unwrap();
    let ti3 = dir.path().join("k.ti3");
    let mut have = 0;
    for (round, ms) in [60u64, 80, 100, 120, 140].iter().enumerate() {
        let mut a = args(c, &extra);
        if round > 0 {
            a.push("--resume");
        }
        let run = common::start(&a);
        let t = Instant::now();
        // wait until it measures, then kill without warning
        while !ti3.exists() && t.elapsed() < Duration::from_secs(20) {
            std::thread::sleep(Duration::from_millis(2));
        }
        std::thread::sleep(Duration::from_millis(*ms));
        signal(run.pid(), "-KILL");
        let done = run.finish(Duration::from_secs(30));
        assert_eq!(done.code, None, "{done:?}");
        let now = rows(&ti3);
        assert!(now.len() >= have, "{} < {have}", now.len());
        same(&now, &want[..now.len()]);
        have = now.len();
        if have == want.len() {
            break;
        }
    }
    assert!(have > 0, "{have}");
    let done = common::run(
        &args(c, &[&extra[..], &["--resume"]].concat()),
        Duration::from_secs(120),
    );
    assert_eq!(done.code, Some(0), "{done:?}");
    same(&rows(&ti3), &want);
}

/// The SHA-256 of a file as coreutils' `sha256sum` prints it (an independent implementation).
fn sha256sum(path: &Path) -> String {
    let out = std::process::Command::new("sha256sum")
        .arg(path)
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");
    String::from_utf8(out.stdout).unwrap()[..64].to_string()
}

/// Waits (at most 20 s) until `path` exists.
fn wait_for(path: &Path) {
    let t = Instant::now();
    while !path.exists() && t.elapsed() < Duration::from_secs(20) {
        std::thread::sleep(Duration::from_millis(2));
    }
    assert!(path.exists(), "{} never appeared", path.display());
}

#[test]
fn a_second_run_on_the_same_output_refuses_at_once_and_the_first_completes() {
    let dir = tempfile::tempdir().unwrap();
    let cal = dir.path().join("c.toml");
    let c = cal.to_str().unwrap();
    let ti3 = dir.path().join("c.ti3");
    // the first run: 49 patches, 15 ms each
    let first = common::start(&args(c, &["--settle", "15"]));
    wait_for(&ti3);
    // the second, on the same output, even with --force (which would move the first run's
    // readings away) and another patch set: refused before it touches anything
    let second = common::run(
        &args(c, &["--force", "--ramp-steps", "5", "--verify", "3"]),
        Duration::from_secs(30),
    );
    let e = second.one_line_error(1);
    assert!(e.contains("is being measured by another run"), "{e}");
    assert!(e.contains(&format!("pid {}", first.pid())), "{e}");
    assert!(e.contains("c.toml.lock"), "{e}");
    assert!(!dir.path().join("c.ti3.1").exists());
    let done = first.finish(Duration::from_secs(60));
    assert_eq!(done.code, Some(0), "{done:?}");
    // the first run's readings, whole, and the calibration fitted from exactly them
    assert_eq!(rows(&ti3).len(), 49);
    let fitted = specpoly_display::calibration::load(&cal).unwrap();
    let prov = &fitted.data().provenance;
    assert_eq!(prov.readings_sha256, sha256sum(&ti3));
    assert_eq!(prov.patches_total, 49);
    // the lock is gone with the run
    assert!(!dir.path().join("c.toml.lock").exists());
}

#[test]
fn a_sigkilled_runs_lock_does_not_block_the_next_run() {
    let dir = tempfile::tempdir().unwrap();
    let cal = dir.path().join("k.toml");
    let c = cal.to_str().unwrap();
    let ti3 = dir.path().join("k.ti3");
    let lock = dir.path().join("k.toml.lock");
    let run = common::start(&args(c, &["--settle", "15"]));
    let pid = run.pid();
    wait_for(&ti3);
    signal(pid, "-KILL");
    let done = run.finish(Duration::from_secs(30));
    assert_eq!(done.code, None, "{done:?}");
    // the killed run's lock file is left, naming it, but the lock died with the process
    let left = std::fs::read_to_string(&lock).unwrap();
    assert!(left.starts_with(&format!("pid {pid}, started ")), "{left}");
    let done = common::run(&args(c, &["--resume"]), Duration::from_secs(60));
    assert_eq!(done.code, Some(0), "{done:?}");
    assert!(
        done.stderr.contains(&format!(
            "k.toml.lock: the run that held it (pid {pid}, started "
        )),
        "{done:?}"
    );
    assert!(done.stderr.contains("taken over"), "{done:?}");
    assert_eq!(rows(&ti3).len(), 49);
    assert!(!lock.exists());
}
