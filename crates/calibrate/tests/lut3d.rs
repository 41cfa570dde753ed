//! 3D LUTs (`specpoly_display::lut3d`) checked in their real consumers and against their
//! formats' specifications.
//!
//! - On every shipped display (data/ti3, the default model fitted on all its readings): a
//!   33³ `.cube` from sRGB (17³ on the Surface, whose 33³ build is slow), applied by Debian's `ffmpeg` (`lut3d`, tetrahedral) and by
//!   OpenColorIO's `ocioconvert --lut` to a 16-bit image of 400 in-gamut source colours
//!   (Halton, off every grid node); the model's prediction of what the display then shows is
//!   compared with the colour the source asks for (`palette`'s CIEDE2000, CIELAB relative to
//!   the display's white). Both consumers must also agree with our own tetrahedral
//!   interpolation of the file's nodes (their reading of the layout).
//! - `.3dl` through both consumers (17³: ffmpeg reads only 17-point `.3dl` files).
//! - The `.cube` and `.3dl` layouts read back by readers written here from the specifications
//!   (Adobe's Cube LUT Specification 1.0: red fastest; Lustre's `.3dl`: a 10-bit mesh line,
//!   12-bit outputs, blue fastest), and madVR's `.3dlut` by a reader of its published header.

use crate::common::displays::{self, de00};
use crate::common::lut3d_consumers as lc;
use specpoly_core::display_model::FULL;
use specpoly_core::{Display, DisplayModel, Transfer, Xyz};
use specpoly_display::lut3d::file::{self, Format};
use specpoly_display::lut3d::source::SourceSpace;
use specpoly_display::lut3d::{build, Lut3d, Options, Target, WhiteMode};

/// The goal at 33³ for in-gamut source colours: mean ΔE00.
const GOAL_MEAN: f64 = 0.3;
/// … and maximum ΔE00.
const GOAL_MAX: f64 = 1.0;
/// Test colours per display.
const COLOURS: usize = 400;

/// ΔE00 of what the display shows for each device triple against what each colour asks for.
fn errors(
    model: &DisplayModel<FULL>,
    white: [f64; 3],
    cols: &[([f64; 3], [f64; 3])],
    devices: &[[f64; 3]],
) -> Vec<f64> {
    cols.iter()
        .zip(devices)
        .map(|((_, want), d)| de00(lc::shown(model, *d), *want, white))
        .collect()
}

/// The largest difference between a consumer's output and our interpolation of the LUT.
fn disagreement(lut: &Lut3d, cols: &[([f64; 3], [f64; 3])], devices: &[[f64; 3]]) -> f64 {
    cols.iter()
        .zip(devices)
        .map(|((c, _), d)| {
            let ours = lut.apply(*c);
            (0..3).map(|i| (ours[i] - d[i]).abs()).fold(0.0, f64::max)
        })
        .fold(0.0, f64::max)
}

/// Fits the shipped display `prefix`, builds its sRGB `.cube` of side `size`, applies it through
/// ffmpeg and OpenColorIO, and checks the displayed colours against `max` (and [`GOAL_MEAN`]).
fn through_consumers(prefix: &str, size: usize, max: f64) {
    let name = displays::shipped_named(prefix);
    let cal = displays::fitted(&name);
    let model = cal.model();
    let opts = Options {
        size,
        ..Options::default()
    };
    let lut = build(model, &name, &opts).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let cube = dir.path().join("display.cube");
    std::fs::write(&cube, file::write(&lut, Format::Cube, opts.source)).unwrap();
    let target = Target::new(model, opts.source, opts.white).unwrap();
    let cols = lc::in_gamut_colours(model, &target, COLOURS);
    assert!(
        cols.len() > COLOURS / 2,
        "{name}: {} in-gamut colours",
        cols.len()
    );
    let image = dir.path().join("colours.ppm");
    lc::write_ppm16(&image, &cols.iter().map(|c| c.0).collect::<Vec<_>>(), 20);
    for (consumer, devices) in [
        ("ffmpeg", lc::ffmpeg_apply(&cube, &image, cols.len())),
        ("OpenColorIO", lc::ocio_apply(&cube, &image, cols.len())),
    ] {
        // the consumer reads the layout as we do: within the file's 6 decimals, 16-bit input
        // and output and its own float arithmetic (OpenColorIO: up to 5 codes of 65535)
        let off = disagreement(&lut, &cols, &devices);
        assert!(
            off < 1e-4,
            "{name}, {consumer}: {off} from our interpolation of the nodes"
        );
        let (mean, worst) = lc::mean_max(&errors(model, target.white(), &cols, &devices));
        eprintln!(
            "{name} through {consumer}: mean {mean:.3}, max {worst:.3} ΔE00 ({} colours)",
            cols.len()
        );
        assert!(mean <= GOAL_MEAN, "{name}, {consumer}: mean ΔE00 {mean}");
        assert!(worst <= max, "{name}, {consumer}: max ΔE00 {worst}");
    }
}

#[test]
fn acer_cube_through_ffmpeg_and_opencolorio() {
    through_consumers("acer", 33, GOAL_MAX);
}

#[test]
fn dell_cube_through_ffmpeg_and_opencolorio() {
    through_consumers("dell", 33, GOAL_MAX);
}

#[test]
fn hp_cube_through_ffmpeg_and_opencolorio() {
    through_consumers("hp", 33, GOAL_MAX);
}

#[test]
fn lenovo_cube_through_ffmpeg_and_opencolorio() {
    through_consumers("lenovo", 33, GOAL_MAX);
}

/// The Surface is tested at 17³ (its 33³ build takes 5–12 s; its figures at 33³ and 65³ are in
/// docs/calibration.md): measured mean 0.17, max 1.87 ΔE00. At 33³ it misses the goal's maximum
/// (1.32 on its darkest colours): its fitted red curve climbs in steps near black (table values
/// 0.0042, 0.0049, 0.0054, then 0.0099 at device 3/63 … 6/63), so its inverse jumps there and no
/// node fit on a 33-point grid follows the jumps; at 65³ it is 0.04 / 0.44.
const SURFACE_MAX_17: f64 = 2.0;

#[test]
fn surface_cube_through_ffmpeg_and_opencolorio() {
    through_consumers("microsoft-surface", 17, SURFACE_MAX_17);
}

/// A display unlike sRGB (wider red, narrower green, gamma 2.4, a bluish black): cheap to
/// invert, asymmetric enough that a transposed layout shows.
fn synthetic() -> DisplayModel<FULL> {
    let d = Display::from_primaries(
        [[0.68, 0.31], [0.28, 0.62], [0.15, 0.07]],
        [30.0, 60.0, 10.0],
        Xyz::new(0.2, 0.2, 0.35),
        [
            Transfer::Gamma(2.4),
            Transfer::Gamma(2.2),
            Transfer::Gamma(2.0),
        ],
    )
    .unwrap();
    DisplayModel::new(d, None)
}

fn synthetic_lut(size: usize) -> Lut3d {
    let opts = Options {
        size,
        ..Options::default()
    };
    build(&synthetic(), "synthetic", &opts).unwrap()
}

#[test]
fn three_dl_through_ffmpeg_and_opencolorio() {
    let lut = synthetic_lut(17);
    let model = synthetic();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("display.3dl");
    std::fs::write(&path, file::write(&lut, Format::ThreeDl, SourceSpace::Srgb)).unwrap();
    let target = Target::new(&model, SourceSpace::Srgb, WhiteMode::Adapt).unwrap();
    let cols = lc::in_gamut_colours(&model, &target, 200);
    let image = dir.path().join("colours.ppm");
    lc::write_ppm16(&image, &cols.iter().map(|c| c.0).collect::<Vec<_>>(), 20);
    // 12-bit outputs (half a step), and ffmpeg's full scale of 4095/4096
    for (consumer, devices, tolerance) in [
        (
            "ffmpeg",
            lc::ffmpeg_apply(&path, &image, cols.len()),
            0.5 / 4095.0 + 1.0 / 4096.0,
        ),
        (
            "OpenColorIO",
            lc::ocio_apply(&path, &image, cols.len()),
            0.5 / 4095.0 + 4e-5,
        ),
    ] {
        let off = disagreement(&lut, &cols, &devices);
        assert!(off < tolerance, "{consumer}: {off} from our interpolation");
        let (mean, worst) = lc::mean_max(&errors(&model, target.white(), &cols, &devices));
        eprintln!(".3dl through {consumer}: mean {mean:.3}, max {worst:.3} ΔE00");
        assert!(mean <= GOAL_MEAN, "{consumer}: mean {mean}");
    }
}

/// The `.cube` text read as Adobe's Cube LUT Specification 1.0 says: `#` comments, keyword lines
/// (`TITLE "…"`, `LUT_3D_SIZE N`, `DOMAIN_MIN`/`DOMAIN_MAX`) before the table, then `N³` lines of
/// three numbers, red changing fastest, then green, then blue. Returns the side and the rows.
fn spec_cube(text: &str) -> (usize, Vec<[f64; 3]>, String) {
    let mut n = 0;
    let mut title = String::new();
    let mut rows = Vec::new();
    for line in text.lines() {
        let t = line.trim();
        if t.is_empty() || t.starts_with('#') {
            continue;
        }
        if let Some(rest) = t.strip_prefix("TITLE") {
            assert!(rows.is_empty(), "TITLE after the table");
            title = rest.trim().to_string();
        } else if let Some(rest) = t.strip_prefix("LUT_3D_SIZE") {
            n = rest.trim().parse().unwrap();
        } else if let Some(rest) = t.strip_prefix("DOMAIN_MIN") {
            assert_eq!(
                rest.split_whitespace()
                    .map(|v| v.parse::<f64>().unwrap())
                    .collect::<Vec<_>>(),
                [0.0; 3]
            );
        } else if let Some(rest) = t.strip_prefix("DOMAIN_MAX") {
            assert_eq!(
                rest.split_whitespace()
                    .map(|v| v.parse::<f64>().unwrap())
                    .collect::<Vec<_>>(),
                [1.0; 3]
            );
        } else {
            let v: Vec<f64> = t.split_whitespace().map(|v| v.parse().unwrap()).collect();
            assert_eq!(v.len(), 3, "{t}");
            rows.push([v[0], v[1], v[2]]);
        }
    }
    assert!((2..=256).contains(&n), "LUT_3D_SIZE {n}");
    assert_eq!(rows.len(), n * n * n);
    (n, rows, title)
}

#[test]
fn cube_and_3dl_layouts_read_as_their_specifications_say() {
    let lut = synthetic_lut(9);
    let n = 9;
    // .cube: row i is node (i mod N, (i / N) mod N, i / N²)
    let text = String::from_utf8(file::write(&lut, Format::Cube, SourceSpace::Srgb)).unwrap();
    let (size, rows, title) = spec_cube(&text);
    assert_eq!(size, n);
    assert!(title.starts_with('"') && title.ends_with('"'), "{title}");
    for (i, row) in rows.iter().enumerate() {
        let node = lut.node(i % n, (i / n) % n, i / (n * n));
        for c in 0..3 {
            assert!(
                (row[c] - node[c]).abs() <= 5e-7,
                "row {i}: {row:?} vs {node:?}"
            );
        }
    }
    // physically: each source primary drives its own device channel most (not transposed)
    for (c, row) in [
        (0, rows[n - 1]),
        (1, rows[n * (n - 1)]),
        (2, rows[n * n * (n - 1)]),
    ] {
        assert!(
            (0..3).all(|k| k == c || row[c] > row[k] + 0.3),
            "primary {c}: {row:?}"
        );
    }
    // .3dl: the first line of numbers is the input mesh (0 … 1023, even steps), then N³ rows of
    // 12-bit integers, row i is node (i / N², (i / N) mod N, i mod N): blue fastest
    let text = String::from_utf8(file::write(&lut, Format::ThreeDl, SourceSpace::Srgb)).unwrap();
    let mut lines = text
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'));
    let mesh: Vec<f64> = lines
        .next()
        .unwrap()
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect();
    assert_eq!(mesh.len(), n);
    assert_eq!((mesh[0], mesh[n - 1]), (0.0, 1023.0));
    for (i, m) in mesh.iter().enumerate() {
        assert!(
            (m - i as f64 * 1023.0 / (n - 1) as f64).abs() <= 1.0,
            "mesh {mesh:?}"
        );
    }
    let rows: Vec<Vec<u32>> = lines
        .map(|l| l.split_whitespace().map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), n * n * n);
    for (i, row) in rows.iter().enumerate() {
        let node = lut.node(i / (n * n), (i / n) % n, i % n);
        for c in 0..3 {
            assert!(row[c] <= 4095);
            assert!(
                (f64::from(row[c]) / 4095.0 - node[c]).abs() <= 0.5 / 4095.0,
                "row {i}"
            );
        }
    }
    // and our own reader (what `verify --lut3d` uses) reads both back
    for (format, tolerance) in [(Format::Cube, 5e-7), (Format::ThreeDl, 0.5 / 4095.0)] {
        let text = String::from_utf8(file::write(&lut, format, SourceSpace::Srgb)).unwrap();
        let back = file::read(&text, format, "x").unwrap();
        for i in 0..n * n * n {
            let (r, g, b) = (i % n, (i / n) % n, i / (n * n));
            let (a, z) = (back.node(r, g, b), lut.node(r, g, b));
            assert!(
                (0..3).all(|c| (a[c] - z[c]).abs() <= tolerance),
                "{format:?} node {i}"
            );
        }
    }
}

fn u32_at(b: &[u8], at: usize) -> u32 {
    u32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]])
}

#[test]
fn madvr_layout_read_from_its_published_header() {
    let lut = synthetic_lut(9);
    let bytes = file::write(&lut, Format::MadVr, SourceSpace::Rec709);
    // struct H3DLUT (little-endian): signature[4], fileVersion, programName[32],
    // programVersion (u64), inputBitDepth[3], inputColorEncoding, outputBitDepth,
    // outputColorEncoding, parametersFileOffset, parametersSize, lutFileOffset,
    // lutCompressionMethod, lutCompressedSize, lutUncompressedSize: 96 bytes
    assert_eq!(&bytes[0..4], b"3DLT");
    assert_eq!(u32_at(&bytes, 4), 1);
    assert!(bytes[8..40].starts_with(b"specpoly"));
    assert_eq!(
        [u32_at(&bytes, 48), u32_at(&bytes, 52), u32_at(&bytes, 56)],
        [8, 8, 8]
    );
    assert_eq!(u32_at(&bytes, 60), 0, "input: RGB");
    assert_eq!(u32_at(&bytes, 64), 16, "16-bit output");
    assert_eq!(u32_at(&bytes, 68), 0, "output: RGB");
    let (p_off, p_len, l_off) = (
        u32_at(&bytes, 72) as usize,
        u32_at(&bytes, 76) as usize,
        u32_at(&bytes, 80) as usize,
    );
    assert_eq!(p_off, 96);
    assert_eq!(u32_at(&bytes, 84), 0, "uncompressed");
    let size = 256usize.pow(3) * 3 * 2;
    assert_eq!([u32_at(&bytes, 88), u32_at(&bytes, 92)], [size as u32; 2]);
    assert_eq!(l_off, p_off + p_len);
    assert_eq!(bytes.len(), l_off + size);
    let params = std::str::from_utf8(&bytes[p_off..p_off + p_len]).unwrap();
    assert!(params.contains("Input_Primaries 0.640000 0.330000 0.300000 0.600000 0.150000 0.060000 0.312700 0.329000"), "{params}");
    assert!(params.contains("Input_Range 0 255") && params.contains("Output_Range 0 255"));
    // entries: red slowest, blue fastest, each B, G, R as u16: the LUT at code/255
    for r in (0..256).step_by(15) {
        for g in (0..256).step_by(17) {
            for b in (0..256).step_by(51) {
                let at = l_off + ((r * 256 + g) * 256 + b) * 6;
                let v = |k: usize| {
                    f64::from(u16::from_le_bytes([
                        bytes[at + 2 * k],
                        bytes[at + 2 * k + 1],
                    ])) / 65535.0
                };
                let want = lut.apply([r, g, b].map(|x| x as f64 / 255.0));
                for (k, c) in [(0, 2), (1, 1), (2, 0)] {
                    assert!(
                        (v(k) - want[c]).abs() <= 0.5 / 65535.0 + 1e-9,
                        "({r}, {g}, {b})"
                    );
                }
            }
        }
    }
}
