//! `specpoly xyz` end to end through the real binary, against a colour computation written here
//! independently of the crate: the data/ CSVs parsed directly, linearly interpolated to 1 nm
//! (end values held: the ColorChecker stops at 730 nm), multiplied, summed in f64 over
//! 380–780 nm, CIELAB by the CIE 015 formula, CIEDE2000 from the `palette` crate.

use crate::common::cli;
use crate::reference_1nm;

use palette::color_difference::Ciede2000;
use palette::white_point::D65 as PD65;

use cli::specpoly;
use reference_1nm::{cmf_1nm, column_at, light_1nm, read, to_1nm};

fn cmf(observer: &str) -> Vec<[f64; 3]> {
    cmf_1nm(if observer == "1931" {
        "cie1931_2deg_1nm.csv"
    } else {
        "cie1964_10deg_1nm.csv"
    })
}

fn patch(name: &str) -> Vec<f64> {
    let (head, rows) = read("reflectances/colorchecker_babelcolor_average.csv");
    let j = head
        .iter()
        .position(|h| h == name)
        .or_else(|| head.iter().position(|h| h.starts_with(&format!("{name} "))))
        .expect(name);
    let (x, y) = column_at(&rows, j);
    to_1nm(&x, &y)
}

/// Independent reference: (XYZ, Lab) of the product of `patches` under `illum`.
fn reference(patches: &[&str], illum: &str, observer: &str) -> ([f64; 3], [f64; 3]) {
    let c = cmf(observer);
    let s = light_1nm(illum);
    let r: Vec<Vec<f64>> = patches.iter().map(|p| patch(p)).collect();
    let (mut xyz, mut w) = ([0.0; 3], [0.0; 3]);
    for i in 0..401 {
        let refl: f64 = r.iter().map(|v| v[i]).product();
        for k in 0..3 {
            w[k] += s[i] * c[i][k];
            xyz[k] += refl * s[i] * c[i][k];
        }
    }
    let k = 100.0 / w[1];
    let xyz = xyz.map(|v| v * k);
    let w = w.map(|v| v * k);
    let f = |t: f64| {
        let d: f64 = 6.0 / 29.0;
        if t > d * d * d {
            t.cbrt()
        } else {
            t / (3.0 * d * d) + 4.0 / 29.0
        }
    };
    let (fx, fy, fz) = (f(xyz[0] / w[0]), f(xyz[1] / w[1]), f(xyz[2] / w[2]));
    (
        xyz,
        [116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)],
    )
}

fn de00(p: [f64; 3], q: [f64; 3]) -> f64 {
    palette::Lab::<PD65, f64>::new(p[0], p[1], p[2])
        .difference(palette::Lab::<PD65, f64>::new(q[0], q[1], q[2]))
}

/// Runs `xyz --json` and returns `(name, [X,Y,Z], [L,a,b])` per row.
fn xyz_json(args: &[&str]) -> Vec<(String, [f64; 3], [f64; 3])> {
    let mut a = vec!["xyz", "--json"];
    a.extend_from_slice(args);
    let (code, out, err) = specpoly(&a);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    v.as_array()
        .unwrap()
        .iter()
        .map(|o| {
            let g = |k: &str| o[k].as_f64().unwrap();
            (
                o["name"].as_str().unwrap().to_string(),
                [g("X"), g("Y"), g("Z")],
                [g("L"), g("a"), g("b")],
            )
        })
        .collect()
}

const PATCHES: [&str; 6] = ["dark skin", "blue", "green", "red", "yellow", "white"];

#[test]
fn exact_agrees_with_an_independent_1nm_computation() {
    let specs: Vec<String> = PATCHES
        .iter()
        .map(|p| format!("colorchecker#{p}"))
        .collect();
    let mut worst: f64 = 0.0;
    for illum in ["D65", "A", "FL2", "FL11"] {
        for obs in ["1931", "1964"] {
            let mut args: Vec<&str> = specs.iter().map(String::as_str).collect();
            args.extend(["--repr", "exact", "--illuminant", illum, "--observer", obs]);
            let rows = xyz_json(&args);
            assert_eq!(rows.len(), PATCHES.len());
            for (row, p) in rows.iter().zip(PATCHES) {
                let (xyz, lab) = reference(&[p], illum, obs);
                let d = de00(row.2, lab);
                worst = worst.max(d);
                assert!(d < 0.01, "{p} {illum} {obs}: ΔE00 {d}");
                assert!(
                    (row.1[1] - xyz[1]).abs() < 0.01,
                    "{p} Y {} {}",
                    row.1[1],
                    xyz[1]
                );
            }
            // an inter-reflection chain
            let rows = xyz_json(&[
                "colorchecker#red",
                "colorchecker#blue",
                "colorchecker#yellow",
                "--product",
                "--repr",
                "exact",
                "--illuminant",
                illum,
                "--observer",
                obs,
            ]);
            assert_eq!(rows.len(), 1);
            let (_, lab) = reference(&["red", "blue", "yellow"], illum, obs);
            let d = de00(rows[0].2, lab);
            assert!(d < 0.01, "product {illum} {obs}: ΔE00 {d}");
        }
    }
    eprintln!("worst ΔE00 exact vs independent: {worst:.2e}");
}

#[test]
fn white_patch_under_d65() {
    // BabelColor's average white patch: Y ≈ 91 (reflectance ≈ 0.9), L* ≈ 96.5, near neutral.
    let rows = xyz_json(&[
        "colorchecker#white",
        "--illuminant",
        "D65",
        "--observer",
        "1931",
    ]);
    let (name, xyz, lab) = &rows[0];
    assert!(name.starts_with("colorchecker#white"), "{name}");
    assert!((xyz[1] - 91.23).abs() < 0.1, "Y {}", xyz[1]);
    assert!((lab[0] - 96.51).abs() < 0.05, "L {}", lab[0]);
    assert!(lab[1].abs() < 1.5 && lab[2].abs() < 3.0, "{lab:?}");
    let (rx, rl) = reference(&["white"], "D65", "1931");
    assert!(de00(*lab, rl) < 0.05 && (xyz[0] - rx[0]).abs() < 0.05);
}

#[test]
fn json_keys_and_text_output() {
    let (code, out, _) = specpoly(&["xyz", "colorchecker#red", "--json"]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let obj = v[0].as_object().unwrap();
    let mut keys: Vec<&str> = obj.keys().map(String::as_str).collect();
    keys.sort_unstable();
    let mut want = vec!["name", "X", "Y", "Z", "x", "y", "L", "a", "b"];
    want.sort_unstable();
    assert_eq!(keys, want);
    let (code, out, _) = specpoly(&["xyz", "colorchecker#red", "colorchecker#blue"]);
    assert_eq!(code, 0);
    assert_eq!(out.lines().count(), 4, "{out}"); // comment, header, two rows
    assert!(out.contains("colorchecker#blue"));
}

#[test]
fn every_repr_runs_and_poly_beats_rgb_on_products() {
    // Chains of 2 and 3 patches under a spiky and a smooth light.
    let chains: [&[&str]; 4] = [
        &["red", "blue"],
        &["green", "red", "yellow"],
        &["blue", "dark skin"],
        &["yellow", "green", "blue"],
    ];
    let mut err = std::collections::HashMap::<&str, Vec<f64>>::new();
    for illum in ["FL11", "D65"] {
        for chain in chains {
            let (_, lab) = reference(chain, illum, "1964");
            for repr in ["poly", "paper", "poly:4x3", "sampled:32", "rgb", "exact"] {
                let mut args: Vec<String> =
                    chain.iter().map(|p| format!("colorchecker#{p}")).collect();
                args.extend(["--product", "--repr", repr, "--illuminant", illum].map(String::from));
                let a: Vec<&str> = args.iter().map(String::as_str).collect();
                let rows = xyz_json(&a);
                err.entry(repr).or_default().push(de00(rows[0].2, lab));
            }
        }
    }
    let mean = |r: &str| err[r].iter().sum::<f64>() / err[r].len() as f64;
    let max = |r: &str| err[r].iter().cloned().fold(0.0, f64::max);
    eprintln!(
        "mean ΔE00: poly {:.3} paper {:.3} rgb {:.3} sampled:32 {:.3}",
        mean("poly"),
        mean("paper"),
        mean("rgb"),
        mean("sampled:32")
    );
    assert!(max("exact") < 0.01);
    assert!(max("poly") < 0.5 && mean("poly") < 0.1);
    assert!(
        mean("rgb") > 10.0 * mean("poly"),
        "rgb {} poly {}",
        mean("rgb"),
        mean("poly")
    );
    assert!(mean("paper") > mean("poly"));
}

#[test]
fn a_csv_file_and_its_columns() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("flat.csv");
    std::fs::write(
        &p,
        "wavelength_nm,half,quarter\n380,0.5,0.25\n780,0.5,0.25\n",
    )
    .unwrap();
    let f = p.to_str().unwrap();
    let rows = xyz_json(&[&format!("{f}#*"), "--repr", "poly"]);
    assert_eq!(rows.len(), 2);
    // a flat 0.5 reflectance: Y = 50 exactly, a* = b* = 0
    assert!((rows[0].1[1] - 50.0).abs() < 1e-3, "{:?}", rows[0]);
    assert!(rows[0].2[1].abs() < 1e-3 && rows[0].2[2].abs() < 1e-3);
    // the product 0.5 · 0.25 = 0.125
    let rows = xyz_json(&[&format!("{f}#half"), &format!("{f}#quarter"), "--product"]);
    assert!((rows[0].1[1] - 12.5).abs() < 1e-3, "{:?}", rows[0]);
    // a light from a file (equal energy) equals the built-in E
    let l = dir.path().join("e.csv");
    std::fs::write(&l, "wavelength_nm,E\n380,1\n780,1\n").unwrap();
    let a = xyz_json(&["colorchecker#red", "--illuminant", l.to_str().unwrap()]);
    let b = xyz_json(&["colorchecker#red", "--illuminant", "E"]);
    assert!((a[0].1[0] - b[0].1[0]).abs() < 1e-3);
}
