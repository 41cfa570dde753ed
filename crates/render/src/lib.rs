//! The spectral ray and path tracer: scene files, meshes, lights, integrators generic over the
//! colour representation, and the way from XYZ pixels to a display's image files and to ΔE00
//! comparisons.
//!
//! ```text
//! scene.toml ─resolve─▶ Scene (tabulated spectra) ─Compiled<T>─▶ XYZ image ─Display─▶ PNG/EXR
//! ```
//!
//! The modules are layered; each uses only modules of the layers below it (and its own):
//!
//! 1. **Leaves**: [`geometry`] (vectors, rays, shapes, the camera), [`upsample`] (sRGB to a
//!    reflectance), [`builtin`] (the built-in scenes' text), [`cpu_time`], [`error`].
//! 2. **Meshes and emitters**: [`mesh`] (triangles, their BVH, OBJ files), [`mesh_ply`] (PLY
//!    files, on [`mesh`]), [`mesh_gltf`] (glTF files, on [`mesh`]), [`lights`] (area lights,
//!    the environment, their sampling).
//! 3. **The scene file**: [`sections`] (the TOML sections as written, with the
//!    [`sections::Integrator`]) → [`scene_value`] (spectra and points resolved) →
//!    [`scene`] (the resolved [`scene::Scene`]) → [`budget`] (the work a scene may ask for) and
//!    [`scene_geometry`] (quads, mesh files, emitters) → [`scene_file`] (the whole file,
//!    parsed and resolved) → [`scene_gltf`] (a glTF file as a scene file).
//! 4. **The compiled scene**: `material` (a scene's materials in representation `T`) →
//!    `filter` (what shadow rays pass through) → [`compiled`] ([`compiled::Compiled`]: every
//!    spectrum converted once, and the queries the integrators share: nearest hit, shadow
//!    rays, light terms, emission).
//! 5. **Integrators**, on the compiled scene: [`tracer`] (Whitted), [`path`] (the path
//!    tracer), [`hero`] (hero-wavelength sampling: a scene compiled with per-path binding).
//! 6. **This root**: [`load`] a scene, [`render`] it (dispatching over the representation and
//!    the integrator), [`compare`] representations against the 1 nm reference; [`Image`],
//!    [`ModeResult`].
//! 7. **Image files and comparisons**, on the root's images: [`output`] (XYZ to display RGB),
//!    [`image_file`] (PNG and EXR files), [`compare_image`] (the comparison panels),
//!    [`equal_time`] (the path tracer's representations at equal time).
//!
//! `duplicates` pairs kept: the serde structs of the scene file's sections ([`sections`], one
//! per TOML table) and the documented fields of [`scene::Scene`] (one doc line each); the point-
//! and area-light weight queries of [`compiled`] (one per kind of light); the `#[from]` variants
//! of [`Error`] for the crates it calls (like `specpoly-led`'s).
#![forbid(unsafe_code)]

// leaves
pub mod builtin;
pub mod bvh_build;
pub mod cpu_time;
pub mod error;
pub mod geometry;
pub mod texture;
pub mod upsample;
// meshes and emitters
pub mod lights;
pub mod mesh;
pub mod mesh_gltf;
pub mod mesh_ply;
// the scene file and the resolved scene
pub mod budget;
pub mod scene;
pub mod scene_file;
pub mod scene_geometry;
pub mod scene_gltf;
pub mod scene_value;
pub mod sections;
// the compiled scene
pub mod compiled;
mod filter;
mod material;
// integrators
pub mod hero;
pub mod path;
pub mod tracer;
// image files and comparisons
pub mod compare_image;
pub mod equal_time;
pub mod image_file;
pub mod output;

use compiled::Compiled;
use rayon::prelude::*;
use scene::Scene;
use scene_file::SceneFile;
use sections::Integrator;
use specpoly_core::{delta_e2000, Lab, Shade, Xyz};
use specpoly_formats::stats::Stats;
use specpoly_spectra::repr::{self, Repr, Visitor};
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::time::Instant;

pub use error::{Error, Result};
pub use output::{to_rgb8, Output};

/// An image of XYZ values (white `Y = 100`), row-major.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Width.
    pub width: u32,
    /// Height.
    pub height: u32,
    /// Pixels, row-major from the top-left.
    pub xyz: Vec<Xyz>,
    /// Rays traced (camera, reflected, refracted and shadow rays).
    pub rays: u64,
}

/// Loads a scene: a built-in name (`example1`, `example2`, `interreflection`), a TOML file or
/// a glTF file (`.gltf`, `.glb`: [`scene_gltf`]).
pub fn load(spec: &str) -> Result<Scene> {
    let path = std::path::Path::new(spec);
    if scene_gltf::is_gltf(spec) {
        return scene_gltf::load(path, spec);
    }
    let looks_like_file = spec.ends_with(".toml") || spec.contains('/');
    if path.exists() && (looks_like_file || builtin::find(spec).is_none()) {
        let text = specpoly_formats::read::text(path)?;
        // file names in the scene are relative to the scene file's folder
        let base = path.parent().map(|p| {
            if p.as_os_str().is_empty() {
                std::path::Path::new(".")
            } else {
                p
            }
        });
        return SceneFile::parse(&text, spec)?.resolve_in(spec, base);
    }
    if let Some(b) = builtin::find(spec) {
        return SceneFile::parse(b.text, b.name)?.resolve(b.name);
    }
    if looks_like_file {
        return Err(Error::NoSuchSceneFile {
            name: spec.to_string(),
        });
    }
    Err(Error::UnknownScene {
        name: spec.to_string(),
        builtins: builtin::names(),
    })
}

/// Progress reporting: called with the number of rows done.
pub type Progress<'a> = &'a (dyn Fn(usize) + Sync);

struct RenderVisit<'a> {
    scene: &'a Scene,
    progress: Option<Progress<'a>>,
}

impl Visitor for RenderVisit<'_> {
    type Output = Result<Image>;
    fn visit<T: Shade>(self) -> Result<Image> {
        let c = Compiled::<T>::new(self.scene).map_err(Error::Convert)?;
        Ok(render_compiled(&c, self.progress))
    }
}

/// Renders a compiled scene in parallel over rows (rayon), with its integrator (Whitted
/// [`tracer`] or [`path`]). Deterministic: every pixel is
/// computed on its own, whichever thread runs it.
pub fn render_compiled<T: Shade>(c: &Compiled<T>, progress: Option<Progress<'_>>) -> Image {
    let (w, h) = (c.width(), c.height());
    let mut xyz = vec![Xyz::default(); (w * h) as usize];
    let done = AtomicUsize::new(0);
    let rays = AtomicU64::new(0);
    xyz.par_chunks_mut(w as usize)
        .enumerate()
        .for_each(|(y, row)| {
            let before = compiled::rays_traced();
            match c.integrator() {
                Integrator::Whitted => tracer::row(c, y as u32, row),
                Integrator::Path => path::row(c, y as u32, row),
            }
            rays.fetch_add(compiled::rays_traced() - before, Ordering::Relaxed);
            if let Some(p) = progress {
                p(done.fetch_add(1, Ordering::Relaxed) + 1);
            }
        });
    Image {
        width: w,
        height: h,
        xyz,
        rays: rays.into_inner(),
    }
}

/// Renders `scene` in representation `repr` (`rgb`, `paper`, `poly`, `sampled:N`, `exact`).
pub fn render(scene: &Scene, repr: Repr, progress: Option<Progress<'_>>) -> Result<Image> {
    if let Repr::Hero(4) = repr {
        return Ok(render_compiled(&hero::compile::<4>(scene)?, progress));
    }
    repr::dispatch(repr, RenderVisit { scene, progress })
}

/// The modes `render --compare` renders: rgb, paper, the default representation and
/// sampled:81, and with the path tracer hero-wavelength sampling (`hero:4`).
pub fn compare_modes(integrator: Integrator) -> Vec<Repr> {
    let mut m = vec![Repr::Rgb, Repr::Paper, Repr::DEFAULT, Repr::Sampled(81)];
    if integrator == Integrator::Path {
        m.push(Repr::Hero(4));
    }
    m
}

/// Camera paths per pixel: `spp` for the path tracer, `samples²` for Whitted.
pub fn paths_per_pixel(scene: &Scene) -> u32 {
    match scene.render.integrator {
        Integrator::Path => scene.render.spp,
        Integrator::Whitted => scene.render.samples * scene.render.samples,
    }
}

/// XYZ of the scene's white: the perfect reflector under its reference light
/// ([`Scene::reference_spd`]), `Y = 100`.
pub fn scene_white(scene: &Scene) -> Xyz {
    let spd = scene.reference_spd();
    let (_, w) = specpoly_core::exact_xyz(scene.observer, &spd.tabulated(), |_| 1.0);
    Xyz::new(w[0] as f32, w[1] as f32, w[2] as f32)
}

/// Writes 8-bit RGB as a PNG, whole or not at all. The PNG has no time stamp: the same pixels
/// give the same bytes.
pub fn write_png(path: &std::path::Path, width: u32, height: u32, rgb: &[u8]) -> Result<()> {
    Ok(specpoly_formats::atomic::write_with(path, |w| {
        let mut enc = png::Encoder::new(w, width, height);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut wr = enc.write_header().map_err(std::io::Error::other)?;
        wr.write_image_data(rgb).map_err(std::io::Error::other)?;
        wr.finish().map_err(std::io::Error::other)
    })?)
}

/// Per-pixel CIEDE2000 between two XYZ images (CIELAB relative to `white`, after `exposure`).
pub fn delta_e(a: &Image, b: &Image, white: Xyz, exposure: f32) -> Vec<f64> {
    a.xyz
        .iter()
        .zip(&b.xyz)
        .map(|(p, q)| {
            delta_e2000(
                Lab::from_xyz(p.scale(exposure), white),
                Lab::from_xyz(q.scale(exposure), white),
            )
        })
        .collect()
}

/// Full scale of the ΔE00 heat map.
pub const HEAT_MAX: f64 = 10.0;

/// A heat-map colour for `de` (black 0 → blue → red → yellow → white at [`HEAT_MAX`]).
pub fn heat(de: f64) -> [u8; 3] {
    const STOPS: [(f64, [f64; 3]); 5] = [
        (0.0, [0.0, 0.0, 0.0]),
        (0.1, [0.1, 0.1, 0.6]),
        (0.3, [0.8, 0.1, 0.2]),
        (0.6, [1.0, 0.8, 0.0]),
        (1.0, [1.0, 1.0, 1.0]),
    ];
    let x = (de / HEAT_MAX).clamp(0.0, 1.0);
    let mut c = STOPS[STOPS.len() - 1].1;
    for w in STOPS.windows(2) {
        let ((x0, c0), (x1, c1)) = (w[0], w[1]);
        if x <= x1 {
            let f = (x - x0) / (x1 - x0);
            c = [0, 1, 2].map(|k| c0[k] + (c1[k] - c0[k]) * f);
            break;
        }
    }
    c.map(|v| (v * 255.0 + 0.5) as u8)
}

/// One representation's render in a [`Comparison`] or an equal-time comparison
/// ([`equal_time`]).
pub struct ModeResult {
    /// The representation.
    pub repr: Repr,
    /// Paths (path tracer) or rays (Whitted) per pixel it was rendered with.
    pub spp: u32,
    /// Its image.
    pub image: Image,
    /// ΔE00 per pixel against the reference.
    pub delta_e: Vec<f64>,
    /// Statistics of `delta_e`.
    pub stats: Stats,
    /// Render time, seconds: the median of `rounds` (nearest rank: the lower middle one).
    pub seconds: f64,
    /// The render time of every round, seconds, in the order run.
    pub rounds: Vec<f64>,
    /// CPU time of the process (all threads) during the render, seconds: the median of
    /// `cpu_rounds`; `None` where the platform does not tell ([`cpu_time`]).
    pub cpu_seconds: Option<f64>,
    /// The CPU time of every round, seconds (empty where the platform does not tell).
    pub cpu_rounds: Vec<f64>,
}

/// The median (nearest rank: the lower middle one) of `v`; `None` when empty.
fn median(v: &[f64]) -> Option<f64> {
    let mut sorted = v.to_vec();
    sorted.sort_by(f64::total_cmp);
    (!sorted.is_empty()).then(|| specpoly_formats::stats::percentile(&sorted, 0.5))
}

/// One timed render: wall seconds, and the process's CPU seconds if known.
#[derive(Clone, Copy, Debug)]
pub struct Timing {
    /// Wall-clock seconds.
    pub wall: f64,
    /// CPU seconds of the process (user + system, all threads), where the platform tells.
    pub cpu: Option<f64>,
}

impl ModeResult {
    /// `image`, rendered in `repr` at `spp` per pixel with the timings `rounds`, measured
    /// against `reference` (CIELAB relative to `white`, after the scene's `exposure`).
    pub fn measured(
        repr: Repr,
        spp: u32,
        image: Image,
        rounds: &[Timing],
        reference: &Image,
        white: Xyz,
        exposure: f32,
    ) -> Self {
        let delta_e = delta_e(&image, reference, white, exposure);
        let wall: Vec<f64> = rounds.iter().map(|t| t.wall).collect();
        let cpu: Vec<f64> = rounds.iter().filter_map(|t| t.cpu).collect();
        Self {
            repr,
            spp,
            stats: Stats::of(&delta_e),
            delta_e,
            image,
            seconds: median(&wall).unwrap_or(0.0),
            rounds: wall,
            cpu_seconds: median(&cpu),
            cpu_rounds: cpu,
        }
    }
}

/// The result of [`compare`].
pub struct Comparison {
    /// Each mode, in the order asked.
    pub modes: Vec<ModeResult>,
    /// The reference image.
    pub reference: Image,
    /// The reference's render time, seconds.
    pub reference_seconds: f64,
}

/// Renders `scene` in `repr` and times it (wall clock and the process's CPU time).
pub fn timed(scene: &Scene, repr: Repr) -> Result<(Image, Timing)> {
    let c0 = cpu_time::process_seconds();
    let t0 = Instant::now();
    let img = render(scene, repr, None)?;
    let wall = t0.elapsed().as_secs_f64();
    let cpu = match (c0, cpu_time::process_seconds()) {
        (Some(a), Some(b)) => Some(b - a),
        _ => None,
    };
    Ok((img, Timing { wall, cpu }))
}

/// Renders the 1 nm reference and `modes` `rounds` times (≥ 1), the modes interleaved in each
/// round so that a shared machine's load weighs on every mode alike, and the ΔE00 of each
/// against the reference; each mode's time is the median of its rounds. `step` is called after
/// each of the `1 + rounds · modes.len()` renders (for a progress bar). Rendering is
/// deterministic, so every round gives the same image; the first is kept.
pub fn compare(scene: &Scene, modes: &[Repr], rounds: u32, step: &dyn Fn()) -> Result<Comparison> {
    let (reference, reference_time) = timed(scene, Repr::Exact)?;
    step();
    let white = scene_white(scene);
    let mut runs: Vec<(Option<Image>, Vec<Timing>)> =
        modes.iter().map(|_| (None, vec![])).collect();
    for _ in 0..rounds.max(1) {
        for (&repr, (image, times)) in modes.iter().zip(&mut runs) {
            let (img, timing) = timed(scene, repr)?;
            times.push(timing);
            image.get_or_insert(img);
            step();
        }
    }
    let spp = paths_per_pixel(scene);
    let out = modes
        .iter()
        .zip(runs)
        .filter_map(|(&repr, (image, times))| {
            let image = image?;
            Some(ModeResult::measured(
                repr,
                spp,
                image,
                &times,
                &reference,
                white,
                scene.render.exposure,
            ))
        })
        .collect();
    Ok(Comparison {
        modes: out,
        reference,
        reference_seconds: reference_time.wall,
    })
}
