//! `specpoly light` and `specpoly mix` through the real binary: the JSON keys of the issue, the
//! figures against colour-science 0.4.7 (`crates/core/tests/data/light_colour_science.csv`, same
//! tolerances as `crates/core/tests/light_colour_science.rs`), the mix's chromaticity against a 1 nm
//! f64 sum of the channel files done here, and clean failures on bad input.

use crate::common::cli;

fn specpoly(args: &[&str]) -> (i32, String, String) {
    cli::run_in(cli::ROOT, args).parts()
}

/// `specpoly mix --channel C… --target TARGET MORE…`.
fn mix(channels: &[&str], target: &str, more: &[&str]) -> (i32, String, String) {
    let mut args = vec!["mix"];
    for c in channels {
        args.extend(["--channel", c]);
    }
    args.extend(["--target", target]);
    args.extend(more);
    specpoly(&args)
}

fn colour_science(name: &str) -> Vec<f64> {
    let p = format!(
        "{}/../core/tests/data/light_colour_science.csv",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(p).unwrap();
    let line = text
        .lines()
        .find(|l| l.starts_with(&format!("{name},")))
        .unwrap();
    let f: Vec<&str> = line.split(',').collect();
    f[f.len() - 8..]
        .iter()
        .map(|v| v.parse().unwrap())
        .collect()
}

#[test]
fn light_json_matches_colour_science() {
    let (code, out, err) = specpoly(&["light", "data/leds/rgbwa.csv#white", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let keys: Vec<&str> = v.as_object().unwrap().keys().map(|k| k.as_str()).collect();
    let mut want = vec![
        "X",
        "Y",
        "Z",
        "x",
        "y",
        "u_prime",
        "v_prime",
        "cct",
        "duv",
        "ra",
        "r9",
        "rf",
        "rg",
        // the standards' checks (light_standards_cli.rs)
        "ri",
        "r15",
        "peak_nm",
        "fwhm_nm",
        "dominant_nm",
        "purity",
        "edi_sc",
        "edi_mc",
        "edi_lc",
        "edi_rh",
        "edi_mel",
        "der_sc",
        "der_mc",
        "der_lc",
        "der_rh",
        "der_mel",
        "ansi_c78377",
        "ja8",
        "ja8_fails",
    ];
    let mut got = keys.clone();
    got.sort();
    want.sort();
    assert_eq!(got, want);
    let cs = colour_science("rgbwa:0,0,0,1,0"); // x, y, cct, duv, ra, r9, rf, rg
    let f = |k: &str| v[k].as_f64().unwrap();
    assert!((f("x") - cs[0]).abs() < 3e-4 && (f("y") - cs[1]).abs() < 3e-4);
    assert!((f("cct") - cs[2]).abs() < 5e-4 * cs[2]);
    assert!((f("duv") - cs[3]).abs() < 2e-5);
    assert!((f("ra") - cs[4]).abs() < 0.1);
    assert!((f("r9") - cs[5]).abs() < 0.1);
    assert!((f("rf") - cs[6]).abs() < 0.05);
    assert!((f("rg") - cs[7]).abs() < 0.05);
    // the channel files are scaled to lumens: Y is the flux
    assert!((f("Y") - 250.0).abs() < 0.01, "{}", f("Y"));
}

#[test]
fn light_text_and_far_from_locus() {
    let (code, out, _) = specpoly(&["light", "FL2"]);
    assert_eq!(code, 0);
    // colour-science 0.4.7 (Ohno 2013): 4224.48 K; the parity tolerance is 0.05 %
    let row: Vec<&str> = out.lines().nth(2).unwrap().split_whitespace().collect();
    let cct: f64 = row[7].parse().unwrap();
    assert!((cct - 4224.48).abs() < 5e-4 * 4224.48, "{out}");
    // a red LED has no CCT: metrics print as '-' / null, colorimetry still printed
    let (code, out, _) = specpoly(&["light", "data/leds/rgb.csv#red", "--json"]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!(v["cct"].is_null() && v["rf"].is_null());
    assert!(v["x"].as_f64().unwrap() > 0.69);
}

fn uv_prime_1nm(files: &[(&str, &str)], d: &[f64]) -> [f64; 2] {
    let root = format!("{}/../..", env!("CARGO_MANIFEST_DIR"));
    let cmf_text =
        std::fs::read_to_string(format!("{root}/data/cmf/cie1931_2deg_1nm.csv")).unwrap();
    let cmf: Vec<Vec<f64>> = cmf_text
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
        .collect();
    let mut xyz = [0.0f64; 3];
    for ((file, col), di) in files.iter().zip(d) {
        let text = std::fs::read_to_string(format!("{root}/{file}")).unwrap();
        let mut lines = text.lines();
        let c = lines
            .next()
            .unwrap()
            .split(',')
            .position(|h| h == *col)
            .unwrap();
        for l in lines {
            let r: Vec<f64> = l.split(',').map(|v| v.parse().unwrap()).collect();
            let row = cmf.iter().find(|m| m[0] == r[0]).unwrap();
            for k in 0..3 {
                xyz[k] += di * r[c] * row[k + 1];
            }
        }
    }
    let den = xyz[0] + 15.0 * xyz[1] + 3.0 * xyz[2];
    [4.0 * xyz[0] / den, 9.0 * xyz[1] / den]
}

#[test]
fn mix_hits_the_target() {
    let files = [
        ("data/leds/rgbwa.csv", "red"),
        ("data/leds/rgbwa.csv", "green"),
        ("data/leds/rgbwa.csv", "blue"),
        ("data/leds/rgbwa.csv", "white"),
        ("data/leds/rgbwa.csv", "amber"),
    ];
    let ch: Vec<String> = files.iter().map(|(f, c)| format!("{c}={f}#{c}")).collect();
    let ch: Vec<&str> = ch.iter().map(String::as_str).collect();
    let (code, out, err) = mix(
        &ch,
        "xy:0.3457,0.3585",
        &[
            "--luminance",
            "0.7",
            "--optimize",
            "rf",
            "--bits",
            "16",
            "--json",
        ],
    );
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    for k in [
        "duties", "x", "y", "u_prime", "v_prime", "cct", "duv", "ra", "rf", "rg", "efficacy",
    ] {
        assert!(v.get(k).is_some(), "{k} missing: {out}");
    }
    let d: Vec<f64> = cli::numbers(&v["duties"]);
    assert_eq!(d.len(), 5);
    for di in &d {
        // 16-bit steps (printed to 6 decimals)
        assert!((di * 65535.0 - (di * 65535.0).round()).abs() < 0.07, "{di}");
    }
    let uv = uv_prime_1nm(&files, &d);
    let (x, y) = (0.3457, 0.3585);
    let den = -2.0 * x + 12.0 * y + 3.0;
    let want = [4.0 * x / den, 9.0 * y / den];
    let e = ((uv[0] - want[0]).powi(2) + (uv[1] - want[1]).powi(2)).sqrt();
    assert!(e < 0.0002, "Δu′v′ {e}");
    assert!(v["rf"].as_f64().unwrap() > 85.0, "{out}");
    // what `mix` reports is the driven light by the standards' sums: its u′v′ are the 1 nm sum's
    // (6 printed decimals), its metrics `light`'s on the spectrum Σ dᵢ·Sᵢ written out
    assert!(
        (v["u_prime"].as_f64().unwrap() - uv[0]).abs() < 1e-6,
        "{out}"
    );
    assert!(
        (v["v_prime"].as_f64().unwrap() - uv[1]).abs() < 1e-6,
        "{out}"
    );
    let text = std::fs::read_to_string(format!("{}/data/leds/rgbwa.csv", cli::ROOT)).unwrap();
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let cols: Vec<usize> = files
        .iter()
        .map(|(_, c)| head.iter().position(|h| h == c).unwrap())
        .collect();
    let mut sum = String::from("wavelength_nm,mix\n");
    for l in lines {
        let r: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
        let s: f64 = cols.iter().zip(&d).map(|(c, di)| di * r[*c]).sum();
        sum += &format!("{},{s}\n", r[0]);
    }
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("mix.csv");
    std::fs::write(&p, sum).unwrap();
    let (code, out, err) = specpoly(&["light", p.to_str().unwrap(), "--json"]);
    assert_eq!(code, 0, "{err}");
    let l: serde_json::Value = serde_json::from_str(&out).unwrap();
    for k in ["x", "y", "cct", "duv", "ra", "rf", "rg"] {
        let (a, b) = (v[k].as_f64().unwrap(), l[k].as_f64().unwrap());
        assert!(
            (a - b).abs() <= 2e-6 * b.abs().max(1.0),
            "{k}: mix {a}, light {b}"
        );
    }
}

#[test]
fn mix_errors() {
    let tw = |c: &str| format!("{c}=data/leds/tunable_white.csv#{c}");
    let (w, c, r) = (tw("warm"), tw("cool"), tw("red"));
    // outside the gamut: data error, one line
    let (code, out, err) = mix(&[&w, &c, &r], "xy:0.2,0.7", &[]);
    assert_eq!(code, 1, "{err}");
    assert!(out.is_empty());
    assert!(err.contains("outside the gamut"), "{err}");
    assert_eq!(err.lines().count(), 1);
    // usage errors
    for bad in [
        mix(&[&w, &c], "cct:3000", &[]),
        mix(&[&w, &c, &r], "cct:90", &[]),
        mix(&[&w, &c, &r], "hsv:1", &[]),
        mix(&[&w, &c, &r], "cct:3000", &["--luminance", "2"]),
        mix(&["nameless", &c, &r], "cct:3000", &[]),
        mix(&["x=no-such.csv", &c, &r], "cct:3000", &[]),
    ]
    .into_iter()
    .enumerate()
    {
        let (i, (code, out, err)) = bad;
        assert_eq!(code, 2, "usage case {i}: {err}");
        assert!(out.is_empty() && !err.contains("panicked"), "{err}");
    }
    // malformed SPD file: data error
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("bad.csv");
    std::fs::write(&p, "wavelength_nm,a\n400,1\n410,NaN\n").unwrap();
    let (code, _, err) = specpoly(&["light", p.to_str().unwrap()]);
    assert_eq!(code, 1, "{err}");
    assert!(!err.contains("panicked"));
    std::fs::write(&p, "wavelength_nm,a\n380,0\n780,0\n").unwrap();
    let (code, _, err) = specpoly(&["light", p.to_str().unwrap()]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("no luminous power"), "{err}");
}

/// A light tabulated over part of 380–780 nm (FL2 cut to 450–650 nm) is refused with the range
/// it needs; `--extrapolate` gives exactly the metrics of the table with its end values written
/// out to 380 and 780 nm (at the same 5 nm step), and says so.
#[test]
fn short_light_refused_or_extrapolated() {
    let text = std::fs::read_to_string(format!(
        "{}/../../data/illuminants/FL2.csv",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    let rows: Vec<(u32, String)> = text
        .lines()
        .skip(1)
        .map(|l| {
            let (w, v) = l.split_once(',').unwrap();
            (w.parse().unwrap(), v.to_string())
        })
        .collect();
    let at = |nm: u32| rows.iter().find(|r| r.0 == nm).unwrap().1.clone();
    let mut cut = String::from("wavelength_nm,fl2\n");
    let mut held = cut.clone();
    for nm in (380..=780).step_by(5) {
        let v = at(nm.clamp(450, 650));
        if (450..=650).contains(&nm) {
            cut += &format!("{nm},{v}\n");
        }
        held += &format!("{nm},{v}\n");
    }
    let dir = tempfile::tempdir().unwrap();
    let (pc, ph) = (dir.path().join("cut.csv"), dir.path().join("held.csv"));
    std::fs::write(&pc, cut).unwrap();
    std::fs::write(&ph, held).unwrap();
    let (code, out, err) = specpoly(&["light", pc.to_str().unwrap()]);
    assert_eq!(code, 1, "{out}");
    assert!(
        err.contains("450-650 nm") && err.contains("380-780 nm") && err.lines().count() == 1,
        "{err}"
    );
    let (code, out, err) = specpoly(&["light", pc.to_str().unwrap(), "--extrapolate", "--json"]);
    assert_eq!(code, 0, "{err}");
    let mut e: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(e["extrapolated_from_nm"], serde_json::json!([450.0, 650.0]));
    e.as_object_mut().unwrap().remove("extrapolated_from_nm");
    let (code, out, err) = specpoly(&["light", ph.to_str().unwrap(), "--json"]);
    assert_eq!(code, 0, "{err}");
    let h: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(e, h);
    // and far from FL2's own 4224 K: the cut light is a different light
    assert!((h["cct"].as_f64().unwrap() - 4224.5).abs() > 100.0, "{h}");
    let (_, out, _) = specpoly(&["light", pc.to_str().unwrap(), "--extrapolate"]);
    assert!(out.contains("extrapolated to 380-780 nm"), "{out}");
}

/// Several lights in one call: `FILE#*` is every column; CSV, JSON Lines and the table give
/// one row a light, the white LED's row within the parity tolerances of colour-science 0.4.7
/// and every row equal to that light's own single-light JSON.
#[test]
fn many_lights_one_row_each() {
    let (code, out, err) = specpoly(&["light", "FL2", "data/leds/rgbwa.csv#*", "--csv"]);
    assert_eq!(code, 0, "{err}");
    let mut rows = out.lines();
    let head: Vec<&str> = rows.next().unwrap().split(',').collect();
    assert_eq!(head[0], "name");
    let rows: Vec<Vec<&str>> = rows.map(|l| l.split(',').collect()).collect();
    let names: Vec<&str> = rows.iter().map(|r| r[0]).collect();
    assert_eq!(names.len(), 6, "{out}");
    assert_eq!(names[0], "FL2");
    assert!(
        names[1..].iter().all(|n| n.contains("rgbwa.csv#")),
        "{names:?}"
    );
    let col = |r: &[&str], k: &str| -> f64 {
        r[head.iter().position(|h| *h == k).unwrap()]
            .parse()
            .unwrap()
    };
    let white = rows.iter().find(|r| r[0].ends_with("#white")).unwrap();
    let cs = colour_science("rgbwa:0,0,0,1,0"); // x, y, cct, duv, ra, r9, rf, rg
    assert!((col(white, "cct") - cs[2]).abs() < 5e-4 * cs[2]);
    assert!((col(white, "duv") - cs[3]).abs() < 2e-5);
    assert!((col(white, "r9") - cs[5]).abs() < 0.1);
    assert!((col(white, "rf") - cs[6]).abs() < 0.05);
    // a narrow-band red has no CCT: empty cells
    let red = rows.iter().find(|r| r[0].ends_with("#red")).unwrap();
    assert_eq!(red[head.iter().position(|h| *h == "rf").unwrap()], "");
    for r in &rows {
        let (code, one, err) = specpoly(&["light", r[0], "--json"]);
        assert_eq!(code, 0, "{err}");
        let v: serde_json::Value = serde_json::from_str(&one).unwrap();
        for (k, h) in head.iter().enumerate().skip(1).take(13) {
            match v[*h].as_f64() {
                Some(want) => assert_eq!(r[k].parse::<f64>().unwrap(), want, "{} {h}", r[0]),
                None => assert_eq!(r[k], "", "{} {h}", r[0]),
            }
        }
    }
    // JSON Lines, the name first
    let (code, out, _) = specpoly(&["light", "FL2", "D65", "--json"]);
    assert_eq!(code, 0);
    let lines: Vec<serde_json::Value> = out
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 2);
    assert_eq!(lines[1]["name"], "D65");
    assert!(
        (lines[1]["cct"].as_f64().unwrap() - 6504.0).abs() < 2.0,
        "{out}"
    );
    // the table: a header comment, the column heads, one row a light
    let (code, out, _) = specpoly(&["light", "FL2", "D65", "A"]);
    assert_eq!(code, 0);
    assert_eq!(out.lines().count(), 2 + 3, "{out}");
    assert!(out.lines().nth(4).unwrap().starts_with("A "), "{out}");
    // one bad light fails the call with its name
    let (code, out, err) = specpoly(&["light", "FL2", "no-such.csv", "--csv"]);
    assert_ne!(code, 0);
    assert!(
        out.is_empty() && err.lines().count() == 1 && err.contains("no-such.csv"),
        "{err}"
    );
}
