//! The full display model's inverse (the core's `DisplayModel::inverse`, behind
//! `Calibration::inverse`, `render --display` and `xyz --display`) on every real display we
//! ship (data/ti3, see data/README.md), each fitted with the default model (its interaction
//! lattice where cross-validation keeps one): for a dense grid of device RGB, the colour the
//! model predicts is inverted and predicted again, and the two must agree within
//! [`ROUND_TRIP_DE`].
//!
//! The oracle is independent of the code under test: the model is evaluated here in f64 from
//! the calibration file's own numbers (tables interpolated linearly, `M` from the primaries'
//! `x, y, Y`, the lattice trilinearly), and ΔE00 is `palette`'s CIEDE2000 (CIELAB relative to
//! the model's white).

use crate::common::displays;

use displays::{de00, fitted, shipped, shipped_named};
use proptest::prelude::*;
use specpoly_core::Xyz;
use specpoly_display::calibration::{Calibration, TransferKind};
use std::sync::OnceLock;

/// The round trip's tolerance: predicted(inverse(w)) against w, ΔE00 (the core's
/// `INVERSE_DE` is half of it, so that its f32 evaluation stays inside).
const ROUND_TRIP_DE: f64 = 0.001;

/// Grid points per side of device RGB (dense near 0, where curves are flat: `(i/(n−1))^1.5`).
const GRID: usize = 13;

/// The model in f64 from the file's numbers.
fn oracle(cal: &Calibration, rgb: [f64; 3]) -> [f64; 3] {
    let d = cal.data();
    let v = rgb.map(|v| v.clamp(0.0, 1.0));
    let t = &d.transfer;
    let lin = [0, 1, 2].map(|c| match t.kind {
        TransferKind::Gamma => v[c].powf(t.gamma[c]),
        TransferKind::Table => {
            let tab = t.tables()[c];
            let x = v[c] * (tab.len() - 1) as f64;
            let i = (x.floor() as usize).min(tab.len() - 2);
            tab[i] + (tab[i + 1] - tab[i]) * (x - i as f64)
        }
    });
    let p = d.primaries.array().map(|p| {
        let k = p.luminance / p.y;
        [p.x * k, p.luminance, (1.0 - p.x - p.y) * k]
    });
    let mut out = [0, 1, 2].map(|r| d.black[r] + (0..3).map(|c| p[c][r] * lin[c]).sum::<f64>());
    if let Some(l) = &d.interaction {
        let g = l.grid;
        let x = v.map(|c| c * (g - 1) as f64);
        let j = x.map(|c| (c.floor() as usize).min(g - 2));
        for a in 0..2 {
            for b in 0..2 {
                for e in 0..2 {
                    let s = [a, b, e];
                    let w: f64 = (0..3)
                        .map(|c| {
                            let f = x[c] - j[c] as f64;
                            if s[c] == 1 {
                                f
                            } else {
                                1.0 - f
                            }
                        })
                        .product();
                    let node = l.values[((j[0] + a) * g + j[1] + b) * g + j[2] + e];
                    for r in 0..3 {
                        out[r] += w * node[r];
                    }
                }
            }
        }
    }
    out
}

/// ΔE00 of the round trip from device values `rgb`, and the solver's iterations and starts.
fn round_trip(cal: &Calibration, rgb: [f64; 3]) -> (f64, u32, u32) {
    let w = oracle(cal, rgb);
    let s = cal.model().inverse(Xyz::from_array(w.map(|v| v as f32)));
    let back = oracle(cal, s.device.map(f64::from));
    let white = oracle(cal, [1.0; 3]);
    (de00(back, w, white), s.iterations, s.starts)
}

#[test]
fn every_shipped_display_inverts_exactly_on_a_dense_grid() {
    let mut lattices = 0;
    let mut misses = Vec::new();
    for name in shipped() {
        let name = name.as_str();
        let cal = fitted(name);
        lattices += usize::from(cal.has_interaction());
        let (mut worst, mut iters, mut most_iters, mut restarted, mut n) =
            (0.0f64, 0u64, 0u32, 0usize, 0usize);
        for i in 0..GRID {
            for j in 0..GRID {
                for k in 0..GRID {
                    let rgb = [i, j, k].map(|v| (v as f64 / (GRID - 1) as f64).powf(1.5));
                    let (de, it, starts) = round_trip(&cal, rgb);
                    if de > ROUND_TRIP_DE {
                        let what = format!("{name}: device {rgb:?} comes back {de:.4} ΔE00 off");
                        misses.push(what);
                    }
                    worst = worst.max(de);
                    iters += it as u64;
                    most_iters = most_iters.max(it);
                    restarted += usize::from(starts > 1);
                    n += 1;
                }
            }
        }
        eprintln!(
            "{name} ({}): {n} colours, max ΔE00 {worst:.5}, mean iterations {:.2}, max {most_iters}, restarted {restarted}, misses so far {}",
            cal.data().fit.model,
            iters as f64 / n as f64,
            misses.len()
        );
    }
    assert!(lattices >= 3, "the shipped displays' fits keep lattices");
    assert!(misses.is_empty(), "{} misses: {misses:#?}", misses.len());
}

fn surface() -> &'static Calibration {
    static CAL: OnceLock<Calibration> = OnceLock::new();
    CAL.get_or_init(|| fitted(&shipped_named("microsoft-surface")))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]
    /// Any device colour of the Surface (its lattice 9, red flat at the foot, the hardest of
    /// the shipped displays) comes back within [`ROUND_TRIP_DE`].
    #[test]
    fn any_device_colour_comes_back(r in 0.0f64..=1.0, g in 0.0f64..=1.0, b in 0.0f64..=1.0) {
        let (de, _, _) = round_trip(surface(), [r, g, b]);
        prop_assert!(de <= ROUND_TRIP_DE, "({r}, {g}, {b}): {de}");
    }
}
