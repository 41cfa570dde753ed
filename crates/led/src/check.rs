//! Is the controller right? Its colour reply against an **independent f64 computation** of the
//! same command, within **one table of tolerances** ([`TOLERANCES`], libm's pattern: one entry
//! per compared quantity with the reason for its size). `specpoly led --check` and the QEMU
//! end-to-end test (`tests/tests/firmware_qemu.rs`) both call [`Oracle::verify`].
//!
//! The controller runs the core's f32 drive step ([`specpoly_core::Display::drive`]) with
//! precomputed f32 moments. The oracle works from the definitions instead, in f64:
//!
//! - a reflectance's XYZ is the 1 nm sum of its polynomial times the light's tabulated power and
//!   the observer ([`specpoly_core::exact_xyz`]), each span's Chebyshev series evaluated as
//!   `Σ cₖ cos(k·arccos t)`, interior breakpoints shared half and half (the moments'
//!   convention); the product's coefficients are the protocol's (the core's reduced multiply,
//!   checked against the exact product in `crates/core/tests/multiply_reduce.rs`);
//! - Cowan's model: the primaries' XYZ `Yᵢ (xᵢ/yᵢ, 1, (1 − xᵢ − yᵢ)/yᵢ)` as the columns of `M`,
//!   the target scaled to the white's luminance, `M x = XYZ` solved by Gaussian elimination
//!   (the device inverts `M` in closed form and applies it in f32);
//! - the gamut maps as `specpoly_core::display` defines them (clip per channel; desaturate
//!   toward the grey of equal luminance), the transfer curves from their definitions (IEC
//!   61966-2-1 for sRGB, `v^γ`, linear interpolation of a table and of its inverse);
//! - the emitted XYZ from the *device's* duties, so a duty one tick off at a rounding boundary
//!   is not also counted against the emitted colour.
//!
//! This repeats Cowan's model in f64 on purpose: a reference must not share the code it checks.

use specpoly_core::{
    exact_xyz, solve::solve, GamutMap, Illuminant, Layout, Observer, Spectrum, Transfer,
    LAMBDA_MAX, LAMBDA_MIN,
};
use specpoly_protocol::{ColourReport, Command, CurveSummary, Gamut, Reflectance, StateReport};
use std::fmt;

/// One compared quantity's tolerance: `|device − oracle| ≤ abs + rel · scale`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    /// What is compared.
    pub quantity: Quantity,
    /// Absolute part.
    pub abs: f64,
    /// Relative part (times the quantity's scale, e.g. the largest target component).
    pub rel: f64,
    /// Why it is this large.
    pub why: &'static str,
}

impl Tolerance {
    /// The bound for a quantity of size `scale`.
    pub fn bound(&self, scale: f64) -> f64 {
        self.abs + self.rel * scale.abs()
    }
}

/// The quantities of a colour reply.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quantity {
    /// `xyz=`: the target XYZ (white `Y = 100`).
    Target,
    /// `linear=`: linear drive after gamut mapping, `[0, 1]`.
    Linear,
    /// The device value `v ∈ [0, 1]` a transfer curve gives (before `round(v · max)`).
    Device,
    /// `led=`: the XYZ emitted at the reported duties (white `Y = 100`).
    Emitted,
}

/// The tolerance table: the device (f32) against the oracle (f64). Measured worst cases over the
/// grid of `tests::the_core_drive_step_agrees_with_the_oracle` are in each reason.
pub const TOLERANCES: [Tolerance; 4] = [
    Tolerance {
        quantity: Quantity::Target,
        abs: 2e-4,
        rel: 2e-6,
        why: "f32 moments (f64 sums rounded) dotted in f32 with 32 f32 coefficients: a few ulp \
              of terms that reach the white's Y = 100 (measured ≤ 8e-6); xyY → XYZ in f32 \
              (a few ulp of the largest component)",
    },
    Tolerance {
        quantity: Quantity::Linear,
        abs: 2e-5,
        rel: 0.0,
        why: "f32 inverse of the primaries' matrix (closed form, condition number up to ~30 for \
              LED primaries) applied in f32 (measured ≤ 1.3e-6)",
    },
    Tolerance {
        quantity: Quantity::Device,
        abs: 2e-6,
        rel: 0.0,
        why: "f32 transfer curve (libm powf, ≤ 1 ulp; table interpolation), on top of the linear \
              drive's tolerance carried through the curve's slope: near black a steep curve \
              turns 1e-6 of linear drive into tens of 16-bit ticks (measured ≤ 25) of no \
              visible consequence, which the emitted colour then bounds",
    },
    Tolerance {
        quantity: Quantity::Emitted,
        abs: 1e-5,
        rel: 2e-6,
        why: "f32 transfer curve and f32 M (from f32 chromaticities) at the same duties: \
              ~16 ulp of the largest component (measured ≤ 3.8e-5 with components up to ~150)",
    },
];

/// The tolerance of `q`.
pub fn tolerance(q: Quantity) -> &'static Tolerance {
    TOLERANCES
        .iter()
        .find(|t| t.quantity == q)
        .unwrap_or(&TOLERANCES[0])
}

/// How close the device came (the largest deviations found).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Agreement {
    /// Largest `|ΔXYZ|` of the target (white `Y = 100`).
    pub target: f64,
    /// Largest `|Δlinear|`.
    pub linear: f64,
    /// Largest difference in ticks from the oracle's rounded duty.
    pub duty: u32,
    /// Largest `|ΔXYZ|` of the emitted colour (white `Y = 100`).
    pub emitted: f64,
}

impl Agreement {
    /// Largest `|ΔXYZ|`, target or emitted.
    pub fn xyz(&self) -> f64 {
        self.target.max(self.emitted)
    }

    /// The larger of each deviation.
    pub fn max(self, o: Agreement) -> Agreement {
        Agreement {
            target: self.target.max(o.target),
            linear: self.linear.max(o.linear),
            duty: self.duty.max(o.duty),
            emitted: self.emitted.max(o.emitted),
        }
    }
}

/// Why the device is wrong: the first quantity out of tolerance, with both values.
#[derive(Clone, Debug, PartialEq)]
pub struct Disagreement {
    /// What disagrees (`xyz`, `linear`, `duty`, `led`, `gamut`, `max`).
    pub what: &'static str,
    /// Channel or component (0..3), if any.
    pub index: Option<usize>,
    /// The device's value.
    pub device: String,
    /// The oracle's value (or accepted range).
    pub oracle: String,
}

impl fmt::Display for Disagreement {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.index {
            Some(i) => write!(f, "{}[{i}]", self.what)?,
            None => write!(f, "{}", self.what)?,
        }
        write!(
            f,
            " is {} on the device, {} by the host's f64 reference",
            self.device, self.oracle
        )
    }
}

impl std::error::Error for Disagreement {}

/// In gamut within this margin (the display model's threshold, `specpoly_core::display`).
const GAMUT_EPS: f64 = 1e-6;

/// The controller's settings, in f64, and the computation of what it must answer.
#[derive(Clone, Debug)]
pub struct Oracle {
    /// `M`, rows X, Y, Z; column `i` is primary `i` at full drive.
    m: [[f64; 3]; 3],
    curves: [Transfer; 3],
    map: GamutMap,
    observer: Observer,
    max: u16,
}

impl Oracle {
    /// From the primaries' chromaticities and luminances, the curves and the settings.
    pub fn new(
        xy: [[f32; 2]; 3],
        luminance: [f32; 3],
        curves: [Transfer; 3],
        map: GamutMap,
        observer: Observer,
        max: u16,
    ) -> Self {
        let mut m = [[0.0; 3]; 3];
        for i in 0..3 {
            let (x, y, l) = (xy[i][0] as f64, xy[i][1] as f64, luminance[i] as f64);
            m[0][i] = l * x / y;
            m[1][i] = l;
            m[2][i] = l * (1.0 - x - y) / y;
        }
        Self {
            m,
            curves,
            map,
            observer,
            max,
        }
    }

    /// From a `state` reply. Tabulated curves are not in the reply (only their size): they
    /// come from `curves` (e.g. the calibration file just sent); `None` if they are needed
    /// and not given.
    pub fn from_state(s: &StateReport, curves: Option<&[Transfer; 3]>) -> Option<Self> {
        let mut t = [Transfer::Linear, Transfer::Linear, Transfer::Linear];
        for (i, (o, c)) in t.iter_mut().zip(s.trc).enumerate() {
            *o = match c {
                CurveSummary::Linear => Transfer::Linear,
                CurveSummary::Srgb => Transfer::Srgb,
                CurveSummary::Gamma(g) => Transfer::Gamma(g),
                CurveSummary::Table(_) => curves?[i].clone(),
            };
        }
        Some(Self::new(
            s.primaries.map(|p| [p[0], p[1]]),
            s.primaries.map(|p| p[2]),
            t,
            s.map,
            s.observer,
            s.max,
        ))
    }

    /// The target XYZ (white `Y = 100`) of a colour command; `None` for other commands.
    pub fn target(&self, cmd: &Command) -> Option<[f64; 3]> {
        match cmd {
            Command::Xyz(v) => Some(v.to_array().map(f64::from)),
            Command::Xyy(v) => {
                let (x, y, big_y) = (v.x as f64, v.y as f64, v.big_y as f64);
                Some(if y > 0.0 {
                    [x * big_y / y, big_y, (1.0 - x - y) * big_y / y]
                } else {
                    [0.0; 3]
                })
            }
            Command::Reflect {
                illuminant,
                product,
                ..
            } => Some(match product {
                Reflectance::Paper(s) => self.reflectance(*illuminant, s),
                Reflectance::Default(s) => self.reflectance(*illuminant, s),
            }),
            _ => None,
        }
    }

    /// XYZ of a polynomial reflectance under a built-in light: the 1 nm f64 sum.
    fn reflectance<const S: usize, const C: usize, L: Layout<S>>(
        &self,
        illuminant: Illuminant,
        r: &Spectrum<S, C, L>,
    ) -> [f64; 3] {
        let c = r.coefficients();
        let at = |nm: f64| {
            let (mut v, mut w) = (0.0, 0.0);
            for s in 0..S {
                let (a, b) = L::BREAKS.span(s);
                let (a, b) = (a as f64, b as f64);
                if nm < a || nm > b {
                    continue;
                }
                let theta = ((2.0 * nm - (a + b)) / (b - a)).clamp(-1.0, 1.0).acos();
                let p: f64 = (0..C)
                    .map(|k| c[k][s] as f64 * (k as f64 * theta).cos())
                    .sum();
                let interior = (nm == a && s > 0) || (nm == b && s + 1 < S);
                let weight = if interior { 0.5 } else { 1.0 };
                v += weight * p;
                w += weight;
            }
            if w > 0.0 {
                v / w
            } else {
                0.0
            }
        };
        let nm = |x: f64| x.clamp(LAMBDA_MIN as f64, LAMBDA_MAX as f64);
        exact_xyz(self.observer, &illuminant.tabulated(), |x| at(nm(x))).0
    }

    /// Linear drive (unclipped) for a target relative to `Y = 100`: `M x = k · XYZ` with `k`
    /// the white's luminance over 100.
    fn linear(&self, target: [f64; 3]) -> Option<[f64; 3]> {
        let white_y: f64 = self.m[1].iter().sum();
        let mut x = target.map(|v| v * white_y / 100.0);
        let mut a = self.m;
        solve(a.as_flattened_mut(), &mut x).ok()?;
        Some(x)
    }

    /// The gamut map applied to linear drive; `(mapped, outside)`.
    fn map_gamut(&self, lin: [f64; 3]) -> ([f64; 3], bool) {
        let outside = lin.iter().any(|v| *v < -GAMUT_EPS || *v > 1.0 + GAMUT_EPS);
        if !outside || self.map == GamutMap::Clip {
            return (lin.map(|v| v.clamp(0.0, 1.0)), outside);
        }
        // desaturate: the grey of equal luminance (luminance clipped to [0, 1]), and the
        // largest step t ∈ [0, 1] toward the colour that stays inside
        let row = self.m[1];
        let sum: f64 = row.iter().sum();
        let y = ((0..3).map(|i| row[i] * lin[i]).sum::<f64>() / sum).clamp(0.0, 1.0);
        let mut t = 1.0f64;
        for c in lin {
            if c > 1.0 && c > y {
                t = t.min((1.0 - y) / (c - y));
            } else if c < 0.0 && c < y {
                t = t.min(y / (y - c));
            }
        }
        let t = t.clamp(0.0, 1.0);
        (lin.map(|c| (y + t * (c - y)).clamp(0.0, 1.0)), true)
    }

    /// Checks a colour reply to `cmd` (which must be a colour command): the target, the linear
    /// drive, the gamut verdict, each duty and the emitted colour, within [`TOLERANCES`].
    pub fn verify(&self, cmd: &Command, dev: &ColourReport) -> Result<Agreement, Disagreement> {
        self.verify_parts(cmd, dev, true)
    }

    /// [`Oracle::verify`] of a controller that holds a drive-correction table (`lut`): the
    /// target, the linear drive and the gamut verdict only, which the table leaves as the
    /// matrix model's; its duties are the full model's and are checked against that
    /// (`specpoly led --check`, [`crate::table`]).
    pub fn verify_matrix_part(
        &self,
        cmd: &Command,
        dev: &ColourReport,
    ) -> Result<Agreement, Disagreement> {
        self.verify_parts(cmd, dev, false)
    }

    fn verify_parts(
        &self,
        cmd: &Command,
        dev: &ColourReport,
        duties: bool,
    ) -> Result<Agreement, Disagreement> {
        let no = |what, index, device: String, oracle: String| Disagreement {
            what,
            index,
            device,
            oracle,
        };
        let target = self.target(cmd).ok_or_else(|| {
            no(
                "command",
                None,
                "a colour".into(),
                "not a colour command".into(),
            )
        })?;
        if dev.max != self.max {
            return Err(no("max", None, dev.max.to_string(), self.max.to_string()));
        }
        let mut agree = Agreement {
            target: within(Quantity::Target, "xyz", dev.xyz.to_array(), target)?,
            ..Agreement::default()
        };

        let Some(raw) = self.linear(target) else {
            return Err(no(
                "cal",
                None,
                "usable".into(),
                "a singular primaries matrix".into(),
            ));
        };
        let (lin, outside) = self.map_gamut(raw);
        let dl = tolerance(Quantity::Linear).bound(1.0);
        // near the gamut's edge either verdict is right
        let edge = raw
            .iter()
            .map(|v| (v + GAMUT_EPS).abs().min((v - 1.0 - GAMUT_EPS).abs()))
            .fold(f64::INFINITY, f64::min);
        let dev_out = dev.gamut != Gamut::In;
        if dev_out != outside && edge > dl {
            let verdict = |o: bool| if o { "out" } else { "in" }.to_string();
            return Err(no("gamut", None, verdict(dev_out), verdict(outside)));
        }
        if dev_out && dev.gamut != Gamut::Out(self.map) {
            return Err(no(
                "gamut",
                None,
                match dev.gamut {
                    Gamut::In => "in".to_string(),
                    Gamut::Out(m) => {
                        format!("out with {}", specpoly_protocol::command::map_name(m))
                    }
                },
                format!(
                    "out with {}",
                    specpoly_protocol::command::map_name(self.map)
                ),
            ));
        }
        for i in 0..3 {
            let e = (dev.linear[i] as f64 - lin[i]).abs();
            if !(e <= dl) {
                return Err(no(
                    "linear",
                    Some(i),
                    dev.linear[i].to_string(),
                    format!("{:.7} ± {dl:.1e}", lin[i]),
                ));
            }
            agree.linear = agree.linear.max(e);
        }

        if !duties {
            return Ok(agree);
        }
        let max = self.max as f64;
        let dv = tolerance(Quantity::Device).bound(1.0);
        for i in 0..3 {
            let curve = &self.curves[i];
            let lo = encode(curve, (lin[i] - dl).clamp(0.0, 1.0)) - dv;
            let hi = encode(curve, (lin[i] + dl).clamp(0.0, 1.0)) + dv;
            // round half up, of the device values the tolerances allow
            let (first, last) = (level(lo, max), level(hi, max));
            let d = dev.duty[i] as f64;
            if d < first || d > last {
                return Err(no(
                    "duty",
                    Some(i),
                    dev.duty[i].to_string(),
                    format!("{first}..={last} of {}", self.max),
                ));
            }
            let nearest = level(encode(curve, lin[i]), max);
            agree.duty = agree.duty.max((d - nearest).abs() as u32);
        }

        let white_y: f64 = self.m[1].iter().sum();
        let k = if white_y > 0.0 { 100.0 / white_y } else { 0.0 };
        let full = max.max(1.0);
        let shown: Vec<f64> = (0..3)
            .map(|i| decode(&self.curves[i], dev.duty[i] as f64 / full))
            .collect();
        let emitted = [0, 1, 2].map(|r| k * (0..3).map(|i| self.m[r][i] * shown[i]).sum::<f64>());
        agree.emitted = within(Quantity::Emitted, "led", dev.led.to_array(), emitted)?;
        Ok(agree)
    }
}

/// The largest `|device − oracle|` of an XYZ triple if every component is within `q`'s
/// tolerance (scaled by the oracle's largest component), else the first that is not.
fn within(
    q: Quantity,
    what: &'static str,
    device: [f32; 3],
    oracle: [f64; 3],
) -> Result<f64, Disagreement> {
    let scale = oracle.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let tol = tolerance(q).bound(scale);
    let mut worst = 0.0f64;
    for (i, (d, o)) in device.iter().zip(oracle).enumerate() {
        let e = (*d as f64 - o).abs();
        if !(e <= tol) {
            return Err(Disagreement {
                what,
                index: Some(i),
                device: d.to_string(),
                oracle: format!("{o:.6} ± {tol:.1e}"),
            });
        }
        worst = worst.max(e);
    }
    Ok(worst)
}

/// `round(v · max)`, half up, for `v` clamped to `[0, 1]`.
fn level(v: f64, max: f64) -> f64 {
    (v.clamp(0.0, 1.0) * max + 0.5).floor()
}

/// Linear light → device value, from the curves' definitions (f64).
fn encode(curve: &Transfer, l: f64) -> f64 {
    let l = l.clamp(0.0, 1.0);
    match curve {
        Transfer::Linear => l,
        // IEC 61966-2-1: V = 12.92 L below 0.0031308, else 1.055 L^(1/2.4) − 0.055
        Transfer::Srgb if l <= 0.003_130_8 => 12.92 * l,
        Transfer::Srgb => 1.055 * l.powf(1.0 / 2.4) - 0.055,
        Transfer::Gamma(g) => l.powf(1.0 / *g as f64),
        Transfer::Table(t) => {
            // the inverse of the piecewise-linear table through (i/(n−1), tᵢ)
            let n = t.len();
            let t: Vec<f64> = t.iter().map(|v| *v as f64).collect();
            if l <= t[0] {
                return 0.0;
            }
            if l >= t[n - 1] {
                return 1.0;
            }
            let i = (1..n).find(|&i| t[i] > l).unwrap_or(n - 1);
            let f = if t[i] > t[i - 1] {
                (l - t[i - 1]) / (t[i] - t[i - 1])
            } else {
                0.0
            };
            ((i - 1) as f64 + f) / (n - 1) as f64
        }
    }
}

/// Device value → linear light, from the curves' definitions (f64).
fn decode(curve: &Transfer, v: f64) -> f64 {
    let v = v.clamp(0.0, 1.0);
    match curve {
        Transfer::Linear => v,
        // IEC 61966-2-1: L = V / 12.92 up to 0.04045, else ((V + 0.055)/1.055)^2.4
        Transfer::Srgb if v <= 0.04045 => v / 12.92,
        Transfer::Srgb => ((v + 0.055) / 1.055).powf(2.4),
        Transfer::Gamma(g) => v.powf(*g as f64),
        Transfer::Table(t) => {
            let x = v * (t.len() - 1) as f64;
            let i = (x.floor() as usize).min(t.len() - 2);
            let f = x - i as f64;
            t[i] as f64 + (t[i + 1] as f64 - t[i] as f64) * f
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use specpoly_core::{DefaultSpectrum, Display, Moments, PaperSpectrum, Tabulated, Xyy, Xyz};

    /// LED-like primaries (saturated, unequal luminances) and sRGB's.
    const PRIMARIES: [([[f32; 2]; 3], [f32; 3]); 2] = [
        (
            [[0.70, 0.29], [0.17, 0.70], [0.135, 0.04]],
            [2.5, 7.25, 1.0],
        ),
        (
            [[0.64, 0.33], [0.30, 0.60], [0.15, 0.06]],
            [0.2126, 0.7152, 0.0722],
        ),
    ];

    fn curves() -> Vec<Transfer> {
        vec![
            Transfer::Linear,
            Transfer::Srgb,
            Transfer::Gamma(2.2),
            Transfer::table(&[0.0, 0.02, 0.1, 0.3, 0.6, 1.0]).unwrap(),
        ]
    }

    fn targets() -> Vec<Xyz> {
        let mut v = vec![
            Xyz::default(),
            Xyz::new(20.0, 20.0, 20.0),
            Xyz::new(41.24, 21.26, 1.93),
        ];
        for x in [0.08f32, 0.2, 0.3127, 0.45, 0.6] {
            for y in [0.05f32, 0.3, 0.329, 0.5, 0.85] {
                for big_y in [0.01f32, 1.0, 18.0, 50.0, 100.0, 140.0] {
                    v.push(Xyy { x, y, big_y }.to_xyz());
                }
            }
        }
        v
    }

    /// What a faithful controller answers: the core's drive step (as the firmware).
    fn device(d: &Display, map: GamutMap, max: u16, target: Xyz) -> ColourReport {
        ColourReport::of(target, &d.drive(target, map, max), map, max)
    }

    #[test]
    fn the_core_drive_step_agrees_with_the_oracle() {
        let mut worst = Agreement::default();
        for (xy, lum) in PRIMARIES {
            for curve in curves() {
                let t = [curve.clone(), curve.clone(), curve.clone()];
                let d = Display::from_primaries(xy, lum, Xyz::default(), t.clone()).unwrap();
                for map in [GamutMap::Clip, GamutMap::Desaturate] {
                    for max in [255u16, 4095, 65535] {
                        let o = Oracle::new(xy, lum, t.clone(), map, Observer::Cie1931, max);
                        for target in targets() {
                            let dev = device(&d, map, max, target);
                            let a = o.verify(&Command::Xyz(target), &dev).unwrap_or_else(|e| {
                                panic!("{curve:?} {map:?} {max} {target:?}: {e}")
                            });
                            worst = worst.max(a);
                        }
                    }
                }
            }
        }
        eprintln!("worst agreement of the core drive step with the f64 oracle: {worst:?}");
    }

    #[test]
    fn reflectances_agree_with_the_1nm_sum() {
        let o = Oracle::new(
            PRIMARIES[0].0,
            PRIMARIES[0].1,
            [Transfer::Linear, Transfer::Linear, Transfer::Linear],
            GamutMap::Clip,
            Observer::Cie1931,
            65535,
        );
        let w: Vec<f32> = (0..41).map(|i| 380.0 + 10.0 * i as f32).collect();
        let v: Vec<f32> = w
            .iter()
            .map(|x| 0.5 + 0.4 * ((x - 380.0) / 37.0).sin())
            .collect();
        let t = Tabulated::new(&w, &v).unwrap();
        let mut worst = 0.0f64;
        for ill in Illuminant::ALL {
            let light = ill.tabulated();
            let pd = DefaultSpectrum::fit(&t).unwrap();
            let pp = PaperSpectrum::fit(&t).unwrap();
            for (got, product) in [
                (
                    Moments::new(Observer::Cie1931, &light).xyz(&pd.mul(&pd)),
                    Reflectance::Default(pd.mul(&pd)),
                ),
                (
                    Moments::new(Observer::Cie1931, &light).xyz(&pp),
                    Reflectance::Paper(pp),
                ),
            ] {
                let cmd = Command::Reflect {
                    illuminant: ill,
                    product,
                    factors: 1,
                    hex: false,
                };
                let want = o.target(&cmd).unwrap();
                for (g, w) in got.to_array().iter().zip(want) {
                    worst = worst.max((*g as f64 - w).abs());
                }
            }
        }
        eprintln!("worst |ΔXYZ| of f32 moments against the f64 1 nm sum: {worst:.2e}");
        assert!(worst <= tolerance(Quantity::Target).bound(100.0), "{worst}");
    }

    #[test]
    fn wrong_answers_are_caught() {
        let (xy, lum) = PRIMARIES[0];
        let t = [
            Transfer::Gamma(2.2),
            Transfer::Gamma(2.2),
            Transfer::Gamma(2.2),
        ];
        let d = Display::from_primaries(xy, lum, Xyz::default(), t.clone()).unwrap();
        let o = Oracle::new(xy, lum, t, GamutMap::Clip, Observer::Cie1931, 1000);
        let target = Xyz::new(20.0, 21.0, 22.0);
        let good = device(&d, GamutMap::Clip, 1000, target);
        assert!(o.verify(&Command::Xyz(target), &good).is_ok());
        let mut bad = good;
        bad.duty[1] += 3;
        assert_eq!(
            o.verify(&Command::Xyz(target), &bad).unwrap_err().what,
            "duty"
        );
        let mut bad = good;
        bad.xyz.y += 0.01;
        assert_eq!(
            o.verify(&Command::Xyz(target), &bad).unwrap_err().what,
            "xyz"
        );
        let mut bad = good;
        bad.led.z *= 1.001;
        assert_eq!(
            o.verify(&Command::Xyz(target), &bad).unwrap_err().what,
            "led"
        );
        let mut bad = good;
        bad.gamut = Gamut::Out(GamutMap::Clip);
        assert_eq!(
            o.verify(&Command::Xyz(target), &bad).unwrap_err().what,
            "gamut"
        );
        let mut bad = good;
        bad.linear[0] += 1e-3;
        assert_eq!(
            o.verify(&Command::Xyz(target), &bad).unwrap_err().what,
            "linear"
        );
    }
}
