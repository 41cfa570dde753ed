//! The framebuffer pixel transform (`specpoly_core::pixel`) against an f64 reference computed
//! here, independently, from the calibration's primaries, black and curves (source curve, source
//! and panel matrices from chromaticities, Bradford, gamut map — none of the fixed-point code):
//!
//! - before panel quantisation (the transform's Q8 levels of an RGB888 transform — the 8-bit
//!   tables of the firmware's RGB888 kernel — read as light between adjacent levels): ΔE00 p99
//!   ≤ 0.5 and max ≤ 1.0 over a strided sample of the 2²⁴ inputs (the rounded 8-bit codes'
//!   figures are printed beside them);
//! - after Bayer-dithered RGB565 quantisation: the mean light of every flat 8×8 block within
//!   0.5 ΔE00 of the reference;
//! - the 3-D table (tetrahedral) path on the same panels, as a cross-check.
//!
//! Panels: the shipped Acer LCD (measured 64-point curves, fitted from data/ti3) and a small
//! SPI LCD (narrow gamut, per-channel gammas, bluish white); sources sRGB, Display P3 and linear
//! sRGB; both gamut maps. `SPECPOLY_PIXEL_STRIDE=1` sweeps all 2²⁴ inputs before quantisation
//! and every 3rd code for the dithered blocks (the figures in docs/calibration.md); the default
//! stride 5 (and 15 for blocks) keeps the test to seconds.

use specpoly_calibrate::fit::{fit, FitOptions};
use specpoly_core::delta_e2000_xyz as delta_e00;
use specpoly_core::pixel::{CubeTransform, Dither, Options, PanelTransform, Source, White};
use specpoly_core::GamutMap;
use specpoly_display::calibration::Calibration;
use specpoly_formats::cgats::read_ti3;
use specpoly_tests::pixel::{primaries, spi_lcd, Curve, Panel};

/// The figures: ΔE00 p99 and max before quantisation, and the 8×8 dithered block mean.
const P99_LIMIT: f64 = 0.5;
const MAX_LIMIT: f64 = 1.0;
const BLOCK_LIMIT: f64 = 0.5;

fn acer() -> Panel {
    let t = read_ti3(specpoly_spectra::data::ACER_TI3, "acer.ti3").unwrap();
    let cal: Calibration = fit(&t.best_units().0, &FitOptions::default()).unwrap();
    let d = cal.data();
    let p = d.primaries.array();
    let tables = d.transfer.tables();
    Panel {
        name: "acer-lcd",
        m: primaries(p.map(|p| [p.x, p.y]), p.map(|p| p.luminance)),
        black: d.black,
        curves: [0, 1, 2].map(|c| Curve::Table(tables[c].to_vec())),
        display: cal.display(),
    }
}

fn stride() -> usize {
    std::env::var("SPECPOLY_PIXEL_STRIDE")
        .ok()
        .and_then(|s| s.parse().ok())
        .filter(|s| (1..=255).contains(s))
        .unwrap_or(5)
}

fn codes(step: usize) -> Vec<u8> {
    let mut v: Vec<u8> = (0..=255).step_by(step).map(|c| c as u8).collect();
    if *v.last().unwrap() != 255 {
        v.push(255);
    }
    v
}

struct Stats {
    n: usize,
    mean: f64,
    p99: f64,
    max: f64,
    worst: [u8; 3],
}

fn stats(mut d: Vec<(f64, [u8; 3])>) -> Stats {
    d.sort_by(|a, b| a.0.total_cmp(&b.0));
    let n = d.len();
    Stats {
        n,
        mean: d.iter().map(|x| x.0).sum::<f64>() / n as f64,
        p99: d[(n as f64 * 0.99) as usize - 1].0,
        max: d[n - 1].0,
        worst: d[n - 1].1,
    }
}

#[test]
fn matrix_path_is_within_the_figures_before_quantisation() {
    let step = stride();
    let cs = codes(step);
    for panel in [acer(), spi_lcd()] {
        let white = panel.white();
        for source in Source::ALL {
            for map in [GamutMap::Clip, GamutMap::Desaturate] {
                let opts = Options {
                    source,
                    map,
                    ..Options::default()
                };
                let p = PanelTransform::new(&panel.display, opts).unwrap();
                let mut d = Vec::with_capacity(cs.len().pow(3));
                let mut rounded = Vec::with_capacity(cs.len().pow(3));
                for &r in &cs {
                    for &g in &cs {
                        for &b in &cs {
                            let rgb = [r, g, b];
                            let want = panel.reference(source, White::Adapt, map, rgb);
                            let lv = p.levels(rgb);
                            let got = panel.xyz([0, 1, 2].map(|c| panel.level_light(c, 8, lv[c])));
                            d.push((delta_e00(got, want, white), rgb));
                            // what an RGB888 panel shows (rounded codes, the firmware's
                            // RGB888 kernel): reported, not a figure of the issue
                            let q = p.apply(rgb, 128);
                            let got = panel.xyz(
                                [0, 1, 2].map(|c| panel.level_light(c, 8, (q[c] as u16) << 8)),
                            );
                            rounded.push((delta_e00(got, want, white), rgb));
                        }
                    }
                }
                let q = stats(rounded);
                eprintln!(
                    "{} {} {map:?} RGB888 rounded: ΔE00 mean {:.4} p99 {:.4} max {:.4} at {:?}",
                    panel.name,
                    source.name(),
                    q.mean,
                    q.p99,
                    q.max,
                    q.worst
                );
                let s = stats(d);
                eprintln!(
                    "{} {} {map:?} (stride {step}, {} px): ΔE00 mean {:.4} p99 {:.4} max {:.4} at {:?}",
                    panel.name,
                    source.name(),
                    s.n,
                    s.mean,
                    s.p99,
                    s.max,
                    s.worst
                );
                assert!(
                    s.p99 <= P99_LIMIT && s.max <= MAX_LIMIT,
                    "{} {source:?} {map:?}: p99 {} max {} at {:?}",
                    panel.name,
                    s.p99,
                    s.max,
                    s.worst
                );
            }
        }
    }
}

#[test]
fn absolute_white_matches_the_reference() {
    let panel = spi_lcd();
    let opts = Options {
        white: White::Absolute,
        ..Options::default()
    };
    let p = PanelTransform::new(&panel.display, opts).unwrap();
    let cs = codes(15);
    let mut d = Vec::new();
    for &r in &cs {
        for &g in &cs {
            for &b in &cs {
                let rgb = [r, g, b];
                let want = panel.reference(Source::Srgb, White::Absolute, GamutMap::Clip, rgb);
                let lv = p.levels(rgb);
                let got = panel.xyz([0, 1, 2].map(|c| panel.level_light(c, 8, lv[c])));
                d.push((delta_e00(got, want, panel.white()), rgb));
            }
        }
    }
    let s = stats(d);
    assert!(
        s.p99 <= P99_LIMIT && s.max <= MAX_LIMIT,
        "p99 {} max {}",
        s.p99,
        s.max
    );
}

#[test]
fn dithered_rgb565_blocks_average_to_the_reference() {
    let bits = Options::RGB565;
    let cs = codes(if stride() == 1 { 3 } else { 15 });
    for panel in [acer(), spi_lcd()] {
        let white = panel.white();
        for source in [Source::Srgb, Source::DisplayP3] {
            let opts = Options {
                source,
                bits,
                ..Options::default()
            };
            let p = PanelTransform::new(&panel.display, opts).unwrap();
            let (mut worst, mut worst_rgb, mut sum, mut n) = (0.0f64, [0u8; 3], 0.0, 0);
            let (mut worst_round, mut sum_round) = (0.0f64, 0.0);
            for &r in &cs {
                for &g in &cs {
                    for &b in &cs {
                        let rgb = [r, g, b];
                        let want = panel.reference(source, White::Adapt, GamutMap::Clip, rgb);
                        let block = |dither: Dither| {
                            let mut light = [0.0f64; 3];
                            for y in 0..8 {
                                for x in 0..8 {
                                    let code = p.apply(rgb, dither.threshold(x, y));
                                    for c in 0..3 {
                                        light[c] +=
                                            panel.level_light(c, bits[c], (code[c] as u16) << 8)
                                                / 64.0;
                                    }
                                }
                            }
                            delta_e00(panel.xyz(light), want, white)
                        };
                        let de = block(Dither::Ordered);
                        let de_round = block(Dither::None);
                        sum += de;
                        sum_round += de_round;
                        worst_round = worst_round.max(de_round);
                        n += 1;
                        if de > worst {
                            (worst, worst_rgb) = (de, rgb);
                        }
                    }
                }
            }
            eprintln!(
                "{} {} RGB565 8×8 blocks ({n} colours): dithered ΔE00 mean {:.4} max {worst:.4} at {worst_rgb:?}; rounded mean {:.4} max {worst_round:.4}",
                panel.name,
                source.name(),
                sum / n as f64,
                sum_round / n as f64
            );
            assert!(
                worst <= BLOCK_LIMIT,
                "{} {source:?}: {worst} at {worst_rgb:?}",
                panel.name
            );
            // dithering is what makes the figure: plain rounding is visibly worse
            assert!(
                worst_round > 2.0 * worst,
                "rounded {worst_round} vs dithered {worst}"
            );
        }
    }
}

#[test]
fn cube_path_agrees_with_the_reference() {
    for panel in [acer(), spi_lcd()] {
        let white = panel.white();
        let cube = CubeTransform::<17>::from_display(&panel.display, Options::default()).unwrap();
        let cs = codes(7);
        let mut d = Vec::new();
        for &r in &cs {
            for &g in &cs {
                for &b in &cs {
                    let rgb = [r, g, b];
                    let want = panel.reference(Source::Srgb, White::Adapt, GamutMap::Clip, rgb);
                    let lv = cube.levels(rgb);
                    // the cube's fraction is linear in code value
                    let got = panel.xyz(
                        [0, 1, 2].map(|c| panel.curves[c].decode(lv[c] as f64 / (255.0 * 256.0))),
                    );
                    d.push((delta_e00(got, want, white), rgb));
                }
            }
        }
        let s = stats(d);
        eprintln!(
            "{} srgb cube 17³ tetrahedral: ΔE00 mean {:.4} p99 {:.4} max {:.4} at {:?}",
            panel.name, s.mean, s.p99, s.max, s.worst
        );
        // a 17³ grid on curved data is coarser than the matrix path; its figure is the mean
        assert!(s.mean <= P99_LIMIT, "{}: mean {}", panel.name, s.mean);
    }
}
