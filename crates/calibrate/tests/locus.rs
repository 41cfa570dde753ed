//! A fitted primary outside the spectral locus (inside the xy triangle, so the triangle test
//! alone lets it through) is moved onto the locus, the user is told, and the loader reads the
//! file back. The oracle is CIE 15's tabulated chromaticities of the locus's ends (CIE 1931,
//! 380 nm: x = 0.1741, y = 0.0050; 780 nm: x = 0.7347, y = 0.2653): a realisable red lies on
//! or above the purple line between them.

use specpoly_calibrate::fit::{fit, FitOptions, MatrixFit};
use specpoly_display::calibration::Calibration;
use specpoly_formats::measurement::Measurement;

/// How far below the purple line (in y) the moved primary may sit: the rounding of the
/// published chromaticities.
const LINE_TOLERANCE: f64 = 2e-4;

fn xyz(x: f64, y: f64, big_y: f64) -> [f64; 3] {
    [x * big_y / y, big_y, (1.0 - x - y) * big_y / y]
}

/// Readings of a display whose red primary, x = 0.70, y = 0.20, lies below the purple line.
fn readings() -> Vec<Measurement> {
    let p = [
        xyz(0.70, 0.20, 20.0),
        xyz(0.30, 0.60, 70.0),
        xyz(0.15, 0.06, 10.0),
    ];
    let mut m = Vec::new();
    let levels = [0.0, 0.25, 0.5, 0.75, 1.0];
    for r in levels {
        for g in levels {
            for b in levels {
                let d = [r, g, b];
                let l = d.map(|v: f64| v.powf(2.2));
                let x = [0, 1, 2].map(|k| (0..3).map(|c| p[c][k] * l[c]).sum::<f64>() + 0.05);
                m.push(Measurement { device: d, xyz: x });
            }
        }
    }
    m
}

#[test]
fn a_primary_outside_the_locus_is_moved_onto_it_and_reported() {
    let purple = |x: f64| 0.0050 + (x - 0.1741) / (0.7347 - 0.1741) * (0.2653 - 0.0050);
    for matrix in [MatrixFit::Cowan, MatrixFit::LeastSquares] {
        let opts = FitOptions {
            matrix,
            ..Default::default()
        };
        let cal = fit(&readings(), &opts).unwrap();
        let red = cal.data().primaries.red;
        assert!(
            red.y >= purple(red.x) - LINE_TOLERANCE,
            "{matrix:?}: red x = {}, y = {} is below the purple line ({})",
            red.x,
            red.y,
            purple(red.x)
        );
        assert!(
            cal.data()
                .fit
                .constrained
                .iter()
                .any(|n| n.contains("red") && n.contains("spectral locus")),
            "{matrix:?}: {:?}",
            cal.data().fit.constrained
        );
        let text = cal.to_toml().unwrap();
        Calibration::from_toml(&text, "written").unwrap();
    }
}
