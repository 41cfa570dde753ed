//! The path tracer and the area and environment lights against closed forms, the 1 nm
//! reference mode, and determinism; meshes and relative paths in scene files.
//!
//! Closed forms (one named tolerance each):
//! - a Lambertian plane of reflectance `ρ` under a uniform environment of radiance `L` reflects
//!   `ρ·L` (the furnace case; the cosine-sampled estimate has no variance);
//! - a Lambertian plane under a sphere light of radiance `L`, radius `R`, centre at distance `d`
//!   straight above reflects `ρ·L·(R/d)²` (irradiance `π L (R/d)²`, Lambert's sphere).
//!
//! Colours are checked against the 1 nm sum of the same spectra (`specpoly_core::exact_xyz`).

use crate::common::scenes;

use scenes::{
    camera_above, furnace, ground, material, path_render, scene, sphere_light, white_y, MC_TOL,
};
use specpoly_render as render;
use specpoly_spectra::repr::Repr;

#[test]
fn furnace_plane_under_the_environment_reflects_rho_l() {
    let s = scene(&furnace((6, 4), 4, 4, "E", ("grey", "0.5")));
    for repr in [Repr::DEFAULT, Repr::Exact, Repr::Rgb] {
        let img = render::render(&s, repr, None).unwrap();
        // every pixel sees the plane (camera looks down at it)
        for p in &img.xyz {
            let rel = (p.y as f64 - 0.5 * white_y()).abs() / (0.5 * white_y());
            assert!(rel < 1e-4, "{repr}: Y {} vs {}", p.y, 0.5 * white_y());
        }
    }
}

/// A grey (0.8) plane under a sphere light of illuminant E at radiance 1, radius 1, 3 above it.
fn sphere_light_scene() -> String {
    [
        path_render(1, 1, 4096, 3),
        "light_samples = 16\n".into(),
        camera_above(),
        "fov = 0.2\n".into(),
        material("grey", "0.8"),
        sphere_light("E", 1.0, [0.0, 3.0, 0.0], 1.0),
        ground("grey"),
    ]
    .concat()
}
#[test]
fn sphere_light_over_a_plane_matches_lambert() {
    let exact = 0.8 * white_y() / 9.0;
    for integrator in ["path", "whitted"] {
        let text = sphere_light_scene().replace(
            "integrator = \"path\"",
            &format!("integrator = \"{integrator}\""),
        );
        let s = scene(&text);
        let img = render::render(&s, Repr::DEFAULT, None).unwrap();
        let y = img.xyz[0].y as f64;
        assert!(
            (y - exact).abs() < MC_TOL * exact,
            "{integrator}: Y {y} vs {exact}"
        );
    }
}

#[test]
fn path_tracing_is_deterministic_across_threads() {
    let mut s = render::load("cornell").unwrap();
    s.render.width = 12;
    s.render.height = 12;
    s.render.spp = 2;
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let two = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    let a = one.install(|| render::render(&s, Repr::DEFAULT, None).unwrap());
    let b = two.install(|| render::render(&s, Repr::DEFAULT, None).unwrap());
    assert_eq!(a, b);
    s.render.seed = 7;
    let c = two.install(|| render::render(&s, Repr::DEFAULT, None).unwrap());
    assert_ne!(a, c, "another seed must give other paths");
}

/// Every mode traces the same paths, so against the 1 nm reference the default polynomial
/// throughput (reduced at every bounce) is far closer than RGB on the Cornell box.
#[test]
fn cornell_poly_is_close_to_the_1nm_reference() {
    let mut s = render::load("cornell").unwrap();
    s.render.width = 16;
    s.render.height = 16;
    s.render.spp = 2;
    let c = render::compare(&s, &[Repr::DEFAULT, Repr::Rgb], 1, &|| ()).unwrap();
    let (poly, rgb) = (c.modes[0].stats, c.modes[1].stats);
    assert!(poly.mean < 0.05, "poly mean ΔE00 {}", poly.mean);
    assert!(
        poly.mean * 5.0 < rgb.mean,
        "poly {} vs rgb {}",
        poly.mean,
        rgb.mean
    );
    // the image is not black: the light reaches the walls
    let y: f32 = c.reference.xyz.iter().map(|p| p.y).sum::<f32>() / c.reference.xyz.len() as f32;
    assert!(y > 5.0, "mean Y {y}");
}

#[test]
fn scene_files_resolve_paths_against_their_folder() {
    let dir = tempfile::tempdir().unwrap();
    let sub = dir.path().join("assets");
    std::fs::create_dir(&sub).unwrap();
    std::fs::write(
        sub.join("paint.csv"),
        "wavelength_nm,paint\n380,0.2\n780,0.6\n",
    )
    .unwrap();
    std::fs::write(
        sub.join("tri.mtl"),
        "newmtl left\nKd 1 0 0\nnewmtl right\nKd 0 1 0\n",
    )
    .unwrap();
    std::fs::write(
        sub.join("tri.obj"),
        "mtllib tri.mtl\nv -1 -1 3\nv 0 -1 3\nv 0 1 3\nv -1 1 3\nv 1 -1 3\nv 1 1 3\n\
         usemtl left\nf 1 2 3 4\nusemtl right\nf 2 5 6 3\n",
    )
    .unwrap();
    let scene_text = r#"
[camera]
position = [0.0, 0.0, 0.0]
look_at = [0.0, 0.0, 1.0]
[[light]]
position = [0.0, 0.0, 0.0]
spectrum = "D65"
[materials.paint]
diffuse = "assets/paint.csv"
[materials.left]
diffuse = 0.5
[materials.green_paint]
diffuse = "assets/paint.csv#paint"
[[mesh]]
file = "assets/tri.obj"
material = "paint"
materials = { right = "green_paint" }
"#;
    let path = dir.path().join("scene.toml");
    std::fs::write(&path, scene_text).unwrap();
    // loaded from another working directory, the names resolve beside the scene file
    let s = render::load(path.to_str().unwrap()).unwrap();
    assert_eq!(s.triangles.len(), 4);
    let names: Vec<&str> = s.materials.iter().map(|m| m.name.as_str()).collect();
    let idx = |n: &str| names.iter().position(|m| *m == n).unwrap();
    let ray = |x: f32| render::geometry::Ray {
        origin: render::geometry::V3::new(x, 0.1, 0.0),
        dir: render::geometry::V3::new(0.0, 0.0, 1.0),
    };
    // `usemtl left` takes the scene material of the same name, `right` the mapped one
    assert_eq!(
        s.triangles.intersect(&ray(-0.5), 1e9).unwrap().2,
        render::mesh::Owner::Material(idx("left"))
    );
    assert_eq!(
        s.triangles.intersect(&ray(0.5), 1e9).unwrap().2,
        render::mesh::Owner::Material(idx("green_paint"))
    );
    let paint = s.materials[idx("paint")].diffuse.as_ref().unwrap();
    assert!((paint.tabulated().at(580.0) - 0.4).abs() < 1e-6);

    // a missing mesh names the resolved path
    std::fs::write(&path, scene_text.replace("tri.obj", "nope.obj")).unwrap();
    let e = render::load(path.to_str().unwrap())
        .unwrap_err()
        .to_string();
    assert!(e.contains("nope.obj") && e.contains("assets"), "{e}");

    // a PLY mesh (ASCII, a unit square at z = 2 as one quad face, scaled and moved by the
    // scene) resolves beside the scene file too
    std::fs::write(
        sub.join("square.ply"),
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
         property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n\
         0 0 2\n1 0 2\n1 1 2\n0 1 2\n4 0 1 2 3\n",
    )
    .unwrap();
    let ply_scene = "[camera]\nposition = [0.0, 0.0, 0.0]\nlook_at = [0.0, 0.0, 1.0]\n\
                     [materials.paint]\ndiffuse = \"assets/paint.csv\"\n\
                     [[mesh]]\nfile = \"assets/square.ply\"\nmaterial = \"paint\"\nscale = 2.0\n\
                     translate = [-1.0, -1.0, 1.0]\n";
    std::fs::write(&path, ply_scene).unwrap();
    let s = render::load(path.to_str().unwrap()).unwrap();
    assert_eq!(s.triangles.len(), 2);
    // scaled to 2 × 2 at z = 2·2 + 1 = 5, centred on the axis
    let (t, _, owner) = s.triangles.intersect(&ray(0.5), 1e9).unwrap();
    assert!((t - 5.0).abs() < 1e-5, "{t}");
    assert_eq!(owner, render::mesh::Owner::Material(0));
    assert!(s.triangles.intersect(&ray(1.5), 1e9).is_none());
}
