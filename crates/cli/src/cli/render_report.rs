//! The report of `specpoly render --compare` (and `--equal-time`): the comparison image (the
//! shown modes, the reference and the modes' ΔE00 heat maps over the colour bar) and the table
//! of modes (`--json`: as JSON). Shared by [`super::render`] and [`super::render_equal_time`],
//! and depending on neither.

use crate::error::Result;
use specpoly_formats::stdout::{print, print_json};
use specpoly_render::{self as render, Output};
use std::fmt::Write as _;
use std::path::Path;

/// Where and how a comparison is reported: the scene as named on the command line, the output
/// image, and `--json`.
pub struct Target<'a> {
    /// The scene argument.
    pub scene: &'a str,
    /// The output image.
    pub output: &'a Path,
    /// Print JSON instead of the table.
    pub json: bool,
}

/// A comparison to print and write: its header line, its modes (the `shown` ones as panels,
/// beside the reference), and the JSON fields that go beside `modes` and `output`.
pub struct Report<'a> {
    pub header: String,
    pub modes: &'a [render::ModeResult],
    pub shown: Vec<&'a render::ModeResult>,
    pub reference: &'a render::Image,
    pub json: serde_json::Value,
}

/// Writes a comparison's image (the shown modes, the reference and the modes' ΔE00 maps,
/// labelled, over the colour bar) and prints its table of modes (`--json`: as JSON).
pub fn report(a: &Target<'_>, out: &Output, r: Report<'_>) -> Result<()> {
    use render::compare_image::{comparison_panels, compose};
    let (cw, ch, px) = compose(&comparison_panels(&r.shown, r.reference, out))?;
    render::write_png(a.output, cw, ch, &px)?;
    let names: Vec<String> = r.shown.iter().map(|m| m.repr.to_string()).collect();
    let written = crate::cli::wrote::line(
        a.output,
        &format!(
            " ({} | reference | their ΔE00, labelled; heat map 0 → {} ΔE00: black, blue, red, \
             yellow, white, its colour bar below)",
            names.join(" | "),
            render::HEAT_MAX
        ),
    );
    if a.json {
        let mut j = r.json;
        j["modes"] = r.modes.iter().map(mode_json).collect();
        j["output"] = a.output.display().to_string().into();
        print_json(&j)?;
        eprintln!("{written}");
        return Ok(());
    }
    let mut o = String::new();
    let _ = writeln!(o, "{}", r.header);
    let _ = writeln!(
        o,
        "{:<11} {:>7} {:>9} {:>8} {:>8} {:>8} {:>8}",
        "mode", "per px", "time (s)", "cpu (s)", "mean", "95th", "max"
    );
    for m in r.modes {
        let cpu = m.cpu_seconds.map_or("-".into(), |c| format!("{c:.2}"));
        let _ = writeln!(
            o,
            "{:<11} {:>7} {:>9.3} {:>8} {:>8.3} {:>8.3} {:>8.3}",
            m.repr.to_string(),
            m.spp,
            m.seconds,
            cpu,
            m.stats.mean,
            m.stats.p95,
            m.stats.max
        );
    }
    print(&o)?;
    eprintln!("{written}");
    Ok(())
}

/// One mode of a comparison as JSON: its name, paths per pixel, wall and CPU time (the median
/// of its rounds, and every round; no CPU time where the platform does not tell), rays traced and ΔE00 against the 1 nm reference (mean, 95th percentile,
/// maximum).
fn mode_json(m: &render::ModeResult) -> serde_json::Value {
    serde_json::json!({
        "mode": m.repr.to_string(),
        "paths_per_pixel": m.spp,
        "seconds": m.seconds,
        "seconds_per_round": m.rounds,
        "cpu_seconds": m.cpu_seconds,
        "cpu_seconds_per_round": m.cpu_rounds,
        "rays": m.image.rays,
        "delta_e00": { "mean": m.stats.mean, "p95": m.stats.p95, "max": m.stats.max },
    })
}
