//! Least-squares fitting of a [`Spectrum`] to tabulated samples, one span at a time
//! (Raso & Fournier 1991, §5.2).
//!
//! Each span's Chebyshev coefficients minimise `Σᵢ (p(λᵢ) − f(λᵢ))²` over a grid of step
//! ≤ 1 nm across the span (both ends included), where `f` is the samples' linear interpolant with
//! the end values held beyond the data ([`Tabulated::at`]). Fitting the interpolant rather than
//! only the raw samples (as the paper did) means: non-uniform spacing and data that stop short
//! of the domain need no special case, a narrow span never runs out of samples, and the fit
//! targets exactly the function the 1 nm colour reference integrates. On uniformly sampled data
//! with spans much wider than the spacing the two agree closely.
//!
//! The normal equations are `C × C` and well conditioned in the Chebyshev basis on `[-1, 1]`;
//! they are solved in f64 by Gaussian elimination with partial pivoting ([`crate::solve`]).

use crate::{cheb::basis_f64, solve::solve, Error, Layout, Spectrum, Tabulated};

/// Per-span fit errors, measured at the data samples that fall inside each span.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitErrors<const S: usize> {
    /// Root-mean-square error per span (0 when no sample lies in the span).
    pub rms: [f32; S],
    /// Largest absolute error per span.
    pub max: [f32; S],
    /// Number of samples per span.
    pub count: [u32; S],
}

impl<const S: usize, const C: usize, L: Layout<S>> Spectrum<S, C, L> {
    /// Fits the samples by least squares in each span of the layout (see the module docs).
    pub fn fit(data: &Tabulated<'_>) -> Result<Self, Error> {
        Self::fit_fn(|nm| data.at(nm))
    }

    /// Fits any function of wavelength (nm) by least squares on a ≤ 1 nm grid per span.
    pub fn fit_fn(f: impl Fn(f64) -> f64) -> Result<Self, Error> {
        let mut out = Self::ZERO;
        for s in 0..S {
            let (a, b) = L::BREAKS.span(s);
            let (a, b) = (a as f64, b as f64);
            let n = (libm::ceil(b - a) as usize + 1).max(2 * C).max(2);
            let mut ata = [[0.0f64; C]; C];
            let mut aty = [0.0f64; C];
            let mut t_k = [0.0f64; C];
            for i in 0..n {
                let t = -1.0 + 2.0 * i as f64 / (n - 1) as f64;
                let nm = 0.5 * (a + b) + 0.5 * (b - a) * t;
                let y = f(nm);
                if !y.is_finite() {
                    return Err(Error::NonFinite(i));
                }
                basis_f64(t, &mut t_k);
                for r in 0..C {
                    aty[r] += t_k[r] * y;
                    for c in 0..C {
                        ata[r][c] += t_k[r] * t_k[c];
                    }
                }
            }
            let mut x = aty;
            solve(ata.as_flattened_mut(), &mut x)?;
            for k in 0..C {
                out.coefficients_mut()[k][s] = x[k] as f32;
            }
        }
        Ok(out)
    }

    /// RMS and max error of the fit at the data samples inside each span (a sample on an
    /// interior breakpoint counts in both spans). Samples outside 380–780 nm are ignored.
    pub fn fit_errors(&self, data: &Tabulated<'_>) -> FitErrors<S> {
        let mut sq = [0.0f64; S];
        let mut max = [0.0f32; S];
        let mut count = [0u32; S];
        for (w, v) in data.wavelengths().iter().zip(data.values()) {
            for s in 0..S {
                let (a, b) = L::BREAKS.span(s);
                if *w >= a && *w <= b {
                    let t = (2.0 * w - (a + b)) / (b - a);
                    let e = (self.span(s).eval(t) - v).abs();
                    sq[s] += (e as f64) * (e as f64);
                    max[s] = max[s].max(e);
                    count[s] += 1;
                }
            }
        }
        let mut rms = [0.0f32; S];
        for s in 0..S {
            if count[s] > 0 {
                rms[s] = libm::sqrt(sq[s] / count[s] as f64) as f32;
            }
        }
        FitErrors { rms, max, count }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{DefaultSpectrum, PaperSpectrum};

    #[test]
    fn a_cubic_is_fitted_exactly() {
        let f = |nm: f64| {
            let x = (nm - 500.0) / 100.0;
            0.2 + 0.1 * x - 0.05 * x * x + 0.01 * x * x * x
        };
        let p = PaperSpectrum::fit_fn(f).unwrap();
        for nm in (380..=780).step_by(7) {
            assert!(
                (p.eval(nm as f32) as f64 - f(nm as f64)).abs() < 1e-5,
                "{nm}"
            );
        }
    }

    #[test]
    fn held_ends_beyond_the_data() {
        let w = [400.0, 500.0, 600.0, 700.0];
        let v = [0.5, 0.5, 0.5, 0.5];
        let t = Tabulated::new(&w, &v).unwrap();
        let p = DefaultSpectrum::fit(&t).unwrap();
        assert!((p.eval(380.0) - 0.5).abs() < 1e-5);
        assert!((p.eval(780.0) - 0.5).abs() < 1e-5);
    }
}
