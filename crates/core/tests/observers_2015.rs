//! The CIE 2015 observers (CIE 170-2) built in: XYZ of every shipped illuminant and reflectance
//! under them equals an independent f64 1 nm sum written here — the published table read from
//! data/cmf as text (zero below its first row, 390 nm), the spectra read from data/ and linearly
//! interpolated (end values held), normalised to Y = 100 for the light's white — within 1e-5
//! relative. And a runtime table ([`CmfTable`]) equal to a built-in gives the same numbers.

use specpoly_core::{exact_xyz, CmfTable, Illuminant, Moments, Observer, Tabulated};

fn csv(path: &str) -> Vec<Vec<f64>> {
    std::fs::read_to_string(format!("{}/../../data/{path}", env!("CARGO_MANIFEST_DIR")))
        .unwrap()
        .lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.split(',').map(|c| c.trim().parse().unwrap()).collect())
        .collect()
}

/// Column `col` of `rows` at `nm`: linear between rows, end values held outside.
fn interp(rows: &[Vec<f64>], col: usize, nm: f64) -> f64 {
    let n = rows.len();
    if nm <= rows[0][0] {
        return rows[0][col];
    }
    if nm >= rows[n - 1][0] {
        return rows[n - 1][col];
    }
    let i = rows.iter().position(|r| r[0] >= nm).unwrap();
    let (a, b) = (&rows[i - 1], &rows[i]);
    a[col] + (b[col] - a[col]) * (nm - a[0]) / (b[0] - a[0])
}

/// The independent sum: XYZ of reflectance `r` (None: the light itself) under `light`.
fn reference(cmf: &[Vec<f64>], light: &[Vec<f64>], r: Option<(&[Vec<f64>], usize)>) -> [f64; 3] {
    let (mut xyz, mut wy) = ([0.0f64; 3], 0.0f64);
    for nm in 380..=780 {
        let Some(row) = cmf.iter().find(|c| c[0] as i32 == nm) else {
            continue; // below 390 nm: the observer is zero
        };
        let s = interp(light, 1, nm as f64);
        let rv = r.map_or(1.0, |(t, c)| interp(t, c, nm as f64));
        for k in 0..3 {
            xyz[k] += s * rv * row[k + 1];
        }
        wy += s * row[2];
    }
    xyz.map(|v| 100.0 * v / wy)
}

fn rel(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3)
        .map(|k| (a[k] - b[k]).abs() / b[k].abs().max(1e-3))
        .fold(0.0, f64::max)
}

const LIGHTS: [(Illuminant, &str); 6] = [
    (Illuminant::A, "A"),
    (Illuminant::D50, "D50"),
    (Illuminant::D65, "D65"),
    (Illuminant::FL2, "FL2"),
    (Illuminant::FL7, "FL7"),
    (Illuminant::FL11, "FL11"),
];

const REFLECTANCES: [&str; 4] = [
    "reflectances/colorchecker_babelcolor_average.csv",
    "reflectances/cie13_3_tcs14_5nm.csv",
    "reflectances/cie224_2017_ces99_5nm.csv",
    "reflectances/cie224_2017_ces99_1nm.csv",
];

/// Largest relative deviation over every shipped light and every reflectance under D65 and A.
fn worst(observer: Observer, file: &str) -> (f64, usize) {
    let cmf = csv(file);
    let (mut worst, mut count) = (0.0f64, 0);
    for (ill, name) in LIGHTS {
        let light = csv(&format!("illuminants/{name}.csv"));
        let tab = ill.tabulated();
        // the light itself: the white of its moments and of the 1 nm reference
        let (_, white) = exact_xyz(observer, &tab, |_| 1.0);
        let m = Moments::<8, 4>::new(observer, &tab).white();
        let want = reference(&cmf, &light, None);
        worst = worst.max(rel(white, want));
        worst = worst.max(rel(<[f64; 3]>::from(m), want));
        count += 1;
        if !matches!(ill, Illuminant::D65 | Illuminant::A) {
            continue;
        }
        for rfile in REFLECTANCES {
            let refl = csv(rfile);
            let w: Vec<f32> = refl.iter().map(|r| r[0] as f32).collect();
            for c in 1..refl[0].len() {
                let v: Vec<f32> = refl.iter().map(|r| r[c] as f32).collect();
                let t = Tabulated::new(&w, &v).unwrap();
                let (got, _) = exact_xyz(observer, &tab, |nm| t.at(nm));
                worst = worst.max(rel(got, reference(&cmf, &light, Some((&refl, c)))));
                count += 1;
            }
        }
    }
    (worst, count)
}

#[test]
fn cie2015_2deg_xyz_of_the_shipped_spectra_equal_an_f64_1nm_sum() {
    let (w, n) = worst(Observer::Cie2015_2, "cmf/cie2015_2deg_1nm.csv");
    eprintln!("CIE 2015 2°: worst relative deviation {w:.1e} over {n} spectra");
    assert!(n > 400, "{n} spectra");
    assert!(w < 1e-5, "worst relative deviation {w:e} over {n} spectra");
}

#[test]
fn cie2015_10deg_xyz_of_the_shipped_spectra_equal_an_f64_1nm_sum() {
    let (w, n) = worst(Observer::Cie2015_10, "cmf/cie2015_10deg_1nm.csv");
    eprintln!("CIE 2015 10°: worst relative deviation {w:.1e} over {n} spectra");
    assert!(w < 1e-5, "worst relative deviation {w:e} over {n} spectra");
}

#[test]
fn a_runtime_table_is_used_like_a_builtin_one() {
    let values = *Observer::Cie2015_10.table();
    let table: &'static CmfTable =
        Box::leak(Box::new(CmfTable::new("copy of 2015-10", values).unwrap()));
    let o = Observer::Table(table);
    assert_eq!(o.name(), "copy of 2015-10");
    assert!(!o.is_builtin());
    let light = Illuminant::FL11.tabulated();
    let r = |nm: f64| 0.5 + 0.4 * (nm / 23.0).sin();
    assert_eq!(
        exact_xyz(o, &light, r),
        exact_xyz(Observer::Cie2015_10, &light, r)
    );
    assert_eq!(
        Moments::<8, 4>::new(o, &light),
        Moments::<8, 4>::new(Observer::Cie2015_10, &light)
    );
}

#[test]
fn runtime_tables_refuse_negative_non_finite_and_empty_channels() {
    let mut v = *Observer::Cie1931.table();
    v[100][1] = -0.01;
    assert_eq!(
        CmfTable::new("x", v),
        Err(specpoly_core::Error::Negative(100))
    );
    v[100][1] = f32::NAN;
    assert_eq!(
        CmfTable::new("x", v),
        Err(specpoly_core::Error::NonFinite(100))
    );
    let mut v = *Observer::Cie1931.table();
    for r in v.iter_mut() {
        r[2] = 0.0;
    }
    assert_eq!(
        CmfTable::new("x", v),
        Err(specpoly_core::Error::ZeroChannel(2))
    );
}

#[test]
fn builtin_names_round_trip() {
    for o in Observer::ALL {
        assert_eq!(Observer::from_name(o.name()), Some(o));
    }
    assert_eq!(
        Observer::from_name("CIE2015-10"),
        Some(Observer::Cie2015_10)
    );
    assert_eq!(Observer::from_name("cié"), None);
}
