//! PLY meshes (Turk's Polygon File Format, the Stanford scanning repository's format): ASCII
//! and binary, read with `ply-rs-bw` (the maintained fork of `ply-rs`). The `vertex` element's
//! `x y z` (float or double) and the `face` element's index list (`vertex_indices` or
//! `vertex_index`, any integer type) are used; polygons are triangulated as fans, like OBJ
//! faces. Vertex normals (`nx ny nz`, all three) make the mesh smooth-shaded ([`crate::mesh`]);
//! other elements and properties (colours, texture coordinates) are ignored.
//!
//! Bounded work: the file is read whole through [`specpoly_formats::read::bytes`] (at most 64 MiB) and
//! the header's element counts are checked against its size before the payload is parsed, so a
//! header announcing a billion vertices is refused before anything is allocated for them.

use crate::error::Result;
use crate::geometry::V3;
use crate::mesh::{mesh_error, ObjPlacement, TriangleSoup, MAX_TRIANGLES};
use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::{DefaultElement, Property};
use std::path::Path;

fn scalar(p: Option<&Property>) -> Option<f64> {
    Some(match p? {
        Property::Float(v) => *v as f64,
        Property::Double(v) => *v,
        Property::Int(v) => *v as f64,
        Property::UInt(v) => *v as f64,
        Property::Short(v) => *v as f64,
        Property::UShort(v) => *v as f64,
        Property::Char(v) => *v as f64,
        Property::UChar(v) => *v as f64,
        _ => return None,
    })
}

fn indices(p: Option<&Property>) -> Option<Vec<i64>> {
    Some(match p? {
        Property::ListInt(v) => v.iter().map(|&i| i as i64).collect(),
        Property::ListUInt(v) => v.iter().map(|&i| i as i64).collect(),
        Property::ListShort(v) => v.iter().map(|&i| i as i64).collect(),
        Property::ListUShort(v) => v.iter().map(|&i| i as i64).collect(),
        Property::ListChar(v) => v.iter().map(|&i| i as i64).collect(),
        Property::ListUChar(v) => v.iter().map(|&i| i as i64).collect(),
        _ => return None,
    })
}

/// The first line of a `ply-rs-bw` error: the rest is the parser's debug dump (the offending
/// line quoted with its newline, the grammar's expected set), which would break the one-line
/// error rule.
fn first_line(e: &dyn std::fmt::Display) -> String {
    let s = e.to_string();
    s.lines().next().unwrap_or("").trim_end().to_string()
}

/// Reads a PLY file into `soup` with material `place.default`; returns how many triangles it
/// added.
pub fn load_ply(path: &Path, place: &ObjPlacement<'_>, soup: &mut TriangleSoup) -> Result<usize> {
    let bytes = specpoly_formats::read::bytes(path)?;
    parse_ply(path, &bytes, place, soup)
}

/// [`load_ply`] of a PLY file's bytes already read; `path` names it in errors.
pub fn parse_ply(
    path: &Path,
    bytes: &[u8],
    place: &ObjPlacement<'_>,
    soup: &mut TriangleSoup,
) -> Result<usize> {
    let bad = |what: String| mesh_error(path, what);
    let mut r = std::io::Cursor::new(bytes);
    let parser = Parser::<DefaultElement>::new();
    let header = parser
        .read_header(&mut r)
        .map_err(|e| bad(format!("not a readable PLY header: {}", first_line(&e))))?;
    for (name, e) in &header.elements {
        // every element takes at least one byte in any encoding
        if e.count > bytes.len() {
            return Err(bad(format!(
                "the header announces {} `{name}` elements in a file of {} bytes",
                e.count,
                bytes.len()
            )));
        }
    }
    let payload = parser
        .read_payload(&mut r, &header)
        .map_err(|e| bad(format!("not a readable PLY file: {}", first_line(&e))))?;
    let empty = Vec::new();
    let verts = payload.get("vertex").unwrap_or(&empty);
    let mut v = Vec::with_capacity(verts.len());
    let mut normals = Vec::new();
    for (i, e) in verts.iter().enumerate() {
        let c = |k: &str| {
            scalar(e.get(k))
                .filter(|x| x.is_finite())
                .ok_or_else(|| bad(format!("vertex {i}: no finite `{k}`")))
        };
        let p = V3::new(c("x")? as f32, c("y")? as f32, c("z")? as f32);
        if !(p.x.is_finite() && p.y.is_finite() && p.z.is_finite()) {
            return Err(bad(format!("vertex {i} is not finite in f32")));
        }
        v.push(crate::mesh::placed(p, place).map_err(|why| bad(format!("vertex {i}: {why}")))?);
        if let (Some(x), Some(y), Some(z)) = (
            scalar(e.get("nx")),
            scalar(e.get("ny")),
            scalar(e.get("nz")),
        ) {
            // a non-finite normal becomes the face's own (`TriangleSoup::push_smooth`)
            normals.push(V3::new(x as f32, y as f32, z as f32));
        }
    }
    // every vertex has a normal, or the mesh is flat
    let smooth = !v.is_empty() && normals.len() == v.len();
    let before = soup.tris.len();
    for (i, f) in payload.get("face").unwrap_or(&empty).iter().enumerate() {
        let idx = indices(f.get("vertex_indices").or_else(|| f.get("vertex_index")))
            .ok_or_else(|| bad(format!("face {i}: no vertex_indices list")))?;
        let vertex = |k: i64| {
            usize::try_from(k)
                .ok()
                .and_then(|k| v.get(k).copied())
                .ok_or_else(|| bad(format!("face {i} refers to a missing vertex {k}")))
        };
        if idx.len() < 3 {
            continue;
        }
        let a = vertex(idx[0])?;
        for w in idx[1..].windows(2) {
            let t = [a, vertex(w[0])?, vertex(w[1])?];
            if smooth {
                // the indices were checked by `vertex` above
                let n = |k: i64| normals[k as usize];
                soup.push_smooth(t, [n(idx[0]), n(w[0]), n(w[1])], place.default);
            } else {
                soup.push(t, place.default);
            }
            if soup.tris.len() > MAX_TRIANGLES {
                return Err(bad(format!(
                    "more than {MAX_TRIANGLES} triangles in the scene"
                )));
            }
        }
    }
    Ok(soup.tris.len() - before)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeMap;

    /// The same square (two triangles as one quad face) in ASCII and in binary little-endian
    /// (written here byte by byte after the PLY specification) reads to the same triangles.
    #[test]
    fn ascii_and_binary_little_endian_agree() {
        let dir = tempfile::tempdir().unwrap();
        let ascii = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
                     property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
                     end_header\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n4 0 1 2 3\n";
        let mut bin =
            b"ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty double x\n\
                        property double y\nproperty double z\nelement face 1\n\
                        property list uchar uint vertex_indices\nend_header\n"
                .to_vec();
        for p in [
            [0.0f64, 0.0, 1.0],
            [1.0, 0.0, 1.0],
            [1.0, 1.0, 1.0],
            [0.0, 1.0, 1.0],
        ] {
            for c in p {
                bin.extend_from_slice(&c.to_le_bytes());
            }
        }
        bin.push(4);
        for i in 0u32..4 {
            bin.extend_from_slice(&i.to_le_bytes());
        }
        let map = BTreeMap::new();
        let place = ObjPlacement {
            scale: 2.0,
            translate: V3::new(0.0, 0.0, 1.0),
            default: 5,
            map: &map,
        };
        let mut out = Vec::new();
        for (name, data) in [("a.ply", ascii.as_bytes().to_vec()), ("b.ply", bin)] {
            let path = dir.path().join(name);
            std::fs::write(&path, data).unwrap();
            let mut soup = TriangleSoup::default();
            assert_eq!(load_ply(&path, &place, &mut soup).unwrap(), 2);
            assert_eq!(soup.owners, vec![super::super::mesh::Owner::Material(5); 2]);
            out.push(soup.tris);
        }
        assert_eq!(out[0], out[1]);
        assert_eq!(out[0][1][1], V3::new(2.0, 2.0, 3.0));

        // an index past the vertices, and an absurd element count, are one-line errors
        let path = dir.path().join("bad.ply");
        std::fs::write(&path, ascii.replace("4 0 1 2 3", "3 0 1 9")).unwrap();
        let e = load_ply(&path, &place, &mut TriangleSoup::default()).unwrap_err();
        assert!(e.to_string().contains("missing vertex 9"), "{e}");
        std::fs::write(
            &path,
            ascii.replace("element vertex 4", "element vertex 999999999"),
        )
        .unwrap();
        let e = load_ply(&path, &place, &mut TriangleSoup::default()).unwrap_err();
        assert!(e.to_string().contains("999999999"), "{e}");
    }
}
