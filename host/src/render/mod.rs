//! The spectral ray tracer: scene files ([`scene`]), geometry ([`geometry`]), the Whitted tracer
//! generic over the colour representation ([`tracer`]), built-in scenes ([`builtin`]), and the
//! way from XYZ pixels to a display's PNG ([`to_rgb8`]) and to ΔE00 comparisons ([`compare`]).
//!
//! ```text
//! scene.toml ─resolve─▶ Scene (tabulated spectra) ─Compiled<T>─▶ XYZ image ─Display─▶ PNG
//! ```

pub mod builtin;
pub mod display;
pub mod geometry;
pub mod image_file;
pub mod lights;
pub mod mesh;
pub mod path;
pub mod scene;
pub mod scene_geometry;
pub mod tracer;
pub mod upsample;

use crate::error::{CliError, Result};
use crate::repr::{self, Repr, Visitor};
use rayon::prelude::*;
use scene::{Scene, SceneFile};
use specpoly_core::{bradford, delta_e2000, quantize8, Display, GamutMap, Lab, Mat3, Shade, Xyz};
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use tracer::Compiled;

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

/// Loads a scene: a built-in name (`example1`, `example2`, `interreflection`) or a TOML file.
/// Returns the scene and the name used in messages.
pub fn load(spec: &str) -> Result<Scene> {
    let path = std::path::Path::new(spec);
    let looks_like_file = spec.ends_with(".toml") || spec.contains('/');
    if path.exists() && (looks_like_file || builtin::find(spec).is_none()) {
        let text = std::fs::read_to_string(path).map_err(|e| CliError::io(path, e))?;
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
        return SceneFile::parse(b.toml, b.name)?.resolve(b.name);
    }
    if looks_like_file {
        return Err(CliError::usage(format!("{spec}: no such scene file")));
    }
    Err(CliError::usage(format!(
        "unknown scene `{spec}`: not a file, and not a built-in ({})",
        builtin::names()
    )))
}

/// Progress reporting: called with the number of rows done.
pub type Progress<'a> = &'a (dyn Fn(usize) + Sync);

struct RenderVisit<'a> {
    scene: &'a Scene,
    progress: Option<Progress<'a>>,
}

impl Visitor for RenderVisit<'_> {
    type Output = Result<Image>;
    fn visit<T: Shade>(self, layout: T::Layout) -> Result<Image> {
        let c = Compiled::<T>::new(self.scene, layout)
            .map_err(|e| CliError::data(format!("converting the scene's spectra: {e}")))?;
        Ok(render_compiled(&c, self.progress))
    }
}

/// Renders a compiled scene in parallel over rows (rayon). Deterministic: every pixel is
/// computed on its own, whichever thread runs it.
pub fn render_compiled<T: Shade>(c: &Compiled<T>, progress: Option<Progress<'_>>) -> Image {
    let (w, h) = (c.width(), c.height());
    let mut xyz = vec![Xyz::default(); (w * h) as usize];
    let done = AtomicUsize::new(0);
    let rays = AtomicU64::new(0);
    xyz.par_chunks_mut(w as usize)
        .enumerate()
        .for_each(|(y, row)| {
            let before = tracer::rays_traced();
            c.row(y as u32, row);
            rays.fetch_add(tracer::rays_traced() - before, Ordering::Relaxed);
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
    repr::dispatch(repr, RenderVisit { scene, progress })
}

/// Camera paths per pixel: `spp` for the path tracer, `samples²` for Whitted.
pub fn paths_per_pixel(scene: &Scene) -> u32 {
    match scene.render.integrator {
        tracer::Integrator::Path => scene.render.spp,
        tracer::Integrator::Whitted => scene.render.samples * scene.render.samples,
    }
}

/// XYZ of the scene's white: the perfect reflector under its reference light
/// ([`Scene::reference_spd`]), `Y = 100`.
pub fn scene_white(scene: &Scene) -> Xyz {
    let spd = scene.reference_spd();
    let (_, w) = specpoly_core::exact_xyz(scene.observer, &spd.tabulated(), |_| 1.0);
    Xyz::new(w[0] as f32, w[1] as f32, w[2] as f32)
}

/// How XYZ pixels become display values.
#[derive(Clone, Debug)]
pub struct Output {
    /// The display.
    pub display: Display,
    /// Gamut mapping.
    pub gamut: GamutMap,
    /// XYZ multiplier before display.
    pub exposure: f32,
    /// Chromatic adaptation applied before display (Bradford, scene white → display white).
    pub adapt: Mat3,
}

impl Output {
    /// The output for `scene` on `display`: its exposure, and its white adapted to the display's
    /// white when the scene asks for white balance.
    pub fn new(scene: &Scene, display: Display, gamut: GamutMap) -> Self {
        let adapt = if scene.render.white_balance {
            let dw = display.white();
            let dw = dw.scale(100.0 / dw.y);
            bradford(scene_white(scene), dw)
        } else {
            Mat3::IDENTITY
        };
        Self {
            display,
            gamut,
            exposure: scene.render.exposure,
            adapt,
        }
    }

    /// One pixel's 8-bit device values.
    pub fn encode(&self, xyz: Xyz) -> [u8; 3] {
        let a = Xyz::from_array(self.adapt.apply(xyz.scale(self.exposure).to_array()));
        let e = self.display.encode_relative(a, self.gamut);
        e.device.map(quantize8)
    }
}

/// The image as 8-bit RGB, row-major (in parallel: the transfer curve's powers cost about as
/// much as tracing a simple scene).
pub fn to_rgb8(img: &Image, out: &Output) -> Vec<u8> {
    let mut rgb = vec![0u8; img.xyz.len() * 3];
    rgb.par_chunks_mut(3)
        .zip(img.xyz.par_iter())
        .for_each(|(px, xyz)| px.copy_from_slice(&out.encode(*xyz)));
    rgb
}

/// Writes 8-bit RGB as a PNG, whole or not at all. The PNG has no time stamp: the same pixels
/// give the same bytes.
pub fn write_png(path: &std::path::Path, width: u32, height: u32, rgb: &[u8]) -> Result<()> {
    crate::io::atomic::write_with(path, |w| {
        let mut enc = png::Encoder::new(w, width, height);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut wr = enc.write_header().map_err(std::io::Error::other)?;
        wr.write_image_data(rgb).map_err(std::io::Error::other)?;
        wr.finish().map_err(std::io::Error::other)
    })
}

/// ΔE00 statistics of one image against a reference.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stats {
    /// Mean.
    pub mean: f64,
    /// 95th percentile.
    pub p95: f64,
    /// Maximum.
    pub max: f64,
}

/// Per-pixel CIEDE2000 between two XYZ images (CIELAB relative to `white`, after `exposure`).
pub fn delta_e(a: &Image, b: &Image, white: Xyz, exposure: f32) -> Vec<f64> {
    a.xyz
        .iter()
        .zip(&b.xyz)
        .map(|(p, q)| {
            delta_e2000(
                Lab::from(p.scale(exposure), white),
                Lab::from(q.scale(exposure), white),
            )
        })
        .collect()
}

/// Mean, 95th percentile (nearest rank) and maximum.
pub fn stats(de: &[f64]) -> Stats {
    if de.is_empty() {
        return Stats {
            mean: 0.0,
            p95: 0.0,
            max: 0.0,
        };
    }
    let mut s = de.to_vec();
    s.sort_by(f64::total_cmp);
    let rank = ((0.95 * s.len() as f64).ceil() as usize).clamp(1, s.len());
    Stats {
        mean: s.iter().sum::<f64>() / s.len() as f64,
        p95: s[rank - 1],
        max: s[s.len() - 1],
    }
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

/// Images side by side (all the same height), separated by `gap` black columns.
pub fn side_by_side(panels: &[(u32, u32, Vec<u8>)], gap: u32) -> (u32, u32, Vec<u8>) {
    let h = panels.iter().map(|p| p.1).max().unwrap_or(0);
    let w: u32 =
        panels.iter().map(|p| p.0).sum::<u32>() + gap * (panels.len() as u32).saturating_sub(1);
    let mut out = vec![0u8; (w * h * 3) as usize];
    let mut x0 = 0u32;
    for (pw, ph, px) in panels {
        for y in 0..*ph {
            let src = &px[(y * pw * 3) as usize..((y + 1) * pw * 3) as usize];
            let dst = ((y * w + x0) * 3) as usize;
            out[dst..dst + src.len()].copy_from_slice(src);
        }
        x0 += pw + gap;
    }
    (w, h, out)
}

/// The result of [`compare`].
pub struct Comparison {
    /// `(mode, its image, ΔE00 per pixel against the reference, statistics)`.
    pub modes: Vec<(Repr, Image, Vec<f64>, Stats)>,
    /// The reference image.
    pub reference: Image,
}

/// Renders `modes` and the 1 nm reference, and the ΔE00 of each against the reference.
pub fn compare(scene: &Scene, modes: &[Repr]) -> Result<Comparison> {
    let reference = render(scene, Repr::Exact, None)?;
    let white = scene_white(scene);
    let mut out = Vec::new();
    for &m in modes {
        let img = render(scene, m, None)?;
        let de = delta_e(&img, &reference, white, scene.render.exposure);
        let s = stats(&de);
        out.push((m, img, de, s));
    }
    Ok(Comparison {
        modes: out,
        reference,
    })
}
