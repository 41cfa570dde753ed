//! The display model's fit: every file it writes loads back (a property test over random
//! plausible measurement sets, primaries beyond the chromaticity triangle and bad readings
//! included), the inverse undoes the forward model, primaries outside the triangle are
//! constrained and reported, a bad reading is found and dropped, and files written before
//! the interaction lattice still load.
//!
//! The synthetic displays are an independent forward model written here (primaries from
//! chromaticities, a power law per channel, black, a crosstalk term and readings noise), not
//! the fit's own code.

use proptest::prelude::*;
use specpoly_calibrate::fit::{fit, fit_and_verify, hold_out_indices, FitOptions};
use specpoly_display::calibration::{self, Calibration};
use specpoly_formats::cgats::read_ti3;
use specpoly_formats::measurement::Measurement;

/// A made-up display.
#[derive(Clone, Debug)]
struct Synth {
    /// Primaries' (x, y, Y) at full drive.
    prim: [[f64; 3]; 3],
    gamma: [f64; 3],
    black: [f64; 3],
    /// Crosstalk: each channel's light is scaled by `1 − c·(sum of the others)/2`.
    crosstalk: f64,
}

impl Synth {
    fn xyz(&self, d: [f64; 3]) -> [f64; 3] {
        let l = [0, 1, 2].map(|c| d[c].powf(self.gamma[c]));
        let mut out = self.black;
        for c in 0..3 {
            let others: f64 = (0..3).filter(|k| *k != c).map(|k| d[k]).sum();
            let k = l[c] * (1.0 - self.crosstalk * others / 2.0);
            let [x, y, big_y] = self.prim[c];
            let p = [x / y * big_y, big_y, (1.0 - x - y) / y * big_y];
            for r in 0..3 {
                out[r] += k * p[r];
            }
        }
        out
    }
}

/// A small deterministic generator for noise and patch positions.
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Black, white, `steps`-level ramps and `mixtures` random patches, read with relative noise
/// up to `noise`.
fn readings(s: &Synth, steps: usize, mixtures: usize, noise: f64, seed: u64) -> Vec<Measurement> {
    let mut rng = Lcg(seed);
    let mut dev = vec![[0.0; 3], [1.0; 3]];
    for c in 0..3 {
        for i in 1..steps {
            let mut d = [0.0; 3];
            d[c] = i as f64 / (steps - 1) as f64;
            dev.push(d);
        }
    }
    for _ in 0..mixtures {
        dev.push([rng.next(), rng.next(), rng.next()]);
    }
    dev.into_iter()
        .map(|d| {
            let x = s.xyz(d);
            Measurement {
                device: d,
                xyz: x.map(|v| v * (1.0 + noise * (2.0 * rng.next() - 1.0))),
            }
        })
        .collect()
}

fn srgb_like() -> Synth {
    Synth {
        prim: [[0.64, 0.33, 50.0], [0.30, 0.60, 160.0], [0.15, 0.06, 20.0]],
        gamma: [2.2; 3],
        black: [0.2, 0.21, 0.3],
        crosstalk: 0.0,
    }
}

fn save_and_load(cal: &Calibration) -> Calibration {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("c.toml");
    cal.save(&p).unwrap();
    calibration::load(&p).unwrap_or_else(|e| panic!("the fit wrote a file the loader refuses: {e}"))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    /// fit → save → load never fails, and the loaded model predicts what the fitted one did.
    #[test]
    fn fitted_files_always_load(
        rx in 0.55f64..0.74, ry_sum in 0.96f64..1.004,
        gx in 0.20f64..0.32, gy in 0.55f64..0.74,
        bx in 0.13f64..0.16, by in 0.03f64..0.09,
        ly in (10.0f64..80.0, 50.0f64..250.0, 3.0f64..30.0),
        gamma in (1.6f64..2.8, 1.6f64..2.8, 1.6f64..2.8),
        black in 0.0f64..0.02,
        crosstalk in 0.0f64..0.08,
        steps in 3usize..18,
        mixtures in 0usize..60,
        noise in 0.0f64..0.01,
        flicker in proptest::option::of(0.3f64..0.9),
        seed in any::<u64>(),
    ) {
        let s = Synth {
            prim: [[rx, ry_sum - rx, ly.0], [gx, gy, ly.1], [bx, by, ly.2]],
            gamma: [gamma.0, gamma.1, gamma.2],
            black: [black * 95.0, black * 100.0, black * 108.0],
            crosstalk,
        };
        let mut m = readings(&s, steps, mixtures, noise, seed);
        if let (Some(f), true) = (flicker, m.len() > 5) {
            let i = m.len() - 1;
            m[i].xyz = m[i].xyz.map(|v| v * f);
        }
        let cal = fit(&m, &FitOptions::default()).unwrap();
        let back = save_and_load(&cal);
        prop_assert_eq!(back.data(), cal.data());
        for p in &m {
            prop_assert_eq!(back.predict(p.device), cal.predict(p.device));
        }
    }
}

#[test]
fn primary_beyond_the_locus_is_constrained_and_reported() {
    // red at x + y = 1.003 (negative Z), as a colorimeter reads a deep red
    let mut s = srgb_like();
    s.prim[0] = [0.700, 0.303, 50.0];
    let m = readings(&s, 9, 40, 0.0, 1);
    for matrix in [
        specpoly_calibrate::fit::MatrixFit::Cowan,
        specpoly_calibrate::fit::MatrixFit::LeastSquares,
    ] {
        let opts = FitOptions {
            matrix,
            ..Default::default()
        };
        let cal = fit(&m, &opts).unwrap();
        let c = &cal.data().fit.constrained;
        // the triangle's note, then (the edge x + y = 1 lying just outside the spectral locus
        // there) the locus's
        assert!((1..=2).contains(&c.len()), "{matrix:?}: {c:?}");
        assert!(c[0].contains("red") && c[0].contains("1.003"), "{c:?}");
        assert!(
            c[1..]
                .iter()
                .all(|n| n.contains("red") && n.contains("spectral locus")),
            "{c:?}"
        );
        let r = cal.data().primaries.red;
        assert!(r.x + r.y <= 1.0 + 1e-9, "{r:?}");
        // still near the true primary
        assert!(
            (r.x - 0.700).abs() < 0.01 && (r.y - 0.303).abs() < 0.01,
            "{r:?}"
        );
        save_and_load(&cal);
        // the fit still fits (ΔE00 on its own patches)
        assert!(cal.data().fit.residual.mean < 0.5, "{:?}", cal.data().fit);
    }
}

fn hp() -> Vec<Measurement> {
    let t = read_ti3(
        include_str!("../../../data/ti3/hp-hp-elitebook-835-g7_588.ti3"),
        "hp.ti3",
    )
    .unwrap();
    t.measurements
}

#[test]
fn a_bad_reading_is_found_dropped_and_reported() {
    let m = hp();
    let (fi, hi) = hold_out_indices(&m);
    let mut fit_set: Vec<Measurement> = fi.iter().map(|i| m[*i]).collect();
    let held: Vec<Measurement> = hi.iter().map(|i| m[*i]).collect();
    let opts = FitOptions {
        absolute: false,
        ..Default::default()
    };
    // the real readings: no false alarm
    let clean = fit_and_verify(&fit_set, &held, &opts).unwrap();
    assert!(
        clean.data().fit.outliers.is_empty(),
        "{:?}",
        clean.data().fit.outliers
    );
    // a reading taken while the backlight flickered: 40 % dark, on a mixture patch
    let bad = fit_set
        .iter()
        .position(|p| p.device.iter().all(|v| (0.3..0.9).contains(v)))
        .unwrap();
    fit_set[bad].xyz = fit_set[bad].xyz.map(|v| v * 0.6);
    let robust = fit_and_verify(&fit_set, &held, &opts).unwrap();
    let o = &robust.data().fit.outliers;
    assert_eq!(o.len(), 1, "{o:?}");
    assert_eq!(o[0].patch, bad + 1);
    assert_eq!(o[0].device, fit_set[bad].device);
    assert!(o[0].reason.contains("flicker"), "{}", o[0].reason);
    assert_eq!(robust.data().provenance.patches_fit, fit_set.len() - 1);
    let naive = fit_and_verify(
        &fit_set,
        &held,
        &FitOptions {
            robust: false,
            ..opts
        },
    )
    .unwrap();
    let (r, n, c) = (
        robust.data().fit.verification.unwrap().mean,
        naive.data().fit.verification.unwrap().mean,
        clean.data().fit.verification.unwrap().mean,
    );
    eprintln!("held-out mean: clean {c:.4}, with the bad reading {n:.4}, dropped {r:.4}");
    assert!(r < n, "dropping it helps: {r} vs {n}");
    assert!((r - c).abs() < 0.01, "as good as without it: {r} vs {c}");
}

#[test]
fn inverse_undoes_predict() {
    // a display with interaction (the TN laptop), and one without
    let t = read_ti3(
        include_str!("../../../data/ti3/lenovo-thinkpad-x61_825.ti3"),
        "lenovo.ti3",
    )
    .unwrap();
    let opts = FitOptions {
        absolute: false,
        ..Default::default()
    };
    let with = fit(&t.measurements, &opts).unwrap();
    assert!(with.has_interaction(), "{}", with.data().fit.model);
    let without = fit(
        &readings(&srgb_like(), 9, 0, 0.0, 2),
        &FitOptions::default(),
    )
    .unwrap();
    assert!(!without.has_interaction());
    for cal in [&with, &without] {
        let wy = cal.data().white[1];
        let mut worst: f64 = 0.0;
        for i in 0..6 {
            for j in 0..6 {
                for k in 0..6 {
                    let rgb = [i, j, k].map(|v| 0.05 + 0.18 * v as f64);
                    let xyz = cal.predict(rgb);
                    let back = cal.inverse(xyz);
                    let again = cal.predict(back);
                    for r in 0..3 {
                        worst = worst.max((again[r] - xyz[r]).abs() / wy);
                    }
                    for c in 0..3 {
                        assert!((back[c] - rgb[c]).abs() < 1e-3, "{rgb:?} → {back:?}");
                    }
                }
            }
        }
        // predict runs in f32 (specpoly-core), the inverse's model in f64
        assert!(worst < 1e-6, "{} {worst}", cal.data().fit.model);
    }
}

#[test]
fn files_without_the_new_keys_load() {
    let text = r#"
format = "specpoly-calibration"
version = 1
units = "cd/m2"
black = [0.1, 0.1, 0.2]
white = [95.0, 100.0, 108.0]
[primaries.red]
x = 0.64
y = 0.33
Y = 21.0
[primaries.green]
x = 0.30
y = 0.60
Y = 72.0
[primaries.blue]
x = 0.15
y = 0.06
Y = 6.9
[transfer]
kind = "gamma"
gamma = [2.2, 2.2, 2.2]
red = [0.0, 1.0]
green = [0.0, 1.0]
blue = [0.0, 1.0]
[fit]
matrix = "cowan"
residual = { patches = 0, mean = 0.0, p95 = 0.0, max = 0.0 }
[provenance]
source = "hand"
created = "2026-01-01T00:00:00Z"
patches_total = 0
patches_fit = 0
patches_verify = 0
"#;
    let cal = Calibration::from_toml(text, "old.toml").unwrap();
    assert!(!cal.has_interaction());
    assert!(cal.data().fit.outliers.is_empty() && cal.data().fit.model.is_empty());
    // and a lattice of the wrong size is refused, in one line
    let bad = format!("{text}\n[interaction]\ngrid = 3\nvalues = [[0.0, 0.0, 0.0]]\n");
    let e = Calibration::from_toml(&bad, "bad.toml")
        .unwrap_err()
        .to_string();
    assert!(e.contains("interaction") && !e.contains('\n'), "{e}");
}
