//! Choosing the interaction lattice by cross-validation, not by how well it fits.
//!
//! A lattice always lowers the error on the patches it was fitted on; whether it predicts
//! patches it has not seen is what matters (a display's profile is used between its patches).
//! So the fit patches are split into [`FOLDS`] folds (every patch but black and the full
//! primaries, by position: patch `i` in fold `i mod 5`); each candidate — no lattice, or a
//! lattice of 2, 5, 7 or 9 nodes a side — is fitted [`FOLDS`] times, each time without one
//! fold, and scored by the mean ΔE00 on the fold it did not see, pooled over the folds. The
//! simplest candidate within [`TIE`] of the best is chosen.

use super::{fit_model, is_anchor, model_name, FitOptions, InteractionChoice};
use crate::error::Result;
use crate::verify;
use specpoly_display::calibration::Candidate;
use specpoly_formats::measurement::Measurement;

/// Folds of the cross-validation.
pub const FOLDS: usize = 5;
/// The lattice sides tried with [`InteractionChoice::Auto`], simplest first.
pub const SIDES: [usize; 4] = [2, 5, 7, 9];
/// A more complex candidate must beat a simpler one by this fraction of its error.
pub const TIE: f64 = 0.01;
/// Below this many patches outside black and the primaries, no lattice is tried.
pub const MIN_PATCHES: usize = 30;

/// The lattice side to fit (`None`: no lattice) and the candidates' scores.
pub fn choose(meas: &[Measurement], opts: &FitOptions) -> Result<(Option<usize>, Vec<Candidate>)> {
    let candidates: Vec<Option<usize>> = match opts.interaction {
        InteractionChoice::None => return Ok((None, Vec::new())),
        InteractionChoice::Grid(g) => return Ok((Some(g), Vec::new())),
        InteractionChoice::Auto => std::iter::once(None)
            .chain(SIDES.iter().map(|g| Some(*g)))
            .collect(),
    };
    let free: Vec<usize> = (0..meas.len()).filter(|i| !is_anchor(&meas[*i])).collect();
    if free.len() < MIN_PATCHES {
        return Ok((None, Vec::new()));
    }
    let mut scores = Vec::new();
    for grid in &candidates {
        let mut sum = 0.0;
        let mut n = 0usize;
        let mut ok = true;
        for fold in 0..FOLDS {
            let (mut train, mut test) = (Vec::new(), Vec::new());
            for (i, m) in meas.iter().enumerate() {
                if is_anchor(m) {
                    train.push(*m);
                } else if free.binary_search(&i).is_ok_and(|k| k % FOLDS == fold) {
                    test.push(*m);
                } else {
                    train.push(*m);
                }
            }
            match fit_model(&train, opts, *grid) {
                Ok(cal) => {
                    let de = verify::delta_e(&cal, &test);
                    sum += de.iter().sum::<f64>();
                    n += de.len();
                }
                Err(_) => {
                    ok = false;
                    break;
                }
            }
        }
        let mean = if ok && n > 0 && sum.is_finite() {
            sum / n as f64
        } else {
            f64::INFINITY
        };
        scores.push((*grid, mean));
    }
    // the simplest within TIE of the best
    let best = scores.iter().map(|s| s.1).fold(f64::INFINITY, f64::min);
    let chosen = scores
        .iter()
        .find(|s| s.1 <= best * (1.0 + TIE))
        .and_then(|s| s.0);
    // candidates that could not be fitted on some fold are left out of the report
    let report = scores
        .iter()
        .filter(|(_, m)| m.is_finite())
        .map(|(g, m)| Candidate {
            model: model_name(opts, *g),
            cv_mean: *m,
        })
        .collect();
    Ok((chosen, report))
}
