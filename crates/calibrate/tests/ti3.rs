//! The fit on the shipped real LCD measurements (data/ti3: an Acer XB271HU read by ArgyllCMS
//! `dispread`, 2068 patches): accuracy on held-out patches. ArgyllCMS `colprof -qm -as`
//! (shaper + matrix) reaches ΔE00 mean 0.25, max 1.2 on held-out patches of this display.

use specpoly_calibrate::fit::{fit, fit_and_verify, is_ramp, FitOptions, MatrixFit};
use specpoly_calibrate::verify;
use specpoly_display::calibration::{Calibration, TransferKind};
use specpoly_formats::cgats::read_ti3;
use specpoly_formats::measurement::Measurement;
use specpoly_formats::stats::Stats;

fn acer() -> Vec<Measurement> {
    let t = read_ti3(specpoly_spectra::data::ACER_TI3, "acer.ti3").unwrap();
    let (m, abs) = t.best_units();
    assert!(abs, "the shipped file carries LUMINANCE_XYZ_CDM2");
    m
}

/// The ramps (black, white, single channels) and every other remaining patch for the fit;
/// the other half of the remaining patches held out.
fn split(m: &[Measurement]) -> (Vec<Measurement>, Vec<Measurement>) {
    let (mut fit, mut held) = (Vec::new(), Vec::new());
    let mut k = 0;
    for p in m {
        if is_ramp(p) {
            fit.push(*p);
        } else {
            if k % 2 == 0 {
                fit.push(*p);
            } else {
                held.push(*p);
            }
            k += 1;
        }
    }
    (fit, held)
}

/// Prints and returns the held-out (mean, max).
fn report(name: &str, cal: &Calibration) -> (f64, f64) {
    let v = cal.data().fit.verification.unwrap();
    eprintln!(
        "{name}: held out {}: mean {:.3} p95 {:.3} max {:.3}",
        v.n, v.mean, v.p95, v.max
    );
    (v.mean, v.max)
}

#[test]
fn held_out_accuracy_beats_argyll_shaper_matrix() {
    let m = acer();
    let (fit_set, held) = split(&m);
    assert_eq!((fit_set.len(), held.len()), (1096, 972));
    let cal = fit_and_verify(&fit_set, &held, &FitOptions::default()).unwrap();
    let s = report("least-squares matrix + joint tables (default)", &cal);
    assert!(s.0 <= 0.25, "mean ΔE00 {} > 0.25", s.0);
    assert!(s.1 <= 1.3, "max ΔE00 {}", s.1);
    // the report records it and the file round-trips
    let back = Calibration::from_toml(&cal.to_toml().unwrap(), "x").unwrap();
    assert_eq!(back.data(), cal.data());
    assert_eq!(cal.data().provenance.patches_verify, 972);
    // tables run from 0 to 1 (the controller's `trc table` rule); the fit writes them so
    let tr = &cal.data().transfer;
    for t in tr.tables() {
        assert_eq!((t[0], t[t.len() - 1]), (0.0, 1.0));
    }
    for (first, last) in [(-0.01, 1.0), (0.0, 1.02)] {
        let mut d = cal.data().clone();
        d.transfer.green[0] = first;
        let n = d.transfer.green.len();
        d.transfer.green[n - 1] = last;
        let e = Calibration::new(d).unwrap_err().to_string();
        assert!(
            e.contains("transfer.green") && e.contains("start at 0 and end at 1"),
            "{e}"
        );
    }

    // the other models, for docs/calibration.md
    for (matrix, transfer) in [
        (MatrixFit::Cowan, TransferKind::Table),
        (MatrixFit::Cowan, TransferKind::Gamma),
        (MatrixFit::LeastSquares, TransferKind::Gamma),
    ] {
        let opts = FitOptions {
            matrix,
            transfer,
            ..Default::default()
        };
        let cal = fit_and_verify(&fit_set, &held, &opts).unwrap();
        let s = report(&format!("{matrix:?} {transfer:?}"), &cal);
        assert!(s.0 < 0.4 && s.1 < 2.0);
    }
}

#[test]
fn pure_cowan_from_the_ramps_alone() {
    let m = acer();
    let ramps: Vec<Measurement> = m.iter().copied().filter(is_ramp).collect();
    let rest: Vec<Measurement> = m.iter().copied().filter(|p| !is_ramp(p)).collect();
    let opts = FitOptions {
        matrix: MatrixFit::Cowan,
        ..Default::default()
    };
    let cal = fit(&ramps, &opts).unwrap();
    let s = Stats::of(&verify::delta_e(&cal, &rest));
    eprintln!(
        "Cowan from {} ramp patches, on the other {}: mean {:.3} p95 {:.3} max {:.3}",
        ramps.len(),
        s.n,
        s.mean,
        s.p95,
        s.max
    );
    assert!(s.mean < 0.4 && s.max < 2.0);
    let d = cal.data();
    // the display: an sRGB-like LCD of ~119 cd/m², gamma ~2.2 (through its video LUT)
    assert!((d.white[1] - 118.724927).abs() < 1e-6);
    assert!((d.primaries.red.x - 0.64).abs() < 0.03, "{:?}", d.primaries);
    assert!((d.primaries.green.y - 0.6).abs() < 0.1, "{:?}", d.primaries);
    for g in d.transfer.gamma {
        assert!((1.9..2.6).contains(&g), "{g}");
    }
    // additivity: R + G + B − 2K is within 1 % of the white's luminance
    assert!(d.fit.additivity_luminance_percent.unwrap().abs() < 1.0);
    assert!(d.fit.additivity_delta_e00.unwrap() < 1.0);
}
