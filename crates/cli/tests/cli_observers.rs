//! `--observer` end to end: a sensitivity CSV holding the CIE 1931 table gives the built-in
//! observer's numbers; bad CSVs and ages outside the CIE 2006 model are refused with one line,
//! a non-zero exit and nothing written by every command that takes an observer (`xyz`,
//! `light`, `render`, `mix`, `calibrate simulate`, `calibrate match`); `light --observer`
//! reports the light under it; `mix --observer` meets its target under that observer (checked
//! by a 1 nm sum over the CSV tables of `data/cmf/` read here).

use crate::common::cli::{specpoly, ROOT};

fn xyz(observer: &str) -> serde_json::Value {
    let (code, out, err) = specpoly(&[
        "xyz",
        "colorchecker#red",
        "colorchecker#blue",
        "--repr",
        "exact",
        "--json",
        "--observer",
        observer,
    ]);
    assert_eq!(code, 0, "{err}");
    serde_json::from_str(&out).unwrap()
}

#[test]
fn a_csv_of_the_1931_table_is_the_1931_observer() {
    let file = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../data/cmf/cie1931_2deg_1nm.csv"
    );
    assert_eq!(xyz(file), xyz("1931"));
    // and the observers differ from each other
    assert_ne!(xyz("2015-10"), xyz("1964"));
    assert_ne!(xyz("cie2006:age=70,field=4"), xyz("2015-10"));
}

#[test]
fn bad_observers_are_refused_in_one_line_with_nothing_written() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (
            "negative.csv",
            "wavelength_nm,x,y,z\n400,0,1,1\n550,-0.1,1,1\n700,1,1,1\n",
        ),
        (
            "missing.csv",
            "wavelength_nm,x,y,z\n400,0,1,1\n550,,1,1\n700,1,1,1\n",
        ),
        (
            "order.csv",
            "wavelength_nm,x,y,z\n400,0,1,1\n700,1,1,1\n550,1,1,1\n",
        ),
        (
            "short.csv",
            "wavelength_nm,x,y,z\n450,0,1,1\n550,1,1,1\n650,1,1,1\n",
        ),
    ];
    let mut observers: Vec<String> = cases
        .iter()
        .map(|(name, text)| {
            let p = dir.path().join(name);
            std::fs::write(&p, text).unwrap();
            p.display().to_string()
        })
        .collect();
    observers.push("cie2006:age=85,field=4".into());
    observers.push("cie2006:age=30,field=12".into());
    observers.push("2016".into());
    let png = dir.path().join("out.png");
    let ti3 = dir.path().join("out.ti3");
    let cal = dir.path().join("out.cal");
    let (png_s, ti3_s, cal_s) = (
        png.to_str().unwrap(),
        ti3.to_str().unwrap(),
        cal.to_str().unwrap(),
    );
    let x61 = format!("{ROOT}/data/ti3/lenovo-thinkpad-x61_825.ti3");
    let leds = ["r", "g", "b"].map(|c| format!("{c}={ROOT}/data/leds/rgb.csv#{}", led_column(c)));
    for o in &observers {
        for args in [
            vec!["xyz", "colorchecker#red", "--observer", o],
            vec!["light", "D65", "--observer", o],
            vec![
                "render",
                "example1",
                "--size",
                "8x8",
                "--observer",
                o,
                "-o",
                png_s,
            ],
            vec![
                "mix",
                "--channel",
                &leds[0],
                "--channel",
                &leds[1],
                "--channel",
                &leds[2],
                "--target",
                "xy:0.31,0.33",
                "--observer",
                o,
            ],
            vec![
                "calibrate",
                "simulate",
                "--display",
                "sim:wled",
                "--observer",
                o,
                "-o",
                ti3_s,
            ],
            vec![
                "calibrate",
                "fit",
                "--ti3",
                &x61,
                "--observer",
                o,
                "-o",
                cal_s,
            ],
            vec![
                "calibrate",
                "match",
                "--a",
                "sim:qdoled",
                "--b",
                "sim:wled",
                "--viewer",
                o,
                "-o",
                cal_s,
            ],
        ] {
            let (code, out, err) = specpoly(&args);
            assert_ne!(code, 0, "{args:?}");
            assert!(out.is_empty(), "{args:?}: {out}");
            assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
            for f in [&png, &ti3, &cal] {
                assert!(!f.exists(), "{args:?}: {f:?} written");
            }
        }
    }
}

fn led_column(c: &str) -> &str {
    match c {
        "r" => "red",
        "g" => "green",
        _ => "blue",
    }
}

#[test]
fn light_reports_its_colour_under_the_observer() {
    let (code, out, err) = specpoly(&["light", "FL11", "--json", "--observer", "1931"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    for k in ["X", "Y", "Z", "x", "y", "u_prime", "v_prime"] {
        let (a, b) = (v[k].as_f64().unwrap(), v["observer"][k].as_f64().unwrap());
        assert!((a - b).abs() <= 1e-6 * a.abs().max(1.0), "{k}: {a} {b}");
    }
    let (code, out, _) = specpoly(&["light", "FL11", "--json", "--observer", "2015-10"]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["observer"]["name"], "2015-10");
    assert!((v["observer"]["x"].as_f64().unwrap() - v["x"].as_f64().unwrap()).abs() > 1e-3);
}

/// `KM · Σ s(λ)·c̄(λ)` at 1 nm over 380–780 nm with the CSV table `data/cmf/FILE` read directly
/// (rows absent below the table's start count as zero).
fn xyz_1nm(cmf: &str, s: &[f64]) -> [f64; 3] {
    let (_, table) = crate::reference_1nm::read(&format!("cmf/{cmf}"));
    let mut out = [0.0; 3];
    for row in &table {
        let nm = row[0] as usize;
        if (380..=780).contains(&nm) {
            for k in 0..3 {
                out[k] += s[nm - 380] * row[k + 1];
            }
        }
    }
    out.map(|v| v * 683.0)
}

fn xy(v: [f64; 3]) -> [f64; 2] {
    let s = v[0] + v[1] + v[2];
    [v[0] / s, v[1] / s]
}

const LEDS: [&str; 5] = ["red", "green", "blue", "white", "amber"];

/// `mix` of the rgbwa LEDs to `target` under `observer` (16-bit duties, least drive): the JSON
/// and the mixed spectrum `Σ dᵢ·Sᵢ` at 1 nm from the duties printed and the CSV read directly.
fn mix_leds(target: &str, observer: &str) -> (serde_json::Value, Vec<f64>) {
    let mut args = vec!["mix".to_string()];
    for c in LEDS {
        args.push("--channel".into());
        args.push(format!("{c}={ROOT}/data/leds/rgbwa.csv#{c}"));
    }
    for a in [
        "--target",
        target,
        "--observer",
        observer,
        "--optimize",
        "power",
        "--bits",
        "16",
        "--json",
    ] {
        args.push(a.into());
    }
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let (code, out, err) = specpoly(&args);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let d = crate::common::cli::numbers(&v["duties"]);
    let cols: Vec<(Vec<f64>, Vec<f64>)> = LEDS
        .iter()
        .map(|c| crate::reference_1nm::column("leds/rgbwa.csv", c))
        .collect();
    let s: Vec<f64> = (380..=780)
        .map(|nm| {
            cols.iter()
                .zip(&d)
                .map(|((x, y), di)| di * crate::reference_1nm::interp(x, y, nm as f64))
                .sum()
        })
        .collect();
    (v, s)
}

/// Measured: the mix's xy under CIE 2015 10° is the target's within 2e-6 (16-bit duties), and
/// its CIE 1931 xy is 0.0036 from the same numbers.
#[test]
fn mix_meets_an_xy_target_under_the_cie_2015_10_observer() {
    let (v, s) = mix_leds("xy:0.3127,0.3290", "2015-10");
    let got = xy(xyz_1nm("cie2015_10deg_1nm.csv", &s));
    let e = (got[0] - 0.3127).hypot(got[1] - 0.3290);
    assert!(e < 2e-5, "2015-10 xy {got:?}: Δxy {e}");
    // the report's observer block is that sum (6 decimals)
    assert_eq!(v["observer"]["name"], "2015-10");
    for (k, g) in ["x", "y"].iter().zip(got) {
        assert!((v["observer"][k].as_f64().unwrap() - g).abs() < 2e-6, "{v}");
    }
    // the same duties under CIE 1931 are elsewhere: the observer changed the mix
    let c1931 = xy(xyz_1nm("cie1931_2deg_1nm.csv", &s));
    let d1931 = (c1931[0] - 0.3127).hypot(c1931[1] - 0.3290);
    eprintln!("Δxy under 2015-10 {e:.2e}; the same duties under 1931: Δxy {d1931:.5}");
    assert!(d1931 > 1e-3, "1931 xy {c1931:?}");
    assert!((v["x"].as_f64().unwrap() - c1931[0]).abs() < 2e-6, "{v}");
}

/// `cct:K` under another observer than CIE 1931 is the Planckian radiator's chromaticity under
/// it (Planck's law with c₂ = 1.4388e-2 m·K summed here at 1 nm); a Duv, defined on CIE 1931
/// only, is refused in one line.
#[test]
fn mix_to_a_cct_under_the_cie_2015_10_observer_is_the_planckian_radiators_chromaticity() {
    let planck: Vec<f64> = (380..=780)
        .map(|nm| {
            let l = nm as f64 * 1e-9;
            1.0 / (l.powi(5) * ((1.4388e-2 / (l * 4000.0)).exp() - 1.0))
        })
        .collect();
    let want = xy(xyz_1nm("cie2015_10deg_1nm.csv", &planck));
    let (_, s) = mix_leds("cct:4000", "2015-10");
    let got = xy(xyz_1nm("cie2015_10deg_1nm.csv", &s));
    let e = (got[0] - want[0]).hypot(got[1] - want[1]);
    eprintln!("4000 K under 2015-10: Δxy to Planck {e:.2e}");
    assert!(e < 2e-5, "{got:?} vs Planck {want:?}: Δxy {e}");
    let ch = |c: &str| format!("{c}={ROOT}/data/leds/rgbwa.csv#{c}");
    let (r, g, b) = (ch("red"), ch("green"), ch("blue"));
    for extra in [
        vec!["--target", "cct:4000,duv:0.002"],
        vec!["--target", "ansi:5000K"],
        vec!["--target", "xy:0.38,0.38", "--target", "ja8"],
        vec!["--target", "xy:0.38,0.38", "--max", "cct=4000"],
    ] {
        let mut args = vec![
            "mix",
            "--channel",
            &r,
            "--channel",
            &g,
            "--channel",
            &b,
            "--observer",
            "2015-10",
        ];
        args.extend(extra.iter().copied());
        let (code, out, err) = specpoly(&args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(out.is_empty(), "{out}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    }
}
