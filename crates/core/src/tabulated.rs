//! Tabulated spectral data: `(wavelength, value)` samples and their linear interpolant.
//!
//! The interpolant is piecewise linear between samples and holds the end values beyond the data,
//! which is how the project treats data that stop short of 380–780 nm (the ColorChecker
//! reflectances end at 730 nm). The same interpolant is used by the fit, the moments and the
//! 1 nm reference, so every representation is compared against the same function.

use crate::{Error, LAMBDA_MAX, LAMBDA_MIN};

/// Borrowed samples of a spectrum: strictly increasing wavelengths (nm) and finite values.
#[derive(Clone, Copy, Debug)]
pub struct Tabulated<'a> {
    wavelengths: &'a [f32],
    values: &'a [f32],
}

impl<'a> Tabulated<'a> {
    /// Checks and wraps samples: same length ≥ 1, finite, strictly increasing wavelengths, and
    /// at least one sample inside 380–780 nm (or samples on both sides of it).
    pub fn new(wavelengths: &'a [f32], values: &'a [f32]) -> Result<Self, Error> {
        if wavelengths.len() != values.len() {
            return Err(Error::LengthMismatch);
        }
        if wavelengths.is_empty() {
            return Err(Error::Empty);
        }
        for (i, (w, v)) in wavelengths.iter().zip(values).enumerate() {
            if !w.is_finite() || !v.is_finite() {
                return Err(Error::NonFinite(i));
            }
            if i > 0 && *w <= wavelengths[i - 1] {
                return Err(Error::NotIncreasing(i));
            }
        }
        let first = wavelengths[0];
        let last = wavelengths[wavelengths.len() - 1];
        if first > LAMBDA_MAX || last < LAMBDA_MIN {
            return Err(Error::OutOfRange);
        }
        Ok(Self {
            wavelengths,
            values,
        })
    }

    /// The wavelengths (nm).
    pub fn wavelengths(&self) -> &'a [f32] {
        self.wavelengths
    }

    /// The values.
    pub fn values(&self) -> &'a [f32] {
        self.values
    }

    /// The linear interpolant at `nm`, holding the end values outside the data.
    pub fn at(&self, nm: f64) -> f64 {
        let w = self.wavelengths;
        let v = self.values;
        let n = w.len();
        if nm <= w[0] as f64 {
            return v[0] as f64;
        }
        if nm >= w[n - 1] as f64 {
            return v[n - 1] as f64;
        }
        // first index with w[i] > nm; 1 ≤ i ≤ n−1
        let i = w.partition_point(|x| (*x as f64) <= nm);
        let (w0, w1) = (w[i - 1] as f64, w[i] as f64);
        let (v0, v1) = (v[i - 1] as f64, v[i] as f64);
        v0 + (v1 - v0) * (nm - w0) / (w1 - w0)
    }
}
