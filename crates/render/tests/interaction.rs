//! `render --display CAL.toml` with a calibration whose model has channel interaction (the
//! Surface Pro's, where the lattice halves the held-out error): pixels are encoded through the
//! full model's inverse, judged by the full forward model (`Calibration::predict`, evaluated
//! directly, not inverted) on colours it reaches: never further off than the matrix model's own
//! device values, at most [`EXACT_DE`] off for every one of them (the core's inverse is exact
//! in the gamut, the dark colours of this panel's flat-footed red curve included), and on
//! average at most half the matrix model's error.

use crate::common::displays;

use specpoly_core::delta_e2000_xyz as delta_e00;
use specpoly_core::{GamutMap, Mat3, Xyz};
use specpoly_display::calibration::Calibration;
use specpoly_render::output::Output;

/// ΔE00 between the full model's emission of the encoded device values and the target (the
/// round-trip tolerance of `display_inverse.rs`).
const EXACT_DE: f64 = 0.01;

fn surface() -> Calibration {
    displays::fitted("microsoft-surface-pro-2017_825.ti3")
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
        model: None,
    };
    let full = matrix_only
        .clone()
        .with_model(Some(Box::new(cal.model().clone())));
    let white = cal.predict([1.0; 3]);
    let k = (display.white().y - display.black().y) / 100.0;
    let levels = [0.15, 0.4, 0.65, 0.9];
    let (mut exact, mut sum_full, mut sum_matrix, mut n) = (0usize, 0.0f64, 0.0f64, 0usize);
    for r in levels {
        for g in levels {
            for b in levels {
                // a colour the full model reaches (its emission for (r, g, b)); the renderer's
                // gamut mapping is the matrix model's, so keep those inside that gamut too
                let t = cal.predict([r, g, b]);
                let relative = Xyz::from_array(t.map(|v| (v / k as f64) as f32));
                let abs = Xyz::from_array(t.map(|v| v as f32));
                if display.encode(abs, GamutMap::Clip).out_of_gamut {
                    continue;
                }
                let full_de =
                    delta_e00(cal.predict(full.device(relative).map(f64::from)), t, white);
                let matrix_de = delta_e00(
                    cal.predict(matrix_only.device(relative).map(f64::from)),
                    t,
                    white,
                );
                assert!(
                    full_de <= matrix_de + 1e-6,
                    "({r}, {g}, {b}): full model ΔE00 {full_de:.4} > matrix model's {matrix_de:.4}"
                );
                exact += usize::from(full_de <= EXACT_DE);
                sum_full += full_de;
                sum_matrix += matrix_de;
                n += 1;
            }
        }
    }
    assert!(
        n >= 32,
        "only {n} of 64 colours inside the matrix model's gamut"
    );
    let (mean_full, mean_matrix) = (sum_full / n as f64, sum_matrix / n as f64);
    assert_eq!(exact, n, "exact on {exact} of {n} colours");
    assert!(
        mean_full <= 0.5 * mean_matrix,
        "mean ΔE00 {mean_full:.4} against the matrix model's {mean_matrix:.4}"
    );
    eprintln!(
        "{n} colours: exact (≤ {EXACT_DE}) on {exact}; mean ΔE00 {mean_full:.4}, matrix model alone {mean_matrix:.4}"
    );
}
