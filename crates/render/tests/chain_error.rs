//! How the degree-reduction error grows with the number of products along a path (the path
//! tracer multiplies the throughput by one reflectance per bounce): chains of 1–10 ColorChecker
//! reflectances, each representation's own product, against the 1 nm f64 product of the
//! tabulated reflectances (`colour::reference`). Prints the table of docs/performance.md
//! ("Reduction error along a path") with `--nocapture`.
//!
//! Two families of chains under D65 (CIE 1931):
//! - **same**: one patch `k` times (light bouncing between walls of one colour, as in the
//!   Cornell box) — 24 chains per length;
//! - **mixed**: `k` consecutive patches (cyclic) — 24 chains per length.
//!
//! Long products are dark; each is also compared at a fixed lightness (both colours scaled so
//! the reference has `Y = 50`), which shows the chromatic error the image would show under a
//! light bright enough to see it.

use specpoly_core::{Illuminant, Observer};
use specpoly_spectra::colour::{self, Colour};
use specpoly_spectra::repr::Repr;

fn scaled(c: &Colour, k: f64) -> Colour {
    Colour {
        xyz: c.xyz.map(|v| v * k),
        white: c.white,
    }
}

#[test]
fn reduction_error_grows_slowly_with_the_number_of_products() {
    let named = specpoly_spectra::spectrum_names::resolve("colorchecker#*").unwrap();
    let tabs: Vec<_> = named.iter().map(|n| n.tabulated()).collect();
    let light = Illuminant::D65.tabulated();
    let obs = Observer::Cie1931;
    let modes = [
        Repr::DEFAULT,
        Repr::Paper,
        Repr::Sampled(81),
        Repr::Sampled(16),
        Repr::Rgb,
    ];
    println!("| chain | k | poly | paper | sampled:81 | sampled:16 | rgb |");
    println!("|---|---:|---|---|---|---|---|");
    let mut poly_at = Vec::new();
    let mut rgb_at = Vec::new();
    for family in ["same", "mixed"] {
        for k in 1..=10usize {
            let chains: Vec<Vec<usize>> = (0..24)
                .map(|i| match family {
                    "same" => vec![i; k],
                    _ => (0..k).map(|j| (i + j) % 24).collect(),
                })
                .collect();
            let refs: Vec<Colour> = chains
                .iter()
                .map(|c| colour::reference(obs, &light, &tabs, c))
                .collect();
            let mut cells = Vec::new();
            for m in modes {
                let got = colour::chains(m, obs, &light, &tabs, &chains).unwrap();
                let (mut abs, mut fixed) = (Vec::new(), Vec::new());
                for (g, r) in got.iter().zip(&refs) {
                    abs.push(g.delta_e(r));
                    if r.xyz[1] > 1e-9 {
                        let s = 50.0 / r.xyz[1];
                        fixed.push(scaled(g, s).delta_e(&scaled(r, s)));
                    }
                }
                let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
                let max = |v: &[f64]| v.iter().cloned().fold(0.0, f64::max);
                cells.push(format!(
                    "{:.3} / {:.2} ({:.2} / {:.1})",
                    mean(&abs),
                    max(&abs),
                    mean(&fixed),
                    max(&fixed)
                ));
                if family == "same" && m == Repr::DEFAULT {
                    poly_at.push(mean(&fixed));
                }
                if family == "same" && m == Repr::Rgb {
                    rgb_at.push(mean(&fixed));
                }
            }
            println!("| {family} | {k} | {} |", cells.join(" | "));
        }
    }
    // the default stays well below RGB at every length of repeated bounces, and below one
    // ΔE00 on average at fixed lightness after ten products
    for k in 1..10 {
        assert!(
            poly_at[k] < rgb_at[k],
            "k = {}: {} vs {}",
            k + 1,
            poly_at[k],
            rgb_at[k]
        );
    }
    assert!(poly_at[9] < 1.0, "poly after 10 products: {}", poly_at[9]);
}
