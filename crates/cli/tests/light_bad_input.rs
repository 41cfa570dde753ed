//! `specpoly light` and `specpoly mix` on input no light can be: a spectrum with negative power
//! beyond the noise is refused with one line (values within −1 % of the peak are summed as they
//! are), a light with no blue gets its defined figures and `null`/`-` for the undefined ones (no
//! `NaN`, no panic; `--tm30` refuses it with one line), and a CSV of 10⁶ columns is refused at
//! its header with one line (`specpoly_formats::csv::MAX_COLUMNS`), not parsed.

use crate::common::cli;
use std::fmt::Write as _;
use std::path::Path;

fn specpoly(args: &[&str]) -> (i32, String, String) {
    cli::run_in(cli::ROOT, args).parts()
}

/// A 5 nm table over 380–780 nm of `f(nm)`.
fn write_spd(path: &Path, f: impl Fn(f64) -> f64) {
    let mut t = String::from("wavelength_nm,light\n");
    for nm in (380..=780).step_by(5) {
        let _ = writeln!(t, "{nm},{}", f(nm as f64));
    }
    std::fs::write(path, t).unwrap();
}

fn one_line(err: &str) -> &str {
    assert_eq!(err.lines().count(), 1, "{err}");
    err.trim_end()
}

#[test]
fn a_negative_spectrum_is_refused_and_noise_is_not() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("negative.csv");
    // a flat light with one value of −0.5 at 500 nm: half the peak below zero
    write_spd(&bad, |nm| if nm == 500.0 { -0.5 } else { 1.0 });
    let (code, out, err) = specpoly(&["light", cli::s(&bad)]);
    assert_eq!((code, out.as_str()), (1, ""), "{err}");
    let err = one_line(&err);
    assert!(
        err.contains("negative spectral power -0.5 at 500 nm")
            && err.contains("below -1% of the peak 1"),
        "{err}"
    );
    // the same light as a mixing channel, and in a table of several lights: refused by name
    let (code, _, err) = specpoly(&["light", "D65", cli::s(&bad), "--csv"]);
    assert_eq!(code, 1);
    assert!(one_line(&err).contains("negative.csv"), "{err}");
    let ch = format!("bad={}", cli::s(&bad));
    let (code, _, err) = specpoly(&[
        "mix",
        "--channel",
        "red=data/leds/rgb.csv#red",
        "--channel",
        "green=data/leds/rgb.csv#green",
        "--channel",
        &ch,
        "--target",
        "cct:4000",
    ]);
    assert_eq!(code, 1, "{err}");
    assert!(one_line(&err).contains("negative spectral power"), "{err}");
    // dark-subtraction noise: alternate nodes 0.4 % of the peak below zero is a light
    let noisy = dir.path().join("noisy.csv");
    write_spd(&noisy, |nm| {
        if (nm as i64 / 5) % 2 == 0 {
            1.0
        } else {
            -0.004
        }
    });
    let (code, out, err) = specpoly(&["light", cli::s(&noisy), "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!(v["cct"].as_f64().is_some(), "{out}");
}

#[test]
fn a_light_with_no_blue_has_no_nan() {
    let dir = tempfile::tempdir().unwrap();
    // nothing below 560 nm: a band at 590 nm and one at 630 nm (a low-pressure-sodium-like
    // amber, within 0.05 Duv of the locus) and a deep red alone (far from it)
    let amber = dir.path().join("amber.csv");
    let band = |nm: f64, c: f64, w: f64| (-0.5 * ((nm - c) / w).powi(2)).exp();
    write_spd(&amber, |nm| {
        if nm < 560.0 {
            0.0
        } else {
            band(nm, 590.0, 6.0) + 0.3 * band(nm, 630.0, 10.0)
        }
    });
    let red = dir.path().join("red.csv");
    write_spd(&red, |nm| {
        if nm < 600.0 {
            0.0
        } else {
            band(nm, 660.0, 10.0)
        }
    });
    for (file, has_cct) in [(&amber, true), (&red, false)] {
        let (code, out, err) = specpoly(&["light", cli::s(file), "--json"]);
        assert_eq!(code, 0, "{err}");
        assert!(!out.contains("NaN") && !out.contains("inf"), "{out}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        // every figure is a finite number or null (serde writes a NaN as null: so each key the
        // light has a CCT for must be a number)
        let keys = ["cct", "duv", "ra", "r9", "r15", "rf", "rg"];
        for k in keys {
            assert_eq!(v[k].as_f64().is_some(), has_cct, "{k}: {out}");
        }
        for k in [
            "X", "Y", "Z", "x", "y", "peak_nm", "edi_mel", "der_mel", "der_sc",
        ] {
            assert!(v[k].as_f64().is_some_and(f64::is_finite), "{k}: {out}");
        }
        // no blue: no s-cone (S 026) response worth the name
        assert!(v["der_sc"].as_f64().unwrap() < 1e-3, "{out}");
        let (code, out, err) = specpoly(&["light", cli::s(file)]);
        assert_eq!(code, 0, "{err}");
        assert!(!out.contains("NaN") && !out.contains("inf"), "{out}");
        if !has_cct {
            let (code, _, err) = specpoly(&["light", cli::s(file), "--tm30"]);
            assert_eq!(code, 1);
            assert!(
                one_line(&err).contains("no correlated colour temperature"),
                "{err}"
            );
        }
    }
    // channels with no blue cannot make 6500 K: one line, nothing printed
    let (code, out, err) = specpoly(&[
        "mix",
        "--channel",
        "red=data/leds/rgbwa.csv#red",
        "--channel",
        "green=data/leds/rgbwa.csv#green",
        "--channel",
        "amber=data/leds/rgbwa.csv#amber",
        "--target",
        "cct:6500",
    ]);
    assert_eq!((code, out.as_str()), (1, ""), "{err}");
    assert!(one_line(&err).contains("gamut"), "{err}");
}

#[test]
fn a_csv_of_a_million_columns_is_refused_at_its_header() {
    let dir = tempfile::tempdir().unwrap();
    let wide = dir.path().join("wide.csv");
    let n = 1_000_000;
    let mut t = String::with_capacity(16 * n);
    t.push_str("wavelength_nm");
    for i in 1..=n {
        let _ = write!(t, ",c{i}");
    }
    for nm in [380, 780] {
        let _ = write!(t, "\n{nm}");
        for _ in 0..n {
            t.push_str(",1");
        }
    }
    t.push('\n');
    std::fs::write(&wide, t).unwrap();
    let spec = format!("{}#c5", cli::s(&wide));
    let (code, out, err) = specpoly(&["light", &spec]);
    assert_eq!((code, out.as_str()), (1, ""), "{err}");
    let err = one_line(&err);
    assert!(
        err.contains(":1:10002:")
            && err.contains("1000000 spectrum columns; a table holds at most 10000"),
        "{err}"
    );
}
