//! `specpoly calibrate export`: the emitted C is compiled with the system C compiler (`cc`) and
//! run; its panel levels and dithered RGB565 codes must equal the Rust transform's on a sample
//! of pixels. The Rust form is compiled by the firmware's build (firmware/build.rs, QEMU tests).

use crate::common::cli;

use cli::s;
use specpoly_core::pixel::{Dither, Options, PanelTransform, Source, White};
use specpoly_core::GamutMap;
use specpoly_display::calibration;
use std::path::{Path, PathBuf};
use std::process::Command;

/// A calibration fitted to the Acer's readings, in `dir`.
fn acer_calibration(dir: &Path) -> PathBuf {
    let toml = dir.join("acer.toml");
    let r = cli::run(&["calibrate", "fit", "--ti3", cli::ACER, "-o", s(&toml)]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    toml
}

/// `specpoly calibrate export --calibration CAL ARGS… -o OUT`.
fn export(cal: &Path, args: &[&str], out: &Path) -> cli::Run {
    let mut all = vec!["calibrate", "export", "--calibration", s(cal)];
    all.extend_from_slice(args);
    all.extend(["-o", s(out)]);
    cli::run(&all)
}

const MAIN_C: &str = r#"
#include <stdio.h>
#include "acer.h"
int main(void) {
    for (int r = 0; r < 256; r += 3)
        for (int g = 0; g < 256; g += 5)
            for (int b = 0; b < 256; b += 7) {
                uint16_t l[3];
                acer_levels((uint8_t)r, (uint8_t)g, (uint8_t)b, l);
                unsigned x = (unsigned)(r + g), y = (unsigned)b;
                printf("%d %d %d %u %u %u %u\n", r, g, b, l[0], l[1], l[2],
                       acer_rgb565((uint8_t)r, (uint8_t)g, (uint8_t)b, x, y));
            }
    return 0;
}
"#;

#[test]
fn c_tables_compute_what_the_rust_transform_computes() {
    let dir = tempfile::tempdir().unwrap();
    let toml = acer_calibration(dir.path());
    let header = dir.path().join("acer.h");
    let out = export(
        &toml,
        &["--source", "p3", "--format", "c-table", "--name", "acer"],
        &header,
    );
    assert_eq!(out.code, 0, "{}", out.stderr);
    assert!(out.stderr.starts_with("wrote "));

    std::fs::write(dir.path().join("main.c"), MAIN_C).unwrap();
    let exe = dir.path().join("levels");
    let cc = Command::new("cc")
        .args(["-std=c99", "-O2", "-Wall", "-Wextra", "-Werror", "-o"])
        .arg(&exe)
        .arg(dir.path().join("main.c"))
        .output()
        .expect("the C compiler `cc` runs (apt-get install gcc)");
    assert!(
        cc.status.success(),
        "cc: {}",
        String::from_utf8_lossy(&cc.stderr)
    );
    let run = Command::new(&exe).output().unwrap();
    assert!(run.status.success());

    let cal = calibration::load(&toml).unwrap();
    let opts = Options {
        source: Source::DisplayP3,
        white: White::Adapt,
        map: GamutMap::Clip,
        bits: Options::RGB565,
    };
    let p = PanelTransform::new(&cal.display(), opts).unwrap();
    let mut n = 0;
    for line in String::from_utf8(run.stdout).unwrap().lines() {
        let v: Vec<u32> = line.split(' ').map(|t| t.parse().unwrap()).collect();
        let rgb = [v[0] as u8, v[1] as u8, v[2] as u8];
        let levels = p.levels(rgb);
        assert_eq!([v[3], v[4], v[5]], levels.map(u32::from), "{rgb:?}");
        let t = Dither::Ordered.threshold(v[0] + v[1], v[2]);
        let c = p.apply(rgb, t);
        let rgb565 = (c[0] as u32) << 11 | (c[1] as u32) << 5 | c[2] as u32;
        assert_eq!(v[6], rgb565, "{rgb:?}");
        n += 1;
    }
    assert_eq!(n, 86 * 52 * 37);
}

#[test]
fn rust_source_and_bad_arguments() {
    let dir = tempfile::tempdir().unwrap();
    let toml = acer_calibration(dir.path());
    let rs = dir.path().join("panel.rs");
    let out = export(&toml, &["--format", "rust", "--bits", "rgb888"], &rs);
    assert_eq!(out.code, 0, "{}", out.stderr);
    let text = std::fs::read_to_string(&rs).unwrap();
    assert!(text.contains("pub static PANEL: specpoly_core::pixel::PixelTransform ="));
    assert!(text.contains("bits: [8, 8, 8]"));

    // a name that is no identifier: usage error, nothing written
    let bad = dir.path().join("bad.h");
    let out = export(&toml, &["--format", "c-table", "--name", "9lives"], &bad);
    assert_eq!(out.code, 2);
    assert!(!bad.exists());
    // a missing calibration: a usage error (as in every command), nothing written
    let out = export(
        &dir.path().join("none.toml"),
        &["--format", "c-table"],
        &bad,
    );
    assert_eq!(out.code, 2);
    assert_eq!(out.stderr.trim().lines().count(), 1);
    assert!(!bad.exists());
}

/// `--format c-blob`: the bytes are the core's blob of the calibration's matrix model (what
/// the C library's `sp_calibration_load` reads), and the model read back predicts what the
/// calibration predicts; a model with a channel-interaction lattice is refused, no file made.
#[test]
fn c_blob_holds_the_calibrations_display_model() {
    let dir = tempfile::tempdir().unwrap();
    let toml = dir.path().join("acer.toml");
    let r = cli::run(&[
        "calibrate",
        "fit",
        "--ti3",
        cli::ACER,
        "--interaction",
        "none",
        "-o",
        s(&toml),
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let path = dir.path().join("acer.bin");
    let out = export(&toml, &["--format", "c-blob"], &path);
    assert_eq!(out.code, 0, "{}", out.stderr);
    assert!(
        out.stderr.contains("calibration blob version 1"),
        "{}",
        out.stderr
    );
    let bytes = std::fs::read(&path).unwrap();
    let display = calibration::load(&toml).unwrap().display();
    let mut want = [0u8; specpoly_core::blob::MAX_BYTES];
    let n = specpoly_core::blob::write(&display, &mut want).unwrap();
    assert_eq!(bytes, want[..n]);
    let back = specpoly_core::blob::read(&bytes).unwrap();
    for rgb in [[1.0, 1.0, 1.0], [0.5, 0.25, 0.75], [0.02, 0.9, 0.1]] {
        let (a, b) = (display.device_to_xyz(rgb), back.device_to_xyz(rgb));
        for (x, y) in a.to_array().iter().zip(b.to_array()) {
            assert!(
                (x - y).abs() <= 1e-4 * x.abs().max(1.0),
                "{rgb:?}: {a:?} {b:?}"
            );
        }
    }

    // a 3³ lattice, asked for (the default `auto` keeps one too, after a costlier
    // cross-validation)
    let lattice = dir.path().join("lattice.toml");
    let r = cli::run(&[
        "calibrate",
        "fit",
        "--ti3",
        cli::ACER,
        "--interaction",
        "3",
        "-o",
        s(&lattice),
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let refused = dir.path().join("refused.bin");
    let out = export(&lattice, &["--format", "c-blob"], &refused);
    assert_eq!(out.code, 1, "{}", out.stderr);
    assert!(out.stderr.contains("channel-interaction"), "{}", out.stderr);
    assert!(!refused.exists());
}
