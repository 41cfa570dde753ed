//! Crashes, hangs and unbounded work (issue 10), one test per class, through the real binary:
//! each bad input ends promptly with one error line and exit code 1 or 2 (never a panic, exit
//! 101, or a signal), or, where the input is legitimate, succeeds.

use crate::common::cli;

use cli::{s, Run};
use std::path::Path;
use std::process::Command;
use std::time::Duration;

/// Runs specpoly, killing it (and failing the test) after `limit`.
fn specpoly_within(args: &[&str], limit: Duration) -> Run {
    let mut child = cli::spawn_piped(Command::new(env!("CARGO_BIN_EXE_specpoly")).args(args));
    drop(child.stdin.take());
    let pid = child.id();
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || tx.send(child.wait_with_output()));
    let Ok(out) = rx.recv_timeout(limit) else {
        let _ = Command::new("kill").args(["-9", &pid.to_string()]).status();
        panic!("specpoly {args:?} still running after {limit:?}");
    };
    out.unwrap().into()
}

fn specpoly(args: &[&str]) -> Run {
    specpoly_within(args, Duration::from_secs(60))
}

/// A clean failure: `code`, one stderr line naming `needle`, no panic.
fn fails(r: &Run, code: i32, needle: &str) {
    assert_eq!(r.code, code, "stderr: {}", r.stderr);
    assert!(!r.stderr.contains("panicked"), "{}", r.stderr);
    assert_eq!(r.stderr.lines().count(), 1, "{}", r.stderr);
    assert!(r.stderr.contains(needle), "`{needle}` not in: {}", r.stderr);
}

/// A one-column spectral CSV, 380–780 nm every 10 nm, every value `v`.
fn csv(name: &str, v: &str) -> String {
    let mut t = format!("wavelength_nm,{name}\n");
    for nm in (380..=780).step_by(10) {
        t += &format!("{nm},{v}\n");
    }
    t
}

#[test]
fn huge_instrument_readings_are_refused_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let mut t = String::from(
        "CTI3\nNUMBER_OF_FIELDS 7\nBEGIN_DATA_FORMAT\nSAMPLE_ID RGB_R RGB_G RGB_B XYZ_X XYZ_Y XYZ_Z\n\
         END_DATA_FORMAT\nNUMBER_OF_SETS 6\nBEGIN_DATA\n",
    );
    t += "1 0 0 0 0.1 0.1 0.1\n2 100 0 0 1e200 1e200 1e200\n3 0 100 0 30 60 10\n";
    t += "4 0 0 100 15 6 80\n5 100 100 100 85 100 110\n6 50 0 0 10 5 0.5\n";
    t += "END_DATA\n";
    let ti3 = dir.path().join("huge.ti3");
    std::fs::write(&ti3, t).unwrap();
    let out = dir.path().join("huge.toml");
    let r = specpoly(&["calibrate", "fit", "--ti3", s(&ti3), "-o", s(&out)]);
    fails(&r, 1, "beyond");
    assert!(!out.exists());
}

#[test]
fn long_and_hostile_names_print_safely() {
    let dir = tempfile::tempdir().unwrap();
    // a name wider than any format width (65 535)
    let long = "n".repeat(70_000);
    let f = dir.path().join("long.csv");
    std::fs::write(&f, csv(&long, "0.5")).unwrap();
    let r = specpoly(&["xyz", s(&f)]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(r.stdout.contains(&long));
    // terminal escape codes in a column name: escaped on stdout and in errors
    let f = dir.path().join("esc.csv");
    std::fs::write(&f, csv("red\u{1b}[2J\u{7}", "0.5")).unwrap();
    let r = specpoly(&["xyz", s(&f)]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(!r.stdout.contains('\u{1b}') && !r.stdout.contains('\u{7}'));
    assert!(r.stdout.contains("red\\u{1b}[2J\\u{7}"), "{}", r.stdout);
    let r = specpoly(&["xyz", &format!("{}#nope\u{1b}[31m", s(&f))]);
    assert_ne!(r.code, 0);
    assert!(!r.stderr.contains('\u{1b}'), "{}", r.stderr);
    assert_eq!(r.stderr.lines().count(), 1, "{}", r.stderr);
}

#[test]
fn huge_waits_and_timeouts_are_usage_errors() {
    let dir = tempfile::tempdir().unwrap();
    let cal = dir.path().join("cal.toml");
    for display in ["web,wait=1e20", "web,timeout=3e19"] {
        let r = specpoly(&cli::calibrate_run(display, "sim", &[], s(&cal)));
        assert!(r.code == 1 || r.code == 2, "{}", r.stderr);
        fails(&r, r.code, "86400");
    }
    let r = specpoly(&cli::calibrate_run(
        "manual",
        "sim,measure-timeout=1e300",
        &[],
        s(&cal),
    ));
    assert!(r.code == 1 || r.code == 2, "{}", r.stderr);
    assert!(!r.stderr.contains("panicked"), "{}", r.stderr);
    let r = specpoly(&[
        "led",
        "--port",
        "/nonexistent",
        "--timeout-ms",
        "18446744073709551615",
        "hello",
    ]);
    assert_eq!(r.code, 2, "{}", r.stderr);
    assert!(!r.stderr.contains("panicked"), "{}", r.stderr);
    assert!(!cal.exists());
}

#[test]
fn plot_of_tiny_values_returns() {
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("tiny.csv");
    std::fs::write(&f, csv("tiny", "1e-40")).unwrap();
    let out = dir.path().join("tiny.svg");
    let r = specpoly_within(&["plot", s(&f), "-o", s(&out)], Duration::from_secs(30));
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(out.exists());
}

/// A scene of two facing planes of material `m` (`mat`: its keys), with `depth` and `cutoff`.
fn scene(dir: &Path, name: &str, mat: &str, depth: u32, cutoff: f32) -> String {
    let mat = format!("[materials.m]\n{mat}\n");
    let text = format!(
        "[render]\nwidth = 2\nheight = 2\nmax_depth = {depth}\ncutoff = {cutoff}\n\
         [camera]\nposition = [0.0, 0.0, -0.5]\nlook_at = [0.0, 0.0, 1.0]\n\
         [ambient]\nspectrum = \"D65\"\nintensity = 0.2\n\
         [[light]]\nposition = [0.0, 0.5, 0.0]\nspectrum = \"D65\"\n{mat}\
         [[plane]]\npoint = [0.0, 0.0, 1.0]\nnormal = [0.0, 0.0, -1.0]\nmaterial = \"m\"\n\
         [[plane]]\npoint = [0.0, 0.0, -1.0]\nnormal = [0.0, 0.0, 1.0]\nmaterial = \"m\"\n"
    );
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_string()
}

const MIRROR: &str = "mirror = 1.0";
const GLASS: &str = "mirror = 1.0\ntransmission = 1.0\nior = 1.5";

#[test]
fn scene_work_is_bounded() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o.png");
    // facing perfect mirrors at the depth limit: a chain of rays, renders promptly
    let ok = scene(dir.path(), "mirrors.toml", MIRROR, 64, 0.0);
    let r = specpoly_within(&["render", &ok, "-o", s(&out)], Duration::from_secs(30));
    assert_eq!(r.code, 0, "{}", r.stderr);
    // beyond the depth limit (was a stack overflow)
    let deep = scene(dir.path(), "deep.toml", MIRROR, 100_000, 0.0);
    let _ = std::fs::remove_file(&out);
    fails(
        &specpoly(&["render", &deep, "-o", s(&out)]),
        1,
        "max_depth 100000",
    );
    // a forking material at depth 40 (was exponential time)
    let fork = scene(dir.path(), "fork.toml", GLASS, 40, 0.0);
    fails(
        &specpoly(&["render", &fork, "-o", s(&out)]),
        1,
        "rays per sample",
    );
    assert!(!out.exists());
    // a half-reflecting, half-transmitting material with a cutoff that prunes the tree renders
    let pruned = scene(
        dir.path(),
        "pruned.toml",
        "mirror = 0.5\ntransmission = 0.5\nior = 1.5",
        40,
        0.01,
    );
    let r = specpoly_within(&["render", &pruned, "-o", s(&out)], Duration::from_secs(30));
    assert_eq!(r.code, 0, "{}", r.stderr);
}

#[test]
fn devices_and_fifos_are_not_read_as_input() {
    let r = specpoly_within(&["xyz", "/dev/zero"], Duration::from_secs(10));
    fails(&r, 1, "not a regular file");
    let r = specpoly_within(
        &["render", "/dev/zero", "-o", "/tmp/never.png"],
        Duration::from_secs(10),
    );
    assert_ne!(r.code, 0);
    assert!(!r.stderr.contains("panicked"));
}

#[test]
fn implausible_reflectances_are_refused_with_a_hint() {
    let dir = tempfile::tempdir().unwrap();
    let percent = dir.path().join("percent.csv");
    std::fs::write(&percent, csv("grey", "45")).unwrap();
    fails(&specpoly(&["xyz", s(&percent)]), 1, "--scale 0.01");
    // the hint works: percent data scaled by 0.01 equals the same data in 0–1
    let r = specpoly(&["xyz", s(&percent), "--scale", "0.01", "--json"]);
    let unit = dir.path().join("unit.csv");
    std::fs::write(&unit, csv("grey", "0.45")).unwrap();
    let q = specpoly(&["xyz", s(&unit), "--json"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let y = |t: &str| -> f64 {
        let v: serde_json::Value = serde_json::from_str(t).unwrap();
        v[0]["Y"].as_f64().unwrap()
    };
    assert!((y(&r.stdout) - y(&q.stdout)).abs() < 1e-4);
    let negative = dir.path().join("neg.csv");
    std::fs::write(&negative, csv("neg", "-0.3")).unwrap();
    fails(&specpoly(&["xyz", s(&negative)]), 1, "negative");
    fails(&specpoly(&["xyz", "D65"]), 1, "--illuminant");
    let huge = dir.path().join("huge.csv");
    std::fs::write(&huge, csv("huge", "3e38")).unwrap();
    let r = specpoly(&["xyz", s(&huge)]);
    assert_eq!(r.code, 1, "{}", r.stderr);
    assert!(!r.stdout.contains("inf") && !r.stdout.to_lowercase().contains("nan"));
}

/// The input limit (64 MiB by default) is the user's to raise or lower with
/// `--max-input-size`: a mesh over it is a one-line error that names the option, the same
/// mesh renders under a larger limit, and a size that is not one is a usage error.
#[test]
fn the_input_limit_is_settable() {
    let dir = tempfile::tempdir().unwrap();
    // a 10 × 10 grid of quads, ≈ 2.5 KB of OBJ
    let mut obj = String::new();
    for j in 0..=10 {
        for i in 0..=10 {
            obj += &format!("v {} {} 3\n", i as f32 / 5.0 - 1.0, j as f32 / 5.0 - 1.0);
        }
    }
    for j in 0..10 {
        for i in 0..10 {
            let v = |a: usize, b: usize| (b * 11 + a + 1).to_string();
            obj += &format!(
                "f {} {} {} {}\n",
                v(i, j),
                v(i + 1, j),
                v(i + 1, j + 1),
                v(i, j + 1)
            );
        }
    }
    assert!(obj.len() > 2048);
    std::fs::write(dir.path().join("grid.obj"), &obj).unwrap();
    let scene = dir.path().join("s.toml");
    std::fs::write(
        &scene,
        "[camera]\nposition = [0.0, 0.0, 0.0]\nlook_at = [0.0, 0.0, 1.0]\n[[light]]\n\
         position = [0.0, 0.0, 0.0]\nspectrum = \"D65\"\n[materials.grey]\ndiffuse = 0.5\n\
         [[mesh]]\nfile = \"grid.obj\"\nmaterial = \"grey\"\n",
    )
    .unwrap();
    let out = dir.path().join("o.png");
    let args = |limit: &'static str| {
        vec![
            "render",
            s(&scene),
            "--size",
            "8x8",
            "-o",
            s(&out),
            "--max-input-size",
            limit,
        ]
    };
    let r = specpoly(&args("2K"));
    fails(&r, 1, "--max-input-size");
    assert!(
        r.stderr.contains("grid.obj") && r.stderr.contains("2 KiB"),
        "{}",
        r.stderr
    );
    assert!(!out.exists());
    let r = specpoly(&args("1M"));
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(out.exists());
    for bad in ["0", "12X", "2T", "-1"] {
        fails(&specpoly(&args(bad)), 2, bad);
    }
}

#[test]
fn file_names_with_control_characters_print_escaped_in_wrote_lines() {
    let dir = tempfile::tempdir().unwrap();
    // an OSC sequence that would retitle the terminal, a bell, a carriage return
    let name = "x\u{1b}]0;owned\u{7}\ry";
    let shown = "x\\u{1b}]0;owned\\u{7}\\ry";
    let p = |ext: &str| dir.path().join(format!("{name}.{ext}"));
    let (cal, png, ti1, h, svg) = (p("toml"), p("png"), p("ti1"), p("h"), p("svg"));
    let runs = [
        vec!["render", "example1", "--size", "4x4", "-o", s(&png)],
        vec!["calibrate", "patches", "-o", s(&ti1)],
        vec![
            "calibrate",
            "run",
            "--display",
            "sim:crt",
            "--instrument",
            "sim",
            "--ramp-steps",
            "3",
            "--verify",
            "1",
            "--target",
            "white=D65,gamma=2.2",
            "-o",
            s(&cal),
        ],
        vec![
            "calibrate",
            "export",
            "--calibration",
            s(&cal),
            "--format",
            "c-table",
            "-o",
            s(&h),
        ],
        vec!["plot", "colorchecker#blue", "-o", s(&svg)],
    ];
    for args in runs {
        let r = specpoly(&args);
        assert_eq!(r.code, 0, "{args:?}: {}", r.stderr);
        for c in ['\u{1b}', '\u{7}', '\r'] {
            assert!(!r.stderr.contains(c), "{args:?}: {:?}", r.stderr);
        }
        assert!(
            r.stderr
                .contains(&format!("wrote {}/{shown}.", dir.path().display())),
            "{args:?}: {}",
            r.stderr
        );
    }
}

#[test]
fn plot_svg_of_a_name_with_control_characters_is_well_formed_xml() {
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("esc.csv");
    std::fs::write(&f, csv("red\u{1b}]0;owned\u{7}\u{0}", "0.5")).unwrap();
    let svg = dir.path().join("esc.svg");
    let r = specpoly(&["plot", s(&f), "-o", s(&svg)]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let text = std::fs::read_to_string(&svg).unwrap();
    // an independent XML 1.0 parser
    let doc = roxmltree::Document::parse(&text).unwrap_or_else(|e| panic!("{e}\n{text}"));
    let shown: Vec<&str> = doc.descendants().filter_map(|n| n.text()).collect();
    assert!(
        shown
            .iter()
            .any(|t| t.contains("red\\u{1b}]0;owned\\u{7}\\u{0}")),
        "{shown:?}"
    );
}
