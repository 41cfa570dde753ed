//! Equal-time comparison of the path tracer's colour representations against a high-sample
//! 1 nm reference (`specpoly render SCENE --compare --equal-time`).
//!
//! The time budget is the time of one render in the budget mode (default `poly`) at the
//! scene's `spp`. Each other mode is first rendered at that `spp` to measure its time per path,
//! then rendered again at `spp · budget / time` paths per pixel (rounded, at least 1), so every
//! mode gets about the same time. The reference is the 1 nm mode (401 samples) at
//! `reference_spp` paths per pixel with **another seed**, so its paths are independent of the
//! compared renders' and its own path noise is not shared with them. The ΔE00 of a mode against
//! the reference therefore holds both path noise (less with more paths) and colour error (RGB's
//! and sampling's bias, hero sampling's wavelength noise): what a user sees at equal time.

use super::{delta_e, render, scene::Scene, scene_white, Image};
use crate::error::Result;
use crate::repr::Repr;
use crate::stats::Stats;
use std::time::Instant;

/// Mixed into the seed of the reference render, so its paths are independent of the others'.
const REFERENCE_SEED: u64 = 0x7265_6665_7265_6E63;

/// One mode at the equal time.
pub struct TimedMode {
    /// The representation.
    pub repr: Repr,
    /// Paths per pixel it got.
    pub spp: u32,
    /// Its render time at `spp` (seconds).
    pub seconds: f64,
    /// Its image.
    pub image: Image,
    /// ΔE00 per pixel against the reference.
    pub delta_e: Vec<f64>,
    /// Statistics of `delta_e`.
    pub stats: Stats,
}

/// The result of [`equal_time`].
pub struct EqualTime {
    /// The time budget (seconds): the budget mode at the scene's `spp`.
    pub budget_seconds: f64,
    /// The modes, in the order asked.
    pub modes: Vec<TimedMode>,
    /// The reference image.
    pub reference: Image,
    /// Its paths per pixel.
    pub reference_spp: u32,
    /// Its render time (seconds).
    pub reference_seconds: f64,
}

fn timed(scene: &Scene, repr: Repr, spp: u32) -> Result<(Image, f64)> {
    let mut s = scene.clone();
    s.render.spp = spp;
    let t0 = Instant::now();
    let img = render(&s, repr, None)?;
    Ok((img, t0.elapsed().as_secs_f64()))
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
    let (reference, reference_seconds) = timed(&rs, Repr::Exact, reference_spp)?;
    step();
    let spp = scene.render.spp;
    let (budget_img, budget_seconds) = timed(scene, budget, spp)?;
    step();
    let white = scene_white(scene);
    let mut out = Vec::new();
    for &repr in modes {
        let (image, spp, seconds) = if repr == budget {
            (budget_img.clone(), spp, budget_seconds)
        } else {
            let (img, t) = timed(scene, repr, spp)?;
            let n = ((spp as f64 * budget_seconds / t.max(1e-9)).round() as u32).clamp(1, 1 << 20);
            if n == spp {
                (img, spp, t)
            } else {
                let (img, t) = timed(scene, repr, n)?;
                (img, n, t)
            }
        };
        step();
        let de = delta_e(&image, &reference, white, scene.render.exposure);
        out.push(TimedMode {
            repr,
            spp,
            seconds,
            stats: Stats::of(&de),
            delta_e: de,
            image,
        });
    }
    Ok(EqualTime {
        budget_seconds,
        modes: out,
        reference,
        reference_spp,
        reference_seconds,
    })
}
