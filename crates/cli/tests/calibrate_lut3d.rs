//! `specpoly calibrate lut3d` through the binary: the file it writes (format from the
//! extension or `--format`), what it says, and bad input — a LUT size of 0, 1 or 1000, an unknown
//! source space, a size that is not a number, an unknown extension, a display model that cannot
//! invert its greys — one line on stderr, and no file written or clobbered. The LUTs' accuracy in ffmpeg and
//! OpenColorIO is tested in `crates/calibrate/tests/lut3d.rs`.

use crate::common::cli;

use cli::s;
use specpoly_display::calibration::{
    Calibration, CalibrationData, FitReport, Lattice, Primaries, Primary, Provenance,
    TransferCurves, TransferKind, FORMAT, VERSION,
};
use std::path::Path;

/// A display TOML of primaries (a matrix model: cheap to invert).
fn display(dir: &Path) -> String {
    let p = dir.join("display.toml");
    std::fs::write(
        &p,
        "primaries = [[0.66, 0.32], [0.29, 0.61], [0.15, 0.06]]\nluminance = [25.0, 65.0, 10.0]\ngamma = 2.3\nblack = [0.1, 0.1, 0.15]\n",
    )
    .unwrap();
    p.to_string_lossy().into_owned()
}

fn lut3d(display: &str, out: &Path, args: &[&str]) -> cli::Run {
    let mut all = vec!["calibrate", "lut3d", display, "-o", s(out)];
    all.extend_from_slice(args);
    cli::run(&all)
}

/// Lines of numbers (the table) of a LUT text.
fn numeric_lines(text: &str) -> Vec<&str> {
    text.lines()
        .filter(|l| l.trim_start().starts_with(|c: char| c.is_ascii_digit()))
        .collect()
}

#[test]
fn writes_cube_and_3dl_and_says_what_it_wrote() {
    let dir = tempfile::tempdir().unwrap();
    let d = display(dir.path());
    let cube = dir.path().join("x.cube");
    let r = lut3d(&d, &cube, &["--size", "5", "--source", "rec709"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(
        r.stderr.contains("wrote ") && r.stderr.contains("cube, 5^3 = 125 nodes from rec709"),
        "{}",
        r.stderr
    );
    let text = std::fs::read_to_string(&cube).unwrap();
    assert!(text.starts_with("# specpoly calibrate lut3d"), "{text}");
    assert!(
        text.contains("ITU-R BT.1886") && text.contains("Bradford"),
        "{text}"
    );
    assert!(text.contains("\nLUT_3D_SIZE 5\n") && text.contains("\nTITLE \""));
    assert_eq!(numeric_lines(&text).len(), 125);
    // .3dl from the extension: the mesh line and 125 rows of integers
    let tdl = dir.path().join("x.3dl");
    let r = lut3d(
        &d,
        &tdl,
        &["--size", "5", "--white", "keep", "--gamut", "desaturate"],
    );
    assert_eq!(r.code, 0, "{}", r.stderr);
    let text = std::fs::read_to_string(&tdl).unwrap();
    let rows = numeric_lines(&text);
    assert_eq!(rows[0], "0 256 512 768 1023");
    assert_eq!(rows.len(), 126);
    assert!(
        text.contains("white: keep") && text.contains("gamut: desaturate"),
        "{text}"
    );
    // --format overrides an extension no format has
    let txt = dir.path().join("x.txt");
    let r = lut3d(&d, &txt, &["--size", "3", "--format", "cube"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(std::fs::read_to_string(&txt)
        .unwrap()
        .contains("LUT_3D_SIZE 3"));
}

/// Asserts a one-line error with exit code `code` mentioning `what`, and `out` still `before`.
fn refused(r: &cli::Run, code: i32, what: &str, out: &Path, before: Option<&str>) {
    assert_eq!(r.code, code, "{}", r.stderr);
    assert_eq!(r.stderr.lines().count(), 1, "{}", r.stderr);
    assert!(
        r.stderr.starts_with("specpoly: error: ") && r.stderr.contains(what),
        "{}",
        r.stderr
    );
    match before {
        Some(b) => assert_eq!(std::fs::read_to_string(out).unwrap(), b),
        None => assert!(!out.exists()),
    }
    // no temporary file left beside it
    let dir = out.parent().unwrap();
    let tmp: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().ends_with(".specpoly-tmp"))
        .collect();
    assert!(tmp.is_empty());
}

#[test]
fn bad_sizes_sources_and_extensions_are_one_line_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let d = display(dir.path());
    let out = dir.path().join("new.cube");
    for size in ["0", "1", "1000"] {
        let r = lut3d(&d, &out, &["--size", size]);
        refused(
            &r,
            2,
            &format!("3D LUT size {size} must be 2–65"),
            &out,
            None,
        );
    }
    let r = lut3d(&d, &out, &["--source", "prophoto"]);
    refused(&r, 2, "'prophoto' for '--source", &out, None);
    let r = lut3d(&d, &dir.path().join("x.lut"), &[]);
    refused(
        &r,
        2,
        "cannot tell the LUT format",
        &dir.path().join("x.lut"),
        None,
    );
    // an existing file is left as it was
    let kept = dir.path().join("kept.cube");
    std::fs::write(&kept, "keep me\n").unwrap();
    let r = lut3d(&d, &kept, &["--size", "1000"]);
    refused(&r, 2, "3D LUT size 1000", &kept, Some("keep me\n"));
    let r = lut3d(&d, &kept, &["--size", "0"]);
    refused(&r, 2, "3D LUT size 0", &kept, Some("keep me\n"));
    let r = lut3d(&d, &kept, &["--source", "prophoto"]);
    refused(&r, 2, "'prophoto' for '--source", &kept, Some("keep me\n"));
    let r = lut3d(&d, &kept, &["--size", "many"]);
    refused(&r, 2, "'many' for '--size", &kept, Some("keep me\n"));
}

/// A calibration of the given lattice (`None`: the matrix model), near-sRGB primaries.
fn calibration(path: &Path, interaction: Option<Lattice>) {
    let primary = |x: f64, y: f64, l: f64| Primary { x, y, luminance: l };
    let data = CalibrationData {
        format: FORMAT.into(),
        version: VERSION,
        units: "relative".into(),
        black: [0.1, 0.1, 0.12],
        white: [95.05, 100.0, 108.9],
        primaries: Primaries {
            red: primary(0.64, 0.33, 21.26),
            green: primary(0.30, 0.60, 71.52),
            blue: primary(0.15, 0.06, 7.22),
        },
        transfer: TransferCurves {
            kind: TransferKind::Gamma,
            gamma: [2.2; 3],
            red: vec![0.0, 1.0],
            green: vec![0.0, 1.0],
            blue: vec![0.0, 1.0],
        },
        interaction,
        fit: FitReport::default(),
        provenance: Provenance::default(),
    };
    Calibration::new(data).unwrap().save(path).unwrap();
}

/// A calibration whose channel interaction makes every mixture far brighter and greener than
/// its channels: no grey between black and white is shown by any device colour.
fn folding_calibration(path: &Path) {
    // corners red slowest: every corner but black (0) and white (7) adds Y = 300
    let values = (0..8)
        .map(|i| {
            if i == 0 || i == 7 {
                [0.0; 3]
            } else {
                [0.0, 300.0, 0.0]
            }
        })
        .collect();
    calibration(path, Some(Lattice { grid: 2, values }));
}

#[test]
fn verify_lut3d_predicts_the_luts_effect_through_the_model() {
    let dir = tempfile::tempdir().unwrap();
    let cal = dir.path().join("cal.toml");
    calibration(&cal, None);
    let cube = dir.path().join("x.cube");
    let r = lut3d(s(&cal), &cube, &["--size", "33"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let verify = |extra: &[&str]| {
        let mut args = vec![
            "calibrate",
            "verify",
            "--calibration",
            s(&cal),
            "--lut3d",
            s(&cube),
        ];
        args.extend_from_slice(extra);
        cli::run(&args)
    };
    let r = verify(&["--require", "recommended", "--json"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let v: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
    assert_eq!(v["pass"], true);
    assert_eq!(v["lut3d"]["patches"], 193);
    assert!(
        v["delta_e00"]["mean"].as_f64().unwrap() < 0.3,
        "{}",
        v["delta_e00"]
    );
    assert!(
        v["delta_e00"]["max"].as_f64().unwrap() < 1.0,
        "{}",
        v["delta_e00"]
    );
    // white and grey balance are judged on the source's white and greys
    let crit = v["criteria"].as_array().unwrap();
    let white = crit.iter().find(|c| c["id"] == "white_delta_e00").unwrap();
    assert!(white["value"].as_f64().unwrap() < 0.05, "{white}");
    // the same LUT taken as a Rec. 2020 one fails, with one line
    let r = verify(&["--source", "rec2020"]);
    assert_eq!(r.code, 1, "{}", r.stderr);
    assert_eq!(r.stderr.lines().count(), 1, "{}", r.stderr);
    assert!(r.stderr.contains("verification failed"), "{}", r.stderr);
    // a LUT file of no format `verify` reads
    let r = cli::run(&[
        "calibrate",
        "verify",
        "--calibration",
        s(&cal),
        "--lut3d",
        "x.3dlut",
    ]);
    assert_eq!(r.code, 2, "{}", r.stderr);
}

#[test]
fn a_model_that_cannot_invert_its_greys_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let cal = dir.path().join("folding.toml");
    folding_calibration(&cal);
    let out = dir.path().join("x.cube");
    let r = lut3d(s(&cal), &out, &["--size", "5"]);
    refused(&r, 1, "cannot invert the colour of source RGB", &out, None);
    assert!(
        r.stderr.contains("a grey between its black and white"),
        "{}",
        r.stderr
    );
    std::fs::write(&out, "old\n").unwrap();
    let r = lut3d(s(&cal), &out, &["--size", "5"]);
    refused(&r, 1, "no 3D LUT written", &out, Some("old\n"));
}
