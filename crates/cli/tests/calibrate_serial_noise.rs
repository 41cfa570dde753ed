//! `--instrument serial:PORT` on a line that is not clean: an independent PR-655 emulator
//! (crates/cli/tests/common/pr655.rs) that echoes every command, or sends noise before every reply,
//! must give the same readings as a clean line (a driver that stopped at patch 1 on either is
//! what this guards against); and Ctrl-C during a run returns the instrument to local mode
//! (`Q`) and keeps the readings.

use crate::common::calibrate_run as common;
use crate::common::pr655;
use crate::common::pr655_rig as rig;

use pr655::Faults;
use rig::{assert_readings_match, emulated, emulated_screen, open_and_measure};
use specpoly_calibrate::instrument::serial::SerialOptions;
use std::time::Duration;

fn opts() -> SerialOptions {
    SerialOptions {
        baud: 9600,
        timeout: Duration::from_millis(800),
        measure_timeout: Duration::from_millis(1000),
        retries: 0,
    }
}

fn full_run(f: Faults) {
    let (h, emu) = emulated(f);
    // no retries: every exchange must succeed at once, through the echo or the noise (the
    // port is closed, sending `Q`, when the measuring is done)
    let (set, got) = open_and_measure(&h, &emu, opts(), 4, 3);
    assert_readings_match(&h, &set, &got.unwrap());
    assert_eq!(emu.measured(), set.len());
    std::thread::sleep(Duration::from_millis(100));
    assert_eq!(emu.quitted(), 1, "Q on close");
}

#[test]
fn echoed_commands_are_skipped() {
    full_run(Faults {
        echo: true,
        ..Faults::default()
    });
}

#[test]
fn noise_before_replies_is_skipped() {
    full_run(Faults {
        noise: true,
        ..Faults::default()
    });
}

#[test]
fn echo_and_noise_together() {
    full_run(Faults {
        echo: true,
        noise: true,
        ..Faults::default()
    });
}

#[test]
fn ctrl_c_returns_the_instrument_to_local_mode_and_keeps_the_readings() {
    let dir = tempfile::tempdir().unwrap();
    let cal = dir.path().join("cal.toml");
    let (_model, shown, emu) = emulated_screen(Faults {
        integration: Duration::from_millis(150),
        echo: true,
        ..Faults::default()
    });
    let inst = format!("serial:{},timeout=2,measure-timeout=2", emu.path);
    let (run, browser) = common::start_web(
        &[
            "--instrument",
            &inst,
            "--settle",
            "0",
            "-o",
            cal.to_str().unwrap(),
        ],
        shown,
    );
    let t = std::time::Instant::now();
    while emu.measured() < 4 && t.elapsed() < Duration::from_secs(30) {
        std::thread::sleep(Duration::from_millis(10));
    }
    let ok = std::process::Command::new("kill")
        .args(["-INT", &run.pid().to_string()])
        .status()
        .unwrap()
        .success();
    assert!(ok);
    let done = run.finish(Duration::from_secs(30));
    drop(browser);
    let e = done.one_line_error(1);
    assert!(e.contains("interrupted (Ctrl-C)"), "{e}");
    assert!(e.contains("readings kept in"), "{e}");
    // the emulator may still be integrating the interrupted M1 when Q arrives
    let t = std::time::Instant::now();
    while emu.quitted() == 0 && t.elapsed() < Duration::from_secs(3) {
        std::thread::sleep(Duration::from_millis(10));
    }
    assert_eq!(emu.quitted(), 1, "Q sent on Ctrl-C");
    let n = common::ti3_rows(&cal.with_extension("ti3")).len();
    assert!((3..=5).contains(&n), "{n} readings");
}
