//! CIE S 026/E:2018 α-opic quantities: the irradiances of the five photoreceptors of the
//! human eye (s-, m-, l-cones, rods, the melanopsin of the ipRGCs), their efficacies of luminous
//! radiation, daylight (D65) efficacy ratios and equivalent daylight illuminances.
//!
//! - α-opic irradiance `E_e,α = Σ E_e,λ(λ)·s_α(λ)·Δλ` over 380–780 nm (W/m² when the light is a
//!   spectral irradiance in W/m²/nm), `s_α` the action spectra of the standard's Table 2
//!   (`data/cmf/cie_s026_2018_alpha_opic_1nm.csv`), each 1 at its peak; the cells the standard
//!   leaves empty count as 0. The sums run on the light's own grid ([`Spd`], 1 or 5 nm, the
//!   action spectra taken at the same nodes), as the colour-rendering sums do.
//! - α-opic efficacy of luminous radiation `K_α,v = E_e,α / E_v` (W/lm), `E_v = Km·Σ E_e,λ·V·Δλ`
//!   with `Km = 683` lm/W and V(λ) = ȳ of the CIE 1931 observer (the project's photometry).
//! - α-opic daylight efficacy ratio `DER_α = K_α,v / K_α,v^D65`, and the α-opic equivalent
//!   daylight (D65) illuminance `EDI_α = E_e,α / K_α,v^D65` (lx) — the illuminance of D65 that
//!   gives the same α-opic irradiance. `K_α,v^D65` are the standard's constants (CIE S 026
//!   Table 4: 0.8173, 1.4558, 1.6289, 1.4497, 1.3262 mW/lm for s, m, l, rod, mel).

use super::{source::KM, Spd};
use crate::observer::S026;
use crate::Observer;

/// The five photoreceptors, in the order of every array here.
pub const NAMES: [&str; 5] = ["s-cone", "m-cone", "l-cone", "rhodopic", "melanopic"];

/// Short keys (JSON, CSV): cyanopic, chloropic, erythropic, rhodopic, melanopic.
pub const KEYS: [&str; 5] = ["sc", "mc", "lc", "rh", "mel"];

/// `K_α,v^D65`, W/lm: CIE S 026:2018's α-opic efficacies of luminous radiation of D65.
pub const K_D65: [f64; 5] = [0.8173e-3, 1.4558e-3, 1.6289e-3, 1.4497e-3, 1.3262e-3];

/// A light's α-opic quantities (arrays in the order of [`NAMES`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AlphaOpic {
    /// α-opic irradiances `E_e,α` (W/m² for a light in W/m²/nm).
    pub irradiance: [f64; 5],
    /// Illuminance `E_v`, lx (`Km·Σ E ȳ Δλ`).
    pub illuminance: f64,
    /// α-opic efficacies of luminous radiation `K_α,v`, W/lm.
    pub elr: [f64; 5],
    /// Daylight (D65) efficacy ratios.
    pub der: [f64; 5],
    /// Equivalent daylight (D65) illuminances, lx.
    pub edi: [f64; 5],
}

/// The action spectra at the light's grid nodes: `[s_α(380 + i·step); 5]`.
fn action(s: &Spd, i: usize) -> [f64; 5] {
    core::array::from_fn(|k| S026[k][i * s.step()] as f64)
}

/// The α-opic quantities of a light (its values taken as a spectral irradiance).
pub fn alpha_opic(s: &Spd) -> AlphaOpic {
    let step = s.step() as f64;
    let mut irradiance = [0.0f64; 5];
    for (i, e) in s.values().iter().enumerate() {
        let a = action(s, i);
        for k in 0..5 {
            irradiance[k] += e * a[k] * step;
        }
    }
    let y = s.sums(Observer::Cie1931)[1];
    let illuminance = KM * y * step;
    let elr = irradiance.map(|e| e / illuminance);
    let der = core::array::from_fn(|k| elr[k] / K_D65[k]);
    let edi = core::array::from_fn(|k| irradiance[k] / K_D65[k]);
    AlphaOpic {
        irradiance,
        illuminance,
        elr,
        der,
        edi,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn action_spectra_peak_at_one() {
        for (k, row) in S026.iter().enumerate() {
            let max = row.iter().cloned().fold(0.0f32, f32::max);
            assert!((max - 1.0).abs() < 1e-4, "{}: {max}", NAMES[k]);
        }
    }

    #[test]
    fn edi_is_der_times_illuminance() {
        let s = Spd::from_fn(5, |nm| 1.0 + (nm - 380.0) / 400.0).unwrap();
        let a = alpha_opic(&s);
        for k in 0..5 {
            assert!((a.edi[k] - a.der[k] * a.illuminance).abs() < 1e-9 * a.edi[k]);
        }
    }
}
