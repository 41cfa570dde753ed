//! The scene file's triangle geometry (`[[quad]]`, `[[mesh]]`) and emitters (`[[area_light]]`,
//! `[environment]`): their TOML sections and their resolution. File names resolve against the
//! scene file's folder.

use crate::lights::{AreaLight, Emitter, EmitterMesh, Environment};
use crate::mesh::{self, ObjPlacement, Owner, TriangleSoup, Triangles};
use crate::scene::{resolve_spectrum_in, v3, SceneFile, SpectrumSpec};
use serde::Deserialize;
use specpoly_formats::error::{CliError, Result};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

fn one() -> f32 {
    1.0
}

/// `[[quad]]`: a planar quadrilateral (two triangles `v0 v1 v2`, `v0 v2 v3`).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct QuadSection {
    /// The four corners in order around the edge.
    pub vertices: [[f32; 3]; 4],
    /// Material name.
    pub material: String,
}

/// `[[mesh]]`: an OBJ or PLY file.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshSection {
    /// The OBJ file, relative to the scene file's folder.
    pub file: String,
    /// Material of faces without a mapped OBJ material.
    pub material: String,
    /// OBJ material name (`usemtl`) → scene material name. OBJ materials whose name is a scene
    /// material map to it without an entry.
    #[serde(default)]
    pub materials: BTreeMap<String, String>,
    /// Uniform scale (applied first).
    #[serde(default = "one")]
    pub scale: f32,
    /// Translation (applied after the scale).
    #[serde(default)]
    pub translate: [f32; 3],
}

/// `[[area_light]]`: a rectangle (`corner`, `u`, `v`), a sphere (`center`, `radius`) or an
/// emissive mesh (`mesh`, with `scale` and `translate`).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AreaLightSection {
    /// Spectral power distribution.
    pub spectrum: SpectrumSpec,
    /// Radiance scale.
    #[serde(default = "one")]
    pub radiance: f32,
    /// Rectangle: a corner.
    pub corner: Option<[f32; 3]>,
    /// Rectangle: first edge.
    pub u: Option<[f32; 3]>,
    /// Rectangle: second edge (it emits on the side of `u × v`).
    pub v: Option<[f32; 3]>,
    /// Sphere: centre.
    pub center: Option<[f32; 3]>,
    /// Sphere: radius.
    pub radius: Option<f32>,
    /// Emissive mesh: an OBJ or PLY file, relative to the scene file's folder.
    pub mesh: Option<String>,
    /// Emissive mesh: uniform scale (applied first).
    pub scale: Option<f32>,
    /// Emissive mesh: translation (applied after the scale).
    pub translate: Option<[f32; 3]>,
}

/// `[environment]`: a constant radiance from every direction.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnvironmentSection {
    /// Spectral power distribution.
    pub spectrum: SpectrumSpec,
    /// Radiance scale.
    #[serde(default = "one")]
    pub radiance: f32,
}

/// Every quad, mesh and emissive-mesh triangle with its BVH. `material(name, what)` finds a
/// scene material; `area_lights` are the scene's (emissive meshes among them).
pub fn triangles(
    f: &SceneFile,
    source: &str,
    base: Option<&Path>,
    material: &dyn Fn(&str, &str) -> Result<usize>,
    area_lights: &[AreaLight],
) -> Result<Triangles> {
    let mut soup = TriangleSoup::default();
    for (k, l) in area_lights.iter().enumerate() {
        if let Emitter::Mesh(m) = &l.shape {
            for t in &m.tris {
                soup.push_owned(*t, Owner::Light(k));
            }
        }
    }
    if soup.tris.len() > mesh::MAX_TRIANGLES {
        return Err(CliError::data(format!(
            "{source}: more than {} triangles in the scene",
            mesh::MAX_TRIANGLES
        )));
    }
    for (i, q) in f.quad.iter().enumerate() {
        let what = format!("quad {}", i + 1);
        let mut vs = [crate::geometry::V3::default(); 4];
        for (k, v) in q.vertices.iter().enumerate() {
            vs[k] = v3(*v, &format!("{source}: {what}"))?;
        }
        let n = (vs[1] - vs[0]).cross(vs[2] - vs[0]);
        if n.length() == 0.0 {
            return Err(CliError::data(format!(
                "{source}: {what}: the corners are collinear"
            )));
        }
        soup.push_quad(vs, material(&q.material, &what)?);
    }
    for (i, m) in f.mesh.iter().enumerate() {
        let what = format!("mesh {} ({})", i + 1, m.file);
        if !(m.scale.is_finite() && m.scale > 0.0) {
            return Err(CliError::data(format!(
                "{source}: {what}: scale must be positive"
            )));
        }
        let default = material(&m.material, &what)?;
        let mut map = BTreeMap::new();
        for (k, _) in f.materials.iter() {
            map.insert(k.clone(), material(k, &what)?);
        }
        for (obj, scene) in &m.materials {
            map.insert(obj.clone(), material(scene, &what)?);
        }
        let path = mesh_path(&m.file, base, source, &what)?;
        let place = ObjPlacement {
            scale: m.scale,
            translate: v3(m.translate, &format!("{source}: {what}: translate"))?,
            default,
            map: &map,
        };
        mesh::load(&path, &place, &mut soup)?;
    }
    Ok(soup.build())
}

/// `file` relative to `base`; an error naming `what` if it is not a file.
fn mesh_path(file: &str, base: Option<&Path>, source: &str, what: &str) -> Result<PathBuf> {
    let path = match base {
        Some(b) if Path::new(file).is_relative() => b.join(file),
        _ => Path::new(file).to_path_buf(),
    };
    if !path.is_file() {
        // a file that does not exist is exit 2 wherever it is named (src/error.rs)
        return Err(CliError::usage(format!(
            "{source}: {what}: no such file {}",
            path.display()
        )));
    }
    Ok(path)
}

/// The area lights and the environment.
pub fn lights(
    f: &SceneFile,
    source: &str,
    base: Option<&Path>,
) -> Result<(Vec<AreaLight>, Option<Environment>)> {
    let mut out = Vec::new();
    for (i, l) in f.area_light.iter().enumerate() {
        let what = format!("{source}: area_light {}", i + 1);
        if !(l.radiance.is_finite() && l.radiance >= 0.0) {
            return Err(CliError::data(format!("{what}: radiance must be ≥ 0")));
        }
        if l.mesh.is_none() && (l.scale.is_some() || l.translate.is_some()) {
            return Err(CliError::data(format!(
                "{what}: scale and translate apply to a mesh only"
            )));
        }
        let shape = match (l.corner, l.u, l.v, l.center, l.radius) {
            (None, None, None, None, None) if l.mesh.is_some() => {
                let file = l.mesh.as_deref().unwrap_or_default();
                let scale = l.scale.unwrap_or(1.0);
                if !(scale.is_finite() && scale > 0.0) {
                    return Err(CliError::data(format!("{what}: scale must be positive")));
                }
                let path = mesh_path(file, base, source, &format!("area_light {}", i + 1))?;
                let place = ObjPlacement {
                    scale,
                    translate: v3(l.translate.unwrap_or_default(), &what)?,
                    default: 0,
                    map: &BTreeMap::new(),
                };
                let mut soup = TriangleSoup::default();
                mesh::load(&path, &place, &mut soup)?;
                let m = EmitterMesh::new(soup.tris).ok_or_else(|| {
                    CliError::data(format!("{what}: the mesh {file} has no area"))
                })?;
                Emitter::Mesh(Arc::new(m))
            }
            (Some(c), Some(u), Some(v), None, None) if l.mesh.is_none() => {
                let (c, u, v) = (v3(c, &what)?, v3(u, &what)?, v3(v, &what)?);
                if u.cross(v).length() == 0.0 {
                    return Err(CliError::data(format!(
                        "{what}: edges u and v must not be parallel or zero"
                    )));
                }
                Emitter::Rect { corner: c, u, v }
            }
            (None, None, None, Some(c), Some(r)) if l.mesh.is_none() => {
                if !(r.is_finite() && r > 0.0) {
                    return Err(CliError::data(format!("{what}: radius must be positive")));
                }
                Emitter::Sphere {
                    center: v3(c, &what)?,
                    radius: r,
                }
            }
            _ => {
                return Err(CliError::data(format!(
                    "{what}: give a rectangle (corner, u, v), a sphere (center, radius) or a mesh (mesh = FILE)"
                )))
            }
        };
        out.push(AreaLight {
            shape,
            spd: resolve_spectrum_in(&l.spectrum, &format!("{what}: spectrum"), base)?,
            radiance: l.radiance,
        });
    }
    let env = match &f.environment {
        Some(e) => {
            if !(e.radiance.is_finite() && e.radiance >= 0.0) {
                return Err(CliError::data(format!(
                    "{source}: environment.radiance must be ≥ 0"
                )));
            }
            Some(Environment {
                spd: resolve_spectrum_in(
                    &e.spectrum,
                    &format!("{source}: environment.spectrum"),
                    base,
                )?,
                radiance: e.radiance,
            })
        }
        None => None,
    };
    Ok((out, env))
}
