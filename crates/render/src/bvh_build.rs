//! The BVH's build: a top-down binned surface-area-heuristic split (Wald 2007, *On fast
//! Construction of SAH-based Bounding Volume Hierarchies*; pbrt-v4 §7.3.2), written into
//! `obvhs`' binary [`Bvh2`] that `obvhs` then turns into its compressed 8-wide BVH
//! ([`obvhs::cwbvh::bvh2_to_cwbvh::bvh2_to_cwbvh`]) for traversal.
//!
//! Why not `obvhs`' own PLOC builder: it merges two clusters only when each is the other's
//! cheapest neighbour in Morton order, and when those merge costs tie or change monotonically
//! along the order — a triangle fan (a disc or a cylinder's cap), long thin triangles crossing
//! one another, copies of a triangle sharing one centroid — only the ends of each run merge per
//! pass: the build becomes quadratic (a 80 000-triangle fan 54 s, 20 000 crossing slivers 12 s;
//! docs/reliability.md). This build's work is bounded by the input's size whatever the mesh.
//!
//! **The split.** A node's triangles are binned by centroid into [`BINS`] equal slabs along
//! each axis over the centroids' extent; of the `3 (BINS − 1)` planes between slabs, the one of
//! least cost `A(L) N(L) + A(R) N(R)` (`A`: half the surface area of a side's bounds, `N`: its
//! triangle count) splits the node. Centroids that coincide cannot be told apart by any plane:
//! such a node, and any node deeper than [`MAX_SAH_DEPTH`], is split at the median of its
//! longest centroid axis instead (in input order when the centroids all coincide), which halves
//! it. So every level costs `O(n)` and there are at most `MAX_SAH_DEPTH + log₂ n` of them:
//! `O(n log n)` time, `2n − 1` nodes, and a depth the 8-wide traversal's 32-entry stack holds.
//!
//! Leaves hold one triangle; the conversion to 8-wide nodes gathers up to three per leaf where
//! its cost model says so (as after `obvhs`' own build).

use obvhs::aabb::Aabb;
use obvhs::bvh2::node::Bvh2Node;
use obvhs::bvh2::Bvh2;

/// Slabs per axis of the binned SAH (Wald's 16: more bins barely change the tree).
pub const BINS: usize = 16;

/// Depth below which a node is split by the SAH; deeper ones (a chain of unbalanced splits)
/// are halved at their median, which bounds the depth by `MAX_SAH_DEPTH + log₂ n`.
pub const MAX_SAH_DEPTH: usize = 48;

/// The binary BVH over boxes `bounds` (one leaf per box; `primitive_indices` maps leaves back
/// to `bounds`' indices). Empty input gives an empty BVH.
pub fn binned_sah(bounds: &[Aabb]) -> Bvh2 {
    let n = bounds.len();
    let mut bvh = Bvh2::default();
    if n == 0 {
        return bvh;
    }
    let centroids: Vec<glam::Vec3A> = bounds.iter().map(|b| b.center()).collect();
    let mut order: Vec<u32> = (0..n as u32).collect();
    let mut nodes: Vec<Bvh2Node> = Vec::with_capacity(2 * n - 1);
    nodes.push(Bvh2Node::new(Aabb::empty(), 0, 0));
    // (node, first, end, depth)
    let mut todo: Vec<(usize, usize, usize, usize)> = vec![(0, 0, n, 1)];
    let mut max_depth = 1;
    while let Some((node, first, end, depth)) = todo.pop() {
        max_depth = max_depth.max(depth);
        let items = &mut order[first..end];
        let mut node_box = Aabb::empty();
        let mut cbox = Aabb::empty();
        for &i in items.iter() {
            node_box = node_box.union(&bounds[i as usize]);
            cbox.extend(centroids[i as usize]);
        }
        if items.len() == 1 {
            nodes[node] = Bvh2Node::new(node_box, 1, first as u32);
            continue;
        }
        let split = if depth < MAX_SAH_DEPTH {
            sah_split(items, bounds, &centroids, &cbox)
        } else {
            None
        };
        let mid = match split {
            Some(m) => m,
            None => median_split(items, &centroids, &cbox),
        };
        let left = nodes.len();
        nodes.push(Bvh2Node::new(Aabb::empty(), 0, 0));
        nodes.push(Bvh2Node::new(Aabb::empty(), 0, 0));
        nodes[node] = Bvh2Node::new(node_box, 0, left as u32);
        todo.push((left + 1, first + mid, end, depth + 1));
        todo.push((left, first, first + mid, depth + 1));
    }
    bvh.nodes = nodes;
    bvh.primitive_indices = order;
    bvh.max_depth = max_depth.max(obvhs::bvh2::DEFAULT_MAX_STACK_DEPTH);
    bvh
}

/// Reorders `items` so the SAH's best plane separates them; the left side's length, or `None`
/// when the centroids coincide (no plane separates them).
fn sah_split(
    items: &mut [u32],
    bounds: &[Aabb],
    centroids: &[glam::Vec3A],
    cbox: &Aabb,
) -> Option<usize> {
    let extent = cbox.diagonal();
    let bin_of = |axis: usize, i: u32| -> usize {
        let t = (centroids[i as usize][axis] - cbox.min[axis]) / extent[axis];
        // t ∈ [0, 1]; the largest centroid falls in the last slab
        ((t * BINS as f32) as usize).min(BINS - 1)
    };
    let mut best: Option<(f32, usize, usize)> = None; // (cost, axis, planes left of it)
    for axis in 0..3 {
        if extent[axis] <= 0.0 {
            continue;
        }
        let mut count = [0usize; BINS];
        let mut bins = [Aabb::empty(); BINS];
        for &i in items.iter() {
            let b = bin_of(axis, i);
            count[b] += 1;
            bins[b] = bins[b].union(&bounds[i as usize]);
        }
        // the right sides' area × count, swept from the right
        let mut right_cost = [0.0f32; BINS];
        let (mut acc, mut acc_n) = (Aabb::empty(), 0usize);
        for b in (1..BINS).rev() {
            acc = acc.union(&bins[b]);
            acc_n += count[b];
            right_cost[b] = if acc_n > 0 {
                acc.half_area() * acc_n as f32
            } else {
                f32::INFINITY
            };
        }
        let (mut acc, mut acc_n) = (Aabb::empty(), 0usize);
        for b in 0..BINS - 1 {
            acc = acc.union(&bins[b]);
            acc_n += count[b];
            if acc_n == 0 || acc_n == items.len() {
                continue;
            }
            let cost = acc.half_area() * acc_n as f32 + right_cost[b + 1];
            if best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, b + 1));
            }
        }
    }
    let (_, axis, plane) = best?;
    // partition: slabs left of the plane first
    let mut l = 0;
    for k in 0..items.len() {
        if bin_of(axis, items[k]) < plane {
            items.swap(l, k);
            l += 1;
        }
    }
    Some(l)
}

/// Halves `items` at the median centroid along the longest centroid axis (in input order when
/// the centroids coincide); the left half's length.
fn median_split(items: &mut [u32], centroids: &[glam::Vec3A], cbox: &Aabb) -> usize {
    let mid = items.len() / 2;
    let extent = cbox.diagonal();
    if extent.max_element() > 0.0 {
        let axis = cbox.largest_axis();
        items.select_nth_unstable_by(mid, |&a, &b| {
            centroids[a as usize][axis].total_cmp(&centroids[b as usize][axis])
        });
    }
    mid
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3A;

    fn boxes(n: usize, f: impl Fn(usize) -> (Vec3A, Vec3A)) -> Vec<Aabb> {
        (0..n)
            .map(|i| {
                let (a, b) = f(i);
                Aabb::new(a.min(b), a.max(b))
            })
            .collect()
    }

    /// Every node's box holds its children's or its primitive's; every primitive is in
    /// exactly one leaf; the depth stays within the bound.
    fn check(bvh: &Bvh2, bounds: &[Aabb]) -> usize {
        let mut seen = vec![false; bounds.len()];
        let mut stack = vec![(0usize, 1usize)];
        let mut depth = 0;
        while let Some((i, d)) = stack.pop() {
            depth = depth.max(d);
            let node = &bvh.nodes[i];
            let a = node.aabb();
            if node.is_leaf() {
                assert_eq!(node.prim_count, 1);
                let p = bvh.primitive_indices[node.first_index as usize] as usize;
                assert!(!seen[p], "primitive {p} twice");
                seen[p] = true;
                assert!(a.min.cmple(bounds[p].min).all() && a.max.cmpge(bounds[p].max).all());
            } else {
                for c in [node.first_index as usize, node.first_index as usize + 1] {
                    let b = bvh.nodes[c].aabb();
                    assert!(a.min.cmple(b.min).all() && a.max.cmpge(b.max).all());
                    stack.push((c, d + 1));
                }
            }
        }
        assert!(seen.iter().all(|s| *s), "a primitive in no leaf");
        assert_eq!(bvh.nodes.len(), 2 * bounds.len() - 1);
        depth
    }

    #[test]
    fn every_primitive_in_one_leaf_and_the_depth_bounded() {
        let tau = std::f32::consts::TAU;
        let n = 3000;
        let cases: Vec<(&str, Vec<Aabb>)> = vec![
            // a grid of small boxes: a balanced tree
            (
                "grid",
                boxes(n, |i| {
                    let p = Vec3A::new((i % 50) as f32, (i / 50) as f32, 0.0);
                    (p, p + 0.5)
                }),
            ),
            // all centroids equal: median splits in input order
            ("coincident", boxes(n, |_| (Vec3A::splat(-1.0), Vec3A::ONE))),
            // a fan's slivers and crossing sticks: the PLOC worst cases
            (
                "fan",
                boxes(n, |i| {
                    let a = tau * i as f32 / n as f32;
                    let (p, q) = (Vec3A::new(a.cos(), a.sin(), 0.0), Vec3A::ZERO);
                    (p.min(q), p.max(q))
                }),
            ),
            (
                "sticks",
                boxes(n, |i| {
                    let a = std::f32::consts::PI * i as f32 / n as f32;
                    let p = Vec3A::new(a.cos(), a.sin(), 0.001);
                    (-p, p)
                }),
            ),
            // exponentially spaced: every SAH split peels one box off, until the depth bound
            (
                "exponential",
                boxes(200, |i| {
                    let x = 1.2f32.powi(i as i32);
                    (Vec3A::new(x, 0.0, 0.0), Vec3A::new(x * 1.01, 1.0, 1.0))
                }),
            ),
        ];
        for (name, b) in &cases {
            let bvh = binned_sah(b);
            let depth = check(&bvh, b);
            let bound = MAX_SAH_DEPTH + (b.len() as f32).log2().ceil() as usize + 1;
            assert!(depth <= bound, "{name}: depth {depth} > {bound}");
        }
        assert!(binned_sah(&[]).nodes.is_empty());
    }

    /// The 8-wide BVH `obvhs` makes of this tree passes `obvhs`' own structural validation,
    /// and rays find the nearest of the triangles a loop over all of them finds.
    #[test]
    fn the_traversed_bvh_finds_what_brute_force_finds() {
        use obvhs::ray::{Ray, RayHit};
        use obvhs::triangle::Triangle;
        let mut tris = Vec::new();
        let n = 24;
        let p = |i: usize, j: usize| {
            let th = std::f32::consts::PI * i as f32 / n as f32;
            let ph = std::f32::consts::PI * j as f32 / n as f32;
            Vec3A::new(th.sin() * ph.cos(), th.cos(), th.sin() * ph.sin() + 5.0)
        };
        for i in 0..n {
            for j in 0..2 * n {
                let (a, b, c, d) = (p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1));
                tris.push(Triangle {
                    v0: a,
                    v1: b,
                    v2: c,
                });
                tris.push(Triangle {
                    v0: a,
                    v1: c,
                    v2: d,
                });
            }
        }
        let bounds: Vec<Aabb> = tris.iter().map(|t| t.aabb()).collect();
        let bvh2 = binned_sah(&bounds);
        check(&bvh2, &bounds);
        let cw = obvhs::cwbvh::bvh2_to_cwbvh::bvh2_to_cwbvh(&bvh2, 3, true, false);
        cw.validate(&tris, false);
        for k in 0..400 {
            let (a, b) = ((k % 20) as f32 * 0.01 - 0.1, (k / 20) as f32 * 0.01 - 0.1);
            let ray = Ray::new(
                Vec3A::ZERO,
                Vec3A::new(a, b, 1.0).normalize(),
                0.0,
                f32::INFINITY,
            );
            let brute = tris
                .iter()
                .map(|t| t.intersect(&ray))
                .fold(f32::INFINITY, f32::min);
            let mut hit = RayHit::none();
            cw.ray_traverse(ray, &mut hit, |r, id| {
                tris[cw.primitive_indices[id] as usize].intersect(r)
            });
            assert_eq!(hit.t, brute, "ray {k}");
        }
    }
}
