//! The scene file's triangle geometry (`[[quad]]`, `[[mesh]]`) and emitters (`[[area_light]]`,
//! `[environment]`) resolved: quads and mesh files ([`crate::mesh`] for OBJ,
//! [`crate::mesh_ply`] for PLY) into one triangle set with its BVH, emitters into
//! [`crate::lights`]. File names resolve against the scene file's folder.

use crate::error::{Error, Result};
use crate::geometry::V3;
use crate::lights::{AreaLight, Emitter, EmitterMesh, Environment};
use crate::mesh::{self, ObjPlacement, Owner, TriangleSoup, Triangles};
use crate::scene_value::{resolve_spectrum_in, v3};
use crate::sections::{
    AreaLightSection, EnvironmentSection, MaterialSection, MeshSection, QuadSection,
};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Every quad, mesh and emissive-mesh triangle with its BVH. `materials` are the scene file's
/// (every mesh maps OBJ materials of their names to them); `material(name, what)` finds a
/// scene material; `area_lights` are the scene's (emissive meshes among them).
pub fn triangles(
    quads: &[QuadSection],
    meshes: &[MeshSection],
    materials: &BTreeMap<String, MaterialSection>,
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
        return Err(Error::invalid(
            source,
            format!("more than {} triangles in the scene", mesh::MAX_TRIANGLES),
        ));
    }
    for (i, q) in quads.iter().enumerate() {
        let what = format!("quad {}", i + 1);
        let mut vs = [V3::default(); 4];
        for (k, v) in q.vertices.iter().enumerate() {
            vs[k] = v3(*v, &format!("{source}: {what}"))?;
        }
        if vs.iter().any(|v| {
            [v.x, v.y, v.z]
                .iter()
                .any(|c| c.abs() > mesh::MAX_COORDINATE)
        }) {
            return Err(Error::invalid(
                source,
                format!("{what}: a corner is beyond ±{:e}", mesh::MAX_COORDINATE),
            ));
        }
        let n = (vs[1] - vs[0]).cross(vs[2] - vs[0]);
        if n.length() == 0.0 {
            return Err(Error::invalid(
                source,
                format!("{what}: the corners are collinear"),
            ));
        }
        soup.push_quad(vs, material(&q.material, &what)?);
    }
    for (i, m) in meshes.iter().enumerate() {
        let what = format!("mesh {} ({})", i + 1, m.file);
        if !(m.scale.is_finite() && m.scale > 0.0) {
            return Err(Error::invalid(
                source,
                format!("{what}: scale must be positive"),
            ));
        }
        let default = material(&m.material, &what)?;
        let mut map = BTreeMap::new();
        for (k, _) in materials.iter() {
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
        load_mesh(&path, &place, &mut soup)?;
    }
    Ok(soup.build())
}

/// Reads a mesh file into `soup`: PLY for a `.ply` name ([`crate::mesh_ply`]), glTF for
/// `.gltf` and `.glb` ([`crate::mesh_gltf`]), else OBJ ([`mesh::load_obj`]); returns how many
/// triangles it added.
fn load_mesh(path: &Path, place: &ObjPlacement<'_>, soup: &mut TriangleSoup) -> Result<usize> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    match ext.as_deref() {
        Some("ply") => crate::mesh_ply::load_ply(path, place, soup),
        Some("gltf" | "glb") => crate::mesh_gltf::load_gltf(path, place, soup),
        _ => mesh::load_obj(path, place, soup),
    }
}

/// `file` relative to `base`; an error naming `what` if it is not a file.
fn mesh_path(file: &str, base: Option<&Path>, source: &str, what: &str) -> Result<PathBuf> {
    let path = match base {
        Some(b) if Path::new(file).is_relative() => b.join(file),
        _ => Path::new(file).to_path_buf(),
    };
    if !path.is_file() {
        // a file that does not exist is exit 2 wherever it is named (src/error.rs)
        return Err(Error::NoSuchMeshFile {
            at: format!("{source}: {what}"),
            path,
        });
    }
    Ok(path)
}

/// The area lights and the environment.
pub fn lights(
    area_lights: &[AreaLightSection],
    environment: &Option<EnvironmentSection>,
    source: &str,
    base: Option<&Path>,
) -> Result<(Vec<AreaLight>, Option<Environment>)> {
    let mut out = Vec::new();
    for (i, l) in area_lights.iter().enumerate() {
        let what = format!("{source}: area_light {}", i + 1);
        if !(l.radiance.is_finite() && l.radiance >= 0.0) {
            return Err(Error::invalid(&what, "radiance must be ≥ 0"));
        }
        if l.mesh.is_none() && (l.scale.is_some() || l.translate.is_some()) {
            return Err(Error::invalid(
                what,
                "scale and translate apply to a mesh only",
            ));
        }
        let shape = match (l.corner, l.u, l.v, l.center, l.radius) {
            (None, None, None, None, None) if l.mesh.is_some() => {
                let file = l.mesh.as_deref().unwrap_or_default();
                let scale = l.scale.unwrap_or(1.0);
                if !(scale.is_finite() && scale > 0.0) {
                    return Err(Error::invalid(&what, "scale must be positive"));
                }
                let path = mesh_path(file, base, source, &format!("area_light {}", i + 1))?;
                let place = ObjPlacement {
                    scale,
                    translate: v3(l.translate.unwrap_or_default(), &what)?,
                    default: 0,
                    map: &BTreeMap::new(),
                };
                let mut soup = TriangleSoup::default();
                load_mesh(&path, &place, &mut soup)?;
                let m = EmitterMesh::new(soup.tris).ok_or_else(|| {
                    Error::invalid(&what, format!("the mesh {file} has no area"))
                })?;
                Emitter::Mesh(Arc::new(m))
            }
            (Some(c), Some(u), Some(v), None, None) if l.mesh.is_none() => {
                let (c, u, v) = (v3(c, &what)?, v3(u, &what)?, v3(v, &what)?);
                if u.cross(v).length() == 0.0 {
                    return Err(Error::invalid(&what, "edges u and v must not be parallel or zero"));
                }
                Emitter::Rect { corner: c, u, v }
            }
            (None, None, None, Some(c), Some(r)) if l.mesh.is_none() => {
                if !(r.is_finite() && r > 0.0) {
                    return Err(Error::invalid(&what, "radius must be positive"));
                }
                Emitter::Sphere {
                    center: v3(c, &what)?,
                    radius: r,
                }
            }
            _ => {
                return Err(Error::invalid(&what, "give a rectangle (corner, u, v), a sphere (center, radius) or a mesh (mesh = FILE)"))
            }
        };
        out.push(AreaLight {
            shape,
            spd: resolve_spectrum_in(&l.spectrum, &format!("{what}: spectrum"), base)?,
            radiance: l.radiance,
        });
    }
    let env = match environment {
        Some(e) => {
            if !(e.radiance.is_finite() && e.radiance >= 0.0) {
                return Err(Error::invalid(source, "environment.radiance must be ≥ 0"));
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
