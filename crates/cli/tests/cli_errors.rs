//! Bad input through the real binary: one clear line on stderr, exit code 2 for usage and 1 for
//! data errors, no panic, nothing on stdout, and no output file (not even a partial one).

use crate::common::cli;

use std::path::Path;

use cli::{run as specpoly, Run};

/// Asserts a clean failure with `code` whose one stderr line mentions every `needles`.
fn fails(r: &Run, code: i32, needles: &[&str]) {
    assert_eq!(r.code, code, "stderr: {}", r.stderr);
    assert!(r.stdout.is_empty(), "stdout: {}", r.stdout);
    assert!(!r.stderr.contains("panicked"), "{}", r.stderr);
    let lines: Vec<&str> = r.stderr.lines().collect();
    if code == 1 {
        // our own errors: exactly one line
        assert_eq!(lines.len(), 1, "{}", r.stderr);
        assert!(lines[0].starts_with("specpoly: error: "), "{}", r.stderr);
    } else {
        assert!(r.stderr.contains("error"), "{}", r.stderr);
    }
    for n in needles {
        assert!(
            r.stderr.to_lowercase().contains(&n.to_lowercase()),
            "`{n}` not in: {}",
            r.stderr
        );
    }
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_string()
}

fn files_in(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn malformed_csv_is_a_data_error_naming_the_file_and_line() {
    let d = tempfile::tempdir().unwrap();
    let cases: [(&str, &str, &[&str]); 9] = [
        ("noheader.csv", "400,0.1\n410,0.2\n", &["no header"]),
        (
            "text.csv",
            "wavelength_nm,a\n400,0.1\n410,abc\n",
            &["text.csv:3", "not a number"],
        ),
        (
            "nan.csv",
            "wavelength_nm,a\n400,NaN\n410,0.2\n",
            &["not finite"],
        ),
        (
            "decreasing.csv",
            "wavelength_nm,a\n400,0.1\n390,0.2\n",
            &["decreasing"],
        ),
        (
            "duplicate.csv",
            "wavelength_nm,a\n400,0.1\n400,0.2\n",
            &["duplicate"],
        ),
        (
            "emptycol.csv",
            "wavelength_nm,a,b\n400,0.1,\n410,0.2,\n",
            &["empty cell", "`b`"],
        ),
        (
            "outside.csv",
            "wavelength_nm,a\n800,0.1\n900,0.2\n",
            &["outside 380-780"],
        ),
        ("empty.csv", "", &["empty"]),
        ("ragged.csv", "wavelength_nm,a\n400,0.1,0.3\n", &["3 cells"]),
    ];
    for (name, text, needles) in cases {
        let f = write(d.path(), name, text);
        let spec = if name == "emptycol.csv" {
            format!("{f}#a")
        } else {
            f.clone()
        };
        for cmd in [
            vec!["xyz", spec.as_str()],
            vec!["fit", spec.as_str()],
            vec!["table1", spec.as_str()],
        ] {
            let r = specpoly(&cmd);
            fails(&r, 1, needles);
            assert!(r.stderr.contains(name), "{}", r.stderr);
        }
    }
}

#[test]
fn unknown_names_are_usage_errors() {
    for (args, needles) in [
        (
            vec!["xyz", "colorchecker#red", "--illuminant", "F99"],
            vec!["F99", "illuminant"],
        ),
        (
            vec!["xyz", "colorchecker#nosuchpatch"],
            vec!["no column `nosuchpatch`"],
        ),
        (vec!["xyz", "colorchecker"], vec!["columns"]),
        (vec!["xyz", "no/such/file.csv"], vec!["no such file"]),
        (
            vec!["xyz", "colorchecker#red", "--repr", "poly:7x3"],
            vec!["supported spans"],
        ),
        (
            vec!["xyz", "colorchecker#red", "--repr", "fancy"],
            vec!["unknown representation"],
        ),
        (
            vec!["xyz", "colorchecker#red", "--observer", "1976"],
            vec!["unknown observer"],
        ),
        (
            vec!["fit", "colorchecker#red", "--repr", "rgb"],
            vec!["polynomial representation"],
        ),
    ] {
        fails(&specpoly(&args), 2, &needles);
    }
    // clap's own usage errors (missing arguments) exit with 2 too
    assert_eq!(specpoly(&["xyz"]).code, 2);
    assert_eq!(specpoly(&["plot", "colorchecker#red"]).code, 2);
}

#[test]
fn no_partial_output_files() {
    let d = tempfile::tempdir().unwrap();
    let out = d.path().join("fig.svg");
    let o = out.to_str().unwrap();
    // bad data: nothing written
    let bad = write(d.path(), "bad.csv", "wavelength_nm,a\n400,x\n");
    fails(&specpoly(&["plot", &bad, "-o", o]), 1, &["not a number"]);
    fails(
        &specpoly(&["plot", "colorchecker#red", "--product", "-o", o]),
        2,
        &["two spectra"],
    );
    fails(
        &specpoly(&["plot", "colorchecker#red", "-o", &format!("{o}.gif")]),
        2,
        &[".svg or .png"],
    );
    assert_eq!(files_in(d.path()), vec!["bad.csv"]);
    // an unwritable path: a data (I/O) error, nothing left behind
    let missing = d.path().join("no/such/dir/fig.png");
    fails(
        &specpoly(&["plot", "colorchecker#red", "-o", missing.to_str().unwrap()]),
        1,
        &["no/such/dir/fig.png"],
    );
    let missing_md = d.path().join("nodir/accuracy.md");
    fails(
        &specpoly(&["accuracy", "-o", missing_md.to_str().unwrap()]),
        1,
        &["nodir/accuracy.md"],
    );
    // a directory in the way of the output file
    std::fs::create_dir(d.path().join("taken.svg")).unwrap();
    let taken = d.path().join("taken.svg");
    fails(
        &specpoly(&["plot", "colorchecker#red", "-o", taken.to_str().unwrap()]),
        1,
        &["taken.svg"],
    );
    assert_eq!(files_in(d.path()), vec!["bad.csv", "taken.svg"]);
    assert_eq!(
        std::fs::read_dir(&taken).unwrap().count(),
        0,
        "nothing written into the directory"
    );
}

#[test]
fn an_observer_name_is_judged_the_same_by_every_command() {
    // CIE 015:2018 names the 1964 observer the "10°" observer: `10` is accepted everywhere
    let xyz = specpoly(&["xyz", "colorchecker#red", "--observer", "10"]);
    assert_eq!(xyz.code, 0, "{}", xyz.stderr);
    assert!(xyz.stdout.contains("CIE 1964 observer"), "{}", xyz.stdout);
    // `led` accepts it too: the failure is the port (exit 1), not the name (exit 2)
    let led = specpoly(&[
        "led",
        "--port",
        "/dev/no-such-port",
        "--observer",
        "10",
        "state",
    ]);
    assert_eq!(led.code, 1, "{}", led.stderr);
    // and an unknown name is the same usage error for both
    for args in [
        vec!["xyz", "colorchecker#red", "--observer", "1976"],
        vec!["fit", "colorchecker#red", "--observer", "1976"],
        vec!["led", "--port", "/dev/null", "--observer", "1976", "state"],
    ] {
        fails(&specpoly(&args), 2, &["unknown observer `1976`"]);
    }
}
