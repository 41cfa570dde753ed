//! Helpers for the tests on the shipped real displays (data/ti3): the default fit of one,
//! `palette`'s CIEDE2000 (an implementation independent of ours), and a profile made
//! tables-only.
#![allow(dead_code)]

use palette::color_difference::Ciede2000;
use palette::white_point::{WhitePoint, D65};
use palette::FromColor;
use specpoly_calibrate::fit::{fit, FitOptions};
use specpoly_display::calibration::Calibration;
use specpoly_formats::cgats::read_ti3;
use specpoly_formats::measurement::Measurement;
use std::path::Path;

/// Every shipped display's `.ti3` (data/ti3), by file name, sorted: a display added there is
/// tested by every test that walks this list.
pub fn shipped() -> Vec<String> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/ti3");
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.ends_with(".ti3"))
        .collect();
    names.sort();
    names
}

/// The shipped display whose file name starts with `prefix` (e.g. `"microsoft-surface"`).
pub fn shipped_named(prefix: &str) -> String {
    shipped()
        .into_iter()
        .find(|n| n.starts_with(prefix))
        .unwrap_or_else(|| panic!("no data/ti3/{prefix}*.ti3"))
}

/// The readings of a shipped `.ti3` (data/ti3), in the file's units.
pub fn readings(name: &str) -> Vec<Measurement> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data/ti3")
        .join(name);
    let text = std::fs::read_to_string(path).unwrap();
    read_ti3(&text, name).unwrap().measurements
}

/// The default model fitted on every reading of a shipped `.ti3`.
pub fn fitted(name: &str) -> Calibration {
    fit(&readings(name), &FitOptions::default()).unwrap()
}

/// ΔE00 by `palette`: XYZ relative to `white` is mapped onto palette's D65 by the same
/// per-component ratio CIELAB uses (`X/X_n`), converted to CIELAB and compared by CIEDE2000.
pub fn de00(a: [f64; 3], b: [f64; 3], white: [f64; 3]) -> f64 {
    let wp = <D65 as WhitePoint<f64>>::get_xyz();
    let wp = [wp.x, wp.y, wp.z];
    let lab = |v: [f64; 3]| {
        let s = [0, 1, 2].map(|i| v[i] / white[i] * wp[i]);
        palette::Lab::<D65, f64>::from_color(palette::Xyz::<D65, f64>::new(s[0], s[1], s[2]))
    };
    lab(a).difference(lab(b))
}

/// An ICC profile's bytes with its colorant and curve tags renamed away (unknown and distinct
/// signatures: Little CMS refuses duplicates), so that only its tables describe the display.
pub fn tables_only(b: &mut [u8]) {
    let n = u32::from_be_bytes([b[128], b[129], b[130], b[131]]) as usize;
    for i in 0..n {
        let at = 132 + 12 * i;
        if [b"rXYZ", b"gXYZ", b"bXYZ", b"rTRC", b"gTRC", b"bTRC"]
            .iter()
            .any(|sig| &b[at..at + 4] == *sig)
        {
            b[at] = b'0' + i as u8;
        }
    }
}
