//! Is this a reflectance? Data that cannot be one is refused with a one-line hint rather than
//! turned into colours: percent-scaled values (0–100: `--scale 0.01`), negative values, an
//! illuminant's spectrum given where a reflectance belongs (`xyz D65` would print `Y ≈ 10 000`),
//! and results that overflowed. Nothing non-finite is ever printed.
//!
//! The one implementation of these checks for `xyz`, `fit`, `plot` (spectra named on the
//! command line, [`Given::Argument`]) and `render` (a scene's material spectra,
//! [`Given::Scene`]); only the hint differs, naming the fix where the data was given.

use crate::spectrum_names::Named;
use crate::{Error, Result};
use specpoly_core::Illuminant;

/// The largest reflectance value accepted: fluorescent samples exceed 1 a little, 1.5 is no
/// longer a reflectance.
pub const MAX_REFLECTANCE: f32 = 1.5;

/// The most negative value accepted (measurement noise around 0).
pub const MIN_REFLECTANCE: f32 = -0.01;

/// Where a reflectance was given, for the hint that fixes it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Given {
    /// On the command line of a command with `--scale` (`xyz`, `fit`, `plot`); `light_flag`:
    /// whether it also takes a light (`--illuminant`).
    Argument {
        /// The command takes `--illuminant`.
        light_flag: bool,
    },
    /// In a scene file's materials (fixed by `{ spectrum = NAME, scale = K }`).
    Scene,
    /// As an array to the Python package (fixed by its `scale=` and `illuminant=` keywords).
    Python,
}

impl Given {
    fn percent_hint(self) -> &'static str {
        match self {
            Given::Argument { .. } => "percent data? add --scale 0.01",
            Given::Scene => "percent data? give it as { spectrum = NAME, scale = 0.01 }",
            Given::Python => "percent data? pass scale=0.01",
        }
    }

    fn illuminant_hint(self) -> &'static str {
        match self {
            Given::Argument { light_flag: true } => {
                "it is an illuminant, not a reflectance: give it with --illuminant"
            }
            Given::Argument { light_flag: false } => {
                "it is an illuminant, not a reflectance: bring it into 0–1 with --scale (0.01 for D65)"
            }
            Given::Scene => {
                "it is an illuminant, not a reflectance: lights go in [[light]], or use { spectrum = NAME, normalize = true }"
            }
            Given::Python => "it is an illuminant, not a reflectance: pass it as illuminant=",
        }
    }
}

/// Refuses `n` if it cannot be a reflectance, with the hint that fixes it where it was
/// `given`.
pub fn reflectance_given(n: &Named, given: Given) -> Result<()> {
    let (lo_i, lo) = extreme(&n.values, |a, b| a < b);
    let (hi_i, hi) = extreme(&n.values, |a, b| a > b);
    if let Some(i) = n.values.iter().position(|v| !v.is_finite()) {
        return Err(Error::NotReflectance {
            name: n.name.clone(),
            why: format!("value at {} nm is not finite", n.wavelengths[i]),
        });
    }
    if lo < MIN_REFLECTANCE {
        return Err(Error::NotReflectance {
            name: n.name.clone(),
            why: format!(
                "reflectance {lo} at {} nm is negative; reflectances lie in 0–1",
                n.wavelengths[lo_i]
            ),
        });
    }
    if hi > MAX_REFLECTANCE {
        let hint = if Illuminant::from_name(n.short()).is_some()
            || Illuminant::from_name(&n.name).is_some()
        {
            given.illuminant_hint().to_string()
        } else if hi <= 100.0 * MAX_REFLECTANCE {
            given.percent_hint().to_string()
        } else {
            format!("reflectances lie in 0–{MAX_REFLECTANCE}")
        };
        return Err(Error::NotReflectance {
            name: n.name.clone(),
            why: format!(
                "reflectance {hi} at {} nm is above {MAX_REFLECTANCE}: {hint}",
                n.wavelengths[hi_i]
            ),
        });
    }
    Ok(())
}

/// [`reflectance_given`] for `xyz`'s arguments.
pub fn reflectance(n: &Named) -> Result<()> {
    reflectance_given(n, Given::Argument { light_flag: true })
}

/// The spectra named on a command line, each multiplied by `scale` and checked as a
/// reflectance: what `xyz`, `fit` and `plot` do with their arguments.
pub fn reflectances(names: &[String], scale: f64, light_flag: bool) -> Result<Vec<Named>> {
    let named = crate::spectrum_names::resolve_all(names)?
        .into_iter()
        .map(|n| scaled(n, scale))
        .collect::<Result<Vec<_>>>()?;
    for n in &named {
        reflectance_given(n, Given::Argument { light_flag })?;
    }
    Ok(named)
}

/// `n` with every value multiplied by `scale` (finite and > 0).
pub fn scaled(mut n: Named, scale: f64) -> Result<Named> {
    if !(scale.is_finite() && scale > 0.0) {
        return Err(Error::BadScale(scale));
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
        Err(Error::Overflow {
            name: name.to_string(),
        })
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

/// Refuses an image with a non-finite pixel (a light or scale so large that it overflowed).
pub fn image(what: &str, xyz: &[specpoly_core::Xyz]) -> Result<()> {
    if xyz
        .iter()
        .all(|p| p.x.is_finite() && p.y.is_finite() && p.z.is_finite())
    {
        Ok(())
    } else {
        Err(Error::ImageOverflow {
            what: what.to_string(),
        })
    }
}
