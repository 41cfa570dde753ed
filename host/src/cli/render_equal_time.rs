//! `specpoly render SCENE --compare --equal-time [--reference-spp N]`: the path tracer's
//! representations at equal time against a high-sample 1 nm reference
//! ([`crate::render::equal_time`]). Prints each mode's paths per pixel, time and ΔE00
//! (mean / 95th / max; `--json` for JSON) and writes the images (top row: each mode and the
//! reference) above their ΔE00 heat maps.

use super::render::RenderArgs;
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

/// Rows of panels stacked, each row's panels side by side (`gap` black pixels between).
fn grid(rows: &[Vec<(u32, u32, Vec<u8>)>], gap: u32) -> (u32, u32, Vec<u8>) {
    let rows: Vec<_> = rows.iter().map(|r| render::side_by_side(r, gap)).collect();
    let w = rows.iter().map(|r| r.0).max().unwrap_or(0);
    let h = rows.iter().map(|r| r.1).sum::<u32>() + gap * (rows.len() as u32).saturating_sub(1);
    let mut out = vec![0u8; (w * h * 3) as usize];
    let mut y0 = 0u32;
    for (rw, rh, px) in &rows {
        for y in 0..*rh {
            let src = &px[(y * rw * 3) as usize..((y + 1) * rw * 3) as usize];
            let dst = (((y0 + y) * w) * 3) as usize;
            out[dst..dst + src.len()].copy_from_slice(src);
        }
        y0 += rh + gap;
    }
    (w, h, out)
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
    let panel = |img: &render::Image| (w, h, render::to_rgb8(img, out));
    let heat = |de: &[f64]| (w, h, de.iter().flat_map(|d| render::heat(*d)).collect());
    let mut top: Vec<_> = c.modes.iter().map(|m| panel(&m.image)).collect();
    top.push(panel(&c.reference));
    let bottom: Vec<_> = c.modes.iter().map(|m| heat(&m.delta_e)).collect();
    let (cw, ch, px) = grid(&[top, bottom], 4);
    render::write_png(&a.output, cw, ch, &px)?;
    if a.json {
        let modes: Vec<_> = c
            .modes
            .iter()
            .map(|m| {
                serde_json::json!({
                    "mode": m.repr.to_string(),
                    "paths_per_pixel": m.spp,
                    "seconds": m.seconds,
                    "rays": m.image.rays,
                    "delta_e00": { "mean": m.stats.mean, "p95": m.stats.p95, "max": m.stats.max },
                })
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
