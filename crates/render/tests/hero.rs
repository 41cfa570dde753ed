//! Hero-wavelength sampling (`--mode hero:4`) in the path tracer, and emissive meshes, against
//! independent references:
//! - hero sampling is unbiased: a coloured Lambertian plane under a uniform environment of a
//!   spiky light (FL11) converges to the 1 nm sum of the same spectra
//!   (`specpoly_core::exact_xyz`), within [`MC_TOL`];
//! - hero sampling traces the same paths as the other modes (its wavelengths have their own
//!   random stream): on a grey scene (no colour error in any mode) its luminance equals the 1 nm
//!   mode's pixel for pixel within [`MC_TOL`] of the mean;
//! - an emissive mesh seen by the camera has its radiance (`Y = 100 · radiance`), and a
//!   triangulated sphere light lights a plane as Lambert's sphere, `ρ·L·(R/d)²`, within the
//!   tessellation's error plus [`MC_TOL`].

use crate::common::scenes;

use scenes::{
    camera_above, furnace, ground, material, path_render, scene, sphere_obj, white_y, MC_TOL,
};
use specpoly_core::Observer;
use specpoly_render as render;
use specpoly_spectra::repr::Repr;

#[test]
fn hero_sampling_converges_to_the_1nm_sum() {
    let s = scene(&furnace(
        (4, 4),
        4096,
        1,
        "FL11",
        ("red", "\"colorchecker#red\""),
    ));
    let fl11 = specpoly_core::Illuminant::FL11.tabulated();
    let red = specpoly_spectra::spectrum_names::resolve("colorchecker#red")
        .unwrap()
        .remove(0);
    let (exact, _) =
        specpoly_core::exact_xyz(Observer::Cie1931, &fl11, |nm| red.tabulated().at(nm));
    let img = render::render(&s, Repr::Hero(4), None).unwrap();
    let n = img.xyz.len() as f64;
    let mean: Vec<f64> = (0..3)
        .map(|k| img.xyz.iter().map(|p| p.to_array()[k] as f64).sum::<f64>() / n)
        .collect();
    for k in 0..3 {
        assert!(
            (mean[k] - exact[k]).abs() < MC_TOL * exact[k],
            "channel {k}: {} vs {}",
            mean[k],
            exact[k]
        );
    }
    // a single path is noisy in colour (the wavelengths are random), unlike poly
    let mut one = s.clone();
    one.render.spp = 1;
    let img = render::render(&one, Repr::Hero(4), None).unwrap();
    let spread = img.xyz.iter().map(|p| p.x).fold(f32::MIN, f32::max)
        - img.xyz.iter().map(|p| p.x).fold(f32::MAX, f32::min);
    assert!(spread > 0.05 * exact[0] as f32, "X spread {spread}");
}

#[test]
fn hero_sampling_traces_the_same_paths() {
    // grey walls under a flat-spectrum light: every mode has the same colour, only paths vary
    let cornell = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../scenes/cornell.toml"
    ))
    .unwrap();
    let grey = cornell
        .replace("\"cornell#white\"", "0.7")
        .replace("\"cornell#red\"", "0.5")
        .replace("\"cornell#green\"", "0.3")
        .replace("\"cornell_light\"", "\"E\"");
    let mut g = scene(&grey);
    g.render.width = 12;
    g.render.height = 12;
    g.render.spp = 4;
    let exact = render::render(&g, Repr::Exact, None).unwrap();
    let hero = render::render(&g, Repr::Hero(4), None).unwrap();
    assert_eq!(exact.rays, hero.rays, "the same rays");
    let mean = |i: &render::Image| i.xyz.iter().map(|p| p.y as f64).sum::<f64>() / 144.0;
    let (a, b) = (mean(&exact), mean(&hero));
    // 576 paths' wavelength noise on a grey image: a few per cent
    assert!((a - b).abs() < 5.0 * MC_TOL * a, "mean Y {b} vs {a}");
}

#[test]
fn emissive_sphere_mesh_lights_like_the_analytic_sphere() {
    let dir = tempfile::tempdir().unwrap();
    let n = 96;
    std::fs::write(
        dir.path().join("ball.obj"),
        sphere_obj(n, [0.0, 3.0, 0.0], 1.0),
    )
    .unwrap();
    let text = [
        path_render(1, 1, 65536, 1),
        camera_above(),
        "fov = 0.2\n".into(),
        material("grey", "0.8"),
        "[[area_light]]\nspectrum = \"E\"\nradiance = 1.0\nmesh = \"ball.obj\"\n".into(),
        ground("grey"),
    ]
    .concat();
    let path = dir.path().join("s.toml");
    std::fs::write(&path, &text).unwrap();
    let s = render::load(path.to_str().unwrap()).unwrap();
    let img = render::render(&s, Repr::DEFAULT, None).unwrap();
    let y = img.xyz[0].y as f64;
    // Lambert's sphere: irradiance π L (R/d)², reflected ρ L (R/d)²; the inscribed polyhedron
    // subtends less: its silhouette's radius is at least R·cos(π/n) (the tessellation's error)
    let exact = 0.8 * white_y() / 9.0;
    let tess = 1.0 - (std::f64::consts::PI / n as f64).cos().powi(2);
    assert!(
        y <= exact * (1.0 + MC_TOL) && y >= exact * (1.0 - tess - MC_TOL),
        "Y {y} vs {exact} (tessellation {tess})"
    );

    // seen by the camera, it has its radiance
    let seen = text
        .replace("position = [0.0, 2.0, -4.0]", "position = [0.0, 3.0, -4.0]")
        .replace("look_at = [0.0, 0.0, 0.0]", "look_at = [0.0, 3.0, 0.0]")
        .replace("radiance = 1.0", "radiance = 2.5")
        .replace("spp = 65536", "spp = 4");
    std::fs::write(&path, seen).unwrap();
    let s = render::load(path.to_str().unwrap()).unwrap();
    let img = render::render(&s, Repr::DEFAULT, None).unwrap();
    let y = img.xyz[0].y as f64;
    assert!((y - 250.0).abs() < 1e-3 * 250.0, "Y {y}");

    // a mesh light with a rectangle's keys too is an error, naming the light
    std::fs::write(
        &path,
        text.replace("mesh = \"ball.obj\"", "mesh = \"ball.obj\"\nradius = 1.0"),
    )
    .unwrap();
    let e = render::load(path.to_str().unwrap())
        .unwrap_err()
        .to_string();
    assert!(e.contains("area_light 1"), "{e}");
}
