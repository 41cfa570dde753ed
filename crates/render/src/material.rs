//! A scene's materials in a colour representation `T`: each coefficient (reflectance or
//! filter) as a [`Coef`] with the scalars the tracers need (flat value, largest value), a
//! material as a [`Mat`], and the 1 nm tables hero-wavelength sampling binds them from
//! ([`MatTables`]). Below the compiled scene and the shadow-ray filters.

use specpoly_core::{Shade, Xyz};

/// One coefficient of a material (a reflectance or filter) in representation `T`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Coef<T> {
    /// The value.
    pub(crate) value: T,
    /// `Some(k)` when the spectrum is flat: products with it are scalings, and
    /// `xyz(T·k) = k·xyz(T)`.
    pub(crate) flat: Option<f32>,
    /// Its largest value over 380–780 nm (bounds a path's weight).
    pub(crate) max: f32,
}

impl<T: Shade> Coef<T> {
    /// `path · self`.
    #[inline]
    pub(crate) fn times(&self, path: &T) -> T {
        match self.flat {
            Some(k) => path.scale(k),
            None => path.mul(&self.value),
        }
    }

    /// `path · self`, with `None` the path of weight one.
    #[inline]
    pub(crate) fn after(&self, path: Option<&T>) -> T {
        match path {
            Some(p) => self.times(p),
            None => self.value,
        }
    }

    /// [`Self::after`] by reference: `self`'s value itself for the path of weight one (no
    /// copy), else the product, formed into `formed`.
    #[inline]
    pub(crate) fn after_ref<'a>(&'a self, path: Option<&T>, formed: &'a mut Option<T>) -> &'a T {
        match path {
            Some(p) => formed.insert(self.times(p)),
            None => &self.value,
        }
    }

    /// `xyz(path · self)` under `light`; `prod` is `path · self` if already formed, and
    /// `path_xyz` caches `xyz(path)` for flat coefficients.
    #[inline]
    pub(crate) fn xyz(
        &self,
        path: &T,
        prod: Option<&T>,
        path_xyz: &mut Option<Xyz>,
        light: &T::Light,
    ) -> Xyz {
        match (self.flat, prod) {
            (Some(k), _) => path_xyz.get_or_insert_with(|| path.xyz(light)).scale(k),
            (None, Some(p)) => p.xyz(light),
            // spectral: `times` is `path.mul(value)`; product and integral in one step
            (None, None) => path.mul_xyz(&self.value, light),
        }
    }
}

/// A material with its spectra in representation `T`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Mat<T> {
    pub(crate) diffuse: Option<Coef<T>>,
    pub(crate) specular: Option<Coef<T>>,
    pub(crate) phong: f32,
    pub(crate) mirror: Option<Coef<T>>,
    pub(crate) transmission: Option<Coef<T>>,
    pub(crate) ior: f32,
}

impl<T: Shade> Mat<T> {
    /// At deeper hits (throughput `tp`), `T·D` and `T·S` (spectral coefficients only), formed
    /// once for all lights. A struct read by reference: destructuring a returned pair copied
    /// both 132-byte halves at every hit (`memcpy`, 8 % of a poly frame of example2).
    #[inline]
    pub(crate) fn times(&self, tp: Option<&T>) -> Formed<T> {
        Formed {
            td: match (tp, &self.diffuse) {
                (Some(tp), Some(d)) if d.flat.is_none() => Some(d.times(tp)),
                _ => None,
            },
            ts: match (tp, &self.specular) {
                (Some(tp), Some(s)) if s.flat.is_none() => Some(s.times(tp)),
                _ => None,
            },
        }
    }

    /// Its transmission filter if a shadow ray passes (with `refraction_blocks`, not through a
    /// refracting surface). By reference: a spectral `Coef` is 136 bytes, and copying it per
    /// crossing was 11 % of a poly frame of example2 (`memcpy` calls; docs/performance.md).
    #[inline]
    pub(crate) fn filter(&self, refraction_blocks: bool) -> Option<&Coef<T>> {
        match &self.transmission {
            Some(f) if !(refraction_blocks && self.ior != 1.0) => Some(f),
            _ => None,
        }
    }
}

/// `T·D` and `T·S` at a hit ([`Mat::times`]).
pub(crate) struct Formed<T> {
    /// `T·D`, if formed.
    pub(crate) td: Option<T>,
    /// `T·S`, if formed.
    pub(crate) ts: Option<T>,
}

/// The 1 nm tables of one material's diffuse, specular, mirror and transmission spectra
/// (`None` where the material has none).
pub type MatTables = [Option<Vec<[f32; 1]>>; 4];
