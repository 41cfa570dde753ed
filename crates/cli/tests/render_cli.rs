//! `specpoly render` through the real binary: outputs, determinism, and scene errors as one
//! line on stderr with the right exit code and no output file left behind.

use crate::common::cli;

use std::path::Path;
use std::process::Output;

fn specpoly(args: &[&str], dir: &Path) -> Output {
    cli::output_in(dir, args)
}

fn stderr(o: &Output) -> String {
    cli::text(&o.stderr)
}

const GOOD: &str = r#"
[render]
width = 24
height = 16
[camera]
position = [0.0, 1.0, -4.0]
look_at = [0.0, 0.5, 0.0]
[ambient]
spectrum = "D65"
intensity = 0.1
[[light]]
position = [2.0, 4.0, -3.0]
spectrum = "A"
[materials.red]
diffuse = "colorchecker#red"
specular = 0.5
phong = 60
[materials.floor]
diffuse = { rgb = [0.5, 0.4, 0.3] }
[materials.glass]
transmission = { spectrum = "colorchecker#blue", normalize = true }
ior = 1.5
[[sphere]]
center = [0.0, 0.5, 0.0]
radius = 0.5
material = "red"
[[box]]
min = [-1.0, 0.0, 0.8]
max = [1.0, 1.0, 1.0]
material = "glass"
[[plane]]
point = [0.0, 0.0, 0.0]
normal = [0.0, 1.0, 0.0]
material = "floor"
"#;

fn png_size(path: &Path) -> (u32, u32) {
    let d = png::Decoder::new(std::fs::File::open(path).unwrap());
    let r = d.read_info().unwrap();
    (r.info().width, r.info().height)
}

#[test]
fn renders_a_scene_file_deterministically() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("s.toml"), GOOD).unwrap();
    let a = specpoly(&["render", "s.toml", "-o", "a.png"], dir.path());
    assert!(a.status.success(), "{}", stderr(&a));
    let b = specpoly(&["render", "s.toml", "-o", "b.png"], dir.path());
    assert!(b.status.success(), "{}", stderr(&b));
    let (pa, pb) = (dir.path().join("a.png"), dir.path().join("b.png"));
    assert_eq!(std::fs::read(&pa).unwrap(), std::fs::read(&pb).unwrap());
    assert_eq!(png_size(&pa), (24, 16));
    for mode in ["rgb", "paper", "sampled:16", "reference"] {
        let o = specpoly(
            &[
                "render", "s.toml", "--mode", mode, "--size", "8x6", "-o", "m.png",
            ],
            dir.path(),
        );
        assert!(o.status.success(), "{mode}: {}", stderr(&o));
        assert_eq!(png_size(&dir.path().join("m.png")), (8, 6));
    }
}

#[test]
fn builtin_scene_and_compare() {
    let dir = tempfile::tempdir().unwrap();
    let o = specpoly(
        &[
            "render",
            "interreflection",
            "--size",
            "32x24",
            "--compare",
            "-o",
            "c.png",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    for m in ["rgb", "paper", "poly"] {
        assert!(out.lines().any(|l| l.starts_with(m)), "{out}");
    }
    // five panels of 32 and four gaps of 4, with a label strip above and the ΔE00 colour bar
    // below (render/compare_image.rs)
    let (w, h) = png_size(&dir.path().join("c.png"));
    assert_eq!(w, 5 * 32 + 4 * 4);
    assert!(h > 24 + 20, "labels and colour bar: {h}");
}

/// `--compare --rounds N --json` with the path tracer: every mode, hero-wavelength sampling
/// among them, rendered N times (interleaved), its time the middle one of its rounds.
#[test]
fn compare_rounds_json() {
    let dir = tempfile::tempdir().unwrap();
    let args = |rounds: &'static str| {
        [
            "render",
            "cornell",
            "--compare",
            "--rounds",
            rounds,
            "--size",
            "8x6",
            "--spp",
            "2",
            "--json",
            "-o",
            "c.png",
        ]
    };
    let o = specpoly(&args("3"), dir.path());
    assert!(o.status.success(), "{}", stderr(&o));
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(j["rounds"], 3);
    let modes = j["modes"].as_array().unwrap();
    let names: Vec<&str> = modes.iter().map(|m| m["mode"].as_str().unwrap()).collect();
    assert_eq!(names, ["rgb", "paper", "poly", "sampled:81", "hero:4"]);
    for m in modes {
        let mut r: Vec<f64> = m["seconds_per_round"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        assert_eq!(r.len(), 3);
        r.sort_by(f64::total_cmp);
        assert_eq!(m["seconds"].as_f64().unwrap(), r[1]);
        assert_eq!(m["paths_per_pixel"], 2);
    }
    // no rounds is a usage error
    let o = specpoly(&args("0"), dir.path());
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}

/// Every scene file shipped in `scenes/` renders from another working folder: the file names
/// in it (`../data/leds/…` in `lightbooth.toml`) resolve beside the scene file.
#[test]
fn shipped_scene_files_render_from_any_folder() {
    let dir = tempfile::tempdir().unwrap();
    let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes");
    let mut n = 0;
    for entry in std::fs::read_dir(&scenes).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "toml") {
            continue;
        }
        let o = specpoly(
            &[
                "render",
                path.to_str().unwrap(),
                "--size",
                "8x6",
                "--spp",
                "1",
                "--samples",
                "1",
                "-o",
                "s.png",
            ],
            dir.path(),
        );
        assert!(o.status.success(), "{}: {}", path.display(), stderr(&o));
        assert_eq!(png_size(&dir.path().join("s.png")), (8, 6));
        n += 1;
    }
    assert!(n >= 5, "{n} scene files");
}

fn fails(scene: &str, code: i32, needle: &str) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("s.toml"), scene).unwrap();
    std::fs::write(
        dir.path().join("bad.csv"),
        "wavelength_nm,v\n400,0.5\n410,oops\n",
    )
    .unwrap();
    std::fs::write(dir.path().join("out.png"), b"previous").unwrap();
    let o = specpoly(&["render", "s.toml", "-o", "out.png"], dir.path());
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(code), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
    assert!(err.contains(needle), "`{needle}` not in: {err}");
    // the old output is untouched and no temporary file is left
    assert_eq!(
        std::fs::read(dir.path().join("out.png")).unwrap(),
        b"previous"
    );
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains("tmp"))
        .collect();
    assert!(left.is_empty(), "{left:?}");
}

#[test]
fn unknown_material() {
    fails(
        &GOOD.replace("material = \"red\"", "material = \"nope\""),
        1,
        "sphere 1: unknown material `nope`",
    );
}

#[test]
fn bad_spectrum_file() {
    fails(
        &GOOD.replace("\"colorchecker#red\"", "\"bad.csv\""),
        1,
        "bad.csv:3:2: `oops` in column `v` is not a number",
    );
}

#[test]
fn negative_radius() {
    fails(
        &GOOD.replace("radius = 0.5", "radius = -0.5"),
        1,
        "sphere 1: radius -0.5 must be positive",
    );
}

#[test]
fn unknown_key() {
    fails(
        &GOOD.replace("phong = 60", "phong = 60\ncolour = 3"),
        1,
        "unknown field `colour`",
    );
}

#[test]
fn usage_errors() {
    let dir = tempfile::tempdir().unwrap();
    for (args, needle) in [
        (
            vec!["render", "nosuchscene", "-o", "x.png"],
            "unknown scene `nosuchscene`",
        ),
        (
            vec!["render", "example1", "--mode", "cmyk", "-o", "x.png"],
            "unknown representation",
        ),
        (
            vec!["render", "example1", "--size", "12", "-o", "x.png"],
            "--size",
        ),
        (
            vec!["render", "example1", "--gamut", "squash", "-o", "x.png"],
            "--gamut",
        ),
        (
            vec![
                "render",
                "example1",
                "--display",
                "nope.toml",
                "-o",
                "x.png",
            ],
            "--display",
        ),
    ] {
        let o = specpoly(&args, dir.path());
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(needle), "{args:?}: {}", stderr(&o));
        assert!(!dir.path().join("x.png").exists());
    }
}

#[test]
fn display_file() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("s.toml"), GOOD).unwrap();
    std::fs::write(
        dir.path().join("d.toml"),
        "primaries = [[0.64, 0.33], [0.30, 0.60], [0.15, 0.06]]\nluminance = [21.26, 71.52, 7.22]\ngamma = 2.2\n",
    )
    .unwrap();
    let o = specpoly(
        &[
            "render",
            "s.toml",
            "--display",
            "d.toml",
            "--gamut",
            "desaturate",
            "-o",
            "d.png",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn calibration_file_from_the_calibration_workflow() {
    let dir = tempfile::tempdir().unwrap();
    let ti3 = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../data/ti3/acer-xb271hu-unit1_dispread_2068.ti3");
    let o = specpoly(
        &[
            "calibrate",
            "fit",
            "--ti3",
            ti3.to_str().unwrap(),
            "-o",
            "acer.toml",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let o = specpoly(
        &[
            "render",
            "example1",
            "--size",
            "16x12",
            "--display",
            "acer.toml",
            "-o",
            "a.png",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let s = specpoly(
        &["render", "example1", "--size", "16x12", "-o", "s.png"],
        dir.path(),
    );
    assert!(s.status.success(), "{}", stderr(&s));
    // a different display gives different device values
    assert_ne!(
        std::fs::read(dir.path().join("a.png")).unwrap(),
        std::fs::read(dir.path().join("s.png")).unwrap()
    );
}

/// `--compare --equal-time`: every path-tracer mode at poly's time against a 1 nm reference;
/// JSON lists each mode's paths per pixel and ΔE00, and the image is two rows of panels.
#[test]
fn equal_time_compare() {
    let dir = tempfile::tempdir().unwrap();
    let o = specpoly(
        &[
            "render",
            "cornell",
            "--compare",
            "--equal-time",
            "--size",
            "8x6",
            "--spp",
            "2",
            "--reference-spp",
            "8",
            "--json",
            "-o",
            "eq.png",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let modes = j["modes"].as_array().unwrap();
    let names: Vec<&str> = modes.iter().map(|m| m["mode"].as_str().unwrap()).collect();
    assert_eq!(names, ["rgb", "poly", "sampled:16", "sampled:81", "hero:4"]);
    for m in modes {
        assert!(m["paths_per_pixel"].as_u64().unwrap() >= 1);
        assert!(m["delta_e00"]["mean"].as_f64().unwrap() >= 0.0);
    }
    assert_eq!(j["reference_paths_per_pixel"], 8);
    // one labelled row: 5 modes, the reference and 5 heat maps, 4-pixel gaps; labels above and
    // the ΔE00 colour bar below make it taller than a panel
    let (w, h) = png_size(&dir.path().join("eq.png"));
    assert_eq!(w, 11 * 8 + 10 * 4);
    assert!(h > 3 * 6, "{h} px: no labels or colour bar");

    // the Whitted tracer has no equal-time comparison; --equal-time needs --compare
    let o = specpoly(
        &[
            "render",
            "example1",
            "--compare",
            "--equal-time",
            "-o",
            "x.png",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(!dir.path().join("x.png").exists());
    let o = specpoly(
        &["render", "cornell", "--equal-time", "-o", "x.png"],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}
