//! Scene set-ups shared by the render tests and the render bench: TOML fragments of the scenes
//! the closed-form cases use (a Lambertian ground plane seen from above by the path tracer, a
//! uniform environment, a sphere light), a latitude–longitude sphere as OBJ text, and the 1 nm
//! `Y` of a white reflector under illuminant E. Include it with
//! `#[path = "common/scenes.rs"] mod scenes;` (the bench: `"../tests/common/scenes.rs"`).
#![allow(dead_code)]

use specpoly_core::Observer;
use specpoly_render::scene::Scene;
use specpoly_render::scene_file::SceneFile;

/// Relative tolerance against a closed form for Monte Carlo estimates at the sample counts the
/// render tests use.
pub const MC_TOL: f64 = 0.01;

/// A scene from its TOML text (names resolve against the working directory).
pub fn scene(text: &str) -> Scene {
    SceneFile::parse(text, "test.toml")
        .unwrap()
        .resolve("test.toml")
        .unwrap()
}

/// `[render]` for the path tracer: `width × height` pixels, `spp` paths a pixel, `max_depth`
/// bounces.
pub fn path_render(width: u32, height: u32, spp: u32, max_depth: u32) -> String {
    format!(
        "[render]\nwidth = {width}\nheight = {height}\nintegrator = \"path\"\nspp = {spp}\n\
         max_depth = {max_depth}\n"
    )
}

/// `[camera]` at `position` looking at `look_at`.
pub fn camera(position: [f64; 3], look_at: [f64; 3]) -> String {
    format!("[camera]\nposition = {position:?}\nlook_at = {look_at:?}\n")
}

/// The camera of the closed-form cases: at (0, 2, −4), looking down at the origin.
pub fn camera_above() -> String {
    camera([0.0, 2.0, -4.0], [0.0; 3])
}

/// A uniform environment of `spectrum` at `radiance`.
pub fn environment(spectrum: &str, radiance: f64) -> String {
    format!("[environment]\nspectrum = \"{spectrum}\"\nradiance = {radiance:?}\n")
}

/// `[materials.NAME]` with `diffuse = DIFFUSE` (`DIFFUSE` as TOML: a number, or a quoted
/// spectrum name).
pub fn material(name: &str, diffuse: &str) -> String {
    format!("[materials.{name}]\ndiffuse = {diffuse}\n")
}

/// A sphere light of `spectrum` at `radiance`, centre `center`, radius `radius`.
pub fn sphere_light(spectrum: &str, radiance: f64, center: [f64; 3], radius: f64) -> String {
    format!(
        "[[area_light]]\nspectrum = \"{spectrum}\"\nradiance = {radiance:?}\ncenter = {center:?}\n\
         radius = {radius:?}\n"
    )
}

/// The ground: a plane through the origin facing up (+y), of `material`.
pub fn ground(material: &str) -> String {
    format!(
        "[[plane]]\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 1.0, 0.0]\nmaterial = \"{material}\"\n"
    )
}

/// The furnace: the ground of material `name` (`diffuse` as in [`material`]) under a uniform
/// environment of `spectrum` at radiance 1, seen from above by the path tracer.
pub fn furnace(
    (width, height): (u32, u32),
    spp: u32,
    max_depth: u32,
    spectrum: &str,
    (name, diffuse): (&str, &str),
) -> String {
    [
        path_render(width, height, spp, max_depth),
        camera_above(),
        environment(spectrum, 1.0),
        material(name, diffuse),
        ground(name),
    ]
    .concat()
}

/// A latitude–longitude sphere of `n × 2n` quads (two triangles each) around `c` of radius `r`,
/// as OBJ text.
pub fn sphere_obj(n: usize, c: [f32; 3], r: f32) -> String {
    use std::fmt::Write;
    let mut obj = String::new();
    for i in 0..=n {
        for j in 0..=2 * n {
            let th = std::f32::consts::PI * i as f32 / n as f32;
            let ph = std::f32::consts::PI * j as f32 / n as f32;
            let v = [
                c[0] + r * th.sin() * ph.cos(),
                c[1] + r * th.cos(),
                c[2] + r * th.sin() * ph.sin(),
            ];
            writeln!(obj, "v {} {} {}", v[0], v[1], v[2]).unwrap();
        }
    }
    let idx = |i: usize, j: usize| i * (2 * n + 1) + j + 1;
    for i in 0..n {
        for j in 0..2 * n {
            let (a, b, c, d) = (idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1));
            writeln!(obj, "f {a} {b} {c}\nf {a} {c} {d}").unwrap();
        }
    }
    obj
}

/// `Y` of a white reflector (reflectance 1) under illuminant E at radiance 1, by the 1 nm sum
/// (`specpoly_core::exact_xyz`): 100.
pub fn white_y() -> f64 {
    let e = specpoly_core::Illuminant::E.tabulated();
    specpoly_core::exact_xyz(Observer::Cie1931, &e, |_| 1.0).1[1]
}
