//! The standards' checks against independent references: peak wavelength, FWHM, dominant
//! wavelength and excitation purity against colour-science 0.4.7 and SciPy
//! (`data/light_standards.py`), CIE S 026 α-opic quantities against luxpy 1.12.5
//! (`data/light_standards_alpha_opic.py`) and the standard's own D65 constants, and the
//! ANSI C78.377 quadrangles against the standard's targets. The lights: the 118 of
//! `light_references.rs` plus 21 coloured ones (every channel of `data/leds/`, Gaussian bands
//! Ohno (2005) LED models of known width and
//! red-blue mixes (two of them purples), `data/light_standards_spd.csv`).

use crate::common::light_data::csv;
use specpoly_core::light::{
    alpha_opic::{alpha_opic, K_D65, NAMES},
    ansi_c78377::{nominal_cct, DUV_TOLERANCE, NOMINAL},
    cct::{cct_to_uv, uv_to_xy, Cct},
    spectral::{dominant, fwhm, peak, WHITE_E},
    Spd,
};
use specpoly_core::{Illuminant, Tabulated};

/// Every reference light on its own grid, by name.
fn lights() -> Vec<(String, Spd)> {
    let mut out = vec![];
    for text in [
        include_str!("data/light_references_spd.csv"),
        include_str!("data/light_standards_spd.csv"),
    ] {
        let (_, rows) = csv(text);
        for s in rows {
            let start: f32 = s[1].parse().unwrap();
            let step: f32 = s[2].parse().unwrap();
            let v: Vec<f32> = s[3..].iter().map(|x| x.parse().unwrap()).collect();
            let nm: Vec<f32> = (0..v.len()).map(|i| start + step * i as f32).collect();
            let spd = Spd::new(&Tabulated::new(&nm, &v).unwrap()).unwrap();
            out.push((s[0].clone(), spd));
        }
    }
    out
}

#[test]
fn peak_fwhm_dominant_wavelength_and_purity_agree_with_colour_science() {
    let lights = lights();
    let (head, refs) = csv(include_str!("data/light_standards.csv"));
    assert_eq!(
        head,
        ["name", "peak_nm", "fwhm_nm", "dominant_nm", "purity"]
    );
    assert_eq!((lights.len(), refs.len()), (142, 142));
    let (mut w_fwhm, mut w_dom, mut w_pur) = (
        (0.0, String::new()),
        (0.0f64, String::new()),
        (0.0, String::new()),
    );
    let mut purples = 0;
    for ((name, s), r) in lights.iter().zip(&refs) {
        assert_eq!(name, &r[0]);
        let want: Vec<Option<f64>> = r[1..].iter().map(|x| x.parse().ok()).collect();
        assert_eq!(peak(s).0, want[0].unwrap(), "{name}: peak");
        match (fwhm(s), want[1]) {
            (Some(a), Some(b)) => {
                if (a - b).abs() > w_fwhm.0 {
                    w_fwhm = ((a - b).abs(), name.clone());
                }
            }
            (a, b) => assert_eq!(a, b, "{name}: FWHM defined on one side only"),
        }
        let (wl, pe) = (want[2].unwrap(), want[3].unwrap());
        if pe < 1e-3 {
            // illuminant E itself: no direction, no dominant wavelength
            assert!(
                dominant(s.xy(), WHITE_E).map_or(true, |d| d.purity < 1e-3),
                "{name}"
            );
            continue;
        }
        let d = dominant(s.xy(), WHITE_E).unwrap();
        assert_eq!(
            d.wavelength < 0.0,
            wl < 0.0,
            "{name}: dominant or complementary"
        );
        purples += (wl < 0.0) as usize;
        // colour-science returns the 1 nm locus node nearest the intersection
        if (d.wavelength - wl).abs() > w_dom.0 {
            w_dom = ((d.wavelength - wl).abs(), name.clone());
        }
        if (d.purity - pe).abs() > w_pur.0 {
            w_pur = ((d.purity - pe).abs(), name.clone());
        }
    }
    println!("FWHM worst {:.2e} nm ({}), dominant wavelength worst {:.3} nm ({}), purity worst {:.2e} ({}), {purples} purples", w_fwhm.0, w_fwhm.1, w_dom.0, w_dom.1, w_pur.0, w_pur.1);
    assert!(w_fwhm.0 < 1e-4, "FWHM {w_fwhm:?}");
    assert!(w_dom.0 <= 0.5 + 1e-6, "dominant wavelength {w_dom:?}");
    // colour-science sums a 5 nm light against the 1 nm observer (interpolating the light):
    // the chromaticities differ by up to 1e-4
    assert!(purples == 2 && w_pur.0 < 2e-4, "purity {w_pur:?}");
}

#[test]
fn alpha_opic_quantities_agree_with_luxpy() {
    let lights = lights();
    let (head, refs) = csv(include_str!("data/light_standards_alpha_opic.csv"));
    assert_eq!(head.len(), 12);
    assert_eq!(refs.len(), 142);
    let mut worst: [(f64, String); 2] = Default::default();
    let mut cubic = (0.0f64, String::new());
    for ((name, s), r) in lights.iter().zip(&refs) {
        assert_eq!(name, &r[0]);
        let want: Vec<f64> = r[1..].iter().map(|x| x.parse().unwrap()).collect();
        let a = alpha_opic(s);
        // luxpy's default first interpolates the light to 1 nm (cubic): the same sums for a
        // 1 nm light, a different light for a spiky 5 nm one
        let d1 = (a.der[4] - want[10]) / want[10];
        if s.step() == 1 {
            assert!(d1.abs() < 5e-3, "{name}: melanopic DER {d1}");
        } else if d1.abs() > cubic.0 {
            cubic = (d1.abs(), name.clone());
        }
        for k in 0..5 {
            // ELR in mW/lm; relative differences
            let de = (a.elr[k] * 1e3 - want[k]) / want[k];
            let dd = (a.der[k] - want[5 + k]) / want[5 + k];
            for (i, d) in [de, dd].into_iter().enumerate() {
                if d.abs() > worst[i].0 {
                    worst[i] = (d.abs(), format!("{name} {}", NAMES[k]));
                }
            }
        }
    }
    println!(
        "alpha-opic ELR worst {:.2e} ({}), DER worst {:.2e} ({}); melanopic DER against \
         luxpy's cubic 1 nm interpolation of 5 nm lights: worst {:.2e} ({})",
        worst[0].0, worst[0].1, worst[1].0, worst[1].1, cubic.0, cubic.1
    );
    // the tolerance for melanopic EDI: 0.5 %
    assert!(worst[0].0 < 5e-3 && worst[1].0 < 5e-3, "{worst:?}");
}

#[test]
fn d65_has_the_standards_alpha_opic_efficacies() {
    // CIE S 026 Table 4's K_α,v^D65 (4 significant digits) from the D65 table at 5 nm
    let t = Illuminant::D65.tabulated();
    let a = alpha_opic(&Spd::new(&t).unwrap());
    for k in 0..5 {
        let rel = (a.elr[k] - K_D65[k]) / K_D65[k];
        println!(
            "D65 {}: {:.5} mW/lm, {:+.1e}",
            NAMES[k],
            a.elr[k] * 1e3,
            rel
        );
        assert!(rel.abs() < 5e-4, "{} {rel}", NAMES[k]);
        assert!((a.der[k] - 1.0).abs() < 5e-4);
    }
}

/// CIE 1931 (x, y) of (CCT, Duv).
fn xy(cct: f64, duv: f64) -> [f64; 2] {
    uv_to_xy(cct_to_uv(Cct { cct, duv }).unwrap())
}

#[test]
fn ansi_quadrangles_follow_the_standards_targets() {
    // the target Duv line of the 2015 edition (flexible CCTs), which the corners from 3000 K
    // up follow at the boundary CCTs; 2200-2700 K keep Duv 0
    let line = |t: f64| 57700.0 / (t * t) - 44.6 / t + 0.0085;
    let mut worst = [0.0f64; 2];
    for n in &NOMINAL {
        let c = xy(n.cct, n.duv);
        worst[0] = worst[0].max((c[0] - n.centre[0]).abs().max((c[1] - n.centre[1]).abs()));
        let (lo, hi) = (n.cct - n.cct_tolerance, n.cct + n.cct_tolerance);
        let d = |t: f64| if n.nominal <= 2700 { 0.0 } else { line(t) };
        let want = [
            xy(lo, d(lo) + DUV_TOLERANCE),
            xy(lo, d(lo) - DUV_TOLERANCE),
            xy(hi, d(hi) - DUV_TOLERANCE),
            xy(hi, d(hi) + DUV_TOLERANCE),
        ];
        for (a, b) in n.corners.iter().zip(want) {
            worst[1] = worst[1].max((a[0] - b[0]).abs().max((a[1] - b[1]).abs()));
        }
        // the target point meets its own nominal CCT
        assert_eq!(nominal_cct(c).map(|m| m.nominal), Some(n.nominal));
    }
    println!(
        "ANSI C78.377: centres within {:.1e}, corners within {:.1e} in x, y",
        worst[0], worst[1]
    );
    assert!(worst[0] < 2e-4 && worst[1] < 3e-4, "{worst:?}");
}
