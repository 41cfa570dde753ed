//! ICC display profiles from a calibration: version 2.4 (ICC.1:2001-04, what DisplayCAL writes
//! and every consumer reads, ArgyllCMS 2.3 included) or 4.4 (ICC.1:2022).
//!
//! Tags: `desc` and `cprt` (v2: `desc` and `text`; v4: `mluc`), `wtpt` (v4: D50, as v4
//! requires of display profiles; v2: the display's white, `Y = 1`), `chad` (Bradford from the
//! display's white to D50, `sf32`), `rXYZ gXYZ bXYZ` (the primaries adapted to D50 and scaled
//! so the white has `Y = 1`), `rTRC gTRC bTRC` (`para` for a pure gamma, otherwise a
//! 1024-entry `curv`), for an absolute calibration `lumi` (the white's luminance in cd/m²),
//! with a video LUT a `vcgt` (Apple's video-card gamma table, type 0: 3 channels × the LUT's
//! entries × 16 bits, as ArgyllCMS and DisplayCAL write it), and on request (a model with
//! channel interaction) `A2B0`/`B2A0` tables (`lut16Type`, in both versions; see [`lut16`]).
//! The header carries the profile ID: the MD5 of the whole profile with the flags, the
//! rendering intent and the ID fields zeroed (ICC.1:2022 §7.2.18); the `md5` crate computes
//! the digest.
//!
//! The profile describes the display *with its video LUT loaded* (the calibration's model
//! was measured through it); the `vcgt` tag is what a loader (`dispwin -L`, the desktop's
//! colour manager) puts in the graphics card.
//!
//! A matrix/TRC profile has no black offset, so the black is folded into the curves: with
//! `k = M⁻¹·K` (the black as linear drive), `XYZ = M·(t + k) = M'·t'` with
//! `M' = M·diag(1 + k)` and `t'_i = (t_i + k_i) / (1 + k_i)`, exact when every `k_i ≥ 0`
//! (black inside the primaries' gamut, as on the shipped LCD); a negative `k_i` is taken as 0
//! and the profile then misses the black's tint in that channel.
//!
//! PCS values: `XYZ_PCS = chad · XYZ / Y_white`, with `Y_white` the model's white (device
//! 1, 1, 1), so relative colorimetric transforms map device white to D50.

use crate::calibration::{Calibration, TransferKind};
use crate::error::{Error, Result};
use crate::video_lut::VideoLut;
use specpoly_core::colorimetry::ICC_D50;
use specpoly_core::{bradford, Mat3, Xyz};

/// The ICC PCS illuminant D50 as the ICC writes it (s15Fixed16-exact values):
/// [`specpoly_core::colorimetry::ICC_D50`] as an array.
pub const D50: [f64; 3] = [ICC_D50.x, ICC_D50.y, ICC_D50.z];

/// Bradford adaptation from the white `white` (any scale: taken at `Y = 1`) to the PCS's D50:
/// the profile's `chad`.
pub fn chad(white: [f64; 3]) -> Mat3<f64> {
    bradford(Xyz::from_array(white.map(|v| v / white[1])), ICC_D50)
}

/// The model's white (device 1, 1, 1) in the calibration's units.
pub fn model_white(cal: &Calibration) -> [f64; 3] {
    cal.predict([1.0; 3])
}

/// The calibration's prediction for device values, as ICC PCS XYZ (D50, white `Y = 1`):
/// `chad · XYZ / Y_white`. What a colour-managed application gets from the profile.
pub fn predict_pcs(cal: &Calibration, rgb: [f64; 3]) -> [f64; 3] {
    let w = model_white(cal);
    chad(w).apply(cal.predict(rgb).map(|v| v / w[1]))
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

/// The profile version written.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum IccVersion {
    /// ICC v2.4 (the default: every consumer reads it).
    #[default]
    V2,
    /// ICC v4.4.
    V4,
}

/// What [`build`] writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct IccOptions {
    /// The version.
    pub version: IccVersion,
    /// Also write `A2B0`/`B2A0` tables sampled from the model (for a model a matrix and three
    /// curves cannot express).
    pub tables: bool,
}

impl IccOptions {
    /// The defaults for `cal`: v2.4, tables when the model has channel interaction.
    pub fn for_calibration(cal: &Calibration) -> Self {
        IccOptions {
            version: IccVersion::V2,
            tables: cal.has_interaction(),
        }
    }
}

/// The profile description (`desc`) of the display calibrated in `cal`, loaded from
/// `cal_path`: the stem of the measurements file it was fitted from (a `.ti3` of DisplayCAL
/// and ArgyllCMS is named after the display), else the calibration file's stem. One rule for
/// `calibrate icc` and for the profile `render --display` embeds.
pub fn description(cal: &Calibration, cal_path: &std::path::Path) -> String {
    let stem = |p: &std::path::Path| {
        p.file_stem()
            .map(|s| s.to_string_lossy().to_string())
            .filter(|s| !s.is_empty())
    };
    let source = &cal.data().provenance.source;
    (!source.is_empty())
        .then(|| stem(std::path::Path::new(source)))
        .flatten()
        .or_else(|| stem(cal_path))
        .unwrap_or_else(|| "specpoly display".into())
}

/// Builds a v4 matrix/TRC profile's bytes. `description` goes into `desc`.
pub fn profile(cal: &Calibration, description: &str) -> Result<Vec<u8>> {
    build(
        cal,
        description,
        &IccOptions {
            version: IccVersion::V4,
            tables: false,
        },
    )
}

/// v2 `textDescriptionType`: ASCII, no Unicode or ScriptCode text.
fn text_description(text: &str) -> Vec<u8> {
    let ascii: Vec<u8> = text
        .chars()
        .map(|c| {
            if c.is_ascii() && !c.is_ascii_control() {
                c as u8
            } else {
                b'?'
            }
        })
        .collect();
    let mut t = b"desc\0\0\0\0".to_vec();
    t.extend_from_slice(&(ascii.len() as u32 + 1).to_be_bytes());
    t.extend_from_slice(&ascii);
    t.push(0);
    t.extend_from_slice(&[0; 8]); // Unicode language code and count
    t.extend_from_slice(&[0; 3]); // ScriptCode code and count
    t.extend_from_slice(&[0; 67]);
    t
}

/// v2 `textType`.
fn text(text: &str) -> Vec<u8> {
    let mut t = b"text\0\0\0\0".to_vec();
    t.extend(text.chars().map(|c| {
        if c.is_ascii() && !c.is_ascii_control() {
            c as u8
        } else {
            b'?'
        }
    }));
    t.push(0);
    t
}

/// The `vcgt` tag (type 0, a table): 3 channels, 16-bit entries.
pub fn vcgt(lut: &VideoLut) -> Vec<u8> {
    let n = lut.len().min(u16::MAX as usize);
    let mut t = b"vcgt\0\0\0\0".to_vec();
    t.extend_from_slice(&0u32.to_be_bytes());
    t.extend_from_slice(&3u16.to_be_bytes());
    t.extend_from_slice(&(n as u16).to_be_bytes());
    t.extend_from_slice(&2u16.to_be_bytes());
    for c in 0..3 {
        for k in 0..n {
            let v = lut.channel(c, k as f64 / (n - 1) as f64);
            t.extend_from_slice(&u16_unit(v).to_be_bytes());
        }
    }
    t
}

fn u16_unit(v: f64) -> u16 {
    (v.clamp(0.0, 1.0) * 65535.0).round() as u16
}

/// PCS XYZ in the 16-bit legacy encoding of `lut16Type` (`0x8000` = 1.0).
fn u16_xyz(v: f64) -> u16 {
    (v * 32768.0).round().clamp(0.0, 65535.0) as u16
}

/// Grid sides tried for the `A2B0`/`B2A0` tables, smallest first: each table takes the first
/// whose check ([`A2B_CHECK_DE`], [`B2A_CHECK_DE`]) passes, else the last.
pub const GRIDS: [usize; 4] = [17, 25, 33, 45];
/// Grid sides tried for `B2A0` (its error is set by the model's folds at the cube's faces more
/// than by the grid: measured on the shipped displays, docs/calibration.md).
pub const B2A_GRIDS: [usize; 2] = [17, 33];
/// `A2B0`'s input curves tried on each grid ([`a2b_shape`]): −2, piecewise linear in light
/// with nodes at light `(j/(grid − 1))²` (dense in the dark and exact for the matrix part:
/// chosen on every shipped display, Little CMS's worst patch 0.33 → 0.22 ΔE00 on the Acer);
/// `light^(1/p)` with 1, even in light (exact for a model without interaction), and 2, more
/// nodes in the dark, where the interaction lattice's cells are.
pub const A2B_POWERS: [f64; 3] = [-2.0, 1.0, 2.0];
/// `A2B0` is good enough when the table, evaluated as a CMM does, is within this ΔE00 of the
/// model at every colour of [`check_colours`].
pub const A2B_CHECK_DE: f64 = 0.05;
/// `B2A0` is good enough when the model's colour of every [`check_colours`] colour, through the
/// table and the model again, is within this ΔE00 of itself.
pub const B2A_CHECK_DE: f64 = 0.05;
/// How far beyond `[0, 1]` (in device linear light) `B2A0`'s table may reach: its nodes outside
/// the gamut extend the model affinely ([`b2a0`]); nodes further out are clipped there.
pub const B2A_OUT_REACH: f64 = 0.5;
/// Margin kept above the model's colours in `B2A0`'s input range, and below and above them in its
/// output range.
pub const B2A_IN_MARGIN: f64 = 0.002;
/// The most of the other two channels mixed into a channel of `B2A0`'s input (`β`, [`b2a0`]).
pub const B2A_BETA_MAX: f64 = 0.25;
/// Rounds of the damped fixed point that extends `B2A0` beyond the gamut ([`b2a_light`]).
pub const B2A_EXTEND_ROUNDS: usize = 30;
/// Face colours per side sampled to set `B2A0`'s input range.
pub const B2A_FACE_STEPS: usize = 32;
/// Entries of `A2B0`'s input curves.
pub const LUT_CURVE: usize = 1024;
/// Entries of `B2A0`'s input and output curves (the most `lut16Type` allows).
pub const B2A_CURVE: usize = 4096;

/// 8-bit levels of the check colours, dense in the dark, none on a table's grid.
const CHECK_LEVELS: [u8; 15] = [0, 1, 2, 4, 7, 12, 20, 33, 50, 77, 110, 150, 190, 230, 255];

/// The colours the tables are checked on: every combination of [`CHECK_LEVELS`] (device values).
pub fn check_colours() -> Vec<[f64; 3]> {
    let l = CHECK_LEVELS.map(|v| v as f64 / 255.0);
    let mut out = Vec::with_capacity(l.len().pow(3));
    for r in l {
        for g in l {
            for b in l {
                out.push([r, g, b]);
            }
        }
    }
    out
}

/// A channel's normalised linear light: the luminance the model predicts for the channel alone
/// at `v`, black subtracted, over its luminance at full drive (a monotone curve sampled at
/// `LUT_CURVE` points, made non-decreasing).
fn channel_curves(cal: &Calibration) -> [Vec<f64>; 3] {
    let black = cal.predict([0.0; 3])[1];
    [0, 1, 2].map(|c| {
        let at = |v: f64| {
            let mut rgb = [0.0; 3];
            rgb[c] = v;
            cal.predict(rgb)[1] - black
        };
        let full = at(1.0).max(f64::MIN_POSITIVE);
        let mut t: Vec<f64> = (0..LUT_CURVE)
            .map(|k| (at(k as f64 / (LUT_CURVE - 1) as f64) / full).clamp(0.0, 1.0))
            .collect();
        t[0] = 0.0;
        for k in 1..LUT_CURVE {
            t[k] = t[k].max(t[k - 1]);
        }
        t[LUT_CURVE - 1] = 1.0;
        t
    })
}

/// The device value at which a non-decreasing curve sampled at `LUT_CURVE` points reaches `l`
/// (the core's table inverse, in f32: far below the 16-bit tables' step).
fn curve_inverse(t: &[f32], l: f64) -> f64 {
    specpoly_core::display::table_inverse(t, l as f32) as f64
}

/// A `lut16Type` (`mft2`) tag: 3 inputs, 3 outputs, the matrix `matrix` (s15Fixed16; used by
/// CMMs only for PCS XYZ input), a `grid`³ table.
fn mft2(
    matrix: &[[i32; 3]; 3],
    inputs: &[Vec<u16>; 3],
    grid: usize,
    clut: &[[u16; 3]],
    outputs: &[Vec<u16>; 3],
) -> Vec<u8> {
    let mut t = b"mft2\0\0\0\0".to_vec();
    t.extend_from_slice(&[3, 3, grid as u8, 0]);
    for row in matrix {
        for v in row {
            t.extend_from_slice(&v.to_be_bytes());
        }
    }
    t.extend_from_slice(&(inputs[0].len() as u16).to_be_bytes());
    t.extend_from_slice(&(outputs[0].len() as u16).to_be_bytes());
    for c in inputs {
        for v in c {
            t.extend_from_slice(&v.to_be_bytes());
        }
    }
    for p in clut {
        for v in p {
            t.extend_from_slice(&v.to_be_bytes());
        }
    }
    for c in outputs {
        for v in c {
            t.extend_from_slice(&v.to_be_bytes());
        }
    }
    t
}

const IDENTITY: [[i32; 3]; 3] = [[65536, 0, 0], [0, 65536, 0], [0, 0, 65536]];

/// A 16-bit curve at `x ∈ [0, 1]`, linearly interpolated (as Little CMS and ArgyllCMS do).
fn curve_at(t: &[u16], x: f64) -> f64 {
    let p = x.clamp(0.0, 1.0) * (t.len() - 1) as f64;
    let i = (p.floor() as usize).min(t.len() - 2);
    let f = p - i as f64;
    (t[i] as f64 + f * (t[i + 1] as f64 - t[i] as f64)) / 65535.0
}

/// A `grid`³ table at `q ∈ [0, 1]³`, trilinear; outputs `0–1` (`u16 / 65535`).
fn clut_at(grid: usize, clut: &[[u16; 3]], q: [f64; 3]) -> [f64; 3] {
    let top = (grid - 1) as f64;
    let mut j = [0usize; 3];
    let mut f = [0.0; 3];
    for c in 0..3 {
        let x = q[c].clamp(0.0, 1.0) * top;
        j[c] = (x.floor() as usize).min(grid - 2);
        f[c] = x - j[c] as f64;
    }
    let mut out = [0.0; 3];
    for corner in 0..8usize {
        let s = [corner >> 2 & 1, corner >> 1 & 1, corner & 1];
        let w: f64 = (0..3)
            .map(|c| if s[c] == 1 { f[c] } else { 1.0 - f[c] })
            .product();
        let n = clut[((j[0] + s[0]) * grid + j[1] + s[1]) * grid + j[2] + s[2]];
        for r in 0..3 {
            out[r] += w * n[r] as f64 / 65535.0;
        }
    }
    out
}

/// The matrix/TRC part of the profile, from the model: `XYZ = M_w · τ(rgb)` with
/// `τ_i(v) = (t_i(v) + k_i) / (1 + k_i)` (the black folded into the curves, `k = M⁻¹K`,
/// negative components taken as 0) and `M_w = M·diag(1 + k)·diag(s)`, `s = (M·diag(1 + k))⁻¹ W`
/// with `W = f(1, 1, 1)` the model's white: the matrix/TRC model's white is the model's
/// (exactly; `s = 1` for a model without channel interaction, whose white is `M(1 + k)`).
#[derive(Clone, Debug)]
pub struct MatrixPart {
    /// `M_w` (rows X, Y, Z; columns R, G, B), the calibration's units.
    pub matrix: [[f64; 3]; 3],
    /// The black as linear drive, `k`.
    pub k: [f64; 3],
    /// The model's white `f(1, 1, 1)`.
    pub white: [f64; 3],
}

/// The profile's matrix/TRC part for `cal` (see [`MatrixPart`]).
pub fn matrix_part(cal: &Calibration) -> Result<MatrixPart> {
    let m = cal.matrix();
    let inv = Mat3(m)
        .inverse()
        .map_err(|_| Error::Unprofilable("the calibration's primaries are singular"))?;
    let k = inv.apply(cal.data().black).map(|v| v.max(0.0));
    let m1 = [0, 1, 2].map(|r| [0, 1, 2].map(|c| m[r][c] * (1.0 + k[c])));
    let white = model_white(cal);
    if !(white[1] > 0.0) || white.iter().any(|v| !v.is_finite()) {
        return Err(Error::Unprofilable(
            "the calibration's white has no luminance",
        ));
    }
    let s = Mat3(m1)
        .inverse()
        .map_err(|_| Error::Unprofilable("the calibration's primaries are singular"))?
        .apply(white);
    if s.iter().any(|v| !(*v > 0.0 && v.is_finite())) {
        return Err(Error::Unprofilable(
            "the model's white lies outside its primaries",
        ));
    }
    let matrix = [0, 1, 2].map(|r| [0, 1, 2].map(|c| m1[r][c] * s[c]));
    Ok(MatrixPart { matrix, k, white })
}

/// `A2B0` on a `grid`³ table: input curves = each channel's normalised linear light
/// ([`channel_curves`]), so the table's nodes are even in light; the table holds the model's PCS
/// XYZ ([`predict_pcs`]) at the device values whose linear light is each node.
fn a2b0(
    cal: &Calibration,
    curves: &[Vec<f64>; 3],
    grid: usize,
    power: f64,
) -> ([Vec<u16>; 3], Vec<[u16; 3]>) {
    let curves: [Vec<f64>; 3] = curves
        .each_ref()
        .map(|c| c.iter().map(|v| a2b_shape(*v, power, grid)).collect());
    let curves32 = curves
        .each_ref()
        .map(|c| c.iter().map(|v| *v as f32).collect::<Vec<_>>());
    let g = |k: usize| k as f64 / (grid - 1) as f64;
    let a_in = [0, 1, 2].map(|c| curves[c].iter().map(|v| u16_unit(*v)).collect::<Vec<_>>());
    let mut clut = Vec::with_capacity(grid.pow(3));
    for r in 0..grid {
        for gg in 0..grid {
            for b in 0..grid {
                let lin = [g(r), g(gg), g(b)];
                let rgb = [0, 1, 2].map(|c| curve_inverse(&curves32[c], lin[c]));
                clut.push(predict_pcs(cal, rgb).map(u16_xyz));
            }
        }
    }
    (a_in, clut)
}

/// `A2B0`'s input coordinate for normalised light `v`: `v^(1/p)` for `p > 0`; for `p < 0`,
/// piecewise linear in light with grid node `j` at light `(j/(grid − 1))^|p|` (dense in the
/// dark, yet a function affine in light — the matrix part, black included — is reproduced
/// exactly between nodes).
fn a2b_shape(v: f64, p: f64, grid: usize) -> f64 {
    if p > 0.0 {
        return v.powf(1.0 / p);
    }
    let top = (grid - 1) as f64;
    let node = |j: f64| (j / top).powf(-p);
    // the node below v: (v^(1/|p|) · top), floored
    let j = (v.max(0.0).powf(1.0 / -p) * top)
        .floor()
        .clamp(0.0, top - 1.0);
    let (a, b) = (node(j), node(j + 1.0));
    ((j + ((v - a) / (b - a)).clamp(0.0, 1.0)) / top).clamp(0.0, 1.0)
}

/// `A2B0` evaluated as a CMM does: PCS XYZ.
fn a2b0_at(inputs: &[Vec<u16>; 3], grid: usize, clut: &[[u16; 3]], rgb: [f64; 3]) -> [f64; 3] {
    let q = [0, 1, 2].map(|c| curve_at(&inputs[c], rgb[c]));
    clut_at(grid, clut, q).map(|v| v * 65535.0 / 32768.0)
}

/// `B2A0`'s parts: matrix (s15Fixed16), input curves, table, output curves.
struct B2a {
    matrix: [[i32; 3]; 3],
    inputs: [Vec<u16>; 3],
    grid: usize,
    clut: Vec<[u16; 3]>,
    outputs: [Vec<u16>; 3],
}

impl B2a {
    /// Device values for PCS XYZ, as a CMM evaluates the table.
    fn at(&self, pcs: [f64; 3]) -> [f64; 3] {
        let v = pcs.map(|x| x * 32768.0 / 65535.0);
        let m = self.matrix.map(|r| r.map(|e| e as f64 / 65536.0));
        let u = Mat3(m).apply(v);
        let q = [0, 1, 2].map(|c| curve_at(&self.inputs[c], u[c]));
        let o = clut_at(self.grid, &self.clut, q);
        [0, 1, 2].map(|c| curve_at(&self.outputs[c], o[c]))
    }
}

/// `B2A0` on a `grid`³ table (PCS XYZ → device), every node solved by the core's inverse
/// ([`specpoly_core::DisplayModel::inverse_with`]).
///
/// A CMM evaluates `lut16Type` as matrix → input curves → table (trilinear) → output curves.
/// With `τ = M_pcs⁻¹ · PCS` the matrix/TRC part's linear light ([`MatrixPart`]):
///
/// - **matrix**: `u = diag(1/top) · B · τ` with `B = I + diag(β)(J − I)` (each channel mixed
///   with `β_c` of the other two): a lut16 matrix has no offset and its input curves clip below
///   0, yet where the channels interact the gamut's faces lie a little outside the matrix/TRC
///   part's cube (`τ_c` down to −0.02 on the shipped displays); `β_c` is the least that keeps
///   `u_c ≥ 0` over the model's colours on the cube's faces (0–0.023 on the shipped displays),
///   `top_c` the largest `u_c` there. (Asking for `u_c ≥ 0.002` instead — more than the
///   black's own `τ_c ≈ 0.001` — drove `β_c` to its cap of 0.25 near black on four of the five
///   shipped displays: a fifth of the grid's span in `u_c` then held the other two channels, the
///   face `D_c = 0` lay at `u_c ≈ 0.18` with blue full, red 0–30 within a quarter of one cell,
///   and colours came back up to 16 codes off.);
/// - **input curves**: piecewise linear, grid node `j` at `u = (j/(grid − 1))²` (rounded to the
///   curve's own samples, so the CMM's interpolation of the curve is exact): nodes dense in the
///   dark, and a function affine in `u` is reproduced exactly by the table;
/// - **table**: each node's device linear light `T = M⁻¹ (XYZ − K − L(D))`, `D` the core
///   inverse's device values for the node's colour (from a neighbour's solution, the global
///   search when the neighbour was shown). Inside the gamut `T = t(D)`; outside it `D` is the
///   nearest the cube allows and `T` extends the model affinely, so the table stays smooth
///   across the gamut's boundary. `T` is affine in `u` for a model without interaction (exact
///   up to 16-bit rounding); with interaction the table holds the lattice's term. Storing `D`
///   instead (as before) put each curve's root singularity `D ∝ T^(1/γ)` inside the table's
///   cells wherever the lattice moves a face off the grid: up to 131 codes back;
/// - **output curves**: `D = t⁻¹(T)` (the core's curve inverse, `T` clipped to `[0, 1]`),
///   [`B2A_CURVE`] entries, the table's `T ∈ [−O, S − O]` as `(T + O) / S`.
fn b2a0(cal: &Calibration, part: &MatrixPart, grid: usize) -> Result<B2a> {
    let singular = || Error::Unprofilable("the calibration's primaries are singular");
    let w = part.white;
    let c_pcs = chad(w);
    let mpcs = c_pcs.mul(&Mat3(part.matrix.map(|r| r.map(|v| v / w[1]))));
    let mw_inv = Mat3(part.matrix).inverse().map_err(|_| singular())?;
    // β and top from the model's colours on the cube's faces
    let faces = face_colours(B2A_FACE_STEPS);
    let taus: Vec<[f64; 3]> = faces
        .iter()
        .map(|d| mw_inv.apply(cal.predict(*d)))
        .collect();
    let beta = [0, 1, 2].map(|c| {
        let (a, b) = ((c + 1) % 3, (c + 2) % 3);
        taus.iter()
            .filter(|t| t[c] < 0.0)
            .map(|t| -t[c] / (t[a] + t[b]).max(1e-6))
            .fold(0.0f64, f64::max)
            .min(B2A_BETA_MAX)
    });
    let mix = Mat3([0, 1, 2].map(|r| [0, 1, 2].map(|c| if r == c { 1.0 } else { beta[r] })));
    let top = [0, 1, 2].map(|c| {
        taus.iter().map(|t| mix.apply(*t)[c]).fold(1.0f64, f64::max) * (1.0 + B2A_IN_MARGIN)
    });
    let inv = mpcs.inverse().map_err(|_| singular())?;
    let a = Mat3([0, 1, 2].map(|r| mix.0[r].map(|v| v / top[r]))).mul(&inv);
    let enc = 65535.0 / 32768.0;
    let matrix: [[i32; 3]; 3] = a.0.map(|r| r.map(|v| (v * enc * 65536.0).round() as i32));
    // what the stored matrix maps back: a node's PCS from its u
    let back = Mat3(matrix.map(|r| r.map(|e| e as f64 / 65536.0)))
        .inverse()
        .map_err(|_| singular())?;
    // the input curves: node j at u_j, on the curve's own samples
    let last = (B2A_CURVE - 1) as f64;
    let mut at = vec![0usize; grid];
    for (j, u) in at.iter_mut().enumerate() {
        let f = j as f64 / (grid - 1) as f64;
        *u = (f * f * last).round() as usize;
    }
    for j in 1..grid {
        at[j] = at[j].max(at[j - 1] + 1);
    }
    if at[grid - 1] > B2A_CURVE - 1 {
        return Err(Error::Unprofilable(
            "the B2A0 grid is finer than its curves",
        ));
    }
    let input: Vec<u16> = (0..B2A_CURVE)
        .map(|i| {
            let j = at.partition_point(|&a| a <= i).clamp(1, grid - 1) - 1;
            let f = (i as f64 - at[j] as f64) / (at[j + 1] - at[j]) as f64;
            u16_unit((j as f64 + f.min(1.0)) / (grid - 1) as f64)
        })
        .collect();
    let node_u = |j: usize| at[j] as f64 / last;
    // the nodes
    let unchad = c_pcs
        .inverse()
        .map_err(|_| Error::Unprofilable("the white is degenerate"))?;
    let want = |n: [usize; 3]| {
        let pcs = back.apply(n.map(node_u)).map(|v| v * enc);
        unchad.apply(pcs).map(|v| v * w[1])
    };
    // the global search only for nodes inside the matrix/TRC part's cube (outside it the
    // colour is, but for the lattice's small reach, outside the gamut too)
    let inside = |n: [usize; 3]| {
        mw_inv
            .apply(want(n))
            .iter()
            .all(|v| (0.0..=1.0).contains(v))
    };
    let light = b2a_light(cal, grid, &want, &inside);
    // the output curves
    let (lo, hi) = light
        .iter()
        .flatten()
        .fold((0.0f64, 1.0f64), |(l, h), v| (l.min(*v), h.max(*v)));
    let offset = (-lo + B2A_IN_MARGIN).min(B2A_OUT_REACH);
    let span = (hi + B2A_IN_MARGIN).min(1.0 + B2A_OUT_REACH) + offset;
    let t = cal.model().display().transfer();
    let outputs = [0, 1, 2].map(|c| {
        (0..B2A_CURVE)
            .map(|i| {
                let l = i as f64 / last * span - offset;
                u16_unit(t[c].encode(l.clamp(0.0, 1.0) as f32) as f64)
            })
            .collect::<Vec<_>>()
    });
    let clut = light
        .iter()
        .map(|v| v.map(|l| u16_unit((l + offset) / span)))
        .collect();
    Ok(B2a {
        matrix,
        inputs: [input.clone(), input.clone(), input],
        grid,
        clut,
        outputs,
    })
}

/// Each `B2A0` node's device linear light `T = M⁻¹ (XYZ − K − L(D))` ([`b2a0`]), `want` the
/// node's XYZ (the calibration's units), nodes red slowest. Solved by the core's inverse in
/// red slices on up to 8 threads, each slice from the white corner down, each node from its
/// neighbour's solution (continuation: where the model folds, neighbours stay on one branch),
/// the global search only next to a node that was shown and for a node `inside` the matrix/TRC
/// part's cube. A node outside the gamut (the
/// inverse's nearest, not exact) takes the fixed point of `T ← M⁻¹ (XYZ − K − L(t⁻¹(T)))`,
/// `t⁻¹` clamping to the cube (damped by ½, [`B2A_EXTEND_ROUNDS`] rounds, kept when it
/// settles; else the nearest's): the lattice held at the face the colour lies beyond, so the
/// extension follows the model across the boundary rather than the nearest point's moves
/// (measured: colours more than 5 codes off on the Lenovo 431 → 243 of 140 608).
fn b2a_light(
    cal: &Calibration,
    grid: usize,
    want: &(impl Fn([usize; 3]) -> [f64; 3] + Sync),
    inside: &(impl Fn([usize; 3]) -> bool + Sync),
) -> Vec<[f64; 3]> {
    use specpoly_core::InverseOptions;
    let model = cal.model();
    let m_inv = Mat3(cal.matrix()).inverse().ok();
    let black = cal.data().black;
    let lattice = model.interaction();
    let curves = model.display().transfer();
    let solve_slice = |r: usize| {
        let mut out = vec![[0.0f64; 3]; grid * grid];
        let mut row_start: Option<([f32; 3], bool)> = None;
        for g in (0..grid).rev() {
            let mut prev = row_start;
            for b in (0..grid).rev() {
                let x = want([r, g, b]);
                let s = model.inverse_with(
                    Xyz::from_array(x.map(|v| v as f32)),
                    InverseOptions {
                        start: prev.map(|p| p.0),
                        global: prev.is_none_or(|p| p.1) && inside([r, g, b]),
                    },
                );
                let d = s.device;
                let l = lattice.map_or([0.0; 3], |l| l.eval(d).map(f64::from));
                let rest = [0, 1, 2].map(|k| x[k] - black[k] - l[k]);
                let mut tl = match &m_inv {
                    Some(mi) => mi.apply(rest),
                    None => cal.linearise(d.map(f64::from)),
                };
                // outside the gamut: the lattice at the clamped device values of `T` itself
                if let (Some(mi), false, Some(lat)) = (&m_inv, s.exact, lattice) {
                    let mut cur = tl;
                    let mut converged = false;
                    for _ in 0..B2A_EXTEND_ROUNDS {
                        let dd = [0, 1, 2].map(|c| curves[c].encode(cur[c] as f32));
                        let l = lat.eval(dd).map(f64::from);
                        let next = mi.apply([0, 1, 2].map(|k| x[k] - black[k] - l[k]));
                        let step = [0, 1, 2].map(|c| 0.5 * (next[c] - cur[c]));
                        cur = [0, 1, 2].map(|c| cur[c] + step[c]);
                        converged = step.iter().all(|v| v.abs() < 1e-7);
                    }
                    if converged {
                        tl = cur;
                    }
                }
                out[g * grid + b] = tl;
                prev = Some((d, s.exact));
                if b == grid - 1 {
                    row_start = prev;
                }
            }
        }
        out
    };
    let threads = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .clamp(1, 8);
    let slices: Vec<Vec<[f64; 3]>> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..threads)
            .map(|k| {
                let solve_slice = &solve_slice;
                s.spawn(move || {
                    (0..grid)
                        .filter(|r| r % threads == k)
                        .map(|r| (r, solve_slice(r)))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        let mut all: Vec<(usize, Vec<[f64; 3]>)> = handles
            .into_iter()
            .flat_map(|h| h.join().unwrap_or_default())
            .collect();
        all.sort_by_key(|p| p.0);
        all.into_iter().map(|p| p.1).collect()
    });
    slices.into_iter().flatten().collect()
}

/// Device values on the cube's six faces, `steps + 1` a side.
fn face_colours(steps: usize) -> Vec<[f64; 3]> {
    let mut out = Vec::with_capacity(6 * (steps + 1) * (steps + 1));
    for i in 0..=steps {
        for j in 0..=steps {
            let (a, b) = (i as f64 / steps as f64, j as f64 / steps as f64);
            for v in [0.0, 1.0] {
                out.extend([[v, a, b], [a, v, b], [a, b, v]]);
            }
        }
    }
    out
}

/// The round trip's worst error over [`check_colours`]: the model's PCS through `b2a`, and
/// the model's colour of the device values it gives against that PCS (ΔE00: codes in a flat
/// foot of a curve, or where the lattice folds the model, are colours the model cannot tell
/// apart).
fn b2a_check(cal: &Calibration, b2a: &B2a) -> f64 {
    check_colours()
        .iter()
        .map(|rgb| {
            let pcs = predict_pcs(cal, *rgb);
            let back = b2a.at(pcs);
            specpoly_core::delta_e2000_xyz(predict_pcs(cal, back), pcs, D50)
        })
        .fold(0.0, f64::max)
}

/// A measured `A2B0`: its worst ΔE00, input curves, grid side and table.
type A2bCandidate = (f64, [Vec<u16>; 3], usize, Vec<[u16; 3]>);

/// `A2B0` and `B2A0` sampled from the model, each on the smallest grid of [`GRIDS`] whose check
/// passes (`A2B0`: within [`A2B_CHECK_DE`] of the model on [`check_colours`]; `B2A0`: those
/// colours' model PCS back within [`B2A_CHECK_DE`]). See [`a2b0`] and [`b2a0`]: both tables
/// are near-linear in their grids (A2B0 in light, B2A0 in the matrix/TRC model's device values),
/// so for a model without channel interaction the first grid passes.
pub fn lut16(cal: &Calibration) -> Result<(Vec<u8>, Vec<u8>)> {
    let part = matrix_part(cal)?;
    let curves = channel_curves(cal);
    let check = check_colours();
    let want: Vec<[f64; 3]> = check.iter().map(|c| predict_pcs(cal, *c)).collect();
    // A2B0: the first (grid, input-curve power) that passes, else the best measured
    let mut a: Option<A2bCandidate> = None;
    'a: for grid in GRIDS {
        for power in A2B_POWERS {
            let (inputs, clut) = a2b0(cal, &curves, grid, power);
            let worst = check
                .iter()
                .zip(&want)
                .map(|(c, w)| {
                    specpoly_core::delta_e2000_xyz(a2b0_at(&inputs, grid, &clut, *c), *w, D50)
                })
                .fold(0.0, f64::max);
            if a.as_ref().is_none_or(|b| worst < b.0) {
                a = Some((worst, inputs, grid, clut));
            }
            if worst <= A2B_CHECK_DE {
                break 'a;
            }
        }
    }
    let (_, inputs, grid, clut) = a.expect("GRIDS is not empty");
    let ident = || vec![0u16, 65535];
    let a2b0 = mft2(
        &IDENTITY,
        &inputs,
        grid,
        &clut,
        &[ident(), ident(), ident()],
    );
    let mut b: Option<(f64, B2a)> = None;
    for grid in B2A_GRIDS {
        let t = b2a0(cal, &part, grid)?;
        let e = b2a_check(cal, &t);
        if b.as_ref().is_none_or(|b| e < b.0) {
            b = Some((e, t));
        }
        if e <= B2A_CHECK_DE {
            break;
        }
    }
    let (_, b) = b.expect("B2A_GRIDS is not empty");
    let b2a0 = mft2(&b.matrix, &b.inputs, b.grid, &b.clut, &b.outputs);
    Ok((a2b0, b2a0))
}

/// Builds the profile's bytes. `description` goes into `desc`.
pub fn build(cal: &Calibration, description: &str, opts: &IccOptions) -> Result<Vec<u8>> {
    let v2 = opts.version == IccVersion::V2;
    let part = matrix_part(cal)?;
    let (m1, k, w) = (part.matrix, part.k, part.white);
    let chad = chad(w);
    let col = |c: usize| chad.apply([m1[0][c] / w[1], m1[1][c] / w[1], m1[2][c] / w[1]]);
    let copyright = "No copyright; written by specpoly from a measured calibration";
    let (desc, cprt, wtpt) = if v2 {
        (
            text_description(description),
            text(copyright),
            xyz_tag(w.map(|v| v / w[1])),
        )
    } else {
        (mluc(description), mluc(copyright), xyz_tag(D50))
    };
    let mut tags: Vec<(&[u8; 4], Vec<u8>)> = vec![
        (b"desc", desc),
        (b"cprt", cprt),
        (b"wtpt", wtpt),
        (b"chad", sf32(&chad.0)),
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
    if let Some(lut) = cal.video_lut() {
        tags.push((b"vcgt", vcgt(lut)));
    }
    if opts.tables {
        let (a2b0, b2a0) = lut16(cal)?;
        tags.push((b"A2B0", a2b0));
        tags.push((b"B2A0", b2a0));
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
    let version: u32 = if v2 { 0x0240_0000 } else { 0x0440_0000 };
    h.extend_from_slice(&version.to_be_bytes());
    h.extend_from_slice(b"mntr");
    h.extend_from_slice(b"RGB ");
    h.extend_from_slice(b"XYZ ");
    for v in created(cal) {
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
    h.extend_from_slice(&[0; 16]); // profile ID, set below
    h.extend_from_slice(&[0; 28]);
    debug_assert_eq!(h.len(), 128);
    h.extend_from_slice(&table);
    h.extend_from_slice(&data);
    let id = profile_id(&h);
    h[84..100].copy_from_slice(&id);
    Ok(h)
}

/// The header's date: when the calibration was fitted (`provenance.created`, so one
/// calibration always gives the same profile bytes), or now if that is not an ISO 8601 UTC time.
fn created(cal: &Calibration) -> [i64; 6] {
    let c = &cal.data().provenance.created;
    let parts: Vec<i64> = c
        .split(|ch: char| !ch.is_ascii_digit())
        .filter(|p| !p.is_empty())
        .filter_map(|p| p.parse().ok())
        .collect();
    match parts[..] {
        [y, mo, d, h, mi, s, ..]
            if (1900..=9999).contains(&y)
                && (1..=12).contains(&mo)
                && (1..=31).contains(&d)
                && h < 24
                && mi < 60
                && s < 61 =>
        {
            [y, mo, d, h, mi, s]
        }
        _ => crate::time::utc_parts(),
    }
}

/// The profile ID (ICC.1:2022 §7.2.18): MD5 of the profile with the header's flags (bytes
/// 44–47), rendering intent (64–67) and profile ID (84–99) set to zero.
pub fn profile_id(profile: &[u8]) -> [u8; 16] {
    let mut p = profile.to_vec();
    if p.len() >= 128 {
        p[44..48].fill(0);
        p[64..68].fill(0);
        p[84..100].fill(0);
    }
    md5::compute(&p).0
}
