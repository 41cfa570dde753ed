//! Triangle meshes: OBJ files (read with `tobj`), quads written in the scene file, and one
//! bounding volume hierarchy over every triangle of the scene (`obvhs`' compressed wide BVH8,
//! traversed by `obvhs`, over a binary tree built by [`crate::bvh_build`]; `bench/bvh-compare`
//! measures `obvhs` against the `bvh` crate, docs/performance.md).
//!
//! Triangles are one-sided for nothing: a hit reports a unit normal and the tracers flip it toward
//! the viewer as for every other shape. A triangle without vertex normals reports its geometric
//! normal `(v1 − v0) × (v2 − v0)` normalised (flat shading); one whose file gives vertex normals
//! (OBJ `vn`, PLY `nx ny nz`) reports them interpolated at the hit by its barycentric
//! coordinates, `n = normalize(b₀n₀ + b₁n₁ + b₂n₂)` (Phong 1975), so a low-poly model shades
//! smoothly. A scene whose meshes have no vertex normals stores none (36 bytes a triangle less).
//!
//! Below the scene file: PLY files are read by [`crate::mesh_ply`] on top of this module, and
//! the scene file picks the reader by the file's name ([`crate::scene_geometry`]).

use crate::error::{Error, Result};
use crate::geometry::{Ray, EPS, V3};
use glam::Vec3A;
use obvhs::cwbvh::CwBvh;
use obvhs::ray::{Ray as BvhRay, RayHit};
use obvhs::triangle::Triangle;
use std::collections::BTreeMap;
use std::path::Path;

/// At most this many triangles per scene (bounds memory on absurd input).
pub const MAX_TRIANGLES: usize = 20_000_000;

/// The largest vertex coordinate a mesh may have, after its scene's scale and translation
/// (10¹⁸ scene units: light-years in millimetres). The BVH builder quantises node bounds in
/// f32 and panics on coordinates above ≈ 10²⁷; a bound well below that keeps every product of
/// two coordinates finite too.
pub const MAX_COORDINATE: f32 = 1e18;

/// A placed vertex within [`MAX_COORDINATE`], or why not.
pub(crate) fn placed(v: V3, place: &ObjPlacement<'_>) -> std::result::Result<V3, String> {
    let p = v * place.scale + place.translate;
    if [p.x, p.y, p.z]
        .iter()
        .all(|c| c.is_finite() && c.abs() <= MAX_COORDINATE)
    {
        Ok(p)
    } else {
        Err(format!(
            "a vertex at ({}, {}, {}) once placed is beyond ±{MAX_COORDINATE:e}",
            p.x, p.y, p.z
        ))
    }
}

fn a3(v: V3) -> Vec3A {
    Vec3A::new(v.x, v.y, v.z)
}

fn v3(v: Vec3A) -> V3 {
    V3::new(v.x, v.y, v.z)
}

/// What a triangle belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Owner {
    /// A surface of scene material `usize`.
    Material(usize),
    /// Emissive mesh `usize` (an index into the scene's area lights).
    Light(usize),
}

/// Every triangle of a scene with its material, and the BVH over them.
#[derive(Clone, Debug, Default)]
pub struct Triangles {
    /// Triangles in BVH order.
    tris: Vec<Triangle>,
    /// Unit geometric normals, in BVH order.
    normals: Vec<V3>,
    /// Unit vertex normals, in BVH order; empty when no triangle of the scene has them.
    shading: Vec<[V3; 3]>,
    /// Owner of each triangle, in BVH order.
    owners: Vec<Owner>,
    /// Texture coordinates and tangent frames, in BVH order; empty when no triangle of the
    /// scene has texture coordinates.
    surface: Vec<Surface>,
    /// `None` when there are no triangles.
    bvh: Option<CwBvh>,
}

/// Triangles before the BVH is built.
#[derive(Clone, Debug, Default)]
pub struct TriangleSoup {
    /// Vertices.
    pub tris: Vec<[V3; 3]>,
    /// Owner of each.
    pub owners: Vec<Owner>,
    /// Vertex normals of each (the geometric normal thrice for a flat triangle); empty until
    /// a triangle with vertex normals is added.
    pub shading: Vec<[V3; 3]>,
    /// Texture coordinates and tangents of each (zeros for a triangle without); empty until
    /// a triangle with texture coordinates is added.
    pub surface: Vec<Surface>,
}

/// A triangle's texture coordinates (glTF `TEXCOORD_0`, origin at the image's top left) and
/// tangent frame for normal maps.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Surface {
    /// `(u, v)` at each vertex.
    pub uv: [[f32; 2]; 3],
    /// The tangent (toward increasing `u`) at each vertex, in the scene frame.
    pub tangent: [V3; 3],
    /// The handedness: the bitangent is `handedness · (N × T)`; 0 for a triangle without
    /// texture coordinates (in a scene where others have them).
    pub handedness: f32,
}

impl Surface {
    /// The tangent frame a triangle's texture coordinates give (the tangent `∂P/∂u` at every
    /// vertex; the handedness that makes `N × T` point to decreasing `v` for the normal `N`
    /// the hit will report: the mean of the vertex normals `vn` if given, else the geometric
    /// one); the tangent is zero where `uv` is degenerate.
    pub fn from_uv(t: &[V3; 3], uv: [[f32; 2]; 3], vn: Option<[V3; 3]>) -> Self {
        let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
        let (du1, dv1) = (uv[1][0] - uv[0][0], uv[1][1] - uv[0][1]);
        let (du2, dv2) = (uv[2][0] - uv[0][0], uv[2][1] - uv[0][1]);
        let r = du1 * dv2 - du2 * dv1;
        let (dpdu, dpdv) = if r != 0.0 && r.is_finite() {
            (
                (e1 * dv2 - e2 * dv1) * (1.0 / r),
                (e2 * du1 - e1 * du2) * (1.0 / r),
            )
        } else {
            (V3::new(0.0, 0.0, 0.0), V3::new(0.0, 0.0, 0.0))
        };
        let n = match vn {
            Some(v) => v[0] + v[1] + v[2],
            None => geometric(t),
        };
        let handedness = if n.cross(dpdu).dot(dpdv) > 0.0 {
            -1.0
        } else {
            1.0
        };
        Self {
            uv,
            tangent: [dpdu; 3],
            handedness,
        }
    }
}

/// The unit geometric normal of a triangle (zero for a degenerate one).
fn geometric(t: &[V3; 3]) -> V3 {
    let n = (t[1] - t[0]).cross(t[2] - t[0]);
    let l = n.length();
    if l > 0.0 {
        n * (1.0 / l)
    } else {
        V3::new(0.0, 0.0, 0.0)
    }
}

impl TriangleSoup {
    /// Adds one triangle of material `material` (degenerate ones, of zero area, are dropped:
    /// they cannot be hit).
    pub fn push(&mut self, t: [V3; 3], material: usize) {
        self.push_owned(t, Owner::Material(material));
    }

    /// Adds one triangle belonging to `owner` (degenerate ones are dropped).
    pub fn push_owned(&mut self, t: [V3; 3], owner: Owner) {
        if (t[1] - t[0]).cross(t[2] - t[0]).length() > 0.0 {
            if !self.shading.is_empty() {
                let n = geometric(&t);
                self.shading.push([n; 3]);
            }
            if !self.surface.is_empty() {
                self.surface.push(Surface::default());
            }
            self.tris.push(t);
            self.owners.push(owner);
        }
    }

    /// Adds one triangle of material `material` with vertex normals `n` (each normalised; a
    /// zero or non-finite one is replaced by the geometric normal). Degenerate triangles are
    /// dropped.
    pub fn push_smooth(&mut self, t: [V3; 3], n: [V3; 3], material: usize) {
        if (t[1] - t[0]).cross(t[2] - t[0]).length() <= 0.0 {
            return;
        }
        if self.shading.is_empty() {
            // the triangles before this one are flat
            self.shading = self.tris.iter().map(|t| [geometric(t); 3]).collect();
        }
        let g = geometric(&t);
        let unit = |v: V3| {
            let l = v.length();
            if l.is_finite() && l > 0.0 {
                v * (1.0 / l)
            } else {
                g
            }
        };
        self.shading.push(n.map(unit));
        if !self.surface.is_empty() {
            self.surface.push(Surface::default());
        }
        self.tris.push(t);
        self.owners.push(Owner::Material(material));
    }

    /// Adds one triangle of material `material` with vertex normals `n` (smooth shading, as
    /// [`Self::push_smooth`]; `None`: flat) and texture coordinates and tangents `surface`.
    /// Degenerate triangles are dropped.
    pub fn push_textured(
        &mut self,
        t: [V3; 3],
        n: Option<[V3; 3]>,
        surface: Surface,
        material: usize,
    ) {
        let before = self.tris.len();
        match n {
            Some(n) => self.push_smooth(t, n, material),
            None => self.push(t, material),
        }
        if self.tris.len() == before {
            return;
        }
        if self.surface.is_empty() {
            self.surface = vec![Surface::default(); self.tris.len()];
        }
        if let Some(last) = self.surface.last_mut() {
            *last = surface;
        }
    }

    /// A planar quad `a b c d` (in order around its edge) as the triangles `abc` and `acd`.
    pub fn push_quad(&mut self, q: [V3; 4], material: usize) {
        self.push([q[0], q[1], q[2]], material);
        self.push([q[0], q[2], q[3]], material);
    }

    /// Drops every triangle that repeats an earlier one of the same owner (the same three
    /// vertices, in any order): it adds no surface, and thousands of coincident triangles make
    /// the BVH builder's clustering quadratic and its tree deeper than its traversal stack
    /// (20 000 copies of one face: 25 s and a failed build). Linear in the triangle count.
    fn dedup(&mut self) {
        let mut seen = std::collections::HashSet::with_capacity(self.tris.len());
        let mut keep = Vec::with_capacity(self.tris.len());
        for (t, o) in self.tris.iter().zip(&self.owners) {
            let mut key = t.map(|v| [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()]);
            key.sort_unstable();
            let owner = match o {
                Owner::Material(m) => (0u8, *m),
                Owner::Light(l) => (1u8, *l),
            };
            keep.push(seen.insert((key, owner)));
        }
        if keep.iter().all(|k| *k) {
            return;
        }
        let mut k = keep.iter();
        self.tris.retain(|_| *k.next().unwrap_or(&true));
        let mut k = keep.iter();
        self.owners.retain(|_| *k.next().unwrap_or(&true));
        if !self.shading.is_empty() {
            let mut k = keep.iter();
            self.shading.retain(|_| *k.next().unwrap_or(&true));
        }
        if !self.surface.is_empty() {
            let mut k = keep.iter();
            self.surface.retain(|_| *k.next().unwrap_or(&true));
        }
    }

    /// Builds the BVH.
    pub fn build(mut self) -> Triangles {
        self.dedup();
        if self.tris.is_empty() {
            return Triangles::default();
        }
        let input: Vec<Triangle> = self
            .tris
            .iter()
            .map(|t| Triangle {
                v0: a3(t[0]),
                v1: a3(t[1]),
                v2: a3(t[2]),
            })
            .collect();
        // the binary tree by binned SAH (bounded work on any mesh: crate::bvh_build), then
        // `obvhs`' 8-wide nodes with up to three triangles per leaf, children ordered
        let bounds: Vec<obvhs::aabb::Aabb> = input.iter().map(padded_bounds).collect();
        let bvh2 = crate::bvh_build::binned_sah(&bounds);
        let bvh = obvhs::cwbvh::bvh2_to_cwbvh::bvh2_to_cwbvh(&bvh2, 3, true, false);
        // reorder into BVH order so a leaf's triangles are contiguous
        let order: Vec<usize> = bvh.primitive_indices.iter().map(|&i| i as usize).collect();
        let tris: Vec<Triangle> = order.iter().map(|&i| input[i]).collect();
        let normals = tris
            .iter()
            .map(|t| v3((t.v1 - t.v0).cross(t.v2 - t.v0).normalize_or_zero()))
            .collect();
        let owners = order.iter().map(|&i| self.owners[i]).collect();
        let shading = if self.shading.is_empty() {
            Vec::new()
        } else {
            order.iter().map(|&i| self.shading[i]).collect()
        };
        let surface = if self.surface.is_empty() {
            Vec::new()
        } else {
            order.iter().map(|&i| self.surface[i]).collect()
        };
        Triangles {
            tris,
            normals,
            shading,
            owners,
            surface,
            bvh: Some(bvh),
        }
    }
}

impl Triangles {
    /// Number of triangles.
    pub fn len(&self) -> usize {
        self.tris.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.tris.is_empty()
    }

    /// The nearest hit with `EPS < t < t_max`: `(t, unit normal, owner)`.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<(f32, V3, Owner)> {
        self.intersect_indexed(ray, t_max)
            .map(|(t, n, o, _)| (t, n, o))
    }

    /// [`Self::intersect`] with the triangle's index (for [`Self::surface_at`]).
    #[inline]
    pub fn intersect_indexed(&self, ray: &Ray, t_max: f32) -> Option<(f32, V3, Owner, u32)> {
        let bvh = self.bvh.as_ref()?;
        let r = BvhRay::new(a3(ray.origin), a3(ray.dir), EPS, t_max);
        let mut hit = RayHit::none();
        if bvh.ray_traverse(r, &mut hit, |r, id| self.tris[id].intersect(r)) {
            let i = hit.primitive_id as usize;
            let n = match self.shading.get(i) {
                Some(vn) => self.interpolated(i, vn, ray.origin + ray.dir * hit.t),
                None => self.normals[i],
            };
            Some((hit.t, n, self.owners[i], hit.primitive_id))
        } else {
            None
        }
    }

    /// Whether any triangle has texture coordinates.
    #[inline]
    pub fn has_surface(&self) -> bool {
        !self.surface.is_empty()
    }

    /// The texture coordinates `(u, v)` and the unit tangent and bitangent of triangle `i` at
    /// its point `p`, for the unit shading normal `n` there (the tangent interpolated and
    /// orthogonalised against `n`, the bitangent `h·(n × t)`); `None` when the triangle has no
    /// texture coordinates, a zero frame where the tangent is degenerate.
    pub fn surface_at(&self, i: u32, p: V3, n: V3) -> Option<([f32; 2], V3, V3)> {
        let s = self
            .surface
            .get(i as usize)
            .filter(|s| s.handedness != 0.0)?;
        // a sliver without finite barycentrics takes its first corner's values
        let (b1, b2) = self.barycentric(i as usize, p).unwrap_or((0.0, 0.0));
        let b0 = 1.0 - b1 - b2;
        let uv = [0, 1].map(|k| s.uv[0][k] * b0 + s.uv[1][k] * b1 + s.uv[2][k] * b2);
        let t = s.tangent[0] * b0 + s.tangent[1] * b1 + s.tangent[2] * b2;
        let t = t - n * n.dot(t);
        let l = t.length();
        let zero = V3::new(0.0, 0.0, 0.0);
        if !(l.is_finite() && l > 1e-12) {
            return Some((uv, zero, zero));
        }
        let t = t * (1.0 / l);
        Some((uv, t, n.cross(t) * s.handedness))
    }

    /// Barycentric coordinates `(b₁, b₂)` of point `p` of triangle `i` (from the normal
    /// equations of `p − v0 = b₁e₁ + b₂e₂`), clamped into the triangle; `None` where the
    /// equations have no finite solution in `f32` (a sliver whose determinant rounds to 0, or
    /// edges whose squared lengths overflow).
    fn barycentric(&self, i: usize, p: V3) -> Option<(f32, f32)> {
        let t = &self.tris[i];
        let (e1, e2, d) = (v3(t.v1 - t.v0), v3(t.v2 - t.v0), p - v3(t.v0));
        let (a, b, c) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
        let (p1, p2) = (d.dot(e1), d.dot(e2));
        let det = a * c - b * b;
        let (b1, b2) = ((c * p1 - b * p2) / det, (a * p2 - b * p1) / det);
        if !(b1.is_finite() && b2.is_finite()) {
            return None;
        }
        let b1 = b1.clamp(0.0, 1.0);
        Some((b1, b2.clamp(0.0, 1.0 - b1)))
    }

    /// The vertex normals `vn` of triangle `i` interpolated at its point `p` ([`Self::barycentric`]);
    /// the geometric normal where they cancel or the barycentrics are not finite.
    fn interpolated(&self, i: usize, vn: &[V3; 3], p: V3) -> V3 {
        let Some((b1, b2)) = self.barycentric(i, p) else {
            return self.normals[i];
        };
        let n = vn[0] * (1.0 - b1 - b2) + vn[1] * b1 + vn[2] * b2;
        let l = n.length();
        if l.is_finite() && l > 1e-6 {
            n * (1.0 / l)
        } else {
            self.normals[i]
        }
    }

    /// Calls `f(owner)` for every crossing of the segment `EPS < t < t_max`, in no
    /// particular order; stops early when `f` returns `false`.
    #[inline]
    pub fn crossings(&self, ray: &Ray, t_max: f32, mut f: impl FnMut(Owner) -> bool) {
        let Some(bvh) = self.bvh.as_ref() else {
            return;
        };
        let r = BvhRay::new(a3(ray.origin), a3(ray.dir), EPS, t_max);
        let mut go = true;
        // any-hit traversal visits every candidate; a shadow ray stops at the first opaque one
        bvh.ray_traverse_miss(r, |r, id| {
            if go && self.tris[id].intersect(r) < t_max {
                go = f(self.owners[id]);
            }
            // a `t` below `tmax` ends the traversal
            if go {
                f32::INFINITY
            } else {
                r.tmin
            }
        });
    }
}

/// A triangle's bounds widened by 2⁻²⁰ of its largest coordinate: the ray–triangle test is not
/// watertight (Möller–Trumbore in `f32`), and a ray through a shared edge can be found inside
/// a triangle while it passes just outside that triangle's exact bounds (measured: 1.3e-8 at
/// coordinates near 4); the margin keeps such hits inside the box that leads to them.
fn padded_bounds(t: &Triangle) -> obvhs::aabb::Aabb {
    let b = t.aabb();
    let scale = b.min.abs().max(b.max.abs()).max_element();
    let pad = Vec3A::splat(scale * (1.0 / (1u32 << 20) as f32) + f32::MIN_POSITIVE);
    obvhs::aabb::Aabb::new(b.min - pad, b.max + pad)
}

/// Where an OBJ file's triangles go: its transform and its materials.
pub struct ObjPlacement<'a> {
    /// Uniform scale, applied first.
    pub scale: f32,
    /// Translation, applied after the scale.
    pub translate: V3,
    /// The material of faces without one (or whose OBJ material has no mapping).
    pub default: usize,
    /// OBJ material name → scene material index.
    pub map: &'a BTreeMap<String, usize>,
}

/// [`Error::Mesh`] for the file `path`.
pub(crate) fn mesh_error(path: &Path, why: impl Into<String>) -> Error {
    Error::Mesh {
        file: path.display().to_string(),
        why: why.into(),
    }
}

/// Reads an OBJ file (faces triangulated as fans) into `soup`; returns how many triangles it
/// added. Faces use the OBJ material of the same name in `place.map` (`usemtl NAME` with the
/// `.mtl` file beside), else `place.default`.
pub fn load_obj(path: &Path, place: &ObjPlacement<'_>, soup: &mut TriangleSoup) -> Result<usize> {
    // the OBJ and its `.mtl` files through the bounded, regular-file read (a `mtllib` naming a
    // device or a FIFO is refused, never read); `tobj` parses the bytes
    let bytes = specpoly_formats::read::bytes(path)?;
    let folder = path.parent().unwrap_or(Path::new("."));
    parse_obj(path, &bytes, MtlSource::Folder(folder), place, soup)
}

/// Where [`parse_obj`] reads the material libraries an OBJ names (`mtllib NAME`).
#[derive(Clone, Copy, Debug)]
pub enum MtlSource<'a> {
    /// `NAME` in this folder, through the bounded, regular-file read (a missing file is no
    /// error: its faces take the default material).
    Folder(&'a Path),
    /// These bytes, whatever the name (a file-less reader: the fuzz target gives the OBJ's own
    /// bytes, so one input exercises both parsers).
    Bytes(&'a [u8]),
}

/// [`load_obj`] of an OBJ file's bytes already read; `path` names it in errors.
pub fn parse_obj(
    path: &Path,
    bytes: &[u8],
    mtl: MtlSource<'_>,
    place: &ObjPlacement<'_>,
    soup: &mut TriangleSoup,
) -> Result<usize> {
    let opts = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ..Default::default()
    };
    check_face_indices(bytes).map_err(|why| mesh_error(path, why))?;
    let mtl_error = std::cell::RefCell::new(None);
    let load_mtl = |name: &Path| -> tobj::MTLLoadResult {
        let read = match mtl {
            MtlSource::Folder(folder) => specpoly_formats::read::bytes(&folder.join(name)),
            MtlSource::Bytes(b) => Ok(b.to_vec()),
        };
        // a missing `.mtl` is not an error (its faces take the default material); one that
        // cannot be read safely, or that `tobj` would panic on, is
        let problem = match read {
            Ok(b) => match check_mtl(&b) {
                Ok(()) => return tobj::load_mtl_buf(&mut &b[..]),
                Err(why) => why,
            },
            Err(specpoly_formats::Error::Missing { .. }) => {
                return Err(tobj::LoadError::OpenFileFailed)
            }
            Err(e) => e.to_string(),
        };
        *mtl_error.borrow_mut() = Some(problem);
        Err(tobj::LoadError::OpenFileFailed)
    };
    let (models, mtl) = tobj::load_obj_buf(&mut &bytes[..], &opts, load_mtl)
        .map_err(|e| mesh_error(path, format!("not a readable OBJ file: {e}")))?;
    if let Some(why) = mtl_error.into_inner() {
        return Err(mesh_error(path, format!("its material library: {why}")));
    }
    // a missing .mtl is not an error: its faces take the default material
    let mtl_names: Vec<String> = mtl
        .map(|m| m.into_iter().map(|m| m.name).collect())
        .unwrap_or_default();
    let before = soup.tris.len();
    for m in &models {
        let mesh = &m.mesh;
        let material = mesh
            .material_id
            .and_then(|i| mtl_names.get(i))
            .and_then(|n| place.map.get(n))
            .copied()
            .unwrap_or(place.default);
        let p = &mesh.positions;
        if p.len() % 3 != 0 {
            return Err(mesh_error(
                path,
                format!("model `{}`: positions are not triples", m.name),
            ));
        }
        let vertex = |i: u32| -> Result<V3> {
            let i = i as usize * 3;
            let v = p.get(i..i + 3).ok_or_else(|| {
                mesh_error(
                    path,
                    format!("model `{}`: a face refers to a missing vertex", m.name),
                )
            })?;
            let v = V3::new(v[0], v[1], v[2]);
            if !(v.x.is_finite() && v.y.is_finite() && v.z.is_finite()) {
                return Err(mesh_error(
                    path,
                    format!("model `{}`: a vertex is not finite", m.name),
                ));
            }
            placed(v, place).map_err(|why| mesh_error(path, format!("model `{}`: {why}", m.name)))
        };
        // vertex normals (`vn`), one per position after tobj's single indexing; scaling and
        // translating the mesh leaves them as they are
        let nv = &mesh.normals;
        let normal = |i: u32| -> Option<V3> {
            let i = i as usize * 3;
            nv.get(i..i + 3).map(|n| V3::new(n[0], n[1], n[2]))
        };
        for f in mesh.indices.chunks_exact(3) {
            let t = [vertex(f[0])?, vertex(f[1])?, vertex(f[2])?];
            match (normal(f[0]), normal(f[1]), normal(f[2])) {
                (Some(a), Some(b), Some(c)) => soup.push_smooth(t, [a, b, c], material),
                _ => soup.push(t, material),
            }
            if soup.tris.len() > MAX_TRIANGLES {
                return Err(mesh_error(
                    path,
                    format!("more than {MAX_TRIANGLES} triangles in the scene",),
                ));
            }
        }
    }
    Ok(soup.tris.len() - before)
}

/// Checks a `.mtl` file's colour lines before `tobj` parses them: `Ka`/`Kd`/`Ks`/`Ke` with fewer
/// than three values make `tobj` 4 panic (it unwraps a short array), so they are refused here
/// with the line.
fn check_mtl(bytes: &[u8]) -> std::result::Result<(), String> {
    let text = String::from_utf8_lossy(bytes);
    for (i, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        if let Some(k @ ("Ka" | "Kd" | "Ks" | "Ke")) = words.next() {
            if words.count() < 3 {
                return Err(format!("line {}: `{k}` needs three numbers", i + 1));
            }
        }
    }
    Ok(())
}

/// Checks an OBJ file's face indices (`f`, `l`: `v`, `v/vt`, `v//vn`, `v/vt/vn`) before `tobj`
/// resolves them: a negative (relative) index reaching before the first element of its kind
/// so far, or a positive one beyond the file's count of that kind (when it has any), is
/// refused with its line. `tobj` 4 turns such an index into a huge `usize` and multiplies it
/// unchecked (`vt * 2`, `vn * 3`: an overflow panic with overflow checks, a wrapped index
/// without). Lines are split and counted as `tobj` does (`v`, `vt`, `vn` lines, words
/// separated by white space).
fn check_face_indices(bytes: &[u8]) -> std::result::Result<(), String> {
    const KIND: [&str; 3] = ["v", "vt", "vn"];
    let text = String::from_utf8_lossy(bytes);
    let count = |w: Option<&str>| KIND.iter().position(|k| w == Some(*k));
    let mut total = [0usize; 3];
    for line in text.lines() {
        if let Some(k) = count(line.split_whitespace().next()) {
            total[k] += 1;
        }
    }
    let mut seen = [0usize; 3];
    for (n, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        let first = words.next();
        if let Some(k) = count(first) {
            seen[k] += 1;
            continue;
        }
        if !matches!(first, Some("f" | "l")) {
            continue;
        }
        for word in words {
            for (k, part) in word.split('/').enumerate().take(3) {
                let Ok(i) = part.parse::<isize>() else {
                    continue;
                };
                let kind = KIND[k];
                if i < 0 && i.unsigned_abs() > seen[k] {
                    return Err(format!(
                        "line {}: index {i} refers before the first `{kind}` ({} so far)",
                        n + 1,
                        seen[k]
                    ));
                }
                if i > 0 && total[k] > 0 && i.unsigned_abs() > total[k] {
                    return Err(format!(
                        "line {}: index {i} is beyond the file's {} `{kind}` lines",
                        n + 1,
                        total[k]
                    ));
                }
            }
        }
    }
    Ok(())
}

/// A procedural test mesh: a unit sphere subdivided as a latitude–longitude grid of `n × 2n`
/// quads (`4n²` triangles less the poles' degenerate ones), radius `r`, centre `c`.
pub fn uv_sphere(n: usize, c: V3, r: f32, material: usize, soup: &mut TriangleSoup) {
    let p = |i: usize, j: usize| {
        let th = std::f32::consts::PI * i as f32 / n as f32;
        let ph = std::f32::consts::PI * j as f32 / n as f32;
        c + V3::new(th.sin() * ph.cos(), th.cos(), th.sin() * ph.sin()) * r
    };
    for i in 0..n {
        for j in 0..2 * n {
            soup.push_quad(
                [p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1)],
                material,
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::geometry::ray;
    use super::*;

    /// The BVH finds the same nearest hit as the analytic sphere the mesh approximates,
    /// within the tessellation's sagitta.
    #[test]
    fn sphere_mesh_hits_like_the_sphere() {
        let mut s = TriangleSoup::default();
        uv_sphere(64, V3::new(0.0, 0.0, 5.0), 1.0, 3, &mut s);
        let t = s.build();
        assert!(t.len() > 16_000);
        let sagitta = 1.0 - (std::f32::consts::PI / 64.0).cos();
        for k in 0..50 {
            let a = k as f32 * 0.0035 - 0.09;
            let r = ray([0.0; 3], [a, 0.5 * a, 1.0]);
            let exact = super::super::geometry::Shape::Sphere {
                center: V3::new(0.0, 0.0, 5.0),
                radius: 1.0,
            }
            .intersect(&r, 1e9)
            .unwrap();
            let (tt, n, m) = t.intersect(&r, 1e9).unwrap();
            assert_eq!(m, Owner::Material(3));
            assert!((tt - exact.t).abs() <= 2.0 * sagitta, "{tt} vs {}", exact.t);
            assert!(n.dot(exact.normal).abs() > 0.99);
        }
        assert!(t.intersect(&ray([0.0; 3], [0.0, 1.0, 0.0]), 1e9).is_none());
        // a segment through the sphere crosses it twice; one ending inside, once
        let mut n = 0;
        // (off the tessellation's vertices and edges)
        t.crossings(&ray([0.0; 3], [0.011, 0.017, 1.0]), 1e9, |_| {
            n += 1;
            true
        });
        assert_eq!(n, 2);
        let mut n = 0;
        t.crossings(&ray([0.0; 3], [0.011, 0.017, 1.0]), 5.0, |_| {
            n += 1;
            true
        });
        assert_eq!(n, 1);
    }

    /// Vertex normals interpolated at the hit follow the sphere a coarse mesh approximates:
    /// the worst angle to the exact normal is a small fraction of the flat normals'.
    #[test]
    fn smooth_normals_follow_the_sphere() {
        let (c, n) = (V3::new(0.0, 0.0, 5.0), 8);
        let mut flat = TriangleSoup::default();
        uv_sphere(n, c, 1.0, 0, &mut flat);
        let mut smooth = TriangleSoup::default();
        for t in &flat.tris {
            smooth.push_smooth(*t, t.map(|p| p - c), 0);
        }
        let (flat, smooth) = (flat.build(), smooth.build());
        let (mut worst_flat, mut worst_smooth) = (0.0f32, 0.0f32);
        for k in 0..400 {
            let (a, b) = (
                (k % 20) as f32 * 0.009 - 0.09,
                (k / 20) as f32 * 0.009 - 0.09,
            );
            let r = ray([0.0; 3], [a, b, 1.0]);
            let exact = super::super::geometry::Shape::Sphere {
                center: c,
                radius: 1.0,
            }
            .intersect(&r, 1e9)
            .unwrap();
            let p = r.origin + r.dir * smooth.intersect(&r, 1e9).unwrap().0;
            let want = (p - c) * (1.0 / (p - c).length());
            let angle = |m: V3| m.dot(want).clamp(-1.0, 1.0).acos();
            worst_smooth = worst_smooth.max(angle(smooth.intersect(&r, 1e9).unwrap().1));
            worst_flat = worst_flat.max(angle(flat.intersect(&r, 1e9).unwrap().1));
            assert!(exact.t > 0.0);
        }
        assert!(worst_flat > 0.1, "{worst_flat}");
        assert!(
            worst_smooth < 0.2 * worst_flat,
            "{worst_smooth} vs {worst_flat}"
        );
    }

    /// An OBJ with `vn` and a PLY with `nx ny nz`: at a vertex the normal is that vertex's,
    /// at the centroid the normalised mean of the three; without normals, the face's.
    #[test]
    fn files_vertex_normals_are_interpolated() {
        let dir = tempfile::tempdir().unwrap();
        let obj = dir.path().join("t.obj");
        std::fs::write(
            &obj,
            "v -1 -1 2\nv 1 -1 2\nv 0 1 2\nvn 0.6 0 -0.8\nvn 0 0.6 -0.8\nvn 0 0 -1\nf 1//1 2//2 3//3\n",
        )
        .unwrap();
        let ply = dir.path().join("t.ply");
        std::fs::write(
            &ply,
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
             property float z\nproperty float nx\nproperty float ny\nproperty float nz\n\
             element face 1\nproperty list uchar int vertex_indices\nend_header\n\
             -1 -1 2 0.6 0 -0.8\n1 -1 2 0 0.6 -0.8\n0 1 2 0 0 -1\n3 0 1 2\n",
        )
        .unwrap();
        let map = BTreeMap::new();
        let place = ObjPlacement {
            scale: 1.0,
            translate: V3::new(0.0, 0.0, 0.0),
            default: 0,
            map: &map,
        };
        let mean = V3::new(0.6, 0.6, -2.6);
        let mean = mean * (1.0 / mean.length());
        for path in [&obj, &ply] {
            let mut s = TriangleSoup::default();
            if path == &obj {
                load_obj(path, &place, &mut s).unwrap();
            } else {
                crate::mesh_ply::load_ply(path, &place, &mut s).unwrap();
            }
            let t = s.build();
            let at = |x: f32, y: f32| {
                t.intersect(&ray([x, y, 0.0], [0.0, 0.0, 1.0]), 1e9)
                    .unwrap()
                    .1
            };
            let n = at(-1.0 / 3.0 + 1.0 / 3.0, -1.0 / 3.0);
            assert!((n.dot(mean) - 1.0).abs() < 1e-5, "{path:?}: {n:?}");
            let n = at(-0.999, -0.9985);
            assert!(
                (n.dot(V3::new(0.6, 0.0, -0.8)) - 1.0).abs() < 1e-3,
                "{path:?}: {n:?}"
            );
        }
        // the same triangle without normals is flat
        std::fs::write(&obj, "v -1 -1 2\nv 1 -1 2\nv 0 1 2\nf 1 2 3\n").unwrap();
        let mut s = TriangleSoup::default();
        load_obj(&obj, &place, &mut s).unwrap();
        assert!(s.shading.is_empty());
        let n = s
            .build()
            .intersect(&ray([0.0, -0.3, 0.0], [0.0, 0.0, 1.0]), 1e9)
            .unwrap()
            .1;
        assert!((n.z.abs() - 1.0).abs() < 1e-6);
    }

    /// A material library `tobj` would panic on (a colour with two numbers) or one that is not
    /// a regular file (a device) is a one-line error; a missing one leaves the default material.
    #[test]
    fn material_libraries_are_checked_before_tobj() {
        let dir = tempfile::tempdir().unwrap();
        let obj = dir.path().join("t.obj");
        let map = BTreeMap::new();
        let place = ObjPlacement {
            scale: 1.0,
            translate: V3::new(0.0, 0.0, 0.0),
            default: 7,
            map: &map,
        };
        let tri = "v -1 -1 2\nv 1 -1 2\nv 0 1 2\nusemtl a\nf 1 2 3\n";
        let load = |mtllib: &str| {
            std::fs::write(&obj, format!("mtllib {mtllib}\n{tri}")).unwrap();
            let mut s = TriangleSoup::default();
            load_obj(&obj, &place, &mut s).map(|_| s)
        };
        std::fs::write(dir.path().join("short.mtl"), "newmtl a\nKd 0.5 0.5\n").unwrap();
        let e = load("short.mtl").unwrap_err().to_string();
        assert!(
            e.contains("line 2") && e.contains("Kd") && !e.contains('\n'),
            "{e}"
        );
        let e = load("/dev/zero").unwrap_err().to_string();
        assert!(e.contains("/dev/zero"), "{e}");
        let s = load("absent.mtl").unwrap();
        assert_eq!(s.owners, [Owner::Material(7)]);
    }

    /// A vertex beyond ±10¹⁸ (the BVH builder panicked above ≈ 10²⁷) is a one-line error, in
    /// OBJ and PLY, and so is one that the scene's scale takes there.
    #[test]
    fn vertices_beyond_the_coordinate_bound_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let map = BTreeMap::new();
        let mut place = ObjPlacement {
            scale: 1.0,
            translate: V3::new(0.0, 0.0, 0.0),
            default: 0,
            map: &map,
        };
        let obj = dir.path().join("t.obj");
        std::fs::write(&obj, "v 0 0 3\nv 1 0 3\nv 0 3e27 3\nf 1 2 3\n").unwrap();
        let e = load_obj(&obj, &place, &mut TriangleSoup::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains("beyond") && !e.contains('\n'), "{e}");
        let ply = dir.path().join("t.ply");
        std::fs::write(
            &ply,
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
             property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
             end_header\n0 0 3\n1 0 3\n0 2e19 3\n3 0 1 2\n",
        )
        .unwrap();
        let e = crate::mesh_ply::load_ply(&ply, &place, &mut TriangleSoup::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains("vertex 2") && e.contains("beyond"), "{e}");
        std::fs::write(&obj, "v 0 0 3\nv 1 0 3\nv 0 1 3\nf 1 2 3\n").unwrap();
        assert!(load_obj(&obj, &place, &mut TriangleSoup::default()).is_ok());
        place.scale = 1e30;
        assert!(load_obj(&obj, &place, &mut TriangleSoup::default()).is_err());
    }

    /// Repeated faces (the same vertices in any order, the same owner) are built once: 20 000
    /// copies of a face took 25 s and overflowed the BVH's traversal depth.
    #[test]
    fn repeated_faces_are_built_once() {
        let mut s = TriangleSoup::default();
        let t = [
            V3::new(0.0, 0.0, 3.0),
            V3::new(1.0, 0.0, 3.0),
            V3::new(0.0, 1.0, 3.0),
        ];
        for k in 0..20_000 {
            s.push([t[k % 3], t[(k + 1) % 3], t[(k + 2) % 3]], 0);
        }
        s.push(t, 1); // another material on the same face stays
        let b = s.build();
        assert_eq!(b.len(), 2);
        let hit = b
            .intersect(&ray([0.2, 0.2, 0.0], [0.0, 0.0, 1.0]), 1e9)
            .unwrap();
        assert!((hit.0 - 3.0).abs() < 1e-6);
    }

    #[test]
    fn face_indices_outside_their_elements_are_refused() {
        let v = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\n";
        let ok = |f: &str| check_face_indices(format!("{v}{f}\n").as_bytes());
        assert_eq!(ok("f 1/1 2/1 3/1"), Ok(()));
        assert_eq!(ok("f -3/-1 -2/-1 -1/-1"), Ok(()));
        // no `vn` lines: `tobj` ignores normal indices, and so does the check
        assert_eq!(ok("f 1//9 2//9 3//9"), Ok(()));
        assert_eq!(
            ok("f -4 -2 -1"),
            Err("line 5: index -4 refers before the first `v` (3 so far)".into())
        );
        assert_eq!(
            ok("l 1/2 2/1"),
            Err("line 5: index 2 is beyond the file's 1 `vt` lines".into())
        );
        // a vertex defined after the face counts (as `tobj` resolves positive indices late)
        assert_eq!(ok("f 1 2 4\nv 1 1 1"), Ok(()));
    }

    #[test]
    fn quads_split_into_two_triangles() {
        let mut s = TriangleSoup::default();
        let q = [
            V3::new(-1.0, -1.0, 2.0),
            V3::new(1.0, -1.0, 2.0),
            V3::new(1.0, 1.0, 2.0),
            V3::new(-1.0, 1.0, 2.0),
        ];
        s.push_quad(q, 0);
        let t = s.build();
        assert_eq!(t.len(), 2);
        for (x, y) in [(0.5, 0.2), (-0.5, -0.2), (0.9, -0.8), (-0.8, 0.9)] {
            let (tt, _, _) = t
                .intersect(&ray([x, y, 0.0], [0.0, 0.0, 1.0]), 1e9)
                .unwrap();
            assert!((tt - 2.0).abs() < 1e-5);
        }
        assert!(t
            .intersect(&ray([1.5, 0.0, 0.0], [0.0, 0.0, 1.0]), 1e9)
            .is_none());
    }
}
