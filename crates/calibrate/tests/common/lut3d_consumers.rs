//! The 3D LUTs' real consumers: Debian's `ffmpeg` (`-vf lut3d`, tetrahedral) and OpenColorIO's
//! `ocioconvert --lut` (a `FileTransform`, its best interpolation: tetrahedral) apply a LUT
//! file to a 16-bit test image of source colours (binary PPM, `P6` with maxval 65535, Netpbm's
//! layout: big-endian samples); what they write is read back as 16-bit RGB. `test.sh`
//! installs both (`apt-get install ffmpeg opencolorio-tools`); a missing one fails the test
//! with that line. The example `lut3d_figures` uses the same helpers.
#![allow(dead_code)]

use specpoly_core::display_model::FULL;
use specpoly_core::{DisplayModel, Xyz};
use specpoly_display::lut3d::Target;
use std::path::Path;
use std::process::Command;

/// The Halton sequence's `i`-th value in base `b` (off every regular grid).
pub fn halton(mut i: usize, b: usize) -> f64 {
    let (mut f, mut r) = (1.0, 0.0);
    while i > 0 {
        f /= b as f64;
        r += f * (i % b) as f64;
        i /= b;
    }
    r
}

/// Up to `count` source colours (Halton, bases 2, 3, 5; on 16-bit codes) whose colour the
/// display shows: inside the gamut of `target`'s matrix part and reached exactly by the model's
/// inverse. Each with the XYZ it asks for.
pub fn in_gamut_colours(
    model: &DisplayModel<FULL>,
    target: &Target,
    count: usize,
) -> Vec<([f64; 3], [f64; 3])> {
    let mut out = Vec::with_capacity(count);
    let mut i = 1;
    while out.len() < count && i < 100 * count {
        let c = [halton(i, 2), halton(i, 3), halton(i, 5)].map(|v| (v * 65535.0).round() / 65535.0);
        i += 1;
        let x = target.xyz(c);
        if !target.in_gamut(x) {
            continue;
        }
        if model.inverse(Xyz::from_array(x.map(|v| v as f32))).exact {
            out.push((c, x));
        }
    }
    out
}

/// Writes `colours` (0–1) as a 16-bit binary PPM, `width` pixels a row (the last row padded
/// with black).
pub fn write_ppm16(path: &Path, colours: &[[f64; 3]], width: usize) {
    let height = colours.len().div_ceil(width);
    let mut bytes = format!("P6\n{width} {height}\n65535\n").into_bytes();
    for i in 0..width * height {
        let c = colours.get(i).copied().unwrap_or([0.0; 3]);
        for v in c {
            bytes.extend_from_slice(&((v.clamp(0.0, 1.0) * 65535.0).round() as u16).to_be_bytes());
        }
    }
    std::fs::write(path, bytes).unwrap();
}

/// Runs a tool; a missing tool fails with the package that has it.
fn run(cmd: &mut Command, package: &str) -> Vec<u8> {
    let name = cmd.get_program().to_string_lossy().to_string();
    let out = cmd.output().unwrap_or_else(|e| {
        panic!(
            "`{name}` cannot run ({e}): install Debian's `{package}` (test.sh does: apt-get install {package})"
        )
    });
    assert!(
        out.status.success(),
        "{name} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out.stdout
}

/// 16-bit little-endian RGB samples as 0–1 triples.
fn rgb48le(bytes: &[u8], n: usize) -> Vec<[f64; 3]> {
    assert!(bytes.len() >= n * 6, "{} bytes for {n} pixels", bytes.len());
    (0..n)
        .map(|i| {
            [0, 1, 2].map(|c| {
                let at = i * 6 + c * 2;
                f64::from(u16::from_le_bytes([bytes[at], bytes[at + 1]])) / 65535.0
            })
        })
        .collect()
}

/// `image` decoded by ffmpeg to 16-bit RGB, `n` pixels.
fn decode(image: &Path, n: usize) -> Vec<[f64; 3]> {
    let out = run(
        Command::new("ffmpeg")
            .args(["-v", "error", "-i"])
            .arg(image)
            .args(["-f", "rawvideo", "-pix_fmt", "rgb48le", "-"]),
        "ffmpeg",
    );
    rgb48le(&out, n)
}

/// ffmpeg's `lut3d` filter (tetrahedral) applied to the 16-bit `image`: the first `n` pixels.
pub fn ffmpeg_apply(lut: &Path, image: &Path, n: usize) -> Vec<[f64; 3]> {
    let out = run(
        Command::new("ffmpeg")
            .args(["-v", "error", "-i"])
            .arg(image)
            .arg("-vf")
            .arg(format!("lut3d=file={}:interp=tetrahedral", lut.display()))
            .args(["-f", "rawvideo", "-pix_fmt", "rgb48le", "-"]),
        "ffmpeg",
    );
    rgb48le(&out, n)
}

/// OpenColorIO's `ocioconvert --lut` applied to the 16-bit `image` (written as a 16-bit TIFF
/// through OpenImageIO, read back by ffmpeg): the first `n` pixels.
pub fn ocio_apply(lut: &Path, image: &Path, n: usize) -> Vec<[f64; 3]> {
    let tif = image.with_extension("ocio.tif");
    run(
        Command::new("ocioconvert")
            .arg("--lut")
            .arg(lut)
            .arg(image)
            .arg(&tif),
        "opencolorio-tools",
    );
    decode(&tif, n)
}

/// What the display shows for device values (the model's prediction).
pub fn shown(model: &DisplayModel<FULL>, device: [f64; 3]) -> [f64; 3] {
    model.device_to_xyz(device.map(|v| v as f32)).into()
}

/// Mean and maximum of a list.
pub fn mean_max(v: &[f64]) -> (f64, f64) {
    (
        v.iter().sum::<f64>() / v.len().max(1) as f64,
        v.iter().cloned().fold(0.0, f64::max),
    )
}
