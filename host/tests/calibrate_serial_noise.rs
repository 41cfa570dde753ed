//! `--instrument serial:PORT` on a line that is not clean: an independent PR-655 emulator
//! (host/tests/common/pr655.rs) that echoes every command, or sends noise before every reply,
//! must give the same readings as a clean line (a driver that stopped at patch 1 on either is
//! what this guards against); and Ctrl-C during a run returns the instrument to local mode
//! (`Q`) and keeps the readings.

#[path = "common/calibrate_run.rs"]
mod common;
#[path = "common/pr655.rs"]
mod pr655;

use pr655::Faults;
use specpoly::calibrate::instrument::serial::{Pr6xx, SerialOptions};
use specpoly::calibrate::patch_display::sim::SimDisplay;
use specpoly::calibrate::patches;
use specpoly::calibrate::run::measure_all;
use specpoly::calibrate::sim::{SimHandle, SimModel};
use std::sync::atomic::Ordering;
use std::time::Duration;

/// The PR-655 reports four significant digits.
const REL: f64 = 5e-4;

fn opts() -> SerialOptions {
    SerialOptions {
        baud: 9600,
        timeout: Duration::from_millis(800),
        measure_timeout: Duration::from_millis(1000),
        retries: 0,
    }
}

fn full_run(f: Faults) {
    let h = SimHandle::new(SimModel::parse("crt,black=0.3").unwrap());
    let hh = h.clone();
    let emu = pr655::spawn(move || hh.read(), f);
    // no retries: every exchange must succeed at once, through the echo or the noise
    let mut inst = Pr6xx::open(&emu.path, opts()).unwrap();
    let set = patches::standard(4, 3).unwrap();
    let mut disp = SimDisplay::new(h.clone());
    let got = measure_all(&mut disp, &mut inst, &set, Duration::ZERO, |_| Ok(())).unwrap();
    assert_eq!(got.len(), set.len());
    let model = h.model();
    for (m, p) in got.iter().zip(&set) {
        let t = model.xyz(p.device);
        for k in 0..3 {
            assert!(
                (m.xyz[k] - t[k]).abs() <= REL * t[k].abs() + 1e-9,
                "{m:?} vs {t:?}"
            );
        }
    }
    assert_eq!(emu.measurements.load(Ordering::SeqCst), set.len());
    drop(inst);
    std::thread::sleep(Duration::from_millis(100));
    assert_eq!(emu.quits.load(Ordering::SeqCst), 1, "Q on close");
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
    let model = SimModel::parse("crt,black=0.3").unwrap();
    let shown = std::sync::Arc::new(std::sync::Mutex::new([0.0f64; 3]));
    let (s, m) = (shown.clone(), model.clone());
    let emu = pr655::spawn(
        move || m.xyz(*s.lock().unwrap()),
        Faults {
            integration: Duration::from_millis(150),
            echo: true,
            ..Faults::default()
        },
    );
    let inst = format!("serial:{},timeout=2,measure-timeout=2", emu.path);
    let mut run = common::start(&[
        "calibrate",
        "run",
        "--display",
        "web,wait=20,timeout=10",
        "--instrument",
        &inst,
        "--settle",
        "0",
        "-o",
        cal.to_str().unwrap(),
    ]);
    let url = run.web_url();
    let browser = common::fake_browser_into(&url, shown);
    let t = std::time::Instant::now();
    while emu.measurements.load(Ordering::SeqCst) < 4 && t.elapsed() < Duration::from_secs(30) {
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
    assert_eq!(done.code, Some(1), "{done:?}");
    let e = done.stderr.trim();
    assert_eq!(e.lines().count(), 1, "{e}");
    assert!(e.contains("interrupted (Ctrl-C)"), "{e}");
    assert!(e.contains("readings kept in"), "{e}");
    // the emulator may still be integrating the interrupted M1 when Q arrives
    let t = std::time::Instant::now();
    while emu.quits.load(Ordering::SeqCst) == 0 && t.elapsed() < Duration::from_secs(3) {
        std::thread::sleep(Duration::from_millis(10));
    }
    assert_eq!(emu.quits.load(Ordering::SeqCst), 1, "Q sent on Ctrl-C");
    let text = std::fs::read_to_string(cal.with_extension("ti3")).unwrap();
    let n = specpoly::io::cgats::read_ti3(&text, "cal.ti3")
        .unwrap()
        .measurements
        .len();
    assert!((3..=5).contains(&n), "{n} readings");
}
