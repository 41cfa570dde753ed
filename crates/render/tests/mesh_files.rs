//! Users' mesh files that broke the renderer, replayed from the fuzz corpus
//! (`fuzz/corpus/obj_mesh/`, docs/reliability.md "Fuzzing"): each loads, builds and shades
//! with finite unit normals.

use specpoly_render::geometry::{Ray, V3};
use specpoly_render::mesh::{load_obj, ObjPlacement, TriangleSoup};
use std::collections::BTreeMap;
use std::path::Path;

fn load(name: &str, soup: &mut TriangleSoup) -> specpoly_render::Result<usize> {
    let map = BTreeMap::new();
    let place = ObjPlacement {
        scale: 1.0,
        translate: V3::new(0.0, 0.0, 0.0),
        default: 0,
        map: &map,
    };
    load_obj(&corpus(name), &place, soup)
}

fn corpus(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fuzz/corpus/obj_mesh")
        .join(name)
}

/// A triangle with vertex normals whose corners are 10⁸ apart in one direction and 10³ in
/// the others: its barycentric determinant rounds to 0 in `f32`, the barycentrics became NaN
/// and `f32::clamp` panicked with a NaN bound while shading a hit. Its rays along each axis
/// through the middle of the mesh's bounds must hit with a finite unit normal, facing
/// against or along the ray (any side: the tracers flip it toward the viewer).
#[test]
fn sliver_with_vertex_normals_shades_without_panicking() {
    let mut soup = TriangleSoup::default();
    let n = load("crash-sliver-normals.obj", &mut soup).unwrap();
    assert!(n >= 2, "{n} triangles");
    // the file's vertices bound x ∈ [−1, 1000], y ∈ [−1, 1000], z ∈ [−1000, 1e8]
    let (lo, hi) = ([-1.0f32, -1.0, -1000.0], [1000.0f32, 1000.0, 1e8]);
    let tris = soup.build();
    let centre = V3::new(
        (lo[0] + hi[0]) / 2.0,
        (lo[1] + hi[1]) / 2.0,
        (lo[2] + hi[2]) / 2.0,
    );
    let mut hits = 0;
    for k in 0..6 {
        let mut a = [0.0; 3];
        a[k / 2] = if k % 2 == 0 { 1.0 } else { -1.0 };
        let dir = V3::new(a[0], a[1], a[2]);
        let ray = Ray {
            origin: centre - dir * 2e8,
            dir,
        };
        if let Some((t, n, _)) = tris.intersect(&ray, f32::INFINITY) {
            hits += 1;
            assert!(t.is_finite() && t > 0.0, "t = {t}");
            assert!((n.length() - 1.0).abs() < 1e-4, "{n:?}");
        }
    }
    assert!(hits > 0, "no ray hit the mesh");
}

/// Line 18 of this file, `f -3 -2/-5`, gives a texture coordinate five back when three `vt`
/// lines precede it: `tobj` turned it into a huge index and multiplied it unchecked (an
/// overflow panic in a build with overflow checks). The file is refused, naming the line.
#[test]
fn relative_index_before_the_first_texture_coordinate_is_refused() {
    let e = load(
        "crash-relative-index-overflow.obj",
        &mut TriangleSoup::default(),
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("line 18: index -5 refers before the first `vt` (3 so far)"),
        "{e}"
    );
}
