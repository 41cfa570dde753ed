//! Equal-time comparison of the path tracer's colour representations against a high-sample
//! 1 nm reference (`specpoly render SCENE --compare --equal-time`).
//!
//! Each mode's time per path is the fastest of [`CALIBRATION_RUNS`] renders at a quarter of the
//! scene's `spp` (the fastest, so that other work on a shared machine disturbs it least). The time
//! budget is the budget mode's (default `poly`) time per path times the scene's `spp`; every mode
//! is then rendered at `budget / its time per path` paths per pixel (rounded, at least 1), so
//! every mode gets about the same time, and the time of that final render is reported. The reference is the 1 nm mode (401 samples) at
//! `reference_spp` paths per pixel with **another seed**, so its paths are independent of the
//! compared renders' and its own path noise is not shared with them. The ΔE00 of a mode against
//! the reference therefore holds both path noise (less with more paths) and colour error (RGB's
//! and sampling's bias, hero sampling's wavelength noise): what a user sees at equal time.

use super::{scene::Scene, scene_white, timed, Image, ModeResult, Timing};
use crate::error::Result;
use specpoly_spectra::repr::Repr;

/// Renders per mode that measure its time per path.
pub const CALIBRATION_RUNS: usize = 3;

/// Mixed into the seed of the reference render, so its paths are independent of the others'.
const REFERENCE_SEED: u64 = 0x7265_6665_7265_6E63;

/// The result of [`equal_time`].
pub struct EqualTime {
    /// The time budget (seconds): the budget mode's time per path times the scene's `spp`.
    pub budget_seconds: f64,
    /// The modes, in the order asked, each with the paths per pixel it got.
    pub modes: Vec<ModeResult>,
    /// The reference image.
    pub reference: Image,
    /// Its paths per pixel.
    pub reference_spp: u32,
    /// Its render time (seconds).
    pub reference_seconds: f64,
}

fn timed_at(scene: &Scene, repr: Repr, spp: u32) -> Result<(Image, Timing)> {
    let mut s = scene.clone();
    s.render.spp = spp;
    timed(&s, repr)
}

/// Renders the reference, the budget mode `budget` at the scene's `spp`, and every mode of
/// `modes` at the paths per pixel that take the same time; `step` is called after each render.
pub fn equal_time(
    scene: &Scene,
    budget: Repr,
    modes: &[Repr],
    reference_spp: u32,
    step: &dyn Fn(),
) -> Result<EqualTime> {
    let mut rs = scene.clone();
    rs.render.seed ^= REFERENCE_SEED;
    let (reference, reference_time) = timed_at(&rs, Repr::Exact, reference_spp)?;
    step();
    let spp = scene.render.spp;
    let probe = (spp / 4).max(1);
    let per_path = |repr: Repr| -> Result<f64> {
        let mut best = f64::INFINITY;
        for _ in 0..CALIBRATION_RUNS {
            best = best.min(timed_at(scene, repr, probe)?.1.wall / probe as f64);
        }
        Ok(best)
    };
    let budget_seconds = per_path(budget)? * spp as f64;
    step();
    let white = scene_white(scene);
    let mut out = Vec::new();
    for &repr in modes {
        let n = if repr == budget {
            spp
        } else {
            ((budget_seconds / per_path(repr)?).round() as u32).clamp(1, 1 << 20)
        };
        let (image, timing) = timed_at(scene, repr, n)?;
        step();
        out.push(ModeResult::measured(
            repr,
            n,
            image,
            &[timing],
            &reference,
            white,
            scene.render.exposure,
        ));
    }
    Ok(EqualTime {
        budget_seconds,
        modes: out,
        reference,
        reference_spp,
        reference_seconds: reference_time.wall,
    })
}
