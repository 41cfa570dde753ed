//! The work a scene may ask for, bounded before rendering. Every reflected or refracted ray
//! recurses (one stack frame per bounce), and a material with both a mirror and a transmission
//! spawns two rays per hit, so the ray tree can grow as `2^max_depth`. Two limits keep a scene
//! file from asking for unbounded time or stack:
//!
//! - `max_depth` ≤ [`MAX_DEPTH`] (a documented depth limit; the recursion is at most that deep);
//! - the worst-case ray tree of one sample ≤ [`MAX_RAYS_PER_SAMPLE`]. The bound takes the
//!   largest mirror value `a` and the largest transmission value `b` over all materials (each
//!   the largest over 380–780 nm, as the tracer's path weight): a ray after `i` reflections and
//!   `j` refractions has weight at most `aⁱ bʲ`, is traced only if that is ≥ `cutoff`, and
//!   there are at most `C(i+j, i)` such rays when some material both reflects and transmits
//!   (otherwise a path never forks and the tree is a chain of `max_depth + 1` rays). The
//!   adaptive cutoff applies in every mode (RGB, spectral, moments), so the bound holds for all.
//!
//! A scene over a limit is refused with the figures and what to change.

use crate::error::{Error, Result};
use crate::scene::Material;
use crate::sections::RenderSection;
use specpoly_spectra::spectrum_names::Named;

/// The deepest path (reflections + refractions) a scene may ask for.
pub const MAX_DEPTH: u32 = 64;

/// The most rays one sample's worst-case ray tree may hold (≈ 2 ms of tracing on one core).
pub const MAX_RAYS_PER_SAMPLE: f64 = 16_384.0;

/// Refuses a `[render]` section and materials whose worst-case work exceeds the limits.
pub fn check(render: &RenderSection, materials: &[Material], source: &str) -> Result<()> {
    if render.max_depth > MAX_DEPTH {
        return Err(Error::DepthLimit {
            file: source.to_string(),
            depth: render.max_depth,
            limit: MAX_DEPTH,
        });
    }
    let peak = |n: &Option<Named>| -> f64 {
        n.as_ref().map_or(0.0, |n| {
            let t = n.tabulated();
            (380..=780).map(|nm| t.at(nm as f64)).fold(0.0f64, f64::max)
        })
    };
    let a = materials
        .iter()
        .map(|m| peak(&m.mirror))
        .fold(0.0, f64::max);
    let b = materials
        .iter()
        .map(|m| peak(&m.transmission))
        .fold(0.0, f64::max);
    let forks = materials
        .iter()
        .any(|m| m.mirror.is_some() && m.transmission.is_some());
    let rays = worst_case_rays(a, b, forks, render.max_depth, render.cutoff as f64);
    if rays > MAX_RAYS_PER_SAMPLE {
        return Err(Error::RayTree {
            file: source.to_string(),
            depth: render.max_depth,
            cutoff: render.cutoff,
            rays,
            limit: MAX_RAYS_PER_SAMPLE,
        });
    }
    Ok(())
}

/// The most rays one primary ray can spawn: `Σ C(i+j, i)` over `i + j ≤ depth` with
/// `aⁱ bʲ ≥ cutoff` (a mirror child needs `a > 0`, a transmitted one `b > 0`); a chain of at
/// most `depth + 1` rays when no material forks.
pub fn worst_case_rays(a: f64, b: f64, forks: bool, depth: u32, cutoff: f64) -> f64 {
    if !forks {
        return if a > 0.0 || b > 0.0 {
            depth as f64 + 1.0
        } else {
            1.0
        };
    }
    let d = depth as usize;
    // binomials by Pascal's triangle in f64 (C(128, 64) ≈ 2.4e37 is finite)
    let mut row = vec![1.0f64];
    let mut total = 0.0;
    for n in 0..=d {
        for (i, c) in row.iter().enumerate() {
            let j = n - i;
            if (i > 0 && a <= 0.0) || (j > 0 && b <= 0.0) {
                continue;
            }
            if a.powi(i as i32) * b.powi(j as i32) >= cutoff {
                total += c;
            }
        }
        let mut next = vec![1.0f64; row.len() + 1];
        for k in 1..row.len() {
            next[k] = row[k - 1] + row[k];
        }
        row = next;
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn full_binary_tree_without_cutoff() {
        // a complete binary tree of depth d has 2^(d+1) − 1 nodes
        for d in 0..20 {
            assert_eq!(
                worst_case_rays(1.0, 1.0, true, d, 0.0),
                2f64.powi(d as i32 + 1) - 1.0
            );
        }
        assert_eq!(worst_case_rays(1.0, 0.0, false, 64, 0.0), 65.0);
    }

    #[test]
    fn cutoff_prunes() {
        // weights 0.5 each, cutoff 0.25: depth ≤ 2 survives → 1 + 2 + 4 rays
        assert_eq!(worst_case_rays(0.5, 0.5, true, 40, 0.25), 7.0);
    }
}
