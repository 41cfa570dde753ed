//! One trait for "a colour that shading multiplies": the ray tracer, `xyz --repr` and the
//! benchmarks are generic over [`Shade`], so every representation runs the *same* code and the
//! speed and accuracy comparisons are honest.
//!
//! Implementations:
//! - [`Spectrum<S, C>`](crate::Spectrum): piecewise polynomials, reduced after each product;
//!   integrated against the light's exact [`Moments`].
//! - [`Sampled<N>`]: `N` point samples at evenly spaced wavelengths over 380–780 nm, the light
//!   and the colour matching functions point-sampled at the same wavelengths, as a sampling
//!   renderer does (Hall & Greenberg 1983).
//! - [`Rgb`]: a linear-sRGB triple. A reflectance becomes the RGB of its exact colour under the
//!   reference light, normalised so the perfect white is `(1, 1, 1)`; products are per channel
//!   (the paper's "RGB problem", §3).

use crate::{
    moments::exact_xyz, Display, Error, Layout, Mat3, Moments, Observer, Spectrum, Tabulated, Xyz,
    LAMBDA_MAX, LAMBDA_MIN,
};

/// A colour quantity that shading multiplies, adds and scales, and finally integrates to XYZ
/// under a light.
///
/// `Send + Sync` (values and lights are plain data) so a renderer can share them across threads.
pub trait Shade: Copy + Send + Sync {
    /// The per-light precomputation this representation integrates against.
    type Light: Send + Sync;
    /// Precomputes a light (tabulated, never fitted) under an observer for this representation.
    fn light(observer: Observer, light: &Tabulated<'_>) -> Self::Light;
    /// The constant reflectance `v`.
    fn constant(v: f32, light: &Self::Light) -> Self;
    /// Product (reduced to the representation's size where it would grow).
    fn mul(&self, o: &Self) -> Self;
    /// Sum.
    fn add(&self, o: &Self) -> Self;
    /// Scalar multiple.
    fn scale(&self, k: f32) -> Self;
    /// XYZ (perfect white under the light: `Y = 100`).
    fn xyz(&self, light: &Self::Light) -> Xyz;
    /// `xyz(self · o, light)`: the product and its integral in one step, the same value as
    /// `self.mul(o).xyz(light)` (a renderer's most frequent pair; a vector implementation keeps
    /// the product in registers).
    #[inline]
    fn mul_xyz(&self, o: &Self, light: &Self::Light) -> Xyz {
        self.mul(o).xyz(light)
    }
    /// The representation of a tabulated reflectance.
    fn from_reflectance(r: &Tabulated<'_>, light: &Self::Light) -> Result<Self, Error>;
    /// Number of stored values.
    fn size() -> usize;
}

impl<const S: usize, const C: usize, L: Layout<S>> Shade for Spectrum<S, C, L> {
    type Light = Moments<S, C, L>;
    fn light(observer: Observer, light: &Tabulated<'_>) -> Self::Light {
        Moments::new(observer, light)
    }
    #[inline]
    fn constant(v: f32, _: &Self::Light) -> Self {
        Spectrum::constant(v)
    }
    #[inline]
    fn mul(&self, o: &Self) -> Self {
        Spectrum::mul(self, o)
    }
    #[inline]
    fn add(&self, o: &Self) -> Self {
        Spectrum::add(self, o)
    }
    #[inline]
    fn scale(&self, k: f32) -> Self {
        Spectrum::scale(self, k)
    }
    #[inline]
    fn xyz(&self, light: &Self::Light) -> Xyz {
        light.xyz(self)
    }
    fn from_reflectance(r: &Tabulated<'_>, _: &Self::Light) -> Result<Self, Error> {
        Spectrum::fit(r)
    }
    fn size() -> usize {
        S * C
    }
}

/// `N` point samples at `380 + 400·i/(N − 1)` nm.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sampled<const N: usize>(pub [f32; N]);

impl<const N: usize> Sampled<N> {
    /// The `i`-th sample wavelength.
    pub fn wavelength(i: usize) -> f64 {
        if N < 2 {
            return 0.5 * (LAMBDA_MIN + LAMBDA_MAX) as f64;
        }
        LAMBDA_MIN as f64 + (LAMBDA_MAX - LAMBDA_MIN) as f64 * i as f64 / (N - 1) as f64
    }
}

/// A light point-sampled at the [`Sampled<N>`] wavelengths, times the colour matching functions,
/// normalised so the perfect white has `Y = 100`.
#[derive(Clone, Debug, PartialEq)]
pub struct SampledLight<const N: usize> {
    w: [[f32; N]; 3],
}

impl<const N: usize> SampledLight<N> {
    /// Point-samples `light` and the observer (1 nm tables linearly interpolated).
    pub fn new(observer: Observer, light: &Tabulated<'_>) -> Self {
        let mut w = [[0.0f64; N]; 3];
        let mut wy = 0.0;
        for i in 0..N {
            let nm = Sampled::<N>::wavelength(i);
            let p = light.at(nm);
            let cmf = observer.cmf_at(nm);
            for k in 0..3 {
                w[k][i] = p * cmf[k];
            }
            wy += w[1][i];
        }
        let norm = if wy > 0.0 { 100.0 / wy } else { 0.0 };
        Self {
            w: w.map(|row| row.map(|v| (v * norm) as f32)),
        }
    }

    /// The weights `w[axis][i]` (axis 0..3 = X, Y, Z): XYZ is `Σᵢ w[axis][i]·vᵢ`.
    pub const fn weights(&self) -> &[[f32; N]; 3] {
        &self.w
    }
}

impl<const N: usize> Shade for Sampled<N> {
    type Light = SampledLight<N>;
    fn light(observer: Observer, light: &Tabulated<'_>) -> Self::Light {
        SampledLight::new(observer, light)
    }
    #[inline]
    fn constant(v: f32, _: &Self::Light) -> Self {
        Sampled([v; N])
    }
    #[inline]
    fn mul(&self, o: &Self) -> Self {
        let mut r = self.0;
        for (a, b) in r.iter_mut().zip(o.0.iter()) {
            *a *= b;
        }
        Sampled(r)
    }
    #[inline]
    fn add(&self, o: &Self) -> Self {
        let mut r = self.0;
        for (a, b) in r.iter_mut().zip(o.0.iter()) {
            *a += b;
        }
        Sampled(r)
    }
    #[inline]
    fn scale(&self, k: f32) -> Self {
        Sampled(self.0.map(|v| v * k))
    }
    #[inline]
    fn xyz(&self, light: &Self::Light) -> Xyz {
        // Eight lane accumulators so the dot products vectorise (a plain iterator sum is
        // sequential in f32): the sampled mode gets the same care as the polynomial one.
        // Lane `l` sums samples `8i + l` in order of `i`; the lanes are folded to 4 per axis,
        // then `(q₀ + q₂) + (q₁ + q₃)`, then the `N mod 8` tail samples. The loops have the
        // shape of `Moments::xyz` (lanes outer, the three axes in registers, index loops, no
        // closures): an axis-outer form over `chunks_exact` compiled well alone but, in the
        // bench, the compiler vectorised it across the three axes (shuffles, 4.5× slower,
        // docs/performance.md, "Kernels at the floor"). The same sums in the same order.
        let w = &light.w;
        let v = &self.0;
        let n8 = N / 8;
        let mut lanes = [[0.0f32; 8]; 3];
        for l in 0..8 {
            let (mut x, mut y, mut z) = (0.0f32, 0.0f32, 0.0f32);
            for i in 0..n8 {
                let c = v[8 * i + l];
                x += w[0][8 * i + l] * c;
                y += w[1][8 * i + l] * c;
                z += w[2][8 * i + l] * c;
            }
            lanes[0][l] = x;
            lanes[1][l] = y;
            lanes[2][l] = z;
        }
        let mut out = [0.0f32; 3];
        for axis in 0..3 {
            let a = &lanes[axis];
            let (q0, q1) = (a[0] + a[4], a[1] + a[5]);
            let (q2, q3) = (a[2] + a[6], a[3] + a[7]);
            let mut tail = -0.0f32;
            for i in 8 * n8..N {
                tail += w[axis][i] * v[i];
            }
            out[axis] = ((q0 + q2) + (q1 + q3)) + tail;
        }
        Xyz::from_array(out)
    }
    fn from_reflectance(r: &Tabulated<'_>, _: &Self::Light) -> Result<Self, Error> {
        let mut s = [0.0f32; N];
        for (i, v) in s.iter_mut().enumerate() {
            *v = r.at(Sampled::<N>::wavelength(i)) as f32;
        }
        Ok(Sampled(s))
    }
    fn size() -> usize {
        N
    }
}

/// A linear-sRGB triple (see the module docs for how reflectances become one).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rgb(pub [f32; 3]);

/// What an RGB renderer knows of a light: the sRGB matrices, the light's white in linear RGB,
/// and (for turning reflectances into RGB) the light at 1 nm, which is the exact reference sum.
#[derive(Clone, Debug)]
pub struct RgbLight {
    to_xyz: Mat3,
    from_xyz: Mat3,
    white_rgb: [f32; 3],
    white_xyz: Xyz,
    exact: SampledLight<401>,
}

impl RgbLight {
    /// The light as an RGB renderer sees it (linear sRGB primaries).
    pub fn new(observer: Observer, light: &Tabulated<'_>) -> Self {
        let d = Display::srgb();
        let (_, white) = exact_xyz(observer, light, |_| 1.0);
        let white_xyz = Xyz::new(white[0] as f32, white[1] as f32, white[2] as f32);
        let white_rgb = d.xyz_to_rgb().apply(white_xyz.to_array());
        Self {
            to_xyz: *d.rgb_to_xyz(),
            from_xyz: *d.xyz_to_rgb(),
            white_rgb,
            white_xyz,
            exact: SampledLight::new(observer, light),
        }
    }

    /// XYZ of the light's white (`Y = 100`).
    pub fn white(&self) -> Xyz {
        self.white_xyz
    }
}

impl Shade for Rgb {
    type Light = RgbLight;
    fn light(observer: Observer, light: &Tabulated<'_>) -> Self::Light {
        RgbLight::new(observer, light)
    }
    #[inline]
    fn constant(v: f32, _: &Self::Light) -> Self {
        Rgb([v; 3])
    }
    #[inline]
    fn mul(&self, o: &Self) -> Self {
        Rgb([self.0[0] * o.0[0], self.0[1] * o.0[1], self.0[2] * o.0[2]])
    }
    #[inline]
    fn add(&self, o: &Self) -> Self {
        Rgb([self.0[0] + o.0[0], self.0[1] + o.0[1], self.0[2] + o.0[2]])
    }
    #[inline]
    fn scale(&self, k: f32) -> Self {
        Rgb(self.0.map(|v| v * k))
    }
    #[inline]
    fn xyz(&self, light: &Self::Light) -> Xyz {
        let w = light.white_rgb;
        Xyz::from_array(
            light
                .to_xyz
                .apply([self.0[0] * w[0], self.0[1] * w[1], self.0[2] * w[2]]),
        )
    }
    fn from_reflectance(r: &Tabulated<'_>, light: &Self::Light) -> Result<Self, Error> {
        let xyz = Sampled::<401>::from_reflectance(r, &light.exact)?.xyz(&light.exact);
        let rgb = light.from_xyz.apply(xyz.to_array());
        let w = light.white_rgb;
        Ok(Rgb([rgb[0] / w[0], rgb[1] / w[1], rgb[2] / w[2]]))
    }
    fn size() -> usize {
        3
    }
}
