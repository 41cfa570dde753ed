//! Hero-wavelength spectral sampling (Wilkie, Nawaz, Droske, Weidlich & Hanika, "Hero wavelength
//! spectral sampling", EGSR 2014), the way pbrt-v4 and Mitsuba 3 render spectra, as the
//! `hero:N` render mode: the honest competitor of the closed spectral algebra.
//!
//! **Per path**, one hero wavelength and `N − 1` companions are drawn: a uniform `u` (its own
//! random stream, so the *paths* are the same as in every other mode) gives
//! `λ_j = P⁻¹((u + j/N) mod 1)`, `j = 0 … N−1`, where `P` is the cumulative distribution of
//! pbrt-v4's visible-wavelength density (`SampleVisibleWavelengths`; Radziszewski, Boryczko &
//! Alda 2009) `p(λ) ∝ sech²(a (λ − 538 nm))`, `a = 0.0072 nm⁻¹`, truncated and renormalised to
//! the project's 380–780 nm. (pbrt-v4 rotates in the warped domain as here; Wilkie et al. rotate
//! uniformly spaced wavelengths, the same thing for a uniform density.) Every reflectance and
//! filter of the scene is evaluated at those `N` wavelengths from its tabulated data
//! ([`bind`]), the path multiplies them lane by lane, and light is integrated with the
//! estimator `xyz = (1/N) Σ_j T(λ_j) L(λ_j) c̄(λ_j) / p(λ_j)` (normalised so a white surface
//! under the light has `Y = 100` in expectation).
//!
//! **Spectral MIS.** Wilkie et al. combine the `N` wavelengths by one-sample multiple importance
//! sampling, the balance heuristic over the path densities each wavelength would have had. In
//! this renderer no sampling decision depends on wavelength (no dispersion: an index of
//! refraction is one number; the continuation is chosen from mode-independent scalars), so the
//! `N` path densities are equal, every balance weight is `1/N`, and the MIS estimator *is* the
//! average above — as in pbrt-v4 for paths without dispersion.
//!
//! Outside the path tracer (the Whitted tracer, `xyz --repr hero:N`), a `Hero<N>` value is the
//! spectrum at the fixed wavelengths of `u = 1/2`: an `N`-point importance quadrature.

use specpoly_core::{Observer, Shade, Tabulated, Xyz, LAMBDA_MAX, LAMBDA_MIN};

/// `a` of the visible-wavelength density `sech²(a (λ − λ₀))` (nm⁻¹).
const A: f64 = 0.0072;
/// Its centre `λ₀` (nm).
const MID: f64 = 538.0;
/// Entries of the 1 nm tables (380..=780 nm).
pub const TABLE: usize = 401;

/// `tanh(a (λ − λ₀))` at the ends of 380–780 nm: the density's cumulative distribution (up to
/// an offset and a scale).
fn cdf_ends() -> (f64, f64) {
    (
        (A * (LAMBDA_MIN as f64 - MID)).tanh(),
        (A * (LAMBDA_MAX as f64 - MID)).tanh(),
    )
}

/// The visible-wavelength density at `nm` (per nm, integrating to 1 over 380–780 nm).
pub fn pdf(nm: f64) -> f64 {
    let (t0, t1) = cdf_ends();
    let c = (A * (nm - MID)).cosh();
    A / (t1 - t0) / (c * c)
}

/// The wavelength whose cumulative probability is `u ∈ [0, 1)` (the inverse of the density's
/// cumulative distribution, closed form).
pub fn sample(u: f64) -> f64 {
    sample_in(u, cdf_ends())
}

/// [`sample`] with the ends `(t0, t1)` of [`cdf_ends`] computed once.
#[inline]
fn sample_in(u: f64, (t0, t1): (f64, f64)) -> f64 {
    (MID + (t0 + u * (t1 - t0)).atanh() / A).clamp(LAMBDA_MIN as f64, LAMBDA_MAX as f64)
}

/// The linear interpolant of a 1 nm table over 380..=780 nm at `nm`.
#[inline]
fn lerp<const K: usize>(t: &[[f32; K]], nm: f32) -> [f32; K] {
    let x = (nm - LAMBDA_MIN).clamp(0.0, (TABLE - 1) as f32);
    let i = (x as usize).min(TABLE - 2);
    let f = x - i as f32;
    let (a, b) = (t[i], t[i + 1]);
    core::array::from_fn(|k| a[k] + (b[k] - a[k]) * f)
}

/// `N` lanes of a spectrum at `N` wavelengths (nm), the same wavelengths for every value of a
/// path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hero<const N: usize> {
    /// The values at the wavelengths.
    pub v: [f32; N],
    /// The wavelengths (nm).
    pub lambda: [f32; N],
}

impl<const N: usize> Hero<N> {
    /// The hero wavelength of `u ∈ [0, 1)` and its `N − 1` companions, stratified in the
    /// density's cumulative distribution.
    pub fn wavelengths(u: f32) -> [f32; N] {
        let ends = cdf_ends();
        core::array::from_fn(|j| {
            let uj = (u as f64 + j as f64 / N as f64).fract();
            sample_in(uj, ends) as f32
        })
    }

    /// The wavelengths outside per-path sampling (`u = 1/2`).
    pub fn fixed() -> [f32; N] {
        Self::wavelengths(0.5)
    }

    /// A 1 nm table (380..=780 nm) at the wavelengths `lambda`.
    #[inline]
    pub fn at(table: &[[f32; 1]], lambda: [f32; N]) -> Self {
        Hero {
            v: lambda.map(|nm| lerp(table, nm)[0]),
            lambda,
        }
    }
}

/// A light for [`Hero`]: `L(λ) c̄(λ) / (N p(λ))` at 1 nm, normalised so the perfect white has
/// `Y = 100` in expectation.
#[derive(Clone, Debug, PartialEq)]
pub struct HeroLight<const N: usize> {
    w: Vec<[f32; 3]>,
}

impl<const N: usize> HeroLight<N> {
    /// The light `light` under `observer`.
    pub fn new(observer: Observer, light: &Tabulated<'_>) -> Self {
        let mut raw = Vec::with_capacity(TABLE);
        let mut wy = 0.0f64;
        for i in 0..TABLE {
            let nm = LAMBDA_MIN as f64 + i as f64;
            let p = light.at(nm);
            let c = observer.cmf_at(nm);
            wy += p * c[1];
            raw.push(c.map(|c| p * c / (N as f64 * pdf(nm))));
        }
        let norm = if wy > 0.0 { 100.0 / wy } else { 0.0 };
        Self {
            w: raw
                .into_iter()
                .map(|c| c.map(|v| (v * norm) as f32))
                .collect(),
        }
    }
}

impl<const N: usize> Shade for Hero<N> {
    type Light = HeroLight<N>;
    fn light(observer: Observer, light: &Tabulated<'_>) -> Self::Light {
        HeroLight::new(observer, light)
    }
    fn constant(v: f32, _: &Self::Light) -> Self {
        Hero {
            v: [v; N],
            lambda: Self::fixed(),
        }
    }
    #[inline]
    fn mul(&self, o: &Self) -> Self {
        Hero {
            v: core::array::from_fn(|j| self.v[j] * o.v[j]),
            lambda: self.lambda,
        }
    }
    #[inline]
    fn add(&self, o: &Self) -> Self {
        Hero {
            v: core::array::from_fn(|j| self.v[j] + o.v[j]),
            lambda: self.lambda,
        }
    }
    #[inline]
    fn scale(&self, k: f32) -> Self {
        Hero {
            v: self.v.map(|v| v * k),
            lambda: self.lambda,
        }
    }
    #[inline]
    fn xyz(&self, light: &Self::Light) -> Xyz {
        let mut out = [0.0f32; 3];
        for j in 0..N {
            let w = lerp(&light.w, self.lambda[j]);
            for k in 0..3 {
                out[k] += self.v[j] * w[k];
            }
        }
        Xyz::from_array(out)
    }
    fn from_reflectance(
        r: &Tabulated<'_>,
        _: &Self::Light,
    ) -> core::result::Result<Self, specpoly_core::Error> {
        let lambda = Self::fixed();
        Ok(Hero {
            v: lambda.map(|nm| r.at(nm as f64) as f32),
            lambda,
        })
    }
    fn size() -> usize {
        N
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The density integrates to one, and `sample` inverts its cumulative distribution (checked
    /// by a 0.01 nm midpoint sum of the density, independent of the closed form).
    #[test]
    fn density_and_inverse_agree() {
        let steps = 40_000;
        let h = (LAMBDA_MAX - LAMBDA_MIN) as f64 / steps as f64;
        let mut cdf = 0.0;
        let mut checked = 0;
        for i in 0..steps {
            let nm = LAMBDA_MIN as f64 + (i as f64 + 0.5) * h;
            cdf += pdf(nm) * h;
            if i % 4000 == 3999 {
                let end = LAMBDA_MIN as f64 + (i + 1) as f64 * h;
                assert!((sample(cdf) - end).abs() < 1e-3, "{} vs {end}", sample(cdf));
                checked += 1;
            }
        }
        assert!((cdf - 1.0).abs() < 1e-6, "{cdf}");
        assert_eq!(checked, 10);
    }
}
