//! [`Spd`]: a light as the colour-rendering standards sum it, on its own 1 nm or 5 nm grid over
//! 380–780 nm.
//!
//! CIE 224:2017 (§4) and CIE 13.3-1995 evaluate a light tabulated over 380–780 nm at 1 nm or
//! 5 nm by sums at that interval, against samples and observers tabulated at the same interval;
//! colour-science 0.4.7 does the same (5 nm data against the 5 nm colour evaluation samples).
//! Interpolating 5 nm data to 1 nm first is *not* neutral: on the CIE fluorescent and LED
//! illuminants it raises Rf by 0.03–0.14 and moves R9 by up to 1.5 (docs/leds.md). So a light
//! whose table holds every 5 nm node of 380–780 nm (and nothing between) is kept at 5 nm, one
//! holding every 1 nm node at 1 nm; any other table (2 nm, 10 nm, irregular) is taken at 1 nm by
//! linear interpolation, the project's rule for tabulated data.
//!
//! A light tabulated over less than 380–780 nm is refused ([`LightError::Range`]): filling the
//! gap with zeros would report a different light (FL1 cut to 450–650 nm: 4988 K instead of
//! 6428 K). [`Spd::extrapolated`] instead holds the end values, the extrapolation CIE 015:2018
//! (§7.2.2) allows when no better knowledge exists.
//!
//! A light with a tabulated value inside 380–780 nm below −[`NEGATIVE_NOISE`] of its peak is
//! refused ([`LightError::Negative`]): a spectroradiometer's dark subtraction leaves noise of
//! either sign around zero, but a value that far below zero is a light emitting negative power
//! (a wrong dark frame, a sign error, a transmittance ratio): every metric of it would be a
//! figure of no light. Values within the noise are summed as they are (colour-science and luxpy
//! sum them too; clipping them at zero would bias every dark band upwards).

use super::{cct, source::KM, LightError};
use crate::{Observer, Tabulated};

/// Shortest wavelength of the colour-rendering sums, nm.
pub const START: f64 = 380.0;
/// Longest wavelength of the colour-rendering sums, nm.
pub const END: f64 = 780.0;

/// The most negative value accepted in a light, as a fraction of its peak (1 %): the size of
/// dark-subtraction noise of a spectroradiometer reading a dim light, far above that of a good
/// measurement.
pub const NEGATIVE_NOISE: f64 = 0.01;

/// Refuses a light whose tabulated values over 380–780 nm (those the sums use, with the nodes
/// just outside that the interpolant reaches, or the end values held) go below −[`NEGATIVE_NOISE`] of its
/// largest value ([`LightError::Negative`]). A light with no positive value is [`LightError::Dark`].
pub fn check_sign(light: &Tabulated<'_>) -> Result<(), LightError> {
    let (w, v) = (light.wavelengths(), light.values());
    // the nodes the interpolant over 380–780 nm uses: from the last at or below 380 nm (else
    // the first) to the first at or above 780 nm (else the last)
    let first = w.iter().rposition(|x| (*x as f64) <= START).unwrap_or(0);
    let last = w
        .iter()
        .position(|x| (*x as f64) >= END)
        .unwrap_or(w.len() - 1);
    let (mut peak, mut low) = (f64::NEG_INFINITY, (0.0, f64::INFINITY));
    for i in first..=last.max(first) {
        let x = v[i] as f64;
        peak = peak.max(x);
        if x < low.1 {
            low = (w[i] as f64, x);
        }
    }
    if !(peak > 0.0) {
        return Err(LightError::Dark);
    }
    if low.1 < -NEGATIVE_NOISE * peak {
        return Err(LightError::Negative {
            nm: low.0,
            value: low.1,
            peak,
        });
    }
    Ok(())
}

/// A light sampled on the standards' grid: `n` values at `start + i·step`, `step` 1 or 5 nm.
#[derive(Clone, Debug, PartialEq)]
pub struct Spd {
    step: usize,
    n: usize,
    values: [f64; 401],
    extrapolated: bool,
}

/// Whether every node of the `step` grid inside `[lo, hi]` is tabulated and no tabulated
/// point inside 380–780 nm lies off it.
fn on_grid(w: &[f32], step: usize) -> bool {
    let (lo, hi) = (w[0] as f64, w[w.len() - 1] as f64);
    let inside = w
        .iter()
        .map(|x| *x as f64)
        .filter(|x| (START..=END).contains(x));
    let mut count = 0usize;
    for x in inside {
        let k = (x - START) / step as f64;
        if k != libm::floor(k) {
            return false;
        }
        count += 1;
    }
    let nodes = (0..=400 / step)
        .map(|i| START + (i * step) as f64)
        .filter(|x| *x >= lo && *x <= hi)
        .count();
    count == nodes && nodes > 0
}

impl Spd {
    /// The light on its own grid; an error if it does not cover 380–780 nm.
    pub fn new(light: &Tabulated<'_>) -> Result<Self, LightError> {
        let w = light.wavelengths();
        let (lo, hi) = (w[0] as f64, w[w.len() - 1] as f64);
        if lo > START || hi < END {
            return Err(LightError::Range { lo, hi });
        }
        check_sign(light)?;
        Self::sample(light, false)
    }

    /// The light on its own grid, the end values held outside its range (CIE 015:2018 §7.2.2);
    /// [`Self::is_extrapolated`] says whether that was needed.
    pub fn extrapolated(light: &Tabulated<'_>) -> Result<Self, LightError> {
        let w = light.wavelengths();
        let short = (w[0] as f64) > START || (w[w.len() - 1] as f64) < END;
        check_sign(light)?;
        Self::sample(light, short)
    }

    fn sample(light: &Tabulated<'_>, extrapolated: bool) -> Result<Self, LightError> {
        let step = if on_grid(light.wavelengths(), 5) {
            5
        } else {
            1
        };
        // `Tabulated::at` is the linear interpolant holding the end values outside the table;
        // on the grid it returns the tabulated values themselves
        Self::from_fn(step, |nm| light.at(nm)).map(|mut s| {
            s.extrapolated = extrapolated;
            s
        })
    }

    /// A computed light (a function of wavelength in nm) at `step` = 1 or 5 nm.
    pub fn from_fn(step: usize, light: impl Fn(f64) -> f64) -> Result<Self, LightError> {
        let step = if step == 5 { 5 } else { 1 };
        let n = 400 / step + 1;
        let mut values = [0.0; 401];
        for (i, v) in values[..n].iter_mut().enumerate() {
            *v = light(START + (i * step) as f64);
            if !v.is_finite() {
                return Err(LightError::Dark);
            }
        }
        let s = Self {
            step,
            n,
            values,
            extrapolated: false,
        };
        if s.sums(Observer::Cie1931)[1] > 0.0 && s.sums(Observer::Cie1964)[1] > 0.0 {
            Ok(s)
        } else {
            Err(LightError::Dark)
        }
    }

    /// The sampling interval, nm (1 or 5).
    pub fn step(&self) -> usize {
        self.step
    }

    /// The values at `380 + i·step` nm.
    pub fn values(&self) -> &[f64] {
        &self.values[..self.n]
    }

    /// Whether the end values were held to reach 380–780 nm.
    pub fn is_extrapolated(&self) -> bool {
        self.extrapolated
    }

    /// The observer's `[x̄, ȳ, z̄]` at the grid's nodes.
    pub fn cmfs(&self, observer: Observer) -> impl Iterator<Item = [f64; 3]> + '_ {
        let t = observer.table();
        (0..self.n).map(move |i| t[i * self.step].map(|c| c as f64))
    }

    /// `Σ S(λ)·R(λ)·[x̄, ȳ, z̄](λ)` over the grid, `R` given at the same nodes.
    pub fn sums_with(&self, observer: Observer, r: impl Fn(usize) -> f64) -> [f64; 3] {
        let mut xyz = [0.0f64; 3];
        for (i, (s, c)) in self.values().iter().zip(self.cmfs(observer)).enumerate() {
            let p = s * r(i);
            for k in 0..3 {
                xyz[k] += p * c[k];
            }
        }
        xyz
    }

    /// `Σ S·[x̄, ȳ, z̄]` over the grid (no interval factor).
    pub fn sums(&self, observer: Observer) -> [f64; 3] {
        self.sums_with(observer, |_| 1.0)
    }

    /// Tristimulus values, 2° observer, `Km·Σ S x̄ Δλ`.
    pub fn xyz(&self) -> [f64; 3] {
        self.sums(Observer::Cie1931)
            .map(|v| KM * v * self.step as f64)
    }

    /// CIE 1931 chromaticity `(x, y)`.
    pub fn xy(&self) -> [f64; 2] {
        let [x, y, z] = self.sums(Observer::Cie1931);
        [x / (x + y + z), y / (x + y + z)]
    }

    /// CIE 1960 UCS `(u, v)` (2°).
    pub fn uv(&self) -> [f64; 2] {
        cct::uv_1960(self.sums(Observer::Cie1931))
    }

    /// CCT and Duv ([`cct::cct_duv`]).
    pub fn cct(&self) -> Result<cct::Cct, LightError> {
        cct::cct_duv(self.uv())
    }
}

#[cfg(test)]
mod tests {
    use super::super::Source;
    use super::*;

    #[test]
    fn grids_are_recognised() {
        let nm5: [f32; 81] = core::array::from_fn(|i| 380.0 + 5.0 * i as f32);
        let v5 = [1.0f32; 81];
        let s = Spd::new(&Tabulated::new(&nm5, &v5).unwrap()).unwrap();
        assert_eq!((s.step(), s.values().len()), (5, 81));
        let nm1: [f32; 401] = core::array::from_fn(|i| 380.0 + i as f32);
        let v1 = [1.0f32; 401];
        let s = Spd::new(&Tabulated::new(&nm1, &v1).unwrap()).unwrap();
        assert_eq!((s.step(), s.values().len()), (1, 401));
        // 10 nm data: interpolated to 1 nm
        let nm10: [f32; 41] = core::array::from_fn(|i| 380.0 + 10.0 * i as f32);
        let s = Spd::new(&Tabulated::new(&nm10, &[1.0f32; 41]).unwrap()).unwrap();
        assert_eq!(s.step(), 1);
    }

    #[test]
    fn partial_range_is_refused_or_extrapolated() {
        let nm = [450.0, 500.0, 650.0];
        let v = [1.0, 2.0, 3.0];
        let t = Tabulated::new(&nm, &v).unwrap();
        assert_eq!(
            Spd::new(&t),
            Err(LightError::Range {
                lo: 450.0,
                hi: 650.0
            })
        );
        let s = Spd::extrapolated(&t).unwrap();
        assert!(s.is_extrapolated());
        assert_eq!((s.values()[0], s.values()[400]), (1.0, 3.0));
        assert_eq!(s.values()[120], 2.0);
    }

    #[test]
    fn negative_values_beyond_the_noise_are_refused() {
        let nm: [f32; 81] = core::array::from_fn(|i| 380.0 + 5.0 * i as f32);
        // dark-subtraction noise of ±0.5 % of the peak is summed as it is
        let noisy: [f32; 81] = core::array::from_fn(|i| if i % 2 == 0 { 2.0 } else { -0.01 });
        assert!(Spd::new(&Tabulated::new(&nm, &noisy).unwrap()).is_ok());
        let mut bad = [1.0f32; 81];
        bad[24] = -0.5;
        let t = Tabulated::new(&nm, &bad).unwrap();
        let want = Err(LightError::Negative {
            nm: 500.0,
            value: -0.5,
            peak: 1.0,
        });
        assert_eq!(Spd::new(&t), want);
        assert_eq!(Spd::extrapolated(&t), want);
        assert_eq!(Source::new(&t).map(|_| ()), want.map(|_: Spd| ()));
        // a negative value outside 380–780 nm that no sum reaches is not the light's
        let (w, v) = ([300.0, 370.0, 380.0, 780.0], [-5.0, 0.0, 1.0, 1.0]);
        assert!(Spd::new(&Tabulated::new(&w, &v).unwrap()).is_ok());
        // the node just below 380 nm is interpolated from: it counts
        let (w, v) = ([370.0, 390.0, 780.0], [-5.0, 1.0, 1.0]);
        assert!(matches!(
            Spd::new(&Tabulated::new(&w, &v).unwrap()),
            Err(LightError::Negative { nm: 370.0, .. })
        ));
        // nothing positive: no light
        let t = Tabulated::new(&nm, &[-0.001f32; 81]).unwrap();
        assert_eq!(check_sign(&t), Err(LightError::Dark));
    }

    #[test]
    fn dark_lights_are_errors() {
        assert_eq!(Spd::from_fn(5, |_| 0.0), Err(LightError::Dark));
        assert_eq!(Spd::from_fn(1, |_| f64::NAN), Err(LightError::Dark));
    }
}
