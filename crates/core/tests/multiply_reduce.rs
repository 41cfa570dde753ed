//! Properties of multiplication with degree reduction (the paper's §6), by proptest:
//! commutativity, exactness when the product's degree fits, and the reduction error bounded by
//! the dropped Chebyshev coefficients (|Tₖ| ≤ 1 on [-1, 1]).

use proptest::prelude::*;
use specpoly_core::Spectrum;

type S8 = Spectrum<8, 4>;

fn spectrum(max_coeffs: usize) -> impl Strategy<Value = S8> {
    prop::collection::vec(-1.0f32..1.0, 32).prop_map(move |v| {
        let mut s = S8::ZERO;
        for k in 0..4 {
            for sp in 0..8 {
                s.coefficients_mut()[k][sp] = if k < max_coeffs { v[k * 8 + sp] } else { 0.0 };
            }
        }
        s
    })
}

fn grid() -> impl Iterator<Item = f32> {
    (0..=400)
        .map(|i| 380.0 + i as f32 + 0.37)
        .filter(|nm| *nm <= 780.0)
}

proptest! {
    #[test]
    fn multiplication_commutes(a in spectrum(4), b in spectrum(4)) {
        let (ab, ba) = (a.mul(&b), b.mul(&a));
        for k in 0..4 {
            for s in 0..8 {
                let (x, y) = (ab.coefficients()[k][s], ba.coefficients()[k][s]);
                prop_assert!((x - y).abs() <= 1e-6 * (1.0 + x.abs()));
            }
        }
    }

    #[test]
    fn exact_when_the_degree_fits(a in spectrum(2), b in spectrum(3)) {
        // degree 1 × degree 2 = degree 3 fits in 4 coefficients: no reduction error
        let reduced = a.mul(&b);
        for nm in grid() {
            let want = a.eval(nm) as f64 * b.eval(nm) as f64;
            prop_assert!((reduced.eval(nm) as f64 - want).abs() < 1e-5, "{nm}");
        }
    }

    #[test]
    fn reduction_error_is_bounded_by_the_dropped_coefficients(a in spectrum(4), b in spectrum(4)) {
        let exact: Spectrum<8, 7> = a.mul_exact(&b);
        let reduced = a.mul(&b);
        // the kept coefficients of the exact product are the reduced ones
        for k in 0..4 {
            for s in 0..8 {
                prop_assert!((exact.coefficients()[k][s] - reduced.coefficients()[k][s]).abs() < 1e-6);
            }
        }
        for nm in grid() {
            let (s, _) = exact.breaks().locate(nm);
            let bound = exact.span(s).tail_bound(4) + 1e-5;
            let e = (exact.eval(nm) - reduced.eval(nm)).abs();
            prop_assert!(e <= bound, "{nm}: error {e} > bound {bound}");
            // and the exact product is the pointwise product
            let want = a.eval(nm) * b.eval(nm);
            prop_assert!((exact.eval(nm) - want).abs() < 1e-5);
        }
    }

    #[test]
    fn addition_and_scaling_are_pointwise(a in spectrum(4), b in spectrum(4), k in -3.0f32..3.0) {
        let c = a.add(&b.scale(k));
        for nm in grid().step_by(13) {
            prop_assert!((c.eval(nm) - (a.eval(nm) + k * b.eval(nm))).abs() < 1e-5);
        }
    }
}
