//! Reference illuminants of the colour-rendering standards, as computed spectra.
//!
//! - Planckian radiator: Planck's law `S(λ) ∝ λ⁻⁵ / (exp(c₂ / λT) − 1)` with
//!   `c₂ = 1.4388·10⁻² m·K` (CIE 015:2018 §3.1).
//! - CIE daylight at CCT `T`: `x_D` by the CIE 015:2018 cubic in `1/T` (4000–7000 K and above),
//!   `y_D = −3x_D² + 2.870x_D − 0.275`, then `S = S₀ + M₁S₁ + M₂S₂` with
//!   `M₁ = (−1.3515 − 1.7703x_D + 5.9114y_D) / M`, `M₂ = (0.0300 − 31.4424x_D + 30.0717y_D) / M`,
//!   `M = 0.0241 + 0.2562x_D − 0.7341y_D` (CIE 015:2018 §3.1, unrounded `M₁`, `M₂` as in
//!   colour-science); the components are tabulated at 5 nm (`data/illuminants/`) and linearly
//!   interpolated.
//! - CIE 13.3-1995: Planckian below 5000 K, daylight from 5000 K.
//! - CIE 224:2017: Planckian below 4000 K, daylight above 5000 K, and between them the mix
//!   `(1 − m)·P/Y_P + m·D/Y_D`, `m = (T − 4000)/1000`, each normalised to its luminance
//!   (CIE 1931 ȳ, as colour-science does).

use super::{source::Source, spd::Spd, LightError};
use crate::observer::DAYLIGHT_S012;
use crate::Observer;

/// Second radiation constant, m·K (CIE 015:2018).
pub const C2: f64 = 1.4388e-2;

/// Relative spectral radiance of a Planckian radiator at `nm` and `t` kelvin (λ in µm, so the
/// values stay near 1 for visible wavelengths and ordinary temperatures).
pub fn planck(nm: f64, t: f64) -> f64 {
    let um = nm * 1e-3;
    let x = C2 / (nm * 1e-9 * t);
    1.0 / (um * um * um * um * um * libm::expm1(x))
}

/// CIE daylight chromaticity `(x_D, y_D)` at CCT `t` (CIE 015:2018 eqs. 3.3–3.5).
pub fn daylight_xy(t: f64) -> [f64; 2] {
    let (t1, t2, t3) = (1e3 / t, 1e6 / (t * t), 1e9 / (t * t * t));
    let x = if t <= 7000.0 {
        -4.6070 * t3 + 2.9678 * t2 + 0.09911 * t1 + 0.244063
    } else {
        -2.0064 * t3 + 1.9018 * t2 + 0.24748 * t1 + 0.237040
    };
    [x, -3.0 * x * x + 2.870 * x - 0.275]
}

/// Relative spectral power of CIE daylight with chromaticity `xy` at `nm`.
pub fn daylight(nm: f64, xy: [f64; 2]) -> f64 {
    let [x, y] = xy;
    let m = 0.0241 + 0.2562 * x - 0.7341 * y;
    let m1 = (-1.3515 - 1.7703 * x + 5.9114 * y) / m;
    let m2 = (0.0300 - 31.4424 * x + 30.0717 * y) / m;
    let p = ((nm - 380.0) / 5.0).clamp(0.0, 80.0);
    let i = (p as usize).min(79);
    let f = p - i as f64;
    let at = |c: usize| DAYLIGHT_S012[c][i] as f64 * (1.0 - f) + DAYLIGHT_S012[c][i + 1] as f64 * f;
    at(0) + m1 * at(1) + m2 * at(2)
}

fn planckian(t: f64) -> Result<Source, LightError> {
    Source::from_fn(|nm| planck(nm, t))
}

fn cie_daylight(t: f64) -> Result<Source, LightError> {
    let xy = daylight_xy(t);
    Source::from_fn(|nm| daylight(nm, xy))
}

/// The CIE 13.3-1995 reference illuminant for CCT `t`.
pub fn cri_reference(t: f64) -> Result<Source, LightError> {
    if t < 5000.0 {
        planckian(t)
    } else {
        cie_daylight(t)
    }
}

/// The CIE 224:2017 reference illuminant for CCT `t`.
pub fn tm30_reference(t: f64) -> Result<Source, LightError> {
    if t < 4000.0 {
        planckian(t)
    } else if t > 5000.0 {
        cie_daylight(t)
    } else {
        let p = planckian(t)?;
        let d = cie_daylight(t)?;
        let m = (t - 4000.0) / 1000.0;
        Source::mix(&[
            ((1.0 - m) / p.luminous_sum(), &p),
            (m / d.luminous_sum(), &d),
        ])
    }
}

/// The CIE 13.3-1995 reference illuminant for CCT `t`, on the `step` nm grid of [`Spd`].
pub fn cri_reference_spd(t: f64, step: usize) -> Result<Spd, LightError> {
    if t < 5000.0 {
        Spd::from_fn(step, |nm| planck(nm, t))
    } else {
        let xy = daylight_xy(t);
        Spd::from_fn(step, |nm| daylight(nm, xy))
    }
}

/// The CIE 224:2017 reference illuminant for CCT `t`, on the `step` nm grid of [`Spd`]; in
/// 4000–5000 K the two parts are normalised by their sums `Σ S ȳ` on that grid.
pub fn tm30_reference_spd(t: f64, step: usize) -> Result<Spd, LightError> {
    if t < 4000.0 {
        return Spd::from_fn(step, |nm| planck(nm, t));
    }
    let xy = daylight_xy(t);
    if t > 5000.0 {
        return Spd::from_fn(step, |nm| daylight(nm, xy));
    }
    let p = Spd::from_fn(step, |nm| planck(nm, t))?;
    let d = Spd::from_fn(step, |nm| daylight(nm, xy))?;
    let (yp, yd) = (p.sums(Observer::Cie1931)[1], d.sums(Observer::Cie1931)[1]);
    let m = (t - 4000.0) / 1000.0;
    Spd::from_fn(step, |nm| {
        (1.0 - m) * planck(nm, t) / yp + m * daylight(nm, xy) / yd
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn d65_from_the_components_matches_the_table() {
        // CIE D65 is daylight at 6500·1.4388/1.4380 K; the table is normalised to 100 at 560 nm.
        let xy = daylight_xy(6500.0 * 1.4388 / 1.4380);
        let table = crate::Illuminant::D65.values();
        let k = 100.0 / daylight(560.0, xy);
        for (i, v) in table.iter().enumerate() {
            let ours = k * daylight(380.0 + 5.0 * i as f64, xy);
            assert!(
                (ours - *v as f64).abs() < 0.05,
                "{} nm: {ours} vs {v}",
                380 + 5 * i
            );
        }
    }
}
