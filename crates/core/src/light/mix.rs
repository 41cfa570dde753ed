//! Duties for 3–6 LED channels that make a target chromaticity at a relative luminance, the
//! remaining freedom spent on colour rendering, efficacy or drive.
//!
//! Each channel is its SPD at full drive ([`Source`]); PWM duty `dᵢ ∈ [0, 1]` scales it linearly,
//! so the mix `Σ dᵢ·Sᵢ` has tristimulus values `A·d` (`A` the 3×N matrix of the channels' XYZ)
//! and moments `Σ wᵢ·Mᵢ` ([`Source::mix`]). For a target chromaticity `(x, y)`:
//!
//! 1. the achievable luminance is the linear programme `max Σ dᵢYᵢ` subject to
//!    `Σ dᵢ(Xᵢ − x/y·Yᵢ) = 0`, `Σ dᵢ(Zᵢ − z/y·Yᵢ) = 0`, `0 ≤ d ≤ 1`; its optimum is at a vertex
//!    where at most two duties are strictly between 0 and 1, so all vertices are enumerated
//!    (`C(N,2)·2^{N−2}` 2×2 solves, 240 for six channels). No positive vertex: out of gamut.
//! 2. The target `Y = L·Y_max` fixes `A·d = t`, a polytope of dimension `N − 3`. Its vertices
//!    (at most three duties free, `C(N,3)·2^{N−3}` 3×3 solves) give the optimum of the linear
//!    objectives: least radiant power `Σ dᵢΦᵢ` (= greatest luminous efficacy of radiation, as `Y`
//!    is fixed) and least drive `Σ dᵢ` (electrical power when the channels draw equal power at
//!    full drive).
//! 3. Rf and Ra are not linear: every vertex is scored, then a pattern search over the `N − 3`
//!    free duties (the other three solved from `A·d = t`) along the axes and their pairwise
//!    diagonals, started at the centroid of the vertices, halfway from it to up to eight
//!    vertices, and at the best vertex; steps from 0.1 halved to 10⁻⁴, infeasible steps rejected.
//!
//! With three channels the duties are unique. The duties are fractions of each channel's light;
//! [`Mix::drive`] turns them into device values through a transfer curve and quantises them.
//!
//! The matrix `A` is the channels' CIE 1931 tristimulus values ([`Source::xyz`]) unless the
//! caller gives it ([`solve_mix_seen`]): the channels' `X, Y, Z` under another observer (CIE 1964,
//! CIE 2015, a runtime table), the target chromaticity then read under that observer and the
//! relative luminance on its `Y`. Linear in the duties either way, so the solve is the same.

use super::{cct, cri, source::Source, tm30, Cct, LightError, Samples};
use crate::display::{quantize, Transfer};
use heapless::Vec;

/// Most channels in a mix.
pub const MAX_CHANNELS: usize = 6;
pub(super) const MAX_VERTICES: usize = 160; // C(6,3)·2³

/// A chromaticity target.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Target {
    /// CIE 1931 (x, y).
    Xy([f64; 2]),
    /// A CCT (K) and Duv from the Planckian locus ([`cct::cct_to_uv`]).
    Cct(Cct),
}

impl Target {
    /// The target's CIE 1931 (x, y).
    pub fn xy(&self) -> Result<[f64; 2], LightError> {
        let xy = match self {
            Target::Xy(xy) => *xy,
            Target::Cct(c) => cct::uv_to_xy(cct::cct_to_uv(*c)?),
        };
        let [x, y] = xy;
        if !(x.is_finite() && y.is_finite() && x > 0.0 && y > 0.0 && x + y < 1.0) {
            return Err(LightError::BadTarget);
        }
        Ok(xy)
    }
}

/// What the freedom left by more than three channels is spent on.
#[derive(Clone, Copy, Debug)]
pub enum Objective<'a> {
    /// Greatest CIE 224:2017 fidelity Rf (with the fitted colour evaluation samples).
    Rf(&'a Samples<99>),
    /// Greatest CIE 13.3 Ra (with the fitted test colour samples).
    Ra(&'a Samples<14>),
    /// Greatest luminous efficacy of radiation (least radiant power).
    Efficacy,
    /// Least total drive `Σ dᵢ`.
    Power,
}

/// A solved mix.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mix {
    duties: [f64; MAX_CHANNELS],
    n: usize,
    /// The light the duties make.
    pub light: Source,
}

impl Mix {
    /// The duties, in channel order, each in [0, 1].
    pub fn duties(&self) -> &[f64] {
        &self.duties[..self.n]
    }

    /// The device values that make this mix through the channels' transfer curve
    /// (`transfer.encode` of each duty, the light fraction), quantised to `bits`-bit PWM steps
    /// when asked ([`crate::display::quantize`]), and the light the device values make
    /// (`transfer.decode`).
    pub fn drive(
        &self,
        channels: &[Source],
        transfer: &Transfer,
        bits: Option<u32>,
    ) -> Result<Driven, LightError> {
        let max = match bits {
            None => None,
            Some(b @ 1..=16) => Some(((1u32 << b) - 1) as u16),
            Some(_) => return Err(LightError::BadTarget),
        };
        let mut drive = [0.0; MAX_CHANNELS];
        let mut light = [0.0; MAX_CHANNELS];
        for i in 0..self.n {
            let mut v = transfer.encode(self.duties[i] as f32);
            if let Some(m) = max {
                v = quantize(v, m) as f32 / m as f32;
            }
            drive[i] = v as f64;
            light[i] = transfer.decode(v) as f64;
        }
        Ok(Driven {
            drive,
            mix: make(channels, &light[..self.n])?,
        })
    }
}

/// Device values for the channels and the mix they make ([`Mix::drive`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Driven {
    drive: [f64; MAX_CHANNELS],
    /// The light the (quantised) device values make.
    pub mix: Mix,
}

impl Driven {
    /// The device values (PWM duties), in channel order, each in [0, 1].
    pub fn drive(&self) -> &[f64] {
        &self.drive[..self.mix.n]
    }
}

pub(super) fn make(channels: &[Source], d: &[f64]) -> Result<Mix, LightError> {
    let mut parts: Vec<(f64, &Source), MAX_CHANNELS> = Vec::new();
    for (di, c) in d.iter().zip(channels) {
        let _ = parts.push((*di, c));
    }
    let mut duties = [0.0; MAX_CHANNELS];
    duties[..d.len()].copy_from_slice(d);
    Ok(Mix {
        duties,
        n: d.len(),
        light: Source::mix(&parts)?,
    })
}

/// Solves the `K × K` system `m·x = r` with the core's one solver; `None` when singular.
fn solve<const K: usize>(m: [[f64; K]; K], r: [f64; K]) -> Option<[f64; K]> {
    let mut a = [0.0f64; 9];
    for (row, v) in m.iter().enumerate() {
        a[row * K..row * K + K].copy_from_slice(v);
    }
    let mut x = r;
    crate::solve::solve(&mut a[..K * K], &mut x).ok()?;
    Some(x)
}

const EPS: f64 = 1e-9;

fn in_unit(v: f64) -> bool {
    (-EPS..=1.0 + EPS).contains(&v)
}

/// The problem for one set of channels and one chromaticity.
pub(super) struct Problem<'c> {
    channels: &'c [Source],
    pub(super) n: usize,
    /// Rows: X, Y, Z of each channel, scaled so the largest |entry| is 1.
    a: [[f64; MAX_CHANNELS]; 3],
    /// Chromaticity constraint rows.
    b: [[f64; MAX_CHANNELS]; 2],
}

impl<'c> Problem<'c> {
    fn new(channels: &'c [Source], seen: &[[f64; 3]], xy: [f64; 2]) -> Result<Self, LightError> {
        let n = channels.len();
        if !(3..=MAX_CHANNELS).contains(&n) {
            return Err(LightError::Channels(n));
        }
        if seen.len() != n {
            return Err(LightError::Channels(seen.len()));
        }
        if !seen.iter().flatten().all(|v| v.is_finite()) {
            return Err(LightError::BadTarget);
        }
        let mut a = [[0.0; MAX_CHANNELS]; 3];
        let mut scale = 0.0f64;
        for (i, c) in seen.iter().enumerate() {
            for (k, v) in c.iter().enumerate() {
                a[k][i] = *v;
                scale = scale.max(v.abs());
            }
        }
        for row in a.iter_mut() {
            for v in row.iter_mut() {
                *v /= scale;
            }
        }
        let [x, y] = xy;
        let mut b = [[0.0; MAX_CHANNELS]; 2];
        for i in 0..n {
            b[0][i] = a[0][i] - x / y * a[1][i];
            b[1][i] = a[2][i] - (1.0 - x - y) / y * a[1][i];
        }
        Ok(Self { channels, n, a, b })
    }

    /// Greatest `Σ dᵢYᵢ` (scaled) at the target chromaticity.
    fn max_luminance(&self) -> f64 {
        let n = self.n;
        let mut best = 0.0f64;
        for p in 0..n {
            for q in p + 1..n {
                let others = n - 2;
                for mask in 0u32..(1 << others) {
                    let mut d = [0.0; MAX_CHANNELS];
                    let mut bit = 0;
                    for (i, di) in d.iter_mut().enumerate().take(n) {
                        if i != p && i != q {
                            *di = ((mask >> bit) & 1) as f64;
                            bit += 1;
                        }
                    }
                    let rhs: [f64; 2] =
                        core::array::from_fn(|r| -(0..n).map(|i| self.b[r][i] * d[i]).sum::<f64>());
                    let m = [[self.b[0][p], self.b[0][q]], [self.b[1][p], self.b[1][q]]];
                    let Some([dp, dq]) = solve(m, rhs) else {
                        continue;
                    };
                    if in_unit(dp) && in_unit(dq) {
                        d[p] = dp.clamp(0.0, 1.0);
                        d[q] = dq.clamp(0.0, 1.0);
                        best = best.max((0..n).map(|i| self.a[1][i] * d[i]).sum());
                    }
                }
            }
        }
        best
    }

    /// Every vertex of `{A·d = t, 0 ≤ d ≤ 1}`.
    fn vertices(&self, t: [f64; 3]) -> Vec<[f64; MAX_CHANNELS], MAX_VERTICES> {
        let n = self.n;
        let mut out = Vec::new();
        for p in 0..n {
            for q in p + 1..n {
                for s in q + 1..n {
                    let free = [p, q, s];
                    for mask in 0u32..(1 << (n - 3)) {
                        let mut d = [0.0; MAX_CHANNELS];
                        let mut bit = 0;
                        for (i, di) in d.iter_mut().enumerate().take(n) {
                            if !free.contains(&i) {
                                *di = ((mask >> bit) & 1) as f64;
                                bit += 1;
                            }
                        }
                        let rhs: [f64; 3] = core::array::from_fn(|r| {
                            t[r] - (0..n).map(|i| self.a[r][i] * d[i]).sum::<f64>()
                        });
                        let m = core::array::from_fn(|r| free.map(|c| self.a[r][c]));
                        let Some(x) = solve(m, rhs) else {
                            continue;
                        };
                        if x.iter().all(|v| in_unit(*v)) {
                            for (k, c) in free.iter().enumerate() {
                                d[*c] = x[k].clamp(0.0, 1.0);
                            }
                            let _ = out.push(d);
                        }
                    }
                }
            }
        }
        out
    }
}

/// Solves for the duties that make `target` at relative luminance `luminance` (0 < L ≤ 1 of the
/// most the channels can give at that chromaticity), spending any freedom on `objective`.
pub fn solve_mix(
    channels: &[Source],
    target: Target,
    luminance: f64,
    objective: Objective<'_>,
) -> Result<Mix, LightError> {
    solve_mix_seen(channels, &cie1931(channels), target, luminance, objective)
}

/// The channels' CIE 1931 tristimulus values ([`Source::xyz`]), the default `A`.
pub(super) fn cie1931(channels: &[Source]) -> Vec<[f64; 3], MAX_CHANNELS> {
    channels
        .iter()
        .take(MAX_CHANNELS)
        .map(Source::xyz)
        .collect()
}

/// [`solve_mix`] with the target met under another observer: `seen[i]` is channel `i`'s
/// tristimulus values under it (any common scale), `target` a chromaticity under it (a
/// [`Target::Cct`] is converted on the CIE 1931 diagram, where CCT is defined: give the
/// Planckian radiator's chromaticity under the observer as a [`Target::Xy`] instead), and
/// `luminance` a fraction of the most its `Y` reaches there. Colour rendering and efficacy are
/// the standards' own, whatever the observer.
///
/// Errors as [`solve_mix`], and [`LightError::Channels`] when `seen` and `channels` differ in
/// length, [`LightError::BadTarget`] for a non-finite entry of `seen`.
pub fn solve_mix_seen(
    channels: &[Source],
    seen: &[[f64; 3]],
    target: Target,
    luminance: f64,
    objective: Objective<'_>,
) -> Result<Mix, LightError> {
    let (p, t, verts) = setup(channels, seen, target, luminance)?;
    let n = p.n;
    let linear = |cost: &dyn Fn(usize) -> f64| -> [f64; MAX_CHANNELS] {
        let mut best = (f64::INFINITY, verts[0]);
        for v in &verts {
            let c: f64 = (0..n).map(|i| v[i] * cost(i)).sum();
            if c < best.0 {
                best = (c, *v);
            }
        }
        best.1
    };
    let d = match objective {
        Objective::Power => linear(&|_| 1.0),
        Objective::Efficacy => linear(&|i| channels[i].radiant_sum()),
        Objective::Rf(ces) => search(&p, t, &verts, &|m: &Mix| {
            tm30::tm30(&m.light, ces).map(|r| r.rf)
        })?,
        Objective::Ra(tcs) => search(&p, t, &verts, &|m: &Mix| {
            cri::cri(&m.light, tcs).map(|r| r.ra)
        })?,
    };
    make(channels, &d[..n])
}

/// The vertices of the polytope of duties.
pub(super) type Vertices = Vec<[f64; MAX_CHANNELS], MAX_VERTICES>;

/// The problem of a target at a relative luminance: the channels' matrix, the target
/// tristimulus values `t` and the vertices of the polytope `A·d = t`, `0 ≤ d ≤ 1`.
pub(super) fn setup<'c>(
    channels: &'c [Source],
    seen: &[[f64; 3]],
    target: Target,
    luminance: f64,
) -> Result<(Problem<'c>, [f64; 3], Vertices), LightError> {
    if !(luminance > 0.0 && luminance <= 1.0) {
        return Err(LightError::BadTarget);
    }
    let xy = target.xy()?;
    let p = Problem::new(channels, seen, xy)?;
    let y_max = p.max_luminance();
    if y_max <= 1e-9 {
        return Err(LightError::OutOfGamut);
    }
    let y = luminance * y_max;
    let t = [xy[0] / xy[1] * y, y, (1.0 - xy[0] - xy[1]) / xy[1] * y];
    let verts = p.vertices(t);
    if verts.is_empty() {
        return Err(LightError::OutOfGamut);
    }
    Ok((p, t, verts))
}

/// Compass search for the greatest `score` over the polytope (see the module docs).
pub(super) fn search(
    p: &Problem<'_>,
    t: [f64; 3],
    verts: &[[f64; MAX_CHANNELS]],
    score: &dyn Fn(&Mix) -> Result<f64, LightError>,
) -> Result<[f64; MAX_CHANNELS], LightError> {
    let n = p.n;
    let mut centroid = [0.0; MAX_CHANNELS];
    for v in verts {
        for i in 0..n {
            centroid[i] += v[i] / verts.len() as f64;
        }
    }
    let eval = |d: &[f64; MAX_CHANNELS]| -> f64 {
        make(p.channels, &d[..n])
            .and_then(|m| score(&m))
            .unwrap_or(f64::NEG_INFINITY)
    };
    if n == 3 {
        return Ok(centroid);
    }
    // basis: the three channels with the best-conditioned columns; the rest are free
    let mut basis = [0, 1, 2];
    let mut best_det = 0.0;
    for a in 0..n {
        for b in a + 1..n {
            for c in b + 1..n {
                let m: [[f64; 3]; 3] = core::array::from_fn(|r| [p.a[r][a], p.a[r][b], p.a[r][c]]);
                let det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
                    - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                    + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
                if det.abs() > best_det {
                    best_det = det.abs();
                    basis = [a, b, c];
                }
            }
        }
    }
    let m: [[f64; 3]; 3] = core::array::from_fn(|r| basis.map(|c| p.a[r][c]));
    // duties from the free ones, or None when infeasible
    let complete = |d: &mut [f64; MAX_CHANNELS]| -> bool {
        let rhs: [f64; 3] = core::array::from_fn(|r| {
            t[r] - (0..n)
                .filter(|i| !basis.contains(i))
                .map(|i| p.a[r][i] * d[i])
                .sum::<f64>()
        });
        match solve(m, rhs) {
            Some(x) if x.iter().all(|v| in_unit(*v)) => {
                for (k, c) in basis.iter().enumerate() {
                    d[*c] = x[k].clamp(0.0, 1.0);
                }
                (0..n).all(|i| in_unit(d[i]))
            }
            _ => false,
        }
    };
    let mut starts: Vec<[f64; MAX_CHANNELS], 10> = Vec::new();
    let _ = starts.push(centroid);
    let stride = verts.len().div_ceil(8).max(1);
    for v in verts.iter().step_by(stride) {
        let mut s = [0.0; MAX_CHANNELS];
        for i in 0..n {
            s[i] = 0.5 * (centroid[i] + v[i]);
        }
        let _ = starts.push(s);
    }
    // the vertices themselves (the optimum often lies on the boundary) and the best as a start
    let mut best = (f64::NEG_INFINITY, centroid);
    for v in verts {
        let f = eval(v);
        if f > best.0 {
            best = (f, *v);
        }
    }
    if best.0 > f64::NEG_INFINITY {
        let _ = starts.push(best.1);
    }
    // search directions in the free duties: the axes and, for two or three free duties, the
    // diagonals (so the search can slide along a face the axes would leave)
    let free: Vec<usize, MAX_CHANNELS> = (0..n).filter(|i| !basis.contains(i)).collect();
    let mut dirs: Vec<[f64; MAX_CHANNELS], 32> = Vec::new();
    for (a, &i) in free.iter().enumerate() {
        let mut e = [0.0; MAX_CHANNELS];
        e[i] = 1.0;
        let _ = dirs.push(e);
        for &j in &free[a + 1..] {
            for sj in [1.0, -1.0] {
                let mut e = [0.0; MAX_CHANNELS];
                e[i] = 1.0;
                e[j] = sj;
                let _ = dirs.push(e);
            }
        }
    }
    for start in starts {
        let mut d = start;
        let mut f = eval(&d);
        let mut step = 0.1;
        while step > 1e-4 {
            let mut moved = false;
            for dir in &dirs {
                for sign in [1.0, -1.0] {
                    let mut e = d;
                    for &i in &free {
                        e[i] += sign * step * dir[i];
                    }
                    if !free.iter().all(|&i| in_unit(e[i])) || !complete(&mut e) {
                        continue;
                    }
                    let fe = eval(&e);
                    if fe > f {
                        d = e;
                        f = fe;
                        moved = true;
                    }
                }
            }
            if !moved {
                step *= 0.5;
            }
        }
        if f > best.0 {
            best = (f, d);
        }
    }
    if best.0 == f64::NEG_INFINITY {
        // the metric is undefined everywhere (target far from the Planckian locus)
        let c = cct::xy_to_uv([t[0] / (t[0] + t[1] + t[2]), t[1] / (t[0] + t[1] + t[2])]);
        return Err(LightError::NoCct { u: c[0], v: c[1] });
    }
    Ok(best.1)
}
