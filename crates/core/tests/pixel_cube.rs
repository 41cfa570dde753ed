//! The tetrahedral 3-D table against f64 functions evaluated here: exact (to the Q8 rounding)
//! for a function affine in the source codes, and within the interpolation bound for a smooth
//! panel model with an interaction term between channels.

use specpoly_core::pixel::CubeTransform;

/// Q8 levels of a device value at 8 bits.
fn q8(d: f64) -> f64 {
    d.clamp(0.0, 1.0) * 255.0 * 256.0
}

/// One node's rounding (½ of a Q8 step) plus the position's Q12 rounding (≤ 1/8192 of a cell)
/// times the largest slope (0.8 of full scale per unit: 0.8 · 255 · 256 / 8 / 8192 ≈ 0.8), plus
/// the result's rounding (½), in Q8 levels.
const AFFINE_TOL: f64 = 2.0;

#[test]
fn affine_functions_are_reproduced() {
    let f = |c: [f64; 3]| {
        [
            0.1 + 0.5 * c[0] + 0.2 * c[1] + 0.1 * c[2],
            0.9 - 0.3 * c[0] + 0.1 * c[2],
            0.25 * c[0] + 0.25 * c[1] + 0.5 * c[2],
        ]
    };
    let cube = CubeTransform::<9>::from_fn([8; 3], f).unwrap();
    let mut worst = 0.0f64;
    for r in (0..=255).step_by(3) {
        for g in (0..=255).step_by(5) {
            for b in (0..=255).step_by(7) {
                let want = f([r, g, b].map(|v| v as f64 / 255.0));
                let got = cube.levels([r as u8, g as u8, b as u8]);
                for c in 0..3 {
                    worst = worst.max((got[c] as f64 - q8(want[c])).abs());
                }
            }
        }
    }
    assert!(worst <= AFFINE_TOL, "worst {worst} Q8 levels");
}

#[test]
fn interaction_model_within_the_interpolation_bound() {
    // gamma-2.2 encoding of a mixed drive with a product (interaction) term, inside [0, 1]
    let f = |c: [f64; 3]| {
        let l = c.map(|v| v.powf(2.2));
        let mix = [
            0.88 * l[0] + 0.04 * l[1] + 0.08 * l[0] * l[1],
            0.05 * l[0] + 0.85 * l[1] + 0.1 * l[2] - 0.05 * l[1] * l[2],
            0.02 * l[1] + 0.94 * l[2] + 0.03 * l[0] * l[2],
        ];
        mix.map(|v| v.clamp(0.0, 1.0).powf(1.0 / 2.2))
    };
    let cube = CubeTransform::<17>::from_fn([8; 3], f).unwrap();
    let fine = CubeTransform::<33>::from_fn([8; 3], f).unwrap();
    // the nodes are the function, rounded
    for i in [0usize, 5, 16] {
        for j in [0usize, 8, 16] {
            let want = f([i as f64 / 16.0, j as f64 / 16.0, 0.5]);
            let got = cube.node(i, j, 8);
            for c in 0..3 {
                assert!((got[c] as f64 - q8(want[c])).abs() <= 0.5 + 1e-9);
            }
        }
    }
    // between nodes: piecewise-linear interpolation is second order, so halving the cell
    // (17³ → 33³) must cut the error about four times where the function is smooth (away from
    // the dark faces, where x^(1/2.2) is not)
    let error = |levels: &dyn Fn([u8; 3]) -> [u16; 3]| {
        let (mut worst, mut sum, mut n) = (0.0f64, 0.0, 0);
        for r in (32..=255).step_by(3) {
            for g in (32..=255).step_by(5) {
                for b in (32..=255).step_by(7) {
                    let want = f([r, g, b].map(|v| v as f64 / 255.0));
                    let got = levels([r as u8, g as u8, b as u8]);
                    for c in 0..3 {
                        let e = (got[c] as f64 - q8(want[c])).abs() / (255.0 * 256.0);
                        worst = worst.max(e);
                        sum += e;
                        n += 1;
                    }
                }
            }
        }
        (worst, sum / n as f64)
    };
    let (w17, m17) = error(&|c| cube.levels(c));
    let (w33, m33) = error(&|c| fine.levels(c));
    eprintln!(
        "17³: worst {w17:.5} mean {m17:.6}; 33³: worst {w33:.5} mean {m33:.6} (of full scale)"
    );
    assert!(w17 < 0.003 && m17 < 0.0003, "17³: {w17} {m17}");
    assert!(
        w33 < w17 / 2.5 && m33 < m17 / 2.5,
        "not second order: {w17} {m17} → {w33} {m33}"
    );
}
