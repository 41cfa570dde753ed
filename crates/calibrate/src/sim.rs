//! A simulated display built from its primaries' spectral power distributions, for testing the
//! measuring workflow without hardware and for checking the fit against a known truth.
//!
//! `sim:SPD[,KEY=VALUE...]` on the command line (`--display` or `--instrument`):
//!
//! | key | default | meaning |
//! |---|---|---|
//! | `SPD` | — | `crt` (built-in, Brainard 1997), `qdoled`, `wled` or `broadband` (built-in model spectra, [`crate::model_spectra`]) or a spectral CSV with `red`, `green`, `blue` columns (or exactly three columns, in that order) |
//! | `white` | `100` | luminance of full white (primaries only), cd/m² |
//! | `gamma` | `2.2` | transfer curve: a number (pure power law), `srgb` (IEC 61966-2-1) or `linear` |
//! | `black` | `0` | black level, cd/m², with the chromaticity of the display's white |
//! | `flare` | `0` | veiling flare (ambient light reflected by the screen), cd/m², chromaticity of D65 |
//! | `white_xy` | — | the native white's chromaticity `X:Y` (e.g. `0.28:0.29`, far bluer than D65): each primary's luminance is rescaled so R + G + B has it (a panel whose backlight or phosphor balance is off) |
//! | `crosstalk` | `0` | channel interaction: each channel's light falls by `crosstalk` × the mean linear drive of the other two (a power supply sagging under load), so white ≠ R + G + B |
//! | `noise` | `0` | measurement noise: each reading's X, Y, Z are multiplied by `1 + σ·N(0, 1)`, σ = `noise` |
//! | `seed` | `1` | seed of the noise (the same seed gives the same readings) |
//!
//! The truth: each primary's XYZ at full drive is the SPD (linearly interpolated) integrated
//! against the CIE 1931 2° observer at 1 nm over 380–780 nm (core's `exact_xyz`), and the three
//! are scaled together so full white has `Y = white`. A device triple `rgb ∈ [0, 1]³` gives
//! `XYZ = Σᵢ Lᵢ · Pᵢ + black + flare`, with `Lᵢ` the transfer curve of `rgbᵢ` after crosstalk.
//!
//! The model keeps the spectra too ([`SimModel::spectrum`]): each primary's SPD at 1 nm over
//! 380–780 nm scaled by the same factor as its XYZ, in W·sr⁻¹·m⁻²·nm⁻¹ (so that
//! `683.002 lm/W · Σ S(λ) ȳ(λ) Δλ` is its luminance in cd/m²), the black as the white's
//! spectrum scaled to `black`, the flare as D65's scaled to `flare`. A patch's spectrum is
//! `Σᵢ Lᵢ Sᵢ(λ) + black(λ) + flare(λ)`: its XYZ under any observer, and what a spectrometer
//! reads.

use crate::error::{Error, Result};
use specpoly_core::{exact_xyz, Illuminant, Observer, Tabulated, Transfer};
use specpoly_formats::device_spec::DeviceSpec;
use specpoly_spectra::spectrum_names;
use std::sync::{Arc, Mutex};

/// The options of a simulated display.
#[derive(Clone, Debug, PartialEq)]
pub struct SimOptions {
    /// Luminance of full white (primaries only), cd/m².
    pub white: f64,
    /// The channels' transfer curve.
    pub transfer: Transfer,
    /// Black level, cd/m² (white's chromaticity).
    pub black: f64,
    /// Flare, cd/m² (D65 chromaticity).
    pub flare: f64,
    /// The native white's chromaticity, if set (see the module docs).
    pub white_xy: Option<[f64; 2]>,
    /// Channel interaction (see the module docs).
    pub crosstalk: f64,
    /// Relative measurement noise σ.
    pub noise: f64,
    /// Noise seed.
    pub seed: u64,
}

impl SimOptions {
    /// The options of `sim:SPD[,KEY=VALUE...]` (see the module docs).
    pub fn from_spec(spec: &DeviceSpec<'_>) -> Result<Self> {
        let mut o = SimOptions::default();
        for &(k, v) in &spec.options {
            match k {
                "white" => {
                    o.white = spec.non_negative(k, v)?;
                    if o.white == 0.0 {
                        return Err(spec.bad(k, v, "must be > 0").into());
                    }
                }
                "gamma" => o.transfer = gamma(spec, v)?,
                "srgb" if v.is_empty() => o.transfer = Transfer::Srgb,
                "black" => o.black = spec.non_negative(k, v)?,
                "white_xy" => {
                    let xy = v
                        .split_once(':')
                        .map(|(x, y)| (spec.number(k, x), spec.number(k, y)));
                    match xy {
                        Some((Ok(x), Ok(y))) if x > 0.0 && y > 0.0 && x + y < 1.0 => {
                            o.white_xy = Some([x, y])
                        }
                        _ => {
                            return Err(spec
                                .bad(k, v, "expected X:Y with x, y > 0 and x + y < 1")
                                .into())
                        }
                    }
                }
                "flare" => o.flare = spec.non_negative(k, v)?,
                "crosstalk" => {
                    o.crosstalk = spec.non_negative(k, v)?;
                    if o.crosstalk >= 1.0 {
                        return Err(spec.bad(k, v, "must be < 1").into());
                    }
                }
                "noise" => o.noise = spec.non_negative(k, v)?,
                "seed" => o.seed = spec.integer(k, v)?,
                _ => {
                    return Err(spec
                        .unknown(
                            k,
                            "white, gamma, black, white_xy, flare, crosstalk, noise, seed",
                        )
                        .into())
                }
            }
        }
        Ok(o)
    }
}

/// `gamma=`: a number 0.1–10 (pure power law), `srgb` or `linear`.
fn gamma(spec: &DeviceSpec<'_>, v: &str) -> Result<Transfer> {
    Ok(match v {
        "srgb" | "sRGB" => Transfer::Srgb,
        "linear" | "1" => Transfer::Linear,
        _ => {
            let g = spec.number("gamma", v)?;
            if !(0.1..=10.0).contains(&g) {
                return Err(spec
                    .bad("gamma", v, "expected 0.1–10, `srgb` or `linear`")
                    .into());
            }
            Transfer::Gamma(g as f32)
        }
    })
}

impl Default for SimOptions {
    fn default() -> Self {
        Self {
            white: 100.0,
            transfer: Transfer::Gamma(2.2),
            black: 0.0,
            white_xy: None,
            flare: 0.0,
            crosstalk: 0.0,
            noise: 0.0,
            seed: 1,
        }
    }
}

/// A simulated display: primaries from spectra, transfer curve, black, flare, crosstalk.
#[derive(Clone, Debug, PartialEq)]
pub struct SimModel {
    /// Where the primaries came from (`crt`, a file name).
    pub source: String,
    /// Options.
    pub options: SimOptions,
    /// XYZ of each primary at full drive (`primaries[i]` = channel `i`), cd/m².
    pub primaries: [[f64; 3]; 3],
    /// Constant XYZ added to every patch: black level + flare.
    pub offset: [f64; 3],
    /// Each primary's spectrum at full drive, 1 nm over 380–780 nm, W·sr⁻¹·m⁻²·nm⁻¹.
    pub spectra: [Vec<f64>; 3],
    /// The spectrum added to every patch (black level + flare), same grid and unit.
    pub offset_spectrum: Vec<f64>,
}

/// The luminous efficacy of radiation at 555 nm used with the CIE observers, lm/W (CIE 015).
pub const KM: f64 = 683.002;

/// `KM · Σ S(λ) c̄(λ)` over 1 nm steps of 380–780 nm: the XYZ (cd/m² when `S` is in
/// W·sr⁻¹·m⁻²·nm⁻¹) of a spectrum sampled at 380, 381, … 780 nm under `observer`.
pub fn spectrum_xyz(observer: Observer, s: &[f64]) -> [f64; 3] {
    let mut xyz = [0.0; 3];
    for (v, c) in s.iter().zip(observer.table().iter()) {
        for k in 0..3 {
            xyz[k] += v * c[k] as f64;
        }
    }
    xyz.map(|v| v * KM)
}

/// XYZ of a spectral power distribution under the CIE 1931 observer, on the scale where the
/// equal-energy spectrum of value 1 has `Y = 100` (any common scale will do: the primaries are
/// rescaled together).
fn spd_xyz(spd: &Tabulated<'_>) -> [f64; 3] {
    let e = Illuminant::E.tabulated();
    let e100 = e.at(550.0);
    let (xyz, _) = exact_xyz(Observer::Cie1931, &e, |nm| spd.at(nm) / e100);
    xyz
}

impl SimModel {
    /// Builds a model from three SPDs `[red, green, blue]` (wavelengths, values) and options.
    pub fn from_spds(
        source: &str,
        wavelengths: &[f32],
        spds: [&[f32]; 3],
        options: SimOptions,
    ) -> Result<Self> {
        let mut p = [[0.0f64; 3]; 3];
        for (i, s) in spds.iter().enumerate() {
            let t = Tabulated::new(wavelengths, s).map_err(|error| Error::SimChannel {
                spectra: source.to_string(),
                channel: i,
                error,
            })?;
            p[i] = spd_xyz(&t);
        }
        if let Some([x, y]) = options.white_xy {
            // scale each primary so that R + G + B has the chromaticity (x, y): s = P⁻¹ · W
            let m = [0, 1, 2].map(|r| [p[0][r], p[1][r], p[2][r]]);
            let w = [x / y, 1.0, (1.0 - x - y) / y];
            let s = specpoly_core::Mat3(m)
                .inverse()
                .ok()
                .map(|inv| inv.0)
                .map(|inv| [0, 1, 2].map(|r| (0..3).map(|c| inv[r][c] * w[c]).sum::<f64>()))
                .filter(|s| s.iter().all(|v| *v > 0.0 && v.is_finite()))
                .ok_or_else(|| Error::SimWhiteOutside {
                    spectra: source.to_string(),
                    x,
                    y,
                })?;
            for (c, k) in p.iter_mut().zip(s) {
                for v in c.iter_mut() {
                    *v *= k;
                }
            }
        }
        let y: f64 = p.iter().map(|c| c[1]).sum();
        if y.is_nan() || y <= 0.0 {
            return Err(Error::SimNoLuminance {
                spectra: source.to_string(),
            });
        }
        let k = options.white / y;
        for c in p.iter_mut() {
            for v in c.iter_mut() {
                *v *= k;
            }
        }
        let white: [f64; 3] = [0, 1, 2].map(|j| p[0][j] + p[1][j] + p[2][j]);
        let d65 = {
            let (w, _) = exact_xyz(Observer::Cie1931, &Illuminant::D65.tabulated(), |_| 1.0);
            w
        };
        let mut offset = [0.0; 3];
        for j in 0..3 {
            offset[j] = white[j] / white[1] * options.black + d65[j] / d65[1] * options.flare;
        }
        // the spectra, each scaled so its 1931 luminance is the primary's
        let mut spectra: [Vec<f64>; 3] = Default::default();
        for (i, s) in spds.iter().enumerate() {
            let t = Tabulated::new(wavelengths, s).map_err(|error| Error::SimChannel {
                spectra: source.to_string(),
                channel: i,
                error,
            })?;
            let raw: Vec<f64> = (380..=780).map(|nm| t.at(nm as f64)).collect();
            let y = spectrum_xyz(Observer::Cie1931, &raw)[1];
            let k = if y > 0.0 { p[i][1] / y } else { 0.0 };
            spectra[i] = raw.iter().map(|v| v * k).collect();
        }
        let d65_spd: Vec<f64> = {
            let t = Illuminant::D65.tabulated();
            (380..=780).map(|nm| t.at(nm as f64)).collect()
        };
        let d65_y = spectrum_xyz(Observer::Cie1931, &d65_spd)[1];
        let offset_spectrum = (0..401)
            .map(|j| {
                let w: f64 = spectra.iter().map(|s| s[j]).sum();
                w / white[1] * options.black + d65_spd[j] / d65_y * options.flare
            })
            .collect();
        Ok(Self {
            source: source.to_string(),
            options,
            primaries: p,
            offset,
            spectra,
            offset_spectrum,
        })
    }

    /// Parses `SPD[,KEY=VALUE...]` (the part after `sim:`).
    pub fn parse(spec: &str) -> Result<Self> {
        Self::from_spec(&DeviceSpec::parse(&format!("sim:{spec}")))
    }

    /// Builds the model of `sim:SPD[,KEY=VALUE...]`.
    pub fn from_spec(spec: &DeviceSpec<'_>) -> Result<Self> {
        let base = spec.required_arg(
            "the primaries' spectra",
            "sim:crt` or `sim:FILE.csv` (columns red, green, blue)",
        )?;
        let o = SimOptions::from_spec(spec)?;
        if let Some(p) = crate::model_spectra::primaries(base) {
            let wl = crate::model_spectra::wavelengths();
            return Self::from_spds(base, &wl, [&p[0], &p[1], &p[2]], o);
        }
        let (source, table) = spectrum_names::load_table(base)?;
        let find = |name: &str| {
            table
                .columns
                .iter()
                .position(|(n, _)| n.eq_ignore_ascii_case(name))
        };
        let idx = match (find("red"), find("green"), find("blue")) {
            (Some(r), Some(g), Some(b)) => [r, g, b],
            _ if table.columns.len() == 3 => [0, 1, 2],
            _ => {
                return Err(Error::SimColumns {
                    spectra: source.to_string(),
                    columns: table
                        .columns
                        .iter()
                        .map(|(n, _)| n.as_str())
                        .collect::<Vec<_>>()
                        .join(", "),
                })
            }
        };
        Self::from_spds(
            &source,
            &table.wavelengths,
            idx.map(|i| table.columns[i].1.as_slice()),
            o,
        )
    }

    /// Each channel's light (0–1 of its full drive) for device values `rgb`: the transfer
    /// curve, then crosstalk.
    pub fn channel_light(&self, rgb: [f64; 3]) -> [f64; 3] {
        let lin = rgb.map(|v| self.options.transfer.decode(v.clamp(0.0, 1.0) as f32) as f64);
        let c = self.options.crosstalk;
        [0, 1, 2].map(|i| {
            let others = (lin[(i + 1) % 3] + lin[(i + 2) % 3]) / 2.0;
            lin[i] * (1.0 - c * others)
        })
    }

    /// The true spectrum (W·sr⁻¹·m⁻²·nm⁻¹ at 380, 381, … 780 nm) for device values `rgb`.
    pub fn spectrum(&self, rgb: [f64; 3]) -> Vec<f64> {
        let eff = self.channel_light(rgb);
        let mut out = self.offset_spectrum.clone();
        for (i, e) in eff.iter().enumerate() {
            for (o, s) in out.iter_mut().zip(&self.spectra[i]) {
                *o += e * s;
            }
        }
        out
    }

    /// The true XYZ (cd/m²) for device values `rgb ∈ [0, 1]³`, without measurement noise.
    pub fn xyz(&self, rgb: [f64; 3]) -> [f64; 3] {
        let eff = self.channel_light(rgb);
        let mut out = self.offset;
        for (i, e) in eff.iter().enumerate() {
            for (j, o) in out.iter_mut().enumerate() {
                *o += e * self.primaries[i][j];
            }
        }
        out
    }

    /// The primaries' chromaticities `[x, y]` and luminances (cd/m²): the truth a fit should
    /// recover.
    pub fn primaries_xy_y(&self) -> [[f64; 3]; 3] {
        self.primaries.map(|p| {
            let s = p[0] + p[1] + p[2];
            [p[0] / s, p[1] / s, p[1]]
        })
    }

    /// One-line description.
    pub fn describe(&self) -> String {
        let o = &self.options;
        let trc = match &o.transfer {
            Transfer::Srgb => "srgb".to_string(),
            Transfer::Linear => "linear".to_string(),
            Transfer::Gamma(g) => format!("gamma {g}"),
            Transfer::Table(_) => "table".to_string(),
        };
        format!(
            "simulated display `{}` (white {} cd/m²{}, {trc}, black {}, flare {}, crosstalk {}, noise {}, seed {})",
            self.source,
            o.white,
            o.white_xy
                .map(|[x, y]| format!(" at x {x} y {y}"))
                .unwrap_or_default(),
            o.black,
            o.flare,
            o.crosstalk,
            o.noise,
            o.seed
        )
    }
}

/// A deterministic normal deviate source (SplitMix64 + Box–Muller): no dependency, the same
/// numbers on every platform for a seed.
#[derive(Clone, Debug)]
pub struct Noise {
    state: u64,
    spare: Option<f64>,
}

impl Noise {
    /// Seeded.
    pub fn new(seed: u64) -> Self {
        Self {
            state: seed ^ 0x5DEE_CE66_D1CE_4E5B,
            spare: None,
        }
    }

    fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in (0, 1].
    fn uniform(&mut self) -> f64 {
        ((self.next_u64() >> 11) as f64 + 1.0) / (1u64 << 53) as f64
    }

    /// A standard normal deviate.
    pub fn normal(&mut self) -> f64 {
        if let Some(s) = self.spare.take() {
            return s;
        }
        let (u, v) = (self.uniform(), self.uniform());
        let r = (-2.0 * u.ln()).sqrt();
        let t = std::f64::consts::TAU * v;
        self.spare = Some(r * t.sin());
        r * t.cos()
    }
}

/// The state a simulated display and the instruments reading it share.
#[derive(Debug)]
pub struct SimState {
    /// The model.
    pub model: SimModel,
    /// The patch on screen (device values).
    pub current: [f64; 3],
    noise: Noise,
}

/// A shared handle on a simulated display: the display sets the patch, instruments (the `sim`
/// instrument, or the PR-655 emulator in the tests) read it.
#[derive(Clone, Debug)]
pub struct SimHandle(Arc<Mutex<SimState>>);

impl SimHandle {
    /// A new simulated display showing black.
    pub fn new(model: SimModel) -> Self {
        let noise = Noise::new(model.options.seed);
        Self(Arc::new(Mutex::new(SimState {
            model,
            current: [0.0; 3],
            noise,
        })))
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, SimState> {
        // a panic while holding the lock cannot leave the state inconsistent (plain values)
        self.0.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Shows a patch.
    pub fn set(&self, rgb: [f64; 3]) {
        self.lock().current = rgb;
    }

    /// The patch on screen.
    pub fn current(&self) -> [f64; 3] {
        self.lock().current
    }

    /// The model.
    pub fn model(&self) -> SimModel {
        self.lock().model.clone()
    }

    /// The true XYZ of the patch on screen.
    pub fn true_xyz(&self) -> [f64; 3] {
        let s = self.lock();
        s.model.xyz(s.current)
    }

    /// A spectrometer's reading of the patch on screen: the true spectrum times the model's
    /// measurement noise (one factor for the whole spectrum).
    pub fn read_spectrum(&self) -> Vec<f64> {
        let mut s = self.lock();
        let sp = s.model.spectrum(s.current);
        let sigma = s.model.options.noise;
        if sigma == 0.0 {
            return sp;
        }
        let k = 1.0 + sigma * s.noise.normal();
        sp.into_iter().map(|v| v * k).collect()
    }

    /// A reading of the patch on screen: the truth with the model's measurement noise.
    pub fn read(&self) -> [f64; 3] {
        let mut s = self.lock();
        let xyz = s.model.xyz(s.current);
        let sigma = s.model.options.noise;
        if sigma == 0.0 {
            return xyz;
        }
        xyz.map(|v| v * (1.0 + sigma * s.noise.normal()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crt_white_and_chromaticities() {
        let m = SimModel::parse("crt").unwrap();
        let w = m.xyz([1.0; 3]);
        assert!((w[1] - 100.0).abs() < 1e-9);
        let p = m.primaries_xy_y();
        // a CRT's P22-like phosphors: red x > 0.6, green y > 0.55, blue y < 0.1
        assert!(p[0][0] > 0.6 && p[1][1] > 0.55 && p[2][1] < 0.1, "{p:?}");
        assert_eq!(m.xyz([0.0; 3]), [0.0; 3]);
    }

    #[test]
    fn options_parse_and_apply() {
        let m =
            SimModel::parse("crt,white=80,gamma=srgb,black=0.5,flare=0.2,crosstalk=0.02").unwrap();
        assert_eq!(m.options.transfer, Transfer::Srgb);
        let b = m.xyz([0.0; 3]);
        assert!((b[1] - 0.7).abs() < 1e-9);
        let w = m.xyz([1.0; 3]);
        // crosstalk: each channel loses 2 %
        assert!((w[1] - (0.7 + 80.0 * 0.98)).abs() < 1e-6, "{w:?}");
        assert!(SimModel::parse("crt,bogus=1").is_err());
        let warm = SimModel::parse("crt,white_xy=0.28:0.29").unwrap();
        let w = warm.xyz([1.0; 3]);
        let s = w[0] + w[1] + w[2];
        assert!((w[0] / s - 0.28).abs() < 1e-9 && (w[1] / s - 0.29).abs() < 1e-9);
        assert!((w[1] - 100.0).abs() < 1e-9);
        assert!(SimModel::parse("crt,white_xy=0.9:0.05").is_err());
        assert!(SimModel::parse("crt,white_xy=0.3").is_err());
        assert!(SimModel::parse("crt,gamma=x").is_err());
        assert!(SimModel::parse("").is_err());
    }

    #[test]
    fn noise_is_seeded() {
        let h1 = SimHandle::new(SimModel::parse("crt,noise=0.01,seed=7").unwrap());
        let h2 = SimHandle::new(SimModel::parse("crt,noise=0.01,seed=7").unwrap());
        h1.set([1.0; 3]);
        h2.set([1.0; 3]);
        let (a, b) = (h1.read(), h2.read());
        assert_eq!(a, b);
        assert!((a[1] - 100.0).abs() < 10.0 && a[1] != 100.0);
        let mut n = Noise::new(3);
        let xs: Vec<f64> = (0..20000).map(|_| n.normal()).collect();
        let mean = xs.iter().sum::<f64>() / xs.len() as f64;
        let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / xs.len() as f64;
        assert!(
            mean.abs() < 0.03 && (var - 1.0).abs() < 0.05,
            "{mean} {var}"
        );
    }
}
