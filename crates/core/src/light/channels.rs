//! Mixing 3–`M` LED channels **on a device**, in f32: the channels' tristimulus values at full
//! drive in, PWM duties for a chromaticity (or CCT) and a relative luminance out; and the fade
//! between two such targets.
//!
//! A light that is a weighted sum of channel spectra `Σ dᵢ·Sᵢ` has tristimulus values (and
//! moments) that are the same weighted sum, so a chromaticity target needs only each channel's
//! `XYZ` (uploaded by the host, which integrates the measured SPD exactly: [`super::Source`]).
//! The host's optimiser ([`super::mix`], f64, Rf/Ra/efficacy/power) is the reference; the device
//! solves the two linear programmes it needs by enumerating vertices, as the host does for its
//! linear objectives:
//!
//! 1. **the most light at the target chromaticity** `(x, y)`: `max Σ dᵢYᵢ` subject to
//!    `Σ dᵢ(y·Xᵢ − x·Yᵢ) = 0`, `Σ dᵢ(y·Zᵢ − z·Yᵢ) = 0`, `0 ≤ d ≤ 1`; at a vertex at most two
//!    duties are strictly inside (0, 1): for each pair, the other duties at 0 or 1, a 2×2 solve
//!    (`C(N,2)·2^{N−2}`: 240 for six channels). No positive vertex: out of gamut.
//! 2. the luminance `L·Y_max` fixes `A·d = t`; with more than three channels the remaining
//!    `N − 3` degrees of freedom are spent on **the least weighted drive** `Σ cᵢdᵢ`: a linear
//!    programme over the polytope, whose optimum is a vertex with at most three duties inside
//!    (0, 1): per triple, one 3×3 inverse, then the other duties at 0 or 1 (`C(N,3)·2^{N−3}`:
//!    160 for six). The weights `cᵢ` are uploaded with the channels: 1 each gives the least total
//!    drive (the host's `--optimize power`), each channel's radiant power the greatest luminous
//!    efficacy of radiation (`efficacy`), its electrical power the least electrical power.
//!
//! Why this rule on a device: it is exact (the optimum of a linear programme, not a heuristic),
//! it needs one number per channel, its cost is fixed and small (≈ 60 000 instructions for six
//! channels; `docs/leds.md`), and it is continuous along a fade except where the optimal vertex
//! changes. The non-linear objectives (Rf, Ra) stay on the host (`specpoly mix`).
//!
//! The duties are fractions of each channel's light; each channel's transfer curve
//! ([`Curve`]) turns them into device values, quantised to the PWM's full scale
//! ([`crate::display::quantize`]).
//!
//! **Fades** ([`Fade`]) step from the point shown to the new target in CIE 1976 `u′v′` (where
//! equal distances are roughly equally visible, and straight lines stay inside the channels'
//! gamut, which is convex there as in `xy`) and in lightness: the relative luminance `L` is
//! interpolated as `L^{1/3}` (CIE L* without its linear toe), each step solved anew.

use super::locus;
use crate::display::{quantize, Transfer};
use heapless::Vec;

/// Fade steps per second: one step every 10 ms.
pub const STEPS_PER_SECOND: u32 = 100;

/// A channel's transfer curve, device value → light (a compact [`Transfer`] without tables: a
/// table per channel would not fit a small device's RAM).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub enum Curve {
    /// `l = v` (PWM).
    #[default]
    Linear,
    /// IEC 61966-2-1.
    Srgb,
    /// `l = v^γ`.
    Gamma(f32),
}

impl Curve {
    /// The core's curve.
    pub fn transfer(self) -> Transfer {
        match self {
            Curve::Linear => Transfer::Linear,
            Curve::Srgb => Transfer::Srgb,
            Curve::Gamma(g) => Transfer::Gamma(g),
        }
    }
}

/// One LED channel (20 B: the curve is kept as one f32, see [`Channel::curve`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Channel {
    /// CIE 1931 `X, Y, Z` at full drive (any unit common to all channels; `Y > 0`).
    pub xyz: [f32; 3],
    /// The weight of its duty in the drive minimised with more than three channels (≥ 0).
    pub cost: f32,
    /// The curve: `γ` of `l = v^γ` (1: linear), or 0 for sRGB.
    gamma: f32,
}

impl Channel {
    /// A channel from its tristimulus values, weight and curve.
    pub fn new(xyz: [f32; 3], cost: f32, curve: Curve) -> Self {
        let mut c = Self {
            xyz,
            cost,
            gamma: 1.0,
        };
        c.set_curve(curve);
        c
    }

    /// Its transfer curve (`gamma 1` reads back as linear, the same curve).
    pub fn curve(&self) -> Curve {
        match self.gamma {
            0.0 => Curve::Srgb,
            1.0 => Curve::Linear,
            g => Curve::Gamma(g),
        }
    }

    /// Sets its transfer curve.
    pub fn set_curve(&mut self, curve: Curve) {
        self.gamma = match curve {
            Curve::Linear => 1.0,
            Curve::Srgb => 0.0,
            Curve::Gamma(g) => g,
        };
    }
}

/// What a mix is asked for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Goal {
    /// CIE 1931 `(x, y)` and relative luminance `lum ∈ [0, 1]`.
    Xy {
        /// `[x, y]`.
        xy: [f32; 2],
        /// Fraction of the most the channels give at that chromaticity.
        lum: f32,
    },
    /// A CCT (K, 1000–25 000), a Duv (|Duv| ≤ 0.05) and a relative luminance.
    Cct {
        /// Correlated colour temperature, K.
        cct: f32,
        /// Distance from the Planckian locus in CIE 1960 (u, v), positive above.
        duv: f32,
        /// Fraction of the most the channels give at that chromaticity.
        lum: f32,
    },
}

/// A solved target: CIE 1976 `u′v′` and relative luminance.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Point {
    /// `[u′, v′]`.
    pub uv: [f32; 2],
    /// Relative luminance in `[0, 1]`.
    pub lum: f32,
}

impl Point {
    /// CIE 1931 `(x, y)`.
    pub fn xy(&self) -> [f32; 2] {
        let [u, v] = self.uv;
        let d = 6.0 * u - 16.0 * v + 12.0;
        [9.0 * u / d, 4.0 * v / d]
    }
}

impl Goal {
    /// The target as a point; `None` for a chromaticity outside `x, y > 0, x + y < 1`, a CCT or
    /// Duv outside the locus table ([`locus`]), or a luminance outside `[0, 1]`.
    pub fn point(&self) -> Option<Point> {
        let (uv, lum) = match *self {
            Goal::Xy { xy: [x, y], lum } => {
                if !(x > 0.0 && y > 0.0 && x + y < 1.0) {
                    return None;
                }
                let d = -2.0 * x + 12.0 * y + 3.0;
                ([4.0 * x / d, 9.0 * y / d], lum)
            }
            Goal::Cct { cct, duv, lum } => {
                let [u, v] = locus::uv(cct, duv)?;
                ([u, 1.5 * v], lum)
            }
        };
        (0.0..=1.0).contains(&lum).then_some(Point { uv, lum })
    }
}

/// Why a mix cannot be made.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MixError {
    /// Fewer than three channels, or a channel index past the next free one or the capacity.
    Channels,
    /// The channels cannot make the target chromaticity.
    OutOfGamut,
    /// A target outside its domain ([`Goal::point`]).
    BadTarget,
}

/// Up to `M` channels (the capacity is in the type; a mix needs at least three).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Channels<const M: usize> {
    list: Vec<Channel, M>,
}

/// Duty tolerance of a vertex (f32 solves of well-scaled systems).
const EPS: f32 = 1e-5;

fn unit(v: f32) -> bool {
    (-EPS..=1.0 + EPS).contains(&v)
}

impl<const M: usize> Channels<M> {
    /// No channels.
    pub const fn new() -> Self {
        Self { list: Vec::new() }
    }

    /// The channels, in order.
    pub fn list(&self) -> &[Channel] {
        &self.list
    }

    /// Sets channel `i` (0-based): an existing one, or the next one.
    pub fn set(&mut self, i: usize, c: Channel) -> Result<(), MixError> {
        let n = self.list.len();
        match self.list.get_mut(i) {
            Some(slot) => *slot = c,
            None if i == n => self.list.push(c).map_err(|_| MixError::Channels)?,
            None => return Err(MixError::Channels),
        }
        Ok(())
    }

    /// Sets channel `i`'s transfer curve (the channel must exist).
    pub fn set_curve(&mut self, i: usize, curve: Curve) -> Result<(), MixError> {
        self.list
            .get_mut(i)
            .ok_or(MixError::Channels)?
            .set_curve(curve);
        Ok(())
    }

    /// Removes every channel.
    pub fn clear(&mut self) {
        self.list.clear();
    }

    /// The light fractions `d` (in channel order; `M − N` zeros after) that make `p`, spending the
    /// freedom beyond three channels on the least `Σ cᵢdᵢ` (module docs).
    pub fn solve(&self, p: Point) -> Result<[f32; M], MixError> {
        let n = self.list.len();
        if n < 3 {
            return Err(MixError::Channels);
        }
        // columns X, Y, Z, scaled so the largest entry is 1
        let mut scale = 0.0f32;
        for c in self.list.iter() {
            for v in c.xyz {
                scale = scale.max(v.abs());
            }
        }
        let mut a = [[0.0f32; 3]; M];
        for (col, c) in a.iter_mut().zip(self.list.iter()) {
            *col = c.xyz.map(|v| v / scale);
        }
        let [x, y] = p.xy();
        let z = 1.0 - x - y;
        let (y_max, brightest) = brightest(&a[..n], [x, y, z]);
        if !(y_max > 1e-6) {
            return Err(MixError::OutOfGamut);
        }
        let lum = p.lum.min(1.0);
        let mut d = brightest;
        if lum < 1.0 && n > 3 {
            let ly = lum * y_max;
            let t = [x / y * ly, ly, z / y * ly];
            if let Some(v) = least_cost(&a[..n], &self.list, t) {
                return Ok(v);
            }
        }
        // at L = 1 the polytope is the brightest point and with three channels a point: the
        // brightest mix scaled down (also the fallback for a degenerate polytope)
        for v in d.iter_mut() {
            *v *= lum;
        }
        Ok(d)
    }

    /// PWM duties (out of `max`) of light fractions `d`: each channel's curve, then
    /// [`quantize`].
    pub fn duties(&self, d: &[f32; M], max: u16) -> [u16; M] {
        let mut out = [0u16; M];
        for (i, c) in self.list.iter().enumerate() {
            out[i] = quantize(c.curve().transfer().encode(d[i]), max);
        }
        out
    }
}

/// The duties `0`/`1` of the channels other than `free`, by the bits of `mask` in channel
/// order (the free ones 0).
fn fixed<const M: usize>(n: usize, free: &[usize], mask: u32) -> [f32; M] {
    let mut d = [0.0f32; M];
    let mut bit = 0;
    for (i, v) in d.iter_mut().enumerate().take(n) {
        if !free.contains(&i) {
            *v = ((mask >> bit) & 1) as f32;
            bit += 1;
        }
    }
    d
}

/// The vertex of greatest `Σ dᵢYᵢ` at chromaticity `xyz = (x, y, z)`, i.e. on the constraints
/// `Σ dᵢbᵢ = 0` with `bᵢ = (y·Xᵢ − x·Yᵢ, y·Zᵢ − z·Yᵢ)` (module docs, step 1): per pair of free
/// duties, every 0/1 setting of the others, a 2×2 solve (Cramer).
fn brightest<const M: usize>(a: &[[f32; 3]], xyz: [f32; 3]) -> (f32, [f32; M]) {
    let n = a.len();
    let [x, y, z] = xyz;
    let bv = |i: usize| [y * a[i][0] - x * a[i][1], y * a[i][2] - z * a[i][1]];
    let mut best = (0.0f32, [0.0f32; M]);
    for p in 0..n {
        for q in p + 1..n {
            let (bp, bq) = (bv(p), bv(q));
            let det = bp[0] * bq[1] - bq[0] * bp[1];
            if det.abs() < 1e-12 {
                continue;
            }
            for mask in 0u32..1 << (n - 2) {
                let d = fixed::<M>(n, &[p, q], mask);
                let (mut r0, mut r1, mut lum) = (0.0f32, 0.0f32, 0.0f32);
                for i in 0..n {
                    if d[i] > 0.0 {
                        let bi = bv(i);
                        r0 -= bi[0];
                        r1 -= bi[1];
                        lum += a[i][1];
                    }
                }
                let dp = (r0 * bq[1] - r1 * bq[0]) / det;
                let dq = (bp[0] * r1 - bp[1] * r0) / det;
                if !(unit(dp) && unit(dq)) {
                    continue;
                }
                let (dp, dq) = (dp.clamp(0.0, 1.0), dq.clamp(0.0, 1.0));
                lum += a[p][1] * dp + a[q][1] * dq;
                if lum > best.0 {
                    let mut d = d;
                    d[p] = dp;
                    d[q] = dq;
                    best = (lum, d);
                }
            }
        }
    }
    best
}

/// The vertex of least `Σ cᵢdᵢ` of `{A·d = t, 0 ≤ d ≤ 1}` (module docs, step 2): per triple of
/// free duties one 3×3 inverse, then every 0/1 setting of the others; `None` when no vertex is
/// within the tolerance.
fn least_cost<const M: usize>(
    a: &[[f32; 3]],
    channels: &[Channel],
    t: [f32; 3],
) -> Option<[f32; M]> {
    let n = a.len();
    let mut best = (f32::INFINITY, [0.0f32; M]);
    for i in 0..n {
        for j in i + 1..n {
            for k in j + 1..n {
                let Some(inv) = inverse([a[i], a[j], a[k]]) else {
                    continue;
                };
                for mask in 0u32..1 << (n - 3) {
                    let mut d = fixed::<M>(n, &[i, j, k], mask);
                    let mut rhs = t;
                    let mut c = 0.0f32;
                    for q in 0..n {
                        if d[q] > 0.0 {
                            for r in 0..3 {
                                rhs[r] -= a[q][r];
                            }
                            c += channels[q].cost;
                        }
                    }
                    let free = inv.map(|row| row[0] * rhs[0] + row[1] * rhs[1] + row[2] * rhs[2]);
                    if !free.iter().all(|v| unit(*v)) {
                        continue;
                    }
                    for (col, v) in [i, j, k].into_iter().zip(free) {
                        d[col] = v.clamp(0.0, 1.0);
                        c += channels[col].cost * d[col];
                    }
                    if c < best.0 {
                        best = (c, d);
                    }
                }
            }
        }
    }
    best.0.is_finite().then_some(best.1)
}

/// The inverse of the 3×3 matrix whose *columns* are `cols`, by the adjugate in f32 (not
/// [`crate::Mat3::inverse`], which works in f64: soft float on a Cortex-M4F, and a solve
/// inverts up to 20 of these); `None` when (nearly) singular.
fn inverse(cols: [[f32; 3]; 3]) -> Option<[[f32; 3]; 3]> {
    // m[r][c] = cols[c][r]; the inverse is the transposed cofactor matrix over the determinant
    let m = |r: usize, c: usize| cols[c][r];
    let cof = |r: usize, c: usize| {
        let (r1, r2, c1, c2) = ((r + 1) % 3, (r + 2) % 3, (c + 1) % 3, (c + 2) % 3);
        m(r1, c1) * m(r2, c2) - m(r1, c2) * m(r2, c1)
    };
    let det = m(0, 0) * cof(0, 0) + m(0, 1) * cof(0, 1) + m(0, 2) * cof(0, 2);
    if !(det.abs() > 1e-9) {
        return None;
    }
    let r = 1.0 / det;
    Some(core::array::from_fn(|i| {
        core::array::from_fn(|j| cof(j, i) * r)
    }))
}

/// A fade from one point to another in [`Fade::steps`] steps: `u′v′` linearly, `L^{1/3}`
/// linearly (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Fade {
    from: Point,
    to: Point,
    step: u16,
    steps: u16,
}

impl Fade {
    /// A fade lasting `ms` milliseconds, one step per 10 ms ([`STEPS_PER_SECOND`]), at least
    /// one step.
    pub fn new(from: Point, to: Point, ms: u32) -> Self {
        let steps = ms
            .div_ceil(1000 / STEPS_PER_SECOND)
            .clamp(1, u16::MAX as u32) as u16;
        Self {
            from,
            to,
            step: 0,
            steps,
        }
    }

    /// At `to` at once (a finished fade).
    pub fn at_once(to: Point) -> Self {
        Self {
            from: to,
            to,
            step: 0,
            steps: 0,
        }
    }

    /// Steps taken and in all.
    pub fn progress(&self) -> (u16, u16) {
        (self.step, self.steps)
    }

    /// Whether steps remain.
    pub fn running(&self) -> bool {
        self.step < self.steps
    }

    /// The point reached so far (the target once finished).
    pub fn now(&self) -> Point {
        if self.running() {
            self.at(self.step as f32 / self.steps as f32)
        } else {
            self.to
        }
    }

    /// Takes the next step and returns its point (the last one is the target exactly), or
    /// `None` when done.
    pub fn next_point(&mut self) -> Option<Point> {
        if !self.running() {
            return None;
        }
        self.step += 1;
        Some(self.now())
    }

    /// The point a fraction `s ∈ [0, 1]` of the way.
    pub fn at(&self, s: f32) -> Point {
        let lerp = |a: f32, b: f32| a + (b - a) * s;
        // L^{1/3} with the powf the curves use (no second cube-root routine in a device's flash)
        let cbrt = |v: f32| crate::math::powf(v, 1.0 / 3.0);
        let l = lerp(cbrt(self.from.lum), cbrt(self.to.lum));
        Point {
            uv: [
                lerp(self.from.uv[0], self.to.uv[0]),
                lerp(self.from.uv[1], self.to.uv[1]),
            ],
            lum: (l * l * l).clamp(0.0, 1.0),
        }
    }
}

/// What [`Mixer::target`] reports: the solved target and its mix.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solved<const M: usize> {
    /// The target point.
    pub point: Point,
    /// Light fractions (before the curves and quantisation), channel order; zeros past `n`.
    pub light: [f32; M],
    /// PWM duties out of the full scale; zeros past `n`.
    pub duty: [u16; M],
    /// Channel count.
    pub n: usize,
    /// Fade steps that will take the LED there (0: shown at once).
    pub steps: u16,
}

/// The device's mixing state: channels, the fade time and the fade to the last target
/// (finished when the target is shown; a target at `u′v′ = (0, 0)`, which no light has, until
/// one is given). The duties shown are not kept (RAM): [`Mixer::duty`] solves them again.
#[derive(Clone, Debug, PartialEq)]
pub struct Mixer<const M: usize> {
    /// The channels.
    pub channels: Channels<M>,
    /// Fade time for new targets, ms (0: at once).
    pub fade_ms: u32,
    fade: Fade,
}

impl<const M: usize> Default for Mixer<M> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const M: usize> Mixer<M> {
    /// No channels, no fade, nothing shown.
    pub const fn new() -> Self {
        let black = Point {
            uv: [0.0; 2],
            lum: 0.0,
        };
        Self {
            channels: Channels::new(),
            fade_ms: 0,
            fade: Fade {
                from: black,
                to: black,
                step: 0,
                steps: 0,
            },
        }
    }

    /// The duties shown now (zeros past the channel count, and all zeros before any target or
    /// when the point shown cannot be made by the channels now).
    pub fn duty(&self, max: u16) -> [u16; M] {
        self.shown()
            .and_then(|p| self.channels.solve(p).ok())
            .map_or([0; M], |d| self.channels.duties(&d, max))
    }

    /// The point shown now, if a target was ever shown.
    pub fn shown(&self) -> Option<Point> {
        (self.fade.to.uv != [0.0; 2]).then(|| self.fade.now())
    }

    /// Whether a fade is under way.
    pub fn fading(&self) -> bool {
        self.fade.running()
    }

    /// Solves `goal`; with a fade time, starts a fade from the point shown now (from black at
    /// the target's chromaticity when nothing was shown), else shows it at once. On an error
    /// nothing changes.
    pub fn target(&mut self, goal: Goal, max: u16) -> Result<Solved<M>, MixError> {
        let point = goal.point().ok_or(MixError::BadTarget)?;
        let light = self.channels.solve(point)?;
        let duty = self.channels.duties(&light, max);
        self.fade = if self.fade_ms > 0 {
            let from = self.shown().unwrap_or(Point { lum: 0.0, ..point });
            Fade::new(from, point, self.fade_ms)
        } else {
            Fade::at_once(point)
        };
        Ok(Solved {
            point,
            light,
            duty,
            n: self.channels.list().len(),
            steps: self.fade.progress().1,
        })
    }

    /// One fade step: the next point solved; returns (step, steps, its duties), or `None` when
    /// no fade is under way. A step that cannot be solved (the channels changed meanwhile) ends
    /// the fade where it is.
    pub fn step(&mut self, max: u16) -> Option<(u16, u16, [u16; M])> {
        let p = self.fade.next_point()?;
        match self.channels.solve(p) {
            Ok(light) => {
                let (k, n) = self.fade.progress();
                Some((k, n, self.channels.duties(&light, max)))
            }
            Err(_) => {
                self.fade = Fade::at_once(p);
                None
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Three narrow-band-like channels and a white, XYZ at full drive.
    fn rgbw() -> Channels<6> {
        let mut c = Channels::new();
        for (i, xyz) in [
            [0.65, 0.30, 0.0],
            [0.25, 0.70, 0.10],
            [0.18, 0.08, 0.95],
            [0.95, 1.0, 0.85],
        ]
        .into_iter()
        .enumerate()
        {
            let ch = Channel::new(xyz, 1.0, Curve::Linear);
            c.set(i, ch).unwrap();
        }
        c
    }

    fn made(c: &Channels<6>, d: &[f32; 6]) -> [f32; 3] {
        let mut xyz = [0.0; 3];
        for (i, ch) in c.list().iter().enumerate() {
            for k in 0..3 {
                xyz[k] += d[i] * ch.xyz[k];
            }
        }
        xyz
    }

    #[test]
    fn a_mix_makes_its_chromaticity_and_the_freedom_goes_to_the_least_drive() {
        let c = rgbw();
        let p = Goal::Xy {
            xy: [0.3127, 0.329],
            lum: 0.5,
        }
        .point()
        .unwrap();
        let d = c.solve(p).unwrap();
        let xyz = made(&c, &d);
        let s = xyz[0] + xyz[1] + xyz[2];
        assert!((xyz[0] / s - 0.3127).abs() < 2e-6 && (xyz[1] / s - 0.329).abs() < 2e-6);
        assert!(d.iter().all(|v| (0.0..=1.0).contains(v)));
        let full = c.solve(Point { lum: 1.0, ..p }).unwrap();
        assert!(
            (made(&c, &full)[1] - 2.0 * xyz[1]).abs() < 1e-5,
            "L is relative"
        );
        // the least drive among every mix of the same colour: the white's duty on a grid, the
        // other three solved for it
        let l = c.list();
        let rgb = inverse([l[0].xyz, l[1].xyz, l[2].xyz]).unwrap();
        let mut least = f32::INFINITY;
        for w in 0..=10_000 {
            let w = w as f32 / 10_000.0;
            let rest: [f32; 3] = core::array::from_fn(|r| xyz[r] - w * c.list()[3].xyz[r]);
            let d3: [f32; 3] = core::array::from_fn(|r| (0..3).map(|k| rgb[r][k] * rest[k]).sum());
            if d3.iter().all(|v| (0.0..=1.0).contains(v)) {
                least = least.min(w + d3.iter().sum::<f32>());
            }
        }
        let sum: f32 = d.iter().sum();
        assert!(d[3] > 0.0 && sum <= least + 1e-5, "{sum} vs {least}");
    }

    #[test]
    fn out_of_gamut_and_too_few_channels_are_errors() {
        let c = rgbw();
        let far = Goal::Xy {
            xy: [0.08, 0.85],
            lum: 1.0,
        };
        assert_eq!(c.solve(far.point().unwrap()), Err(MixError::OutOfGamut));
        let mut two: Channels<6> = Channels::new();
        two.set(0, c.list()[0]).unwrap();
        assert_eq!(two.set(2, c.list()[1]), Err(MixError::Channels));
        two.set(1, c.list()[1]).unwrap();
        assert_eq!(
            two.solve(Point {
                uv: [0.2, 0.45],
                lum: 1.0
            }),
            Err(MixError::Channels)
        );
        assert!(Goal::Cct {
            cct: 500.0,
            duv: 0.0,
            lum: 1.0
        }
        .point()
        .is_none());
    }

    #[test]
    fn a_fade_ends_on_its_target_and_approaches_it_monotonically() {
        let mut m: Mixer<6> = Mixer::new();
        m.channels = rgbw();
        let a = Goal::Cct {
            cct: 2700.0,
            duv: 0.0,
            lum: 0.2,
        };
        let b = Goal::Cct {
            cct: 6500.0,
            duv: 0.0,
            lum: 0.9,
        };
        m.target(a, 65535).unwrap();
        m.fade_ms = 250;
        let end = m.target(b, 65535).unwrap();
        assert_eq!(end.steps, 25);
        let target = end.point;
        let mut last = f32::INFINITY;
        let mut n = 0;
        let mut duty = [0; 6];
        while let Some((k, all, d)) = m.step(65535) {
            duty = d;
            n += 1;
            assert_eq!((k, all), (n, 25));
            let p = m.shown().unwrap();
            let dist = libm::hypotf(p.uv[0] - target.uv[0], p.uv[1] - target.uv[1])
                + (libm::cbrtf(p.lum) - libm::cbrtf(target.lum)).abs();
            assert!(dist < last, "step {k}");
            last = dist;
        }
        assert_eq!(n, 25);
        assert_eq!(duty, end.duty);
        assert_eq!(m.duty(65535), end.duty);
        assert!(!m.fading());
    }
}
