//! `specpoly render SCENE --compare --equal-time [--reference-spp N]`: the path tracer's
//! representations at equal time against a high-sample 1 nm reference
//! ([`specpoly_render::equal_time`]). Prints each mode's paths per pixel, time and ΔE00
//! (mean / 95th / max; `--json` for JSON) and writes the images (top row: each mode and the
//! reference) above their ΔE00 heat maps.

use crate::cli::render_report::{report, Report, Target};
use crate::error::{CliError, Result};
use specpoly_calibrate::progress;
use specpoly_render::equal_time::equal_time;
use specpoly_render::scene::Scene;
use specpoly_render::sections::Integrator;
use specpoly_render::Output;
use specpoly_spectra::repr::Repr;

/// The modes compared, the budget mode (`poly`) among them.
pub fn modes() -> [Repr; 5] {
    [
        Repr::Rgb,
        Repr::DEFAULT,
        Repr::Sampled(16),
        Repr::Sampled(81),
        Repr::Hero(4),
    ]
}

/// Runs the equal-time comparison for `render --compare --equal-time`.
pub fn run(a: &Target<'_>, reference_spp: u32, scene: &Scene, out: &Output) -> Result<()> {
    if scene.render.integrator != Integrator::Path {
        return Err(CliError::usage(
            "--equal-time compares the path tracer: add --integrator path",
        ));
    }
    let (w, h) = (scene.render.width, scene.render.height);
    let modes = modes();
    let pb = progress::bar(2 + modes.len() as u64, "equal time", "renders");
    let c = equal_time(scene, Repr::DEFAULT, &modes, reference_spp, &|| pb.inc(1))?;
    pb.finish_and_clear();
    report(
        a,
        out,
        Report {
            header: format!(
                "{}: {w}x{h}, path tracer at equal time ({} at {} paths/pixel: {:.2} s); ΔE00 \
                 against the 1 nm reference at {} paths/pixel ({:.1} s)",
                a.scene,
                Repr::DEFAULT,
                scene.render.spp,
                c.budget_seconds,
                c.reference_spp,
                c.reference_seconds
            ),
            modes: &c.modes,
            shown: c.modes.iter().collect(),
            reference: &c.reference,
            json: serde_json::json!({
                "scene": a.scene,
                "width": w,
                "height": h,
                "integrator": "path",
                "budget_mode": Repr::DEFAULT.to_string(),
                "budget_seconds": c.budget_seconds,
                "reference_paths_per_pixel": c.reference_spp,
                "reference_seconds": c.reference_seconds,
            }),
        },
    )
}
