//! Both paths of the kernels — the portable one (this test crate is built for the x86-64
//! baseline, SSE2) and the AVX2 + FMA one where the CPU has it, called directly, in batches and
//! through `Wide`'s run-time choice — agree within [`ULP_BOUND`] (sampled products to the bit),
//! by proptest over random spectra and moments, for the default (8 × cubic) and paper
//! (2 × cubic) presets and sampled-81; and each path agrees with an independent oracle:
//! - the reduced product with the first `C` Chebyshev coefficients of the exact product, found in
//!   f64 by the discrete Chebyshev transform at Chebyshev–Gauss nodes of the two polynomials
//!   evaluated as `Σ cₖ cos(kθ)` (exact for degree < 8: Mason & Handscomb 2003, §4.6), not by the
//!   product formula under test;
//! - →XYZ with an f64 1 nm sum of the polynomial times the light and observer ([`exact_xyz`]);
//! - sampled products with the f64 product rounded once (IEEE: the f32 product is correctly
//!   rounded), sampled →XYZ with an f64 dot product.

use proptest::prelude::*;
use specpoly_core::{
    exact_xyz, DefaultSpectrum, Illuminant, Layout, Moments, Observer, Paper, PaperSpectrum,
    Sampled, SampledLight, Shade, Spectrum, Uniform, Xyz,
};
use specpoly_simd::{Avx2Fma, Kernels, Wide, ULP_BOUND};

/// Error of an f32 kernel against its f64 oracle, relative to the sum of the magnitudes that
/// enter it (a few f32 roundings over ≤ 81 terms: 81 · 2⁻²⁴ ≈ 5·10⁻⁶).
const TOL: f64 = 1e-5;

/// Plus, for results in the subnormal range, 64 of its steps (2⁻¹⁴⁹ each) absolutely.
const SUBNORMAL: f64 = 64.0 * 1.401298464324817e-45;

/// Every path that runs on this CPU: the portable code, `Wide`'s run-time choice and, where the
/// CPU has it, the AVX2 copy called directly.
fn mul_paths<T: Kernels>(a: &T, b: &T) -> Vec<(&'static str, T)> {
    let mut v = vec![
        ("portable", a.mul(b)),
        ("runtime", Wide(*a).mul(&Wide(*b)).0),
    ];
    if let Some(k) = Avx2Fma::detect() {
        v.push(("avx2", T::mul_with(k, a, b)));
        let mut out = [*a];
        T::mul_each(k, &[*a], &[*b], &mut out);
        v.push(("avx2 batch", out[0]));
    }
    v
}

fn xyz_paths<T: Kernels>(a: &T, light: &T::Light) -> Vec<(&'static str, Xyz)> {
    let mut v = vec![("portable", a.xyz(light)), ("runtime", Wide(*a).xyz(light))];
    if let Some(k) = Avx2Fma::detect() {
        v.push(("avx2", T::xyz_with(k, a, light)));
        let mut out = [Xyz::default()];
        T::xyz_each(k, &[*a], light, &mut out);
        v.push(("avx2 batch", out[0]));
    }
    v
}

/// `mul_xyz` (the product kept in registers) on every path: bit for bit that path's product then
/// its →XYZ, as the renderer relies on (its images do not change when it fuses the two).
fn fused_paths_agree<T: Kernels>(a: &T, b: &T, light: &T::Light) -> Result<(), TestCaseError> {
    let bits = |x: Xyz| x.to_array().map(f32::to_bits);
    prop_assert_eq!(
        bits(a.mul_xyz(b, light)),
        bits(a.mul(b).xyz(light)),
        "portable"
    );
    let (wa, wb) = (Wide(*a), Wide(*b));
    prop_assert_eq!(
        bits(wa.mul_xyz(&wb, light)),
        bits(wa.mul(&wb).xyz(light)),
        "runtime"
    );
    if let Some(k) = Avx2Fma::detect() {
        prop_assert_eq!(
            bits(T::mul_xyz_with(k, a, b, light)),
            bits(T::xyz_with(k, &T::mul_with(k, a, b), light)),
            "avx2"
        );
    }
    Ok(())
}

/// `|x − y| ≤ ULP_BOUND · 2⁻²⁴ · terms` (and equal when both are NaN-free and `terms` is 0).
fn within_bound(x: f32, y: f32, terms: f64) -> bool {
    (x as f64 - y as f64).abs() <= ULP_BOUND * f32::EPSILON as f64 / 2.0 * terms + SUBNORMAL
}

/// A coefficient: mostly ordinary values, sometimes ±0, tiny (subnormal products) or large.
fn coef() -> impl Strategy<Value = f32> {
    prop_oneof![
        8 => -2.0f32..2.0,
        1 => Just(0.0f32),
        1 => Just(-0.0f32),
        1 => -1e-20f32..1e-20,
        1 => -1e6f32..1e6,
    ]
}

fn spectrum<const S: usize, const C: usize, L: Layout<S>>(
) -> impl Strategy<Value = Spectrum<S, C, L>> {
    prop::collection::vec(coef(), S * C).prop_map(|v| {
        let mut s = Spectrum::<S, C, L>::ZERO;
        for (i, x) in v.into_iter().enumerate() {
            s.coefficients_mut()[i / S][i % S] = x;
        }
        s
    })
}

fn moments<const S: usize, const C: usize, L: Layout<S>>() -> impl Strategy<Value = Moments<S, C, L>>
{
    prop::collection::vec(-50.0f32..50.0, 3 * S * C).prop_map(|v| {
        let mut m = [[[0.0f32; S]; C]; 3];
        for (i, x) in v.into_iter().enumerate() {
            m[i / (S * C)][(i / S) % C][i % S] = x;
        }
        Moments::from_parts(m, Xyz::new(95.0, 100.0, 108.0))
    })
}

fn sampled() -> impl Strategy<Value = Sampled<81>> {
    prop::collection::vec(coef(), 81).prop_map(|v| Sampled(v.try_into().unwrap()))
}

/// The sum of the magnitudes of the terms of the reduced product's coefficient `k` in span `s`:
/// `½ Σ_{i+j=k} |aᵢbⱼ| + ½ Σ_{|i−j|=k} |aᵢbⱼ|`.
fn product_terms<const S: usize, const C: usize, L: Layout<S>>(
    a: &Spectrum<S, C, L>,
    b: &Spectrum<S, C, L>,
    k: usize,
    s: usize,
) -> f64 {
    let (a, b) = (a.coefficients(), b.coefficients());
    let mut t = 0.0;
    for i in 0..C {
        for j in 0..C {
            let p = 0.5 * (a[i][s] as f64 * b[j][s] as f64).abs();
            if i + j == k {
                t += p;
            }
            if i.abs_diff(j) == k {
                t += p;
            }
        }
    }
    t
}

fn paths_agree_spectra<const S: usize, const C: usize, L: Layout<S>>(
    a: &Spectrum<S, C, L>,
    b: &Spectrum<S, C, L>,
    m: &Moments<S, C, L>,
) -> Result<(), TestCaseError>
where
    Spectrum<S, C, L>: Kernels<Light = Moments<S, C, L>>,
{
    let paths = mul_paths(a, b);
    let portable = paths[0].1;
    for (name, p) in &paths {
        for k in 0..C {
            for s in 0..S {
                let (x, y) = (p.coefficients()[k][s], portable.coefficients()[k][s]);
                prop_assert!(
                    within_bound(x, y, product_terms(a, b, k, s)),
                    "mul, {name} vs portable, T{k} span {s}: {x} vs {y}"
                );
            }
        }
    }
    let paths = xyz_paths(a, m);
    for (name, x) in &paths {
        for axis in 0..3 {
            let mut terms = 0.0;
            for k in 0..C {
                for s in 0..S {
                    terms += (m.moments()[axis][k][s] as f64 * a.coefficients()[k][s] as f64).abs();
                }
            }
            let (g, p) = (x.to_array()[axis], paths[0].1.to_array()[axis]);
            prop_assert!(
                within_bound(g, p, terms),
                "xyz, {name} vs portable, axis {axis}: {g} vs {p}"
            );
        }
    }
    Ok(())
}

proptest! {
    #[test]
    fn default_preset_paths_agree(
        a in spectrum::<8, 4, Uniform>(), b in spectrum::<8, 4, Uniform>(), m in moments::<8, 4, Uniform>()
    ) {
        let (a, b): (DefaultSpectrum, DefaultSpectrum) = (a, b);
        paths_agree_spectra(&a, &b, &m)?;
        fused_paths_agree(&a, &b, &m)?;
    }

    #[test]
    fn paper_preset_paths_agree(
        a in spectrum::<2, 4, Paper>(), b in spectrum::<2, 4, Paper>(), m in moments::<2, 4, Paper>()
    ) {
        let (a, b): (PaperSpectrum, PaperSpectrum) = (a, b);
        paths_agree_spectra(&a, &b, &m)?;
        fused_paths_agree(&a, &b, &m)?;
    }

    #[test]
    fn sampled_81_paths_agree(a in sampled(), b in sampled(), ill in 0..7usize) {
        let light = SampledLight::<81>::new(Observer::Cie1931, &Illuminant::ALL[ill].tabulated());
        let paths = mul_paths(&a, &b);
        for (name, p) in &paths {
            // one multiplication per sample on every path: the same bits
            prop_assert_eq!(p.0.map(f32::to_bits), paths[0].1 .0.map(f32::to_bits), "mul, {}", name);
        }
        fused_paths_agree(&a, &b, &light)?;
        let w = light.weights();
        let paths = xyz_paths(&a, &light);
        for (name, x) in &paths {
            for axis in 0..3 {
                let terms: f64 = (0..81).map(|i| (w[axis][i] as f64 * a.0[i] as f64).abs()).sum();
                let (g, p) = (x.to_array()[axis], paths[0].1.to_array()[axis]);
                prop_assert!(within_bound(g, p, terms), "xyz, {name} vs portable, axis {axis}: {g} vs {p}");
            }
        }
    }

    #[test]
    fn default_product_matches_the_chebyshev_transform(
        a in spectrum::<8, 4, Uniform>(), b in spectrum::<8, 4, Uniform>()
    ) {
        let (a, b): (DefaultSpectrum, DefaultSpectrum) = (a, b);
        product_matches_the_transform(&a, &b)?;
    }

    #[test]
    fn paper_product_matches_the_chebyshev_transform(
        a in spectrum::<2, 4, Paper>(), b in spectrum::<2, 4, Paper>()
    ) {
        let (a, b): (PaperSpectrum, PaperSpectrum) = (a, b);
        product_matches_the_transform(&a, &b)?;
    }

    #[test]
    fn sampled_81_matches_f64(a in sampled(), b in sampled(), ill in 0..7usize) {
        for (name, p) in mul_paths(&a, &b) {
            for i in 0..81 {
                // one IEEE rounding of the exact product
                prop_assert_eq!(p.0[i].to_bits(), ((a.0[i] as f64 * b.0[i] as f64) as f32).to_bits(), "{}", name);
            }
        }
        let light = SampledLight::<81>::new(Observer::Cie1964, &Illuminant::ALL[ill].tabulated());
        let w = light.weights();
        for (name, x) in xyz_paths(&a, &light) {
            for (axis, got) in x.to_array().into_iter().enumerate() {
                let want: f64 = (0..81).map(|i| w[axis][i] as f64 * a.0[i] as f64).sum();
                let scale: f64 = (0..81).map(|i| (w[axis][i] as f64 * a.0[i] as f64).abs()).sum();
                prop_assert!((got as f64 - want).abs() <= TOL * scale + SUBNORMAL, "{name}: axis {axis}: {got} vs {want}");
            }
        }
    }
}

/// `Σₖ cₖ Tₖ(cos θ) = Σₖ cₖ cos kθ`, in f64.
fn eval_trig(c: &[f64], theta: f64) -> f64 {
    c.iter()
        .enumerate()
        .map(|(k, v)| v * (k as f64 * theta).cos())
        .sum()
}

/// Span `s` of `p` as f64 coefficients.
fn span_f64<const S: usize, const C: usize, L: Layout<S>>(
    p: &Spectrum<S, C, L>,
    s: usize,
) -> Vec<f64> {
    (0..C).map(|k| p.coefficients()[k][s] as f64).collect()
}

fn product_matches_the_transform<const S: usize, const C: usize, L: Layout<S>>(
    a: &Spectrum<S, C, L>,
    b: &Spectrum<S, C, L>,
) -> Result<(), TestCaseError>
where
    Spectrum<S, C, L>: Kernels,
{
    // M nodes integrate exactly every product of degree < 2M; the product has degree 2C − 2.
    const M: usize = 8;
    assert!(2 * C - 2 < M);
    for (name, got) in mul_paths(a, b) {
        for s in 0..S {
            let (ca, cb) = (span_f64(a, s), span_f64(b, s));
            let scale: f64 =
                ca.iter().map(|v| v.abs()).sum::<f64>() * cb.iter().map(|v| v.abs()).sum::<f64>();
            for k in 0..C {
                let mut want = 0.0;
                for j in 0..M {
                    let th = std::f64::consts::PI * (j as f64 + 0.5) / M as f64;
                    want += eval_trig(&ca, th) * eval_trig(&cb, th) * (k as f64 * th).cos();
                }
                want *= if k == 0 { 1.0 } else { 2.0 } / M as f64;
                let g = got.coefficients()[k][s] as f64;
                prop_assert!(
                    (g - want).abs() <= TOL * scale + SUBNORMAL,
                    "{name}: span {s}, T{k}: {g} vs {want}"
                );
            }
        }
    }
    Ok(())
}

/// `p(λ)` in f64 (trigonometric form), the mean of the two spans on an interior breakpoint,
/// as the moments weigh it.
fn eval_f64<const S: usize, const C: usize, L: Layout<S>>(p: &Spectrum<S, C, L>, nm: f64) -> f64 {
    let mut sum = 0.0;
    let mut n = 0;
    for s in 0..S {
        let (lo, hi) = L::BREAKS.span(s);
        let (lo, hi) = (lo as f64, hi as f64);
        if nm < lo || nm > hi {
            continue;
        }
        let t = ((2.0 * nm - (lo + hi)) / (hi - lo)).clamp(-1.0, 1.0);
        sum += eval_trig(&span_f64(p, s), t.acos());
        n += 1;
    }
    sum / n as f64
}

fn xyz_matches_the_1nm_sum<const S: usize, const C: usize, L: Layout<S>>(p: &Spectrum<S, C, L>)
where
    Spectrum<S, C, L>: Kernels<Light = Moments<S, C, L>>,
{
    for ill in Illuminant::ALL {
        for obs in [Observer::Cie1931, Observer::Cie1964] {
            let tab = ill.tabulated();
            let m = Moments::<S, C, L>::new(obs, &tab);
            let (want, white) = exact_xyz(obs, &tab, |nm| eval_f64(p, nm));
            // |p(λ)| ≤ Σₖ |cₖ| on every span, so |X| ≤ X_white · that
            let bound = (0..S)
                .map(|s| span_f64(p, s).iter().map(|v| v.abs()).sum::<f64>())
                .fold(0.0, f64::max);
            for (name, got) in xyz_paths(p, &m) {
                for axis in 0..3 {
                    let g = got.to_array()[axis] as f64;
                    assert!(
                        (g - want[axis]).abs() <= TOL * white[axis] * bound,
                        "{name}, {ill:?}, {obs:?}, axis {axis}: {g} vs {}",
                        want[axis]
                    );
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    #[test]
    fn default_xyz_matches_the_1nm_sum(p in spectrum::<8, 4, Uniform>()) {
        let p: DefaultSpectrum = p;
        xyz_matches_the_1nm_sum(&p);
    }

    #[test]
    fn paper_xyz_matches_the_1nm_sum(p in spectrum::<2, 4, Paper>()) {
        let p: PaperSpectrum = p;
        xyz_matches_the_1nm_sum(&p);
    }
}

#[cfg(target_arch = "x86_64")]
#[test]
fn the_avx2_path_runs_where_the_cpu_has_it() {
    let cpu = std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma");
    let forced = std::env::var_os("SPECPOLY_KERNELS").is_some_and(|v| v == "portable");
    assert_eq!(Avx2Fma::detect().is_some(), cpu && !forced);
}
