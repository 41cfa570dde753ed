//! Dense linear systems `A x = b` in f64, by Gaussian elimination with partial pivoting: the
//! project's one solver. It serves the spectral fit's normal equations (`C × C`,
//! [`crate::fit`]), the display model's 3×3 inverse ([`crate::Mat3::inverse`]), the host's
//! calibration least squares (3×3 and the `3(n − 1)`-unknown curve refit) and the LED check's
//! f64 reference. Slices, not arrays, so fixed-size (`[[f64; N]; N]::as_flattened_mut`) and
//! heap-allocated systems share it without allocation.
//!
//! Hand-written rather than a linear-algebra crate: a dozen lines, `no_std` without an
//! allocator, and the systems are small (nalgebra or faer would bring far more than this uses).

use crate::Error;

/// A pivot at most this fraction of the matrix's largest magnitude counts as zero: the
/// system is singular to working precision (condition number ≳ 10¹²).
pub const SINGULAR: f64 = 1e-12;

/// Solves `A x = b` for row-major `a` (`n × n`, `n = b.len()`); on success `b` holds `x`.
/// `a` is overwritten (its upper triangle after elimination).
///
/// Errors: [`Error::LengthMismatch`] if `a` is not `n × n`; [`Error::Singular`] if a pivot is
/// at most [`SINGULAR`] times the largest `|aᵢⱼ|` (or the matrix is zero); [`Error::NonFinite`]
/// (with the row) if the input holds NaN or infinity.
pub fn solve(a: &mut [f64], b: &mut [f64]) -> Result<(), Error> {
    let n = b.len();
    if a.len() != n * n {
        return Err(Error::LengthMismatch);
    }
    let mut scale = 0.0f64;
    for (i, v) in a.iter().enumerate() {
        if !v.is_finite() {
            return Err(Error::NonFinite(i / n.max(1)));
        }
        scale = scale.max(v.abs());
    }
    if let Some(r) = b.iter().position(|v| !v.is_finite()) {
        return Err(Error::NonFinite(r));
    }
    let tiny = SINGULAR * scale;
    for col in 0..n {
        let mut piv = col;
        for r in col + 1..n {
            if a[r * n + col].abs() > a[piv * n + col].abs() {
                piv = r;
            }
        }
        if !(a[piv * n + col].abs() > tiny) {
            return Err(Error::Singular);
        }
        if piv != col {
            for c in 0..n {
                a.swap(col * n + c, piv * n + c);
            }
            b.swap(col, piv);
        }
        for r in col + 1..n {
            let f = a[r * n + col] / a[col * n + col];
            if f != 0.0 {
                for c in col..n {
                    a[r * n + c] -= f * a[col * n + c];
                }
                b[r] -= f * b[col];
            }
        }
    }
    for r in (0..n).rev() {
        let mut s = b[r];
        for c in r + 1..n {
            s -= a[r * n + c] * b[c];
        }
        b[r] = s / a[r * n + r];
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_system_with_a_known_answer() {
        // Hilbert-like but well conditioned; x = (1, −2, 3) by construction.
        let mut a = [[4.0, -2.0, 1.0], [-2.0, 4.0, -2.0], [1.0, -2.0, 4.0]];
        let x = [1.0, -2.0, 3.0];
        let mut b = [0.0; 3];
        for r in 0..3 {
            b[r] = (0..3).map(|c| a[r][c] * x[c]).sum();
        }
        solve(a.as_flattened_mut(), &mut b).unwrap();
        for (g, w) in b.iter().zip(x) {
            assert!((g - w).abs() < 1e-14, "{b:?}");
        }
    }

    #[test]
    fn needs_pivoting() {
        let mut a = [[0.0, 1.0], [1.0, 1.0]];
        let mut b = [2.0, 3.0];
        solve(a.as_flattened_mut(), &mut b).unwrap();
        assert_eq!(b, [1.0, 2.0]);
    }

    #[test]
    fn singular_and_malformed_systems_are_errors() {
        let mut a = [[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 0.0, 1.0]];
        assert_eq!(
            solve(a.as_flattened_mut(), &mut [1.0, 2.0, 3.0]),
            Err(Error::Singular)
        );
        let mut same = [[0.3, 0.3, 0.3]; 3];
        assert_eq!(
            solve(same.as_flattened_mut(), &mut [1.0; 3]),
            Err(Error::Singular)
        );
        assert_eq!(solve(&mut [0.0; 4], &mut [1.0, 1.0]), Err(Error::Singular));
        assert_eq!(
            solve(&mut [1.0; 3], &mut [1.0, 1.0]),
            Err(Error::LengthMismatch)
        );
        assert_eq!(
            solve(&mut [1.0, 0.0, 0.0, f64::NAN], &mut [1.0, 1.0]),
            Err(Error::NonFinite(1))
        );
    }
}
