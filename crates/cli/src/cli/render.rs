//! `specpoly render SCENE|FILE.toml [--mode M] [--display sRGB|DISPLAY.toml] [--size WxH]
//! [--gamut clip|desaturate] [--compare] -o OUT.png`
//!
//! Renders a built-in scene or a scene file with the spectral Whitted ray tracer and writes a PNG
//! encoded for the display (`-o -`: to stdout, the summary line then on stderr). `--compare` renders `rgb`, `paper`, `poly`, `sampled:81` (and `hero:4` with the
//! path tracer; `--rounds N` times, interleaved) and the 1 nm reference,
//! writes `rgb | poly | reference | ΔE00 rgb | ΔE00 poly` side by side, and prints the ΔE00
//! statistics of each mode against the reference. `--equal-time` is [`render_equal_time`]; both
//! comparisons are written and printed by [`crate::cli::render_report`].

use crate::cli::args::{self, Gamut};
use crate::cli::render_equal_time;
use crate::cli::render_report::{report, Report, Target};
use crate::error::{CliError, Result};
use specpoly_calibrate::progress;
use specpoly_core::Observer;
use specpoly_display::spec::DisplaySpec;
use specpoly_formats::stdout::{print, print_json};
use specpoly_plot::size::Size;
use specpoly_render::image_file::{self as image_out, ExrSpace};
use specpoly_render::sections::Integrator;
use specpoly_render::{self as render, builtin, Output};
use specpoly_spectra::repr::Repr;
use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `specpoly render`.
#[derive(Debug, clap::Args)]
#[command(after_help = render_help())]
pub struct RenderArgs {
    /// A built-in scene (example1, example2, interreflection) or a scene file (.toml).
    #[arg(value_name = "SCENE|FILE.toml")]
    pub scene: String,
    /// Colour representation: rgb, paper, poly, poly:SxD, sampled:N, hero:N, reference (= exact).
    #[arg(long, default_value = "poly")]
    pub mode: Repr,
    /// The display: sRGB, or a display TOML (primaries, luminances, gamma; see docs/scenes.md).
    #[arg(long, default_value = "sRGB")]
    pub display: String,
    /// Out-of-gamut colours: clip (per channel, as the paper) or desaturate (toward grey).
    #[arg(long, value_enum, ignore_case = true, default_value_t = Gamut::Clip)]
    pub gamut: Gamut,
    /// Image size, overriding the scene's: WIDTHxHEIGHT.
    #[arg(long, value_name = "WxH")]
    pub size: Option<Size>,
    /// Observer, overriding the scene's: 1931, 1964, 2015-2, 2015-10, cie2006:age=A,field=F
    /// or FILE.csv of three sensitivities.
    #[arg(long, value_name = "NAME|FILE", value_parser = args::observer)]
    pub observer: Option<Observer>,
    /// Rays per pixel along each axis (1–16), overriding the scene's.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=16))]
    pub samples: Option<u32>,
    /// Render rgb, paper, poly, sampled:81 and the reference; write rgb, poly, reference and ΔE00 heat maps side by side.
    #[arg(long)]
    pub compare: bool,
    /// With --compare and the path tracer: every mode at the time poly takes at --spp, against a --reference-spp 1 nm render.
    #[arg(long, requires = "compare")]
    pub equal_time: bool,
    /// With --compare: render the modes N times, interleaved, and report each one's median time.
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=100))]
    pub rounds: u32,
    /// Paths per pixel of the --equal-time reference (1 nm, another seed).
    #[arg(long, value_name = "N", default_value_t = 4096, value_parser = clap::value_parser!(u32).range(1..=1 << 20))]
    pub reference_spp: u32,
    /// Light transport: whitted (the paper's model; default) or path (path tracing), overriding the scene's.
    #[arg(long, value_parser = clap::value_parser!(Integrator))]
    pub integrator: Option<Integrator>,
    /// Path tracer: paths per pixel (1–2^20), overriding the scene's.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1 << 20))]
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
    /// Output image: .png (8 or 16 bits, with sRGB or ICC colour metadata) or .exr (linear);
    /// `-` writes the PNG to stdout.
    #[arg(short, long, value_name = "OUT.png|OUT.exr|-")]
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

/// Runs `specpoly render`.
pub fn run(a: &RenderArgs) -> Result<()> {
    let mode = a.mode;
    // `-o -`: the PNG is stdout's whole content, so nothing else may go there
    let to_stdout = a.output == std::path::Path::new("-");
    if to_stdout && (a.json || a.compare) {
        return Err(CliError::usage(format!(
            "-o - writes the image to stdout, where {} prints too: name an image file",
            if a.json { "--json" } else { "--compare" }
        )));
    }
    if to_stdout {
        // before rendering, not after
        specpoly_formats::stdout::check_open()?;
    }
    let format = image_out::format_for(&a.output, a.bits)?;
    let space: ExrSpace = a.exr_space.parse()?;
    let spec = DisplaySpec::open(&a.display)?;
    let tag = image_out::colour_tag(&spec)?;
    let mut scene = render::load(&a.scene)?;
    if let Some(size) = a.size {
        scene.render.width = size.width;
        scene.render.height = size.height;
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
    if let Some(o) = a.observer {
        scene.observer = o;
    }
    let out =
        Output::new(&scene, spec.display(), a.gamut.into()).with_model(spec.interaction_model());
    let (w, h) = (scene.render.width, scene.render.height);

    if a.equal_time {
        let to = Target {
            scene: &a.scene,
            output: &a.output,
            json: a.json,
        };
        return render_equal_time::run(&to, a.reference_spp, &scene, &out);
    }
    if a.compare {
        return run_compare(a, &scene, &out);
    }

    let pb = progress::bar(h as u64, &mode.to_string(), "rows");
    let tick = |n: usize| pb.set_position(n as u64);
    let t0 = Instant::now();
    let img = render::render(&scene, mode, Some(&tick))?;
    let secs = t0.elapsed().as_secs_f64();
    pb.finish_and_clear();
    specpoly_spectra::plausible::image(&a.scene, &img.xyz)?;
    image_out::write(&a.output, &img, &out, format, &tag, space)?;
    let paths = render::paths_per_pixel(&scene);
    if a.json {
        print_json(&serde_json::json!({
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
        }))?;
    } else {
        let line = format!(
            "{}: {w}x{h}, {paths} {} per pixel, {}, mode {mode}, {secs:.2} s → {}\n",
            a.scene,
            if scene.render.integrator == Integrator::Path {
                "paths"
            } else {
                "rays"
            },
            scene.render.integrator,
            if to_stdout {
                "stdout".into()
            } else {
                a.output.display().to_string()
            }
        );
        if to_stdout {
            eprint!("{}", specpoly_formats::escape::control(&line));
        } else {
            print(&line)?;
        }
    }
    crate::cli::wrote::wrote(&a.output, "");
    Ok(())
}

fn run_compare(a: &RenderArgs, scene: &render::scene::Scene, out: &Output) -> Result<()> {
    let (w, h) = (scene.render.width, scene.render.height);
    let modes = render::compare_modes(scene.render.integrator);
    let pb = progress::bar(
        1 + (a.rounds as usize * modes.len()) as u64,
        "compare",
        "renders",
    );
    let c = render::compare(scene, &modes, a.rounds, &|| pb.inc(1))?;
    pb.finish_and_clear();
    specpoly_spectra::plausible::image(&a.scene, &c.reference.xyz)?;
    for m in &c.modes {
        specpoly_spectra::plausible::image(&format!("{} ({})", a.scene, m.repr), &m.image.xyz)?;
    }
    let paths = render::paths_per_pixel(scene);
    let unit = match scene.render.integrator {
        Integrator::Path => "paths",
        Integrator::Whitted => "rays",
    };
    let to = Target {
        scene: &a.scene,
        output: &a.output,
        json: a.json,
    };
    report(
        &to,
        out,
        Report {
            header: format!(
                "{}: {w}x{h}, {paths} {unit}/pixel, {}, {} round{} of the modes interleaved \
                 (median time); ΔE00 (CIEDE2000) against the 1 nm reference ({:.2} s)",
                a.scene,
                scene.render.integrator,
                a.rounds,
                if a.rounds == 1 { "" } else { "s" },
                c.reference_seconds
            ),
            modes: &c.modes,
            // rgb and the default representation side by side
            shown: c
                .modes
                .iter()
                .filter(|m| m.repr == Repr::Rgb || m.repr == Repr::DEFAULT)
                .collect(),
            reference: &c.reference,
            json: serde_json::json!({
                "scene": a.scene,
                "width": w,
                "height": h,
                "integrator": scene.render.integrator.to_string(),
                "paths_per_pixel": paths,
                "rounds": a.rounds,
                "reference_seconds": c.reference_seconds,
            }),
        },
    )
}
