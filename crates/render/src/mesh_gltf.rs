//! glTF 2.0 files (Khronos, <https://registry.khronos.org/glTF/specs/2.0/glTF-2.0.html>):
//! `.gltf` (JSON with its buffers in `.bin` files or `data:` URIs) and `.glb` (binary), parsed
//! with the `gltf` crate (JSON and GLB chunks only: no image decoder, no file access of its own).
//!
//! **Geometry.** The nodes of the file's default scene (else its first scene, else every node
//! that is no node's child) are walked from their roots, each node's matrix (or translation ·
//! rotation · scale) composed onto its parent's, and every mesh primitive of mode `TRIANGLES`,
//! `TRIANGLE_STRIP` or `TRIANGLE_FAN` (others, points and lines, have no area and are skipped)
//! becomes triangles: `POSITION` (float VEC3), `NORMAL` if present (smooth shading, transformed
//! by the inverse transpose of the node's matrix), `indices` (unsigned byte, short or int) or
//! the vertices in order. Primitives whose material has a texture also give `TEXCOORD_0`
//! (float, or normalized unsigned byte or short), and those with a normal map `TANGENT`
//! (with `NORMAL`; else tangents are derived from the texture coordinates,
//! [`crate::mesh::Surface::from_uv`]). Images ([`GltfFile::image`]) are PNG files beside the
//! file, `data:` URIs or buffer views, decoded by [`crate::texture::decode_png`].
//!
//! **Frame.** glTF is right-handed with +Y up and +Z toward the viewer of the model's front;
//! the scene frame is left-handed (x right, y up, z into the screen). The loader maps a glTF
//! point `(x, y, z)` to `(x, y, −z)`, so a model and its cameras seen here look as in a glTF
//! viewer (not mirrored). A mesh entry's `scale` and `translate` apply after that.
//!
//! **Materials.** A primitive takes the scene material named like its glTF material, else the
//! one named `gltf#INDEX` (the glTF material's index; what a glTF scene file makes, see
//! [`crate::scene_gltf`]), else the entry's `material`.
//!
//! **Bounded reading.** The file is read through [`specpoly_formats::read::bytes`] (the
//! `--max-input-size` limit), and so is every external buffer; the file and its buffers
//! together may not exceed that limit. Every buffer view and accessor is checked to lie inside
//! its data before it is read (the `gltf` crate's own readers index without checking), a GLB
//! header shorter than itself is refused before the crate reads it (its length arithmetic
//! would underflow), a primitive whose `POSITION` names a missing accessor is refused before
//! the crate validates the file (its validation indexes with it unchecked), children that
//! form a cycle are refused, node trees are walked at most
//! [`MAX_NODE_VISITS`] node visits in total (subtrees shared many times in malformed files),
//! and a non-finite transform is refused. Every error is one line naming the file and the JSON path (`accessors[3]`,
//! `nodes[2].matrix`, `buffers[0].uri`).

use crate::error::{Error, Result};
use crate::geometry::V3;
use crate::mesh::{mesh_error, ObjPlacement, Surface, TriangleSoup, MAX_TRIANGLES};
use glam::{Mat3, Mat4, Vec3};
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::Mode;
use gltf::Semantic;
use std::path::{Path, PathBuf};

/// Node visits in one walk of a file's node trees at most: a tree of a million nodes is far
/// beyond published models, and a malformed file whose children form a cycle or a lattice of
/// shared subtrees stops here.
pub const MAX_NODE_VISITS: usize = 1_000_000;

/// A glTF file read and checked: the document and the data of each buffer.
pub struct GltfFile {
    /// The file.
    pub path: PathBuf,
    /// The parsed document.
    pub doc: gltf::Document,
    /// Each buffer's bytes (at least its `byteLength`).
    buffers: Vec<Vec<u8>>,
    /// Where files its `uri`s name are read (buffers, images); `None`: none are read.
    folder: Option<PathBuf>,
}

/// A node placed in the scene: its index and its world matrix (glTF frame).
#[derive(Clone, Copy, Debug)]
pub struct Placed {
    /// The node's index in `nodes`.
    pub node: usize,
    /// Its world matrix (the product of its ancestors' and its own), glTF's frame.
    pub world: Mat4,
}

/// glTF's right-handed frame to the scene's left-handed one: `(x, y, z) → (x, y, −z)`.
pub fn to_scene(v: Vec3) -> V3 {
    V3::new(v.x, v.y, -v.z)
}

/// Decodes standard base64 (RFC 4648 §4, padding optional, no whitespace); `None` if malformed.
fn base64(text: &str) -> Option<Vec<u8>> {
    let digit = |c: u8| -> Option<u32> {
        Some(match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' => 62,
            b'/' => 63,
            _ => return None,
        } as u32)
    };
    let body = text.trim_end_matches('=');
    if text.len() - body.len() > 2 || body.len() % 4 == 1 {
        return None;
    }
    let mut out = Vec::with_capacity(body.len() / 4 * 3 + 2);
    for chunk in body.as_bytes().chunks(4) {
        let mut acc = 0u32;
        for (i, &c) in chunk.iter().enumerate() {
            acc |= digit(c)? << (18 - 6 * i);
        }
        let bytes = acc.to_be_bytes();
        out.extend_from_slice(&bytes[1..chunk.len()]);
    }
    Some(out)
}

/// `%XX` escapes of a relative URI decoded (RFC 3986 §2.1); `None` if malformed.
fn percent_decode(uri: &str) -> Option<String> {
    let b = uri.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'%' {
            let hex = std::str::from_utf8(b.get(i + 1..i + 3)?).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(b[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

/// The component size in bytes.
fn component_size(t: DataType) -> usize {
    match t {
        DataType::I8 | DataType::U8 => 1,
        DataType::I16 | DataType::U16 => 2,
        DataType::U32 | DataType::F32 => 4,
    }
}

/// Checks that every mesh primitive's `POSITION` names an accessor that exists, before the
/// `gltf` crate validates the file: its validation indexes `accessors` with that number
/// unchecked (a panic; `gltf-json` 1.4 `mesh.rs`). A file the check cannot parse is left to
/// the crate, which reports it.
fn check_positions(bytes: &[u8]) -> std::result::Result<(), String> {
    use gltf::json::mesh::Semantic;
    use gltf::json::validation::Checked;
    let glb;
    let json: &[u8] = if bytes.starts_with(b"glTF") {
        match gltf::Glb::from_slice(bytes) {
            Ok(g) => {
                glb = g;
                &glb.json
            }
            Err(_) => return Ok(()),
        }
    } else {
        bytes
    };
    let Ok(root) = gltf::json::Root::from_slice(json) else {
        return Ok(());
    };
    for (i, m) in root.meshes.iter().enumerate() {
        for (j, p) in m.primitives.iter().enumerate() {
            if let Some(a) = p.attributes.get(&Checked::Valid(Semantic::Positions)) {
                if a.value() >= root.accessors.len() {
                    return Err(format!(
                        "meshes[{i}].primitives[{j}].attributes.POSITION: accessor {} does not exist (the file has {})",
                        a.value(),
                        root.accessors.len()
                    ));
                }
            }
        }
    }
    Ok(())
}

impl GltfFile {
    /// Reads and checks `path` (a `.gltf` or `.glb` file) and its buffers.
    pub fn open(path: &Path) -> Result<Self> {
        let bytes = specpoly_formats::read::bytes(path)?;
        Self::from_bytes(path, bytes, path.parent().or(Some(Path::new("."))))
    }

    /// [`GltfFile::open`] of a file's bytes already read; `path` names it in errors. External
    /// buffers and images (`uri` a file name) are read from `folder`; with `None` they are
    /// refused (a file-less reader: the fuzz target).
    pub fn from_bytes(path: &Path, bytes: Vec<u8>, folder: Option<&Path>) -> Result<Self> {
        let bad = |why: String| mesh_error(path, why);
        if bytes.starts_with(b"glTF") {
            // the crate subtracts the header's size from its length field unchecked
            let length = bytes
                .get(8..12)
                .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize);
            if !length.is_some_and(|l| (20..=bytes.len()).contains(&l)) {
                return Err(bad(format!(
                    "not a readable GLB file: its header gives a length of {} bytes for a file of {}",
                    length.map_or("no".into(), |l| l.to_string()),
                    bytes.len()
                )));
            }
        }
        check_positions(&bytes).map_err(bad)?;
        let gltf::Gltf { document, blob } = gltf::Gltf::from_slice(&bytes).map_err(|e| {
            let text = match e {
                gltf::Error::Validation(v) => v
                    .iter()
                    .take(3)
                    .map(|(p, e)| format!("{p}: {e}"))
                    .collect::<Vec<_>>()
                    .join("; "),
                e => e.to_string(),
            };
            bad(format!(
                "not a valid glTF 2.0 file: {}",
                text.replace(['\n', '\r'], " ")
            ))
        })?;
        let mut total = bytes.len() as u64;
        let limit = specpoly_formats::read::max_input_bytes();
        let mut blob = blob;
        let mut buffers = Vec::new();
        for b in document.buffers() {
            let at = format!("buffers[{}]", b.index());
            let data = match b.source() {
                gltf::buffer::Source::Bin => blob.take().ok_or_else(|| {
                    bad(format!(
                        "{at}: refers to the GLB binary chunk, which the file has not (or which an earlier buffer took)"
                    ))
                })?,
                gltf::buffer::Source::Uri(uri) => {
                    if let Some(rest) = uri.strip_prefix("data:") {
                        let payload = rest
                            .split_once(";base64,")
                            .map(|(_, p)| p)
                            .ok_or_else(|| bad(format!("{at}.uri: a data URI that is not base64")))?;
                        base64(payload)
                            .ok_or_else(|| bad(format!("{at}.uri: malformed base64 data")))?
                    } else {
                        let name = percent_decode(uri)
                            .filter(|n| !n.contains("://"))
                            .ok_or_else(|| {
                                bad(format!("{at}.uri `{uri}`: only relative file names and data URIs are read"))
                            })?;
                        let folder = folder.ok_or_else(|| {
                            bad(format!("{at}.uri `{uri}`: external buffers are not read here"))
                        })?;
                        specpoly_formats::read::bytes(&folder.join(&name))
                            .map_err(|e| bad(format!("{at}.uri: {e}")))?
                    }
                }
            };
            total += data.len() as u64;
            if total > limit {
                return Err(bad(format!(
                    "{at}: the file and its buffers exceed the input limit of {} (--max-input-size)",
                    specpoly_formats::read::size_text(limit)
                )));
            }
            if data.len() < b.length() {
                return Err(bad(format!(
                    "{at}: byteLength {} but its data has {} bytes",
                    b.length(),
                    data.len()
                )));
            }
            buffers.push(data);
        }
        for v in document.views() {
            let end = v.offset().checked_add(v.length());
            if end.is_none_or(|e| e > v.buffer().length()) {
                return Err(bad(format!(
                    "bufferViews[{}]: bytes {}..{} lie outside buffers[{}] ({} bytes)",
                    v.index(),
                    v.offset(),
                    end.map_or("∞".into(), |e| e.to_string()),
                    v.buffer().index(),
                    v.buffer().length()
                )));
            }
        }
        Ok(Self {
            path: path.to_path_buf(),
            doc: document,
            buffers,
            folder: folder.map(Path::to_path_buf),
        })
    }

    /// The decoded image `images[i]` (a PNG in a buffer view, a `data:` URI or a file beside
    /// the glTF file, read through the `--max-input-size` limit; its decoded size is bounded
    /// too, before it is allocated: [`crate::texture::decode_png`]).
    pub fn image(&self, i: usize) -> Result<crate::texture::Image> {
        let at = format!("images[{i}]");
        let image = self
            .doc
            .images()
            .nth(i)
            .ok_or_else(|| self.bad(format!("{at}: no such image")))?;
        let owned;
        let bytes: &[u8] = match image.source() {
            gltf::image::Source::View { view, .. } => {
                &self.buffers[view.buffer().index()][view.offset()..view.offset() + view.length()]
            }
            gltf::image::Source::Uri { uri, .. } => {
                owned = self.uri_bytes(uri, &format!("{at}.uri"))?;
                &owned
            }
        };
        if bytes.starts_with(&[0xFF, 0xD8, 0xFF]) {
            return Err(self.bad(format!(
                "{at}: a JPEG image; textures are read from PNG images only"
            )));
        }
        crate::texture::decode_png(bytes, specpoly_formats::read::max_input_bytes())
            .map_err(|why| self.bad(format!("{at}: {why}")))
    }

    /// The bytes a buffer's or an image's `uri` names: a base64 `data:` URI, or a relative
    /// file name (percent-escapes decoded) beside the glTF file, read through the bounded read.
    fn uri_bytes(&self, uri: &str, at: &str) -> Result<Vec<u8>> {
        if let Some(rest) = uri.strip_prefix("data:") {
            let payload = rest
                .split_once(";base64,")
                .map(|(_, p)| p)
                .ok_or_else(|| self.bad(format!("{at}: a data URI that is not base64")))?;
            return base64(payload).ok_or_else(|| self.bad(format!("{at}: malformed base64 data")));
        }
        let name = percent_decode(uri)
            .filter(|n| !n.contains("://"))
            .ok_or_else(|| {
                self.bad(format!(
                    "{at} `{uri}`: only relative file names and data URIs are read"
                ))
            })?;
        let folder = self
            .folder
            .as_ref()
            .ok_or_else(|| self.bad(format!("{at} `{uri}`: external files are not read here")))?;
        specpoly_formats::read::bytes(&folder.join(&name))
            .map_err(|e| self.bad(format!("{at}: {e}")))
    }

    fn bad(&self, why: String) -> Error {
        mesh_error(&self.path, why)
    }

    /// The bytes of accessor `a`'s elements: `(data, start, stride, element size)`, checked to
    /// lie inside its buffer view; `what` names its use in errors.
    fn elements(&self, a: &gltf::Accessor<'_>, what: &str) -> Result<(&[u8], usize, usize)> {
        let at = format!("accessors[{}] ({what})", a.index());
        if a.sparse().is_some() {
            return Err(self.bad(format!("{at}: sparse accessors are not read")));
        }
        let view = a
            .view()
            .ok_or_else(|| self.bad(format!("{at}: has no bufferView")))?;
        let size = component_size(a.data_type()) * a.dimensions().multiplicity();
        let stride = view.stride().unwrap_or(size);
        if stride < size {
            return Err(self.bad(format!(
                "{at}: byteStride {stride} is below the element size {size}"
            )));
        }
        // the last element ends at offset + stride·(count − 1) + size, inside the view
        let end = (a.count() as u64)
            .checked_sub(1)
            .map(|n| a.offset() as u64 + n * stride as u64 + size as u64)
            .unwrap_or(0);
        if end > view.length() as u64 {
            return Err(self.bad(format!(
                "{at}: {} elements from byte {} need {end} bytes, its bufferViews[{}] has {}",
                a.count(),
                a.offset(),
                view.index(),
                view.length()
            )));
        }
        let data =
            &self.buffers[view.buffer().index()][view.offset()..view.offset() + view.length()];
        Ok((&data[a.offset().min(data.len())..], stride, size))
    }

    /// A float VEC3 accessor's elements.
    fn vec3s(&self, a: &gltf::Accessor<'_>, what: &str) -> Result<Vec<Vec3>> {
        if a.data_type() != DataType::F32 || a.dimensions() != Dimensions::Vec3 {
            return Err(self.bad(format!(
                "accessors[{}] ({what}): {:?} {:?}, where glTF requires float VEC3",
                a.index(),
                a.data_type(),
                a.dimensions()
            )));
        }
        let (data, stride, _) = self.elements(a, what)?;
        let f = |b: &[u8], k: usize| {
            f32::from_le_bytes([b[4 * k], b[4 * k + 1], b[4 * k + 2], b[4 * k + 3]])
        };
        Ok((0..a.count())
            .map(|i| {
                let e = &data[i * stride..i * stride + 12];
                Vec3::new(f(e, 0), f(e, 1), f(e, 2))
            })
            .collect())
    }

    /// An index accessor's elements (unsigned byte, short or int scalars).
    fn indices(&self, a: &gltf::Accessor<'_>) -> Result<Vec<u32>> {
        let (data, stride, _) = self.elements(a, "indices")?;
        if a.dimensions() != Dimensions::Scalar {
            return Err(self.bad(format!("accessors[{}] (indices): not SCALAR", a.index())));
        }
        let read: fn(&[u8]) -> u32 = match a.data_type() {
            DataType::U8 => |b| b[0] as u32,
            DataType::U16 => |b| u16::from_le_bytes([b[0], b[1]]) as u32,
            DataType::U32 => |b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
            t => {
                return Err(self.bad(format!(
                    "accessors[{}] (indices): {t:?}, where glTF requires an unsigned type",
                    a.index()
                )))
            }
        };
        Ok((0..a.count()).map(|i| read(&data[i * stride..])).collect())
    }

    /// The nodes of the scene to render with their world matrices, parents before children:
    /// the default scene's, else the first scene's, else every root node's.
    pub fn placed_nodes(&self) -> Result<Vec<Placed>> {
        let roots: Vec<usize> = match self
            .doc
            .default_scene()
            .or_else(|| self.doc.scenes().next())
        {
            Some(s) => s.nodes().map(|n| n.index()).collect(),
            None => {
                let mut child = vec![false; self.doc.nodes().len()];
                for n in self.doc.nodes() {
                    for c in n.children() {
                        child[c.index()] = true;
                    }
                }
                (0..child.len()).filter(|&i| !child[i]).collect()
            }
        };
        let nodes: Vec<gltf::Node<'_>> = self.doc.nodes().collect();
        let mut out = Vec::new();
        let mut stack: Vec<(usize, Mat4, usize)> = roots
            .iter()
            .rev()
            .map(|&r| (r, Mat4::IDENTITY, 0))
            .collect();
        while let Some((i, parent, depth)) = stack.pop() {
            // a path longer than the node count repeats a node: the children form a cycle
            if depth > nodes.len() {
                return Err(self.bad(format!("nodes[{i}]: the children form a cycle")));
            }
            if out.len() >= MAX_NODE_VISITS {
                return Err(self.bad(format!(
                    "the node trees visit more than {MAX_NODE_VISITS} nodes (subtrees shared many times)"
                )));
            }
            let n = &nodes[i];
            let (local, field) = match n.transform() {
                gltf::scene::Transform::Matrix { matrix } => {
                    (Mat4::from_cols_array_2d(&matrix), "matrix")
                }
                gltf::scene::Transform::Decomposed {
                    translation,
                    rotation,
                    scale,
                } => (
                    Mat4::from_scale_rotation_translation(
                        Vec3::from(scale),
                        glam::Quat::from_array(rotation),
                        Vec3::from(translation),
                    ),
                    "translation/rotation/scale",
                ),
            };
            let world = parent * local;
            if !local.is_finite() || !world.is_finite() {
                return Err(self.bad(format!("nodes[{i}].{field}: not finite")));
            }
            out.push(Placed { node: i, world });
            for c in n.children().collect::<Vec<_>>().into_iter().rev() {
                stack.push((c.index(), world, depth + 1));
            }
        }
        Ok(out)
    }

    /// A float VEC2, or normalized unsigned byte or short VEC2 accessor's elements (glTF's
    /// `TEXCOORD_n` types).
    fn vec2s(&self, a: &gltf::Accessor<'_>, what: &str) -> Result<Vec<[f32; 2]>> {
        let (data, stride, _) = self.elements(a, what)?;
        let ok = a.dimensions() == Dimensions::Vec2
            && (a.data_type() == DataType::F32
                || (a.normalized() && matches!(a.data_type(), DataType::U8 | DataType::U16)));
        if !ok {
            return Err(self.bad(format!(
                "accessors[{}] ({what}): {:?} {:?}, where glTF requires float, or normalized unsigned byte or short, VEC2",
                a.index(),
                a.data_type(),
                a.dimensions()
            )));
        }
        let t = a.data_type();
        let read = |e: &[u8], k: usize| -> f32 {
            match t {
                DataType::U8 => e[k] as f32 / 255.0,
                DataType::U16 => u16::from_le_bytes([e[2 * k], e[2 * k + 1]]) as f32 / 65535.0,
                _ => f32::from_le_bytes([e[4 * k], e[4 * k + 1], e[4 * k + 2], e[4 * k + 3]]),
            }
        };
        Ok((0..a.count())
            .map(|i| {
                let e = &data[i * stride..];
                [read(e, 0), read(e, 1)]
            })
            .collect())
    }

    /// A float VEC4 accessor's elements (glTF's `TANGENT`: xyz and the handedness w).
    fn vec4s(&self, a: &gltf::Accessor<'_>, what: &str) -> Result<Vec<[f32; 4]>> {
        if a.data_type() != DataType::F32 || a.dimensions() != Dimensions::Vec4 {
            return Err(self.bad(format!(
                "accessors[{}] ({what}): {:?} {:?}, where glTF requires float VEC4",
                a.index(),
                a.data_type(),
                a.dimensions()
            )));
        }
        let (data, stride, _) = self.elements(a, what)?;
        Ok((0..a.count())
            .map(|i| {
                let e = &data[i * stride..];
                [0, 1, 2, 3].map(|k| {
                    f32::from_le_bytes([e[4 * k], e[4 * k + 1], e[4 * k + 2], e[4 * k + 3]])
                })
            })
            .collect())
    }

    /// Every triangle of the placed meshes, in the scene frame ([`to_scene`]) before any mesh
    /// entry's placement, given to `f` one by one. Texture coordinates (`TEXCOORD_0`) are
    /// read for primitives whose material has a texture, tangents (`TANGENT`, else derived from
    /// the texture coordinates) for those whose material has a normal map.
    pub fn triangles(&self, mut f: impl FnMut(Tri) -> Result<()>) -> Result<()> {
        let nodes: Vec<gltf::Node<'_>> = self.doc.nodes().collect();
        for p in self.placed_nodes()? {
            let Some(mesh) = nodes[p.node].mesh() else {
                continue;
            };
            let normal_matrix = Mat3::from_mat4(p.world).inverse().transpose();
            for prim in mesh.primitives() {
                let at = format!("meshes[{}].primitives[{}]", mesh.index(), prim.index());
                let mode = prim.mode();
                if !matches!(
                    mode,
                    Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
                ) {
                    continue;
                }
                let pos = prim
                    .get(&Semantic::Positions)
                    .ok_or_else(|| self.bad(format!("{at}: no POSITION attribute")))?;
                let pos = self.vec3s(&pos, "POSITION")?;
                let same_count = |n: usize, what: &str| {
                    if n != pos.len() {
                        Err(self.bad(format!(
                            "{at}.attributes.{what}: {n} elements for {} positions",
                            pos.len()
                        )))
                    } else {
                        Ok(())
                    }
                };
                let normals = match prim.get(&Semantic::Normals) {
                    Some(a) => {
                        let n = self.vec3s(&a, "NORMAL")?;
                        same_count(n.len(), "NORMAL")?;
                        Some(n)
                    }
                    None => None,
                };
                let material = prim.material();
                let normal_map = material.normal_texture().is_some();
                let textured = normal_map
                    || material
                        .pbr_metallic_roughness()
                        .base_color_texture()
                        .is_some();
                let uvs = match (textured, prim.get(&Semantic::TexCoords(0))) {
                    (true, Some(a)) => {
                        let uv = self.vec2s(&a, "TEXCOORD_0")?;
                        same_count(uv.len(), "TEXCOORD_0")?;
                        Some(uv)
                    }
                    _ => None,
                };
                // glTF's tangents complete its normals: without normals (flat shading) the
                // tangents are derived as for a primitive without them
                let tangents = match (
                    normal_map && uvs.is_some() && normals.is_some(),
                    prim.get(&Semantic::Tangents),
                ) {
                    (true, Some(a)) => {
                        let t = self.vec4s(&a, "TANGENT")?;
                        same_count(t.len(), "TANGENT")?;
                        Some(t)
                    }
                    _ => None,
                };
                let idx: Vec<u32> = match prim.indices() {
                    Some(a) => self.indices(&a)?,
                    None => (0..pos.len() as u32).collect(),
                };
                let corners: Vec<[u32; 3]> = match mode {
                    Mode::Triangles => idx.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
                    // every other strip triangle reversed keeps the winding (irrelevant here:
                    // triangles are two-sided)
                    Mode::TriangleStrip => idx.windows(3).map(|w| [w[0], w[1], w[2]]).collect(),
                    _ => match idx.first() {
                        Some(&a) => idx[1..].windows(2).map(|w| [a, w[0], w[1]]).collect(),
                        None => vec![],
                    },
                };
                let world: Vec<V3> = pos
                    .iter()
                    .map(|&v| to_scene(p.world.transform_point3(v)))
                    .collect();
                let world_n: Option<Vec<V3>> = normals
                    .as_ref()
                    .map(|ns| ns.iter().map(|&n| to_scene(normal_matrix * n)).collect());
                // a given tangent T with handedness w means the bitangent w·(N × T) in the
                // model's frame: both are carried to the scene frame (which mirrors z), and
                // the handedness there is the sign that gives the carried bitangent back
                let world_t: Option<Vec<(V3, f32)>> = tangents.as_ref().map(|ts| {
                    ts.iter()
                        .enumerate()
                        .map(|(k, t)| {
                            let tv = Vec3::new(t[0], t[1], t[2]);
                            let n = normals.as_ref().map_or(Vec3::Z, |ns| normal_matrix * ns[k]);
                            let tw = p.world.transform_vector3(tv);
                            let b = n.cross(tw) * if t[3] < 0.0 { -1.0 } else { 1.0 };
                            let ts = to_scene(tw);
                            let bs = to_scene(b);
                            let ns = world_n.as_ref().map_or(V3::new(0.0, 0.0, 1.0), |w| w[k]);
                            let h = if ns.cross(ts).dot(bs) < 0.0 {
                                -1.0
                            } else {
                                1.0
                            };
                            (ts, h)
                        })
                        .collect()
                });
                for c in corners {
                    let get = |k: u32| {
                        world.get(k as usize).copied().ok_or_else(|| {
                            self.bad(format!(
                                "{at}.indices: index {k} is beyond its {} vertices",
                                world.len()
                            ))
                        })
                    };
                    let t = [get(c[0])?, get(c[1])?, get(c[2])?];
                    let n = world_n.as_ref().map(|ns| c.map(|k| ns[k as usize]));
                    let surface = uvs.as_ref().map(|uv| {
                        let uv = c.map(|k| uv[k as usize]);
                        let mut s = Surface::from_uv(&t, uv, n);
                        if let Some(wt) = &world_t {
                            s.tangent = c.map(|k| wt[k as usize].0);
                            s.handedness = wt[c[0] as usize].1;
                        }
                        s
                    });
                    f(Tri {
                        vertices: t,
                        normals: n,
                        surface,
                        material: prim.material().index(),
                    })?;
                }
            }
        }
        Ok(())
    }
}

/// One triangle of a glTF file ([`GltfFile::triangles`]), in the scene frame.
pub struct Tri {
    /// Its vertices.
    pub vertices: [V3; 3],
    /// Its vertex normals, if the primitive has them.
    pub normals: Option<[V3; 3]>,
    /// Its texture coordinates and tangents, if its material has textures.
    pub surface: Option<Surface>,
    /// Its glTF material's index.
    pub material: Option<usize>,
}

/// Reads a glTF file's triangles into `soup` (see the module docs for materials and frame);
/// returns how many it added.
pub fn load_gltf(path: &Path, place: &ObjPlacement<'_>, soup: &mut TriangleSoup) -> Result<usize> {
    add_gltf(&GltfFile::open(path)?, place, soup)
}

/// [`load_gltf`] of a file already read and checked.
pub fn add_gltf(
    file: &GltfFile,
    place: &ObjPlacement<'_>,
    soup: &mut TriangleSoup,
) -> Result<usize> {
    let path = &file.path;
    let materials: Vec<usize> = file
        .doc
        .materials()
        .enumerate()
        .map(|(i, m)| {
            m.name()
                .and_then(|n| place.map.get(n))
                .or_else(|| place.map.get(&format!("gltf#{i}")))
                .copied()
                .unwrap_or(place.default)
        })
        .collect();
    let before = soup.tris.len();
    file.triangles(|tri| {
        let material = tri
            .material
            .and_then(|i| materials.get(i))
            .copied()
            .unwrap_or(place.default);
        let mut placed = [V3::default(); 3];
        for k in 0..3 {
            placed[k] =
                crate::mesh::placed(tri.vertices[k], place).map_err(|why| mesh_error(path, why))?;
        }
        match (tri.normals, tri.surface) {
            (n, Some(s)) => soup.push_textured(placed, n, s, material),
            (Some(n), None) => soup.push_smooth(placed, n, material),
            (None, None) => soup.push(placed, material),
        }
        if soup.tris.len() > MAX_TRIANGLES {
            return Err(mesh_error(
                path,
                format!("more than {MAX_TRIANGLES} triangles in the scene"),
            ));
        }
        Ok(())
    })?;
    Ok(soup.tris.len() - before)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_and_percent_escapes_decode() {
        // RFC 4648 §10's test vectors
        for (text, plain) in [
            ("", ""),
            ("Zg==", "f"),
            ("Zm8=", "fo"),
            ("Zm9v", "foo"),
            ("Zm9vYg==", "foob"),
            ("Zm9vYmE=", "fooba"),
            ("Zm9vYmFy", "foobar"),
        ] {
            assert_eq!(base64(text).unwrap(), plain.as_bytes(), "{text}");
        }
        assert!(base64("Zm9v!").is_none());
        assert!(base64("Z").is_none());
        assert_eq!(percent_decode("a%20b.bin").unwrap(), "a b.bin");
        assert!(percent_decode("a%2").is_none());
    }
}
