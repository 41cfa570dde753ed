//! The rig of the serial-instrument tests: the simulated CRT as the screen, measured through the
//! real PR-655/670 driver (`Pr6xx`) talking to the emulator of `common/pr655.rs`, and the check
//! of its readings against the display's truth. Include it after `pr655` with
//! `#[path = "common/pr655_rig.rs"] mod rig;`.
#![allow(dead_code)]

use super::pr655::{self, Faults};
use specpoly_calibrate::instrument::serial::{Pr6xx, SerialOptions};
use specpoly_calibrate::patch_display::sim::SimDisplay;
use specpoly_calibrate::patches::{self, Patch};
use specpoly_calibrate::run::{measure_all, Interrupted};
use specpoly_calibrate::sim::{SimHandle, SimModel};
use specpoly_formats::measurement::Measurement;
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// The PR-655 reports four significant digits: a reading is the truth within this (relative).
pub const REL: f64 = 5e-4;

/// The simulated CRT and an emulator measuring it with `faults`.
pub fn emulated(faults: Faults) -> (SimHandle, pr655::Emulator) {
    let h = SimHandle::new(SimModel::parse("crt,black=0.3").unwrap());
    let hh = h.clone();
    let emu = pr655::spawn(move || hh.read(), faults);
    (h, emu)
}

/// The patches `patches::standard(ramp_steps, verify)` measured on `h` through `inst`.
pub fn measure_standard(
    h: &SimHandle,
    inst: &mut Pr6xx,
    ramp_steps: usize,
    verify: usize,
) -> (Vec<Patch>, Result<Vec<Measurement>, Interrupted>) {
    let set = patches::standard(ramp_steps, verify).unwrap();
    let mut disp = SimDisplay::new(h.clone());
    let got = measure_all(&mut disp, inst, &set, Duration::ZERO, |_| Ok(()));
    (set, got)
}

/// Opens the emulator's port with `options` and measures the standard set.
pub fn open_and_measure(
    h: &SimHandle,
    emu: &pr655::Emulator,
    options: SerialOptions,
    ramp_steps: usize,
    verify: usize,
) -> (Vec<Patch>, Result<Vec<Measurement>, Interrupted>) {
    let mut inst = Pr6xx::open(&emu.path, options).unwrap();
    measure_standard(h, &mut inst, ramp_steps, verify)
}

/// Every reading is its patch's XYZ on the display to the PR-655's four digits.
pub fn assert_readings_match(h: &SimHandle, set: &[Patch], got: &[Measurement]) {
    assert_eq!(got.len(), set.len());
    let model = h.model();
    for (m, p) in got.iter().zip(set) {
        assert_eq!(m.device, p.device);
        let t = model.xyz(p.device);
        for k in 0..3 {
            assert!(
                (m.xyz[k] - t[k]).abs() <= REL * t[k].abs() + 1e-9,
                "{m:?} vs {t:?}"
            );
        }
    }
}

/// An emulator measuring the simulated CRT showing whatever is written into the returned
/// colour (the patch a fake browser is shown), with `faults`.
pub fn emulated_screen(faults: Faults) -> (SimModel, Arc<Mutex<[f64; 3]>>, pr655::Emulator) {
    let model = SimModel::parse("crt,black=0.3").unwrap();
    let shown = Arc::new(Mutex::new([0.0f64; 3]));
    let (s, m) = (shown.clone(), model.clone());
    let emu = pr655::spawn(move || m.xyz(*s.lock().unwrap()), faults);
    (model, shown, emu)
}
