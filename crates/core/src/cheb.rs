//! A Chebyshev series on `[-1, 1]` with a fixed number of coefficients.
//!
//! `p(t) = Σₖ cₖ Tₖ(t)` with `T₀ = 1`, `T₁ = t`, `Tₖ₊₁ = 2t·Tₖ − Tₖ₋₁`, coefficients low to high.
//!
//! Why Chebyshev: the paper (Raso & Fournier 1991, §6.1, eq. 6) reduces a product's degree by
//! converting to the Chebyshev basis, dropping the high coefficients and converting back. Kept in
//! that basis throughout, the reduction *is* a truncation and costs nothing, and since
//! `|Tₖ(t)| ≤ 1` on `[-1, 1]` the error of dropping coefficients is bounded by the sum of their
//! magnitudes (Fox & Parker 1968, ch. 3). Coefficients of a smooth function decay fast, so f32
//! suffices, where monomials in raw nanometres (λ³ ≈ 4.7·10⁸) would not.
//!
//! The product uses `Tᵢ·Tⱼ = ½(Tᵢ₊ⱼ + T|ᵢ₋ⱼ|)` (Mason & Handscomb 2003, §2.4.1).

/// A Chebyshev series with `N` coefficients (degree `N − 1`) on `[-1, 1]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cheb<const N: usize> {
    /// Coefficients of `T₀ … T_{N−1}`, low to high.
    pub c: [f32; N],
}

impl<const N: usize> Default for Cheb<N> {
    fn default() -> Self {
        Self::ZERO
    }
}

impl<const N: usize> Cheb<N> {
    /// The zero series.
    pub const ZERO: Self = Self { c: [0.0; N] };

    /// A constant series `v`.
    pub const fn constant(v: f32) -> Self {
        let mut c = [0.0; N];
        if N > 0 {
            c[0] = v;
        }
        Self { c }
    }

    /// Evaluates at `t ∈ [-1, 1]` by Clenshaw's recurrence.
    #[inline]
    pub fn eval(&self, t: f32) -> f32 {
        let (mut b1, mut b2) = (0.0f32, 0.0f32);
        let t2 = 2.0 * t;
        let mut k = N;
        while k > 1 {
            k -= 1;
            let b0 = self.c[k] + t2 * b1 - b2;
            b2 = b1;
            b1 = b0;
        }
        if N == 0 {
            0.0
        } else {
            self.c[0] + t * b1 - b2
        }
    }

    /// Sum of two series.
    #[inline]
    pub fn add(&self, o: &Self) -> Self {
        let mut c = self.c;
        for (a, b) in c.iter_mut().zip(o.c.iter()) {
            *a += b;
        }
        Self { c }
    }

    /// The series times a scalar.
    #[inline]
    pub fn scale(&self, k: f32) -> Self {
        let mut c = self.c;
        for a in c.iter_mut() {
            *a *= k;
        }
        Self { c }
    }

    /// Product truncated to `N` coefficients: the paper's eq. 6 (degree reduction) done in the
    /// Chebyshev basis, where it is the exact product with the terms of degree ≥ `N` dropped.
    ///
    /// Only the kept coefficients are computed: for output `k`,
    /// `cₖ = ½ Σ_{i+j=k} aᵢbⱼ + ½ Σ_{|i−j|=k} aᵢbⱼ`.
    #[inline]
    pub fn mul_truncated(&self, o: &Self) -> Self {
        let a = &self.c;
        let b = &o.c;
        let mut c = [0.0f32; N];
        for i in 0..N {
            for j in 0..N {
                let p = 0.5 * a[i] * b[j];
                let s = i + j;
                if s < N {
                    c[s] += p;
                }
                let d = i.abs_diff(j);
                // d < N always
                c[d] += p;
            }
        }
        Self { c }
    }

    /// The exact product, of degree `2(N−1)`, into a series with `M ≥ 2N − 1` coefficients
    /// (checked at compile time).
    pub fn mul_exact<const M: usize>(&self, o: &Self) -> Cheb<M> {
        const { assert!(M + 1 >= 2 * N, "mul_exact needs M >= 2N - 1 coefficients") };
        let mut c = [0.0f32; M];
        for i in 0..N {
            for j in 0..N {
                let p = 0.5 * self.c[i] * o.c[j];
                c[i + j] += p;
                c[i.abs_diff(j)] += p;
            }
        }
        Cheb { c }
    }

    /// Keeps the first `K` coefficients (`K ≤ N` or zero-pads when `K > N`).
    pub fn resize<const K: usize>(&self) -> Cheb<K> {
        let mut c = [0.0f32; K];
        for (d, s) in c.iter_mut().zip(self.c.iter()) {
            *d = *s;
        }
        Cheb { c }
    }

    /// Bound on `max_{t∈[-1,1]} |p(t) − truncate_K(p)(t)|`: the sum of the dropped magnitudes.
    pub fn tail_bound(&self, keep: usize) -> f32 {
        self.c.iter().skip(keep).map(|v| v.abs()).sum()
    }

    /// `∫₋₁¹ p(t) dt = Σ cₖ · 2/(1 − k²)` over even `k` (odd terms integrate to zero).
    pub fn integral(&self) -> f32 {
        let mut s = 0.0;
        let mut k = 0;
        while k < N {
            s += self.c[k] * basis_integral(k) as f32;
            k += 2;
        }
        s
    }
}

/// `∫₋₁¹ Tₖ(t) dt`: `2/(1 − k²)` for even `k`, 0 for odd `k`.
pub fn basis_integral(k: usize) -> f64 {
    if k % 2 == 1 {
        0.0
    } else {
        let k = k as f64;
        2.0 / (1.0 - k * k)
    }
}

/// Evaluates `T₀(t) … T_{N−1}(t)` into `out` (f64, used by fitting and moments).
#[inline]
pub fn basis_f64<const N: usize>(t: f64, out: &mut [f64; N]) {
    if N == 0 {
        return;
    }
    out[0] = 1.0;
    if N > 1 {
        out[1] = t;
    }
    let mut k = 2;
    while k < N {
        out[k] = 2.0 * t * out[k - 1] - out[k - 2];
        k += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cheb_direct(c: &[f32], t: f64) -> f64 {
        // Tₖ(cos θ) = cos kθ
        let th = libm::acos(t);
        c.iter()
            .enumerate()
            .map(|(k, v)| *v as f64 * libm::cos(k as f64 * th))
            .sum()
    }

    #[test]
    fn clenshaw_matches_trigonometric_definition() {
        let p = Cheb::<5> {
            c: [0.3, -1.2, 0.7, 0.25, -0.05],
        };
        for i in 0..=20 {
            let t = -1.0 + i as f64 * 0.1;
            assert!((p.eval(t as f32) as f64 - cheb_direct(&p.c, t)).abs() < 1e-5);
        }
    }

    #[test]
    fn integral_of_t2_is_minus_two_thirds() {
        let p = Cheb::<3> { c: [0.0, 0.0, 1.0] };
        assert!((p.integral() + 2.0 / 3.0).abs() < 1e-7);
    }
}
