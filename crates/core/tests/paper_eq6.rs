//! The paper's eq. 6 computed literally (monomials in raw nanometres, R T M T⁻¹ R⁻¹, f64)
//! equals the crate's Chebyshev truncation, span by span.

use proptest::prelude::*;
use specpoly_core::paper::{eval_monomial, mul_monomial, reduce_eq6, to_monomial};
use specpoly_core::{PaperSpectrum, PAPER_BREAKS};

fn cubic() -> impl Strategy<Value = PaperSpectrum> {
    prop::collection::vec(-1.0f32..1.0, 8).prop_map(|v| {
        let mut s = PaperSpectrum::ZERO;
        for k in 0..4 {
            for sp in 0..2 {
                s.coefficients_mut()[k][sp] = v[k * 2 + sp];
            }
        }
        s
    })
}

proptest! {
    #[test]
    fn eq6_equals_chebyshev_truncation(a in cubic(), b in cubic()) {
        let reduced = a.mul(&b);
        for s in 0..2 {
            let (lo, hi) = PAPER_BREAKS.span(s);
            let (lo, hi) = (lo as f64, hi as f64);
            let pa = to_monomial(&a.span(s), lo, hi);
            let pb = to_monomial(&b.span(s), lo, hi);
            let p6: [f64; 7] = mul_monomial(&pa, &pb);
            let p3 = reduce_eq6(&p6, 4, lo, hi);
            prop_assert!(p3[4..].iter().all(|v| *v == 0.0));
            for i in 0..=20 {
                let nm = lo + (hi - lo) * i as f64 / 20.0;
                let t = (2.0 * nm - (lo + hi)) / (hi - lo);
                let want = reduced.span(s).eval(t as f32) as f64;
                let got = eval_monomial(&p3, nm);
                // raw-λ monomials lose ~7 digits to cancellation (λ⁶ ≈ 2e17): compare to 1e-6
                prop_assert!((got - want).abs() < 1e-5, "span {s}, {nm} nm: eq.6 {got} vs {want}");
            }
        }
    }
}
