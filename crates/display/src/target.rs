//! Calibration to targets (what ArgyllCMS's `dispcal` does): per-channel video LUTs that bring
//! a display's grey axis to a target white point, luminance and tone curve, refined from
//! measurements until the target is met or no better is possible.
//!
//! `--target white=D65|native|X,Y,gamma=G|srgb|bt1886|lstar,luminance=N|native` (any order,
//! any subset; defaults `white=D65,gamma=2.2,luminance=native`), parsed with the project's one
//! `key=value` parser ([`specpoly_formats::device_spec`]).
//!
//! **The aim.** With the display's black `K` (device 0, which no LUT can lower) and the target
//! white `W` (the chromaticity asked for, at the luminance asked for or the highest the display
//! reaches at that chromaticity), the grey of input `v` should measure
//!
//! ```text
//! XYZ(v) = K + f(v) · (W − K)
//! ```
//!
//! with `f` the relative tone curve, `f(0) = 0`, `f(1) = 1`: `gamma=G` `f = v^G`; `srgb` the
//! IEC 61966-2-1 decoding; `lstar` the CIE 1976 lightness scale (`L* = 100 v`); `bt1886` the
//! ITU-R BT.1886 EOTF `L = a·max(v + b, 0)^2.4` for the display's own white and black
//! luminances `L_W`, `L_B` (`a = (L_W^{1/2.4} − L_B^{1/2.4})^{2.4}`, `b = L_B^{1/2.4} /
//! (L_W^{1/2.4} − L_B^{1/2.4})`), `f = (L − L_B)/(L_W − L_B)`. The line from `K` to `W` is what
//! an additive display can show exactly: its linear drive is `f(v)` times that of `W`. Near
//! black the chromaticity so moves from the black's to the white's, as `dispcal` blends it.
//!
//! **The solve.** The first LUT is the model's inverse of the aim at each of the LUT's
//! entries ([`initial_lut`]). Each iteration measures a grey ramp through the LUT, and moves
//! each measured level by the model's local correction: `rgb' = inverse(predict(rgb) + aim −
//! measured)` (a Newton step with the model's Jacobian), the corrections interpolated linearly
//! between the measured levels ([`refine`]); after the first, steps are damped by
//! [`LATER_GAIN`] so reading noise is not carried into the LUT in full. It stops when every
//! grey is within [`GREY_TOLERANCE`] (ΔE00) and [`TONE_TOLERANCE`] (luminance) of its aim, after
//! [`MISSES`] iterations in a row that do not improve on the best (the best LUT is kept), or
//! after [`Options::iterations`].

use crate::calibration::Calibration;
use crate::error::{Error, Result};
use crate::video_lut::VideoLut;
use specpoly_core::delta_e2000_xyz as delta_e00;
use specpoly_formats::device_spec::DeviceSpec;

/// A grey (and the white) counts as on target within this ΔE00 of its aim: DisplayCAL's
/// "recommended" white tolerance (1) halved, as the refinement reaches it on every simulated
/// display with 0.1 % reading noise.
pub const GREY_TOLERANCE: f64 = 0.5;

/// A white of a chromaticity other than the native one is aimed this far below the brightest
/// the model says the display reaches, so the measured refinement has room to correct the
/// model's error (a channel at full drive cannot go higher).
pub const HEADROOM: f64 = 0.99;

/// The step taken after the first refinement, a fraction of the model's: the first corrects
/// the model's error in full; later ones mostly see reading noise, which a full step would
/// carry into the LUT (a damped step of gain `g` leaves `g / (2 − g)` of its variance).
pub const LATER_GAIN: f64 = 0.6;

/// Iterations in a row that do not improve on the best before the solve gives up.
pub const MISSES: usize = 2;

/// A grey's luminance counts as on target within this share of the white's, in percent.
pub const TONE_TOLERANCE: f64 = 0.5;

/// The target white.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum White {
    /// The display's own white (device 1, 1, 1).
    Native,
    /// A chromaticity `x, y` (D65 is `0.3127, 0.3290`).
    Xy([f64; 2]),
}

/// The target tone curve of the grey axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tone {
    /// `f(v) = v^γ`.
    Gamma(f64),
    /// IEC 61966-2-1 (sRGB).
    Srgb,
    /// ITU-R BT.1886 for the display's black and white.
    Bt1886,
    /// CIE L*: perceptually even steps.
    Lstar,
}

/// `--target`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Target {
    /// White point.
    pub white: White,
    /// Tone curve.
    pub tone: Tone,
    /// White luminance, cd/m² (`None`: the most the display gives at the target white).
    pub luminance: Option<f64>,
}

impl Default for Target {
    fn default() -> Self {
        Target {
            white: White::Xy(D65),
            tone: Tone::Gamma(2.2),
            luminance: None,
        }
    }
}

/// D65's chromaticity (CIE 15:2004, 4 decimals as IEC 61966-2-1 writes it).
pub const D65: [f64; 2] = [0.3127, 0.3290];

/// Parses `--target` (the clap value parser).
pub fn parse(s: &str) -> Result<Target> {
    let text = format!("target,{s}");
    let spec = DeviceSpec::parse(&text);
    let mut t = Target::default();
    let mut i = 0;
    let opts = &spec.options;
    let bad = |k: &str, v: &str, why: &'static str| Error::TargetValue {
        spec: s.to_string(),
        key: k.to_string(),
        value: v.to_string(),
        why,
    };
    while i < opts.len() {
        let (k, v) = opts[i];
        match k {
            "white" => {
                t.white = match v.to_ascii_lowercase().as_str() {
                    "native" => White::Native,
                    "d65" => White::Xy(D65),
                    "d50" => White::Xy([0.3457, 0.3585]),
                    _ => {
                        // `x,y` (the `,` splits it into two options) or `x:y`
                        let (xs, ys) = match v.split_once(':') {
                            Some((x, y)) => (x, y),
                            None => {
                                let y = opts
                                    .get(i + 1)
                                    .filter(|(y, e)| e.is_empty() && y.parse::<f64>().is_ok())
                                    .map(|(y, _)| *y)
                                    .ok_or_else(|| bad(k, v, "expected D65, D50, native or x,y"))?;
                                i += 1;
                                (v, y)
                            }
                        };
                        let x = spec.number(k, xs).map_err(|_| bad(k, v, "not a number"))?;
                        let y = spec.number(k, ys).map_err(|_| bad(k, ys, "not a number"))?;
                        if !(x > 0.0 && y > 0.0 && x + y < 1.0) {
                            return Err(bad(k, v, "x, y must be > 0 with x + y < 1"));
                        }
                        White::Xy([x, y])
                    }
                }
            }
            "gamma" | "tone" => {
                t.tone = match v.to_ascii_lowercase().as_str() {
                    "srgb" => Tone::Srgb,
                    "bt1886" => Tone::Bt1886,
                    "lstar" | "l*" => Tone::Lstar,
                    _ => match v.parse::<f64>() {
                        Ok(g) if (1.0..=4.0).contains(&g) => Tone::Gamma(g),
                        _ => return Err(bad(k, v, "expected 1–4, srgb, bt1886 or lstar")),
                    },
                }
            }
            "luminance" => {
                t.luminance = if v.eq_ignore_ascii_case("native") || v.eq_ignore_ascii_case("max") {
                    None
                } else {
                    match v.parse::<f64>() {
                        Ok(l) if l.is_finite() && l > 0.0 && l <= 10_000.0 => Some(l),
                        _ => return Err(bad(k, v, "expected cd/m² in (0, 10000] or native")),
                    }
                }
            }
            _ => {
                return Err(Error::TargetKey {
                    spec: s.to_string(),
                    key: k.to_string(),
                })
            }
        }
        i += 1;
    }
    Ok(t)
}

impl std::fmt::Display for Target {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.white {
            White::Native => write!(f, "white=native")?,
            White::Xy([x, y]) => write!(f, "white={x},{y}")?,
        }
        match self.tone {
            Tone::Gamma(g) => write!(f, ",gamma={g}")?,
            Tone::Srgb => write!(f, ",gamma=srgb")?,
            Tone::Bt1886 => write!(f, ",gamma=bt1886")?,
            Tone::Lstar => write!(f, ",gamma=lstar")?,
        }
        match self.luminance {
            Some(l) => write!(f, ",luminance={l}"),
            None => write!(f, ",luminance=native"),
        }
    }
}

/// The device values whose predicted XYZ is `xyz`, if the display can show it (the model's
/// inverse, checked by predicting it back within 1/10 000 of the white's luminance).
pub fn reach(cal: &Calibration, xyz: [f64; 3]) -> Option<[f64; 3]> {
    let rgb = inverse(cal, xyz);
    let back = cal.predict(rgb);
    let scale = cal.predict([1.0; 3])[1].abs().max(f64::MIN_POSITIVE);
    let ok = (0..3).all(|c| (back[c] - xyz[c]).abs() <= 1e-4 * scale);
    ok.then_some(rgb)
}

/// The model's inverse: device values in `[0, 1]` for an XYZ ([`Calibration::inverse`]).
pub fn inverse(cal: &Calibration, xyz: [f64; 3]) -> [f64; 3] {
    cal.inverse(xyz)
}

/// Relative luminance of CIE L* (CIE 15:2004): `Y/Y_n` for `L* = l`.
fn lstar_to_y(l: f64) -> f64 {
    if l > 8.0 {
        ((l + 16.0) / 116.0).powi(3)
    } else {
        l / 903.296_296
    }
}

/// What the grey axis should measure: black, white and the tone curve between.
#[derive(Clone, Debug, PartialEq)]
pub struct Aim {
    /// The target white's XYZ (the calibration's units).
    pub white: [f64; 3],
    /// The display's black XYZ.
    pub black: [f64; 3],
    /// The tone curve.
    pub tone: Tone,
}

impl Aim {
    /// The aim for `target` on the display `cal` models; `notes` say what could not be met
    /// (a luminance above what the display reaches at the target white).
    pub fn new(cal: &Calibration, target: &Target) -> Result<(Aim, Vec<String>)> {
        let black = cal.predict([0.0; 3]);
        let native = cal.predict([1.0; 3]);
        let mut notes = Vec::new();
        // the unit-luminance XYZ of the target chromaticity
        let unit = match target.white {
            White::Native => native.map(|v| v / native[1]),
            White::Xy([x, y]) => [x / y, 1.0, (1.0 - x - y) / y],
        };
        // the brightest white of that chromaticity the display shows (bisection on Y)
        let max_y = if target.white == White::Native {
            native[1]
        } else {
            let (mut lo, mut hi) = (0.0, native[1] * 1.5);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if reach(cal, unit.map(|v| v * mid)).is_some() {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            if lo <= black[1] * 1.5 {
                let s = unit[0] + 1.0 + unit[2];
                return Err(Error::invalid(
                    format!("target white x {:.4} y {:.4}", unit[0] / s, 1.0 / s),
                    "is outside the display's gamut",
                ));
            }
            lo * HEADROOM
        };
        let y = match target.luminance {
            None => max_y,
            Some(l) if !cal.absolute() => {
                notes.push(format!(
                    "luminance={l}: the calibration is relative (no cd/m²): using the most the display gives"
                ));
                max_y
            }
            Some(l) if l > max_y => {
                notes.push(format!(
                    "luminance {l} cd/m² is more than the display gives at the target white ({max_y:.2} cd/m²): using {max_y:.2}"
                ));
                max_y
            }
            Some(l) if l <= black[1] * 1.5 => {
                return Err(Error::invalid(
                    format!("luminance {l} cd/m²"),
                    format!("is not above the display's black ({:.3} cd/m²)", black[1]),
                ))
            }
            Some(l) => l,
        };
        Ok((
            Aim {
                white: unit.map(|v| v * y),
                black,
                tone: target.tone,
            },
            notes,
        ))
    }

    /// The relative tone curve `f(v)`, `f(0) = 0`, `f(1) = 1`.
    pub fn relative(&self, v: f64) -> f64 {
        let v = v.clamp(0.0, 1.0);
        match self.tone {
            Tone::Gamma(g) => v.powf(g),
            Tone::Srgb => {
                if v <= 0.04045 {
                    v / 12.92
                } else {
                    ((v + 0.055) / 1.055).powf(2.4)
                }
            }
            Tone::Lstar => lstar_to_y(100.0 * v),
            Tone::Bt1886 => {
                let (lw, lb) = (self.white[1], self.black[1].max(0.0));
                let (w, b) = (lw.powf(1.0 / 2.4), lb.powf(1.0 / 2.4));
                let a = (w - b).powf(2.4);
                let off = b / (w - b);
                let l = a * (v + off).max(0.0).powf(2.4);
                ((l - lb) / (lw - lb)).clamp(0.0, 1.0)
            }
        }
    }

    /// The XYZ the grey `(v, v, v)` should measure.
    pub fn xyz(&self, v: f64) -> [f64; 3] {
        let f = self.relative(v);
        [0, 1, 2].map(|c| self.black[c] + f * (self.white[c] - self.black[c]))
    }
}

/// The first LUT: the model's inverse of the aim at each entry, made non-decreasing.
pub fn initial_lut(cal: &Calibration, aim: &Aim, entries: usize) -> VideoLut {
    let mut lut = VideoLut::identity(entries);
    for k in 0..entries {
        let rgb = inverse(cal, aim.xyz(lut.input(k)));
        for (c, t) in lut.tables_mut().into_iter().enumerate() {
            t[k] = rgb[c].clamp(0.0, 1.0);
        }
    }
    monotone(&mut lut);
    lut
}

fn monotone(lut: &mut VideoLut) {
    for t in lut.tables_mut() {
        for k in 1..t.len() {
            if t[k] < t[k - 1] {
                t[k] = t[k - 1];
            }
        }
    }
}

/// One refinement: greys at `levels` (inputs, increasing, 0 and 1 included) measured `xyz`
/// through `lut`; returns the LUT corrected by `gain` × the model's step (see the module docs).
pub fn refine(
    cal: &Calibration,
    aim: &Aim,
    lut: &VideoLut,
    levels: &[f64],
    xyz: &[[f64; 3]],
    gain: f64,
) -> VideoLut {
    // the device-value correction at each measured level
    let deltas: Vec<[f64; 3]> = levels
        .iter()
        .zip(xyz)
        .map(|(&v, m)| {
            if v == 0.0 {
                return [0.0; 3]; // black is where the display is; no LUT moves it
            }
            let rgb = lut.apply([v; 3]);
            let p = cal.predict(rgb);
            let want = aim.xyz(v);
            let goal = [0, 1, 2].map(|c| p[c] + want[c] - m[c]);
            let new = inverse(cal, goal);
            [0, 1, 2].map(|c| gain * (new[c] - rgb[c]))
        })
        .collect();
    let mut out = lut.clone();
    for k in 0..out.len() {
        let x = out.input(k);
        let j = levels
            .partition_point(|l| *l <= x)
            .clamp(1, levels.len() - 1);
        let (a, b) = (levels[j - 1], levels[j]);
        let f = if b > a {
            ((x - a) / (b - a)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        for (c, t) in out.tables_mut().into_iter().enumerate() {
            let d = deltas[j - 1][c] + f * (deltas[j][c] - deltas[j - 1][c]);
            t[k] = (t[k] + d).clamp(0.0, 1.0);
        }
    }
    monotone(&mut out);
    out
}

/// How a grey ramp measured through a LUT meets the aim.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Score {
    /// Iteration (1 = the model's first LUT).
    pub iteration: usize,
    /// The measured white's chromaticity.
    pub white_xy: [f64; 2],
    /// Its distance from the target chromaticity in xy.
    pub white_delta_xy: f64,
    /// ΔE00 of the measured white against the target white.
    pub white_delta_e00: f64,
    /// The measured white's luminance (the calibration's units).
    pub white_luminance: f64,
    /// The largest luminance error of a grey, in percent of the target white's luminance.
    pub tone_error_percent: f64,
    /// ΔE00 of the greys against their aims (reference white: the target white): mean.
    pub grey_delta_e00_mean: f64,
    /// … and largest.
    pub grey_delta_e00_max: f64,
}

impl Score {
    /// Scores readings `xyz` of greys at `levels` (the last is 1, the white).
    pub fn of(aim: &Aim, iteration: usize, levels: &[f64], xyz: &[[f64; 3]]) -> Score {
        let w = xyz[xyz.len() - 1];
        let xy = |v: [f64; 3]| {
            let s = v[0] + v[1] + v[2];
            [v[0] / s, v[1] / s]
        };
        let (mw, tw) = (xy(w), xy(aim.white));
        let des: Vec<f64> = levels
            .iter()
            .zip(xyz)
            .map(|(&v, m)| delta_e00(*m, aim.xyz(v), aim.white))
            .collect();
        let tone = levels
            .iter()
            .zip(xyz)
            .map(|(&v, m)| (m[1] - aim.xyz(v)[1]).abs() / aim.white[1] * 100.0)
            .fold(0.0, f64::max);
        Score {
            iteration,
            white_xy: mw,
            white_delta_xy: ((mw[0] - tw[0]).powi(2) + (mw[1] - tw[1]).powi(2)).sqrt(),
            white_delta_e00: delta_e00(w, aim.white, aim.white),
            white_luminance: w[1],
            tone_error_percent: tone,
            grey_delta_e00_mean: des.iter().sum::<f64>() / des.len() as f64,
            grey_delta_e00_max: des.iter().copied().fold(0.0, f64::max),
        }
    }

    /// How far from the target, in tolerances: the worse of the greys' (and the white's) ΔE00
    /// over [`GREY_TOLERANCE`] and the tone error over [`TONE_TOLERANCE`] (met at ≤ 1).
    pub fn badness(&self) -> f64 {
        (self.grey_delta_e00_max.max(self.white_delta_e00) / GREY_TOLERANCE)
            .max(self.tone_error_percent / TONE_TOLERANCE)
    }

    /// Whether every grey and the white are within [`GREY_TOLERANCE`] and every grey's
    /// luminance within [`TONE_TOLERANCE`].
    pub fn met(&self) -> bool {
        self.grey_delta_e00_max <= GREY_TOLERANCE
            && self.white_delta_e00 <= GREY_TOLERANCE
            && self.tone_error_percent <= TONE_TOLERANCE
    }
}

/// Measures device triples (a display and an instrument, or ArgyllCMS's `dispread`).
pub use crate::error::MeterError;

/// Something that measures device colours.
pub trait Meter {
    /// The XYZ of each of `devices`, in order. Meters are the measuring crate's, which still
    /// returns its own error; the solve passes it on as [`crate::Error::Meter`].
    fn measure(&mut self, devices: &[[f64; 3]]) -> std::result::Result<Vec<[f64; 3]>, MeterError>;
}

/// The solve's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// Grey levels measured per iteration (0 and 1 included).
    pub levels: usize,
    /// Most iterations (measured ramps).
    pub iterations: usize,
    /// LUT entries per channel.
    pub entries: usize,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            levels: 17,
            iterations: 8,
            entries: 256,
        }
    }
}

/// What [`calibrate`] found.
#[derive(Clone, Debug)]
pub struct Outcome {
    /// The best LUT.
    pub lut: VideoLut,
    /// The aim.
    pub aim: Aim,
    /// Every iteration's score, in order.
    pub scores: Vec<Score>,
    /// The index in `scores` of the kept LUT's.
    pub best: usize,
    /// What could not be met.
    pub notes: Vec<String>,
}

impl Outcome {
    /// The kept LUT's score.
    pub fn score(&self) -> &Score {
        &self.scores[self.best]
    }
}

/// The grey levels an iteration measures: `levels` inputs on the 8-bit grid, 0 and 1 included.
pub fn grey_levels(levels: usize) -> Vec<f64> {
    let n = levels.max(2);
    let mut v: Vec<f64> = (0..n)
        .map(|k| ((k as f64 / (n - 1) as f64) * 255.0).round() / 255.0)
        .collect();
    v.dedup();
    v
}

/// Computes a LUT for `target` from the model `cal` and refines it with measurements from
/// `meter` (see the module docs). `progress` is told each iteration's score.
pub fn calibrate(
    cal: &Calibration,
    target: &Target,
    meter: &mut dyn Meter,
    opts: &Options,
    progress: &mut dyn FnMut(&Score) -> Result<()>,
) -> Result<Outcome> {
    let (mut aim, notes) = Aim::new(cal, target)?;
    if target.white == White::Native && target.luminance.is_none() {
        // the native white is what the display shows at full drive, not what the model says
        if let Some(w) = meter.measure(&[[1.0; 3]]).map_err(Error::Meter)?.first() {
            aim.white = *w;
        }
    }
    let levels = grey_levels(opts.levels);
    let mut lut = initial_lut(cal, &aim, opts.entries);
    let mut scores: Vec<Score> = Vec::new();
    let mut best: Option<(usize, VideoLut)> = None;
    let mut misses = 0;
    for it in 1..=opts.iterations.max(1) {
        let devices: Vec<[f64; 3]> = levels.iter().map(|&v| lut.apply([v; 3])).collect();
        let xyz = meter.measure(&devices).map_err(Error::Meter)?;
        let score = Score::of(&aim, it, &levels, &xyz);
        progress(&score)?;
        let better = best
            .as_ref()
            .is_none_or(|(b, _)| score.badness() < scores[*b].badness());
        let met = score.met();
        scores.push(score);
        if better {
            best = Some((scores.len() - 1, lut.clone()));
            misses = 0;
        } else {
            misses += 1;
            if misses == MISSES {
                break; // no better than the best twice running: keep the best
            }
        }
        if met {
            break;
        }
        let gain = if it == 1 { 1.0 } else { LATER_GAIN };
        lut = refine(cal, &aim, &lut, &levels, &xyz, gain);
    }
    let (best, lut) = best.expect("at least one iteration ran");
    Ok(Outcome {
        lut,
        aim,
        scores,
        best,
        notes,
    })
}

/// `.cal` keywords describing the target and what was reached (as `dispcal` records its
/// target in `TARGET_WHITE_XYZ`…).
pub fn cal_keywords(target: &Target, o: &Outcome) -> Vec<(String, String)> {
    let s = o.score();
    vec![
        ("SPECPOLY_TARGET".into(), target.to_string()),
        (
            "TARGET_WHITE_XYZ".into(),
            format!(
                "{:.6} {:.6} {:.6}",
                o.aim.white[0], o.aim.white[1], o.aim.white[2]
            ),
        ),
        (
            "SPECPOLY_ACHIEVED".into(),
            format!(
                "white x {:.4} y {:.4} dxy {:.5} dE00 {:.3}; tone error {:.3} %; greys dE00 mean {:.3} max {:.3}",
                s.white_xy[0],
                s.white_xy[1],
                s.white_delta_xy,
                s.white_delta_e00,
                s.tone_error_percent,
                s.grey_delta_e00_mean,
                s.grey_delta_e00_max
            ),
        ),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_targets() {
        assert_eq!(parse("").unwrap(), Target::default());
        let t = parse("white=0.30,0.32,gamma=2.4,luminance=120").unwrap();
        assert_eq!(t.white, White::Xy([0.30, 0.32]));
        assert_eq!(t.tone, Tone::Gamma(2.4));
        assert_eq!(t.luminance, Some(120.0));
        assert_eq!(
            parse("gamma=bt1886,white=native").unwrap().white,
            White::Native
        );
        assert_eq!(
            parse("white=0.3:0.31").unwrap().white,
            White::Xy([0.3, 0.31])
        );
        assert_eq!(parse("gamma=lstar").unwrap().tone, Tone::Lstar);
        assert_eq!(
            parse(&Target::default().to_string()).unwrap(),
            Target::default()
        );
        for bad in [
            "white=0.3",
            "white=0.8,0.5",
            "gamma=9",
            "gamma=x",
            "luminance=-1",
            "luminance=NaN",
            "colour=red",
        ] {
            assert!(parse(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn tone_curves_end_at_0_and_1() {
        for tone in [Tone::Gamma(2.2), Tone::Srgb, Tone::Bt1886, Tone::Lstar] {
            let aim = Aim {
                white: [95.0, 100.0, 108.0],
                black: [0.2, 0.21, 0.25],
                tone,
            };
            assert!(aim.relative(0.0).abs() < 1e-12, "{tone:?}");
            assert!((aim.relative(1.0) - 1.0).abs() < 1e-12, "{tone:?}");
            assert!(
                aim.relative(0.5) > 0.1 && aim.relative(0.5) < 0.3,
                "{tone:?}"
            );
        }
    }
}
