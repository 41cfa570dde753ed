//! The paper, literally, for reproduction and cross-checks only (Raso & Fournier 1991).
//!
//! - Eq. 6, `P₃ = R T M T⁻¹ R⁻¹ P₆`: degree reduction done with matrices on monomial
//!   coefficients in raw nanometres (f64). `R⁻¹` maps a polynomial in λ ∈ [a, b] to one in
//!   `t = (2λ − a − b)/(b − a) ∈ [-1, 1]`, `T⁻¹` maps monomials in `t` to Chebyshev
//!   coefficients, `M` keeps the first `K` of them, and `T`, `R` map back. The crate does the
//!   same thing as a plain truncation of Chebyshev coefficients ([`crate::Spectrum::mul`]); the
//!   tests show both agree.
//! - Eq. 7: the colour matching functions fitted by cubics on the same spans, and the product
//!   with the spectrum integrated analytically. The light is a polynomial fit too, as in the
//!   paper's Optik (§7.1, footnote 9). The crate's own path ([`crate::Moments`]) keeps the
//!   colour matching functions and the light as tabulated data instead.
//!
//! Monomials in raw nanometres are badly conditioned (λ⁶ ≈ 2·10¹⁷ at 780 nm): in f64 this
//! module is good to ~1e-7 relative on the paper's spans; in f32 it would be unusable.

use crate::{Cheb, Layout, Observer, Spectrum, Tabulated, Xyz};

fn binom(n: usize, k: usize) -> f64 {
    let mut r = 1.0;
    for i in 0..k {
        r = r * (n - i) as f64 / (i + 1) as f64;
    }
    r
}

/// `R⁻¹`: monomial coefficients in λ (on `[a, b]`) → monomial coefficients in `t`.
/// With `λ = αt + β`, `λʲ = Σᵢ C(j, i) αⁱ β^(j−i) tⁱ`.
pub fn range_to_unit<const N: usize>(a: f64, b: f64) -> [[f64; N]; N] {
    let (alpha, beta) = (0.5 * (b - a), 0.5 * (a + b));
    let mut m = [[0.0; N]; N];
    for j in 0..N {
        for i in 0..=j {
            m[i][j] = binom(j, i) * libm::pow(alpha, i as f64) * libm::pow(beta, (j - i) as f64);
        }
    }
    m
}

/// `R`: monomial coefficients in `t` → monomial coefficients in λ (on `[a, b]`).
/// With `t = (λ − β)/α`, `tʲ = α⁻ʲ Σᵢ C(j, i) (−β)^(j−i) λⁱ`.
pub fn unit_to_range<const N: usize>(a: f64, b: f64) -> [[f64; N]; N] {
    let (alpha, beta) = (0.5 * (b - a), 0.5 * (a + b));
    let mut m = [[0.0; N]; N];
    for j in 0..N {
        for i in 0..=j {
            m[i][j] = binom(j, i) * libm::pow(-beta, (j - i) as f64) / libm::pow(alpha, j as f64);
        }
    }
    m
}

/// `T`: Chebyshev coefficients → monomial coefficients in `t` (column `k` holds `Tₖ`).
pub fn chebyshev_matrix<const N: usize>() -> [[f64; N]; N] {
    let mut m = [[0.0; N]; N];
    for k in 0..N {
        match k {
            0 => m[0][0] = 1.0,
            1 => m[1][1] = 1.0,
            _ => {
                // Tₖ = 2t·Tₖ₋₁ − Tₖ₋₂
                for i in 0..N {
                    let up = if i > 0 { 2.0 * m[i - 1][k - 1] } else { 0.0 };
                    m[i][k] = up - m[i][k - 2];
                }
            }
        }
    }
    m
}

/// `T⁻¹`: monomial coefficients in `t` → Chebyshev coefficients (T is upper triangular).
pub fn chebyshev_matrix_inverse<const N: usize>() -> [[f64; N]; N] {
    let t = chebyshev_matrix::<N>();
    let mut inv = [[0.0; N]; N];
    // Solve T · X = I column by column, back substitution.
    for col in 0..N {
        for i in (0..N).rev() {
            let mut s = if i == col { 1.0 } else { 0.0 };
            for j in i + 1..N {
                s -= t[i][j] * inv[j][col];
            }
            inv[i][col] = s / t[i][i];
        }
    }
    inv
}

fn matmul<const N: usize>(a: &[[f64; N]; N], b: &[[f64; N]; N]) -> [[f64; N]; N] {
    let mut r = [[0.0; N]; N];
    for i in 0..N {
        for j in 0..N {
            r[i][j] = (0..N).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    r
}

fn matvec<const N: usize>(a: &[[f64; N]; N], x: &[f64; N]) -> [f64; N] {
    let mut r = [0.0; N];
    for (i, v) in r.iter_mut().enumerate() {
        *v = (0..N).map(|k| a[i][k] * x[k]).sum();
    }
    r
}

/// Eq. 6 on one span `[a, b]`: reduces the degree-`N−1` monomial polynomial `p` (raw λ,
/// coefficients low to high) to degree `K − 1`, returning `N` coefficients whose top `N − K`
/// are zero.
pub fn reduce_eq6<const N: usize>(p: &[f64; N], keep: usize, a: f64, b: f64) -> [f64; N] {
    let r = unit_to_range::<N>(a, b);
    let r_inv = range_to_unit::<N>(a, b);
    let t = chebyshev_matrix::<N>();
    let t_inv = chebyshev_matrix_inverse::<N>();
    let mut m = [[0.0; N]; N];
    for (i, row) in m.iter_mut().enumerate().take(keep.min(N)) {
        row[i] = 1.0;
    }
    let op = matmul(&r, &matmul(&t, &matmul(&m, &matmul(&t_inv, &r_inv))));
    let mut out = matvec(&op, p);
    for v in out.iter_mut().skip(keep) {
        *v = 0.0;
    }
    out
}

/// A span's Chebyshev series as monomial coefficients in raw λ (`R T c`), f64.
pub fn to_monomial<const C: usize>(p: &Cheb<C>, a: f64, b: f64) -> [f64; C] {
    let c = p.c.map(|v| v as f64);
    matvec(
        &unit_to_range::<C>(a, b),
        &matvec(&chebyshev_matrix::<C>(), &c),
    )
}

/// Product of two monomial polynomials into `M ≥ N + K − 1` coefficients.
pub fn mul_monomial<const N: usize, const K: usize, const M: usize>(
    p: &[f64; N],
    q: &[f64; K],
) -> [f64; M] {
    let mut r = [0.0; M];
    for (i, a) in p.iter().enumerate() {
        for (j, b) in q.iter().enumerate() {
            if i + j < M {
                r[i + j] += a * b;
            }
        }
    }
    r
}

/// Horner evaluation of monomial coefficients (low to high) at `x`.
pub fn eval_monomial(p: &[f64], x: f64) -> f64 {
    p.iter().rev().fold(0.0, |acc, c| acc * x + c)
}

/// The colour matching functions fitted by `C`-coefficient polynomials on the spans of `L` (the
/// paper's cubic fits of x̄, ȳ, z̄, §5.3).
pub fn cmf_fit<const S: usize, const C: usize, L: Layout<S>>(
    observer: Observer,
) -> [Spectrum<S, C, L>; 3] {
    let fit = |k: usize| Spectrum::fit_fn(|nm| observer.cmf_at(nm)[k]).unwrap_or(Spectrum::ZERO);
    [fit(0), fit(1), fit(2)]
}

/// The paper's whole colour path for a cubic reflectance `r` under a light:
/// the light fitted by cubics on the same spans, `Q = r · light` reduced (the renderer's
/// product), then `X = K ∫ Q x̄ dλ` with x̄ the cubic fit and the degree-6 product integrated
/// analytically (eq. 7), `K = 100 / ∫ light ȳ dλ`.
pub fn xyz_paper_path<const S: usize, L: Layout<S>>(
    observer: Observer,
    light: &Tabulated<'_>,
    r: &Spectrum<S, 4, L>,
) -> Xyz {
    let l = Spectrum::<S, 4, L>::fit(light).unwrap_or(Spectrum::ZERO);
    let cmf = cmf_fit::<S, 4, L>(observer);
    let q = r.mul(&l);
    let integrate = |a: &Spectrum<S, 4, L>, b: &Spectrum<S, 4, L>| a.mul_exact::<7>(b).integral();
    let k = 100.0 / integrate(&l, &cmf[1]);
    Xyz::new(
        k * integrate(&q, &cmf[0]),
        k * integrate(&q, &cmf[1]),
        k * integrate(&q, &cmf[2]),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chebyshev_matrices_are_inverse() {
        let t = chebyshev_matrix::<7>();
        let ti = chebyshev_matrix_inverse::<7>();
        let p = matmul(&t, &ti);
        for (i, row) in p.iter().enumerate() {
            for (j, v) in row.iter().enumerate() {
                assert!((v - if i == j { 1.0 } else { 0.0 }).abs() < 1e-12);
            }
        }
        // T₃ = 4t³ − 3t
        assert_eq!([t[0][3], t[1][3], t[2][3], t[3][3]], [0.0, -3.0, 0.0, 4.0]);
    }

    #[test]
    fn range_matrices_are_inverse() {
        let p = matmul(
            &range_to_unit::<7>(380.0, 550.0),
            &unit_to_range::<7>(380.0, 550.0),
        );
        for (i, row) in p.iter().enumerate() {
            for (j, v) in row.iter().enumerate() {
                assert!(
                    (v - if i == j { 1.0 } else { 0.0 }).abs() < 1e-6,
                    "{i} {j} {v}"
                );
            }
        }
    }
}
