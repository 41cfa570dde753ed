//! A 3×3 matrix for colour-space conversions (row-major, `y = M x`), in f32 (the kernels, the
//! firmware) or f64 (the host's ICC profiles, CIECAM02, test references): one type,
//! [`Mat3<T>`], over the crate's two component types ([`Real`]). Products and the inverse
//! differ by component type where the precision asks for it: an f32 product sums in f64, the
//! f32 inverse refines the adjugate by a Newton step summed with its rounding errors (no f64),
//! the f64 inverse is the adjugate alone.

use crate::Error;
use core::fmt::Debug;
use core::ops::{Add, Div, Mul, Neg, Sub};

/// The crate's two component types, f32 (kernels) and f64 (the host's edges): what
/// [`Mat3`] and [`Xyz`](crate::Xyz) are generic over. Sealed: implemented for `f32` and `f64`
/// only.
pub trait Real:
    Copy
    + Default
    + Debug
    + PartialOrd
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + sealed::Sealed
{
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// 1/3 (the equal-energy chromaticity).
    const THIRD: Self;
    /// From f64 (rounded to nearest for f32).
    fn from_f64(v: f64) -> Self;
    /// To f64 (exact).
    fn to_f64(self) -> f64;
    /// `a · b` of two 3-vectors: the entries of [`Mat3::mul`]. f32 sums the products in f64
    /// and rounds once.
    fn dot3(a: [Self; 3], b: [Self; 3]) -> Self;
    /// The inverse of a 3×3 matrix, or [`Error::Singular`] ([`Mat3::inverse`]).
    fn inverse3(m: &[[Self; 3]; 3]) -> Result<[[Self; 3]; 3], Error>;
}

mod sealed {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
}

/// A 3×3 matrix, row-major, of f32 (the default: the kernels' type) or f64.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mat3<T = f32>(pub [[T; 3]; 3]);

impl<T: Real> Mat3<T> {
    /// The identity.
    pub const IDENTITY: Mat3<T> = Mat3([
        [T::ONE, T::ZERO, T::ZERO],
        [T::ZERO, T::ONE, T::ZERO],
        [T::ZERO, T::ZERO, T::ONE],
    ]);

    /// `diag(d)`.
    pub fn diagonal(d: [T; 3]) -> Mat3<T> {
        Mat3([
            [d[0], T::ZERO, T::ZERO],
            [T::ZERO, d[1], T::ZERO],
            [T::ZERO, T::ZERO, d[2]],
        ])
    }

    /// `M x`.
    #[inline]
    pub fn apply(&self, x: [T; 3]) -> [T; 3] {
        let m = &self.0;
        [
            m[0][0] * x[0] + m[0][1] * x[1] + m[0][2] * x[2],
            m[1][0] * x[0] + m[1][1] * x[1] + m[1][2] * x[2],
            m[2][0] * x[0] + m[2][1] * x[1] + m[2][2] * x[2],
        ]
    }

    /// `self · o` (f32: each entry summed in f64, [`Real::dot3`]).
    pub fn mul(&self, o: &Mat3<T>) -> Mat3<T> {
        let col = |j: usize| [o.0[0][j], o.0[1][j], o.0[2][j]];
        Mat3([0, 1, 2].map(|i| [0, 1, 2].map(|j| T::dot3(self.0[i], col(j)))))
    }

    /// The inverse, or [`Error::Singular`]. f32: in f32 alone, refined (see the `Real` impl
    /// for f32); f64: the adjugate over the determinant, singular when the determinant is not
    /// finite or below 10⁻³⁰⁰ in magnitude.
    pub fn inverse(&self) -> Result<Mat3<T>, Error> {
        T::inverse3(&self.0).map(Mat3)
    }

    /// Each entry converted to `U` (f64 → f32 rounds to nearest).
    pub fn cast<U: Real>(&self) -> Mat3<U> {
        Mat3(self.0.map(|r| r.map(|v| U::from_f64(v.to_f64()))))
    }
}

impl Real for f32 {
    const ZERO: f32 = 0.0;
    const ONE: f32 = 1.0;
    const THIRD: f32 = 1.0 / 3.0;
    #[inline]
    fn from_f64(v: f64) -> f32 {
        v as f32
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self as f64
    }
    #[inline]
    fn dot3(a: [f32; 3], b: [f32; 3]) -> f32 {
        (0..3).map(|k| a[k] as f64 * b[k] as f64).sum::<f64>() as f32
    }

    /// The inverse in f32 alone (no soft f64 on a single-precision
    /// FPU, e.g. the Cortex-M4F firmware, where f64 linked ≈ 3.4 KiB).
    ///
    /// The matrix is first scaled by the power of two `s` at or below its largest magnitude
    /// (exact; `|aᵢⱼ| < 2`, no overflow or underflow in the determinant), inverted by the
    /// adjugate, `X₀ = adj(A/s)ᵀ / det`, and refined by one Newton step `X₁ = X₀ + X₀ R` whose
    /// residual `R = I − (A/s) X₀` is summed with its rounding errors (Dekker's exact product,
    /// Knuth's exact sum; Ogita, Rump & Oishi, "Accurate sum and dot product", SIAM J. Sci.
    /// Comput. 26, 2005), which leaves about the error of rounding `X₁`; the inverse of `A` is
    /// `X₁ / s`. Singular when an entry of `X₀` exceeds 10⁶ or is not finite (condition number
    /// ≳ 10⁶, beyond what f32 resolves). Against Gauss–Jordan elimination in f64: ≤ 1 ulp of
    /// the largest entry over display matrices (unit test `inverse_matches_f64`).
    fn inverse3(a: &[[f32; 3]; 3]) -> Result<[[f32; 3]; 3], Error> {
        let top = a.iter().flatten().fold(0.0f32, |a, v| a.max(v.abs()));
        if !(top.is_finite() && top >= f32::MIN_POSITIVE) {
            return Err(Error::Singular);
        }
        // a power of two, so that `A/s` is exact
        let scale = f32::from_bits(top.to_bits() & 0x7f80_0000);
        let m = a.map(|r| r.map(|v| v / scale));
        let (cof, det) = cofactors(&m);
        let mut x = [[0.0f32; 3]; 3];
        let mut big = 0.0f32;
        for (i, row) in x.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v = cof[j][i] / det;
                big = big.max(v.abs());
            }
        }
        // ‖A/s‖ < 6, so `top` > cond/36: refused beyond what f32 resolves (and 0/0, x/0)
        if !(big <= 1e6) {
            return Err(Error::Singular);
        }
        // residual R = I − (A/s) X₀, each entry summed with its rounding errors (Dekker's
        // product, Knuth's sum: no f64), then X₁ = X₀ + X₀ R
        let mut r = [[0.0f32; 3]; 3];
        for (i, row) in r.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                let (mut sum, mut err) = (if i == j { 1.0 } else { 0.0 }, 0.0f32);
                for k in 0..3 {
                    let (p, pe) = two_product(m[i][k], x[k][j]);
                    let (t, te) = two_sum(sum, -p);
                    sum = t;
                    err += te - pe;
                }
                *v = sum + err;
            }
        }
        let xr = mul_f32(&x, &r);
        let mut out = [[0.0f32; 3]; 3];
        for (i, row) in out.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v = (x[i][j] + xr[i][j]) / scale;
                if !v.is_finite() {
                    return Err(Error::Singular);
                }
            }
        }
        Ok(out)
    }
}

impl Real for f64 {
    const ZERO: f64 = 0.0;
    const ONE: f64 = 1.0;
    const THIRD: f64 = 1.0 / 3.0;
    #[inline]
    fn from_f64(v: f64) -> f64 {
        v
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self
    }
    #[inline]
    fn dot3(a: [f64; 3], b: [f64; 3]) -> f64 {
        (0..3).map(|k| a[k] * b[k]).sum::<f64>()
    }

    /// The adjugate over the determinant; singular when the determinant is not finite or
    /// `|det| < 10⁻³⁰⁰`.
    fn inverse3(m: &[[f64; 3]; 3]) -> Result<[[f64; 3]; 3], Error> {
        let (cof, det) = cofactors(m);
        if !det.is_finite() || det.abs() < 1e-300 {
            return Err(Error::Singular);
        }
        Ok([0, 1, 2].map(|i| [0, 1, 2].map(|j| cof[j][i] / det)))
    }
}

/// The cofactor matrix `C` of `m` (`Cᵢⱼ` the signed minor of row `i`, column `j`) and the
/// determinant by expansion along the first row: `m⁻¹ = Cᵀ / det`.
#[inline]
fn cofactors<T: Real>(m: &[[T; 3]; 3]) -> ([[T; 3]; 3], T) {
    let c =
        |r0: usize, c0: usize, r1: usize, c1: usize| m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0];
    let cof = [
        [c(1, 1, 2, 2), -c(1, 0, 2, 2), c(1, 0, 2, 1)],
        [-c(0, 1, 2, 2), c(0, 0, 2, 2), -c(0, 0, 2, 1)],
        [c(0, 1, 1, 2), -c(0, 0, 1, 2), c(0, 0, 1, 1)],
    ];
    let det = m[0][0] * cof[0][0] + m[0][1] * cof[0][1] + m[0][2] * cof[0][2];
    (cof, det)
}

/// `a + b = s + e` exactly, `s` the rounded sum (Knuth's TwoSum).
#[inline]
fn two_sum(a: f32, b: f32) -> (f32, f32) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// `a · b = p + e` exactly, `p` the rounded product (Dekker's TwoProduct with Veltkamp's
/// split; no fused multiply-add). Exact while `|a|, |b| ≤ 2¹⁰⁰` (no overflow in the split).
#[inline]
fn two_product(a: f32, b: f32) -> (f32, f32) {
    let split = |v: f32| {
        let c = 4097.0 * v;
        let hi = c - (c - v);
        (hi, v - hi)
    };
    let p = a * b;
    let ((ah, al), (bh, bl)) = (split(a), split(b));
    (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
}

/// `a · b` in f32 (the inverse's refinement; [`Mat3::mul`] sums in f64).
fn mul_f32(a: &[[f32; 3]; 3], b: &[[f32; 3]; 3]) -> [[f32; 3]; 3] {
    let mut r = [[0.0f32; 3]; 3];
    for (i, row) in r.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
        }
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn inverse_roundtrip() {
        let m = Mat3::<f32>([
            [0.4124, 0.3576, 0.1805],
            [0.2126, 0.7152, 0.0722],
            [0.0193, 0.1192, 0.9505],
        ]);
        let p = m.mul(&m.inverse().unwrap());
        for i in 0..3 {
            for j in 0..3 {
                let e = if i == j { 1.0 } else { 0.0 };
                assert!((p.0[i][j] - e).abs() < 1e-6);
            }
        }
        assert_eq!(
            Mat3::<f32>([[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 0.0, 1.0]]).inverse(),
            Err(Error::Singular)
        );
        assert_eq!(Mat3::<f32>([[0.0; 3]; 3]).inverse(), Err(Error::Singular));
        assert_eq!(
            Mat3([[f32::NAN, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]).inverse(),
            Err(Error::Singular)
        );
    }

    /// The f32 inverse against the inverse computed in f64 by Gauss–Jordan elimination: display
    /// matrices from random primaries (chromaticities in the spectral locus's box, luminances
    /// over six decades), the worst error in ulps of the largest entry of the f64 inverse.
    /// The reference inverse: Gauss–Jordan elimination with partial pivoting in f64 (an
    /// independent algorithm: the code under test uses the adjugate).
    fn gauss_jordan(a: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
        let mut m = [[0.0f64; 6]; 3];
        for (i, row) in m.iter_mut().enumerate() {
            row[..3].copy_from_slice(&a[i]);
            row[3 + i] = 1.0;
        }
        for col in 0..3 {
            let p = (col..3)
                .max_by(|&x, &y| m[x][col].abs().total_cmp(&m[y][col].abs()))
                .unwrap_or(col);
            m.swap(col, p);
            let d = m[col][col];
            m[col].iter_mut().for_each(|v| *v /= d);
            for r in 0..3 {
                if r != col {
                    let f = m[r][col];
                    for k in 0..6 {
                        m[r][k] -= f * m[col][k];
                    }
                }
            }
        }
        m.map(|row| [row[3], row[4], row[5]])
    }

    /// Random display matrices (columns: primaries from chromaticities in the spectral
    /// locus's box, luminances over six decades), with their max-norm reciprocal condition.
    fn display_matrices(n: usize, mut f: impl FnMut([[f64; 3]; 3])) {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut uniform = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..n {
            let mut m = [[0.0f64; 3]; 3];
            for i in 0..3 {
                let (x, y) = (0.05 + 0.7 * uniform(), 0.02 + 0.8 * uniform());
                let l = libm::pow(10.0, 6.0 * uniform() - 3.0);
                m[0][i] = x / y * l;
                m[1][i] = l;
                m[2][i] = (1.0 - x - y) / y * l;
            }
            f(m)
        }
    }

    /// The f64 inverse: `A · A⁻¹ = I` and against Gauss–Jordan elimination, both relative to
    /// the inverse's largest entry, over display matrices not too close to singular
    /// (reciprocal condition ≥ 10⁻⁶: ~10 of 16 digits left).
    #[test]
    fn inverse_f64_matches_gauss_jordan() {
        /// The one tolerance: relative to the largest entry (of `A⁻¹`, or of `A` times `A⁻¹`),
        /// i.e. the condition number (≤ 10⁶) times a few f64 epsilons.
        const REL: f64 = 1e-9;
        let (mut worst_inv, mut worst_id, mut tested) = (0.0f64, 0.0f64, 0);
        display_matrices(20_000, |m| {
            let exact = gauss_jordan(m);
            let top = exact.iter().flatten().fold(0.0f64, |t, v| t.max(v.abs()));
            let n = m.iter().flatten().fold(0.0f64, |t, v| t.max(v.abs()));
            if 1.0 / (top * n) < 1e-6 {
                return;
            }
            tested += 1;
            let a = Mat3::<f64>(m);
            let inv = a.inverse().expect("well-conditioned");
            let id = a.mul(&inv);
            for i in 0..3 {
                for j in 0..3 {
                    worst_inv = worst_inv.max((inv.0[i][j] - exact[i][j]).abs() / top);
                    let e = if i == j { 1.0 } else { 0.0 };
                    worst_id = worst_id.max((id.0[i][j] - e).abs());
                }
            }
        });
        assert!(tested > 10_000, "{tested}");
        assert!(
            worst_inv <= REL,
            "inverse: worst {worst_inv:e} over {tested}"
        );
        assert!(worst_id <= REL, "A·A⁻¹: worst {worst_id:e} over {tested}");
        assert_eq!(
            Mat3::<f64>([[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 0.0, 1.0]]).inverse(),
            Err(Error::Singular)
        );
        assert_eq!(Mat3::<f64>([[0.0; 3]; 3]).inverse(), Err(Error::Singular));
        assert_eq!(
            Mat3::<f64>([[f64::NAN, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]).inverse(),
            Err(Error::Singular)
        );
    }

    /// The one Bradford table, narrowed to f32, is the f32 literals the kernels had (no
    /// double rounding through f64).
    #[test]
    fn bradford_narrowed_is_the_f32_literals() {
        let f32_literals: [[f32; 3]; 3] = [
            [0.8951, 0.2664, -0.1614],
            [-0.7502, 1.7135, 0.0367],
            [0.0389, -0.0685, 1.0296],
        ];
        assert_eq!(crate::colorimetry::BRADFORD.cast::<f32>().0, f32_literals);
    }

    #[test]
    fn inverse_matches_f64() {
        /// The one tolerance: ulps of the inverse's largest entry.
        const ULPS: f64 = 1.0;
        // the oracle: Gauss–Jordan elimination with partial pivoting in f64 (not the
        // adjugate the code under test uses)
        let f64_inverse = |a: &Mat3| gauss_jordan(a.cast::<f64>().0);
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut uniform = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let (mut worst, mut tested) = (0.0f64, 0);
        while tested < 20_000 {
            let mut m = [[0.0f32; 3]; 3];
            for i in 0..3 {
                let (x, y) = (0.05 + 0.7 * uniform(), 0.02 + 0.8 * uniform());
                let l = libm::pow(10.0, 6.0 * uniform() - 3.0);
                m[0][i] = (x / y * l) as f32;
                m[1][i] = l as f32;
                m[2][i] = ((1.0 - x - y) / y * l) as f32;
            }
            let a = Mat3(m);
            let exact = f64_inverse(&a);
            let top = exact.iter().flatten().fold(0.0f64, |t, v| t.max(v.abs()));
            let det_rel = {
                let n = a.0.iter().flatten().fold(0.0f32, |t, v| t.max(v.abs())) as f64;
                1.0 / (top * n) // ≈ 1 / condition number (max-norm)
            };
            // primaries nearly on a line: f32 cannot resolve the inverse (nor can the display)
            if det_rel < 1e-3 {
                continue;
            }
            tested += 1;
            let got = a.inverse().expect("well-conditioned");
            let ulp = top * f32::EPSILON as f64;
            for i in 0..3 {
                for j in 0..3 {
                    worst = worst.max((got.0[i][j] as f64 - exact[i][j]).abs() / ulp);
                }
            }
        }
        assert!(
            worst <= ULPS,
            "worst {worst} ulps of the largest entry over {tested}"
        );
    }
}
