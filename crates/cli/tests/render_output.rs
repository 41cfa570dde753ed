//! `specpoly render -o` in every format, read back by independent decoders (`png`, `exr`):
//! 8-bit PNG with an `sRGB` chunk, 16-bit PNG, linear EXR (display RGB and XYZ, their
//! `chromaticities` read by `exrheader` and `oiiotool`), the display's
//! ICC profile in `iCCP` (byte-identical to `specpoly calibrate icc`), and an unknown extension
//! as a usage error that leaves no file.

use crate::common::cli;

use cli::{output as specpoly, ACER};
use std::path::{Path, PathBuf};
use std::process::Output;

fn ok(args: &[&str]) -> Output {
    let o = specpoly(args);
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// `(info, samples)` of a PNG.
fn png(path: &Path) -> (png::Info<'static>, Vec<u8>) {
    let d = png::Decoder::new(std::fs::File::open(path).unwrap());
    let mut r = d.read_info().unwrap();
    let mut buf = vec![0; r.output_buffer_size()];
    let f = r.next_frame(&mut buf).unwrap();
    buf.truncate(f.buffer_size());
    (r.info().clone(), buf)
}

/// The channels of an EXR by name.
fn exr(path: &Path) -> Vec<(String, Vec<f32>)> {
    use exr::prelude::*;
    let img = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_file(path)
        .unwrap();
    img.layer_data
        .channel_data
        .list
        .iter()
        .map(|c| {
            let v = match &c.sample_data {
                FlatSamples::F32(v) => v.clone(),
                other => panic!("not f32: {other:?}"),
            };
            (c.name.to_string(), v)
        })
        .collect()
}

/// The sRGB transfer curve (IEC 61966-2-1).
fn srgb_encode(l: f32) -> f32 {
    if l <= 0.003_130_8 {
        12.92 * l
    } else {
        1.055 * l.powf(1.0 / 2.4) - 0.055
    }
}

fn render(dir: &Path, name: &str, extra: &[&str]) -> PathBuf {
    let out = dir.join(name);
    let mut args = vec!["render", "example1", "--size", "12x8", "-o", s(&out)];
    args.extend_from_slice(extra);
    ok(&args);
    out
}

#[test]
fn png_8_and_16_bit_agree_and_carry_srgb() {
    let dir = tempfile::tempdir().unwrap();
    let (i8, p8) = png(&render(dir.path(), "a.png", &[]));
    assert_eq!(i8.bit_depth, png::BitDepth::Eight);
    assert!(i8.srgb.is_some(), "no sRGB chunk");
    let (i16, p16) = png(&render(dir.path(), "a16.png", &["--bits", "16"]));
    assert_eq!(i16.bit_depth, png::BitDepth::Sixteen);
    assert!(i16.srgb.is_some());
    assert_eq!(p16.len(), 2 * p8.len());
    // the same display values quantised to 8 and 16 bits
    for (k, v8) in p8.iter().enumerate() {
        let v16 = u16::from_be_bytes([p16[2 * k], p16[2 * k + 1]]) as f32 / 65535.0;
        assert!(
            (v16 * 255.0 - *v8 as f32).abs() <= 0.5 + 1e-3,
            "{k}: {v8} vs {v16}"
        );
    }
}

#[test]
fn exr_holds_the_linear_values_of_the_png() {
    let dir = tempfile::tempdir().unwrap();
    let (_, p8) = png(&render(dir.path(), "a.png", &[]));
    let rgb = exr(&render(dir.path(), "a.exr", &[]));
    let names: Vec<&str> = rgb.iter().map(|c| c.0.as_str()).collect();
    assert_eq!(names, ["B", "G", "R"]);
    let chan = |n: &str| &rgb.iter().find(|c| c.0 == n).unwrap().1;
    let (r, g, b) = (chan("R"), chan("G"), chan("B"));
    assert_eq!(r.len(), 12 * 8);
    let mut compared = 0;
    for k in 0..r.len() {
        let lin = [r[k], g[k], b[k]];
        if lin.iter().all(|v| (0.0..=1.0).contains(v)) {
            for c in 0..3 {
                let e = (srgb_encode(lin[c]) * 255.0).round();
                assert!((e - p8[3 * k + c] as f32).abs() <= 1.0, "{k}/{c}");
            }
            compared += 1;
        }
    }
    assert!(compared > 40, "{compared}");

    // XYZ: the sRGB matrix (IEC 61966-2-1) takes the linear RGB to it, up to the white
    // balance (the scene's D65 against sRGB's rounded D65 chromaticity)
    // (OpenEXR's XYZ convention: X, Y, Z in the R, G, B channels)
    let xyz = exr(&render(dir.path(), "x.exr", &["--exr-space", "xyz"]));
    let chan = |n: &str| &xyz.iter().find(|c| c.0 == n).unwrap().1;
    let (x, y, z) = (chan("R"), chan("G"), chan("B"));
    for k in 0..r.len() {
        let ys = 0.2126 * r[k] + 0.7152 * g[k] + 0.0722 * b[k];
        let xs = 0.4124 * r[k] + 0.3576 * g[k] + 0.1805 * b[k];
        let zs = 0.0193 * r[k] + 0.1192 * g[k] + 0.9505 * b[k];
        let tol = 2e-3 * y[k].abs().max(0.01);
        assert!((ys - y[k]).abs() < tol, "{k}: Y {ys} vs {}", y[k]);
        assert!((xs - x[k]).abs() < 2.0 * tol, "{k}: X {xs} vs {}", x[k]);
        assert!((zs - z[k]).abs() < 2.0 * tol, "{k}: Z {zs} vs {}", z[k]);
    }
}

#[test]
fn a_calibrated_display_puts_its_icc_profile_in_the_png() {
    let dir = tempfile::tempdir().unwrap();
    let cal = dir.path().join("acer.toml");
    ok(&["calibrate", "fit", "--ti3", ACER, "-o", s(&cal)]);
    let icc = dir.path().join("acer.icc");
    ok(&["calibrate", "icc", s(&cal), "-o", s(&icc)]);
    let out = render(dir.path(), "c.png", &["--display", s(&cal)]);
    let (info, _) = png(&out);
    assert!(info.srgb.is_none());
    let embedded = info.icc_profile.expect("an iCCP chunk").into_owned();
    assert_eq!(embedded, std::fs::read(&icc).unwrap());
}

#[test]
fn unknown_extensions_are_usage_errors() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["a.jpg", "noext"] {
        let out = dir.path().join(name);
        let o = specpoly(&["render", "example1", "--size", "4x4", "-o", s(&out)]);
        assert_eq!(o.status.code(), Some(2));
        let e = String::from_utf8_lossy(&o.stderr);
        assert_eq!(e.trim_end().lines().count(), 1, "{e}");
        assert!(e.contains(".png or .exr"), "{e}");
        assert!(!out.exists());
    }
    let o = specpoly(&[
        "render",
        "example1",
        "--bits",
        "12",
        "-o",
        s(&dir.path().join("a.png")),
    ]);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn json_statistics() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("c.png");
    let o = ok(&[
        "render",
        "cornell",
        "--size",
        "8x8",
        "--spp",
        "2",
        "--json",
        "-o",
        s(&out),
    ]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["integrator"], "path");
    assert_eq!(v["paths_per_pixel"], 2);
    assert!(v["seconds"].as_f64().unwrap() >= 0.0);
    assert!(v["rays"].as_u64().unwrap() >= 8 * 8 * 2);
}

/// `chromaticities` of an EXR as `exrheader` (OpenEXR's own tool) prints them: red, green,
/// blue, white.
fn exrheader_chromaticities(path: &Path) -> [[f64; 2]; 4] {
    let o = std::process::Command::new("exrheader")
        .arg(path)
        .output()
        .expect("exrheader (Debian: openexr; ./test.sh installs it)");
    let text = String::from_utf8_lossy(&o.stdout);
    let at = text
        .find("chromaticities (type chromaticities)")
        .expect(&text);
    let mut xy = [[0.0; 2]; 4];
    for (k, name) in ["red", "green", "blue", "white"].iter().enumerate() {
        let line = text[at..]
            .lines()
            .find(|l| l.trim_start().starts_with(name))
            .unwrap();
        let inner = &line[line.find('(').unwrap() + 1..line.find(')').unwrap()];
        let v: Vec<f64> = inner
            .split_whitespace()
            .map(|t| t.parse().unwrap())
            .collect();
        xy[k] = [v[0], v[1]];
    }
    xy
}

/// The RGB → XYZ matrix of a set of chromaticities with the white at `Y = 1` (SMPTE RP 177,
/// what OpenEXR's `RGBtoXYZ` computes).
fn rgb_to_xyz(c: &[[f64; 2]; 4]) -> [[f64; 3]; 3] {
    let col = |[x, y]: [f64; 2]| [x / y, 1.0, (1.0 - x - y) / y];
    let p = [col(c[0]), col(c[1]), col(c[2])]; // columns
    let w = col(c[3]);
    let m = [
        [p[0][0], p[1][0], p[2][0]],
        [p[0][1], p[1][1], p[2][1]],
        [p[0][2], p[1][2], p[2][2]],
    ];
    // solve m · s = w (Cramer)
    let det = |a: [[f64; 3]; 3]| {
        a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
            - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
            + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
    };
    let d = det(m);
    let mut s = [0.0; 3];
    for (k, sk) in s.iter_mut().enumerate() {
        let mut a = m;
        for r in 0..3 {
            a[r][k] = w[r];
        }
        *sk = det(a) / d;
    }
    let mut out = [[0.0; 3]; 3];
    for r in 0..3 {
        for k in 0..3 {
            out[r][k] = m[r][k] * s[k];
        }
    }
    out
}

/// An EXR says what its values are: `exrheader` and OpenImageIO read the `chromaticities`
/// attribute (sRGB's published primaries and D65 for the default display, a display TOML's
/// own primaries, OpenEXR's XYZ convention for `--exr-space xyz`), and the XYZ a reader
/// derives from the display-RGB file through them is the XYZ file's.
#[test]
fn exr_carries_its_chromaticities() {
    let dir = tempfile::tempdir().unwrap();
    let rgb = render(dir.path(), "a.exr", &[]);
    let xyz = render(dir.path(), "x.exr", &["--exr-space", "xyz"]);
    let c = exrheader_chromaticities(&rgb);
    // IEC 61966-2-1: the sRGB primaries and D65
    let srgb = [[0.64, 0.33], [0.30, 0.60], [0.15, 0.06], [0.3127, 0.3290]];
    for k in 0..4 {
        for i in 0..2 {
            assert!((c[k][i] - srgb[k][i]).abs() < 1e-4, "{c:?}");
        }
    }
    let cx = exrheader_chromaticities(&xyz);
    assert_eq!(cx[..3], [[1.0, 0.0], [0.0, 1.0], [0.0, 0.0]]);
    assert!((cx[3][0] - 1.0 / 3.0).abs() < 1e-5 && (cx[3][1] - 1.0 / 3.0).abs() < 1e-5);
    // OpenImageIO reads the same attribute
    let o = std::process::Command::new("oiiotool")
        .args(["--info", "-v", s(&rgb)])
        .output()
        .expect("oiiotool (Debian: openimageio-tools; ./test.sh installs it)");
    let info = String::from_utf8_lossy(&o.stdout);
    assert!(
        info.contains("chromaticities: 0.64, 0.33, 0.3, 0.6, 0.15, 0.06, 0.3127, 0.329"),
        "{info}"
    );
    // a reader's XYZ from the RGB file's chromaticities = the XYZ file (white Y = 1 in both)
    let (a, b) = (exr(&rgb), exr(&xyz));
    let chan =
        |img: &Vec<(String, Vec<f32>)>, n: &str| img.iter().find(|c| c.0 == n).unwrap().1.clone();
    let (r, g, bl) = (chan(&a, "R"), chan(&a, "G"), chan(&a, "B"));
    let want = [chan(&b, "R"), chan(&b, "G"), chan(&b, "B")];
    let m = rgb_to_xyz(&c);
    for k in 0..r.len() {
        for row in 0..3 {
            let got = m[row][0] * r[k] as f64 + m[row][1] * g[k] as f64 + m[row][2] * bl[k] as f64;
            let w = want[row][k] as f64;
            assert!(
                (got - w).abs() < 1e-3 * w.abs().max(0.01),
                "{k}/{row}: {got} vs {w}"
            );
        }
    }
    // a display TOML: its own primaries
    let toml = dir.path().join("d.toml");
    std::fs::write(
        &toml,
        "primaries = [[0.68, 0.32], [0.265, 0.69], [0.15, 0.06]]\nluminance = [22.9, 69.2, 7.9]\ngamma = 2.2\n",
    )
    .unwrap();
    let p3 = render(dir.path(), "p.exr", &["--display", s(&toml)]);
    let c = exrheader_chromaticities(&p3);
    for (k, want) in [[0.68, 0.32], [0.265, 0.69], [0.15, 0.06]]
        .iter()
        .enumerate()
    {
        assert!(
            (c[k][0] - want[0]).abs() < 1e-4 && (c[k][1] - want[1]).abs() < 1e-4,
            "{c:?}"
        );
    }
}
