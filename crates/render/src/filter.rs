//! What a shadow ray passes through on its way to a light, and the first-hit colours of light
//! arriving through one filter.
//!
//! A shadow ray multiplies the transmission filter `F` of every transmitting surface it crosses
//! (Whitted 1980; see [`crate::tracer`]); the compiled scene's shadow rays
//! ([`crate::compiled`]) build a [`Filter`]. Below the compiled scene, on its materials
//! ([`crate::material`]). In a scene like the paper's Example 2 most filtered
//! shadow rays cross one filter once or twice, so [`Filter`] keeps "`count` crossings of one
//! material" as a reference and a count, and forms the product `Fᶜᵒᵘⁿᵗ` only when it is needed,
//! with the same products in the same order as forming it crossing by crossing (so images are
//! bit-identical). A spectral value is 128–324 bytes: passing references instead of values
//! between the shadow test and the light term avoids a copy per shadow ray
//! (docs/performance.md, "The renderer with these kernels").
//!
//! At a first hit (throughput one) light through `count` crossings of filter `F` contributes
//! `a·xyz(Fᶜᵒᵘⁿᵗ·D, L) + b·xyz(Fᶜᵒᵘⁿᵗ·S, L)`: XYZ is linear, so [`FilteredFirst`] tabulates the
//! two integrals per material, filter, count and light once per frame, as the unfiltered first
//! hit's `xyz(D, L)`, `xyz(S, L)` are.

use crate::material::{Coef, Mat};
use specpoly_core::{Shade, Xyz};

/// Crossings tabulated per filter at first hits: a straight ray crosses a convex cell's wall at
/// most twice.
pub(crate) const FIRST_COUNTS: u32 = 2;

/// The filters a shadow ray crossed.
#[derive(Debug)]
pub(crate) enum Filter<'a, T> {
    /// None: the light arrives unfiltered.
    Clear,
    /// `count` (≥ 1) crossings of material `mat`'s filter `coef`, and nothing else.
    Same {
        /// The filter.
        coef: &'a Coef<T>,
        /// Its material's index.
        mat: usize,
        /// Crossings.
        count: u32,
    },
    /// Crossings of several filters: their product.
    Mixed(&'a T),
}

impl<T: Shade> Filter<'_, T> {
    /// Whether the light arrives unfiltered.
    #[inline]
    pub(crate) fn is_clear(&self) -> bool {
        matches!(self, Filter::Clear)
    }

    /// Calls `f` with the product of the filters (`None` when clear), formed only for two or
    /// more crossings of one filter: `F`, then `F·F`, … as [`power`] forms it.
    #[inline]
    pub(crate) fn with<R>(&self, f: impl FnOnce(Option<&T>) -> R) -> R {
        match self {
            Filter::Clear => f(None),
            Filter::Same { coef, count: 1, .. } => f(Some(&coef.value)),
            Filter::Same { coef, count, .. } => f(Some(&power(coef, *count))),
            Filter::Mixed(v) => f(Some(v)),
        }
    }
}

/// `F` multiplied `count` times as a shadow ray forms it crossing by crossing: `F`, then
/// `F·(previous)` with [`Coef::times`].
#[inline]
pub(crate) fn power<T: Shade>(coef: &Coef<T>, count: u32) -> T {
    let mut acc = coef.value;
    for _ in 1..count {
        acc = coef.times(&acc);
    }
    acc
}

/// Accumulates the filters crossed by one shadow ray, crossing by crossing.
pub(crate) struct Crossings<'a, T> {
    /// `Some((coef, material, count))` while every crossing was of one filter.
    same: Option<(&'a Coef<T>, usize, u32)>,
    /// The product once two different filters were crossed.
    mixed: Option<T>,
}

impl<'a, T: Shade> Crossings<'a, T> {
    /// No crossings yet.
    #[inline]
    pub(crate) fn new() -> Self {
        Self {
            same: None,
            mixed: None,
        }
    }

    /// One more crossing of material `mat`'s filter `f`.
    #[inline]
    pub(crate) fn cross(&mut self, f: &'a Coef<T>, mat: usize) {
        if let Some(acc) = &mut self.mixed {
            *acc = f.times(acc);
            return;
        }
        match &mut self.same {
            None => self.same = Some((f, mat, 1)),
            Some((_, m, count)) if *m == mat => *count += 1,
            Some((g, _, count)) => {
                let acc = power(g, *count);
                self.mixed = Some(f.times(&acc));
                self.same = None;
            }
        }
    }

    /// The filters crossed, the product (if any) kept in `scratch`.
    #[inline]
    pub(crate) fn finish(self, scratch: &'a mut Option<T>) -> Filter<'a, T> {
        match (self.same, self.mixed) {
            (_, Some(v)) => Filter::Mixed(scratch.insert(v)),
            (Some((coef, mat, count)), None) => Filter::Same { coef, mat, count },
            (None, None) => Filter::Clear,
        }
    }
}

/// First-hit colours through filters: for material `m`, filter material `f`, count `c` and light
/// slot `l`, `(xyz(Fᶜ·D, L), xyz(Fᶜ·S, L))` exactly as the light term forms them from the
/// product.
#[derive(Debug, Default)]
pub(crate) struct FilteredFirst {
    /// The materials with a transmission filter, in the order of the table.
    filters: Vec<usize>,
    /// Light slots per (filter, count).
    slots: usize,
    /// `[material][(filter index · FIRST_COUNTS + count − 1) · slots + light slot]`.
    table: Vec<Vec<(Xyz, Xyz)>>,
}

impl FilteredFirst {
    /// Tabulates every material against every filter of `mats`, for 1..=[`FIRST_COUNTS`]
    /// crossings and the lights `lights` (in slot order).
    pub(crate) fn new<T: Shade>(mats: &[Mat<T>], lights: &[&T::Light]) -> Self {
        let filters: Vec<usize> = (0..mats.len())
            .filter(|&i| mats[i].transmission.is_some())
            .collect();
        let slots = lights.len();
        let table = mats
            .iter()
            .map(|m| {
                if m.diffuse.is_none() && m.specular.is_none() {
                    return Vec::new();
                }
                let mut row = Vec::with_capacity(filters.len() * FIRST_COUNTS as usize * slots);
                for &fi in &filters {
                    let Some(f) = &mats[fi].transmission else {
                        continue;
                    };
                    for count in 1..=FIRST_COUNTS {
                        let path = power(f, count);
                        for light in lights {
                            let mut path_xyz = None;
                            let x = |c: &Option<Coef<T>>, path_xyz: &mut Option<Xyz>| {
                                c.as_ref()
                                    .map_or(Xyz::default(), |c| c.xyz(&path, None, path_xyz, light))
                            };
                            let xd = x(&m.diffuse, &mut path_xyz);
                            let xs = x(&m.specular, &mut path_xyz);
                            row.push((xd, xs));
                        }
                    }
                }
                row
            })
            .collect();
        Self {
            filters,
            slots,
            table,
        }
    }

    /// `(xyz(Fᶜᵒᵘⁿᵗ·D, L), xyz(Fᶜᵒᵘⁿᵗ·S, L))` for material `mi`, filter material `fi` and light
    /// slot `slot`, if tabulated.
    #[inline]
    pub(crate) fn get(&self, mi: usize, fi: usize, count: u32, slot: usize) -> Option<(Xyz, Xyz)> {
        if count == 0 || count > FIRST_COUNTS || slot >= self.slots {
            return None;
        }
        let k = self.filters.iter().position(|&f| f == fi)?;
        let i = (k * FIRST_COUNTS as usize + (count - 1) as usize) * self.slots + slot;
        self.table.get(mi)?.get(i).copied()
    }
}

#[cfg(test)]
mod tests {
    use super::FIRST_COUNTS;
    use crate::compiled::Compiled;
    use specpoly_core::{delta_e2000, exact_xyz, DefaultSpectrum, Lab};

    /// Largest ΔE00 between a tabulated first-hit colour and the 1 nm f64 integral: the default
    /// representation's fit and reduced products are good to about 0.01 on example2
    /// (docs/performance.md, colour error against the 1 nm reference).
    const TOL_DE00: f64 = 0.05;

    /// The filtered first-hit table against an independent oracle, the 1 nm f64 sum of the
    /// tabulated spectra (`exact_xyz`): example2's red paint lit through 1 and 2 crossings of its
    /// blue filter, `xyz(Fᶜ·D, L)`, and the flat specular `xyz(Fᶜ·0.7, L)`. A wrong index
    /// (material, filter, count or light) misses by far more than the tolerance.
    #[test]
    fn filtered_first_hits_match_the_1nm_integral() {
        let scene = crate::load("example2").expect("built-in scene");
        let c = Compiled::<DefaultSpectrum>::new(&scene).expect("compiles");
        let index = |name: &str| {
            scene
                .materials
                .iter()
                .position(|m| m.name == name)
                .expect("material")
        };
        let (red, blue) = (index("red_paint"), index("blue_filter"));
        let m = &scene.materials[red];
        let d = m.diffuse.as_ref().expect("diffuse").tabulated();
        let s = m.specular.as_ref().expect("specular").tabulated();
        let f = scene.materials[blue]
            .transmission
            .as_ref()
            .expect("filter")
            .tabulated();
        let light = scene.lights[0].spd.tabulated();
        for count in 1..=FIRST_COUNTS {
            let (xd, xs) = c
                .first_filtered()
                .get(red, blue, count, 0)
                .expect("tabulated");
            let through = |nm: f64| f.at(nm).powi(count as i32);
            for (got, r) in [(xd, &d), (xs, &s)] {
                let (want, white) = exact_xyz(scene.observer, &light, |nm| through(nm) * r.at(nm));
                let de = delta_e2000(Lab::from_xyz(got, white), Lab::from_xyz(want, white));
                assert!(
                    de <= TOL_DE00,
                    "count {count}: ΔE00 {de} ({got:?} vs {want:?})"
                );
            }
        }
        // not tabulated: more crossings than a convex cell gives, or an unknown filter
        assert!(c
            .first_filtered()
            .get(red, blue, FIRST_COUNTS + 1, 0)
            .is_none());
        assert!(c.first_filtered().get(red, red, 1, 0).is_none());
    }
}
