//! A display modelled by spectra: its primaries' spectra at full drive and its black's, so one
//! set of measurements gives the display's XYZ under any observer.
//!
//! A patch's spectrum is `S(rgb) = Σᵢ Lᵢ(rgbᵢ)·Pᵢ(λ) + K(λ)`, with `Pᵢ` primary `i`'s spectrum
//! above black (full channel `i` minus black), `K` the black's and `Lᵢ` the channel's transfer
//! curve (a power law). Its XYZ under observer `o` is `683.002 · Σ S(λ) ō(λ) Δλ`
//! ([`crate::sim::spectrum_xyz`]), so the display's primaries and white are known under every
//! observer: CIE 1931, 1964, 2015, a viewer's own.
//!
//! From a spectral `.ti3` (ArgyllCMS `dispread` with a spectrometer, or `calibrate simulate`):
//! the patches at device (1,0,0), (0,1,0), (0,0,1) and (0,0,0) give `Pᵢ + K` and `K` (repeats
//! averaged); the spectra are resampled linearly to 1 nm over 380–780 nm (0 outside the
//! measured bands). The transfer curve's exponent `γ` is fitted to the single-channel and grey
//! ramps' luminance above black, `L(v) = v^γ`, least squares on `ln L` over the patches with
//! `0.05 ≤ L ≤ 0.95`; 2.2 when there are none.

use crate::error::{Error, Result};
use crate::sim::{spectrum_xyz, SimModel};
use specpoly_core::{Observer, Transfer};
use specpoly_formats::cgats::Ti3;

/// 1 nm samples over 380..=780 nm.
pub const SAMPLES: usize = 401;

/// Every patch's XYZ of a spectral `.ti3` recomputed from its spectrum under `observer`, on the
/// file's own scale: `k · 683.002 · Σ S(λ) ō(λ)` at 1 nm over 380–780 nm (the spectra
/// resampled linearly, 0 outside the measured bands), `k` making the brightest patch's CIE 1931
/// `Y` of its spectrum equal to the `Y` the file gives it (so relative and absolute files keep
/// their units). Under CIE 1931 this gives back the file's XYZ when they were computed from the
/// same spectra. `source` names the file in errors.
///
/// Errors: [`Error::SpectralTi3`] without spectra, or when the brightest patch is dark.
pub fn xyz_under(t: &Ti3, observer: Observer, source: &str) -> Result<Vec<[f64; 3]>> {
    let bad = |why: &str| Error::SpectralTi3 {
        file: source.to_string(),
        why: why.to_string(),
    };
    let spectra = t.spectra.as_ref().ok_or_else(|| {
        bad("no spectra (SPECTRAL_BANDS and SPEC_… fields) to compute XYZ under another observer from: measure with a spectrometer")
    })?;
    let resampled =
        |i: usize| -> Vec<f64> { (380..=780).map(|nm| spectra.at(i, nm as f64)).collect() };
    let brightest = (0..t.measurements.len())
        .filter(|i| t.measurements[*i].xyz[1].is_finite())
        .max_by(|a, b| t.measurements[*a].xyz[1].total_cmp(&t.measurements[*b].xyz[1]))
        .ok_or_else(|| bad("no patches"))?;
    let y_file = t.measurements[brightest].xyz[1];
    let y_spec = spectrum_xyz(Observer::Cie1931, &resampled(brightest))[1];
    if !(y_file > 0.0 && y_spec > 0.0 && y_spec.is_finite()) {
        return Err(bad("the brightest patch is dark: no scale for the spectra"));
    }
    let k = y_file / y_spec;
    Ok((0..t.measurements.len())
        .map(|i| spectrum_xyz(observer, &resampled(i)).map(|v| v * k))
        .collect())
}

/// A display's spectral model.
#[derive(Clone, Debug, PartialEq)]
pub struct SpectralDisplay {
    /// Where it came from.
    pub name: String,
    /// Each primary's spectrum above black at full drive, W·sr⁻¹·m⁻²·nm⁻¹ at 380…780 nm.
    pub primaries: [Vec<f64>; 3],
    /// The black's spectrum.
    pub black: Vec<f64>,
    /// The channels' transfer curve.
    pub transfer: Transfer,
}

impl SpectralDisplay {
    /// The spectral model of a simulated display (its truth; crosstalk is not modelled).
    pub fn from_sim(m: &SimModel) -> Self {
        Self {
            name: m.source.clone(),
            primaries: m.spectra.clone(),
            black: m.offset_spectrum.clone(),
            transfer: m.options.transfer.clone(),
        }
    }

    /// The model of a spectral `.ti3` (see the module docs); `source` names it in errors.
    pub fn from_ti3(t: &Ti3, source: &str) -> Result<Self> {
        let bad = |why: String| Error::SpectralTi3 {
            file: source.to_string(),
            why,
        };
        let spectra = t.spectra.as_ref().ok_or_else(|| {
            bad("no spectra (SPECTRAL_BANDS and SPEC_… fields: measure with a spectrometer)".into())
        })?;
        // spectra on the file's XYZ scale; to cd/m²-consistent radiance (mW → W) when absolute
        let scale = t.absolute_scale().unwrap_or(1.0) / 1000.0;
        let resampled = |i: usize| -> Vec<f64> {
            (380..=780)
                .map(|nm| spectra.at(i, nm as f64) * scale)
                .collect()
        };
        let mean_of = |target: [f64; 3]| -> Option<Vec<f64>> {
            let idx: Vec<usize> = t
                .measurements
                .iter()
                .enumerate()
                .filter(|(_, m)| (0..3).all(|k| (m.device[k] - target[k]).abs() < 1e-6))
                .map(|(i, _)| i)
                .collect();
            if idx.is_empty() {
                return None;
            }
            let mut s = vec![0.0; SAMPLES];
            for i in &idx {
                for (a, b) in s.iter_mut().zip(resampled(*i)) {
                    *a += b / idx.len() as f64;
                }
            }
            Some(s)
        };
        let black = mean_of([0.0; 3]).ok_or_else(|| bad("no black patch (0, 0, 0)".into()))?;
        let mut primaries: [Vec<f64>; 3] = Default::default();
        for (i, name) in ["red (1, 0, 0)", "green (0, 1, 0)", "blue (0, 0, 1)"]
            .iter()
            .enumerate()
        {
            let mut d = [0.0; 3];
            d[i] = 1.0;
            let full = mean_of(d).ok_or_else(|| bad(format!("no full {name} patch")))?;
            primaries[i] = full.iter().zip(&black).map(|(f, k)| f - k).collect();
            let y = spectrum_xyz(Observer::Cie1931, &primaries[i])[1];
            if !(y > 0.0) {
                return Err(bad(format!("the {name} patch is not brighter than black")));
            }
        }
        // the transfer curve's exponent from single-channel and grey ramps
        let k_y = spectrum_xyz(Observer::Cie1931, &black)[1];
        let p_y = primaries
            .clone()
            .map(|p| spectrum_xyz(Observer::Cie1931, &p)[1]);
        let (mut sxx, mut sxy) = (0.0, 0.0);
        let xyz_scale = t.absolute_scale().unwrap_or(1.0);
        for m in &t.measurements {
            let on: Vec<usize> = (0..3).filter(|k| m.device[*k] > 0.0).collect();
            let v = m.device[on.first().copied().unwrap_or(0)];
            let single = on.len() == 1;
            let grey = on.len() == 3 && m.device.iter().all(|d| (d - v).abs() < 1e-9);
            if !(single || grey) || !(0.02..0.98).contains(&v) {
                continue;
            }
            let full: f64 = on.iter().map(|k| p_y[*k]).sum();
            let l = (m.xyz[1] * xyz_scale - k_y) / full;
            if (0.05..=0.95).contains(&l) {
                sxx += v.ln() * v.ln();
                sxy += v.ln() * l.ln();
            }
        }
        let gamma = if sxx > 0.0 { sxy / sxx } else { 2.2 };
        Ok(Self {
            name: source.to_string(),
            primaries,
            black,
            transfer: Transfer::Gamma(gamma as f32),
        })
    }

    /// The primaries' XYZ above black at full drive under `observer` (`[i]` = channel `i`).
    pub fn primaries_xyz(&self, observer: Observer) -> [[f64; 3]; 3] {
        [0, 1, 2].map(|i| spectrum_xyz(observer, &self.primaries[i]))
    }

    /// The black's XYZ under `observer`.
    pub fn black_xyz(&self, observer: Observer) -> [f64; 3] {
        spectrum_xyz(observer, &self.black)
    }

    /// The XYZ under `observer` of the channels' light `lin` (0–1 of full drive).
    pub fn xyz_linear(&self, lin: [f64; 3], observer: Observer) -> [f64; 3] {
        let p = self.primaries_xyz(observer);
        let mut out = self.black_xyz(observer);
        for i in 0..3 {
            for k in 0..3 {
                out[k] += lin[i] * p[i][k];
            }
        }
        out
    }

    /// The XYZ under `observer` of device values `rgb`.
    pub fn xyz(&self, rgb: [f64; 3], observer: Observer) -> [f64; 3] {
        let lin = rgb.map(|v| self.transfer.decode(v.clamp(0.0, 1.0) as f32) as f64);
        self.xyz_linear(lin, observer)
    }

    /// The spectrum of device values `rgb`.
    pub fn spectrum(&self, rgb: [f64; 3]) -> Vec<f64> {
        let lin = rgb.map(|v| self.transfer.decode(v.clamp(0.0, 1.0) as f32) as f64);
        let mut s = self.black.clone();
        for i in 0..3 {
            for (o, p) in s.iter_mut().zip(&self.primaries[i]) {
                *o += lin[i] * p;
            }
        }
        s
    }
}
