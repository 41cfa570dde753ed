//! Colour of reflectances and chains of reflectances under a light, in any representation,
//! and the f64 reference they are judged against. Shared by `xyz`, `fit`, `accuracy` (and any
//! other command that needs "the colour of this spectrum").
//!
//! The maths (CIE 015:2018 §7): a reflectance `R(λ)` under a light `S(λ)` seen by an observer
//! `x̄, ȳ, z̄` has `X = K Σ_λ R(λ) S(λ) x̄(λ)` (likewise `Y`, `Z`), summed at 1 nm over
//! 380–780 nm with `K = 100 / Σ_λ S(λ) ȳ(λ)`, so the perfect white has `Y = 100`. An
//! inter-reflection chain `R₁ R₂ … Rₖ` is the product of the reflectances, wavelength by
//! wavelength. The reference ([`reference()`]) does exactly this in f64 on the linear
//! interpolants of the tabulated data ([`specpoly_core::exact_xyz`]); a representation
//! ([`Chains`]) converts every reflectance, multiplies with its own `Shade::mul` (degree
//! reduction for polynomials, per-sample for sampling, per-channel for RGB) and integrates
//! with its own `Shade::xyz`. CIELAB is always taken against the light's exact white, so the
//! white-point error of a representation (e.g. a coarsely sampled light) counts as error.

use crate::repr::{Repr, Visitor};
use specpoly_core::{
    delta_e2000, exact_xyz, Error, Lab, Observer, PaperSpectrum, Shade, Tabulated, Xyz,
};

/// A computed colour: XYZ and the white it is relative to (both with the white's `Y = 100`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Colour {
    /// Tristimulus values.
    pub xyz: [f64; 3],
    /// The light's white (perfect reflector).
    pub white: [f64; 3],
}

impl Colour {
    /// Chromaticity `x, y` (paper eq. 8); black gets the white's chromaticity.
    pub fn xy(&self) -> [f64; 2] {
        specpoly_core::chromaticity(self.xyz, self.white)
    }

    /// CIELAB against the white.
    pub fn lab(&self) -> Lab {
        Lab::from_xyz(self.xyz, self.white)
    }

    /// CIEDE2000 between two colours.
    pub fn delta_e(&self, o: &Colour) -> f64 {
        delta_e2000(self.lab(), o.lab())
    }
}

/// The light's exact white (1 nm f64 sum; `Y = 100`).
pub fn white(observer: Observer, light: &Tabulated<'_>) -> [f64; 3] {
    exact_xyz(observer, light, |_| 1.0).1
}

/// The reference colour of the chain `spectra[chain[0]] · spectra[chain[1]] · …` (1 nm f64 sum
/// of the product of the linear interpolants).
pub fn reference(
    observer: Observer,
    light: &Tabulated<'_>,
    spectra: &[Tabulated<'_>],
    chain: &[usize],
) -> Colour {
    let (xyz, white) = exact_xyz(observer, light, |nm| {
        chain.iter().map(|&i| spectra[i].at(nm)).product()
    });
    Colour { xyz, white }
}

/// A [`Visitor`]: the colours of chains of reflectances in one representation, as
/// [`crate::repr::dispatch`] monomorphises it. Every chain must be non-empty.
pub struct Chains<'a> {
    /// The observer.
    pub observer: Observer,
    /// The light (tabulated, never fitted).
    pub light: Tabulated<'a>,
    /// The reflectances.
    pub spectra: &'a [Tabulated<'a>],
    /// Each chain: indices into `spectra`, multiplied in this order.
    pub chains: &'a [Vec<usize>],
}

impl Visitor for Chains<'_> {
    type Output = Result<Vec<Colour>, Error>;
    fn visit<T: Shade>(self) -> Self::Output {
        let light = T::light(self.observer, &self.light);
        let white = white(self.observer, &self.light);
        let reps = self
            .spectra
            .iter()
            .map(|r| T::from_reflectance(r, &light))
            .collect::<Result<Vec<T>, Error>>()?;
        Ok(self
            .chains
            .iter()
            .map(|chain| {
                let q = chain[1..]
                    .iter()
                    .fold(reps[chain[0]], |acc, &i| acc.mul(&reps[i]));
                let xyz = q.xyz(&light);
                Colour {
                    xyz: [xyz.x as f64, xyz.y as f64, xyz.z as f64],
                    white,
                }
            })
            .collect())
    }
}

/// The colours of `chains` in representation `repr` (see [`Chains`]).
pub fn chains(
    repr: Repr,
    observer: Observer,
    light: &Tabulated<'_>,
    spectra: &[Tabulated<'_>],
    chains: &[Vec<usize>],
) -> Result<Vec<Colour>, Error> {
    crate::repr::dispatch(
        repr,
        Chains {
            observer,
            light: *light,
            spectra,
            chains,
        },
    )
}

/// The paper's literal colour path (Raso & Fournier 1991, eq. 7 with the light fitted too;
/// [`specpoly_core::paper::xyz_paper_path`]): each reflectance fitted by the paper's 2 cubic
/// spans, the chain multiplied with reduction, then light and CMFs as cubics.
pub fn paper_path(
    observer: Observer,
    light: &Tabulated<'_>,
    spectra: &[Tabulated<'_>],
    chains: &[Vec<usize>],
) -> Result<Vec<Colour>, Error> {
    let white = white(observer, light);
    let reps = spectra
        .iter()
        .map(PaperSpectrum::fit)
        .collect::<Result<Vec<_>, Error>>()?;
    Ok(chains
        .iter()
        .map(|chain| {
            let q = chain[1..]
                .iter()
                .fold(reps[chain[0]], |acc, &i| acc.mul(&reps[i]));
            let xyz: Xyz = specpoly_core::paper::xyz_paper_path(observer, light, &q);
            Colour {
                xyz: [xyz.x as f64, xyz.y as f64, xyz.z as f64],
                white,
            }
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use specpoly_core::Illuminant;

    #[test]
    fn exact_repr_matches_reference() {
        let d65 = Illuminant::D65.tabulated();
        let a = Illuminant::A.tabulated();
        let spectra = [d65, a];
        let ch = [vec![0], vec![0, 1]];
        let r = chains(Repr::Exact, Observer::Cie1964, &d65, &spectra, &ch).unwrap();
        for (c, chain) in r.iter().zip(&ch) {
            let want = reference(Observer::Cie1964, &d65, &spectra, chain);
            for k in 0..3 {
                assert!((c.xyz[k] / want.xyz[k] - 1.0).abs() < 1e-4);
            }
        }
    }
}
