//! Colour accuracy against the 1 nm reference (issue: default mean ≤ 0.1, max ≤ 0.5 ΔE00).
//!
//! Reference, computed here independently of the crate: the ColorChecker reflectances
//! (data/reflectances, 10 nm, held beyond 730 nm) and the illuminants (data/illuminants, 5 nm)
//! linearly interpolated to 1 nm, times the CIE 1964 observer (data/cmf, 1 nm), summed in f64
//! over 380–780 nm; products of reflectances taken at 1 nm. The crate under test fits each
//! reflectance, multiplies with degree reduction, and integrates against the light's moments.

use crate::common::reference_1nm;

use reference_1nm::{cmf_1nm, light_1nm, read, to_1nm};
use specpoly_core::{
    delta_e2000, Illuminant, Lab, Layout, Moments, Observer, Paper, Spectrum, Tabulated, Uniform,
};

struct Data {
    cmf: Vec<[f64; 3]>,            // 380..=780
    refl: Vec<(String, Vec<f64>)>, // 1 nm, 380..=780
    wl: Vec<f32>,
    raw: Vec<Vec<f32>>,
}

fn data() -> Data {
    let cmf = cmf_1nm("cie1964_10deg_1nm.csv");
    let (head, rows) = read("reflectances/colorchecker_babelcolor_average.csv");
    let x: Vec<f64> = rows.iter().map(|r| r[0]).collect();
    let mut refl = Vec::new();
    let mut raw = Vec::new();
    for (j, name) in head.iter().enumerate().skip(1) {
        let y: Vec<f64> = rows.iter().map(|r| r[j]).collect();
        refl.push((name.clone(), to_1nm(&x, &y)));
        raw.push(y.iter().map(|v| *v as f32).collect());
    }
    Data {
        cmf,
        refl,
        wl: x.iter().map(|v| *v as f32).collect(),
        raw,
    }
}

/// Reference XYZ and white of a 1 nm reflectance under a 1 nm light.
fn reference(d: &Data, light: &[f64], r: &[f64]) -> ([f64; 3], [f64; 3]) {
    let (mut xyz, mut w) = ([0.0; 3], [0.0; 3]);
    for i in 0..401 {
        for k in 0..3 {
            w[k] += light[i] * d.cmf[i][k];
            xyz[k] += r[i] * light[i] * d.cmf[i][k];
        }
    }
    let n = 100.0 / w[1];
    (xyz.map(|v| v * n), w.map(|v| v * n))
}

/// Every chain of 1, 2 and 3 distinct patches (singles, all pairs, every 7th triple).
fn chains(n: usize) -> Vec<Vec<usize>> {
    let mut v: Vec<Vec<usize>> = (0..n).map(|i| vec![i]).collect();
    for i in 0..n {
        for j in i + 1..n {
            v.push(vec![i, j]);
        }
    }
    let mut t = 0;
    for i in 0..n {
        for j in i + 1..n {
            for k in j + 1..n {
                if t % 7 == 0 {
                    v.push(vec![i, j, k]);
                }
                t += 1;
            }
        }
    }
    v
}

/// (mean, max) ΔE00 per chain length 1..=3 for one representation.
fn errors<const S: usize, const C: usize, L: Layout<S>>() -> [(f64, f64); 3] {
    let d = data();
    let fits: Vec<Spectrum<S, C, L>> = d
        .raw
        .iter()
        .map(|v| Spectrum::fit(&Tabulated::new(&d.wl, v).unwrap()).unwrap())
        .collect();
    let mut acc = [(0.0, 0.0, 0usize); 3];
    for (ill, file) in [
        (Illuminant::D65, "D65"),
        (Illuminant::A, "A"),
        (Illuminant::FL2, "FL2"),
        (Illuminant::FL11, "FL11"),
    ] {
        let light = light_1nm(file);
        let m = Moments::<S, C, L>::new(Observer::Cie1964, &ill.tabulated());
        for chain in chains(d.refl.len()) {
            let r: Vec<f64> = (0..401)
                .map(|i| chain.iter().map(|&c| d.refl[c].1[i]).product())
                .collect();
            let (want, white) = reference(&d, &light, &r);
            let p = chain[1..]
                .iter()
                .fold(fits[chain[0]], |p, &c| p.mul(&fits[c]));
            let got = m.xyz(&p).to_array().map(|v| v as f64);
            let e = delta_e2000(Lab::from_xyz(want, white), Lab::from_xyz(got, white));
            let a = &mut acc[chain.len() - 1];
            a.0 += e;
            a.1 = f64::max(a.1, e);
            a.2 += 1;
        }
    }
    acc.map(|(s, m, n)| (s / n as f64, m))
}

#[test]
fn default_preset_meets_the_target() {
    let e = errors::<8, 4, Uniform>();
    eprintln!("default 8x3: {e:?}");
    for (len, (mean, max)) in e.iter().enumerate() {
        assert!(*mean <= 0.1, "chain {}: mean ΔE00 {mean}", len + 1);
        assert!(*max <= 0.5, "chain {}: max ΔE00 {max}", len + 1);
    }
}

#[test]
fn paper_preset_is_the_papers_accuracy_and_worse_than_the_default() {
    let e = errors::<2, 4, Paper>();
    let d = errors::<8, 4, Uniform>();
    eprintln!("paper 2x3: {e:?}");
    // measured here: mean ≈ 0.8–1.2 on single reflectances (issue's reference figure)
    assert!(
        (0.5..2.0).contains(&e[0].0),
        "paper singles mean {}",
        e[0].0
    );
    for len in 0..3 {
        assert!(
            e[len].0 > 5.0 * d[len].0,
            "chain {}: paper not worse",
            len + 1
        );
    }
}
