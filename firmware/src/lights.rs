//! The built-in lights as moments, computed at build time by `specpoly-core`'s
//! [`Moments::new`](specpoly_core::Moments::new) (see build.rs), for both observers and both
//! presets.
//!
//! For a reflectance with coefficients `c[k][s]` (Chebyshev term `k` of span `s`),
//! `X = Σₛ Σₖ Mₓ[k][s] · c[k][s]` (and likewise `Y`, `Z`) is the 1 nm sum of the polynomial
//! times the light's tabulated power and the colour matching functions, normalised so the
//! perfect reflector has `Y = 100`. The sum runs in the order of `Moments::xyz`, so results
//! are the core's to the bit.

use specpoly_core::{Illuminant, Observer, Spectrum, Xyz};

/// One light under one observer for a preset of `S` cubic spans.
pub struct LightMoments<const S: usize> {
    /// `m[axis][k][s]`, axis 0..3 = X, Y, Z.
    pub m: [[[f32; S]; 4]; 3],
    /// XYZ of the perfect reflector.
    pub white: [f32; 3],
}

include!(concat!(env!("OUT_DIR"), "/lights.rs"));

/// Whether this build carries the observer's moments (CIE 1964 needs feature `observer-1964`).
pub fn has_observer(observer: Observer) -> bool {
    observer == Observer::Cie1931 || cfg!(feature = "observer-1964")
}

/// The table index of (observer, illuminant); an observer not built in falls back to 1931.
fn index(observer: Observer, illuminant: Illuminant) -> usize {
    let o = match observer {
        Observer::Cie1964 if has_observer(observer) => 1,
        _ => 0,
    };
    let i = Illuminant::ALL
        .iter()
        .position(|x| *x == illuminant)
        .unwrap_or(0);
    o * Illuminant::ALL.len() + i
}

/// The moments of the paper preset (2 cubic spans split at 550 nm).
pub fn paper(observer: Observer, illuminant: Illuminant) -> &'static LightMoments<2> {
    &PAPER[index(observer, illuminant).min(PAPER.len() - 1)]
}

/// The moments of the default preset (8 uniform cubic spans).
pub fn default(observer: Observer, illuminant: Illuminant) -> &'static LightMoments<8> {
    &DEFAULT[index(observer, illuminant).min(DEFAULT.len() - 1)]
}

impl<const S: usize> LightMoments<S> {
    /// XYZ of reflectance `r` under this light: three dot products of length `4·S`.
    pub fn xyz(&self, r: &Spectrum<S, 4>) -> Xyz {
        let c = r.coefficients();
        let mut out = [0.0f32; 3];
        for (o, m) in out.iter_mut().zip(self.m.iter()) {
            let mut acc = [0.0f32; S];
            for k in 0..4 {
                for s in 0..S {
                    acc[s] += m[k][s] * c[k][s];
                }
            }
            *o = acc.iter().sum();
        }
        Xyz::new(out[0], out[1], out[2])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use specpoly_core::{Breaks, Moments, PAPER_BREAKS};

    fn wavy<const S: usize>(breaks: specpoly_core::Breaks<S>) -> Spectrum<S, 4> {
        let mut r = Spectrum::<S, 4>::zero(breaks);
        for k in 0..4 {
            for s in 0..S {
                r.coefficients_mut()[k][s] = 0.4 / (1.0 + k as f32) + 0.03 * s as f32 - 0.01;
            }
        }
        r
    }

    #[test]
    fn tables_are_the_cores_moments_to_the_bit() {
        for o in Observer::ALL.into_iter().filter(|o| has_observer(*o)) {
            for i in Illuminant::ALL {
                let light = i.tabulated();
                let mp = Moments::<2, 4>::new(o, &light, PAPER_BREAKS);
                let md = Moments::<8, 4>::new(o, &light, Breaks::uniform());
                let rp = wavy(PAPER_BREAKS);
                let rd = wavy(Breaks::<8>::uniform());
                assert_eq!(paper(o, i).xyz(&rp), mp.xyz(&rp), "{o:?} {i:?}");
                assert_eq!(default(o, i).xyz(&rd), md.xyz(&rd), "{o:?} {i:?}");
                assert_eq!(Xyz::from_array(default(o, i).white), md.white());
            }
        }
    }
}
