//! Build and trace speed of `obvhs` (PLOC BVH2 → compressed wide BVH8, and the BVH2 itself)
//! against `bvh` (SAH binned BVH, nearest-first traversal) on the same triangles, the same rays
//! and the same triangle test, on 1 and 2 threads (docs/performance.md, "BVH").
//!
//! Scenes:
//! - `cornell`: the built-in Cornell box's quads (read from `scenes/cornell.toml`), 30 triangles;
//! - `mesh137k`: a height-field terrain of 200 × 200 quads and a latitude–longitude sphere of
//!   120 × 240 quads above it (≈ 137 000 triangles), generated here.
//!
//! Rays: 512 × 512 primary rays from a pinhole camera, then one secondary ray from every hit in
//! a direction from a fixed hash (incoherent). Each figure is the median of 5 runs.
//! `cd bench/bvh-compare && cargo run --release`

use glam::Vec3A;
use std::time::{Duration, Instant};

#[derive(Clone, Copy)]
struct Tri {
    v: [Vec3A; 3],
    node: usize,
}

/// Möller–Trumbore; `f32::INFINITY` for a miss.
#[inline]
fn hit(t: &[Vec3A; 3], o: Vec3A, d: Vec3A, tmin: f32, tmax: f32) -> f32 {
    let e1 = t[1] - t[0];
    let e2 = t[2] - t[0];
    let p = d.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-12 {
        return f32::INFINITY;
    }
    let inv = 1.0 / det;
    let s = o - t[0];
    let u = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return f32::INFINITY;
    }
    let q = s.cross(e1);
    let v = d.dot(q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return f32::INFINITY;
    }
    let t = e2.dot(q) * inv;
    if t > tmin && t < tmax {
        t
    } else {
        f32::INFINITY
    }
}

fn quad(out: &mut Vec<Tri>, a: Vec3A, b: Vec3A, c: Vec3A, d: Vec3A) {
    out.push(Tri { v: [a, b, c], node: 0 });
    out.push(Tri { v: [a, c, d], node: 0 });
}

fn mesh() -> Vec<Tri> {
    let mut out = Vec::new();
    let n = 200;
    let h = |i: usize, j: usize| {
        let (x, z) = (i as f32 / n as f32 * 20.0 - 10.0, j as f32 / n as f32 * 20.0 - 10.0);
        Vec3A::new(x, 0.3 * (x * 1.3).sin() * (z * 0.7).cos() + 0.1 * (x * z * 0.2).sin(), z)
    };
    for i in 0..n {
        for j in 0..n {
            quad(&mut out, h(i, j), h(i + 1, j), h(i + 1, j + 1), h(i, j + 1));
        }
    }
    let m = 120;
    let s = |i: usize, j: usize| {
        let th = std::f32::consts::PI * i as f32 / m as f32;
        let ph = std::f32::consts::PI * j as f32 / m as f32;
        Vec3A::new(th.sin() * ph.cos(), th.cos(), th.sin() * ph.sin()) * 2.0 + Vec3A::new(0.0, 2.5, 0.0)
    };
    for i in 0..m {
        for j in 0..2 * m {
            quad(&mut out, s(i, j), s(i + 1, j), s(i + 1, j + 1), s(i, j + 1));
        }
    }
    out.retain(|t| (t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]).length() > 0.0);
    out
}

/// The quads of the built-in Cornell box (`vertices = [[x, y, z], …]` lines of its scene file).
fn cornell() -> Vec<Tri> {
    let text = include_str!("../../../scenes/cornell.toml");
    let mut out = Vec::new();
    for line in text.lines().filter_map(|l| l.strip_prefix("vertices = ")) {
        let nums: Vec<f32> = line
            .split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-'))
            .filter(|s| !s.is_empty())
            .map(|s| s.parse().expect("a number"))
            .collect();
        assert_eq!(nums.len(), 12, "{line}");
        let p = |k: usize| Vec3A::new(nums[3 * k], nums[3 * k + 1], nums[3 * k + 2]);
        quad(&mut out, p(0), p(1), p(2), p(3));
    }
    out
}

/// `w × h` pinhole rays from `eye` toward `at`, vertical field of view `fov` degrees.
fn rays(eye: Vec3A, at: Vec3A, fov: f32) -> Vec<(Vec3A, Vec3A)> {
    let (w, h) = (512, 512);
    let fwd = (at - eye).normalize();
    let right = Vec3A::Y.cross(fwd).normalize();
    let up = fwd.cross(right);
    let k = (fov.to_radians() * 0.5).tan();
    let mut v = Vec::with_capacity(w * h);
    for y in 0..h {
        for x in 0..w {
            let u = (x as f32 + 0.5) / w as f32 * 2.0 - 1.0;
            let t = 1.0 - (y as f32 + 0.5) / h as f32 * 2.0;
            v.push((eye, (fwd + right * (u * k) + up * (t * k)).normalize()));
        }
    }
    v
}

/// Secondary rays: from each primary hit, a direction from a fixed hash (incoherent).
fn secondary(primary: &[(Vec3A, Vec3A)], t: &[f32]) -> Vec<(Vec3A, Vec3A)> {
    let mut out = Vec::new();
    for (k, ((o, d), t)) in primary.iter().zip(t).enumerate() {
        if t.is_finite() {
            let mut z = (k as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15);
            z ^= z >> 29;
            let a = (z & 0xffff) as f32 / 65536.0 * std::f32::consts::TAU;
            let b = ((z >> 16) & 0xffff) as f32 / 65536.0 * 2.0 - 1.0;
            let r = (1.0 - b * b).max(0.0).sqrt();
            let dir = Vec3A::new(a.cos() * r, b, a.sin() * r);
            out.push((*o + *d * (t * (1.0 - 1e-4)), dir));
        }
    }
    out
}

/// The median time of 5 runs of `f`, and its last result.
fn median<T>(f: impl Fn() -> T) -> (T, Duration) {
    let mut times = Vec::new();
    let mut out = None;
    for _ in 0..5 {
        let t0 = Instant::now();
        let r = f();
        times.push(t0.elapsed());
        out = Some(r);
    }
    times.sort();
    (out.unwrap(), times[2])
}

/// `trace` over `rays` split among `threads` scoped threads.
fn parallel(
    threads: usize,
    rays: &[(Vec3A, Vec3A)],
    trace: &(dyn Fn(&[(Vec3A, Vec3A)]) -> Vec<f32> + Sync),
) -> Vec<f32> {
    if threads == 1 {
        return trace(rays);
    }
    let chunk = rays.len().div_ceil(threads);
    std::thread::scope(|s| {
        let parts: Vec<_> = rays.chunks(chunk).map(|c| s.spawn(move || trace(c))).collect();
        parts.into_iter().flat_map(|p| p.join().unwrap()).collect()
    })
}

mod bvh_crate {
    use super::*;
    use bvh::aabb::{Aabb, Bounded};
    use bvh::bounding_hierarchy::BHShape;
    use nalgebra::{Point3, Vector3};

    impl Bounded<f32, 3> for Tri {
        fn aabb(&self) -> Aabb<f32, 3> {
            let p = |v: Vec3A| Point3::new(v.x, v.y, v.z);
            Aabb::empty().grow(&p(self.v[0])).grow(&p(self.v[1])).grow(&p(self.v[2]))
        }
    }
    impl BHShape<f32, 3> for Tri {
        fn set_bh_node_index(&mut self, i: usize) {
            self.node = i;
        }
        fn bh_node_index(&self) -> usize {
            self.node
        }
    }

    pub fn build(tris: &mut [Tri]) -> bvh::bvh::Bvh<f32, 3> {
        bvh::bvh::Bvh::build(tris)
    }

    /// Nearest hit: candidates come nearest-AABB-first; stop once the next box starts beyond
    /// the best hit.
    pub fn trace(b: &bvh::bvh::Bvh<f32, 3>, tris: &[Tri], rays: &[(Vec3A, Vec3A)]) -> Vec<f32> {
        rays.iter()
            .map(|(o, d)| {
                let r = bvh::ray::Ray::new(Point3::new(o.x, o.y, o.z), Vector3::new(d.x, d.y, d.z));
                let mut t_best = f32::INFINITY;
                for tri in b.nearest_traverse_iterator(&r, tris) {
                    if let Some((enter, _)) = r.intersection_slice_for_aabb(&tri.aabb()) {
                        if enter > t_best {
                            break;
                        }
                    }
                    t_best = t_best.min(hit(&tri.v, *o, *d, 1e-4, t_best));
                }
                t_best
            })
            .collect()
    }
}

mod obvhs_crate {
    use super::*;
    use obvhs::ray::{Ray, RayHit};
    use obvhs::triangle::Triangle;

    pub fn input(tris: &[Tri]) -> Vec<Triangle> {
        tris.iter().map(|t| Triangle { v0: t.v[0], v1: t.v[1], v2: t.v[2] }).collect()
    }

    pub fn build_cw(t: &[Triangle]) -> obvhs::cwbvh::CwBvh {
        obvhs::cwbvh::builder::build_cwbvh_from_tris(t, obvhs::BvhBuildParams::medium_build(), &mut Duration::default())
    }

    pub fn build_2(t: &[Triangle]) -> obvhs::bvh2::Bvh2 {
        obvhs::bvh2::builder::build_bvh2_from_tris(t, obvhs::BvhBuildParams::medium_build(), &mut Duration::default())
    }

    pub fn trace_cw(b: &obvhs::cwbvh::CwBvh, ordered: &[[Vec3A; 3]], rays: &[(Vec3A, Vec3A)]) -> Vec<f32> {
        rays.iter()
            .map(|(o, d)| {
                let mut h = RayHit::none();
                b.ray_traverse(Ray::new(*o, *d, 1e-4, f32::INFINITY), &mut h, |r, id| {
                    hit(&ordered[id], r.origin, r.direction, r.tmin, r.tmax)
                });
                h.t
            })
            .collect()
    }

    pub fn trace_2(b: &obvhs::bvh2::Bvh2, ordered: &[[Vec3A; 3]], rays: &[(Vec3A, Vec3A)]) -> Vec<f32> {
        rays.iter()
            .map(|(o, d)| {
                let mut h = RayHit::none();
                b.ray_traverse(Ray::new(*o, *d, 1e-4, f32::INFINITY), &mut h, |r, id| {
                    hit(&ordered[id], r.origin, r.direction, r.tmin, r.tmax)
                });
                h.t
            })
            .collect()
    }
}

fn run(name: &str, tris: Vec<Tri>, primary: Vec<(Vec3A, Vec3A)>) {
    println!("\n{name}: {} triangles, {} primary rays", tris.len(), primary.len());
    let input = obvhs_crate::input(&tris);
    let (cw, t_cw) = median(|| obvhs_crate::build_cw(&input));
    let (b2, t_b2) = median(|| obvhs_crate::build_2(&input));
    let ((bv, bv_tris), t_bv) = median(|| {
        let mut t = tris.clone();
        let b = bvh_crate::build(&mut t);
        (b, t)
    });
    let ord_cw: Vec<[Vec3A; 3]> = cw.primitive_indices.iter().map(|&i| tris[i as usize].v).collect();
    let ord_b2: Vec<[Vec3A; 3]> = b2.primitive_indices.iter().map(|&i| tris[i as usize].v).collect();
    let hits_cw = obvhs_crate::trace_cw(&cw, &ord_cw, &primary);
    let second = secondary(&primary, &hits_cw);
    let agree = |a: &[f32], b: &[f32]| {
        a.iter()
            .zip(b)
            .filter(|(x, y)| !(x.is_infinite() && y.is_infinite()) && (*x - *y).abs() > 1e-3 * x.abs().max(1.0))
            .count()
    };
    println!("| BVH | threads | build | primary Mrays/s | secondary Mrays/s |");
    println!("|---|---:|---:|---:|---:|");
    let mrays = |n: usize, t: Duration| n as f64 / t.as_secs_f64() / 1e6;
    type Tracer<'a> = Box<dyn Fn(&[(Vec3A, Vec3A)]) -> Vec<f32> + Sync + 'a>;
    let tracers: [(&str, Duration, Tracer); 3] = [
        ("obvhs 0.4 CWBVH (BVH8), medium_build", t_cw, Box::new(|r: &[(Vec3A, Vec3A)]| obvhs_crate::trace_cw(&cw, &ord_cw, r))),
        ("obvhs 0.4 BVH2, medium_build", t_b2, Box::new(|r: &[(Vec3A, Vec3A)]| obvhs_crate::trace_2(&b2, &ord_b2, r))),
        ("bvh 0.13 (SAH), nearest-first iterator", t_bv, Box::new(|r: &[(Vec3A, Vec3A)]| bvh_crate::trace(&bv, &bv_tris, r))),
    ];
    for (label, build, trace) in &tracers {
        let p_hits = trace(&primary);
        let s_hits = trace(&second);
        let bad = agree(&hits_cw, &p_hits) + agree(&obvhs_crate::trace_cw(&cw, &ord_cw, &second), &s_hits);
        for threads in [1, 2] {
            let (_, p) = median(|| parallel(threads, &primary, trace.as_ref()));
            let (_, s) = median(|| parallel(threads, &second, trace.as_ref()));
            println!(
                "| {label} | {threads} | {:.2} ms | {:.2} | {:.2} |{}",
                build.as_secs_f64() * 1e3,
                mrays(primary.len(), p),
                mrays(second.len(), s),
                if bad > 0 { format!(" ({bad} hits differ from CWBVH)") } else { String::new() }
            );
        }
    }
}

fn main() {
    let eye = Vec3A::new(-278.0, 273.0, -800.0);
    run("cornell", cornell(), rays(eye, Vec3A::new(-278.0, 273.0, 0.0), 39.3));
    run(
        "mesh137k",
        mesh(),
        rays(Vec3A::new(0.0, 6.0, -14.0), Vec3A::new(0.0, 1.0, 0.0), 53.0),
    );
}
