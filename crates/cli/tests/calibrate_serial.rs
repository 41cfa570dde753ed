//! `--instrument serial:PORT`: the PR-655/670 remote-mode driver against an emulated PR-655
//! on a pseudo-terminal — good readings, malformed, slow, error and missing replies, no
//! instrument, a missing port, and a port that disappears mid-run — through the library and
//! through the real binary (with the web display and a fake browser as the screen).

use crate::common::calibrate_run as common;
use crate::common::pr655;
use crate::common::pr655_rig as rig;

use pr655::Faults;
use rig::{assert_readings_match, emulated, emulated_screen, measure_standard, open_and_measure};
use specpoly_calibrate::instrument::serial::{Pr6xx, SerialOptions};
use specpoly_calibrate::instrument::Instrument;
use specpoly_calibrate::patch_display::sim::SimDisplay;
use specpoly_calibrate::patches;
use specpoly_calibrate::run::measure_all;
use specpoly_calibrate::sim::SimModel;
use std::time::{Duration, Instant};

fn quick() -> SerialOptions {
    SerialOptions {
        baud: 9600,
        timeout: Duration::from_millis(500),
        measure_timeout: Duration::from_millis(800),
        retries: 2,
    }
}

/// [`quick`] with `retries`.
fn retrying(retries: u32) -> SerialOptions {
    SerialOptions { retries, ..quick() }
}

#[test]
fn c_exponent_format() {
    assert_eq!(pr655::c_exp(123.4), "1.234e+002");
    assert_eq!(pr655::c_exp(0.01234), "1.234e-002");
    assert_eq!("1.234e+002".parse::<f64>().unwrap(), 123.4);
}

#[test]
fn readings_through_the_pty_match_the_display() {
    let (h, emu) = emulated(Faults::default());
    let mut inst = Pr6xx::open(&emu.path, quick()).unwrap();
    assert!(inst.describe().contains(&emu.path));
    let set = patches::standard(3, 2).unwrap();
    let mut disp = SimDisplay::new(h.clone());
    let mut saves = 0;
    let got = measure_all(&mut disp, &mut inst, &set, Duration::ZERO, |m| {
        saves += 1;
        assert_eq!(m.len(), saves);
        Ok(())
    })
    .unwrap();
    assert_readings_match(&h, &set, &got);
    assert_eq!(emu.measured(), set.len());
}

#[test]
fn transient_faults_are_retried() {
    let (h, emu) = emulated(Faults {
        garbage_on: vec![2],
        slow_on: vec![(4, Duration::from_millis(1500))],
        status_on: vec![(7, 18)],
        ..Faults::default()
    });
    let (set, got) = open_and_measure(&h, &emu, quick(), 3, 0);
    assert_readings_match(&h, &set, &got.unwrap());
    // three failed M1s were repeated
    assert!(emu.measured() >= set.len() + 3);
}

#[test]
fn a_slow_reply_within_the_timeout_is_waited_for() {
    let (h, emu) = emulated(Faults {
        slow_on: vec![(1, Duration::from_millis(400))],
        ..Faults::default()
    });
    let mut inst = Pr6xx::open(&emu.path, quick()).unwrap();
    h.set([1.0; 3]);
    let xyz = inst.measure().unwrap();
    assert!((xyz[1] - 100.3).abs() < 0.1, "{xyz:?}");
    assert_eq!(emu.measured(), 1);
}

#[test]
fn persistent_garbage_stops_the_run_with_the_readings_so_far() {
    let (h, emu) = emulated(Faults {
        garbage_from: Some(3),
        ..Faults::default()
    });
    let e = open_and_measure(&h, &emu, quick(), 3, 0).1.unwrap_err();
    assert_eq!(e.taken.len(), 2);
    let msg = e.error.to_string();
    assert!(msg.contains("patch 3 of"), "{msg}");
    assert!(msg.contains("garbled reply to `M1`"), "{msg}");
    assert!(msg.contains("3 attempts"), "{msg}");
    assert!(!msg.contains('\n'));
}

#[test]
fn an_error_status_that_persists_is_reported_with_its_code() {
    let (_h, emu) = emulated(Faults {
        status_on: vec![(1, 18), (2, 18)],
        ..Faults::default()
    });
    let mut inst = Pr6xx::open(&emu.path, retrying(1)).unwrap();
    let msg = inst.measure().unwrap_err().to_string();
    assert!(
        msg.contains("instrument error 0018 (light too low)"),
        "{msg}"
    );
}

#[test]
fn no_instrument_on_the_port() {
    let (_h, emu) = emulated(Faults {
        silent: true,
        ..Faults::default()
    });
    let t = Instant::now();
    let e = Pr6xx::open(&emu.path, retrying(1))
        .err()
        .expect("no instrument");
    let msg = e.to_string();
    assert!(msg.contains("no instrument answered on"), "{msg}");
    assert!(msg.contains("PHOTO"), "{msg}");
    assert_eq!(
        specpoly::error::CliError::from(specpoly_calibrate::Error::from(e)).exit_code(),
        1
    );
    assert!(t.elapsed() < Duration::from_secs(5));
}

#[test]
fn a_missing_port() {
    let e = Pr6xx::open("/dev/specpoly-no-such-port", quick())
        .err()
        .expect("no port");
    assert!(
        e.to_string()
            .starts_with("cannot open serial port /dev/specpoly-no-such-port"),
        "{e}"
    );
}

#[test]
fn the_port_disappears_mid_run() {
    let (h, emu) = emulated(Faults {
        vanish_on: Some(4),
        ..Faults::default()
    });
    let mut inst = Pr6xx::open(&emu.path, quick()).unwrap();
    let t = Instant::now();
    let e = measure_standard(&h, &mut inst, 3, 0).1.unwrap_err();
    assert_eq!(e.taken.len(), 3);
    let msg = e.error.to_string();
    assert!(msg.contains("serial port failed"), "{msg}");
    // no waiting out the retries on a dead port
    assert!(t.elapsed() < Duration::from_secs(2), "{:?}", t.elapsed());
}

// ---- through the binary: web display + fake browser as the screen, emulator as the instrument

struct BinRun {
    _dir: tempfile::TempDir,
    cal: std::path::PathBuf,
    done: common::Finished,
    model: SimModel,
}

fn binary_run(faults: Faults, serial_opts: &str) -> BinRun {
    let dir = tempfile::tempdir().unwrap();
    let cal = dir.path().join("cal.toml");
    // the emulator measures what the (fake) browser shows
    let (model, shown, emu) = emulated_screen(faults);
    let inst = format!("serial:{}{serial_opts}", emu.path);
    let (run, browser) = common::start_web(
        &[
            "--instrument",
            &inst,
            "--ramp-steps",
            "4",
            "--verify",
            "2",
            "--settle",
            "0",
            "-o",
            cal.to_str().unwrap(),
        ],
        shown,
    );
    let done = run.finish(Duration::from_secs(90));
    drop(browser);
    drop(emu);
    BinRun {
        _dir: dir,
        cal,
        done,
        model,
    }
}

#[test]
fn binary_full_run_over_the_pty() {
    let r = binary_run(Faults::default(), ",timeout=1,measure-timeout=1");
    assert_eq!(r.done.code, Some(0), "{:?}", r.done);
    assert!(r.cal.is_file());
    let rows = common::ti3_rows(&r.cal.with_extension("ti3"));
    assert_eq!(rows.len(), patches::standard(4, 2).unwrap().len());
    // RGB 0–100 then XYZ: the readings are the display's truth to the PR-655's 4 digits
    for row in &rows {
        let dev = [row[0] / 100.0, row[1] / 100.0, row[2] / 100.0];
        let t = r.model.xyz(dev);
        assert!(
            (row[4] - t[1]).abs() <= 1e-3 * t[1] + 1e-4,
            "{row:?} vs {t:?}"
        );
    }
}

#[test]
fn binary_port_disappears_keeps_the_readings() {
    let r = binary_run(
        Faults {
            vanish_on: Some(6),
            ..Faults::default()
        },
        ",timeout=1,measure-timeout=1",
    );
    let err = r.done.one_line_error(1);
    assert!(err.starts_with("specpoly: error: "), "{err}");
    assert!(err.contains("serial port failed"), "{err}");
    assert!(err.contains("5 readings kept in"), "{err}");
    assert!(!r.cal.exists());
    assert_eq!(common::ti3_rows(&r.cal.with_extension("ti3")).len(), 5);
}

#[test]
fn binary_garbage_reply_keeps_the_readings() {
    let r = binary_run(
        Faults {
            garbage_from: Some(4),
            ..Faults::default()
        },
        ",timeout=1,measure-timeout=1,retries=1",
    );
    let err = r.done.one_line_error(1);
    assert!(err.contains("garbled reply"), "{err}");
    assert_eq!(common::ti3_rows(&r.cal.with_extension("ti3")).len(), 3);
}

#[test]
fn binary_no_instrument() {
    let dir = tempfile::tempdir().unwrap();
    let cal = dir.path().join("cal.toml");
    let (_h, emu) = emulated(Faults {
        silent: true,
        ..Faults::default()
    });
    let inst = format!("serial:{},timeout=0.3,retries=0", emu.path);
    let done = common::calibrate(
        "sim:crt",
        &inst,
        &[],
        cal.to_str().unwrap(),
        Duration::from_secs(30),
    );
    assert_eq!(done.code, Some(1), "{done:?}");
    assert!(
        done.stderr.contains("no instrument answered on"),
        "{done:?}"
    );
    assert_eq!(done.stderr.trim().lines().count(), 1, "{done:?}");
    let done = common::calibrate(
        "sim:crt",
        "serial:/dev/specpoly-no-such-port",
        &[],
        cal.to_str().unwrap(),
        Duration::from_secs(30),
    );
    assert_eq!(done.code, Some(1), "{done:?}");
    assert!(done.stderr.contains("cannot open serial port"), "{done:?}");
}
