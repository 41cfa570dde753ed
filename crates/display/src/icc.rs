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

/// Grid points per input of the `A2B0`/`B2A0` tables.
pub const GRID: usize = 17;
/// Entries of the tables' input curves.
pub const LUT_CURVE: usize = 1024;
/// `B2A0`'s grid holds linear drive `l` as `(l + B2A_OFFSET) / B2A_SPAN` (so `l ∈ [−1, 2]`,
/// beyond the gamut, stays linear in XYZ and interpolates exactly up to the boundary); its
/// output curves (`B2A_CURVE` entries, the most `lut16Type` allows) clip and encode.
pub const B2A_OFFSET: f64 = 1.0;
/// See [`B2A_OFFSET`].
pub const B2A_SPAN: f64 = 3.0;
/// Entries of `B2A0`'s output curves.
pub const B2A_CURVE: usize = 4096;

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

/// A `lut16Type` (`mft2`) tag: 3 inputs, 3 outputs, identity matrix.
fn mft2(inputs: &[Vec<u16>; 3], clut: &[[u16; 3]], outputs: &[Vec<u16>; 3]) -> Vec<u8> {
    let mut t = b"mft2\0\0\0\0".to_vec();
    t.extend_from_slice(&[3, 3, GRID as u8, 0]);
    for r in 0..3 {
        for c in 0..3 {
            t.extend_from_slice(&s15(if r == c { 1.0 } else { 0.0 }));
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

/// `A2B0` and `B2A0` sampled from the model.
///
/// `A2B0` (device → PCS XYZ): each input curve is the channel's normalised linear light
/// ([`channel_curves`]), so the 17³ grid is even in light, not in code values; the grid holds
/// the model's PCS XYZ ([`predict_pcs`]) at the device values whose linear light is each grid
/// point. `B2A0` (PCS XYZ → device): identity input curves over the PCS encoding, the grid holds
/// each channel's linear light of the model's inverse (outside the gamut the base matrix's,
/// unclipped, offset as [`B2A_OFFSET`] says), and the output curves clip it and turn it back
/// into device values. For an additive model both grids are linear in their inputs, so
/// trilinear interpolation is exact up to 16-bit rounding (XYZ steps of 1/32768: up to
/// ΔE00 ≈ 0.2 in the darkest colours); a model with channel interaction is sampled at 17³
/// points.
pub fn lut16(cal: &Calibration) -> Result<(Vec<u8>, Vec<u8>)> {
    let curves = channel_curves(cal);
    let curves32 = curves
        .each_ref()
        .map(|c| c.iter().map(|v| *v as f32).collect::<Vec<_>>());
    let g = |k: usize| k as f64 / (GRID - 1) as f64;
    // A2B0
    let a_in = [0, 1, 2].map(|c| curves[c].iter().map(|v| u16_unit(*v)).collect::<Vec<_>>());
    let mut a_clut = Vec::with_capacity(GRID * GRID * GRID);
    for r in 0..GRID {
        for gg in 0..GRID {
            for b in 0..GRID {
                let lin = [g(r), g(gg), g(b)];
                let rgb = [0, 1, 2].map(|c| curve_inverse(&curves32[c], lin[c]));
                a_clut.push(predict_pcs(cal, rgb).map(u16_xyz));
            }
        }
    }
    let ident = || vec![0u16, 65535];
    let a2b0 = mft2(&a_in, &a_clut, &[ident(), ident(), ident()]);
    // B2A0
    let w = model_white(cal);
    if !(w[1] > 0.0) {
        return Err(Error::Unprofilable(
            "the calibration's white has no luminance",
        ));
    }
    let unchad = chad(w)
        .inverse()
        .map_err(|_| Error::Unprofilable("the white is degenerate"))?;
    let lin_of = |rgb: [f64; 3]| {
        [0, 1, 2].map(|c| {
            let t = &curves[c];
            let x = rgb[c].clamp(0.0, 1.0) * (t.len() - 1) as f64;
            let i = (x.floor() as usize).min(t.len() - 2);
            t[i] + (x - i as f64) * (t[i + 1] - t[i])
        })
    };
    let full = 1.0 + 32767.0 / 32768.0;
    let display = cal.display();
    let mut b_clut = Vec::with_capacity(GRID * GRID * GRID);
    for x in 0..GRID {
        for y in 0..GRID {
            for z in 0..GRID {
                let pcs = [g(x) * full, g(y) * full, g(z) * full];
                let xyz = unchad.apply(pcs).map(|v| v * w[1]);
                // inside the gamut the model's own inverse; outside, the base matrix's linear
                // drive unclipped, so the grid stays linear across the gamut's boundary
                let lin = match crate::target::reach(cal, xyz) {
                    Some(rgb) => lin_of(rgb),
                    None => display
                        .xyz_to_linear(specpoly_core::Xyz::new(
                            xyz[0] as f32,
                            xyz[1] as f32,
                            xyz[2] as f32,
                        ))
                        .map(|v| v as f64),
                };
                b_clut.push(lin.map(|l| u16_unit((l + B2A_OFFSET) / B2A_SPAN)));
            }
        }
    }
    let b_out = [0, 1, 2].map(|c| {
        (0..B2A_CURVE)
            .map(|k| {
                let l = k as f64 / (B2A_CURVE - 1) as f64 * B2A_SPAN - B2A_OFFSET;
                u16_unit(curve_inverse(&curves32[c], l.clamp(0.0, 1.0)))
            })
            .collect::<Vec<_>>()
    });
    let b2a0 = mft2(&[ident(), ident(), ident()], &b_clut, &b_out);
    Ok((a2b0, b2a0))
}

/// Builds the profile's bytes. `description` goes into `desc`.
pub fn build(cal: &Calibration, description: &str, opts: &IccOptions) -> Result<Vec<u8>> {
    let v2 = opts.version == IccVersion::V2;
    let m = cal.matrix(); // rows X, Y, Z; columns R, G, B
    let black = cal.data().black;
    let inv = Mat3(m)
        .inverse()
        .map_err(|_| Error::Unprofilable("the calibration's primaries are singular"))?;
    let k = inv.apply(black).map(|v| v.max(0.0));
    // M' = M diag(1 + k)
    let m1 = [0, 1, 2].map(|r| [0, 1, 2].map(|c| m[r][c] * (1.0 + k[c])));
    let w = [0, 1, 2].map(|r| m1[r][0] + m1[r][1] + m1[r][2]);
    if w[1].is_nan() || w[1] <= 0.0 {
        return Err(Error::Unprofilable(
            "the calibration's white has no luminance",
        ));
    }
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
