//! `specpoly light`'s standards checks and `specpoly mix` to a specification, through the real
//! binary: the white LED's spectrum figures and α-opic DER against colour-science / SciPy /
//! luxpy (`crates/core/tests/data/light_standards*.csv`), its ANSI and JA8 verdicts, the same
//! figures in the CSV, a 4-channel mix that meets JA8 at 3000 K and 4000 K after 16-bit
//! quantisation (red, green, white, amber of `rgbwa.csv`; its chromaticity by an independent 1 nm sum against the ANSI centres; its Ra
//! and R9 are `light`'s sums, checked against colour-science in `light_cli.rs`), and the closest
//! mix when limits cannot be met.

use crate::common::cli;

fn specpoly(args: &[&str]) -> (i32, String, String) {
    cli::run_in(cli::ROOT, args).parts()
}

/// The row `name` of a reference CSV of core's tests, by header.
fn reference(file: &str, name: &str) -> std::collections::HashMap<String, String> {
    let text = std::fs::read_to_string(format!(
        "{}/../core/tests/data/{file}",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let row = lines.find(|l| l.starts_with(&format!("{name},"))).unwrap();
    head.iter()
        .zip(row.split(','))
        .map(|(h, v)| (h.to_string(), v.to_string()))
        .collect()
}

#[test]
fn light_reports_the_standards_checks() {
    let (code, out, err) = specpoly(&["light", "data/leds/rgbwa.csv#white", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let f = |k: &str| v[k].as_f64().unwrap();
    let cs = reference("light_standards.csv", "rgbwa#white");
    let num =
        |m: &std::collections::HashMap<String, String>, k: &str| -> f64 { m[k].parse().unwrap() };
    assert_eq!(f("peak_nm"), num(&cs, "peak_nm"));
    assert!((f("fwhm_nm") - num(&cs, "fwhm_nm")).abs() < 1e-4);
    assert!((f("dominant_nm") - num(&cs, "dominant_nm")).abs() <= 0.5);
    assert!((f("purity") - num(&cs, "purity")).abs() < 2e-4);
    let lx = reference("light_standards_alpha_opic.csv", "rgbwa#white");
    for k in ["sc", "mc", "lc", "rh", "mel"] {
        let (a, b) = (f(&format!("der_{k}")), num(&lx, &format!("der_{k}")));
        assert!((a - b).abs() < 5e-3 * b, "der_{k}: {a} {b}");
        // EDI = DER × illuminance (the SPD as W/m²/nm: Y is the illuminance in lx)
        let edi = f(&format!("edi_{k}"));
        assert!((edi - a * f("Y")).abs() < 1e-5 * edi.max(1.0), "edi_{k}");
    }
    assert_eq!(v["ri"].as_array().unwrap().len(), 14);
    assert_eq!(v["ri"][8].as_f64(), v["r9"].as_f64());
    // R15 (JIS Z 8726's skin sample) against colour-science's "CIE 2024" set
    let r15 = reference("light_references_r15.csv", "rgbwa:0/0/0/1/0");
    assert!((f("r15") - num(&r15, "r15")).abs() < 0.1, "{}", f("r15"));
    // 4103 K, Duv -0.0006: inside the 4000 K quadrangle; JA8 misses Ra, R9 and CCT
    assert_eq!(v["ansi_c78377"], 4000);
    assert_eq!(v["ja8"], false);
    assert_eq!(v["ja8_fails"], serde_json::json!(["ra", "r9", "cct"]));
    // the text report lists each clause with its figure and result
    let (code, out, err) = specpoly(&["light", "data/leds/rgbwa.csv#white"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("ANSI C78.377-2017 4000 K quadrangle"), "{out}");
    let ja8: Vec<&str> = out.lines().filter(|l| l.starts_with("JA8 ")).collect();
    assert_eq!(ja8.len(), 4, "{out}");
    assert!(
        ja8[0].ends_with("fail") && ja8[3].ends_with("pass"),
        "{out}"
    );
    // the CSV carries the same figures; a red LED has no CCT, so no JA8 verdict, and a
    // complementary wavelength is negative only for purples
    let (code, out, err) = specpoly(&["light", "data/leds/rgbwa.csv#*", "--csv"]);
    assert_eq!(code, 0, "{err}");
    let mut lines = out.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |k: &str| head.iter().position(|h| *h == k).unwrap();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    let red = &rows[0];
    assert_eq!(red[col("ja8")], "");
    assert_eq!(red[col("ansi_c78377")], "");
    let red_ref = reference("light_standards.csv", "rgbwa#red");
    assert!(
        (red[col("dominant_nm")].parse::<f64>().unwrap() - num(&red_ref, "dominant_nm")).abs()
            <= 0.5
    );
    let white = &rows[3];
    assert_eq!(white[col("ja8_fails")], "ra;r9;cct");
    assert_eq!(white[col("peak_nm")].parse::<f64>().unwrap(), f("peak_nm"));
}

/// Δu′v′ of the mix of `rgbwa.csv`'s red, green, white, amber at duties `d`, by a 1 nm f64 sum
/// here, to (x, y).
fn duv_prime(d: &[f64], xy: [f64; 2]) -> f64 {
    let read = |p: &str| -> Vec<Vec<f64>> {
        std::fs::read_to_string(format!("{}/{p}", cli::ROOT))
            .unwrap()
            .lines()
            .skip(1)
            .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
            .collect()
    };
    let (leds, cmf) = (
        read("data/leds/rgbwa.csv"),
        read("data/cmf/cie1931_2deg_1nm.csv"),
    );
    let mut xyz = [0.0f64; 3];
    for r in &leds {
        let m = cmf.iter().find(|m| m[0] == r[0]).unwrap();
        let s: f64 = [1, 2, 4, 5].iter().zip(d).map(|(c, di)| di * r[*c]).sum();
        for k in 0..3 {
            xyz[k] += s * m[1 + k];
        }
    }
    let uv = |x: f64, y: f64, z: f64| {
        let den = x + 15.0 * y + 3.0 * z;
        [4.0 * x / den, 9.0 * y / den]
    };
    let a = uv(xyz[0], xyz[1], xyz[2]);
    let b = uv(xy[0], xy[1], 1.0 - xy[0] - xy[1]);
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt()
}

#[test]
fn a_four_channel_mix_meets_ja8() {
    let ch = |c: &str| format!("{c}=data/leds/rgbwa.csv#{c}");
    let chans = [ch("red"), ch("green"), ch("white"), ch("amber")];
    // the ANSI nominal CCTs' centres as the standard tabulates them
    for (k, centre) in [("3000", [0.4339, 0.4033]), ("4000", [0.3818, 0.3797])] {
        let mut args = vec!["mix"];
        for c in &chans {
            args.extend(["--channel", c.as_str()]);
        }
        let t = format!("ansi:{k}K");
        args.extend(["--target", &t, "--target", "ja8", "--luminance", "0.8"]);
        args.extend(["--bits", "16", "--json"]);
        let (code, out, err) = specpoly(&args);
        assert_eq!(code, 0, "{k}: {err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        let limits = v["limits"].as_array().unwrap();
        assert_eq!(limits.len(), 2);
        assert!(limits.iter().all(|l| l["met"] == true), "{out}");
        assert!(v["ra"].as_f64().unwrap() >= 90.0 && v["r9"].as_f64().unwrap() >= 50.0);
        let d = cli::numbers(&v["duties"]);
        let e = duv_prime(&d, centre);
        println!(
            "ja8 at {k} K: Ra {} R9 {}, Δu'v' to the ANSI centre {e:.1e}",
            v["ra"], v["r9"]
        );
        assert!(e < 5e-4, "{k}: Δu′v′ {e}");
    }
}

#[test]
fn limits_no_mix_can_meet_give_the_closest() {
    let ch = |c: &str| format!("{c}=data/leds/rgb.csv#{c}");
    let (r, g, b) = (ch("red"), ch("green"), ch("blue"));
    let (code, out, err) = specpoly(&[
        "mix",
        "--channel",
        &r,
        "--channel",
        &g,
        "--channel",
        &b,
        "--target",
        "cct:4000",
        "--min",
        "ra=90",
        "--json",
    ]);
    assert_eq!(code, 1, "{out}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("ra >= 90 (best "), "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["limits"][0]["met"], false);
    // target-level limits and bad limits are usage errors
    for (more, code_want) in [
        (vec!["--target", "cct:5000", "--target", "ja8"], 2),
        (
            vec!["--target", "cct:3000,duv:0.004", "--max", "duv=0.003"],
            2,
        ),
        (vec!["--target", "cct:3000", "--min", "cri=90"], 2),
        (vec!["--target", "ja8"], 2),
    ] {
        let mut args = vec!["mix", "--channel", &r, "--channel", &g, "--channel", &b];
        args.extend(more.iter().copied());
        let (code, out, err) = specpoly(&args);
        assert_eq!(code, code_want, "{more:?}: {err}");
        assert!(out.is_empty() && err.lines().count() == 1, "{err}");
    }
}
