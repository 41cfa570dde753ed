//! 3D LUT files: what each format's specification or published layout says, written from a
//! [`Lut3d`], and the two text formats read back (for `verify --lut3d`).
//!
//! - **`.cube`** (Adobe, *Cube LUT Specification* 1.0, 2013; what Resolve, ffmpeg's `lut3d`
//!   and OpenColorIO read): `#` comment lines, `TITLE "…"`, `LUT_3D_SIZE N` (2–256),
//!   `DOMAIN_MIN 0 0 0`, `DOMAIN_MAX 1 1 1`, then `N³` lines `R G B` of output values with the
//!   **red index changing fastest**, then green, then blue. Written with 6 decimals.
//! - **`.3dl`** (Autodesk Lustre/Flame, the layout ffmpeg and OpenColorIO read): `#` comment
//!   lines, one line of the `N` input mesh values in 10 bits (`0 64 128 … 1023` for 17: steps of
//!   `1024/(N − 1)`, the last held at 1023), then `N³` lines of 12-bit integer outputs
//!   (`0–4095`) with the **blue index changing fastest**, red slowest. ffmpeg 5.1 reads only
//!   17-point `.3dl` files and divides by 4096 (its full scale is `4095/4096`); OpenColorIO
//!   takes `N` from the mesh line and the output depth from the largest value.
//! - **madVR `.3dlut`** (binary; the header madVR publishes, as Kodi's and MPDN's readers
//!   reproduce it): a 96-byte little-endian header — `"3DLT"`, file version 1, the program's
//!   name (32 bytes), its version (u64), the input bit depth per channel (3 × u32: 8), input
//!   encoding (0 = RGB), output bit depth (16), output encoding (0 = RGB), the parameters'
//!   offset and size, the LUT's offset, compression (0 = none), compressed and uncompressed
//!   sizes — then the parameters as text (`Input_Primaries` of the source, `Input_Range` and
//!   `Output_Range` 0–255: full range), then `256³` entries of three u16 in the order
//!   **B, G, R**, red index slowest, blue fastest. madVR's input is always 8 bits per channel,
//!   so the table is the LUT interpolated (tetrahedrally) at `k/255`: 96 MiB.

use super::source::SourceSpace;
use super::Lut3d;
use crate::error::{Error, Result};
use std::fmt::Write;
use std::path::Path;

/// The largest side read from a file (the Cube specification's limit).
pub const READ_SIZE_MAX: usize = 256;

/// A 3D LUT file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Adobe/Resolve `.cube`.
    Cube,
    /// Autodesk Lustre `.3dl`.
    ThreeDl,
    /// madVR `.3dlut`.
    MadVr,
}

impl Format {
    /// The format a file name's extension names (`.cube`, `.3dl`, `.3dlut`; any case).
    pub fn from_path(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "cube" => Some(Format::Cube),
            "3dl" => Some(Format::ThreeDl),
            "3dlut" => Some(Format::MadVr),
            _ => None,
        }
    }

    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            Format::Cube => "cube",
            Format::ThreeDl => "3dl",
            Format::MadVr => "madvr",
        }
    }
}

/// A header line made safe for every reader: one line, ASCII (others become `?`).
fn ascii_line(s: &str) -> String {
    specpoly_formats::escape::one_line(s)
        .chars()
        .map(|c| {
            if c.is_ascii() && !c.is_ascii_control() {
                c
            } else {
                '?'
            }
        })
        .collect()
}

/// The file's bytes of `lut` in `format`; `source` is the space the LUT's input is in (madVR's
/// header names its primaries).
pub fn write(lut: &Lut3d, format: Format, source: SourceSpace) -> Vec<u8> {
    match format {
        Format::Cube => cube(lut).into_bytes(),
        Format::ThreeDl => three_dl(lut).into_bytes(),
        Format::MadVr => madvr(lut, source),
    }
}

fn comments(lut: &Lut3d, out: &mut String) {
    for line in lut.header() {
        let _ = writeln!(out, "# {}", ascii_line(line));
    }
}

/// The `.cube` text (module docs).
pub fn cube(lut: &Lut3d) -> String {
    let n = lut.size();
    let mut out = String::with_capacity(n * n * n * 27 + 2048);
    comments(lut, &mut out);
    let title = ascii_line(lut.title()).replace('"', "'");
    let _ = writeln!(out, "TITLE \"{title}\"");
    let _ = writeln!(out, "LUT_3D_SIZE {n}");
    let _ = writeln!(out, "DOMAIN_MIN 0.0 0.0 0.0");
    let _ = writeln!(out, "DOMAIN_MAX 1.0 1.0 1.0");
    for b in 0..n {
        for g in 0..n {
            for r in 0..n {
                let v = lut.node(r, g, b);
                let _ = writeln!(out, "{:.6} {:.6} {:.6}", v[0], v[1], v[2]);
            }
        }
    }
    out
}

/// The 10-bit input mesh of a `.3dl` with `n` points (module docs).
pub fn mesh(n: usize) -> Vec<u32> {
    let step = 1024 / (n as u32 - 1);
    (0..n as u32)
        .map(|i| {
            if 1024 % (n as u32 - 1) == 0 {
                (i * step).min(1023)
            } else {
                (f64::from(i) * 1023.0 / (n - 1) as f64).round() as u32
            }
        })
        .collect()
}

/// The `.3dl` text (module docs).
pub fn three_dl(lut: &Lut3d) -> String {
    let n = lut.size();
    let mut out = String::with_capacity(n * n * n * 16 + 2048);
    comments(lut, &mut out);
    let m: Vec<String> = mesh(n).iter().map(u32::to_string).collect();
    let _ = writeln!(out, "{}", m.join(" "));
    let q = |v: f64| (v.clamp(0.0, 1.0) * 4095.0).round() as u32;
    for r in 0..n {
        for g in 0..n {
            for b in 0..n {
                let v = lut.node(r, g, b);
                let _ = writeln!(out, "{} {} {}", q(v[0]), q(v[1]), q(v[2]));
            }
        }
    }
    out
}

/// madVR's fixed input side (8 bits per channel).
pub const MADVR_SIDE: usize = 256;
/// The madVR header's size in bytes.
pub const MADVR_HEADER: usize = 96;

/// The madVR `.3dlut` bytes (module docs).
pub fn madvr(lut: &Lut3d, source: SourceSpace) -> Vec<u8> {
    let p = source.primaries();
    let w = super::source::D65_XY;
    let mut params = String::new();
    let _ = write!(
        params,
        "Input_Primaries {:.6} {:.6} {:.6} {:.6} {:.6} {:.6} {:.6} {:.6}\r\nInput_Range 0 255\r\nOutput_Range 0 255\r\n",
        p[0][0], p[0][1], p[1][0], p[1][1], p[2][0], p[2][1], w[0], w[1]
    );
    let params = params.into_bytes();
    let lut_bytes = MADVR_SIDE.pow(3) * 3 * 2;
    let lut_offset = MADVR_HEADER + params.len();
    let mut out = Vec::with_capacity(lut_offset + lut_bytes);
    let u32le = |out: &mut Vec<u8>, v: usize| out.extend_from_slice(&(v as u32).to_le_bytes());
    out.extend_from_slice(b"3DLT");
    u32le(&mut out, 1);
    let mut name = [0u8; 32];
    name[..8].copy_from_slice(b"specpoly");
    out.extend_from_slice(&name);
    out.extend_from_slice(&1u64.to_le_bytes());
    for _ in 0..3 {
        u32le(&mut out, 8);
    }
    u32le(&mut out, 0); // input: RGB
    u32le(&mut out, 16);
    u32le(&mut out, 0); // output: RGB
    u32le(&mut out, MADVR_HEADER);
    u32le(&mut out, params.len());
    u32le(&mut out, lut_offset);
    u32le(&mut out, 0); // no compression
    u32le(&mut out, lut_bytes);
    u32le(&mut out, lut_bytes);
    debug_assert_eq!(out.len(), MADVR_HEADER);
    out.extend_from_slice(&params);
    let q = |v: f64| ((v.clamp(0.0, 1.0) * 65535.0).round() as u16).to_le_bytes();
    let top = (MADVR_SIDE - 1) as f64;
    for r in 0..MADVR_SIDE {
        for g in 0..MADVR_SIDE {
            for b in 0..MADVR_SIDE {
                let v = lut.apply([r as f64 / top, g as f64 / top, b as f64 / top]);
                out.extend_from_slice(&q(v[2]));
                out.extend_from_slice(&q(v[1]));
                out.extend_from_slice(&q(v[0]));
            }
        }
    }
    out
}

/// A line of numbers, or `None` when one word is not a number.
fn numbers(line: &str) -> Option<Vec<f64>> {
    line.split_whitespace().map(|w| w.parse().ok()).collect()
}

/// Reads a `.cube` or `.3dl` file's text (by `format`); `name` names it in errors.
pub fn read(text: &str, format: Format, name: &str) -> Result<Lut3d> {
    let lut = match format {
        Format::Cube => read_cube(text),
        Format::ThreeDl => read_3dl(text),
        Format::MadVr => Err("madVR .3dlut files are not read (give the .cube or .3dl)".into()),
    };
    lut.map_err(|why| Error::invalid(format!("{name}:"), why))
}

fn read_cube(text: &str) -> std::result::Result<Lut3d, String> {
    let mut size = None;
    let mut title = String::new();
    let mut nodes = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = raw.trim();
        let at = i + 1;
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let word = line.split_whitespace().next().unwrap_or("");
        match word {
            "TITLE" => title = line[5..].trim().trim_matches('"').to_string(),
            "LUT_3D_SIZE" => {
                let n: usize = line[11..].trim().parse().map_err(|_| {
                    format!(
                        "line {at}: LUT_3D_SIZE `{}` is not a whole number",
                        &line[11..]
                    )
                })?;
                if !(2..=READ_SIZE_MAX).contains(&n) {
                    return Err(format!(
                        "line {at}: LUT_3D_SIZE {n} is not 2–{READ_SIZE_MAX}"
                    ));
                }
                size = Some(n);
            }
            "LUT_1D_SIZE" => {
                return Err(format!("line {at}: a 1D LUT (LUT_1D_SIZE), not a 3D LUT"))
            }
            "DOMAIN_MIN" | "DOMAIN_MAX" => {
                let want = if word == "DOMAIN_MIN" { 0.0 } else { 1.0 };
                let v = numbers(&line[10..])
                    .filter(|v| v.len() == 3)
                    .ok_or_else(|| format!("line {at}: {word} needs three numbers"))?;
                if v.iter().any(|x| *x != want) {
                    return Err(format!(
                        "line {at}: {word} {} {} {}: only the domain 0–1 is read",
                        v[0], v[1], v[2]
                    ));
                }
            }
            _ if word.starts_with(|c: char| c.is_ascii_alphabetic()) && !nodes.is_empty() => {
                return Err(format!("line {at}: keyword `{word}` after the table"));
            }
            _ if word.starts_with(|c: char| c.is_ascii_alphabetic()) => {} // other keywords (Resolve's LUT_3D_INPUT_RANGE …) are not ours to read
            _ => {
                let v = numbers(line)
                    .filter(|v| v.len() == 3 && v.iter().all(|x| x.is_finite()))
                    .ok_or_else(|| format!("line {at}: expected three numbers, found `{line}`"))?;
                nodes.push([v[0], v[1], v[2]]);
            }
        }
    }
    let n = size.ok_or("no LUT_3D_SIZE")?;
    if nodes.len() != n * n * n {
        return Err(format!(
            "LUT_3D_SIZE {n} needs {} table lines, found {}",
            n * n * n,
            nodes.len()
        ));
    }
    Lut3d::new_unchecked(n, nodes, &title)
}

fn read_3dl(text: &str) -> std::result::Result<Lut3d, String> {
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let (at, mesh_line) = lines.next().ok_or("no mesh line")?;
    let mesh = numbers(mesh_line).ok_or_else(|| format!("line {at}: the mesh is not numbers"))?;
    let n = mesh.len();
    if !(2..=READ_SIZE_MAX).contains(&n) {
        return Err(format!(
            "line {at}: a mesh of {n} values (2–{READ_SIZE_MAX})"
        ));
    }
    let mut raw = Vec::with_capacity(n * n * n);
    for (at, line) in lines {
        let v = numbers(line)
            .filter(|v| v.len() == 3 && v.iter().all(|x| x.is_finite() && *x >= 0.0))
            .ok_or_else(|| format!("line {at}: expected three whole numbers, found `{line}`"))?;
        raw.push([v[0], v[1], v[2]]);
    }
    if raw.len() != n * n * n {
        return Err(format!(
            "a mesh of {n} needs {} table lines, found {}",
            n * n * n,
            raw.len()
        ));
    }
    // the output depth: the smallest of 10, 12, 14, 16 bits that holds the largest value
    let top = raw.iter().flatten().cloned().fold(0.0, f64::max);
    let full = [10, 12, 14, 16]
        .iter()
        .map(|b| f64::from((1u32 << b) - 1))
        .find(|f| top <= *f)
        .ok_or_else(|| format!("an output value {top} beyond 16 bits"))?;
    // blue fastest in the file; ours red fastest
    let mut nodes = vec![[0.0; 3]; n * n * n];
    for (i, v) in raw.iter().enumerate() {
        let (r, g, b) = (i / (n * n), (i / n) % n, i % n);
        nodes[r + n * (g + n * b)] = v.map(|x| x / full);
    }
    Lut3d::new_unchecked(n, nodes, "")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn meshes_are_lustres() {
        assert_eq!(
            mesh(17),
            vec![0, 64, 128, 192, 256, 320, 384, 448, 512, 576, 640, 704, 768, 832, 896, 960, 1023]
        );
        assert_eq!(mesh(33)[1], 32);
        assert_eq!(*mesh(33).last().unwrap(), 1023);
        assert_eq!(mesh(65)[1], 16);
    }

    #[test]
    fn the_cube_specification_example_is_read() {
        // the shape of the Cube LUT Specification 1.0's example: comments, a title, a domain,
        // a 2³ table, red fastest (this one swaps red and blue)
        let text =
            "# Comment\nTITLE \"swap\"\n\nLUT_3D_SIZE 2\nDOMAIN_MIN 0 0 0\nDOMAIN_MAX 1 1 1\n\
            0 0 0\n0 0 1\n0 1 0\n0 1 1\n1 0 0\n1 0 1\n1 1 0\n1 1 1\n";
        let lut = read(text, Format::Cube, "x.cube").unwrap();
        assert_eq!(lut.title(), "swap");
        assert_eq!(lut.node(1, 0, 0), [0.0, 0.0, 1.0]);
        assert_eq!(lut.node(0, 0, 1), [1.0, 0.0, 0.0]);
        assert_eq!(lut.node(0, 1, 0), [0.0, 1.0, 0.0]);
        for bad in [
            "LUT_3D_SIZE 2\n0 0 0\n",
            "LUT_3D_SIZE 1\n0 0 0\n",
            "LUT_1D_SIZE 2\n0 0 0\n1 1 1\n",
            "LUT_3D_SIZE 2\nDOMAIN_MAX 2 2 2\n",
        ] {
            assert!(read(bad, Format::Cube, "x.cube").is_err(), "{bad}");
        }
    }

    #[test]
    fn a_lustre_3dl_is_read_blue_fastest() {
        // a 2-point mesh, 12-bit outputs, blue fastest: the red input drives the blue output
        let text = "# c\n0 1023\n0 0 0\n0 0 0\n0 4095 0\n0 4095 0\n0 0 4095\n0 0 4095\n0 4095 4095\n0 4095 4095\n";
        let lut = read(text, Format::ThreeDl, "x.3dl").unwrap();
        assert_eq!(lut.node(1, 0, 0), [0.0, 0.0, 1.0]);
        assert_eq!(lut.node(0, 1, 0), [0.0, 1.0, 0.0]);
        assert_eq!(lut.node(0, 0, 1), [0.0, 0.0, 0.0]);
    }
}
