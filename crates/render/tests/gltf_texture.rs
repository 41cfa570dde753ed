//! glTF textures, texture coordinates and normal maps, on scenes built here (tiny glTF files
//! with PNG images encoded by the `png` crate): pixels against closed forms (IEC 61966-2-1's
//! decoding and matrix for a texel's colour under D65; Lambert's cosine for a normal map's
//! normal), and malformed textures as one-line errors with the JSON path.

use crate::common::b64;
use serde_json::{json, Value};
use specpoly_core::{delta_e2000, Lab, Xyz};
use specpoly_render as render;
use specpoly_spectra::repr::Repr;

/// An 8-bit RGB PNG of `w × h` texels, rows from the top.
fn png(w: u32, h: u32, texels: &[[u8; 3]]) -> Vec<u8> {
    let mut out = Vec::new();
    let mut e = png::Encoder::new(&mut out, w, h);
    e.set_color(png::ColorType::Rgb);
    e.set_depth(png::BitDepth::Eight);
    let mut wr = e.write_header().unwrap();
    wr.write_image_data(&texels.concat()).unwrap();
    wr.finish().unwrap();
    out
}

/// IEC 61966-2-1: an 8-bit sRGB value decoded.
fn linear(v: u8) -> f64 {
    let c = v as f64 / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// IEC 61966-2-1's linear sRGB → XYZ, white `Y = 100`.
fn srgb_xyz(c: [f64; 3]) -> Xyz {
    const M: [[f64; 3]; 3] = [
        [0.4124, 0.3576, 0.1805],
        [0.2126, 0.7152, 0.0722],
        [0.0193, 0.1192, 0.9505],
    ];
    let v = [0, 1, 2].map(|i| 100.0 * (0..3).map(|k| M[i][k] * c[k]).sum::<f64>());
    Xyz::new(v[0] as f32, v[1] as f32, v[2] as f32)
}

/// One primitive's vertex data.
#[derive(Default)]
struct Prim {
    pos: Vec<[f32; 3]>,
    normals: Vec<[f32; 3]>,
    uvs: Vec<[f32; 2]>,
    tangents: Vec<[f32; 4]>,
    idx: Vec<u32>,
}

/// A glTF file: `prim` with material 0 (`material`), the PNG `images` as data URIs with the
/// `textures` and `samplers` given, a point light at `light` (glTF frame) and any `extra`
/// top-level fields (overriding).
fn gltf(
    prim: &Prim,
    material: Value,
    images: &[Vec<u8>],
    textures: Value,
    samplers: Value,
) -> Value {
    gltf_multi(&[(prim, 0)], vec![material], images, textures, samplers)
}

/// [`gltf`] with several primitives (each with its material's index) in one mesh.
fn gltf_multi(
    prims: &[(&Prim, usize)],
    materials: Vec<Value>,
    images: &[Vec<u8>],
    textures: Value,
    samplers: Value,
) -> Value {
    let mut bin: Vec<u8> = Vec::new();
    let mut views = Vec::new();
    let mut accessors = Vec::new();
    let mut add = |data: Vec<u8>, acc: Value| {
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        views.push(json!({"buffer": 0, "byteOffset": bin.len(), "byteLength": data.len()}));
        bin.extend_from_slice(&data);
        let mut acc = acc;
        acc["bufferView"] = json!(views.len() - 1);
        accessors.push(acc);
        accessors.len() - 1
    };
    let f32s = |v: &[f32]| v.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
    let mut primitives = Vec::new();
    for &(prim, material) in prims {
        let mut attributes = serde_json::Map::new();
        let (lo, hi) = prim.pos.iter().fold(
            ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]),
            |(lo, hi), p| {
                (
                    [0, 1, 2].map(|k| lo[k].min(p[k])),
                    [0, 1, 2].map(|k| hi[k].max(p[k])),
                )
            },
        );
        let a = add(
            f32s(&prim.pos.concat()),
            json!({"componentType": 5126, "count": prim.pos.len(), "type": "VEC3", "min": lo, "max": hi}),
        );
        attributes.insert("POSITION".into(), json!(a));
        if !prim.normals.is_empty() {
            let a = add(
                f32s(&prim.normals.concat()),
                json!({"componentType": 5126, "count": prim.normals.len(), "type": "VEC3"}),
            );
            attributes.insert("NORMAL".into(), json!(a));
        }
        if !prim.uvs.is_empty() {
            let a = add(
                f32s(&prim.uvs.concat()),
                json!({"componentType": 5126, "count": prim.uvs.len(), "type": "VEC2"}),
            );
            attributes.insert("TEXCOORD_0".into(), json!(a));
        }
        if !prim.tangents.is_empty() {
            let a = add(
                f32s(&prim.tangents.concat()),
                json!({"componentType": 5126, "count": prim.tangents.len(), "type": "VEC4"}),
            );
            attributes.insert("TANGENT".into(), json!(a));
        }
        let idx = add(
            prim.idx.iter().flat_map(|i| i.to_le_bytes()).collect(),
            json!({"componentType": 5125, "count": prim.idx.len(), "type": "SCALAR"}),
        );
        primitives.push(json!({"attributes": attributes, "indices": idx, "material": material}));
    }
    json!({
        "asset": {"version": "2.0"},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": primitives}],
        "materials": materials,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": bin.len(), "uri": format!("data:application/octet-stream;base64,{}", b64(&bin))}],
        "images": images.iter().map(|p| json!({"uri": format!("data:image/png;base64,{}", b64(p))})).collect::<Vec<_>>(),
        "textures": textures,
        "samplers": samplers,
    })
}

/// Adds a point light at `at` (glTF frame) to `doc`.
fn with_light(mut doc: Value, at: [f32; 3]) -> Value {
    doc["nodes"] = json!([{"mesh": 0}, {"translation": at, "extensions": {"KHR_lights_punctual": {"light": 0}}}]);
    doc["scenes"] = json!([{"nodes": [0, 1]}]);
    doc["extensionsUsed"] = json!(["KHR_lights_punctual"]);
    doc["extensions"] =
        json!({"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 1.0}]}});
    doc
}

/// The square `±1` in glTF's xy plane facing +Z, texture coordinates `(0, 0)` at its top left.
fn square() -> Prim {
    Prim {
        pos: vec![[-1., -1., 0.], [1., -1., 0.], [1., 1., 0.], [-1., 1., 0.]],
        normals: vec![[0., 0., 1.]; 4],
        uvs: vec![[0., 1.], [1., 1.], [1., 0.], [0., 0.]],
        tangents: vec![],
        idx: vec![0, 1, 2, 0, 2, 3],
    }
}

/// A material of base colour `texture` (or the factor alone), not metallic, polished (its
/// 4 % reflection is a mirror, and mirrors see the black background here: no highlight).
fn matte(texture: Option<usize>) -> Value {
    let mut m = json!({"pbrMetallicRoughness": {"metallicFactor": 0.0, "roughnessFactor": 0.0}});
    if let Some(t) = texture {
        m["pbrMetallicRoughness"]["baseColorTexture"] = json!({"index": t});
    }
    m
}

const NEAREST: i64 = 9728;
const CLAMP: i64 = 33071;

fn load(doc: &Value, dir: &std::path::Path, name: &str) -> Result<render::scene::Scene, String> {
    let path = dir.join(name);
    std::fs::write(&path, doc.to_string()).unwrap();
    render::load(path.to_str().unwrap()).map_err(|e| e.to_string())
}

/// The camera ray through pixel `(x, y)`'s centre meets scene plane `z = 0` at `(px, py)`.
fn on_plane(s: &render::scene::Scene, x: u32, y: u32) -> (f32, f32) {
    let (w, h) = (s.render.width, s.render.height);
    let r = s.camera.ray(
        (x as f32 + 0.5) / w as f32,
        (y as f32 + 0.5) / h as f32,
        w as f32 / h as f32,
    );
    let t = -r.origin.z / r.dir.z;
    (r.origin.x + t * r.dir.x, r.origin.y + t * r.dir.y)
}

/// The image size of the square's renders.
const W: u32 = 25;
const H: u32 = 22;

const TEXELS: [[u8; 3]; 4] = [[200, 40, 30], [20, 160, 60], [40, 70, 220], [230, 210, 40]];

/// A textured square lit head-on from far away: every pixel is its texel's colour under the
/// light, `M_sRGB · decode(texel) · 100` (the upsampled reflectance under D65; the light's
/// cosine is 1 within 10⁻⁶), with nearest-texel lookup (each pixel against the texel its hit
/// point lies in) and with bilinear filtering (against the bilinear mean of the four decoded
/// texels, clamped at the edges: filtering acts on the spectra, so on linear colours).
#[test]
fn a_textured_square_shows_each_texels_colour_under_the_light() {
    let dir = tempfile::tempdir().unwrap();
    let image = png(2, 2, &TEXELS);
    let lin = |i: usize| TEXELS[i].map(linear);
    use render::sections::Integrator;
    for (nearest, integrator) in [
        (true, Integrator::Whitted),
        (false, Integrator::Whitted),
        (true, Integrator::Path),
    ] {
        let mut sampler = json!({"wrapS": CLAMP, "wrapT": CLAMP});
        if nearest {
            sampler["magFilter"] = json!(NEAREST);
        }
        let doc = with_light(
            gltf(
                &square(),
                matte(Some(0)),
                std::slice::from_ref(&image),
                json!([{"source": 0, "sampler": 0}]),
                json!([sampler]),
            ),
            [0.0, 0.0, 1e6],
        );
        let mut s = load(&doc, dir.path(), "square.gltf").unwrap();
        // not square: no pixel's ray runs exactly along the square's diagonal, which the
        // triangle test (not watertight) can miss on both sides
        s.render.width = W;
        s.render.height = H;
        // the path tracer: the point light's direct term at the first hit; the bounces leave
        // the scene (no environment)
        s.render.integrator = integrator;
        s.render.spp = 1;
        let img = render::render(&s, Repr::DEFAULT, None).unwrap();
        let white = render::scene_white(&s);
        let (mut worst, mut n) = (0.0f64, 0);
        for y in 0..H {
            for x in 0..W {
                let got = img.xyz[(y * W + x) as usize];
                let (px, py) = on_plane(&s, x, y);
                let (u, v) = ((px + 1.0) / 2.0, (1.0 - py) / 2.0);
                // the path tracer's ray is jittered over the pixel (0.07 in u and v here):
                // away from the square's and the texels' edges by that much
                let m = if integrator == Integrator::Path {
                    0.08
                } else {
                    0.0
                };
                if !(m..1.0 - m).contains(&u) || !(m..1.0 - m).contains(&v) {
                    continue;
                }
                let want = if nearest {
                    // away from the texel edges, where the hit point's rounding decides
                    if (u - 0.5).abs() < 0.02 + m || (v - 0.5).abs() < 0.02 + m {
                        continue;
                    }
                    lin((v >= 0.5) as usize * 2 + (u >= 0.5) as usize)
                } else {
                    let f = |t: f32| ((2.0 * t - 0.5) as f64).clamp(0.0, 1.0);
                    let (fx, fy) = (f(u), f(v));
                    [0, 1, 2].map(|k| {
                        (1.0 - fy) * ((1.0 - fx) * lin(0)[k] + fx * lin(1)[k])
                            + fy * ((1.0 - fx) * lin(2)[k] + fx * lin(3)[k])
                    })
                };
                let want = srgb_xyz(want);
                let de = delta_e2000(Lab::from_xyz(got, white), Lab::from_xyz(want, white));
                // each texel's colour: the upsampling's round trip (≤ 0.01) and the
                // representation's fit, measured 0.0074; blends of texels measured 0.020
                let limit = if nearest { 0.015 } else { 0.03 };
                assert!(
                    de < limit,
                    "nearest {nearest}, pixel ({x}, {y}) at uv ({u}, {v}): {got:?} vs {want:?}, ΔE00 {de}"
                );
                worst = worst.max(de);
                n += 1;
            }
        }
        eprintln!(
            "textured square, nearest {nearest}, {integrator:?}: {n} pixels, max ΔE00 {worst:.2e}"
        );
        assert!(n > 80, "{n}");
        // hero-wavelength sampling does not bind a texture's palette to its wavelengths
        let e = render::render(&s, Repr::Hero(4), None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("hero-wavelength") && e.contains("gltf#0"), "{e}");
    }
}

/// A textured material on a primitive without texture coordinates (beside one with them)
/// shows its factor: white, `Y = 100` under the head-on light.
#[test]
fn a_textured_material_without_texture_coordinates_shows_its_factor() {
    let dir = tempfile::tempdir().unwrap();
    let mut bare = square();
    bare.uvs.clear();
    for p in &mut bare.pos {
        p[0] += 3.0;
    }
    let doc = with_light(
        gltf_multi(
            &[(&square(), 0), (&bare, 0)],
            vec![matte(Some(0))],
            &[png(2, 2, &TEXELS)],
            json!([{"source": 0}]),
            json!([]),
        ),
        [1.5, 0.0, 1e6],
    );
    let mut s = load(&doc, dir.path(), "bare.gltf").unwrap();
    s.render.width = W;
    s.render.height = H;
    let img = render::render(&s, Repr::DEFAULT, None).unwrap();
    let mut n = 0;
    for y in 0..H {
        for x in 0..W {
            let (px, py) = on_plane(&s, x, y);
            if (2.1..3.9).contains(&px) && (-0.9..0.9).contains(&py) {
                let got = img.xyz[(y * W + x) as usize].to_array()[1];
                assert!((got - 100.0).abs() < 0.01, "({x}, {y}): Y {got}");
                n += 1;
            }
        }
    }
    assert!(n > 20, "{n}");
}

/// A cube `±0.5`, each face mapped onto the whole texture, normals per face.
fn cube() -> Prim {
    let mut p = Prim::default();
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            let mut n = [0.0; 3];
            n[axis] = sign;
            let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
            let base = p.pos.len() as u32;
            for (i, (ua, ub)) in [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)]
                .into_iter()
                .enumerate()
            {
                let mut v = [0.0; 3];
                v[axis] = 0.5 * sign;
                v[a] = ua;
                v[b] = ub;
                p.pos.push(v);
                p.normals.push(n);
                p.uvs.push([[0., 1.], [1., 1.], [1., 0.], [0., 0.]][i]);
            }
            p.idx.extend([0, 1, 2, 0, 2, 3].map(|k| base + k));
        }
    }
    p
}

/// A textured cube seen from a corner (a glTF camera), lit from the camera's side: every
/// pixel on the cube has the chromaticity of one of the four texels (nearest lookup; the
/// light's cosine only scales the colour), and each texel covers a good share of the cube.
#[test]
fn a_textured_box_shows_its_four_texels_on_each_face() {
    let dir = tempfile::tempdir().unwrap();
    let mut doc = gltf(
        &cube(),
        matte(Some(0)),
        &[png(2, 2, &TEXELS)],
        json!([{"source": 0, "sampler": 0}]),
        json!([{"magFilter": NEAREST}]),
    );
    // the camera at (2, 1.6, 2.4) looking at the origin; a point light beside it
    let eye = glam::Vec3::new(2.0, 1.6, 2.4);
    // the camera's local −Z toward the origin, its +Y up: columns x, y, z of its rotation
    let z = eye.normalize();
    let x = glam::Vec3::Y.cross(z).normalize();
    let rot = glam::Quat::from_mat3(&glam::Mat3::from_cols(x, z.cross(x), z));
    doc["nodes"] = json!([
        {"mesh": 0},
        {"camera": 0, "translation": eye.to_array(), "rotation": rot.to_array()},
        {"translation": [3.0, 2.5, 2.0], "extensions": {"KHR_lights_punctual": {"light": 0}}}
    ]);
    doc["scenes"] = json!([{"nodes": [0, 1, 2]}]);
    doc["cameras"] = json!([{"type": "perspective", "perspective": {"yfov": 0.6, "aspectRatio": 1.0, "znear": 0.1}}]);
    doc["extensionsUsed"] = json!(["KHR_lights_punctual"]);
    doc["extensions"] = json!({"KHR_lights_punctual": {"lights": [{"type": "point"}]}});
    let mut s = load(&doc, dir.path(), "box.gltf").unwrap();
    s.render.width = 40;
    s.render.height = 40;
    let img = render::render(&s, Repr::DEFAULT, None).unwrap();
    let xy = |c: Xyz| {
        let [x, y, z] = c.to_array();
        (x / (x + y + z), y / (x + y + z))
    };
    let texel_xy: Vec<(f32, f32)> = TEXELS.iter().map(|t| xy(srgb_xyz(t.map(linear)))).collect();
    let mut count = [0usize; 4];
    for (i, &c) in img.xyz.iter().enumerate() {
        if c.to_array()[1] < 0.5 {
            continue; // the background, or a face turned from the light
        }
        let (x, y) = xy(c);
        let d: Vec<f32> = texel_xy
            .iter()
            .map(|t| ((t.0 - x).powi(2) + (t.1 - y).powi(2)).sqrt())
            .collect();
        let (k, best) =
            d.iter().enumerate().fold(
                (0, f32::INFINITY),
                |a, (k, &v)| if v < a.1 { (k, v) } else { a },
            );
        assert!(best < 2e-3, "pixel {i}: xy ({x}, {y}) is no texel's: {d:?}");
        count[k] += 1;
    }
    eprintln!("textured box: pixels per texel {count:?}");
    let lit: usize = count.iter().sum();
    assert!(lit > 300, "{lit}");
    assert!(count.iter().all(|&c| c * 8 > lit), "{count:?}");
}

/// The normal-mapped square: each quadrant of a 2 × 2 normal map (nearest lookup) tilts the
/// normal its own way, `n = normalize((2c − 1)_x·T + (2c − 1)_y·B + (2c − 1)_z·N)` with
/// `T = +x` (increasing u), `B = +y` (up in the image), `N = +z` in glTF's frame, and each
/// pixel of a grey 0.5 square under a point light at `L` is `Y = 50 · max(0, n · l)` (no
/// fall-off: Whitted's point lights). The same from derived tangents and from a `TANGENT`
/// attribute; and with the map's `scale` 0 the square is flat.
#[test]
fn a_normal_mapped_square_shades_by_the_mapped_normals() {
    let dir = tempfile::tempdir().unwrap();
    let map = [
        [128u8, 128, 255],
        [218, 128, 218],
        [128, 218, 218],
        [38, 128, 218],
    ];
    let light = [0.4f32, 0.7, 1.0];
    let mut material = json!({
        "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.0},
        "normalTexture": {"index": 0}
    });
    let render_with = |prim: &Prim, material: &Value| {
        let doc = with_light(
            gltf(
                prim,
                material.clone(),
                &[png(2, 2, &map)],
                json!([{"source": 0, "sampler": 0}]),
                json!([{"magFilter": NEAREST}]),
            ),
            light,
        );
        let mut s = load(&doc, dir.path(), "bumpy.gltf").unwrap();
        s.render.width = W;
        s.render.height = H;
        let img = render::render(&s, Repr::DEFAULT, None).unwrap();
        (s, img)
    };
    let (s, derived) = render_with(&square(), &material);
    let mut n = 0;
    let _ = &s;
    for y in 0..H {
        for x in 0..W {
            let (px, py) = on_plane(&s, x, y);
            let (u, v) = ((px + 1.0) / 2.0, (1.0 - py) / 2.0);
            if !(0.0..1.0).contains(&u)
                || !(0.0..1.0).contains(&v)
                || (u - 0.5).abs() < 0.02
                || (v - 0.5).abs() < 0.02
            {
                continue;
            }
            let c = map[(v >= 0.5) as usize * 2 + (u >= 0.5) as usize]
                .map(|c| 2.0 * c as f64 / 255.0 - 1.0);
            let len = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
            // the hit point in glTF's frame is (px, py, 0)
            let l = [light[0] - px, light[1] - py, light[2]].map(|v| v as f64);
            let ll = (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]).sqrt();
            let cos = (c[0] * l[0] + c[1] * l[1] + c[2] * l[2]) / (len * ll);
            let want = 50.0 * cos.max(0.0);
            let got = derived.xyz[(y * W + x) as usize].to_array()[1] as f64;
            assert!(
                (got - want).abs() < 0.05,
                "pixel ({x}, {y}) uv ({u}, {v}): Y {got} vs {want}"
            );
            n += 1;
        }
    }
    assert!(n > 150, "{n}");
    // given tangents (+x, handedness +1) are the derived ones
    let mut with_t = square();
    with_t.tangents = vec![[1.0, 0.0, 0.0, 1.0]; 4];
    let (_, given) = render_with(&with_t, &material);
    for (a, b) in given.xyz.iter().zip(&derived.xyz) {
        assert!(
            (a.to_array()[1] - b.to_array()[1]).abs() < 1e-3,
            "{a:?} vs {b:?}"
        );
    }
    // scale 0: the map's x and y vanish, the normal is the surface's, the square flat
    material["normalTexture"]["scale"] = json!(0.0);
    let (_, flat) = render_with(&square(), &material);
    material.as_object_mut().unwrap().remove("normalTexture");
    let (_, plain) = render_with(&square(), &material);
    for (a, b) in flat.xyz.iter().zip(&plain.xyz) {
        assert!(
            (a.to_array()[1] - b.to_array()[1]).abs() < 1e-3,
            "{a:?} vs {b:?}"
        );
    }
}

/// A latitude–longitude sphere of radius 1 with normals and texture coordinates (`u` with the
/// longitude, `v` from the north pole), `n` rows.
fn sphere(n: usize) -> Prim {
    let mut p = Prim::default();
    for i in 0..=n {
        for j in 0..=2 * n {
            let (th, ph) = (
                std::f32::consts::PI * i as f32 / n as f32,
                std::f32::consts::PI * j as f32 / n as f32,
            );
            let v = [th.sin() * ph.cos(), th.cos(), -th.sin() * ph.sin()];
            p.pos.push(v);
            p.normals.push(v);
            p.uvs.push([j as f32 / (2 * n) as f32, i as f32 / n as f32]);
        }
    }
    let row = (2 * n + 1) as u32;
    for i in 0..n as u32 {
        for j in 0..2 * n as u32 {
            let (a, b, c, d) = (
                i * row + j,
                (i + 1) * row + j,
                (i + 1) * row + j + 1,
                i * row + j + 1,
            );
            p.idx.extend([a, b, c, a, c, d]);
        }
    }
    p
}

/// A smooth sphere whose normal map is flat (`(128, 128, 255)`) on its northern half and
/// tilted on its southern half (nearest lookup): the northern pixels render as the sphere
/// without the map (within the 8-bit map's tilt of 0.4 % of a radian), the southern ones do
/// not; with the map's `scale` 0 the whole sphere renders as without the map.
#[test]
fn a_normal_mapped_sphere_differs_where_its_map_says() {
    let dir = tempfile::tempdir().unwrap();
    let map = [[128u8, 128, 255], [230, 60, 200]];
    let base = json!({"pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.7, 0.7, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.0}});
    let prim = sphere(24);
    let render_with = |material: &Value| {
        let doc = with_light(
            gltf(
                &prim,
                material.clone(),
                &[png(1, 2, &map)],
                json!([{"source": 0, "sampler": 0}]),
                json!([{"magFilter": NEAREST}]),
            ),
            [-2.0, 3.0, 4.0],
        );
        let mut s = load(&doc, dir.path(), "sphere.gltf").unwrap();
        s.render.width = 32;
        s.render.height = 32;
        (render::render(&s, Repr::DEFAULT, None).unwrap(), s)
    };
    let (smooth, s) = render_with(&base);
    let mut mapped_m = base.clone();
    mapped_m["normalTexture"] = json!({"index": 0});
    let (mapped, _) = render_with(&mapped_m);
    mapped_m["normalTexture"]["scale"] = json!(0.0);
    let (flat, _) = render_with(&mapped_m);
    let (mut north, mut south) = ((0.0f64, 0), (0.0f64, 0));
    for y in 0..32u32 {
        for x in 0..32u32 {
            let i = (y * 32 + x) as usize;
            let (a, b, f) = (
                smooth.xyz[i].to_array()[1] as f64,
                mapped.xyz[i].to_array()[1] as f64,
                flat.xyz[i].to_array()[1] as f64,
            );
            assert!(
                (f - a).abs() < 1e-3,
                "scale 0, pixel ({x}, {y}): {f} vs {a}"
            );
            // the hit's latitude from the analytic sphere (the mesh is within 1 % of it)
            let r = s
                .camera
                .ray((x as f32 + 0.5) / 32.0, (y as f32 + 0.5) / 32.0, 1.0);
            let (o, d) = (r.origin, r.dir);
            let bq = o.dot(d);
            let disc = bq * bq - (o.dot(o) - 1.0);
            if disc <= 0.0 || a < 10.0 {
                continue;
            }
            let t = -bq - disc.sqrt();
            let py = o.y + t * d.y;
            let v = py.clamp(-1.0, 1.0).acos() / std::f32::consts::PI;
            if (v - 0.5).abs() < 0.08 {
                continue;
            }
            let rel = (b - a).abs() / a;
            if v < 0.5 {
                north = (north.0.max(rel), north.1 + 1);
            } else {
                south = (south.0 + rel, south.1 + 1);
            }
        }
    }
    eprintln!(
        "normal-mapped sphere: north {} pixels, largest change {:.4}; south {} pixels, mean change {:.3}",
        north.1, north.0, south.1, south.0 / south.1 as f64
    );
    assert!(north.1 > 50 && south.1 > 20, "{north:?} {south:?}");
    assert!(north.0 < 0.05, "{north:?}");
    assert!(south.0 / south.1 as f64 > 0.2, "{south:?}");
}

/// A filter cube (`KHR_materials_transmission` 1, `KHR_materials_ior` 1, base colour
/// `c = (0.2, 0.6, 0.6)`: the filter `F` is `c` upsampled) in front of a grey 0.8 square, lit
/// by a directional light along the view: the square seen through the cube is
/// `F⁴ · 0.8` under D65 (two walls on the way in, two on the shadow ray; Whitted's filters),
/// against colour-science's Jakob–Hanika spectrum of `c` (`data/jakob2019_references.csv`,
/// 10 nm, linearly interpolated) and the 1 nm D65 and CIE 1931 tables; beside the cube it is
/// the grey `Y = 80`. The reference mode (1 nm samples) and the default one.
#[test]
fn a_filter_cube_colours_the_square_behind_it() {
    use specpoly_core::{exact_xyz, Illuminant, Observer};
    let dir = tempfile::tempdir().unwrap();
    let mut back = square();
    for p in &mut back.pos {
        *p = [2.0 * p[0], 2.0 * p[1], -1.5];
    }
    let polished = |c: [f32; 3]| json!({"pbrMetallicRoughness": {"baseColorFactor": [c[0], c[1], c[2], 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.0}});
    let mut filter = polished([0.2, 0.6, 0.6]);
    filter["extensions"] = json!({
        "KHR_materials_transmission": {"transmissionFactor": 1.0},
        "KHR_materials_ior": {"ior": 1.0}
    });
    let mut doc = gltf_multi(
        &[(&cube(), 0), (&back, 1)],
        vec![filter, polished([0.8, 0.8, 0.8])],
        &[],
        json!([]),
        json!([]),
    );
    doc["nodes"] = json!([{"mesh": 0}, {"extensions": {"KHR_lights_punctual": {"light": 0}}}]);
    doc["scenes"] = json!([{"nodes": [0, 1]}]);
    doc["extensionsUsed"] = json!([
        "KHR_lights_punctual",
        "KHR_materials_transmission",
        "KHR_materials_ior"
    ]);
    doc["extensions"] = json!({"KHR_lights_punctual": {"lights": [{"type": "directional"}]}});
    let mut s = load(&doc, dir.path(), "filter.gltf").unwrap();
    s.render.width = 32;
    s.render.height = 32;
    // colour-science's spectrum of c
    let text = include_str!("data/jakob2019_references.csv");
    let row: Vec<f64> = text
        .lines()
        .find(|l| l.starts_with("0.2,0.6,0.6,"))
        .unwrap()
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    let f = |nm: f64| {
        let x = ((nm - 380.0) / 10.0).clamp(0.0, 40.0);
        let i = (x.floor() as usize).min(39);
        let t = x - i as f64;
        row[4 + i] * (1.0 - t) + row[5 + i] * t
    };
    let d65 = Illuminant::D65.tabulated();
    let (want, _) = exact_xyz(Observer::Cie1931, &d65, |nm| 0.8 * f(nm).powi(4));
    let want = Xyz::new(want[0] as f32, want[1] as f32, want[2] as f32);
    let white = render::scene_white(&s);
    for (repr, limit) in [(Repr::Exact, 0.1), (Repr::DEFAULT, 0.2)] {
        let img = render::render(&s, repr, None).unwrap();
        // half a pixel off the centre each way: off the faces' diagonals (x = y)
        let centre = img.xyz[15 * 32 + 15];
        let de = delta_e2000(Lab::from_xyz(centre, white), Lab::from_xyz(want, white));
        eprintln!("filter cube, {repr}: centre {centre:?}, closed form {want:?}, ΔE00 {de:.3}");
        assert!(de < limit, "{repr}: {centre:?} vs {want:?}: ΔE00 {de}");
        // a corner pixel sees the square beside the cube
        let corner = img.xyz[8 * 32 + 8].to_array();
        assert!((corner[1] - 80.0).abs() < 0.05, "{corner:?}");
    }
}

/// Minimal CRC-32 (ISO 3309) for hand-made PNG chunks.
fn crc32(data: &[u8]) -> u32 {
    let mut c = 0xFFFF_FFFFu32;
    for &b in data {
        c ^= b as u32;
        for _ in 0..8 {
            c = if c & 1 != 0 {
                0xEDB8_8320 ^ (c >> 1)
            } else {
                c >> 1
            };
        }
    }
    !c
}

/// A PNG whose header claims `w × h` RGBA texels, over a few bytes of image data.
fn png_claim(w: u32, h: u32) -> Vec<u8> {
    let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
    let mut chunk = |kind: &[u8], body: &[u8]| {
        out.extend_from_slice(&(body.len() as u32).to_be_bytes());
        let mut c = kind.to_vec();
        c.extend_from_slice(body);
        out.extend_from_slice(&c);
        out.extend_from_slice(&crc32(&c).to_be_bytes());
    };
    let mut ihdr = Vec::new();
    ihdr.extend_from_slice(&w.to_be_bytes());
    ihdr.extend_from_slice(&h.to_be_bytes());
    ihdr.extend_from_slice(&[8, 6, 0, 0, 0]);
    chunk(b"IHDR", &ihdr);
    chunk(b"IDAT", &[0x78, 0x9C, 0x03, 0x00, 0x00, 0x00, 0x00, 0x01]);
    chunk(b"IEND", &[]);
    out
}

/// Malformed textures: one-line errors naming the file and the JSON path, before anything
/// large is allocated (a PNG header claiming 2 GiB of texels over 45 bytes).
#[test]
fn bad_textures_are_one_line_errors_with_the_json_path() {
    let dir = tempfile::tempdir().unwrap();
    let good = |images: Vec<Vec<u8>>| {
        gltf(
            &square(),
            matte(Some(0)),
            &images,
            json!([{"source": 0}]),
            json!([]),
        )
    };
    let mut missing = good(vec![png(1, 1, &[[1, 2, 3]])]);
    missing["images"][0]["uri"] = json!("absent.png");
    let mut jpeg = good(vec![vec![0xFF, 0xD8, 0xFF, 0xE0, 0, 0]]);
    jpeg["images"][0]["uri"] = json!("data:image/jpeg;base64,/9j/4AAA");
    let mut short_uv = good(vec![png(1, 1, &[[1, 2, 3]])]);
    short_uv["accessors"][2]["count"] = json!(3);
    let cases = [
        (missing, "images[0].uri"),
        (
            good(vec![png_claim(32768, 16384)]),
            "images[0]: a 32768 × 16384 image",
        ),
        (
            good(vec![b"not a png".to_vec()]),
            "images[0]: not a readable PNG",
        ),
        (jpeg, "images[0]: a JPEG image"),
        (
            short_uv,
            "attributes.TEXCOORD_0: 3 elements for 4 positions",
        ),
    ];
    for (doc, want) in cases {
        let e = load(&doc, dir.path(), "bad.gltf").expect_err(want);
        assert!(
            e.contains(want) && !e.contains('\n') && e.contains("bad.gltf"),
            "want `{want}` in: {e}"
        );
    }
    // an index past the vertices names the primitive's indices
    let mut p = square();
    p.idx[4] = 40;
    let e = load(
        &gltf(&p, matte(None), &[], json!([]), json!([])),
        dir.path(),
        "bad.gltf",
    )
    .unwrap_err();
    assert!(
        e.contains("meshes[0].primitives[0].indices: index 40"),
        "{e}"
    );
    // a transform whose product is NaN (an infinite scale times a zero) names the node
    let mut doc = gltf(&square(), matte(None), &[], json!([]), json!([]));
    doc["nodes"][0]["matrix"] = json!([1e39, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]);
    let e = load(&doc, dir.path(), "bad.gltf").unwrap_err();
    assert!(e.contains("nodes[0].matrix: not finite"), "{e}");
    // JSON has no NaN: a file that writes one is not JSON, and the error says where
    let text = gltf(&square(), matte(None), &[], json!([]), json!([]))
        .to_string()
        .replace(
            "\"nodes\":[{\"mesh\":0}]",
            "\"nodes\":[{\"mesh\":0,\"translation\":[NaN,0,0]}]",
        );
    let path = dir.path().join("nan.gltf");
    std::fs::write(&path, text).unwrap();
    let e = render::load(path.to_str().unwrap())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("nan.gltf") && e.contains("column") && !e.contains('\n'),
        "{e}"
    );
}
