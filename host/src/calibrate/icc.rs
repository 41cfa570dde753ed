//! ICC v4 matrix/TRC display profile from a calibration (ICC.1:2022, profile version 4.4).
//!
//! Tags: `desc` and `cprt` (`mluc`), `wtpt` (D50, as v4 requires of display profiles), `chad`
//! (Bradford from the display's white to D50, `sf32`), `rXYZ gXYZ bXYZ` (the primaries
//! adapted to D50 and scaled so the white has `Y = 1`), `rTRC gTRC bTRC` (`para` for a pure
//! gamma, otherwise a 1024-entry `curv`) and, for an absolute calibration, `lumi` (the
//! white's luminance in cd/m²).
//!
//! A matrix/TRC profile has no black offset, so the black is folded into the curves: with
//! `k = M⁻¹·K` (the black as linear drive), `XYZ = M·(t + k) = M'·t'` with
//! `M' = M·diag(1 + k)` and `t'_i = (t_i + k_i) / (1 + k_i)`, exact when every `k_i ≥ 0`
//! (black inside the primaries' gamut, as on the shipped LCD); a negative `k_i` is taken as 0
//! and the profile then misses the black's tint in that channel.
//!
//! PCS values: `XYZ_PCS = chad · XYZ / Y_white`, with `Y_white` the model's white (device
//! 1, 1, 1), so relative colorimetric transforms map device white to D50.

use super::file::{Calibration, TransferKind};
use crate::error::{CliError, Result};

/// The ICC PCS illuminant D50 as the ICC writes it (s15Fixed16-exact values).
pub const D50: [f64; 3] = [0.9642, 1.0, 0.8249];

/// The Bradford matrix (Lam 1985), as in `specpoly_core::colorimetry::BRADFORD`.
const BRADFORD: [[f64; 3]; 3] = [
    [0.8951, 0.2664, -0.1614],
    [-0.7502, 1.7135, 0.0367],
    [0.0389, -0.0685, 1.0296],
];

fn mat_vec(m: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|r| m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2])
}

fn mat_mul(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

/// The inverse of a 3×3 matrix (adjugate), `None` if singular.
pub fn mat_inv(m: &[[f64; 3]; 3]) -> Option<[[f64; 3]; 3]> {
    let c =
        |r0: usize, c0: usize, r1: usize, c1: usize| m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0];
    let cof = [
        [c(1, 1, 2, 2), -c(1, 0, 2, 2), c(1, 0, 2, 1)],
        [-c(0, 1, 2, 2), c(0, 0, 2, 2), -c(0, 0, 2, 1)],
        [c(0, 1, 1, 2), -c(0, 0, 1, 2), c(0, 0, 1, 1)],
    ];
    let det = m[0][0] * cof[0][0] + m[0][1] * cof[0][1] + m[0][2] * cof[0][2];
    if !det.is_finite() || det.abs() < 1e-300 {
        return None;
    }
    Some([0, 1, 2].map(|i| [0, 1, 2].map(|j| cof[j][i] / det)))
}

/// Bradford adaptation from white `from` to white `to` (f64).
pub fn bradford(from: [f64; 3], to: [f64; 3]) -> [[f64; 3]; 3] {
    let s = mat_vec(&BRADFORD, from);
    let d = mat_vec(&BRADFORD, to);
    let diag = [
        [d[0] / s[0], 0.0, 0.0],
        [0.0, d[1] / s[1], 0.0],
        [0.0, 0.0, d[2] / s[2]],
    ];
    // the Bradford matrix is invertible (det ≈ 1.9)
    let inv = mat_inv(&BRADFORD).unwrap_or([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
    mat_mul(&mat_mul(&inv, &diag), &BRADFORD)
}

/// The model's white (device 1, 1, 1) in the calibration's units.
pub fn model_white(cal: &Calibration) -> [f64; 3] {
    cal.predict([1.0; 3])
}

/// The calibration's prediction for device values, as ICC PCS XYZ (D50, white `Y = 1`):
/// `chad · XYZ / Y_white`. What a colour-managed application gets from the profile.
pub fn predict_pcs(cal: &Calibration, rgb: [f64; 3]) -> [f64; 3] {
    let w = model_white(cal);
    let chad = bradford(w.map(|v| v / w[1]), D50);
    mat_vec(&chad, cal.predict(rgb).map(|v| v / w[1]))
}

fn s15(v: f64) -> [u8; 4] {
    ((v * 65536.0).round() as i32).to_be_bytes()
}

fn xyz_number(out: &mut Vec<u8>, v: [f64; 3]) {
    for c in v {
        out.extend_from_slice(&s15(c));
    }
}

fn xyz_tag(v: [f64; 3]) -> Vec<u8> {
    let mut t = b"XYZ \0\0\0\0".to_vec();
    xyz_number(&mut t, v);
    t
}

fn mluc(text: &str) -> Vec<u8> {
    let s: Vec<u8> = text.encode_utf16().flat_map(|u| u.to_be_bytes()).collect();
    let mut t = b"mluc\0\0\0\0".to_vec();
    t.extend_from_slice(&1u32.to_be_bytes());
    t.extend_from_slice(&12u32.to_be_bytes());
    t.extend_from_slice(b"enUS");
    t.extend_from_slice(&(s.len() as u32).to_be_bytes());
    t.extend_from_slice(&28u32.to_be_bytes());
    t.extend_from_slice(&s);
    t
}

fn sf32(m: &[[f64; 3]; 3]) -> Vec<u8> {
    let mut t = b"sf32\0\0\0\0".to_vec();
    for row in m {
        for v in row {
            t.extend_from_slice(&s15(*v));
        }
    }
    t
}

/// Entries of a sampled `curv` TRC.
pub const CURVE_POINTS: usize = 1024;

fn trc(cal: &Calibration, channel: usize, k: f64) -> Vec<u8> {
    let d = cal.data();
    if d.transfer.kind == TransferKind::Gamma && k == 0.0 {
        // parametricCurveType, function 0: Y = X^g
        let mut t = b"para\0\0\0\0".to_vec();
        t.extend_from_slice(&0u16.to_be_bytes());
        t.extend_from_slice(&0u16.to_be_bytes());
        t.extend_from_slice(&s15(d.transfer.gamma[channel]));
        return t;
    }
    let mut t = b"curv\0\0\0\0".to_vec();
    t.extend_from_slice(&(CURVE_POINTS as u32).to_be_bytes());
    for i in 0..CURVE_POINTS {
        let v = i as f64 / (CURVE_POINTS - 1) as f64;
        let mut rgb = [0.0; 3];
        rgb[channel] = v;
        let l = cal.linearise(rgb)[channel];
        let y = ((l + k) / (1.0 + k)).clamp(0.0, 1.0);
        t.extend_from_slice(&((y * 65535.0).round() as u16).to_be_bytes());
    }
    t
}

/// Builds the profile's bytes. `description` goes into `desc`.
pub fn profile(cal: &Calibration, description: &str) -> Result<Vec<u8>> {
    let m = cal.matrix(); // rows X, Y, Z; columns R, G, B
    let black = cal.data().black;
    let inv =
        mat_inv(&m).ok_or_else(|| CliError::data("the calibration's primaries are singular"))?;
    let k = mat_vec(&inv, black).map(|v| v.max(0.0));
    // M' = M diag(1 + k)
    let m1 = [0, 1, 2].map(|r| [0, 1, 2].map(|c| m[r][c] * (1.0 + k[c])));
    let w = [0, 1, 2].map(|r| m1[r][0] + m1[r][1] + m1[r][2]);
    if w[1].is_nan() || w[1] <= 0.0 {
        return Err(CliError::data("the calibration's white has no luminance"));
    }
    let chad = bradford(w.map(|v| v / w[1]), D50);
    let col = |c: usize| mat_vec(&chad, [m1[0][c] / w[1], m1[1][c] / w[1], m1[2][c] / w[1]]);

    let mut tags: Vec<(&[u8; 4], Vec<u8>)> = vec![
        (b"desc", mluc(description)),
        (
            b"cprt",
            mluc("No copyright; written by specpoly from a measured calibration"),
        ),
        (b"wtpt", xyz_tag(D50)),
        (b"chad", sf32(&chad)),
        (b"rXYZ", xyz_tag(col(0))),
        (b"gXYZ", xyz_tag(col(1))),
        (b"bXYZ", xyz_tag(col(2))),
        (b"rTRC", trc(cal, 0, k[0])),
        (b"gTRC", trc(cal, 1, k[1])),
        (b"bTRC", trc(cal, 2, k[2])),
    ];
    if cal.absolute() {
        tags.push((b"lumi", xyz_tag([0.0, cal.data().white[1], 0.0])));
    }

    let table_len = 4 + 12 * tags.len();
    let mut offset = 128 + table_len;
    let mut table = Vec::with_capacity(table_len);
    let mut data = Vec::new();
    table.extend_from_slice(&(tags.len() as u32).to_be_bytes());
    for (sig, bytes) in &tags {
        table.extend_from_slice(*sig);
        table.extend_from_slice(&(offset as u32).to_be_bytes());
        table.extend_from_slice(&(bytes.len() as u32).to_be_bytes());
        data.extend_from_slice(bytes);
        while data.len() % 4 != 0 {
            data.push(0);
        }
        offset = 128 + table_len + data.len();
    }
    let size = 128 + table.len() + data.len();
    let mut h = Vec::with_capacity(size);
    h.extend_from_slice(&(size as u32).to_be_bytes());
    h.extend_from_slice(&[0; 4]); // preferred CMM
    h.extend_from_slice(&0x0440_0000u32.to_be_bytes()); // v4.4
    h.extend_from_slice(b"mntr");
    h.extend_from_slice(b"RGB ");
    h.extend_from_slice(b"XYZ ");
    for v in super::file::utc_parts() {
        h.extend_from_slice(&(v as u16).to_be_bytes());
    }
    h.extend_from_slice(b"acsp");
    h.extend_from_slice(&[0; 4]); // platform
    h.extend_from_slice(&[0; 4]); // flags
    h.extend_from_slice(&[0; 4]); // manufacturer
    h.extend_from_slice(&[0; 4]); // model
    h.extend_from_slice(&[0; 8]); // attributes
    h.extend_from_slice(&0u32.to_be_bytes()); // perceptual
    xyz_number(&mut h, D50);
    h.extend_from_slice(b"spcp"); // creator
    h.extend_from_slice(&[0; 16]); // profile ID (optional: zero)
    h.extend_from_slice(&[0; 28]);
    debug_assert_eq!(h.len(), 128);
    h.extend_from_slice(&table);
    h.extend_from_slice(&data);
    Ok(h)
}
