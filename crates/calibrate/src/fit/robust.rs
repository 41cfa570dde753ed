//! Bad readings: a patch read during a flicker, while the display was still settling, or of
//! the wrong colour pulls a least-squares fit towards it. After each fit, every patch's
//! ΔE00 against the model is compared with a robust scale of all of them — the median `m`
//! and `σ = 1.4826 · MAD` (the median absolute deviation, scaled to a normal standard
//! deviation; Rousseeuw & Croux 1993) — and the patches beyond `max(FLOOR, m + K·σ)` and
//! within a factor 2 of the worst are dropped (a bad ramp step drags its neighbours off the
//! model too; they come back once it is gone), at most [`MAX_SHARE`] of the patches per
//! round (beyond that the model, not the data, is wrong); then the model is chosen and
//! fitted again, up to [`ROUNDS`] fits. Black and the full-drive primaries are never dropped (the model is
//! built on them). The dropped patches and why are in the fit report.

use super::{fit_model, is_anchor, select, FitOptions};
use crate::error::Result;
use crate::verify;
use specpoly_display::calibration::{Calibration, Outlier};
use specpoly_formats::measurement::Measurement;

/// How many robust standard deviations above the median a patch's ΔE00 must be.
pub const K: f64 = 10.0;
/// The smallest ΔE00 ever called an outlier (DisplayCAL's recommended maximum is 3).
pub const FLOOR: f64 = 2.0;
/// The largest share of the patches dropped in one round.
pub const MAX_SHARE: f64 = 0.02;
/// Fits at most (the last is never tested).
pub const ROUNDS: usize = 4;

/// The median and the normal-consistent MAD of `v` (not empty).
pub fn robust_scale(v: &[f64]) -> (f64, f64) {
    let med = |s: &mut Vec<f64>| {
        s.sort_by(f64::total_cmp);
        let n = s.len();
        if n % 2 == 1 {
            s[n / 2]
        } else {
            0.5 * (s[n / 2 - 1] + s[n / 2])
        }
    };
    let m = med(&mut v.to_vec());
    let sigma = 1.4826 * med(&mut v.iter().map(|x| (x - m).abs()).collect());
    (m, sigma)
}

/// Chooses the model, fits it, drops outliers and repeats (module docs). Returns the
/// calibration (its report holding the candidates and the outliers) and the patches kept.
pub fn fit_robust(
    meas: &[Measurement],
    opts: &FitOptions,
) -> Result<(Calibration, Vec<Measurement>)> {
    let mut keep = vec![true; meas.len()];
    let mut outliers: Vec<Outlier> = Vec::new();
    let mut round = 0;
    loop {
        let idx: Vec<usize> = (0..meas.len()).filter(|i| keep[*i]).collect();
        let set: Vec<Measurement> = idx.iter().map(|i| meas[*i]).collect();
        let (grid, candidates) = select::choose(&set, opts)?;
        let mut cal = fit_model(&set, opts, grid)?;
        cal.report_mut().0.candidates = candidates;
        let bad = if opts.robust && round + 1 < ROUNDS {
            flag(&cal, &set)
        } else {
            Vec::new()
        };
        if bad.is_empty() {
            outliers.sort_by_key(|o| o.patch);
            cal.report_mut().0.outliers = outliers;
            return Ok((cal, set));
        }
        round += 1;
        for (k, de, reason) in bad {
            let i = idx[k];
            keep[i] = false;
            outliers.push(Outlier {
                patch: i + 1,
                device: meas[i].device,
                delta_e00: de,
                reason,
            });
        }
    }
}

/// The patches of `set` (positions) beyond the limit, worst first, at most [`MAX_SHARE`] of
/// them, with their ΔE00 and the reason.
fn flag(cal: &Calibration, set: &[Measurement]) -> Vec<(usize, f64, String)> {
    let de = verify::delta_e(cal, set);
    if de.is_empty() || de.iter().any(|v| !v.is_finite()) {
        return Vec::new();
    }
    let (m, sigma) = robust_scale(&de);
    let limit = FLOOR.max(m + K * sigma);
    let worst = de.iter().copied().fold(0.0, f64::max);
    let mut bad: Vec<(usize, f64)> = de
        .iter()
        .enumerate()
        .filter(|(i, d)| **d > limit && **d >= 0.5 * worst && !is_anchor(&set[*i]))
        .map(|(i, d)| (i, *d))
        .collect();
    bad.sort_by(|a, b| b.1.total_cmp(&a.1));
    bad.truncate(((set.len() as f64 * MAX_SHARE) as usize).max(1));
    bad.into_iter()
        .map(|(i, d)| {
            (
                i,
                d,
                format!(
                    "ΔE00 {d:.2} against the fitted model, beyond the limit {limit:.2} (median {m:.2} + {K}·{sigma:.2}, robust σ): a reading during a flicker or of the wrong patch"
                ),
            )
        })
        .collect()
}
