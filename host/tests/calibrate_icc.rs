//! The ICC v4 export, read back by Little CMS: device RGB → PCS XYZ (D50) through the profile
//! agrees with the calibration's own prediction adapted to D50 with Bradford.

use lcms2::{InfoType, Intent, Locale, PixelFormat, Profile, Transform};
use specpoly::calibrate::file::{Calibration, TransferKind};
use specpoly::calibrate::fit::{fit, FitOptions, InteractionChoice, MatrixFit};
use specpoly::calibrate::icc;
use specpoly::calibrate::verify::delta_e00;
use specpoly::io::cgats::read_ti3;

fn acer(opts: &FitOptions) -> Calibration {
    let t = read_ti3(specpoly::data::ACER_TI3, "acer.ti3").unwrap();
    // a matrix/TRC profile holds no interaction lattice: fit the matrix model alone
    let opts = FitOptions {
        interaction: InteractionChoice::None,
        ..*opts
    };
    fit(&t.best_units().0, &opts).unwrap()
}

fn check(cal: &Calibration, label: &str) {
    let bytes = icc::profile(cal, label).unwrap();
    let p = Profile::new_icc(&bytes).expect("lcms reads the profile");
    assert!((p.version() - 4.4).abs() < 1e-6, "version {}", p.version());
    assert_eq!(
        p.info(InfoType::Description, Locale::new("en_US"))
            .as_deref(),
        Some(label)
    );
    let xyz = Profile::new_xyz();
    let t: Transform<[f64; 3], [f64; 3]> = Transform::new(
        &p,
        PixelFormat::RGB_DBL,
        &xyz,
        PixelFormat::XYZ_DBL,
        Intent::RelativeColorimetric,
    )
    .unwrap();
    // RGB_DBL is 0–1 in lcms; a 9³ grid plus the ramps' dark end
    let mut src = Vec::new();
    for r in 0..9 {
        for g in 0..9 {
            for b in 0..9 {
                src.push([r as f64 / 8.0, g as f64 / 8.0, b as f64 / 8.0]);
            }
        }
    }
    for i in 1..20 {
        let v = i as f64 / 255.0;
        src.extend([[v, 0.0, 0.0], [0.0, v, 0.0], [0.0, 0.0, v], [v, v, v]]);
    }
    let mut dst = vec![[0.0; 3]; src.len()];
    t.transform_pixels(&src, &mut dst);
    let (mut worst, mut worst_xyz) = (0.0f64, 0.0f64);
    for (rgb, got) in src.iter().zip(&dst) {
        let want = icc::predict_pcs(cal, *rgb);
        let de = delta_e00(*got, want, icc::D50);
        worst = worst.max(de);
        for c in 0..3 {
            worst_xyz = worst_xyz.max((got[c] - want[c]).abs());
        }
    }
    eprintln!("{label}: lcms vs calibration: max ΔE00 {worst:.4}, max |ΔXYZ| {worst_xyz:.2e}");
    assert!(worst < 0.05, "{label}: ΔE00 {worst}");
    assert!(worst_xyz < 1e-3, "{label}: ΔXYZ {worst_xyz}");
    // white → D50
    let mut w = [[0.0; 3]];
    t.transform_pixels(&[[1.0; 3]], &mut w);
    for c in 0..3 {
        assert!((w[0][c] - icc::D50[c]).abs() < 2e-4, "{:?}", w[0]);
    }
}

#[test]
fn lcms_agrees_with_the_calibration() {
    check(&acer(&FitOptions::default()), "acer table least-squares");
    check(
        &acer(&FitOptions {
            transfer: TransferKind::Gamma,
            matrix: MatrixFit::Cowan,
            ..Default::default()
        }),
        "acer gamma cowan",
    );
}

#[test]
fn pure_gamma_without_black_uses_para() {
    // a black-free gamma calibration: para curves, still agreeing with lcms
    let mut d = acer(&FitOptions {
        transfer: TransferKind::Gamma,
        ..Default::default()
    })
    .data()
    .clone();
    d.black = [0.0; 3];
    let cal = Calibration::new(d).unwrap();
    let bytes = icc::profile(&cal, "para").unwrap();
    assert!(bytes.windows(4).any(|w| w == b"para"));
    check(&cal, "para");
}
