//! The colours of many reflectances sampled on one wavelength grid, as one linear map.
//!
//! ## Why a matrix
//!
//! In every representation the colour of *one* reflectance is linear in its samples:
//! - the reflectance is the samples' linear interpolant (end values held), linear in the
//!   samples ([`specpoly_core::Tabulated::at`]);
//! - the representation is linear in that function: a piecewise polynomial is its
//!   least-squares fit, the solution of normal equations whose matrix depends only on the
//!   layout, so the coefficients are a fixed linear map of the right-hand side
//!   ([`specpoly_core::fit`]); `sampled:N`, `hero:N` (outside a path) and `exact` are point
//!   values; `rgb` is the exact colour through a fixed matrix and a per-channel division;
//! - the integral against the light and the observer is a dot product (moments or weights).
//!
//! So for reflectances `r` sampled at the grid `λ₁ … λₖ`, `XYZ = W r` with one `3 × k` matrix
//! `W` per (grid, representation, observer, light). Column `j` of `W` is the colour of the
//! unit spectrum `eⱼ` (1 at `λⱼ`, 0 at the other samples), computed by the representation
//! itself: [`Shade::from_reflectance`] then [`Shade::xyz`], the very path
//! [`crate::colour::chains`] takes for each reflectance. Applying `W` costs `3k`
//! multiply-adds a reflectance instead of its conversion (the 1 nm interpolant and, for the
//! polynomials, a fit per span); building `W` costs `k` conversions, so it pays when a batch
//! has more reflectances than the grid has samples, or when `W` is kept for the next batch.
//!
//! ## What equals what
//!
//! `W r` is the per-reflectance colour up to f32 rounding: that path rounds the
//! representation's values (fit coefficients, samples) to f32 and sums in f32, here each
//! column is computed by the same f32 code and the columns are combined in f64 (differences
//! are of the order of 10⁻⁷ relative to the white, `Y = 100`). Products of reflectances
//! (inter-reflection chains) are not linear in any one reflectance and are not covered here.

use crate::colour::{self, Colour};
use crate::plausible;
use crate::repr::{Repr, Visitor};
use core::ops::Range;
use specpoly_core::{Error, Observer, Shade, Tabulated};

/// `W` for one wavelength grid, representation, observer and light, with the light's exact
/// white (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct GridWeights {
    /// `w[axis][j]`, axis 0..3 = X, Y, Z: the colour of the unit spectrum at `λⱼ`.
    w: [Vec<f64>; 3],
    /// The light's exact white (1 nm f64 sum, `Y = 100`), as [`colour::white`].
    white: [f64; 3],
}

/// A [`Visitor`]: the colours of the unit spectra `e_j`, `j` in `cols`, of a grid in one
/// representation.
struct Columns<'a> {
    observer: Observer,
    light: Tabulated<'a>,
    wavelengths: &'a [f32],
    cols: Range<usize>,
}

impl Visitor for Columns<'_> {
    type Output = Result<[Vec<f64>; 3], Error>;
    fn visit<T: Shade>(self) -> Self::Output {
        let k = self.wavelengths.len();
        let light = T::light(self.observer, &self.light);
        let cols = self.cols.start.min(k)..self.cols.end.min(k);
        let mut w = [
            Vec::with_capacity(cols.len()),
            Vec::with_capacity(cols.len()),
            Vec::with_capacity(cols.len()),
        ];
        let mut unit = vec![0.0f32; k];
        for j in cols {
            unit[j] = 1.0;
            let tab = Tabulated::new(self.wavelengths, &unit)?;
            let xyz = T::from_reflectance(&tab, &light)?.xyz(&light);
            unit[j] = 0.0;
            w[0].push(xyz.x as f64);
            w[1].push(xyz.y as f64);
            w[2].push(xyz.z as f64);
        }
        Ok(w)
    }
}

impl GridWeights {
    /// `W` of the grid `wavelengths` (nm, strictly increasing, as [`Tabulated::new`] requires)
    /// in representation `repr` under `light` and `observer`.
    pub fn new(
        repr: Repr,
        observer: Observer,
        light: &Tabulated<'_>,
        wavelengths: &[f32],
    ) -> Result<Self, Error> {
        let cols = Self::columns(repr, observer, light, wavelengths, 0..wavelengths.len())?;
        Ok(Self::from_columns(observer, light, [cols]))
    }

    /// Columns `cols` of `W` (rows X, Y, Z): [`Self::new`] in parts, for a caller that
    /// computes the parts in parallel and joins them with [`Self::from_columns`].
    pub fn columns(
        repr: Repr,
        observer: Observer,
        light: &Tabulated<'_>,
        wavelengths: &[f32],
        cols: Range<usize>,
    ) -> Result<[Vec<f64>; 3], Error> {
        crate::repr::dispatch(
            repr,
            Columns {
                observer,
                light: *light,
                wavelengths,
                cols,
            },
        )
    }

    /// `W` from its [`Self::columns`] in order (together covering the grid), with the light's
    /// white under `observer`.
    pub fn from_columns(
        observer: Observer,
        light: &Tabulated<'_>,
        parts: impl IntoIterator<Item = [Vec<f64>; 3]>,
    ) -> Self {
        let mut w: [Vec<f64>; 3] = Default::default();
        for part in parts {
            for (all, p) in w.iter_mut().zip(part) {
                all.extend(p);
            }
        }
        Self {
            w,
            white: colour::white(observer, light),
        }
    }

    /// Number of grid samples `k`.
    pub fn len(&self) -> usize {
        self.w[0].len()
    }

    /// Whether the grid is empty (never for a grid [`Self::new`] accepted).
    pub fn is_empty(&self) -> bool {
        self.w[0].is_empty()
    }

    /// The rows of `W`: `[X, Y, Z]`, each `k` weights.
    pub fn weights(&self) -> &[Vec<f64>; 3] {
        &self.w
    }

    /// The light's exact white.
    pub fn white(&self) -> [f64; 3] {
        self.white
    }

    /// The colour of the reflectance `r` (`k` samples on the grid): `W r`. Samples beyond the
    /// `k`-th are ignored, missing ones count as 0 (give exactly `k`).
    pub fn colour(&self, r: &[f64]) -> Colour {
        Colour {
            xyz: self.xyz(r),
            white: self.white,
        }
    }

    /// `W r` of the reflectance `r` read as the per-reflectance path reads it, or `None` when
    /// that path would refuse it. Each value is rounded to f32 (the library's samples) and,
    /// with `scale ≠ 1`, multiplied in f64 and rounded to f32 again ([`plausible::scaled`]);
    /// `None` when any is not finite or outside [`plausible::MIN_REFLECTANCE`] ..=
    /// [`plausible::MAX_REFLECTANCE`] ([`plausible::reflectance_given`]'s bounds), when the
    /// colour is not finite, or when `r` does not have `k` values. A caller that gets `None`
    /// takes the per-reflectance path, whose error names the problem. One pass over `r`,
    /// [`LANES`] partial sums per axis.
    pub fn reflectance_xyz(&self, r: &[f64], scale: f64) -> Option<[f64; 3]> {
        if r.len() != self.len() || !(scale.is_finite() && scale > 0.0) {
            return None;
        }
        let xyz = if scale == 1.0 {
            self.checked::<false>(r, scale)?
        } else {
            self.checked::<true>(r, scale)?
        };
        xyz.iter().all(|v| v.is_finite()).then_some(xyz)
    }

    /// [`Self::reflectance_xyz`]'s loop, with or without the scaling (one copy each, no
    /// branch inside).
    #[inline(always)]
    fn checked<const SCALED: bool>(&self, r: &[f64], scale: f64) -> Option<[f64; 3]> {
        let read = |v: f64| -> f64 {
            let f = v as f32;
            let f = if SCALED { (f as f64 * scale) as f32 } else { f };
            f as f64
        };
        // the bounds as f32 numbers, compared in f64 (exact: every f32 is an f64)
        let (lo, hi) = (
            plausible::MIN_REFLECTANCE as f64,
            plausible::MAX_REFLECTANCE as f64,
        );
        let [wx, wy, wz] = &self.w;
        let mut lanes = [[0.0f64; LANES]; 3];
        let mut ok = [true; LANES];
        let chunks = r
            .chunks_exact(LANES)
            .zip(wx.chunks_exact(LANES))
            .zip(wy.chunks_exact(LANES).zip(wz.chunks_exact(LANES)));
        for ((v, x), (y, z)) in chunks {
            for l in 0..LANES {
                let f = read(v[l]);
                // NaN fails both comparisons, ±∞ one of them
                ok[l] &= (f >= lo) & (f <= hi);
                lanes[0][l] += x[l] * f;
                lanes[1][l] += y[l] * f;
                lanes[2][l] += z[l] * f;
            }
        }
        let mut out = lanes.map(|a| fold(&a));
        let tail = r.len() / LANES * LANES;
        for (j, v) in r.iter().enumerate().skip(tail) {
            let f = read(*v);
            ok[0] &= (f >= lo) & (f <= hi);
            for (axis, o) in out.iter_mut().enumerate() {
                *o += self.w[axis][j] * f;
            }
        }
        ok.iter().all(|o| *o).then_some(out)
    }

    /// `W r` alone: the three sums in one pass over `r`, [`LANES`] independent partial sums per
    /// axis (so they vectorise and the additions' latencies overlap), then the tail.
    pub fn xyz(&self, r: &[f64]) -> [f64; 3] {
        let [wx, wy, wz] = &self.w;
        let mut lanes = [[0.0f64; LANES]; 3];
        let chunks = r
            .chunks_exact(LANES)
            .zip(wx.chunks_exact(LANES))
            .zip(wy.chunks_exact(LANES).zip(wz.chunks_exact(LANES)));
        for ((v, x), (y, z)) in chunks {
            for l in 0..LANES {
                lanes[0][l] += x[l] * v[l];
                lanes[1][l] += y[l] * v[l];
                lanes[2][l] += z[l] * v[l];
            }
        }
        let mut out = lanes.map(|a| fold(&a));
        let tail = r.len().min(self.len()) / LANES * LANES;
        for (axis, o) in out.iter_mut().enumerate() {
            for (w, v) in self.w[axis][tail..].iter().zip(&r[tail.min(r.len())..]) {
                *o += w * v;
            }
        }
        out
    }
}

/// Partial sums per axis in the row loops: 8 (four were bound by the additions' latency,
/// measured 2× slower a value).
const LANES: usize = 8;

/// The partial sums added pairwise.
fn fold(a: &[f64; LANES]) -> f64 {
    ((a[0] + a[4]) + (a[2] + a[6])) + ((a[1] + a[5]) + (a[3] + a[7]))
}
