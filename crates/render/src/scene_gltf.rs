//! A glTF 2.0 file as a whole scene (`specpoly render model.glb`): its meshes, materials,
//! camera and `KHR_lights_punctual` lights become a scene file ([`SceneFile`]) whose one
//! `[[mesh]]` is the glTF file itself ([`crate::mesh_gltf`] reads its triangles, in the scene
//! frame `(x, y, −z)`), so a glTF scene is checked and resolved by the same rules as a TOML
//! one. (The file is therefore parsed twice: once for this translation, once for the mesh.)
//!
//! **Materials** (glTF's metallic-roughness model mapped to Whitted's and Phong's; material `i`
//! becomes scene material `gltf#i`). With base colour `c` (`baseColorFactor`, linear sRGB,
//! upsampled to a reflectance as `{ rgb = … }` is), metallic `m`, roughness `r`, transmission
//! `t` (`KHR_materials_transmission`) and index `η` (`KHR_materials_ior`, default 1.5):
//!
//! - diffuse `= (1 − m)(1 − t)·c`;
//! - the specular reflectance at normal incidence `F₀ = 0.04·(1 − m) + m·c` (glTF's own
//!   dielectric `F₀` and the metal's base colour, the specification's Appendix B) is the Phong
//!   coefficient with exponent `n = 2/α² − 2`, `α = r²` (Walter et al. 2007's correspondence of
//!   the Beckmann and Phong lobes), `n` within 1…10 000; for `r < 0.05` it is the `mirror`
//!   reflectance instead (a polished surface);
//! - transmission `= t·c` with index `η`.
//!
//! A material whose `extras` has a `specpoly` object takes it as written instead: the fields
//! of a scene file's `[materials.NAME]` (`{"specpoly": {"diffuse": "colorchecker#red",
//! "phong": 60}}`), so spectral data rides in a glTF file. A primitive without a material is a
//! grey Lambertian 0.8.
//!
//! **Textures** ([`crate::texture`]): a material's `baseColorTexture` (PNG, `TEXCOORD_0`)
//! replaces the diffuse reflectance `(1 − m)(1 − t)·c` by `(1 − m)(1 − t)·c·texel` (each
//! texel decoded from sRGB and upsampled) where a triangle has texture coordinates; the
//! specular, mirror and transmission terms keep the factor `c`. Its `normalTexture` perturbs
//! the shading normal. Not with `extras.specpoly` for the base colour (the spectra written
//! there stand), nor with hero-wavelength sampling (refused).
//!
//! **Camera**: the first perspective camera met walking the scene's nodes (its node's
//! position, looking down its −Z with its +Y up; `yfov`; `aspectRatio` sets the width for a
//! height of 256). Without one (most published models), a 40° camera looks along the scene's
//! +z (glTF's −Z: at the model's front) at the centre of the triangles' bounds, from the
//! distance at which their bounding sphere fills the height.
//!
//! **Lights**: `point` and `spot` become point lights at their node's position (the spot's
//! cone is not modelled), `directional` a point light 1000 bounding radii away against its
//! direction. The renderer's point lights do not fall off with distance (Whitted's model), so
//! intensities are taken relative: the largest becomes 1. A light's spectrum is
//! `extras.specpoly.spectrum` (any spectrum the scene file takes: `"A"`, `"FL11"`, a file)
//! if given, else D65 for a white `color`; another colour is refused (name a spectrum).
//! Without lights, a D65 light at the camera (a head light) and a D65 ambient of 0.1.

use crate::error::{Error, Result};
use crate::mesh_gltf::{to_scene, GltfFile};
use crate::scene_file::SceneFile;
use crate::sections::{
    AmbientSection, CameraSection, LightSection, MaterialSection, MeshSection, RenderSection,
    SpectrumSpec, SpectrumTable,
};
use crate::texture::{BaseColour, Image, MaterialTextures, NormalMap, Sampling, Wrap};
use glam::Vec3;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Arc;

/// The scene material of primitives without a glTF material.
pub const DEFAULT_MATERIAL: &str = "gltf#default";

/// `extras` of a glTF material or light: `{"specpoly": …}`; other keys are left alone.
#[derive(Deserialize)]
struct Extras<T> {
    specpoly: Option<T>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LightExtras {
    spectrum: SpectrumSpec,
}

fn extras<T: serde::de::DeserializeOwned>(
    raw: &gltf::json::Extras,
    at: &str,
    file: &Path,
) -> Result<Option<T>> {
    let Some(raw) = raw else { return Ok(None) };
    let e: Extras<T> = serde_json::from_str(raw.get())
        .map_err(|e| crate::mesh::mesh_error(file, format!("{at}.extras.specpoly: {e}")))?;
    Ok(e.specpoly)
}

fn rgb(c: [f32; 3]) -> SpectrumSpec {
    let c = c.map(|v| v.clamp(0.0, 1.0));
    if c[0] == c[1] && c[1] == c[2] {
        SpectrumSpec::Constant(c[0])
    } else {
        SpectrumSpec::Table(SpectrumTable {
            rgb: Some(c),
            ..Default::default()
        })
    }
}

/// The Phong exponent of roughness `r`: `2/α² − 2` with `α = r²`, within 1…10 000.
pub fn phong_exponent(r: f32) -> f32 {
    let a = (r * r).max(1e-6);
    (2.0 / (a * a) - 2.0).clamp(1.0, 10_000.0)
}

/// Scene material of glTF material `m` (see the module docs).
fn material(m: &gltf::Material<'_>, file: &Path) -> Result<MaterialSection> {
    let at = format!("materials[{}]", m.index().unwrap_or(0));
    if let Some(s) = extras::<MaterialSection>(m.extras(), &at, file)? {
        return Ok(s);
    }
    let pbr = m.pbr_metallic_roughness();
    let f = pbr.base_color_factor();
    let c = [f[0], f[1], f[2]];
    let (metal, rough) = (
        pbr.metallic_factor().clamp(0.0, 1.0),
        pbr.roughness_factor().clamp(0.0, 1.0),
    );
    let t = m
        .transmission()
        .map_or(0.0, |t| t.transmission_factor().clamp(0.0, 1.0));
    let ior = m.ior().unwrap_or(1.5);
    if ![f[0], f[1], f[2], metal, rough, t, ior]
        .iter()
        .all(|v| v.is_finite())
    {
        return Err(crate::mesh::mesh_error(
            file,
            format!("{at}: a factor is not finite"),
        ));
    }
    let f0 = c.map(|v| 0.04 * (1.0 - metal) + metal * v);
    let polished = rough < 0.05;
    let zero = SpectrumSpec::Constant(0.0);
    Ok(MaterialSection {
        diffuse: rgb(c.map(|v| (1.0 - metal) * (1.0 - t) * v)),
        specular: if polished { zero.clone() } else { rgb(f0) },
        phong: phong_exponent(rough),
        mirror: if polished { rgb(f0) } else { zero.clone() },
        transmission: if t > 0.0 { rgb(c.map(|v| t * v)) } else { zero },
        ior: if t > 0.0 { ior } else { 1.0 },
    })
}

/// The scene file a glTF file makes (see the module docs). Its `[[mesh]]` names the file by
/// its name; resolve it with the file's folder as the base.
pub fn scene_file(path: &Path) -> Result<SceneFile> {
    scene_file_of(&GltfFile::open(path)?)
}

/// [`scene_file`] of a file already read and checked.
pub fn scene_file_of(file: &GltfFile) -> Result<SceneFile> {
    let path = file.path.as_path();
    let bad = |why: String| crate::mesh::mesh_error(path, why);
    let mut materials = BTreeMap::new();
    for (i, m) in file.doc.materials().enumerate() {
        materials.insert(format!("gltf#{i}"), material(&m, path)?);
    }
    materials.insert(
        DEFAULT_MATERIAL.to_string(),
        MaterialSection {
            diffuse: SpectrumSpec::Constant(0.8),
            specular: SpectrumSpec::Constant(0.0),
            phong: 32.0,
            mirror: SpectrumSpec::Constant(0.0),
            transmission: SpectrumSpec::Constant(0.0),
            ior: 1.0,
        },
    );
    // the triangles' bounds (scene frame)
    let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    file.triangles(|tri| {
        for v in tri.vertices {
            if ![v.x, v.y, v.z]
                .iter()
                .all(|c| c.is_finite() && c.abs() <= crate::mesh::MAX_COORDINATE)
            {
                return Err(bad(format!(
                    "a vertex at ({}, {}, {}) once placed by its nodes is beyond ±{:e}",
                    v.x,
                    v.y,
                    v.z,
                    crate::mesh::MAX_COORDINATE
                )));
            }
            let v = Vec3::new(v.x, v.y, v.z);
            lo = lo.min(v);
            hi = hi.max(v);
        }
        Ok(())
    })?;
    if !(lo.is_finite() && hi.is_finite()) {
        return Err(bad("the scene has no triangles".into()));
    }
    let centre = (lo + hi) * 0.5;
    let radius = ((hi - lo).length() * 0.5).max(1e-6);
    let mut render = RenderSection::default();
    let placed = file.placed_nodes()?;
    let nodes: Vec<gltf::Node<'_>> = file.doc.nodes().collect();
    let mut camera = None;
    for p in &placed {
        let Some(cam) = nodes[p.node].camera() else {
            continue;
        };
        if let gltf::camera::Projection::Perspective(c) = cam.projection() {
            let at = format!("cameras[{}]", cam.index());
            let fov = c.yfov().to_degrees();
            if !(fov > 0.0 && fov < 180.0) {
                return Err(bad(format!("{at}.perspective.yfov: must be in (0, π)")));
            }
            if let Some(a) = c.aspect_ratio() {
                if !(a.is_finite() && a > 0.0) {
                    return Err(bad(format!(
                        "{at}.perspective.aspectRatio: must be positive"
                    )));
                }
                render.width = ((render.height as f32 * a).round() as u32).clamp(1, 16384);
            }
            let pos = to_scene(p.world.transform_point3(Vec3::ZERO));
            let fwd = to_scene(p.world.transform_vector3(Vec3::NEG_Z));
            let up = to_scene(p.world.transform_vector3(Vec3::Y));
            camera = Some(CameraSection {
                position: [pos.x, pos.y, pos.z],
                look_at: [pos.x + fwd.x, pos.y + fwd.y, pos.z + fwd.z],
                up: [up.x, up.y, up.z],
                fov,
            });
            break;
        }
    }
    let camera = camera.unwrap_or_else(|| {
        let fov = 40.0f32;
        let d = radius / (0.5 * fov.to_radians()).sin();
        CameraSection {
            position: [centre.x, centre.y, centre.z - d],
            look_at: centre.to_array(),
            up: [0.0, 1.0, 0.0],
            fov,
        }
    });
    // lights
    let mut lights = Vec::new();
    for p in &placed {
        let Some(l) = nodes[p.node].light() else {
            continue;
        };
        let at = format!("extensions.KHR_lights_punctual.lights[{}]", l.index());
        let spectrum = match extras::<LightExtras>(l.extras(), &at, path)? {
            Some(e) => e.spectrum,
            None => {
                let c = l.color();
                if !(c[0] == c[1] && c[1] == c[2]) {
                    return Err(bad(format!(
                        "{at}.color {c:?} is not white: name its spectrum in \
                         extras (\"specpoly\": {{\"spectrum\": \"A\"}})"
                    )));
                }
                SpectrumSpec::Name("D65".into())
            }
        };
        let position = match l.kind() {
            gltf::khr_lights_punctual::Kind::Directional => {
                let d = p.world.transform_vector3(Vec3::NEG_Z).normalize_or_zero();
                let d = Vec3::new(d.x, d.y, -d.z);
                centre - d * (1000.0 * radius)
            }
            _ => {
                let q = to_scene(p.world.transform_point3(Vec3::ZERO));
                Vec3::new(q.x, q.y, q.z)
            }
        };
        let intensity = l.intensity();
        if !(intensity.is_finite() && intensity >= 0.0) {
            return Err(bad(format!("{at}.intensity: must be ≥ 0")));
        }
        lights.push(LightSection {
            position: position.to_array(),
            spectrum,
            intensity,
        });
    }
    let max = lights.iter().map(|l| l.intensity).fold(0.0f32, f32::max);
    for l in &mut lights {
        l.intensity = if max > 0.0 { l.intensity / max } else { 1.0 };
    }
    let ambient = if lights.is_empty() {
        lights.push(LightSection {
            position: camera.position,
            spectrum: SpectrumSpec::Name("D65".into()),
            intensity: 1.0,
        });
        Some(AmbientSection {
            spectrum: SpectrumSpec::Name("D65".into()),
            intensity: 0.1,
            background: SpectrumSpec::Constant(0.0),
        })
    } else {
        None
    };
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .ok_or_else(|| bad("not a file name".into()))?;
    Ok(SceneFile {
        render,
        camera,
        ambient,
        light: lights,
        materials,
        sphere: vec![],
        plane: vec![],
        boxes: vec![],
        quad: vec![],
        mesh: vec![MeshSection {
            file: name,
            material: DEFAULT_MATERIAL.to_string(),
            materials: BTreeMap::new(),
            scale: 1.0,
            translate: [0.0; 3],
        }],
        area_light: vec![],
        environment: None,
        base: None,
    })
}

/// Whether `spec` names a glTF file (`.gltf`, `.glb`, any case).
pub fn is_gltf(spec: &str) -> bool {
    let l = spec.to_ascii_lowercase();
    l.ends_with(".gltf") || l.ends_with(".glb")
}

/// Loads a glTF file as a scene ([`scene_file`], resolved against the file's folder).
pub fn load(path: &Path, source: &str) -> Result<crate::scene::Scene> {
    if !path.is_file() {
        return Err(Error::NoSuchSceneFile {
            name: source.to_string(),
        });
    }
    let base = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let mut scene = scene_file(path)?.resolve_in(source, Some(base))?;
    attach_textures(&GltfFile::open(path)?, &mut scene)?;
    Ok(scene)
}

/// How glTF texture `t` is looked up.
fn sampling(t: &gltf::Texture<'_>) -> Sampling {
    use gltf::texture::{MagFilter, WrappingMode};
    let wrap = |w: WrappingMode| match w {
        WrappingMode::ClampToEdge => Wrap::Clamp,
        WrappingMode::MirroredRepeat => Wrap::Mirror,
        WrappingMode::Repeat => Wrap::Repeat,
    };
    let s = t.sampler();
    Sampling {
        wrap_s: wrap(s.wrap_s()),
        wrap_t: wrap(s.wrap_t()),
        nearest: s.mag_filter() == Some(MagFilter::Nearest),
    }
}

/// Gives each scene material `gltf#i` the textures of glTF material `i`: its base-colour
/// texture (unless its `extras` define the material: then the spectra written there stand),
/// times the factor its diffuse reflectance has ([`material`]), and its normal map. Each
/// image is decoded once.
fn attach_textures(file: &GltfFile, scene: &mut crate::scene::Scene) -> Result<()> {
    let mut images: BTreeMap<usize, Arc<Image>> = BTreeMap::new();
    let mut image = |i: usize| -> Result<Arc<Image>> {
        if let Some(im) = images.get(&i) {
            return Ok(im.clone());
        }
        let im = Arc::new(file.image(i)?);
        images.insert(i, im.clone());
        Ok(im)
    };
    let bad = |why: String| crate::mesh::mesh_error(&file.path, why);
    for (i, m) in file.doc.materials().enumerate() {
        let at = format!("materials[{i}]");
        let pbr = m.pbr_metallic_roughness();
        let mut tex = MaterialTextures::default();
        let spectral = extras::<serde_json::Value>(m.extras(), &at, &file.path)?.is_some();
        if let (Some(info), false) = (pbr.base_color_texture(), spectral) {
            if info.tex_coord() != 0 {
                return Err(bad(format!(
                    "{at}.pbrMetallicRoughness.baseColorTexture.texCoord: only TEXCOORD_0 is read"
                )));
            }
            let t = info.texture();
            let f = pbr.base_color_factor();
            let (metal, trans) = (
                pbr.metallic_factor().clamp(0.0, 1.0),
                m.transmission()
                    .map_or(0.0, |t| t.transmission_factor().clamp(0.0, 1.0)),
            );
            let k = (1.0 - metal) * (1.0 - trans);
            let factor = [f[0], f[1], f[2]].map(|v| v.clamp(0.0, 1.0) * k);
            let im = image(t.source().index())?;
            tex.base = Some(BaseColour::new(&im, sampling(&t), factor));
        }
        if let Some(n) = m.normal_texture() {
            if n.tex_coord() != 0 {
                return Err(bad(format!(
                    "{at}.normalTexture.texCoord: only TEXCOORD_0 is read"
                )));
            }
            let t = n.texture();
            if !n.scale().is_finite() {
                return Err(bad(format!("{at}.normalTexture.scale: not finite")));
            }
            tex.normal = Some(NormalMap {
                image: image(t.source().index())?,
                sampling: sampling(&t),
                scale: n.scale(),
            });
        }
        if tex.base.is_none() && tex.normal.is_none() {
            continue;
        }
        let name = format!("gltf#{i}");
        if let Some(sm) = scene.materials.iter_mut().find(|sm| sm.name == name) {
            sm.textures = Some(Arc::new(tex));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Walter et al. 2007's correspondence: α = r², n = 2/α² − 2 (r = 1 is the broadest
    /// lobe, n clamped to 1; r = 0.5: α = 1/4, n = 30).
    #[test]
    fn roughness_maps_to_the_phong_exponent() {
        assert_eq!(phong_exponent(1.0), 1.0);
        assert!((phong_exponent(0.5) - 30.0).abs() < 1e-3);
        assert_eq!(phong_exponent(0.0), 10_000.0);
    }
}
