//! The reflectance checks of `xyz` (crates/spectra/src/plausible.rs) in `fit`, `plot` and a scene's
//! materials (`render`): percent data, negative values, an illuminant given as a reflectance,
//! overflow — each refused with one line naming the fix where the data was given, never a
//! result with inf or NaN. Independent check: the hint's fix (`--scale 0.01`, `scale = 0.01`)
//! gives the same output as the same data written in 0–1.

use crate::common::cli;

use std::path::Path;

use cli::{run as specpoly, Run};

fn fails(r: &Run, needle: &str) {
    assert_eq!(r.code, 1, "stderr: {}", r.stderr);
    assert_eq!(r.stderr.lines().count(), 1, "{}", r.stderr);
    assert!(r.stderr.contains(needle), "`{needle}` not in: {}", r.stderr);
    let out = r.stdout.to_lowercase();
    assert!(!out.contains("inf") && !out.contains("nan"), "{}", r.stdout);
}

fn csv(dir: &Path, name: &str, v: f64) -> String {
    let mut t = format!("wavelength_nm,{name}\n");
    for nm in (380..=780).step_by(10) {
        // a smooth spectrum, so fits and plots have something to do
        let x = (nm as f64 - 380.0) / 400.0;
        t += &format!("{nm},{}\n", v * (0.3 + 0.5 * x));
    }
    let p = dir.join(format!("{name}.csv"));
    std::fs::write(&p, t).unwrap();
    p.display().to_string()
}

#[test]
fn fit_and_plot_refuse_what_is_not_a_reflectance() {
    let dir = tempfile::tempdir().unwrap();
    let percent = csv(dir.path(), "percent", 100.0);
    let unit = csv(dir.path(), "unit", 1.0);
    let negative = csv(dir.path(), "neg", -1.0);
    let huge = csv(dir.path(), "huge", 3e38);
    let svg = dir.path().join("p.svg").display().to_string();
    fails(&specpoly(&["fit", &percent]), "--scale 0.01");
    fails(&specpoly(&["fit", &negative]), "negative");
    fails(&specpoly(&["fit", "D65"]), "illuminant");
    fails(&specpoly(&["fit", &huge]), "above 1.5");
    fails(&specpoly(&["plot", &percent, "-o", &svg]), "--scale 0.01");
    fails(&specpoly(&["plot", "D65", "-o", &svg]), "--scale");
    assert!(!Path::new(&svg).exists());
    // the hint's fix gives what the 0–1 data gives
    let a = specpoly(&["fit", &percent, "--scale", "0.01", "--json"]);
    let b = specpoly(&["fit", &unit, "--json"]);
    assert_eq!(a.code, 0, "{}", a.stderr);
    let coeffs = |t: &str| {
        let v: serde_json::Value = serde_json::from_str(t).unwrap();
        v[0]["spans"][0]["coefficients"].clone()
    };
    assert_eq!(coeffs(&a.stdout), coeffs(&b.stdout));
    let r = specpoly(&["plot", &percent, "--scale", "0.01", "-o", &svg]);
    assert_eq!(r.code, 0, "{}", r.stderr);
}

fn scene(dir: &Path, diffuse: &str, light_scale: &str) -> String {
    let text = format!(
        r#"
[render]
width = 8
height = 8

[camera]
position = [0, 0, 5]
look_at = [0, 0, 0]

[materials.paint]
diffuse = {diffuse}

[[sphere]]
center = [0, 0, 0]
radius = 1
material = "paint"

[[light]]
position = [3, 3, 5]
spectrum = "D65"
intensity = {light_scale}
"#
    );
    let p = dir.join("s.toml");
    std::fs::write(&p, text).unwrap();
    p.display().to_string()
}

#[test]
fn render_refuses_implausible_materials_and_overflowing_images() {
    let dir = tempfile::tempdir().unwrap();
    let percent = csv(dir.path(), "percent", 100.0);
    let png = dir.path().join("o.png").display().to_string();
    let s = scene(dir.path(), &format!("\"{percent}\""), "1");
    fails(&specpoly(&["render", &s, "-o", &png]), "scale = 0.01");
    let s = scene(dir.path(), "\"D65\"", "1");
    fails(&specpoly(&["render", &s, "-o", &png]), "[[light]]");
    let s = scene(dir.path(), "-0.5", "1");
    fails(&specpoly(&["render", &s, "-o", &png]), "negative");
    let s = scene(dir.path(), "0.5", "3e38");
    fails(&specpoly(&["render", &s, "-o", &png]), "not finite");
    assert!(!Path::new(&png).exists());
    // the hint's fix renders the same image as the 0–1 data
    let fixed = scene(
        dir.path(),
        &format!("{{ spectrum = \"{percent}\", scale = 0.01 }}"),
        "1",
    );
    let r = specpoly(&["render", &fixed, "--json", "-o", &png]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let a = std::fs::read(&png).unwrap();
    let unit = csv(dir.path(), "unit", 1.0);
    let s = scene(dir.path(), &format!("\"{unit}\""), "1");
    let r = specpoly(&["render", &s, "-o", &png]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert_eq!(std::fs::read(&png).unwrap(), a);
}
