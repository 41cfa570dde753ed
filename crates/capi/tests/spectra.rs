//! The spectra functions: the compiled-in moments are the core's `Moments::new` to the bit
//! (every moment read back through `sp_spectrum_xyz` with a unit coefficient), and the XYZ of
//! fitted spectra agrees with colour-science's (an independent 1 nm integration of the same
//! samples, `tests/data/spectra_references.py`).

use specpoly_c::display::SpXyz;
use specpoly_c::spectrum::{
    sp_light_white, sp_spectrum_eval, sp_spectrum_fit, sp_spectrum_mul, sp_spectrum_xyz,
    SpIlluminant, SpObserver, SpSpectrum,
};
use specpoly_c::SpStatus;
use specpoly_core::{Illuminant, Moments, Observer};
use std::fmt::Write;
use std::path::Path;

const OBSERVERS: [(SpObserver, Observer); 4] = [
    (SpObserver::Cie1931, Observer::Cie1931),
    (SpObserver::Cie1964, Observer::Cie1964),
    (SpObserver::Cie2015_2, Observer::Cie2015_2),
    (SpObserver::Cie2015_10, Observer::Cie2015_10),
];

const LIGHTS: [(SpIlluminant, Illuminant); 7] = [
    (SpIlluminant::A, Illuminant::A),
    (SpIlluminant::D50, Illuminant::D50),
    (SpIlluminant::D65, Illuminant::D65),
    (SpIlluminant::E, Illuminant::E),
    (SpIlluminant::Fl2, Illuminant::FL2),
    (SpIlluminant::Fl7, Illuminant::FL7),
    (SpIlluminant::Fl11, Illuminant::FL11),
];

/// `src/lights.rs` as generated from the core's `Moments::new`.
fn lights_source() -> String {
    let mut s = String::from(
        "//! The moments of the built-in lights under the four built-in observers for the default\n\
         //! spectrum (8 uniform cubic spans): `specpoly_core::Moments::new`'s values printed in\n\
         //! their shortest round-trip form. Generated, and checked to the bit, by the test\n\
         //! `spectra::the_compiled_in_moments_are_the_cores`\n\
         //! (`SPECPOLY_WRITE_LIGHTS=1 cargo test -p specpoly-c --test main spectra`); do not edit.\n\n\
         use specpoly_core::{Moments, Xyz};\n\n\
         /// Observers in the table, in `SpObserver` order: CIE 1931, CIE 1964, CIE 2015 2°,\n\
         /// CIE 2015 10°.\n\
         pub(crate) const OBSERVERS: usize = 4;\n\
         /// Lights per observer, in `Illuminant::ALL` order.\n\
         pub(crate) const LIGHTS: usize = 7;\n\n\
         /// Observer-major: entry `o · LIGHTS + i`.\n\
         #[rustfmt::skip]\n\
         pub(crate) static MOMENTS: [Moments<8, 4>; OBSERVERS * LIGHTS] = [\n",
    );
    for (_, o) in OBSERVERS {
        for (_, i) in LIGHTS {
            let m = Moments::<8, 4>::new(o, &i.tabulated());
            let w = m.white();
            writeln!(
                s,
                "    // {} {}\n    Moments::from_parts({:?}, Xyz::new({:?}, {:?}, {:?})),",
                o.name(),
                i.name(),
                m.moments(),
                w.x,
                w.y,
                w.z
            )
            .unwrap();
        }
    }
    s.push_str("];\n");
    s
}

fn xyz(s: &SpSpectrum, o: SpObserver, i: SpIlluminant) -> (SpStatus, SpXyz) {
    let mut out = SpXyz::default();
    // SAFETY: valid pointers.
    let st = unsafe { sp_spectrum_xyz(s, o as i32, i as i32, &mut out) };
    (st, out)
}

#[test]
fn the_compiled_in_moments_are_the_cores() {
    if std::env::var_os("SPECPOLY_WRITE_LIGHTS").is_some() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/lights.rs");
        let tmp = path.with_extension("rs.tmp");
        std::fs::write(&tmp, lights_source()).unwrap();
        std::fs::rename(&tmp, &path).unwrap();
    }
    assert_eq!(
        Illuminant::ALL.map(|i| i.name()),
        LIGHTS.map(|(_, i)| i.name())
    );
    for (so, o) in OBSERVERS {
        for (si, i) in LIGHTS {
            let m = Moments::<8, 4>::new(o, &i.tabulated());
            let mut white = SpXyz::default();
            // SAFETY: a valid pointer.
            assert_eq!(
                unsafe { sp_light_white(so as i32, si as i32, &mut white) },
                SpStatus::Ok
            );
            let w = m.white();
            assert_eq!(
                [white.x, white.y, white.z].map(f32::to_bits),
                [w.x, w.y, w.z].map(f32::to_bits)
            );
            for k in 0..4 {
                for s in 0..8 {
                    let mut unit = SpSpectrum::default();
                    unit.coef[k][s] = 1.0;
                    let (st, v) = xyz(&unit, so, si);
                    assert_eq!(st, SpStatus::Ok);
                    let want = [0, 1, 2].map(|a| m.moments()[a][k][s].to_bits());
                    assert_eq!(
                        [v.x, v.y, v.z].map(f32::to_bits),
                        want,
                        "{o:?} {i:?} T{k} span {s}"
                    );
                }
            }
        }
    }
}

/// The samples of `tests/data/spectra_samples.csv`: wavelengths and one column per patch.
pub fn samples() -> (Vec<f32>, Vec<(String, Vec<f32>)>) {
    let text = include_str!("data/spectra_samples.csv");
    let mut lines = text.lines();
    let names: Vec<String> = lines
        .next()
        .unwrap()
        .split(',')
        .skip(1)
        .map(String::from)
        .collect();
    let mut nm = Vec::new();
    let mut cols = vec![Vec::new(); names.len()];
    for l in lines {
        let v: Vec<f32> = l.split(',').map(|x| x.parse().unwrap()).collect();
        nm.push(v[0]);
        for (c, x) in cols.iter_mut().zip(&v[1..]) {
            c.push(*x);
        }
    }
    (nm, names.into_iter().zip(cols).collect())
}

fn fit(nm: &[f32], v: &[f32]) -> SpSpectrum {
    let mut s = SpSpectrum::default();
    // SAFETY: slices of equal length, a valid output.
    let st = unsafe { sp_spectrum_fit(nm.as_ptr(), v.as_ptr(), nm.len(), &mut s) };
    assert_eq!(st, SpStatus::Ok);
    s
}

/// colour-science's XYZ (1 nm sums of the samples' interpolant) against the library's (of the
/// 8-span cubic fit, and of the product reduced to cubics). The difference is the fit's (and,
/// for `r²`, the reduction's): at most 0.02 in X, Y or Z (white Y = 100) for `r` and 0.05 for
/// `r²` (measured 0.013 and 0.032 over the four observers, the red's edge at 600 nm the
/// largest).
#[test]
fn fitted_spectra_give_colour_sciences_xyz_within_the_fits_error() {
    let (nm, patches) = samples();
    let refs = include_str!("data/spectra_references.csv");
    let mut worst = [0.0f32; 2];
    let mut n = 0;
    for l in refs.lines().skip(1) {
        let f: Vec<&str> = l.split(',').collect();
        let (_, r) = patches.iter().find(|(p, _)| p == f[0]).unwrap();
        let r = fit(&nm, r);
        let (which, s) = match f[1] {
            "r" => (0, r),
            _ => {
                let mut p = SpSpectrum::default();
                // SAFETY: valid pointers.
                assert_eq!(unsafe { sp_spectrum_mul(&r, &r, &mut p) }, SpStatus::Ok);
                (1, p)
            }
        };
        let light = LIGHTS.iter().find(|(_, i)| i.name() == f[2]).unwrap().0;
        let o = OBSERVERS.iter().find(|(_, o)| o.name() == f[3]).unwrap().0;
        let (st, v) = xyz(&s, o, light);
        assert_eq!(st, SpStatus::Ok);
        let want: Vec<f32> = f[4..7].iter().map(|x| x.parse().unwrap()).collect();
        for (g, w) in [v.x, v.y, v.z].iter().zip(&want) {
            worst[which] = worst[which].max((g - w).abs());
        }
        n += 1;
    }
    assert_eq!(n, 72);
    eprintln!("largest |ΔXYZ|: r {}, r² {}", worst[0], worst[1]);
    assert!(worst[0] <= 0.02 && worst[1] <= 0.05, "{worst:?}");
}

/// The fit and the evaluation agree with the samples' interpolant within the fit's error; the
/// product evaluates to the product of the values (within the reduction's error).
#[test]
fn fit_eval_and_product_follow_the_samples() {
    let (nm, patches) = samples();
    for (name, v) in &patches {
        let s = fit(&nm, v);
        let mut sq = SpSpectrum::default();
        // SAFETY: valid pointers.
        assert_eq!(unsafe { sp_spectrum_mul(&s, &s, &mut sq) }, SpStatus::Ok);
        for (w, want) in nm.iter().zip(v) {
            let (mut a, mut b) = (0.0f32, 0.0f32);
            // SAFETY: valid pointers.
            unsafe {
                assert_eq!(sp_spectrum_eval(&s, *w, &mut a), SpStatus::Ok);
                assert_eq!(sp_spectrum_eval(&sq, *w, &mut b), SpStatus::Ok);
            }
            assert!((a - want).abs() < 0.03, "{name} {w} nm: {a} vs {want}");
            assert!((b - a * a).abs() < 0.01, "{name} {w} nm: {b} vs {}", a * a);
        }
    }
}

#[test]
fn spectra_functions_return_their_status_codes() {
    let nm = [400.0f32, 500.0, 600.0];
    let v = [0.1f32, 0.5, 0.2];
    let mut s = SpSpectrum::default();
    let mut x = 0.0f32;
    let mut out = SpXyz::default();
    let nan = f32::NAN;
    let fit_st = |nm: &[f32], v: &[f32], n: usize, s: *mut SpSpectrum| {
        // SAFETY: `n` is at most the slices' length.
        unsafe { sp_spectrum_fit(nm.as_ptr(), v.as_ptr(), n, s) }
    };
    assert_eq!(fit_st(&nm, &v, 3, &mut s), SpStatus::Ok);
    assert_eq!(fit_st(&nm, &v, 0, &mut s), SpStatus::Size);
    assert_eq!(
        fit_st(&nm, &v, 3, std::ptr::null_mut()),
        SpStatus::NullPointer
    );
    assert_eq!(
        fit_st(&[400.0, nan, 600.0], &v, 3, &mut s),
        SpStatus::NotFinite
    );
    assert_eq!(
        fit_st(&nm, &[0.1, f32::INFINITY, 0.2], 3, &mut s),
        SpStatus::NotFinite
    );
    assert_eq!(
        fit_st(&[400.0, 400.0, 600.0], &v, 3, &mut s),
        SpStatus::Domain
    );
    assert_eq!(
        fit_st(&[800.0, 900.0, 1000.0], &v, 3, &mut s),
        SpStatus::Domain
    );
    // SAFETY: NULL or valid pointers throughout.
    unsafe {
        assert_eq!(
            sp_spectrum_fit(std::ptr::null(), v.as_ptr(), 3, &mut s),
            SpStatus::NullPointer
        );
        assert_eq!(
            sp_spectrum_fit(nm.as_ptr(), v.as_ptr(), usize::MAX, &mut s),
            SpStatus::Size
        );
        assert_eq!(sp_spectrum_eval(&s, 379.9, &mut x), SpStatus::Domain);
        assert_eq!(sp_spectrum_eval(&s, nan, &mut x), SpStatus::NotFinite);
        assert_eq!(
            sp_spectrum_eval(std::ptr::null(), 500.0, &mut x),
            SpStatus::NullPointer
        );
        assert_eq!(sp_spectrum_xyz(&s, 4, 0, &mut out), SpStatus::Domain);
        assert_eq!(sp_spectrum_xyz(&s, 0, 7, &mut out), SpStatus::Domain);
        assert_eq!(sp_spectrum_xyz(&s, -1, 0, &mut out), SpStatus::Domain);
        assert_eq!(sp_light_white(0, -1, &mut out), SpStatus::Domain);
        assert_eq!(
            sp_spectrum_xyz(&s, 0, 0, std::ptr::null_mut()),
            SpStatus::NullPointer
        );
        let mut bad = s;
        bad.coef[3][7] = nan;
        assert_eq!(sp_spectrum_xyz(&bad, 0, 0, &mut out), SpStatus::NotFinite);
        assert_eq!(sp_spectrum_mul(&s, &bad, &mut bad), SpStatus::NotFinite);
        let mut huge = s;
        huge.coef[0][0] = f32::MAX;
        assert_eq!(sp_spectrum_mul(&huge, &huge, &mut bad), SpStatus::NotFinite);
        // `out` may be an input
        let want = {
            let mut p = SpSpectrum::default();
            sp_spectrum_mul(&s, &s, &mut p);
            p
        };
        let mut t = s;
        assert_eq!(sp_spectrum_mul(&t, &s, &mut t), SpStatus::Ok);
        assert_eq!(t, want);
    }
}
