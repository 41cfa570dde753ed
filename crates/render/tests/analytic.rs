//! One pixel of an analytic scene against a value derived by hand: a Lambertian sphere lit by one
//! point light, seen through the centre pixel, with no ambient light and a black background.
//!
//! The centre ray of a 65 × 65 image from (0, 0, −5) toward the origin hits the unit sphere at
//! p = (0, 0, −1) with normal N = (0, 0, −1). The light at (0, 4, −4) is in direction
//! L = (0, 4, −3)/5, so N·L = 3/5. With intensity I = 0.8 and the tracer's convention (a white
//! facing the light has Y = 100·I), the pixel is
//!
//! XYZ = I · (N·L) · 100 · Σ_λ R(λ) S(λ) x̄(λ) / Σ_λ S(λ) ȳ(λ)   (and likewise Y, Z),
//!
//! summed here at 1 nm over 380–780 nm from the data files themselves (linear interpolation,
//! end values held), independently of the library's own sums.

use crate::reference_1nm;

use reference_1nm::{column, interp};
use specpoly_render as render;
use specpoly_spectra::repr::Repr;

const SCENE: &str = r#"
[render]
width = 65
height = 65
samples = 1
observer = "1931"
[camera]
position = [0.0, 0.0, -5.0]
look_at = [0.0, 0.0, 0.0]
fov = 30
[[light]]
position = [0.0, 4.0, -4.0]
spectrum = "FL2"
intensity = 0.8
[materials.paint]
diffuse = "colorchecker#orange"
[[sphere]]
center = [0.0, 0.0, 0.0]
radius = 1.0
material = "paint"
"#;

#[test]
fn centre_pixel_matches_a_hand_derived_1nm_sum() {
    let refl = column("reflectances/colorchecker_babelcolor_average.csv", "orange");
    let light = column("illuminants/FL2.csv", "relative_power");
    let cmf: Vec<(Vec<f64>, Vec<f64>)> = ["x_bar", "y_bar", "z_bar"]
        .iter()
        .map(|n| column("cmf/cie1931_2deg_1nm.csv", n))
        .collect();
    let mut sum = [0.0f64; 3];
    let mut white_y = 0.0;
    for nm in 380..=780 {
        let nm = nm as f64;
        let s = interp(&light.0, &light.1, nm);
        let r = interp(&refl.0, &refl.1, nm);
        for k in 0..3 {
            sum[k] += r * s * interp(&cmf[k].0, &cmf[k].1, nm);
        }
        white_y += s * interp(&cmf[1].0, &cmf[1].1, nm);
    }
    let geometry = 0.8 * 0.6;
    let expected = sum.map(|v| geometry * 100.0 * v / white_y);

    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("one.toml");
    std::fs::write(&path, SCENE).unwrap();
    let scene = render::load(path.to_str().unwrap()).unwrap();
    for (mode, tol) in [(Repr::Exact, 2e-3), (Repr::DEFAULT, 0.02)] {
        let img = render::render(&scene, mode, None).unwrap();
        let p = img.xyz[(32 * 65 + 32) as usize].to_array();
        for k in 0..3 {
            let rel = (p[k] as f64 - expected[k]).abs() / expected[k];
            assert!(
                rel < tol,
                "{mode}: component {k}: {} vs hand-derived {} ({rel:.2e})",
                p[k],
                expected[k]
            );
        }
    }
    // the corner pixel misses the sphere: black background
    let img = render::render(&scene, Repr::Exact, None).unwrap();
    assert_eq!(img.xyz[0].to_array(), [0.0; 3]);
}
