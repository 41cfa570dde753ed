//! The display model on every real display we ship (data/ti3: an Acer XB271HU IPS monitor, a
//! Dell U2718Q IPS monitor, an HP EliteBook 835 G7 laptop, a Lenovo ThinkPad X61 TN laptop
//! and a Microsoft Surface Pro 2017 tablet, all i1Display Pro readings; see data/README.md):
//! fitted on 4/5 of the patches (`calibrate fit --hold-out`), scored on the other 1/5 with
//! ΔE00 from the `palette` crate (CIELAB relative to the measured white, CIEDE2000), an
//! implementation independent of ours.
//!
//! The oracle is ArgyllCMS: `colprof -qm -as` (shaper/matrix) and `colprof -qm` (cLUT)
//! fitted on the same 4/5 and evaluated on the same 1/5 with `xicclu` (absolute colorimetric,
//! forward table). `argyll_on_the_same_split` runs both on the HP laptop's split and asserts
//! that our held-out mean is at or below both; the figures of every display are in
//! docs/calibration.md ("The display model against ArgyllCMS"), with the commands.

use crate::common::displays;

use displays::{de00, shipped};
use specpoly_calibrate::fit::{fit_and_verify, hold_out_indices, FitOptions};
use specpoly_formats::cgats::read_ti3;
use specpoly_formats::measurement::Measurement;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Our goal on every display: held-out mean ΔE00 at most this (issue 12).
const GOAL_MEAN: f64 = 1.0;

fn ti3_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data/ti3")
        .join(name)
}

/// The readings in the file's own units (white Y = 100), in row order.
fn readings(name: &str) -> (String, Vec<Measurement>) {
    let text = std::fs::read_to_string(ti3_path(name)).unwrap();
    let t = read_ti3(&text, name).unwrap();
    let m = t.measurements.clone();
    (text, m)
}

fn white_of(m: &[Measurement]) -> [f64; 3] {
    let w: Vec<&Measurement> = m
        .iter()
        .filter(|p| p.device.iter().all(|v| *v >= 1.0 - 1e-9))
        .collect();
    [0, 1, 2].map(|i| w.iter().map(|p| p.xyz[i]).sum::<f64>() / w.len() as f64)
}

/// Our held-out mean ΔE00 (palette) on `name`, and what the fit chose.
fn ours(name: &str) -> (f64, String) {
    let (h, _, m) = ours_full(name);
    (h, m)
}

/// Our held-out and self-fit mean ΔE00 (palette) on `name`, and what the fit chose.
fn ours_full(name: &str) -> (f64, f64, String) {
    let (_, m) = readings(name);
    let white = white_of(&m);
    let (fi, hi) = hold_out_indices(&m);
    let fit: Vec<Measurement> = fi.iter().map(|i| m[*i]).collect();
    let held: Vec<Measurement> = hi.iter().map(|i| m[*i]).collect();
    let opts = FitOptions {
        absolute: false,
        ..Default::default()
    };
    let cal = fit_and_verify(&fit, &held, &opts).unwrap();
    let de: Vec<f64> = held
        .iter()
        .map(|p| de00(cal.predict(p.device), p.xyz, white))
        .collect();
    let mean = de.iter().sum::<f64>() / de.len() as f64;
    // our own ΔE00 agrees with palette's
    let v = cal.data().fit.verification.unwrap();
    assert!((v.mean - mean).abs() < 1e-3, "{} vs {mean}", v.mean);
    let own = fit
        .iter()
        .map(|p| de00(cal.predict(p.device), p.xyz, white))
        .sum::<f64>()
        / fit.len() as f64;
    let f = &cal.data().fit;
    let mut what = f.model.clone();
    if !f.outliers.is_empty() {
        what.push_str(&format!(", {} outliers dropped", f.outliers.len()));
    }
    (mean, own, what)
}

#[test]
fn every_display_within_goal() {
    for name in shipped() {
        let name = name.as_str();
        let (mean, model) = ours(name);
        eprintln!("{name}: held-out ΔE00 mean {mean:.3} ({model})");
        assert!(mean <= GOAL_MEAN, "{name}: {mean} ({model})");
    }
}

/// The fit patches of `name` as a .ti3 for colprof: the source's header and the rows of the
/// 4/5 split (the `CAL` table dropped).
fn write_split(name: &str, dir: &Path) -> (PathBuf, Vec<Measurement>, [f64; 3]) {
    let (text, m) = readings(name);
    let (fi, hi) = hold_out_indices(&m);
    let lines: Vec<&str> = text.lines().collect();
    let begin = lines.iter().position(|l| l.trim() == "BEGIN_DATA").unwrap();
    let end = lines.iter().position(|l| l.trim() == "END_DATA").unwrap();
    let rows = &lines[begin + 1..end];
    assert_eq!(rows.len(), m.len());
    let mut out = String::new();
    for l in &lines[..begin] {
        if l.starts_with("NUMBER_OF_SETS") {
            out.push_str(&format!("NUMBER_OF_SETS {}\n", fi.len()));
        } else {
            out.push_str(l);
            out.push('\n');
        }
    }
    out.push_str("BEGIN_DATA\n");
    for i in &fi {
        out.push_str(rows[*i]);
        out.push('\n');
    }
    out.push_str("END_DATA\n");
    let base = dir.join("split");
    std::fs::write(base.with_extension("ti3"), out).unwrap();
    let held = hi.iter().map(|i| m[*i]).collect();
    (base, held, white_of(&m))
}

/// `xicclu -ff -ia -pX`: the profile's absolute XYZ (white Y = 100) for device values.
fn xicclu(icc: &Path, dev: &[[f64; 3]]) -> Vec<[f64; 3]> {
    use std::io::Write;
    let mut c = Command::new("xicclu")
        .args(["-ff", "-ia", "-pX"])
        .arg(icc)
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .spawn()
        .expect("xicclu (ArgyllCMS, installed by test.sh)");
    let mut input = String::new();
    for d in dev {
        input.push_str(&format!("{:.6} {:.6} {:.6}\n", d[0], d[1], d[2]));
    }
    c.stdin.take().unwrap().write_all(input.as_bytes()).unwrap();
    let o = c.wait_with_output().unwrap();
    assert!(o.status.success());
    let v: Vec<[f64; 3]> = String::from_utf8_lossy(&o.stdout)
        .lines()
        .filter(|l| l.contains("[XYZ]"))
        .map(|l| {
            let t = l.rsplit("->").next().unwrap();
            let n: Vec<f64> = t
                .split_whitespace()
                .take(3)
                .map(|x| x.parse().unwrap())
                .collect();
            [n[0], n[1], n[2]]
        })
        .collect();
    assert_eq!(v.len(), dev.len());
    v
}

/// ArgyllCMS's profile of `name`'s 4/5 split made with `colprof ARGS`, run in `dir`:
/// a running child; [`argyll_score`] waits for it.
struct ArgyllRun {
    tag: String,
    child: std::process::Child,
    icc: PathBuf,
    fit: Vec<Measurement>,
    held: Vec<Measurement>,
    white: [f64; 3],
}

fn argyll_start(name: &str, args: &[&str], dir: &Path) -> ArgyllRun {
    let tag = args.join("");
    let d = dir.join(&tag);
    std::fs::create_dir_all(&d).unwrap();
    let (base, held, white) = write_split(name, &d);
    let icc = base.with_extension("icc");
    let child = Command::new("colprof")
        .args(args)
        .arg("-O")
        .arg(&icc)
        .arg(&base)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("colprof (ArgyllCMS, installed by test.sh)");
    let (_, m) = readings(name);
    let (fi, _) = hold_out_indices(&m);
    let fit = fi.iter().map(|i| m[*i]).collect();
    ArgyllRun {
        tag,
        child,
        icc,
        fit,
        held,
        white,
    }
}

/// Mean ΔE00 (palette) of the profile on the held-out and on the fit patches.
fn argyll_score(run: ArgyllRun) -> (f64, f64) {
    let o = run.child.wait_with_output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let mean = |set: &[Measurement]| {
        let dev: Vec<[f64; 3]> = set.iter().map(|p| p.device).collect();
        let pred = xicclu(&run.icc, &dev);
        pred.iter()
            .zip(set)
            .map(|(p, m)| de00(*p, m.xyz, run.white))
            .sum::<f64>()
            / set.len() as f64
    };
    let r = (mean(&run.held), mean(&run.fit));
    eprintln!(
        "ArgyllCMS colprof {}: held-out ΔE00 mean {:.3} over {}, self-fit {:.3}",
        run.tag,
        r.0,
        run.held.len(),
        r.1
    );
    r
}

#[test]
fn argyll_on_the_same_split() {
    let name = "hp-hp-elitebook-835-g7_588.ti3";
    let dir = tempfile::tempdir().unwrap();
    // both profiles at once (two cores)
    let runs = [
        argyll_start(name, &["-qm", "-as"], dir.path()),
        argyll_start(name, &["-qm"], dir.path()),
    ];
    let (our, model) = ours(name);
    eprintln!("ours: {our:.3} ({model})");
    for r in runs {
        let (m, _) = argyll_score(r);
        assert!(our <= m, "ours {our} > ArgyllCMS {m}");
    }
}

/// The table of docs/calibration.md: every display, ours against both ArgyllCMS profiles
/// (minutes: `cargo test -p specpoly --test calibrate_displays -- --ignored --nocapture`).
#[test]
#[ignore]
fn table_for_the_docs() {
    let dir = tempfile::tempdir().unwrap();
    let mut rows = Vec::new();
    for name in shipped() {
        let name = name.as_str();
        let d = dir.path().join(name);
        let runs = [
            argyll_start(name, &["-qm", "-as"], &d),
            argyll_start(name, &["-qm"], &d),
        ];
        let (our, own, model) = ours_full(name);
        let [a, b] = runs.map(argyll_score);
        rows.push(format!(
            "| {name} | **{our:.3}** | {:.3} | {:.3} | {own:.3} | {:.3} | {:.3} | {model} |",
            a.0, b.0, a.1, b.1
        ));
        eprintln!("{}", rows.last().unwrap());
    }
    eprintln!("{}", rows.join("\n"));
}
