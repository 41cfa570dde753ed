//! The built-in Cornell box's spectra (`data/cornell/`, from the Cornell Program of Computer
//! Graphics' "Cornell Box Data" page) against an independent transcription of the same page:
//! the visionaray renderer's `spd_cornell.h` (MIT), its four arrays copied beside this test in
//! `data/cornell/visionaray_spd_cornell.txt`. Every value must agree to the page's 3 decimals
//! ([`DECIMALS`]), at the same wavelengths (400–700 nm in 4 nm steps; the light at 400, 500,
//! 600 and 700 nm).

use std::collections::BTreeMap;
use std::path::Path;

/// The page gives 3 decimals: two transcriptions agree within half a unit of the last one.
const DECIMALS: f64 = 0.5e-3;

fn repo(p: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").join(p);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The transcription: name → values.
fn visionaray() -> BTreeMap<String, Vec<f64>> {
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/cornell/visionaray_spd_cornell.txt"),
    )
    .unwrap();
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| {
            let mut w = l.split_whitespace();
            let name = w.next().unwrap().to_string();
            (name, w.map(|v| v.parse().unwrap()).collect())
        })
        .collect()
}

/// A project CSV: the wavelengths and each named column.
fn csv(p: &str) -> (Vec<f64>, BTreeMap<String, Vec<f64>>) {
    let text = repo(p);
    let mut lines = text.lines();
    let names: Vec<String> = lines
        .next()
        .unwrap()
        .split(',')
        .skip(1)
        .map(str::to_string)
        .collect();
    let mut nm = Vec::new();
    let mut cols: BTreeMap<String, Vec<f64>> = BTreeMap::new();
    for l in lines.filter(|l| !l.trim().is_empty()) {
        let v: Vec<f64> = l.split(',').map(|x| x.trim().parse().unwrap()).collect();
        nm.push(v[0]);
        for (n, x) in names.iter().zip(&v[1..]) {
            cols.entry(n.clone()).or_default().push(*x);
        }
    }
    (nm, cols)
}

#[test]
fn cornell_spectra_match_an_independent_transcription() {
    let other = visionaray();
    let (nm, refl) = csv("data/cornell/cornell_box_reflectance.csv");
    assert_eq!(
        nm,
        (0..76).map(|i| 400.0 + 4.0 * i as f64).collect::<Vec<_>>()
    );
    for name in ["white", "green", "red"] {
        let (ours, theirs) = (&refl[name], &other[name]);
        assert_eq!(ours.len(), theirs.len(), "{name}");
        for (i, (a, b)) in ours.iter().zip(theirs).enumerate() {
            assert!(
                (a - b).abs() <= DECIMALS,
                "{name} at {} nm: {a} vs {b}",
                nm[i]
            );
        }
    }
    let (nm, light) = csv("data/cornell/cornell_box_light.csv");
    assert_eq!(nm, [400.0, 500.0, 600.0, 700.0]);
    for (a, b) in light["light"].iter().zip(&other["light"]) {
        assert!((a - b).abs() <= DECIMALS, "light: {a} vs {b}");
    }
}
