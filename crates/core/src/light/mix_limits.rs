//! Mixing to a specification: the duties of [`super::mix`] with lower limits on the mix's
//! colour rendering (`Ra ≥ 90`, `R9 ≥ 50`, `Rf ≥ 85`, `Rg ≥ 95`), the freedom left spent on the
//! objective.
//!
//! The limits join the objective in one score for the same compass search over the polytope of
//! duties that make the target (module docs of [`super::mix`]): a mix that meets every limit
//! scores its objective (Rf or Ra as they are, efficacy and least drive as the negated cost
//! relative to the dearest channel, both in [−6, 0]); a mix that misses scores
//! `−10⁴ − shortfall`, the shortfall being the sum of the amounts by which it misses. So the
//! search first walks towards the limits and, once inside, towards the objective. When no mix
//! meets them, the one with the least shortfall is returned with that shortfall: how close the
//! channels get. A chromaticity limit (CCT, Duv, an ANSI C78.377 quadrangle) is a limit on the
//! target, not on the duties, and is checked there.

use super::mix::{cie1931, make, search, setup, Mix, Objective, Target, MAX_CHANNELS};
use super::{cri, source::Source, tm30, LightError, Samples};

/// A colour-rendering figure of a mix.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Metric {
    /// CIE 13.3 Ra.
    Ra,
    /// CIE 13.3 R9.
    R9,
    /// CIE 224:2017 Rf.
    Rf,
    /// TM-30 Rg.
    Rg,
}

/// `metric ≥ min`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limit {
    /// The figure.
    pub metric: Metric,
    /// Its least value.
    pub min: f64,
}

/// A mix solved under limits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limited {
    /// The mix.
    pub mix: Mix,
    /// Sum of the amounts by which it misses the limits (0: it meets them all).
    pub shortfall: f64,
}

/// The figures `limits` ask for, of one light (the fitted samples' fast path).
fn shortfall(
    light: &Source,
    limits: &[Limit],
    tcs: &Samples<14>,
    ces: &Samples<99>,
) -> Result<f64, LightError> {
    let needs = |m: &[Metric]| limits.iter().any(|l| m.contains(&l.metric));
    let c = if needs(&[Metric::Ra, Metric::R9]) {
        Some(cri::cri(light, tcs)?)
    } else {
        None
    };
    let t = if needs(&[Metric::Rf, Metric::Rg]) {
        Some(tm30::tm30(light, ces)?)
    } else {
        None
    };
    let mut s = 0.0;
    for l in limits {
        let v = match (l.metric, &c, &t) {
            (Metric::Ra, Some(c), _) => c.ra,
            (Metric::R9, Some(c), _) => c.r[8],
            (Metric::Rf, _, Some(t)) => t.rf,
            (Metric::Rg, _, Some(t)) => t.rg,
            _ => return Err(LightError::BadTarget),
        };
        s += (l.min - v).max(0.0);
    }
    Ok(s)
}

/// Solves for the duties that make `target` at relative luminance `luminance` meeting `limits`,
/// spending what freedom is left on `objective` (see the module docs).
pub fn solve_mix_limited(
    channels: &[Source],
    target: Target,
    luminance: f64,
    objective: Objective<'_>,
    limits: &[Limit],
    tcs: &Samples<14>,
    ces: &Samples<99>,
) -> Result<Limited, LightError> {
    let seen = cie1931(channels);
    solve_mix_limited_seen(
        channels, &seen, target, luminance, objective, limits, tcs, ces,
    )
}

/// [`solve_mix_limited`] with the target met under another observer (`seen`, as
/// [`super::mix::solve_mix_seen`]); the limits are the standards' figures, whatever the
/// observer.
#[allow(clippy::too_many_arguments)] // the limited solve's inputs plus the observer's matrix
pub fn solve_mix_limited_seen(
    channels: &[Source],
    seen: &[[f64; 3]],
    target: Target,
    luminance: f64,
    objective: Objective<'_>,
    limits: &[Limit],
    tcs: &Samples<14>,
    ces: &Samples<99>,
) -> Result<Limited, LightError> {
    if limits.iter().any(|l| !l.min.is_finite()) {
        return Err(LightError::BadTarget);
    }
    let (p, t, verts) = setup(channels, seen, target, luminance)?;
    let n = p.n;
    let dearest = |cost: &dyn Fn(usize) -> f64| (0..n).map(cost).fold(f64::MIN_POSITIVE, f64::max);
    let radiant = |i: usize| channels[i].radiant_sum();
    let (r_max, one) = (dearest(&radiant), 1.0);
    let score = |m: &Mix| -> Result<f64, LightError> {
        let s = shortfall(&m.light, limits, tcs, ces)?;
        if s > 0.0 {
            return Ok(-1e4 - s);
        }
        let d = m.duties();
        Ok(match objective {
            Objective::Rf(ces) => tm30::tm30(&m.light, ces)?.rf,
            Objective::Ra(tcs) => cri::cri(&m.light, tcs)?.ra,
            Objective::Efficacy => -(0..n).map(|i| d[i] * radiant(i)).sum::<f64>() / r_max,
            Objective::Power => -d.iter().sum::<f64>() / one,
        })
    };
    let d: [f64; MAX_CHANNELS] = search(&p, t, &verts, &score)?;
    let mix = make(channels, &d[..n])?;
    let shortfall = shortfall(&mix.light, limits, tcs, ces)?;
    Ok(Limited { mix, shortfall })
}
