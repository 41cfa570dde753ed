//! Accuracy of the tracer's modes on the built-in scenes, against the 1 nm reference (the same
//! tracer with 401 samples at 1 nm). Small images keep the test quick.

use specpoly_render as render;
use specpoly_spectra::repr::Repr;

fn scene(name: &str, w: u32, h: u32) -> render::scene::Scene {
    let mut s = render::load(name).unwrap();
    s.render.width = w;
    s.render.height = h;
    s.render.samples = 1;
    s
}

#[test]
fn poly_matches_the_reference_on_the_papers_examples() {
    for name in ["example1", "example2", "interreflection"] {
        let s = scene(name, 64, 48);
        let c = render::compare(&s, &[Repr::DEFAULT, Repr::Rgb], 1, &|| ()).unwrap();
        let poly = c.modes[0].stats;
        assert!(poly.mean <= 0.5, "{name}: poly mean ΔE00 {}", poly.mean);
        assert!(poly.max <= 2.0, "{name}: poly max ΔE00 {}", poly.max);
    }
}

#[test]
fn rgb_fails_on_the_interreflection() {
    let s = scene("interreflection", 64, 48);
    let c = render::compare(&s, &[Repr::DEFAULT, Repr::Rgb], 1, &|| ()).unwrap();
    let (poly, rgb) = (c.modes[0].stats, c.modes[1].stats);
    assert!(
        rgb.mean > 10.0 * poly.mean && rgb.p95 > 3.0 && rgb.max > 5.0,
        "rgb {rgb:?} vs poly {poly:?}"
    );
}

#[test]
fn rendering_is_deterministic() {
    let s = scene("example2", 48, 32);
    let a = render::render(&s, Repr::DEFAULT, None).unwrap();
    let b = render::render(&s, Repr::DEFAULT, None).unwrap();
    assert_eq!(a, b);
}
