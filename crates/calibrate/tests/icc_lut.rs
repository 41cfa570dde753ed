//! A LUT-only ICC display profile (`A2B0`/`B2A0`, no colorants or curves) read as a display
//! keeps its channel interaction: the Surface Pro's calibration (lattice 9) is written as a
//! profile with tables, its matrix/TRC tags renamed away, and read back
//! (`icc_read::load_model`). The oracle is the display's own readings (data/ti3): the profile's
//! full model predicts them within [`LUT_DE`] of what the calibration itself predicts (mean
//! ΔE00), and better than the matrix model the profile held before by at least [`GAIN`]
//! (ΔE00 from the project's CIEDE2000, tested against Sharma 2005's table).

use crate::common::displays;

use specpoly_calibrate::fit::{fit, FitOptions};
use specpoly_core::delta_e2000_xyz as delta_e00;
use specpoly_display::icc::{self, IccOptions, IccVersion};
use specpoly_display::icc_read;

/// Mean ΔE00 on the readings: the profile's model against the calibration's (measured 0.466 →
/// 0.482).
const LUT_DE: f64 = 0.1;
/// How much lower the full model's mean ΔE00 must be than the matrix model's (measured 2.87 →
/// 0.48).
const GAIN: f64 = 1.0;

#[test]
fn a_lut_profile_keeps_its_interaction() {
    let meas = displays::readings("microsoft-surface-pro-2017_825.ti3");
    let cal = fit(&meas, &FitOptions::default()).unwrap();
    assert!(cal.has_interaction());
    let mut b = icc::build(
        &cal,
        "surface tables",
        &IccOptions {
            version: IccVersion::V2,
            tables: true,
        },
    )
    .unwrap();
    displays::tables_only(&mut b);
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("tables.icc");
    std::fs::write(&p, &b).unwrap();
    let model = icc_read::load_model(&p).unwrap();
    assert!(
        model.interaction().is_some(),
        "the table's interaction is kept"
    );
    // every model judged relative to its own white, against the readings relative to theirs
    let white = |f: &dyn Fn([f64; 3]) -> [f64; 3]| f([1.0; 3]);
    let mean = |f: &dyn Fn([f64; 3]) -> [f64; 3]| {
        let w = white(f);
        let mw = meas
            .iter()
            .filter(|m| m.device.iter().all(|v| *v >= 1.0 - 1e-9))
            .map(|m| m.xyz)
            .next()
            .unwrap();
        let s: f64 = meas
            .iter()
            .map(|m| {
                let p = f(m.device).map(|v| v / w[1]);
                let q = m.xyz.map(|v| v / mw[1]);
                delta_e00(p, q, mw.map(|v| v / mw[1]))
            })
            .sum();
        s / meas.len() as f64
    };
    let of_cal = mean(&|d| cal.predict(d));
    let full = mean(&|d| <[f64; 3]>::from(model.device_to_xyz(d.map(|v| v as f32))));
    let matrix = mean(&|d| <[f64; 3]>::from(model.display().device_to_xyz(d.map(|v| v as f32))));
    eprintln!("mean ΔE00 on the readings: calibration {of_cal:.3}, LUT profile's full model {full:.3}, its matrix model {matrix:.3}");
    assert!(full <= of_cal + LUT_DE, "{full} against {of_cal}");
    assert!(
        full + GAIN <= matrix,
        "{full} against the matrix model's {matrix}"
    );
}
