//! `specpoly render SCENE --compare --equal-time [--reference-spp N]`: the path tracer's
//! representations at equal time against a high-sample 1 nm reference
//! ([`crate::render::equal_time`]). Prints each mode's paths per pixel, time and ΔE00
//! (mean / 95th / max; `--json` for JSON) and writes the images (top row: each mode and the
//! reference) above their ΔE00 heat maps.

use super::render::{mode_json, RenderArgs};
use crate::error::{CliError, Result};
use crate::io::progress;
use crate::io::stdout::{print, print_json};
use crate::render::equal_time::equal_time;
use crate::render::scene::Scene;
use crate::render::tracer::Integrator;
use crate::render::{self, Output};
use crate::repr::Repr;
use std::fmt::Write as _;

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
pub fn run(a: &RenderArgs, scene: &Scene, out: &Output) -> Result<()> {
    if scene.render.integrator != Integrator::Path {
        return Err(CliError::usage(
            "--equal-time compares the path tracer: add --integrator path",
        ));
    }
    let (w, h) = (scene.render.width, scene.render.height);
    let modes = modes();
    let pb = progress::bar(2 + modes.len() as u64, "equal time", "renders");
    let c = equal_time(scene, Repr::DEFAULT, &modes, a.reference_spp, &|| pb.inc(1))?;
    pb.finish_and_clear();
    use crate::render::compare_image::{compose, Panel};
    let panel = |label: String, rgb: Vec<u8>| Panel {
        label,
        width: w,
        height: h,
        rgb,
    };
    // one labelled row: each mode, the reference, then each mode's ΔE00 map, and the colour bar
    let mut panels: Vec<Panel> = c
        .modes
        .iter()
        .map(|m| panel(m.repr.to_string(), render::to_rgb8(&m.image, out)))
        .collect();
    panels.push(panel(
        "reference".into(),
        render::to_rgb8(&c.reference, out),
    ));
    panels.extend(c.modes.iter().map(|m| {
        panel(
            format!("ΔE00 {} (mean {:.2})", m.repr, m.stats.mean),
            m.delta_e.iter().flat_map(|d| render::heat(*d)).collect(),
        )
    }));
    let (cw, ch, px) = compose(&panels)?;
    render::write_png(&a.output, cw, ch, &px)?;
    if a.json {
        let modes: Vec<_> = c
            .modes
            .iter()
            .map(|m| {
                let mut v = mode_json(m.repr, m.seconds, m.image.rays, &m.stats);
                v["paths_per_pixel"] = m.spp.into();
                v
            })
            .collect();
        print_json(&serde_json::json!({
            "scene": a.scene,
            "width": w,
            "height": h,
            "integrator": "path",
            "budget_mode": Repr::DEFAULT.to_string(),
            "budget_seconds": c.budget_seconds,
            "reference_paths_per_pixel": c.reference_spp,
            "reference_seconds": c.reference_seconds,
            "modes": modes,
            "output": a.output.display().to_string(),
        }))?;
        eprintln!("wrote {}", a.output.display());
        return Ok(());
    }
    let mut o = String::new();
    let _ = writeln!(
        o,
        "{}: {w}x{h}, path tracer at equal time ({} at {} paths/pixel: {:.2} s); ΔE00 against the 1 nm reference at {} paths/pixel ({:.1} s)",
        a.scene,
        Repr::DEFAULT,
        scene.render.spp,
        c.budget_seconds,
        c.reference_spp,
        c.reference_seconds
    );
    let _ = writeln!(
        o,
        "{:<11} {:>6} {:>9} {:>8} {:>8} {:>8}",
        "mode", "paths", "time (s)", "mean", "95th", "max"
    );
    for m in &c.modes {
        let _ = writeln!(
            o,
            "{:<11} {:>6} {:>9.2} {:>8.3} {:>8.3} {:>8.3}",
            m.repr.to_string(),
            m.spp,
            m.seconds,
            m.stats.mean,
            m.stats.p95,
            m.stats.max
        );
    }
    let names: Vec<String> = c.modes.iter().map(|m| m.repr.to_string()).collect();
    let _ = writeln!(
        o,
        "wrote {} (top: {} | reference; below: their ΔE00, heat map 0 → {} ΔE00)",
        a.output.display(),
        names.join(" | "),
        render::HEAT_MAX
    );
    print(&o)
}
