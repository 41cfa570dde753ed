//! Soft shadows of a rectangle light against the closed-form form factor, in umbra, penumbra
//! and full light, for both integrators.
//!
//! A square light of side 1 and radiance `L` faces down at height `h = 1`, centred above the
//! origin of a Lambertian ground of reflectance `ρ`. An opaque black half-plane at height 1/2
//! covers `x ≥ e`: seen from the origin it hides the part `x ≥ 2e` of the light. The origin then
//! sees the strip `x ∈ [−1/2, c]`, `c = clamp(2e, −1/2, 1/2)`, and reflects
//! `Y = 100 · ρ · L · F` with `F` the point-to-rectangle form factor. `F` is summed from the
//! classic corner form factor of a parallel rectangle `a × b` at height `h` with the point under
//! a corner (Howell, "A catalog of radiation heat transfer configuration factors", B-13;
//! `X = a/h`, `Y = b/h`):
//!
//! `F_c = 1/(2π) · [X/√(1+X²) · atan(Y/√(1+X²)) + Y/√(1+Y²) · atan(X/√(1+Y²))]`,
//!
//! `F = 2·F_c(1/2, 1/2) + 2·sign(c)·F_c(|c|, 1/2)` (zero when `c = −1/2`).
//!
//! The path tracer samples the light once per path (uniform in area), so it is checked within
//! [`MC_TOL`] of the unshadowed value; the Whitted tracer's deterministic `n × n` grid resolves
//! the shadow edge to one column of samples, so it is checked within [`GRID_TOL`].

use crate::common::scenes;

use scenes::{camera, ground, material, path_render, scene, white_y, MC_TOL};
use specpoly_render as render;
use specpoly_spectra::repr::Repr;
use std::f64::consts::PI;

/// The Whitted tracer's grid of 16 × 16 samples of the light: the shadow edge cuts at most one
/// column of 16 samples, 1/16 of the unshadowed value.
const GRID_TOL: f64 = 1.0 / 16.0;

/// Reflectance of the ground.
const RHO: f64 = 0.8;
/// Radiance of the light.
const RADIANCE: f64 = 2.0;

/// The corner form factor `F_c` of a parallel `a × b` rectangle at height 1 (module docs).
fn corner(a: f64, b: f64) -> f64 {
    let (x, y) = (a, b);
    let (sx, sy) = ((1.0 + x * x).sqrt(), (1.0 + y * y).sqrt());
    (x / sx * (y / sx).atan() + y / sy * (x / sy).atan()) / (2.0 * PI)
}

/// The form factor from the origin to the strip `x ∈ [−1/2, c]` of the light.
fn strip(c: f64) -> f64 {
    let c = c.clamp(-0.5, 0.5);
    2.0 * corner(0.5, 0.5) + 2.0 * c.signum() * corner(c.abs(), 0.5)
}

/// The scene with the blocker's edge at `x = e`, for `integrator`.
fn blocked(e: f64, integrator: &str) -> String {
    [
        path_render(1, 1, 16384, 0).replace("\"path\"", &format!("\"{integrator}\"")),
        "light_samples = 16\n".into(),
        // from the −x side, so camera rays pass beside the blocker and the light
        camera([-4.0, 2.0, 0.0], [0.0; 3]),
        "fov = 0.02\n".into(),
        material("grey", &format!("{RHO:?}")),
        material("black", "0.0"),
        format!(
            "[[area_light]]\nspectrum = \"E\"\nradiance = {RADIANCE:?}\n\
             corner = [-0.5, 1.0, -0.5]\nu = [1.0, 0.0, 0.0]\nv = [0.0, 0.0, 1.0]\n"
        ),
        format!(
            "[[quad]]\nvertices = [[{e:?}, 0.5, -3.0], [3.0, 0.5, -3.0], [3.0, 0.5, 3.0], \
             [{e:?}, 0.5, 3.0]]\nmaterial = \"black\"\n"
        ),
        ground("grey"),
    ]
    .concat()
}

#[test]
fn rectangle_light_shadows_match_the_form_factor() {
    let full = RHO * RADIANCE * strip(0.5) * white_y();
    // umbra, penumbra (a fifth, half, four fifths of the light) and full light
    for e in [-0.3, -0.15, 0.0, 0.15, 0.3] {
        let exact = RHO * RADIANCE * strip(2.0 * e) * white_y();
        for (integrator, tol) in [("path", MC_TOL), ("whitted", GRID_TOL)] {
            let s = scene(&blocked(e, integrator));
            let img = render::render(&s, Repr::DEFAULT, None).unwrap();
            let y = img.xyz[0].y as f64;
            assert!(
                (y - exact).abs() <= tol * full,
                "{integrator}, edge at x = {e}: Y {y} vs {exact} (unshadowed {full})"
            );
        }
    }
    // the closed form itself: the whole light from under its centre is 4 corners, and a
    // half-plane through the point hides half of it
    assert!((strip(0.5) - 4.0 * corner(0.5, 0.5)).abs() < 1e-12);
    assert!((strip(0.0) - 2.0 * corner(0.5, 0.5)).abs() < 1e-12);
    assert_eq!(strip(-0.5), 0.0);
}
