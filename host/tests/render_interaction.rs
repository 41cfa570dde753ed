//! `render --display CAL.toml` with a calibration whose model has channel interaction (the
//! Surface Pro's, where the lattice halves the held-out error): pixels are encoded through the
//! full model's inverse, so the full forward model (`Calibration::predict`, evaluated directly,
//! not inverted) emits what the matrix model maps each colour to, within [`EXACT_DE`]. The
//! matrix model's own device values miss by the lattice's correction, which shows the check can
//! fail.

use specpoly::calibrate::file::Calibration;
use specpoly::calibrate::fit::{fit, FitOptions};
use specpoly::calibrate::verify::delta_e00;
use specpoly::io::cgats::read_ti3;
use specpoly::render::output::Output;
use specpoly_core::{GamutMap, Mat3, Xyz};
use std::path::Path;

/// ΔE00 between the full model's emission of the encoded device values and the target
/// (Newton's inverse converges far below this; f32 device values limit it).
const EXACT_DE: f64 = 0.02;

fn surface() -> Calibration {
    let name = "microsoft-surface-pro-2017_825.ti3";
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/ti3").join(name);
    let text = std::fs::read_to_string(path).unwrap();
    let t = read_ti3(&text, name).unwrap();
    fit(&t.measurements, &FitOptions::default()).unwrap()
}

#[test]
fn a_calibration_with_interaction_renders_through_its_full_model() {
    let cal = surface();
    assert!(cal.has_interaction(), "the Surface's fit keeps its lattice");
    let display = cal.display();
    let matrix_only = Output {
        display: display.clone(),
        gamut: GamutMap::Clip,
        exposure: 1.0,
        adapt: Mat3::IDENTITY,
        exact: None,
    };
    let full = matrix_only.clone().with_model(Some(cal.clone()));
    let white = cal.predict([1.0; 3]);
    let k = (display.white().y - display.black().y) / 100.0;
    let levels = [0.15f32, 0.4, 0.65, 0.9];
    let (mut worst_full, mut sum_matrix, mut n) = (0.0f64, 0.0f64, 0usize);
    for r in levels {
        for g in levels {
            for b in levels {
                // an in-gamut colour: what the matrix model emits for (r, g, b)
                let target = display.device_to_xyz([r, g, b]);
                let relative = Xyz::from_array(target.to_array().map(|v| v / k));
                let t = target.to_array().map(f64::from);
                let d = full.device(relative).map(f64::from);
                worst_full = worst_full.max(delta_e00(cal.predict(d), t, white));
                let m = matrix_only.device(relative).map(f64::from);
                sum_matrix += delta_e00(cal.predict(m), t, white);
                n += 1;
            }
        }
    }
    let mean_matrix = sum_matrix / n as f64;
    assert!(
        worst_full <= EXACT_DE,
        "full model: worst ΔE00 {worst_full:.4} > {EXACT_DE}"
    );
    assert!(
        mean_matrix > 10.0 * EXACT_DE,
        "the matrix model alone is as good ({mean_matrix:.4}): the lattice would not matter"
    );
    eprintln!("full model worst ΔE00 {worst_full:.5}; matrix model alone mean {mean_matrix:.3}");
}
