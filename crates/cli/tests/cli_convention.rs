//! One CLI convention across the commands (README "The CLI", src/error.rs): `--json` where
//! results are printed (numbers as JSON numbers), `wrote FILE` on stderr for every file written,
//! the same exit code for the same failure in every command (a missing input file is 2), errors
//! on one line — clap's and TOML's included — without Rust `Debug` forms, and `calibrate predict`
//! answering each line of a pipe as it arrives.

use crate::common::cli;

use cli::{text, ACER, ROOT};
use std::io::{BufRead, BufReader, Write};
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::sync::mpsc;
use std::time::Duration;

fn specpoly(args: &[&str]) -> Output {
    cli::output_in(ROOT, args)
}

/// Exit `code`, exactly one line on stderr starting `specpoly: error: `, nothing on stdout,
/// and no Rust `Debug` form in it.
fn one_line_error(o: &Output, code: i32, what: &str) {
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(code), "{what}: {err}");
    assert_eq!(
        err.trim_end().lines().count(),
        1,
        "{what}: not one line: {err}"
    );
    assert!(err.starts_with("specpoly: error: "), "{what}: {err}");
    for leak in ["Some(", "None", "Err(", "Ok(", "panicked", "\\n"] {
        assert!(!err.contains(leak), "{what}: `{leak}` in {err}");
    }
}

/// Every string in a JSON value, with its key path; numbers must not hide in strings.
fn strings<'a>(v: &'a serde_json::Value, path: String, out: &mut Vec<(String, &'a str)>) {
    match v {
        serde_json::Value::String(s) => out.push((path, s)),
        serde_json::Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                strings(x, format!("{path}[{i}]"), out);
            }
        }
        serde_json::Value::Object(o) => {
            for (k, x) in o {
                assert!(
                    k.chars()
                        .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
                        || ["X", "Y", "Z", "x", "y", "L", "a", "b"].contains(&k.as_str()),
                    "{path}.{k}: keys are snake_case (or a CIE symbol)"
                );
                strings(x, format!("{path}.{k}"), out);
            }
        }
        _ => {}
    }
}

/// Parses `--json` output and checks no number is written as a string.
fn json(o: &Output, what: &str) -> serde_json::Value {
    assert!(o.status.success(), "{what}: {}", text(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout)
        .unwrap_or_else(|e| panic!("{what}: {e}: {}", text(&o.stdout)));
    let mut s = Vec::new();
    strings(&v, what.to_string(), &mut s);
    for (path, s) in s {
        assert!(
            s.trim().parse::<f64>().is_err(),
            "{path}: the number {s:?} is a string"
        );
    }
    v
}

#[test]
fn a_missing_input_file_is_exit_2_in_every_command() {
    let dir = tempfile::tempdir().unwrap();
    let none = dir.path().join("none");
    let f = |ext: &str| format!("{}.{ext}", none.display());
    let (csv, toml, ti3, ti1) = (f("csv"), f("toml"), f("ti3"), f("ti1"));
    let out = dir.path().join("out");
    let o = |ext: &str| format!("{}.{ext}", out.display());
    let cases: Vec<Vec<String>> = vec![
        vec!["xyz".into(), csv.clone()],
        vec!["fit".into(), csv.clone()],
        vec!["table1".into(), csv.clone()],
        vec!["plot".into(), csv.clone(), "-o".into(), o("svg")],
        vec!["light".into(), csv.clone()],
        vec!["render".into(), toml.clone(), "-o".into(), o("png")],
        vec![
            "render".into(),
            "example1".into(),
            "--display".into(),
            toml.clone(),
            "-o".into(),
            o("png"),
        ],
        vec![
            "calibrate".into(),
            "fit".into(),
            "--ti3".into(),
            ti3.clone(),
            "-o".into(),
            o("toml"),
        ],
        vec!["calibrate".into(), "show".into(), toml.clone()],
        vec![
            "calibrate".into(),
            "predict".into(),
            "--calibration".into(),
            toml.clone(),
        ],
        vec![
            "calibrate".into(),
            "verify".into(),
            "--calibration".into(),
            toml.clone(),
            "--ti3".into(),
            ACER.into(),
        ],
        vec![
            "calibrate".into(),
            "icc".into(),
            toml.clone(),
            "-o".into(),
            o("icc"),
        ],
        vec![
            "calibrate".into(),
            "export".into(),
            "--calibration".into(),
            toml.clone(),
            "--format".into(),
            "c-table".into(),
            "-o".into(),
            o("h"),
        ],
        vec![
            "calibrate".into(),
            "run".into(),
            "--display".into(),
            "sim:crt".into(),
            "--instrument".into(),
            "sim".into(),
            "--patches".into(),
            ti1,
            "-o".into(),
            o("toml"),
        ],
        vec![
            "led".into(),
            "--port".into(),
            "/dev/null".into(),
            "--calibration".into(),
            toml.clone(),
            "state".into(),
        ],
    ];
    for args in &cases {
        let a: Vec<&str> = args.iter().map(String::as_str).collect();
        let r = specpoly(&a);
        one_line_error(&r, 2, &a.join(" "));
        assert!(text(&r.stdout).is_empty(), "{a:?}");
        assert!(
            text(&r.stderr).contains("none."),
            "{a:?}: names the file: {}",
            text(&r.stderr)
        );
    }
    assert!(
        std::fs::read_dir(dir.path()).unwrap().next().is_none(),
        "nothing written"
    );
}

#[test]
fn clap_and_toml_errors_are_one_line() {
    for args in [
        vec!["xyz", "colorchecker#red", "--bogus"],
        vec!["plot", "colorchecker#red"],
        vec!["calibrate"],
        vec![],
        vec!["render", "example1", "--samples", "99", "-o", "x.png"],
        vec![
            "calibrate",
            "verify",
            "--calibration",
            "a.toml",
            "--ti3",
            "b",
            "--require",
            "perfect",
        ],
    ] {
        let r = specpoly(&args);
        one_line_error(&r, 2, &format!("{args:?}"));
    }
    // the line keeps clap's usage where clap gives one
    for args in [
        vec!["xyz", "colorchecker#red", "--bogus"],
        vec!["calibrate"],
    ] {
        let r = specpoly(&args);
        assert!(
            text(&r.stderr).contains("usage: specpoly"),
            "{args:?}: {}",
            text(&r.stderr)
        );
    }
    // --help and --version are not errors
    let r = specpoly(&["--version"]);
    assert!(r.status.success());
    let r = specpoly(&["calibrate", "verify", "--help"]);
    assert!(r.status.success() && text(&r.stdout).contains("--report"));

    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("bad.toml");
    // the value's own line and column (toml 0.8 keeps the span of a type error)
    std::fs::write(&scene, "[render]\nwidth = \"eight\"\n").unwrap();
    let r = specpoly(&["render", scene.to_str().unwrap(), "-o", "x.png"]);
    one_line_error(&r, 1, "scene");
    assert!(
        text(&r.stderr).contains("bad.toml:2:9:"),
        "{}",
        text(&r.stderr)
    );
    let display = dir.path().join("display.toml");
    std::fs::write(&display, "gamma = 2.2\nprimaries = \"x\"\n").unwrap();
    let r = specpoly(&[
        "render",
        "example1",
        "--display",
        display.to_str().unwrap(),
        "-o",
        dir.path().join("x.png").to_str().unwrap(),
    ]);
    one_line_error(&r, 1, "display");
    assert!(
        text(&r.stderr).contains("display.toml:2:"),
        "{}",
        text(&r.stderr)
    );
}

/// The Acer's calibration, fitted once per test run (with `--json`, checked here).
fn fitted() -> String {
    static CAL: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    CAL.get_or_init(|| {
        let cal = Path::new(env!("CARGO_TARGET_TMPDIR")).join("cli_convention_acer.toml");
        let r = specpoly(&[
            "calibrate",
            "fit",
            "--ti3",
            ACER,
            "-o",
            cal.to_str().unwrap(),
            "--json",
        ]);
        let v = json(&r, "calibrate fit");
        for k in [
            "output",
            "patches_fit",
            "fit_delta_e00",
            "held_out_delta_e00",
            "notes",
        ] {
            assert!(v.get(k).is_some(), "calibrate fit: no {k}");
        }
        assert!(v["fit_delta_e00"]["mean"].is_number());
        assert_eq!(text(&r.stderr).trim(), format!("wrote {}", cal.display()));
        cal.to_str().unwrap().to_string()
    })
    .clone()
}

#[test]
fn json_everywhere_results_are_printed() {
    let dir = tempfile::tempdir().unwrap();
    let cal = fitted();
    let png = dir.path().join("r.png");
    let runs: Vec<(&str, Vec<&str>)> = vec![
        ("xyz", vec!["xyz", "colorchecker#red", "--json"]),
        ("fit", vec!["fit", "colorchecker#red", "--json"]),
        ("table1", vec!["table1", "colorchecker#blue", "--json"]),
        (
            "light",
            vec!["light", "data/leds/rgbwa.csv#white", "--json"],
        ),
        (
            "mix",
            vec![
                "mix",
                "--channel",
                "r=data/leds/rgb.csv#red",
                "--channel",
                "g=data/leds/rgb.csv#green",
                "--channel",
                "b=data/leds/rgb.csv#blue",
                "--target",
                "cct:5000",
                "--json",
            ],
        ),
        ("calibrate show", vec!["calibrate", "show", &cal, "--json"]),
        (
            "render",
            vec![
                "render",
                "example1",
                "--size",
                "16x12",
                "--json",
                "-o",
                png.to_str().unwrap(),
            ],
        ),
    ];
    for (what, args) in runs {
        let r = specpoly(&args);
        json(&r, what);
    }
    // calibrate run: progress on stderr, the result as JSON on stdout
    let run_cal = dir.path().join("crt.toml");
    let r = specpoly(&cli::calibrate_run(
        "sim:crt,seed=1",
        "sim",
        &["--ramp-steps", "3", "--verify", "2", "--json"],
        run_cal.to_str().unwrap(),
    ));
    let v = json(&r, "calibrate run");
    for k in [
        "readings",
        "patches_measured",
        "patches_verify",
        "fit_delta_e00",
    ] {
        assert!(v.get(k).is_some(), "calibrate run: no {k}");
    }
    assert_eq!(v["patches_verify"], 2);
    let err = text(&r.stderr);
    assert!(
        err.contains(&format!("wrote {}", run_cal.display())),
        "{err}"
    );
    // calibrate verify (with the other commands' checks of its JSON)
    let v = json(
        &specpoly(&[
            "calibrate",
            "verify",
            "--calibration",
            &cal,
            "--ti3",
            ACER,
            "--json",
        ]),
        "calibrate verify",
    );
    for k in [
        "delta_e00",
        "criteria",
        "pass",
        "level",
        "patch_results",
        "worst",
    ] {
        assert!(v.get(k).is_some(), "verify: no {k}");
    }
}

#[test]
fn wrote_file_on_stderr_for_every_file_written() {
    let dir = tempfile::tempdir().unwrap();
    let cal = fitted();
    let p = |n: &str| dir.path().join(n).to_str().unwrap().to_string();
    let runs: Vec<(String, Vec<String>)> = vec![
        (
            p("fig.svg"),
            vec![
                "plot".into(),
                "colorchecker#red".into(),
                "-o".into(),
                p("fig.svg"),
            ],
        ),
        (
            p("r.png"),
            vec![
                "render".into(),
                "example1".into(),
                "--size".into(),
                "16x12".into(),
                "-o".into(),
                p("r.png"),
            ],
        ),
        (
            p("a.icc"),
            vec![
                "calibrate".into(),
                "icc".into(),
                cal.clone(),
                "-o".into(),
                p("a.icc"),
            ],
        ),
        (
            p("p.ti1"),
            vec![
                "calibrate".into(),
                "patches".into(),
                "-o".into(),
                p("p.ti1"),
            ],
        ),
        (
            p("t.h"),
            vec![
                "calibrate".into(),
                "export".into(),
                "--calibration".into(),
                cal.clone(),
                "--format".into(),
                "c-table".into(),
                "-o".into(),
                p("t.h"),
            ],
        ),
        (
            p("rep.html"),
            vec![
                "calibrate".into(),
                "verify".into(),
                "--calibration".into(),
                cal.clone(),
                "--ti3".into(),
                ACER.into(),
                "--report".into(),
                p("rep.html"),
            ],
        ),
    ];
    for (file, args) in runs {
        let a: Vec<&str> = args.iter().map(String::as_str).collect();
        let r = specpoly(&a);
        assert!(r.status.success(), "{a:?}: {}", text(&r.stderr));
        let err = text(&r.stderr);
        assert!(
            err.lines().any(|l| l.starts_with(&format!("wrote {file}"))),
            "{a:?}: stderr {err}"
        );
        assert!(
            !text(&r.stdout).contains("wrote "),
            "{a:?}: `wrote` belongs on stderr"
        );
        assert!(Path::new(&file).is_file(), "{file}");
    }
}

#[test]
fn predict_answers_each_line_as_it_arrives() {
    let cal = fitted();
    let mut c = Command::new(env!("CARGO_BIN_EXE_specpoly"))
        .args(["calibrate", "predict", "--calibration", &cal, "--json"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stdin = c.stdin.take().unwrap();
    let (tx, rx) = mpsc::channel();
    let stdout = c.stdout.take().unwrap();
    std::thread::spawn(move || {
        for line in BufReader::new(stdout).lines() {
            if tx.send(line.unwrap()).is_err() {
                break;
            }
        }
    });
    // a conversation: each answer must come back while stdin is still open
    for (n, rgb) in [(1, "1 1 1"), (2, "0 0 0"), (3, "0.5, 0.25, 0")] {
        writeln!(stdin, "{rgb}").unwrap();
        stdin.flush().unwrap();
        let got = rx
            .recv_timeout(Duration::from_secs(20))
            .unwrap_or_else(|_| panic!("no answer to line {n} while the pipe is open"));
        let v: serde_json::Value = serde_json::from_str(&got).unwrap();
        assert_eq!(v["line"], n);
        assert!(v["Y"].is_number(), "{got}");
    }
    // a bad line: an error naming it, the answers before it kept, exit 1
    writeln!(stdin, "0.2 0.3").unwrap();
    drop(stdin);
    let st = c.wait().unwrap();
    assert_eq!(st.code(), Some(1));
    let mut err = String::new();
    std::io::Read::read_to_string(&mut c.stderr.take().unwrap(), &mut err).unwrap();
    assert!(err.contains("stdin:4:"), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(
        rx.recv_timeout(Duration::from_secs(5)).is_err(),
        "nothing after the bad line"
    );
}
