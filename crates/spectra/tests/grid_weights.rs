//! One grid's linear map `W`: for the 24 ColorChecker reflectances (10 nm, 380–730 nm, ends
//! held) it gives every representation's per-reflectance colour ([`colour::chains`]) to f32
//! rounding, and in `exact` the f64 1 nm sum of the interpolant ([`colour::reference`], summed
//! wavelength by wavelength, not through `W`).

use specpoly_core::{Illuminant, Observer, Tabulated};
use specpoly_spectra::colour;
use specpoly_spectra::grid_weights::GridWeights;
use specpoly_spectra::repr::Repr;
use specpoly_spectra::spectrum_names::resolve;

fn close(a: [f64; 3], b: [f64; 3], tol: f64, what: &str) {
    for k in 0..3 {
        // relative to the white (Y = 100): dark colours' components are small
        assert!(
            (a[k] - b[k]).abs() <= tol * (100.0 + b[k].abs()),
            "{what}: {a:?} vs {b:?}"
        );
    }
}

#[test]
fn w_times_samples_is_each_representations_colour() {
    let cc = resolve("colorchecker#*").unwrap();
    let wl = cc[0].wavelengths.clone();
    let tabs: Vec<Tabulated<'_>> = cc.iter().map(|n| n.tabulated()).collect();
    let chains: Vec<Vec<usize>> = (0..tabs.len()).map(|i| vec![i]).collect();
    for (light, observer) in [
        (Illuminant::D65, Observer::Cie1931),
        (Illuminant::FL11, Observer::Cie2015_10),
    ] {
        let lt = light.tabulated();
        for repr in [
            "poly",
            "paper",
            "poly:4x5",
            "sampled:41",
            "hero:4",
            "rgb",
            "exact",
        ] {
            let repr: Repr = repr.parse().unwrap();
            let w = GridWeights::new(repr, observer, &lt, &wl).unwrap();
            assert_eq!(w.len(), wl.len());
            // built in two parts (as a parallel caller does): the same matrix
            let parts = [0..10, 10..wl.len()]
                .map(|c| GridWeights::columns(repr, observer, &lt, &wl, c).unwrap());
            assert_eq!(GridWeights::from_columns(observer, &lt, parts), w);
            let per = colour::chains(repr, observer, &lt, &tabs, &chains).unwrap();
            for (i, n) in cc.iter().enumerate() {
                let r: Vec<f64> = n.values.iter().map(|v| *v as f64).collect();
                let c = w.colour(&r);
                assert_eq!(c.white, per[i].white);
                close(c.xyz, per[i].xyz, 2e-6, &format!("{repr} {}", n.name));
                if repr == Repr::Exact {
                    let want = colour::reference(observer, &lt, &tabs, &[i]);
                    close(
                        c.xyz,
                        want.xyz,
                        2e-6,
                        &format!("exact reference {}", n.name),
                    );
                }
            }
        }
    }
}

#[test]
fn a_grid_that_is_not_increasing_is_refused() {
    let lt = Illuminant::D65.tabulated();
    let e = GridWeights::new(
        Repr::DEFAULT,
        Observer::Cie1964,
        &lt,
        &[400.0, 500.0, 450.0],
    );
    assert!(e.is_err());
}

#[test]
fn rows_are_read_and_refused_as_the_per_reflectance_path_does() {
    let cc = resolve("colorchecker#*").unwrap();
    let wl = cc[0].wavelengths.clone();
    let lt = Illuminant::D65.tabulated();
    let w = GridWeights::new(Repr::DEFAULT, Observer::Cie1964, &lt, &wl).unwrap();
    let r: Vec<f64> = cc[5].values.iter().map(|v| *v as f64).collect();
    assert_eq!(w.reflectance_xyz(&r, 1.0), Some(w.colour(&r).xyz));
    // percent data with scale 0.01: the library's scaled samples, f32 (x · 0.01)
    let pct: Vec<f64> = r.iter().map(|v| v * 100.0).collect();
    let scaled: Vec<f64> = pct
        .iter()
        .map(|v| ((*v as f32) as f64 * 0.01) as f32 as f64)
        .collect();
    assert_eq!(w.reflectance_xyz(&pct, 0.01), Some(w.colour(&scaled).xyz));
    // what the per-reflectance path refuses, in the body and in the tail of the row
    for (i, bad) in [(3, f64::NAN), (9, -0.02), (35, 1.6), (34, f64::INFINITY)] {
        let mut b = r.clone();
        b[i] = bad;
        assert_eq!(w.reflectance_xyz(&b, 1.0), None, "{i}: {bad}");
    }
    // the bounds themselves are reflectances
    let mut edge = r.clone();
    edge[0] = 1.5;
    edge[1] = -0.01;
    assert!(w.reflectance_xyz(&edge, 1.0).is_some());
    assert_eq!(w.reflectance_xyz(&r[1..], 1.0), None);
    assert_eq!(w.reflectance_xyz(&r, 0.0), None);
}
