//! Output paths through the real binary (issue 10): `-o -` is stdout (also for `render`; a
//! closed stdout is an error, not a lost output), a symlink is written
//! through (the link stays), a FIFO is written directly, the temporary file is exclusive and
//! random (a planted symlink at the old predictable name is not followed), and a temporary file
//! a killed run left behind is cleaned up.

use std::os::unix::fs::{symlink, FileTypeExt};
use std::path::Path;
use std::process::{Command, Stdio};

fn specpoly(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_specpoly"))
        .args(args)
        .stdin(Stdio::null())
        .output()
        .expect("run specpoly")
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// `plot colorchecker#blue -o OUT` (an SVG: deterministic text).
fn plot(out: &str) -> std::process::Output {
    specpoly(&["plot", "colorchecker#blue", "-o", out])
}

/// A real display's measurements (data/README.md).
const TI3: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../data/ti3/acer-xb271hu-unit1_dispread_2068.ti3"
);

#[test]
fn dash_writes_to_stdout() {
    let r = specpoly(&[
        "calibrate",
        "fit",
        "--ti3",
        concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../data/ti3/acer-xb271hu-unit1_dispread_2068.ti3"
        ),
        "-o",
        "-",
    ]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    assert!(String::from_utf8_lossy(&r.stdout).contains("format"));
    assert!(!Path::new("-").exists());
}

/// `plot -o -`: the SVG on stdout (the same bytes as the file), `--format png` a PNG; a name
/// without an image extension needs `--format`, and one that contradicts it is refused.
#[test]
fn plot_dash_writes_the_figure_to_stdout() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("f.svg");
    assert!(plot(s(&file)).status.success());
    let r = plot("-");
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    assert_eq!(r.stdout, std::fs::read(&file).unwrap());
    assert!(String::from_utf8_lossy(&r.stderr).contains("wrote stdout"));
    let r = specpoly(&["plot", "colorchecker#blue", "-o", "-", "--format", "png"]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let png = png::Decoder::new(&r.stdout[..]).read_info().unwrap();
    assert_eq!((png.info().width, png.info().height), (900, 560));
    let named = dir.path().join("figure");
    let r = specpoly(&["plot", "colorchecker#blue", "-o", s(&named)]);
    assert_eq!(r.status.code(), Some(2));
    let r = specpoly(&[
        "plot",
        "colorchecker#blue",
        "-o",
        s(&named),
        "--format",
        "png",
    ]);
    assert!(r.status.success());
    assert!(png::Decoder::new(std::fs::File::open(&named).unwrap())
        .read_info()
        .is_ok());
    let r = specpoly(&[
        "plot",
        "colorchecker#blue",
        "-o",
        s(&file),
        "--format",
        "png",
    ]);
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(2), "{err}");
    assert!(err.contains("--format says png"), "{err}");
    assert!(!Path::new("-").exists());
}

#[test]
fn render_dash_writes_the_png_to_stdout_and_a_closed_stdout_is_an_error() {
    let r = specpoly(&["render", "example1", "--size", "8x6", "-o", "-"]);
    let err = String::from_utf8_lossy(&r.stderr);
    assert!(r.status.success(), "{err}");
    // stdout is the PNG alone (read by the `png` crate); the summary went to stderr
    let png = png::Decoder::new(&r.stdout[..]).read_info().unwrap();
    assert_eq!((png.info().width, png.info().height), (8, 6));
    assert!(err.contains("8x6") && err.contains("→ stdout"), "{err}");
    assert!(!Path::new("-").exists());
    // stdout also taken by --json: refused before rendering
    let r = specpoly(&["render", "example1", "--size", "8x6", "-o", "-", "--json"]);
    assert_eq!(r.status.code(), Some(2));
    assert!(r.stdout.is_empty());
    // `>&-`: stdout closed, the image would be lost; one line, exit 1, nothing rendered
    for args in [
        &["render", "example1", "--size", "8x6", "-o", "-"][..],
        &["calibrate", "patches", "-o", "-"][..],
    ] {
        let r = Command::new("sh")
            .arg("-c")
            .arg(r#"exec "$0" "$@" >&-"#)
            .arg(env!("CARGO_BIN_EXE_specpoly"))
            .args(args)
            .stdin(Stdio::null())
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(1), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(
            err.contains("stdout: it is closed (`>&-`), so the output would be lost"),
            "{err}"
        );
    }
    // a stdout that is /dev/null opened for writing (`>/dev/null`) is a stdout like any other
    let r = Command::new("sh")
        .arg("-c")
        .arg(r#"exec "$0" "$@" >/dev/null"#)
        .arg(env!("CARGO_BIN_EXE_specpoly"))
        .args(["render", "example1", "--size", "8x6", "-o", "-"])
        .output()
        .unwrap();
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
}

#[test]
fn symlinks_are_written_through() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("real.svg");
    std::fs::write(&target, "old").unwrap();
    let link = dir.path().join("link.svg");
    symlink("real.svg", &link).unwrap();
    let r = plot(s(&link));
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(std::fs::read_to_string(&target).unwrap().contains("<svg"));
    // a dangling link: the file is created where it points
    let dangling = dir.path().join("dangling.svg");
    symlink("new.svg", &dangling).unwrap();
    assert!(plot(s(&dangling)).status.success());
    assert!(std::fs::symlink_metadata(&dangling)
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(dir.path().join("new.svg").is_file());
}

#[test]
fn fifos_and_devices_are_written_directly() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("pipe.svg");
    assert!(Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap()
        .success());
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read(fifo).unwrap())
    };
    let r = plot(s(&fifo));
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let bytes = reader.join().unwrap();
    assert!(String::from_utf8_lossy(&bytes).contains("<svg"));
    assert!(std::fs::symlink_metadata(&fifo)
        .unwrap()
        .file_type()
        .is_fifo());
    let r = specpoly(&["calibrate", "fit", "--ti3", TI3, "-o", "/dev/null"]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    assert!(std::fs::metadata("/dev/null")
        .unwrap()
        .file_type()
        .is_char_device());
}

#[test]
fn temporary_files_are_exclusive_and_stale_ones_cleaned() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("p.svg");
    // a link planted at the old predictable temporary name is not followed
    let victim = dir.path().join("victim.txt");
    std::fs::write(&victim, "keep me").unwrap();
    for pid in 0..4 {
        let _ = symlink(&victim, dir.path().join(format!(".p.svg.tmp{pid}")));
    }
    // a temporary file a killed run left an hour ago
    let stale = dir.path().join(".p.svg.AbC123.specpoly-tmp");
    std::fs::write(&stale, "half").unwrap();
    let hour_ago = std::time::SystemTime::now() - std::time::Duration::from_secs(3600);
    std::fs::File::options()
        .write(true)
        .open(&stale)
        .unwrap()
        .set_modified(hour_ago)
        .unwrap();
    let r = plot(s(&out));
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "keep me");
    assert!(!stale.exists(), "stale temporary file left");
    let ours: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().ends_with(".specpoly-tmp"))
        .collect();
    assert!(ours.is_empty());
}
