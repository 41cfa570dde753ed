//! `specpoly calibrate run` on the simulated CRT (data/displays/crt_brainard_1997.csv), through
//! the real binary: the primaries recovered from noisy readings agree with the SPD-integrated
//! truth within 0.001 in x and y and 0.5 % in luminance; the manual display; usage errors.

use crate::common::calibrate_run as common;

use specpoly_calibrate::patches;
use specpoly_calibrate::sim::SimModel;
use specpoly_display::calibration;
use std::time::Duration;

fn xyy(p: [f64; 3]) -> [f64; 3] {
    let s = p[0] + p[1] + p[2];
    [p[0] / s, p[1] / s, p[1]]
}

fn run_sim(display: &str, extra: &[&str]) -> (tempfile::TempDir, common::Finished) {
    let dir = tempfile::tempdir().unwrap();
    let cal = dir.path().join("crt.toml");
    let done = common::calibrate(
        display,
        "sim",
        extra,
        cal.to_str().unwrap(),
        Duration::from_secs(120),
    );
    (dir, done)
}

const NOISY: &str = "sim:crt,noise=0.001,black=0.2,flare=0.1,seed=42";

#[test]
fn readings_give_the_primaries_of_the_simulated_crt() {
    let (dir, done) = run_sim(NOISY, &[]);
    assert_eq!(done.code, Some(0), "{done:?}");
    let rows = common::ti3_rows(&dir.path().join("crt.ti3"));
    assert_eq!(rows.len(), patches::standard(9, 16).unwrap().len());
    let truth = SimModel::parse(NOISY.trim_start_matches("sim:")).unwrap();
    let black = rows
        .iter()
        .find(|r| r[..3] == [0.0; 3])
        .expect("a black patch");
    for ch in 0..3 {
        let full = rows
            .iter()
            .find(|r| (0..3).all(|k| r[k] == if k == ch { 100.0 } else { 0.0 }))
            .expect("a full primary");
        let got = xyy([0, 1, 2].map(|k| full[3 + k] - black[3 + k]));
        let want = xyy(truth.primaries[ch]);
        assert!(
            (got[0] - want[0]).abs() < 1e-3,
            "ch {ch} x {got:?} {want:?}"
        );
        assert!(
            (got[1] - want[1]).abs() < 1e-3,
            "ch {ch} y {got:?} {want:?}"
        );
        assert!(
            (got[2] / want[2] - 1.0).abs() < 5e-3,
            "ch {ch} Y {got:?} {want:?}"
        );
    }
    // the fitted calibration: primaries within 0.001 in x, y and 0.5 % in Y of the truth
    let cal = calibration::load(&dir.path().join("crt.toml")).unwrap();
    let d = cal.data();
    assert_eq!(d.units, "cd/m2");
    let mut worst = [0.0f64; 3];
    for (ch, p) in d.primaries.array().iter().enumerate() {
        let want = xyy(truth.primaries[ch]);
        let e = [
            (p.x - want[0]).abs(),
            (p.y - want[1]).abs(),
            (p.luminance / want[2] - 1.0).abs(),
        ];
        assert!(e[0] < 1e-3 && e[1] < 1e-3, "ch {ch}: {p:?} vs {want:?}");
        assert!(e[2] < 5e-3, "ch {ch}: {p:?} vs {want:?}");
        for k in 0..3 {
            worst[k] = worst[k].max(e[k]);
        }
    }
    // black and flare are recovered as the black level
    let b = truth.xyz([0.0; 3]);
    assert!(
        (d.black[1] / b[1] - 1.0).abs() < 0.01,
        "{:?} vs {b:?}",
        d.black
    );
    let v = d.fit.verification.expect("verification statistics");
    assert_eq!(v.n, 16);
    assert!(v.mean < 1.0 && v.max < 3.0, "{v:?}");
    println!(
        "worst primary error: x {:.5}, y {:.5}, Y {:.3} %; verification ΔE00 mean {:.2}, max {:.2}",
        worst[0],
        worst[1],
        worst[2] * 100.0,
        v.mean,
        v.max
    );
}

#[test]
fn same_seed_same_readings() {
    let (d1, r1) = run_sim(NOISY, &["--ramp-steps", "3", "--verify", "2"]);
    let (d2, r2) = run_sim(NOISY, &["--ramp-steps", "3", "--verify", "2"]);
    assert_eq!(r1.code, Some(0), "{r1:?}");
    assert_eq!(r2.code, Some(0), "{r2:?}");
    let a = std::fs::read_to_string(d1.path().join("crt.ti3")).unwrap();
    let b = std::fs::read_to_string(d2.path().join("crt.ti3")).unwrap();
    assert_eq!(
        common::ti3_rows(&d1.path().join("crt.ti3")),
        common::ti3_rows(&d2.path().join("crt.ti3"))
    );
    assert!(!a.is_empty() && !b.is_empty());
}

#[test]
fn manual_display_waits_for_enter() {
    let dir = tempfile::tempdir().unwrap();
    let cal = dir.path().join("m.toml");
    let n = patches::standard(3, 1).unwrap().len();
    let mut run = common::start(&common::calibrate_args(
        "manual",
        "sim:crt",
        &["--ramp-steps", "3", "--verify", "1"],
        cal.to_str().unwrap(),
    ));
    run.stdin(&"\n".repeat(n));
    let done = run.finish(Duration::from_secs(60));
    assert_eq!(done.code, Some(0), "{done:?}");
    assert!(done.stderr.contains("patch 1: set RGB 0 0 0"), "{done:?}");
    assert!(done.stderr.contains("set RGB 255 255 255"), "{done:?}");
    assert_eq!(common::ti3_rows(&dir.path().join("m.ti3")).len(), n);

    // `q` stops; what was measured stays (--force: the first run's readings go to m.ti3.1)
    let mut run = common::start(&common::calibrate_args(
        "manual",
        "sim:crt",
        &["--force"],
        cal.to_str().unwrap(),
    ));
    run.stdin("\n\n\nq\n");
    let done = run.finish(Duration::from_secs(60));
    assert_eq!(done.code, Some(1), "{done:?}");
    assert!(done.stderr.contains("stopped by the user"), "{done:?}");
    assert!(done.stderr.contains("3 readings kept in"), "{done:?}");
    assert_eq!(common::ti3_rows(&dir.path().join("m.ti3")).len(), 3);
    assert_eq!(common::ti3_rows(&dir.path().join("m.ti3.1")).len(), n);
}

#[test]
fn usage_errors_exit_2() {
    for (display, instrument, needle) in [
        (
            "manual",
            "sim",
            "--instrument sim reads a simulated display",
        ),
        ("sim:crt", "sim:crt", "already simulated"),
        ("projector", "sim", "--display `projector`"),
        ("sim:crt,gamma=abc", "sim", "not a number"),
        ("sim:crt", "usb", "--instrument `usb`"),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let cal = dir.path().join("x.toml");
        let done = common::calibrate(
            display,
            instrument,
            &[],
            cal.to_str().unwrap(),
            Duration::from_secs(30),
        );
        assert_eq!(done.code, Some(2), "{display} {instrument}: {done:?}");
        assert!(
            done.stderr.contains(needle),
            "{display} {instrument}: {done:?}"
        );
        assert_eq!(done.stderr.trim().lines().count(), 1, "{done:?}");
    }
    let done = common::calibrate(
        "sim:crt",
        "sim",
        &["--ramp-steps", "1"],
        "x.toml",
        Duration::from_secs(30),
    );
    assert_eq!(done.code, Some(2), "{done:?}");
}
