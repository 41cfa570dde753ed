//! Running the real `specpoly` binary from the integration tests: one place that starts it with
//! its arguments (stdin closed, stdout and stderr captured) and hands back the exit code and the
//! output as text. Include it with `#[path = "common/cli.rs"] mod cli;`.
#![allow(dead_code)]

use std::path::Path;
use std::process::{Child, Command, Output, Stdio};

/// The repository's root (the data files' paths in the docs are relative to it).
pub const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");

/// The Acer XB271HU's 2 068 readings (ArgyllCMS `dispread`), the calibration tests' data.
pub const ACER: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../data/ti3/acer-xb271hu-unit1_dispread_2068.ti3"
);

/// A finished run: exit code (-1 when killed by a signal), stdout and stderr as text.
#[derive(Debug)]
pub struct Run {
    pub code: i32,
    pub stdout: String,
    pub stderr: String,
}

impl Run {
    /// `(code, stdout, stderr)`.
    pub fn parts(self) -> (i32, String, String) {
        (self.code, self.stdout, self.stderr)
    }
}

impl From<Output> for Run {
    fn from(o: Output) -> Self {
        Run {
            code: o.status.code().unwrap_or(-1),
            stdout: text(&o.stdout),
            stderr: text(&o.stderr),
        }
    }
}

/// `specpoly ARGS` in the crate's folder (Cargo's working directory for tests).
pub fn output(args: &[&str]) -> Output {
    command(args).output().expect("run specpoly")
}

/// `specpoly ARGS` in `dir`.
pub fn output_in(dir: impl AsRef<Path>, args: &[&str]) -> Output {
    command(args)
        .current_dir(dir)
        .output()
        .expect("run specpoly")
}

/// `specpoly ARGS` in the crate's folder with `stdin` on its standard input.
pub fn output_with_stdin(args: &[&str], stdin: &str) -> Output {
    use std::io::Write;
    let mut c = spawn_piped(Command::new(env!("CARGO_BIN_EXE_specpoly")).args(args));
    c.stdin.take().unwrap().write_all(stdin.as_bytes()).unwrap();
    c.wait_with_output().unwrap()
}

/// `specpoly ARGS` in the crate's folder, as a [`Run`].
pub fn run(args: &[&str]) -> Run {
    output(args).into()
}

/// `specpoly ARGS` in `dir`, as a [`Run`].
pub fn run_in(dir: impl AsRef<Path>, args: &[&str]) -> Run {
    output_in(dir, args).into()
}

/// `specpoly ARGS` in the crate's folder: `(code, stdout, stderr)`.
pub fn specpoly(args: &[&str]) -> (i32, String, String) {
    run(args).parts()
}

/// Starts `c` with its stdin, stdout and stderr piped to the test.
pub fn spawn_piped(c: &mut Command) -> Child {
    c.stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("start {c:?}: {e}"))
}

fn command(args: &[&str]) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_specpoly"));
    c.args(args).stdin(Stdio::null());
    c
}

/// `calibrate run --display DISPLAY --instrument INSTRUMENT MORE… -o OUT`.
pub fn calibrate_run<'a>(
    display: &'a str,
    instrument: &'a str,
    more: &[&'a str],
    out: &'a str,
) -> Vec<&'a str> {
    let mut a = vec![
        "calibrate",
        "run",
        "--display",
        display,
        "--instrument",
        instrument,
    ];
    a.extend_from_slice(more);
    a.extend(["-o", out]);
    a
}

/// The numbers of a JSON array.
pub fn numbers(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .unwrap_or_else(|| panic!("not an array: {v}"))
        .iter()
        .map(|x| x.as_f64().unwrap_or_else(|| panic!("not a number: {x}")))
        .collect()
}

/// Bytes as text (lossy).
pub fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

/// A path as an argument.
pub fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}
