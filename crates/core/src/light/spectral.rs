//! The shape and hue of a light: peak wavelength, full width at half maximum, dominant (or
//! complementary) wavelength and excitation purity.
//!
//! - **Peak wavelength** `λp`: the wavelength of the largest value on the light's grid
//!   ([`Spd`], 1 or 5 nm; the first of equal maxima), as a spectroradiometer reports it.
//! - **FWHM**: from the peak outwards, the first crossing of half the peak value on each side,
//!   each by linear interpolation between the two samples around it; undefined when the light
//!   does not fall below half on both sides inside 380–780 nm (a broad-band light).
//! - **Dominant wavelength** `λd` and **excitation purity** `pe` (CIE 015:2018 §9.1): the
//!   straight line in the CIE 1931 (x, y) diagram from the achromatic stimulus `n` through the
//!   light meets the spectral locus (380–780 nm at 1 nm, joined linearly, closed by the purple
//!   line from 780 to 380 nm) at `λd`, interpolated between the two locus nodes it falls
//!   between; `pe = |xy − n| / |xy_λ − n|`. When the line meets the purple line, the light has
//!   no dominant wavelength: the *complementary* wavelength `λc` (the line extended backwards
//!   through `n`) is given instead, reported negative as CIE 015 and colour-science do, and
//!   `pe` is measured to the purple line. The achromatic stimulus for a light source is the
//!   equal-energy stimulus E (x = y = 1/3) unless another is given.

use super::{LightError, Spd};
use crate::Observer;

/// The equal-energy stimulus E, the achromatic point for light sources.
pub const WHITE_E: [f64; 2] = [1.0 / 3.0, 1.0 / 3.0];

/// Peak wavelength (nm) and value of a light on its own grid.
pub fn peak(s: &Spd) -> (f64, f64) {
    let v = s.values();
    let mut best = 0usize;
    for (i, x) in v.iter().enumerate() {
        if *x > v[best] {
            best = i;
        }
    }
    (super::spd::START + (best * s.step()) as f64, v[best])
}

/// Full width at half maximum, nm, around the peak; `None` when the light stays above half its
/// peak up to an end of 380–780 nm.
pub fn fwhm(s: &Spd) -> Option<f64> {
    let v = s.values();
    let step = s.step() as f64;
    let (p_nm, p) = peak(s);
    if !(p > 0.0) {
        return None;
    }
    let half = p / 2.0;
    let ip = ((p_nm - super::spd::START) / step) as usize;
    // left: the first sample below half going down from the peak
    let mut left = None;
    for i in (0..ip).rev() {
        if v[i] < half {
            let f = (half - v[i]) / (v[i + 1] - v[i]);
            left = Some((i as f64 + f) * step);
            break;
        }
    }
    let mut right = None;
    for i in ip + 1..v.len() {
        if v[i] < half {
            let f = (v[i - 1] - half) / (v[i - 1] - v[i]);
            right = Some(((i - 1) as f64 + f) * step);
            break;
        }
    }
    Some(right? - left?)
}

/// A dominant (positive) or complementary (negative) wavelength and the excitation purity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dominant {
    /// Dominant wavelength, nm; negative: the complementary wavelength of a purple.
    pub wavelength: f64,
    /// Excitation purity, 0 (the achromatic point) to 1 (on the spectral locus or purple line;
    /// a hair above 1 for a narrow band between two locus nodes).
    pub purity: f64,
}

/// The CIE 1931 spectral locus at `nm` (380–780, integer).
fn locus(nm: usize) -> [f64; 2] {
    let [x, y, z] = Observer::Cie1931.table()[nm - 380].map(|c| c as f64);
    [x / (x + y + z), y / (x + y + z)]
}

/// Where the ray from `n` in direction `d` first meets segment `a`–`b`: `(t, s)` with the
/// point `n + t·d = a + s·(b − a)`, `t > 0`, `0 ≤ s ≤ 1`.
fn ray_segment(n: [f64; 2], d: [f64; 2], a: [f64; 2], b: [f64; 2]) -> Option<(f64, f64)> {
    let e = [b[0] - a[0], b[1] - a[1]];
    let den = d[0] * e[1] - d[1] * e[0];
    if den == 0.0 {
        return None;
    }
    let w = [a[0] - n[0], a[1] - n[1]];
    let t = (w[0] * e[1] - w[1] * e[0]) / den;
    let s = (w[0] * d[1] - w[1] * d[0]) / den;
    (t > 0.0 && (0.0..=1.0).contains(&s)).then_some((t, s))
}

/// Where the ray from `n` along `d` leaves the locus: `(t, Some(λ))` on the spectral locus,
/// `(t, None)` on the purple line.
fn exit(n: [f64; 2], d: [f64; 2]) -> Option<(f64, Option<f64>)> {
    let mut best: Option<(f64, Option<f64>)> = None;
    let mut keep = |t: f64, w: Option<f64>| {
        if best.is_none_or(|(bt, _)| t < bt) {
            best = Some((t, w));
        }
    };
    for nm in 380..780 {
        if let Some((t, s)) = ray_segment(n, d, locus(nm), locus(nm + 1)) {
            keep(t, Some(nm as f64 + s));
        }
    }
    if let Some((t, _)) = ray_segment(n, d, locus(780), locus(380)) {
        keep(t, None);
    }
    best
}

/// Dominant wavelength and excitation purity of chromaticity `xy` against the achromatic
/// point `white` (CIE 015:2018 §9.1); an error at the achromatic point itself or outside the
/// diagram.
pub fn dominant(xy: [f64; 2], white: [f64; 2]) -> Result<Dominant, LightError> {
    let d = [xy[0] - white[0], xy[1] - white[1]];
    let r = libm::hypot(d[0], d[1]);
    if !(r > 1e-12) || !xy.iter().chain(&white).all(|v| v.is_finite()) {
        return Err(LightError::BadTarget);
    }
    let (t, w) = exit(white, d).ok_or(LightError::BadTarget)?;
    // the ray leaves the locus at n + t·d: the light is at t = 1
    // a light on the locus between two nodes can lie a hair outside the chords joining them
    // (the locus is not convex everywhere: up to 1.0001 for a narrow red band)
    let purity = 1.0 / t;
    if purity > 1.001 {
        return Err(LightError::BadTarget);
    }
    let wavelength = match w {
        Some(w) => w,
        None => {
            let (_, c) = exit(white, [-d[0], -d[1]]).ok_or(LightError::BadTarget)?;
            -c.ok_or(LightError::BadTarget)?
        }
    };
    Ok(Dominant { wavelength, purity })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spectral_colours_are_their_own_wavelength() {
        for nm in [450usize, 520, 580, 610, 650] {
            let d = dominant(locus(nm), WHITE_E).unwrap();
            assert!((d.wavelength - nm as f64).abs() < 1e-6, "{nm} {d:?}");
            assert!((d.purity - 1.0).abs() < 1e-9);
        }
        // halfway to the locus: purity 1/2
        let l = locus(600);
        let mid = [(l[0] + WHITE_E[0]) / 2.0, (l[1] + WHITE_E[1]) / 2.0];
        let d = dominant(mid, WHITE_E).unwrap();
        assert!((d.purity - 0.5).abs() < 1e-9 && (d.wavelength - 600.0).abs() < 1e-6);
    }

    #[test]
    fn purples_get_a_negative_complementary_wavelength() {
        let d = dominant([0.35, 0.2], WHITE_E).unwrap();
        assert!(d.wavelength < -490.0 && d.wavelength > -570.0, "{d:?}");
        assert!(d.purity > 0.0 && d.purity < 1.0);
        assert!(dominant(WHITE_E, WHITE_E).is_err());
        assert!(dominant([0.9, 0.9], WHITE_E).is_err());
    }

    #[test]
    fn peak_and_fwhm_of_a_triangle() {
        // a triangle 40 nm wide at its base: FWHM 20 nm
        let s = Spd::from_fn(1, |nm| (1.0 - (nm - 550.0).abs() / 20.0).max(0.0)).unwrap();
        assert_eq!(peak(&s), (550.0, 1.0));
        assert!((fwhm(&s).unwrap() - 20.0).abs() < 1e-12);
        // broad band: no FWHM
        let flat = Spd::from_fn(5, |_| 1.0).unwrap();
        assert_eq!(fwhm(&flat), None);
    }
}
