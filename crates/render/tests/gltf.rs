//! glTF 2.0 scenes: files written by an independent tool (trimesh, `data/gltf/make_gltf.py`)
//! render as their OBJ twins do, a published sample asset (Khronos' Box) renders its closed
//! form, and malformed files are one-line errors naming the JSON path.

use crate::common::b64;
use specpoly_core::{delta_e2000, Lab, Xyz};
use specpoly_render as render;
use specpoly_spectra::repr::Repr;
use std::path::{Path, PathBuf};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/gltf")
}

/// The same two objects, once from trimesh's GLB (materials mapped by their glTF names) and
/// once from the OBJ files the script wrote with the node transforms applied in float64.
fn twin_scene(meshes: &str) -> String {
    format!(
        r#"
[render]
width = 40
height = 40
[camera]
position = [0.0, 0.2, -3.2]
look_at = [0.0, -0.1, 0.3]
fov = 40
[ambient]
spectrum = "D65"
intensity = 0.1
[[light]]
position = [-3.0, 4.0, -4.0]
spectrum = "D65"
[materials.red]
diffuse = "colorchecker#red"
specular = 0.3
phong = 20
[materials.blue]
diffuse = "colorchecker#blue"
[materials.grey]
diffuse = 0.5
{meshes}
"#
    )
}

#[test]
fn a_glb_renders_as_its_obj_twin() {
    let dir = tempfile::tempdir().unwrap();
    let d = data();
    let glb = twin_scene(&format!(
        "[[mesh]]\nfile = \"{}\"\nmaterial = \"grey\"\n",
        d.join("scene.glb").display()
    ));
    let obj = twin_scene(&format!(
        "[[mesh]]\nfile = \"{}\"\nmaterial = \"red\"\n[[mesh]]\nfile = \"{}\"\nmaterial = \"blue\"\n",
        d.join("scene_sphere.obj").display(),
        d.join("scene_box.obj").display()
    ));
    let render = |text: &str, name: &str| {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        let s = render::load(path.to_str().unwrap()).unwrap();
        assert_eq!(s.triangles.len(), 320 + 12, "{name}");
        (
            render::render(&s, Repr::DEFAULT, None).unwrap(),
            render::scene_white(&s),
        )
    };
    let (a, white) = render(&glb, "glb.toml");
    let (b, _) = render(&obj, "obj.toml");
    let de: Vec<f64> = a
        .xyz
        .iter()
        .zip(&b.xyz)
        .map(|(p, q)| delta_e2000(Lab::from_xyz(*p, white), Lab::from_xyz(*q, white)))
        .collect();
    let mean = de.iter().sum::<f64>() / de.len() as f64;
    let max = de.iter().cloned().fold(0.0, f64::max);
    // the same triangles up to float rounding (f32 node matrices here, float64 in the script):
    // measured mean 1.3e-6, max below 0.001
    assert!(mean < 1e-3 && max < 0.01, "mean ΔE00 {mean}, max {max}");
    // both objects are in view: reddish and bluish pixels (a* > 20, b* < −20)
    let lab: Vec<Lab> = a.xyz.iter().map(|p| Lab::from_xyz(*p, white)).collect();
    assert!(lab.iter().filter(|l| l.a > 20.0).count() > 100);
    assert!(lab.iter().filter(|l| l.b < -20.0).count() > 50);
}

/// Khronos' Box sample (CC BY 4.0, Cesium) as a whole scene: no camera and no light, so the
/// default camera looks at the cube's front face and the head light sits at the camera. Its
/// material gives only a base colour (0.8, 0, 0): glTF's defaults make it metallic 1 and
/// roughness 1, so the face is a Phong lobe of exponent 1 and coefficient the base colour.
/// At the centre pixel the lobe's `R·V = 1`, so the pixel is the base colour's XYZ under D65,
/// `M_sRGB · (0.8, 0, 0) · 100` (IEC 61966-2-1's matrix, applied here).
#[test]
fn the_box_sample_asset_renders_its_closed_form() {
    let path = data().join("Box.gltf");
    let mut s = render::load(path.to_str().unwrap()).unwrap();
    assert_eq!(s.triangles.len(), 12);
    s.render.width = 9;
    s.render.height = 9;
    let img = render::render(&s, Repr::DEFAULT, None).unwrap();
    let c = img.xyz[4 * 9 + 4];
    let want = Xyz::new(0.8 * 41.24, 0.8 * 21.26, 0.8 * 1.93);
    let white = render::scene_white(&s);
    let de = delta_e2000(Lab::from_xyz(c, white), Lab::from_xyz(want, white));
    eprintln!("box centre {c:?} want {want:?} ΔE00 {de}");
    assert!(de < UPSAMPLE_DE, "centre {c:?} vs {want:?}: ΔE00 {de}");
    // the corner pixels miss the cube: black
    assert_eq!(img.xyz[0], Xyz::default());
}

/// The ΔE00 allowed at the centre pixel: the upsampling's round trip (within 0.01 over the
/// sRGB cube, `upsample.rs`) and the renderer's f32 sums; the earlier three-band upsampling
/// missed this colour by ≈ 2.5.
const UPSAMPLE_DE: f64 = 0.02;

/// A one-triangle glTF whose buffer (3 positions, then 3 u16 indices) is a data URI; `edit`
/// changes the JSON before it is written.
fn triangle(edit: impl FnOnce(&mut serde_json::Value)) -> String {
    let mut bin = Vec::new();
    for v in [0.0f32, 0.0, 2.0, 1.0, 0.0, 2.0, 0.0, 1.0, 2.0] {
        bin.extend_from_slice(&v.to_le_bytes());
    }
    for i in [0u16, 1, 2] {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    let mut doc = serde_json::json!({
        "asset": {"version": "2.0"},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
             "min": [0, 0, 2], "max": [1, 1, 2]},
            {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}
        ],
        "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
        "buffers": [{"byteLength": 42, "uri": format!("data:application/octet-stream;base64,{}", b64(&bin))}]
    });
    edit(&mut doc);
    doc.to_string()
}

/// Loads glTF text as a scene from a temporary file; the error's text if refused.
fn load_text(text: &[u8], name: &str) -> Result<render::scene::Scene, String> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, text).unwrap();
    render::load(path.to_str().unwrap()).map_err(|e| e.to_string())
}

#[test]
fn a_well_formed_triangle_loads() {
    let s = load_text(triangle(|_| ()).as_bytes(), "t.gltf").unwrap();
    assert_eq!(s.triangles.len(), 1);
    // its buffer in a .bin file beside it
    let s = render::load(data().join("tri.gltf").to_str().unwrap()).unwrap();
    assert_eq!(s.triangles.len(), 1);
}

#[test]
fn malformed_files_are_one_line_errors_with_the_json_path() {
    use serde_json::json;
    let cases: Vec<(String, &str)> = vec![
        (
            triangle(|d| d["buffers"][0]["uri"] = json!("absent.bin")),
            "buffers[0].uri",
        ),
        // an index beyond the three vertices
        (
            triangle(|d| {
                let uri = d["buffers"][0]["uri"].as_str().unwrap().to_string();
                let mut bin = Vec::new();
                for v in [0.0f32, 0.0, 2.0, 1.0, 0.0, 2.0, 0.0, 1.0, 2.0] {
                    bin.extend_from_slice(&v.to_le_bytes());
                }
                for i in [0u16, 1, 9] {
                    bin.extend_from_slice(&i.to_le_bytes());
                }
                assert!(uri.starts_with("data:"));
                d["buffers"][0]["uri"] = json!(format!(
                    "data:application/octet-stream;base64,{}",
                    b64(&bin)
                ));
            }),
            "index 9",
        ),
        // a 2 GB buffer claimed over 42 bytes of data
        (
            triangle(|d| d["buffers"][0]["byteLength"] = json!(2_147_483_648u64)),
            "byteLength",
        ),
        // an accessor reaching past its view
        (
            triangle(|d| d["accessors"][0]["count"] = json!(1_000_000)),
            "accessors[0]",
        ),
        // a view reaching past its buffer
        (
            triangle(|d| d["bufferViews"][1]["byteLength"] = json!(4000)),
            "bufferViews[1]",
        ),
        // a transform that overflows f32
        (
            triangle(|d| d["nodes"][0]["scale"] = json!([1e39, 1.0, 1.0])),
            "nodes",
        ),
        // a finite transform that takes the vertices beyond the coordinate bound
        (
            triangle(|d| {
                d["nodes"][0]["matrix"] =
                    json!([1e38, 0, 0, 0, 0, 1e38, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1])
            }),
            "beyond",
        ),
        // a node that is its own child
        (triangle(|d| d["nodes"][0]["children"] = json!([0])), "node"),
        // a reference to a missing accessor
        (
            triangle(|d| d["meshes"][0]["primitives"][0]["indices"] = json!(7)),
            "indices",
        ),
        // a POSITION naming an accessor that does not exist (the `gltf` crate's validation
        // indexed with it and panicked; the fuzz corpus's input)
        (
            triangle(|d| d["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = json!(5)),
            "meshes[0].primitives[0].attributes.POSITION: accessor 5 does not exist (the file has 2)",
        ),
        (
            String::from_utf8(
                std::fs::read(
                    Path::new(env!("CARGO_MANIFEST_DIR"))
                        .join("../../fuzz/corpus/gltf/crash-position-accessor-missing.gltf"),
                )
                .unwrap(),
            )
            .unwrap(),
            "accessor 0 does not exist (the file has 0)",
        ),
        ("{ not json".to_string(), "not a valid glTF"),
    ];
    for (text, want) in cases {
        let e = load_text(text.as_bytes(), "bad.gltf").expect_err(want);
        assert!(
            e.contains(want) && !e.contains('\n') && e.contains("bad.gltf"),
            "want `{want}` in: {e}"
        );
    }
    // GLB: a header whose length is below its own size, a truncated file, a chunk longer than
    // the file
    let glb = std::fs::read(data().join("scene.glb")).unwrap();
    let mut short = glb.clone();
    short[8..12].copy_from_slice(&4u32.to_le_bytes());
    for (bytes, what) in [
        (short, "short header"),
        (glb[..glb.len() / 2].to_vec(), "truncated"),
        (glb[..10].to_vec(), "ten bytes"),
    ] {
        let e = load_text(&bytes, "bad.glb").expect_err(what);
        assert!(!e.contains('\n') && e.contains("bad.glb"), "{what}: {e}");
    }
}

/// A glTF scene's camera (glTF's −Z at a node 5 units along +Z: the scene's +z from z = −5),
/// its `KHR_lights_punctual` lights (intensities relative; a spectrum from `extras`, D65 for a
/// white light, a directional one far against its direction) and a spectral material from
/// `extras`; a coloured light without a spectrum is refused with its path.
#[test]
fn cameras_lights_and_extras_are_read() {
    use serde_json::json;
    let doc = triangle(|d| {
        d["nodes"] = json!([
            {"mesh": 0},
            {"camera": 0, "translation": [0.0, 0.0, 5.0]},
            {"translation": [0.0, 2.0, 1.0], "extensions": {"KHR_lights_punctual": {"light": 0}}},
            {"extensions": {"KHR_lights_punctual": {"light": 1}}}
        ]);
        d["scenes"] = json!([{"nodes": [0, 1, 2, 3]}]);
        d["cameras"] = json!([{"type": "perspective", "perspective": {"yfov": 0.5, "aspectRatio": 2.0, "znear": 0.1}}]);
        d["extensionsUsed"] = json!(["KHR_lights_punctual"]);
        d["extensions"] = json!({"KHR_lights_punctual": {"lights": [
            {"type": "point", "intensity": 5.0, "extras": {"specpoly": {"spectrum": "A"}}},
            {"type": "directional", "intensity": 10.0}
        ]}});
        d["materials"] = json!([{"name": "paint", "extras": {"specpoly": {"diffuse": "colorchecker#red", "phong": 60}}}]);
        d["meshes"][0]["primitives"][0]["material"] = json!(0);
    });
    let s = load_text(doc.as_bytes(), "lit.gltf").unwrap();
    assert_eq!((s.render.width, s.render.height), (512, 256));
    let r = s.camera.ray(0.5, 0.5, 2.0);
    assert!(
        (r.origin.z + 5.0).abs() < 1e-6 && (r.dir.z - 1.0).abs() < 1e-6,
        "{r:?}"
    );
    assert_eq!(s.lights.len(), 2);
    assert_eq!(s.lights[0].spd.name, "A");
    assert!((s.lights[0].intensity - 0.5).abs() < 1e-6);
    assert!(
        (s.lights[0].position.y - 2.0).abs() < 1e-6 && (s.lights[0].position.z + 1.0).abs() < 1e-6
    );
    assert_eq!(s.lights[1].spd.name, "D65");
    assert!(
        s.lights[1].position.z < -100.0,
        "{:?}",
        s.lights[1].position
    );
    let paint = s.materials.iter().find(|m| m.name == "gltf#0").unwrap();
    assert!(paint.diffuse.as_ref().unwrap().name.contains("red") && paint.phong == 60.0);
    let coloured = triangle(|d| {
        d["nodes"] = json!([{"mesh": 0}, {"extensions": {"KHR_lights_punctual": {"light": 0}}}]);
        d["scenes"] = json!([{"nodes": [0, 1]}]);
        d["extensions"] = json!({"KHR_lights_punctual": {"lights": [{"type": "point", "color": [1.0, 0.5, 0.2]}]}});
    });
    let e = load_text(coloured.as_bytes(), "c.gltf").unwrap_err();
    assert!(e.contains("lights[0].color") && !e.contains('\n'), "{e}");
}
