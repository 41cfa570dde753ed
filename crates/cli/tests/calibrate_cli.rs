//! `specpoly calibrate fit/show/predict/verify/icc` through the real binary, and bad input:
//! one line on stderr, exit 1 (2 for usage), no panic, no partial output file.

use std::path::{Path, PathBuf};
use std::process::Output;

use crate::common::cli;

use cli::{output_with_stdin as specpoly, s, ACER};

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).to_string()
}

fn one_line_error(o: &Output, code: i32, contains: &str) {
    let e = stderr(o);
    assert_eq!(o.status.code(), Some(code), "stderr: {e}");
    assert_eq!(e.trim_end().lines().count(), 1, "not one line: {e}");
    assert!(!e.contains("panicked"), "{e}");
    assert!(e.contains(contains), "{e:?} lacks {contains:?}");
}

fn fitted(dir: &Path) -> PathBuf {
    let cal = dir.join("acer.toml");
    let o = specpoly(
        &[
            "calibrate",
            "fit",
            "--ti3",
            ACER,
            "-o",
            s(&cal),
            "--hold-out",
        ],
        "",
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("held-out ΔE00 (389 patches)"), "{out}");
    cal
}

#[test]
fn fit_show_predict_verify_icc() {
    let dir = tempfile::tempdir().unwrap();
    let cal = fitted(dir.path());
    let text = std::fs::read_to_string(&cal).unwrap();
    assert!(text.contains("format = \"specpoly-calibration\"") && text.contains("version = 1"));
    assert!(text.contains("video-LUT"), "the CAL table is noted");

    let o = specpoly(&["calibrate", "show", s(&cal), "--json"], "");
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    for k in [
        "format",
        "version",
        "units",
        "primaries",
        "white",
        "black",
        "contrast",
        "transfer",
        "gamma",
        "matrix",
        "fit",
        "provenance",
    ] {
        assert!(v.get(k).is_some(), "no {k}");
    }
    assert_eq!(v["units"], "cd/m2");
    // the fit names the readings it came from by their SHA-256 (coreutils' `sha256sum`)
    let sum = std::process::Command::new("sha256sum")
        .arg(ACER)
        .output()
        .unwrap();
    let sum = String::from_utf8(sum.stdout).unwrap();
    assert_eq!(v["provenance"]["readings_sha256"], sum[..64]);
    assert!((v["white"]["Y"].as_f64().unwrap() - 118.724927).abs() < 1e-6);
    assert!(v["primaries"]["red"]["x"].as_f64().unwrap() > 0.6);
    let o = specpoly(&["calibrate", "show", s(&cal)], "");
    assert!(String::from_utf8_lossy(&o.stdout).contains("gamma"));

    let o = specpoly(
        &["calibrate", "predict", "--calibration", s(&cal)],
        "1 1 1\n\n0 0 0\n0.5,0.25,0\n",
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    let rows: Vec<Vec<f64>> = out
        .lines()
        .map(|l| l.split_whitespace().map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 3);
    assert!((rows[0][1] - 118.72).abs() < 0.5, "{out}");
    assert!((rows[1][1] - 0.113).abs() < 0.01, "{out}");

    let o = specpoly(
        &[
            "calibrate",
            "verify",
            "--calibration",
            s(&cal),
            "--ti3",
            ACER,
        ],
        "",
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.contains("nominal") && out.contains("recommended"),
        "{out}"
    );
    // DisplayCAL's four criteria and ISO 14861's two, none failing
    assert_eq!(out.matches("pass").count(), 6, "{out}");
    assert!(!out.contains("FAIL"), "{out}");

    let icc = dir.path().join("acer.icc");
    let o = specpoly(&["calibrate", "icc", s(&cal), "-o", s(&icc)], "");
    assert!(o.status.success(), "{}", stderr(&o));
    let b = std::fs::read(&icc).unwrap();
    assert_eq!(&b[36..40], b"acsp");
    assert_eq!(
        u32::from_be_bytes([b[0], b[1], b[2], b[3]]) as usize,
        b.len()
    );
}

#[test]
fn bad_ti3_is_one_line_with_the_line_number_and_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let good = std::fs::read_to_string(ACER).unwrap();
    let cases: Vec<(String, &str)> = vec![
        (
            good.replacen("NUMBER_OF_SETS 2068", "NUMBER_OF_SETS 2000", 1),
            ":36: NUMBER_OF_SETS is 2000",
        ),
        (
            good.replacen("5 0.0000000 0.0000000", "5 0.0000000 zero", 1),
            ":42: RGB_G `zero` is not a number",
        ),
        (
            good.replacen(" XYZ_Z\n", " XYZ_W\n", 1),
            "has no field XYZ_Z",
        ),
        (
            good.replacen("NUMBER_OF_FIELDS 7", "NUMBER_OF_FIELDS 8", 1),
            ":31: NUMBER_OF_FIELDS is 8",
        ),
        (
            good.split("BEGIN_DATA\n").next().unwrap().to_string(),
            "no BEGIN_DATA",
        ),
        (
            good.replacen(
                "6 1.9608000 1.9608000 1.9608000 0.1267730 0.1285230 0.2010740",
                "6 1.9608000 1.9608000 1.9608000 0.1267730",
                1,
            ),
            ":43: expected 7 values",
        ),
        (
            good.replacen(
                "1 100.00000 100.00000 100.00000",
                "1 180.00000 100.00000 100.00000",
                1,
            ),
            ":38: RGB_R 180.00000 is outside 0–100",
        ),
        (String::new(), "empty file"),
    ];
    for (i, (text, want)) in cases.iter().enumerate() {
        let ti3 = dir.path().join(format!("bad{i}.ti3"));
        std::fs::write(&ti3, text).unwrap();
        let out = dir.path().join(format!("bad{i}.toml"));
        let o = specpoly(&["calibrate", "fit", "--ti3", s(&ti3), "-o", s(&out)], "");
        one_line_error(&o, 1, want);
        assert!(!out.exists(), "case {i} left a file");
    }
    // no black patch
    let ti3 = dir.path().join("noblack.ti3");
    std::fs::write(&ti3, "CTI3\nNUMBER_OF_FIELDS 7\nBEGIN_DATA_FORMAT\nSAMPLE_ID RGB_R RGB_G RGB_B XYZ_X XYZ_Y XYZ_Z\nEND_DATA_FORMAT\nNUMBER_OF_SETS 1\nBEGIN_DATA\n1 100 100 100 95 100 108\nEND_DATA\n").unwrap();
    let out = dir.path().join("noblack.toml");
    let o = specpoly(&["calibrate", "fit", "--ti3", s(&ti3), "-o", s(&out)], "");
    one_line_error(&o, 1, "no black patch");
    assert!(!out.exists());
}

#[test]
fn bad_calibration_files_and_predict_input() {
    let dir = tempfile::tempdir().unwrap();
    let cal = fitted(dir.path());
    let text = std::fs::read_to_string(&cal).unwrap();
    let cases: Vec<(String, &str)> = vec![
        (
            text.replace("version = 1", "version = 2"),
            "version 2 is not supported",
        ),
        (
            text.replace("format = \"specpoly-calibration\"", "format = \"x\""),
            "format is \"x\"",
        ),
        (
            text.replace("units = \"cd/m2\"", "units = \"nits\""),
            "units",
        ),
        (text.replacen("x = 0.", "x = -0.", 1), "primaries.red"),
        (text.replace("[primaries.red]", "[primaries.rouge]"), "red"),
        (
            "format = \"specpoly-calibration\"\nversion = 1\nblack = [".into(),
            "bad5.toml:3:",
        ),
        ("not toml at all ===".into(), ""),
    ];
    for (i, (t, want)) in cases.iter().enumerate() {
        let p = dir.path().join(format!("bad{i}.toml"));
        std::fs::write(&p, t).unwrap();
        let o = specpoly(&["calibrate", "show", s(&p)], "");
        one_line_error(&o, 1, want);
        let icc = dir.path().join(format!("bad{i}.icc"));
        let o = specpoly(&["calibrate", "icc", s(&p), "-o", s(&icc)], "");
        one_line_error(&o, 1, "");
        assert!(!icc.exists());
    }
    for (input, want) in [
        ("0.1 0.2 0.3\n0.1 0.2\n", "stdin:2: expected three"),
        ("0.1 0.2 1.5\n", "stdin:1: `1.5` is outside 0–1"),
        ("0.1 x 0.3\n", "stdin:1: `x` is not a number"),
    ] {
        let o = specpoly(&["calibrate", "predict", "--calibration", s(&cal)], input);
        one_line_error(&o, 1, want);
    }
    let o = specpoly(
        &["calibrate", "predict", "--calibration", "/nonexistent.toml"],
        "",
    );
    // a missing input file is a usage error, in every command (src/error.rs)
    one_line_error(&o, 2, "/nonexistent.toml");
}
