//! Is this a reflectance? Data that cannot be one is refused with a one-line hint rather than
//! turned into colours: percent-scaled values (0–100: `--scale 0.01`), negative values, an
//! illuminant's spectrum given where a reflectance belongs (`xyz D65` would print `Y ≈ 10 000`),
//! and results that overflowed. Nothing non-finite is ever printed.

use crate::error::{CliError, Result};
use crate::spectrum_names::Named;
use specpoly_core::Illuminant;

/// The largest reflectance value accepted: fluorescent samples exceed 1 a little, 1.5 is no
/// longer a reflectance.
pub const MAX_REFLECTANCE: f32 = 1.5;

/// The most negative value accepted (measurement noise around 0).
pub const MIN_REFLECTANCE: f32 = -0.01;

/// Refuses `n` if it cannot be a reflectance, with the hint that fixes it.
pub fn reflectance(n: &Named) -> Result<()> {
    let (lo_i, lo) = extreme(&n.values, |a, b| a < b);
    let (hi_i, hi) = extreme(&n.values, |a, b| a > b);
    if lo < MIN_REFLECTANCE {
        return Err(CliError::data(format!(
            "{}: reflectance {lo} at {} nm is negative; reflectances lie in 0–1",
            n.name, n.wavelengths[lo_i]
        )));
    }
    if hi > MAX_REFLECTANCE {
        let hint = if Illuminant::from_name(&n.name).is_some() {
            "it is an illuminant, not a reflectance: give it with --illuminant".to_string()
        } else if hi <= 100.0 * MAX_REFLECTANCE {
            "percent data? add --scale 0.01".to_string()
        } else {
            format!("reflectances lie in 0–{MAX_REFLECTANCE}")
        };
        return Err(CliError::data(format!(
            "{}: reflectance {hi} at {} nm is above {MAX_REFLECTANCE}: {hint}",
            n.name, n.wavelengths[hi_i]
        )));
    }
    Ok(())
}

/// `n` with every value multiplied by `scale` (finite and > 0).
pub fn scaled(mut n: Named, scale: f64) -> Result<Named> {
    if !(scale.is_finite() && scale > 0.0) {
        return Err(CliError::usage(format!("--scale {scale}: must be > 0")));
    }
    if scale != 1.0 {
        for v in &mut n.values {
            *v = (*v as f64 * scale) as f32;
        }
        n = Named::new(n.name, n.wavelengths, n.values)?;
    }
    Ok(n)
}

/// Refuses a result with a non-finite component (an overflow) instead of printing it.
pub fn finite(name: &str, values: &[f64]) -> Result<()> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(CliError::data(format!(
            "{name}: the result overflowed (not finite); check the input's scale"
        )))
    }
}

fn extreme(v: &[f32], better: impl Fn(f32, f32) -> bool) -> (usize, f32) {
    let mut best = (0, v.first().copied().unwrap_or(0.0));
    for (i, x) in v.iter().copied().enumerate() {
        if better(x, best.1) {
            best = (i, x);
        }
    }
    best
}
