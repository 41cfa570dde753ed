//! `specpoly render SCENE|FILE.toml [--mode M] [--display sRGB|DISPLAY.toml] [--size WxH]
//! [--gamut clip|desaturate] [--compare] -o OUT.png`
//!
//! Renders a built-in scene or a scene file with the spectral Whitted ray tracer and writes a PNG
//! encoded for the display. `--compare` renders `rgb`, `paper`, `poly`, `sampled:81` and the 1 nm reference,
//! writes `rgb | poly | reference | ΔE00 rgb | ΔE00 poly` side by side, and prints the ΔE00
//! statistics of each mode against the reference.

use crate::error::{CliError, Result};
use crate::render::image_file::{self as image_out, ExrSpace};
use crate::render::tracer::Integrator;
use crate::render::{self, builtin, Output};
use crate::repr::Repr;
use indicatif::{ProgressBar, ProgressStyle};
use specpoly_core::GamutMap;
use std::io::IsTerminal;
use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `specpoly render`.
#[derive(Debug, clap::Args)]
#[command(after_help = render_help())]
pub struct RenderArgs {
    /// A built-in scene (example1, example2, interreflection) or a scene file (.toml).
    #[arg(value_name = "SCENE|FILE.toml")]
    pub scene: String,
    /// Colour representation: rgb, paper, poly, poly:SxD, sampled:N, reference (= exact).
    #[arg(long, default_value = "poly")]
    pub mode: String,
    /// The display: sRGB, or a display TOML (primaries, luminances, gamma; see docs/scenes.md).
    #[arg(long, default_value = "sRGB")]
    pub display: String,
    /// Out-of-gamut colours: clip (per channel, as the paper) or desaturate (toward grey).
    #[arg(long, default_value = "clip")]
    pub gamut: String,
    /// Image size, overriding the scene's: WIDTHxHEIGHT.
    #[arg(long, value_name = "WxH")]
    pub size: Option<String>,
    /// Rays per pixel along each axis, overriding the scene's.
    #[arg(long, value_name = "N")]
    pub samples: Option<u32>,
    /// Render rgb, paper, poly, sampled:81 and the reference; write rgb, poly, reference and ΔE00 heat maps side by side.
    #[arg(long)]
    pub compare: bool,
    /// Light transport: whitted (the paper's model; default) or path (path tracing), overriding the scene's.
    #[arg(long, value_parser = clap::value_parser!(Integrator))]
    pub integrator: Option<Integrator>,
    /// Path tracer: paths per pixel, overriding the scene's.
    #[arg(long, value_name = "N")]
    pub spp: Option<u32>,
    /// PNG bits per channel: 8 or 16.
    #[arg(long, default_value_t = 8)]
    pub bits: u8,
    /// EXR contents: rgb (the display's linear RGB) or xyz.
    #[arg(long, default_value = "rgb")]
    pub exr_space: String,
    /// Print the render statistics as JSON on stdout.
    #[arg(long)]
    pub json: bool,
    /// Output image: .png (8 or 16 bits, with sRGB or ICC colour metadata) or .exr (linear).
    #[arg(short, long, value_name = "OUT.png|OUT.exr")]
    pub output: PathBuf,
}

fn render_help() -> String {
    let mut s = String::from("Built-in scenes:\n");
    for b in builtin::SCENES {
        s.push_str(&format!("  {:<16} {}\n", b.name, b.about));
    }
    s.push_str("Scene file format: docs/scenes.md");
    s
}

fn parse_size(s: &str) -> Result<(u32, u32)> {
    let bad = || CliError::usage(format!("--size `{s}`: expected WIDTHxHEIGHT, e.g. 512x512"));
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let (w, h): (u32, u32) = (w.parse().map_err(|_| bad())?, h.parse().map_err(|_| bad())?);
    if w == 0 || h == 0 || w > 16384 || h > 16384 {
        return Err(CliError::usage(format!(
            "--size `{s}`: each side must be 1..16384"
        )));
    }
    Ok((w, h))
}

fn parse_gamut(s: &str) -> Result<GamutMap> {
    match s.to_ascii_lowercase().as_str() {
        "clip" => Ok(GamutMap::Clip),
        "desaturate" => Ok(GamutMap::Desaturate),
        _ => Err(CliError::usage(format!(
            "--gamut `{s}`: use clip or desaturate"
        ))),
    }
}

/// A progress bar on a terminal, nothing otherwise.
fn progress_bar(rows: u64, label: &str) -> Option<ProgressBar> {
    if !std::io::stderr().is_terminal() {
        return None;
    }
    let pb = ProgressBar::new(rows);
    let style = ProgressStyle::with_template("{prefix:>10} [{bar:40}] {pos}/{len} rows {elapsed}")
        .unwrap_or_else(|_| ProgressStyle::default_bar())
        .progress_chars("=> ");
    pb.set_style(style);
    pb.set_prefix(label.to_string());
    Some(pb)
}

/// Runs `specpoly render`.
pub fn run(a: &RenderArgs) -> Result<()> {
    // validate every argument before the (possibly long) render
    let mode: Repr = a.mode.parse()?;
    let gamut = parse_gamut(&a.gamut)?;
    let size = a.size.as_deref().map(parse_size).transpose()?;
    if let Some(n) = a.samples {
        if n == 0 || n > 16 {
            return Err(CliError::usage(format!("--samples {n}: must be 1..16")));
        }
    }
    if let Some(n) = a.spp {
        if n == 0 || n > 1 << 20 {
            return Err(CliError::usage(format!(
                "--spp {n}: must be 1..{}",
                1 << 20
            )));
        }
    }
    let format = image_out::format_for(&a.output, a.bits)?;
    let space: ExrSpace = a.exr_space.parse()?;
    let display = render::display::load(&a.display)?;
    let tag = image_out::colour_tag(&a.display)?;
    let mut scene = render::load(&a.scene)?;
    if let Some((w, h)) = size {
        scene.render.width = w;
        scene.render.height = h;
    }
    if let Some(n) = a.samples {
        scene.render.samples = n;
    }
    if let Some(i) = a.integrator {
        scene.render.integrator = i;
    }
    if let Some(n) = a.spp {
        scene.render.spp = n;
    }
    let out = Output::new(&scene, display, gamut);
    let (w, h) = (scene.render.width, scene.render.height);

    if a.compare {
        return run_compare(a, &scene, &out);
    }

    let pb = progress_bar(h as u64, &mode.to_string());
    let tick = |n: usize| {
        if let Some(pb) = &pb {
            pb.set_position(n as u64);
        }
    };
    let t0 = Instant::now();
    let img = render::render(&scene, mode, Some(&tick))?;
    let secs = t0.elapsed().as_secs_f64();
    if let Some(pb) = pb {
        pb.finish_and_clear();
    }
    image_out::write(&a.output, &img, &out, format, &tag, space)?;
    let paths = render::paths_per_pixel(&scene);
    if a.json {
        let v = serde_json::json!({
            "scene": a.scene,
            "width": w,
            "height": h,
            "integrator": scene.render.integrator.to_string(),
            "mode": mode.to_string(),
            "paths_per_pixel": paths,
            "seconds": secs,
            "rays": img.rays,
            "rays_per_second": img.rays as f64 / secs.max(1e-9),
            "output": a.output.display().to_string(),
        });
        crate::io::stdout::print(&format!("{v:#}\n"))?;
    } else {
        println!(
            "{}: {w}x{h}, {paths} {} per pixel, {}, mode {mode}, {secs:.2} s → {}",
            a.scene,
            if scene.render.integrator == Integrator::Path {
                "paths"
            } else {
                "rays"
            },
            scene.render.integrator,
            a.output.display()
        );
    }
    eprintln!("wrote {}", a.output.display());
    Ok(())
}

fn run_compare(a: &RenderArgs, scene: &render::scene::Scene, out: &Output) -> Result<()> {
    let (w, h) = (scene.render.width, scene.render.height);
    let modes = [Repr::Rgb, Repr::Paper, Repr::DEFAULT, Repr::Sampled(81)];
    let pb = progress_bar(1 + modes.len() as u64, "compare");
    let t0 = Instant::now();
    let reference = render::render(scene, Repr::Exact, None)?;
    let t_ref = t0.elapsed().as_secs_f64();
    if let Some(pb) = &pb {
        pb.inc(1);
    }
    let white = render::scene_white(scene);
    let mut rows = Vec::new();
    for m in modes {
        let t = Instant::now();
        let img = render::render(scene, m, None)?;
        let secs = t.elapsed().as_secs_f64();
        let de = render::delta_e(&img, &reference, white, scene.render.exposure);
        rows.push((m, img, render::stats(&de), de, secs));
        if let Some(pb) = &pb {
            pb.inc(1);
        }
    }
    if let Some(pb) = pb {
        pb.finish_and_clear();
    }
    let panel = |img: &render::Image| (w, h, render::to_rgb8(img, out));
    let heat = |de: &[f64]| (w, h, de.iter().flat_map(|d| render::heat(*d)).collect());
    let (rgb_row, poly_row) = (&rows[0], &rows[2]);
    let panels = [
        panel(&rgb_row.1),
        panel(&poly_row.1),
        panel(&reference),
        heat(&rgb_row.3),
        heat(&poly_row.3),
    ];
    let (cw, ch, px) = render::side_by_side(&panels, 4);
    render::write_png(&a.output, cw, ch, &px)?;
    if a.json {
        let modes: Vec<_> = rows
            .iter()
            .map(|(m, img, st, _, secs)| {
                serde_json::json!({
                    "mode": m.to_string(),
                    "seconds": secs,
                    "rays": img.rays,
                    "delta_e00": { "mean": st.mean, "p95": st.p95, "max": st.max },
                })
            })
            .collect();
        let v = serde_json::json!({
            "scene": a.scene,
            "width": w,
            "height": h,
            "integrator": scene.render.integrator.to_string(),
            "paths_per_pixel": render::paths_per_pixel(scene),
            "reference_seconds": t_ref,
            "modes": modes,
            "output": a.output.display().to_string(),
        });
        crate::io::stdout::print(&format!("{v:#}\n"))?;
        eprintln!("wrote {}", a.output.display());
        return Ok(());
    }
    println!(
        "{}: {w}x{h}, {} rays/pixel; ΔE00 (CIEDE2000) against the 1 nm reference ({t_ref:.2} s)",
        a.scene,
        scene.render.samples * scene.render.samples
    );
    println!(
        "{:<11} {:>8} {:>8} {:>8} {:>9}",
        "mode", "mean", "95th", "max", "time (s)"
    );
    for (m, _, s, _, secs) in &rows {
        println!(
            "{:<11} {:>8.3} {:>8.3} {:>8.3} {:>9.2}",
            m.to_string(),
            s.mean,
            s.p95,
            s.max,
            secs
        );
    }
    println!(
        "wrote {} (rgb | poly | reference | ΔE00 rgb | ΔE00 poly; heat map 0 → {} ΔE00: black, blue, red, yellow, white)",
        a.output.display(),
        render::HEAT_MAX
    );
    Ok(())
}
