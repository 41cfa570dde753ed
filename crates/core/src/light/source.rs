//! [`Source`]: a light's moments for both standard observers plus its unnormalised sums.
//!
//! Colour rendering needs two observers: CIE 13.3 and the CCT use the CIE 1931 2° observer,
//! CIE 224:2017 (TM-30) the CIE 1964 10° observer for the samples. The unnormalised 1 nm sums
//! `Σ S x̄`, `Σ S ȳ`, `Σ S z̄` (2°), `Σ S ȳ₁₀` and `Σ S` (radiant) make mixing exact: the mix
//! `Σ dᵢ·Sᵢ` has sums `Σ dᵢ·sumsᵢ` and normalised moments `Σ wᵢ·Mᵢ` with
//! `wᵢ = dᵢ·Yᵢ / Σⱼ dⱼ·Yⱼ` (per observer).

use super::LightError;
use crate::{Moments, Observer, Tabulated, DEFAULT_COEFFS, DEFAULT_SPANS};

/// Moments on the default layout (8 cubic spans), against which the fitted samples integrate.
pub type LightMoments = Moments<DEFAULT_SPANS, DEFAULT_COEFFS>;

/// Maximum luminous efficacy of radiation, lm/W (photopic, CIE 1931 ȳ as V(λ)).
pub const KM: f64 = 683.0;

/// A light source summarised for colorimetry, colour rendering and mixing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Source {
    /// Moments against the CIE 1931 2° observer (white `Y = 100`).
    pub m2: LightMoments,
    /// Moments against the CIE 1964 10° observer (white `Y = 100`).
    pub m10: LightMoments,
    /// `[Σ S x̄, Σ S ȳ, Σ S z̄]`, 2°, 1 nm steps over 380–780 nm.
    raw_xyz: [f64; 3],
    /// `Σ S ȳ₁₀`.
    raw_y10: f64,
    /// `Σ S` (radiant power in the SPD's units × nm).
    radiant: f64,
}

impl Source {
    /// A source from its tabulated SPD: the linear interpolant, as everywhere in the project,
    /// but zero outside the tabulated range (a light emits nothing where it was not measured:
    /// CIE 224:2017 fills missing values with zeros; holding the end values, the convention
    /// for reflectances, would invent light).
    ///
    /// A light with values below −1 % of its peak is refused ([`super::spd::check_sign`]).
    pub fn new(light: &Tabulated<'_>) -> Result<Self, LightError> {
        super::spd::check_sign(light)?;
        let w = light.wavelengths();
        let (lo, hi) = (w[0] as f64, w[w.len() - 1] as f64);
        Self::from_fn(|nm| {
            if nm < lo || nm > hi {
                0.0
            } else {
                light.at(nm)
            }
        })
    }

    /// A source from a computed SPD (a function of wavelength in nm).
    pub fn from_fn(light: impl Fn(f64) -> f64) -> Result<Self, LightError> {
        let mut raw_xyz = [0.0f64; 3];
        let mut raw_y10 = 0.0;
        let mut radiant = 0.0;
        let t2 = Observer::Cie1931.table();
        let t10 = Observer::Cie1964.table();
        for i in 0..401 {
            let p = light(380.0 + i as f64);
            for k in 0..3 {
                raw_xyz[k] += p * t2[i][k] as f64;
            }
            raw_y10 += p * t10[i][1] as f64;
            radiant += p;
        }
        let ok = |v: f64| v.is_finite() && v > 0.0;
        if !ok(raw_xyz[1]) || !ok(raw_y10) || !raw_xyz.iter().all(|v| v.is_finite()) {
            return Err(LightError::Dark);
        }
        Ok(Self {
            m2: Moments::from_fn(Observer::Cie1931, &light),
            m10: Moments::from_fn(Observer::Cie1964, &light),
            raw_xyz,
            raw_y10,
            radiant,
        })
    }

    /// The mixture `Σ dᵢ·Sᵢ` of sources (duties `dᵢ ≥ 0`, not all zero).
    pub fn mix(parts: &[(f64, &Source)]) -> Result<Self, LightError> {
        let mut raw_xyz = [0.0f64; 3];
        let mut raw_y10 = 0.0;
        let mut radiant = 0.0;
        for (d, s) in parts {
            if !d.is_finite() || *d < 0.0 {
                return Err(LightError::BadTarget);
            }
            for k in 0..3 {
                raw_xyz[k] += d * s.raw_xyz[k];
            }
            raw_y10 += d * s.raw_y10;
            radiant += d * s.radiant;
        }
        if raw_xyz[1] <= 0.0 || raw_y10 <= 0.0 {
            return Err(LightError::Dark);
        }
        let mut w2 = [(0.0f32, &parts.first().ok_or(LightError::Dark)?.1.m2); 6];
        let mut w10 = w2;
        if parts.len() > w2.len() {
            return Err(LightError::Channels(parts.len()));
        }
        for (i, (d, s)) in parts.iter().enumerate() {
            w2[i] = ((d * s.raw_xyz[1] / raw_xyz[1]) as f32, &s.m2);
            w10[i] = ((d * s.raw_y10 / raw_y10) as f32, &s.m10);
        }
        Ok(Self {
            m2: Moments::blend(&w2[..parts.len()]),
            m10: Moments::blend(&w10[..parts.len()]),
            raw_xyz,
            raw_y10,
            radiant,
        })
    }

    /// Tristimulus values, 2° observer, `Km · Σ S x̄ Δλ` (lumens for `Y` when the SPD is in W/nm).
    pub fn xyz(&self) -> [f64; 3] {
        self.raw_xyz.map(|v| KM * v)
    }

    /// CIE 1931 chromaticity `(x, y)`.
    pub fn xy(&self) -> [f64; 2] {
        let [x, y, z] = self.raw_xyz;
        let s = x + y + z;
        [x / s, y / s]
    }

    /// CIE 1960 UCS `(u, v)` (2°).
    pub fn uv(&self) -> [f64; 2] {
        super::cct::uv_1960(self.raw_xyz)
    }

    /// CIE 1976 UCS `(u′, v′)`.
    pub fn uv_prime(&self) -> [f64; 2] {
        let [u, v] = self.uv();
        [u, 1.5 * v]
    }

    /// CCT and Duv ([`super::cct::cct_duv`]).
    pub fn cct(&self) -> Result<super::Cct, LightError> {
        super::cct::cct_duv(self.uv())
    }

    /// Luminous efficacy of radiation, lm/W: `Km · Σ S ȳ / Σ S` over 380–780 nm.
    pub fn efficacy(&self) -> f64 {
        KM * self.raw_xyz[1] / self.radiant
    }

    /// Unnormalised luminous sum `Σ S ȳ` (2°).
    pub fn luminous_sum(&self) -> f64 {
        self.raw_xyz[1]
    }

    /// Radiant sum `Σ S` over 380–780 nm at 1 nm.
    pub fn radiant_sum(&self) -> f64 {
        self.radiant
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_light_outside_the_data() {
        let nm = [500.0, 600.0];
        let short = Source::new(&Tabulated::new(&nm, &[1.0, 1.0]).unwrap()).unwrap();
        let nm_full = [380.0, 499.0, 500.0, 600.0, 601.0, 780.0];
        let v = [0.0, 0.0, 1.0, 1.0, 0.0, 0.0];
        let full = Source::new(&Tabulated::new(&nm_full, &v).unwrap()).unwrap();
        assert_eq!(short.xyz(), full.xyz());
        assert_eq!(short.radiant_sum(), 101.0);
    }

    #[test]
    fn dark_lights_are_errors() {
        let nm = [380.0, 780.0];
        assert_eq!(
            Source::new(&Tabulated::new(&nm, &[0.0, 0.0]).unwrap()),
            Err(LightError::Dark)
        );
        assert_eq!(Source::from_fn(|_| f64::NAN).unwrap_err(), LightError::Dark);
    }
}
