//! Area lights (rectangles and spheres with a uniform spectral radiance) and the environment
//! light (a constant spectral radiance from every direction), with the sampling both tracers
//! use for direct light.
//!
//! Radiometry: a light's radiance is `radiance · SPD(λ)`, the SPD normalised so that a perfect
//! white diffuse surface seeing radiance `1` in every direction has `Y = 100` (the tracers
//! integrate against the SPD's exact moments, as for point lights). A Lambertian surface of
//! reflectance `D` lit by an area light reflects
//! `L_o = ∫ (D/π) · L_e · cos θ dω`, estimated from one light sample `ω` of density `p(ω)` as
//! `(D/π) · L_e · cos θ / p(ω)`:
//! - a **rectangle** (corner `c`, edges `u`, `v`, emitting on the side of `u × v`) is sampled
//!   uniformly in area: `p(ω) = r² / (A · cos θ_l)`;
//! - a **sphere** (centre `c`, radius `R`) is sampled uniformly in the cone of directions it
//!   subtends (Shirley, Wang & Zimmerman, "Monte Carlo techniques for direct lighting
//!   calculations", ACM TOG 15(1), 1996): `p(ω) = 1 / Ω`, `Ω = 2π (1 − cos α)`,
//!   `sin α = R / d`;
//! - an **emissive mesh** (triangles emitting on both sides) is sampled uniformly in area: a
//!   triangle with probability proportional to its area, a uniform point in it (Turk, "Generating
//!   random points in triangles", Graphics Gems, 1990: `√a` warping), `p(ω) = r² / (A · |cos θ_l|)`
//!   with `A` the mesh's total area. Its triangles are in the scene's BVH (camera and mirror rays
//!   see them) and are opaque to shadow rays, so a sample on a hidden side is occluded;
//! - the **environment** is sampled with the cosine density `p(ω) = cos θ / π`, which makes its
//!   estimate exactly `D · L_env` when unoccluded.

use crate::geometry::{Ray, EPS, V3};
use specpoly_spectra::spectrum_names::Named;
use std::f32::consts::PI;
use std::sync::Arc;

/// The triangles of an emissive mesh with their cumulative areas.
#[derive(Clone, Debug, PartialEq)]
pub struct EmitterMesh {
    /// The triangles.
    pub tris: Vec<[V3; 3]>,
    /// `cdf[i]`: the area of triangles `0..=i` over the total area.
    cdf: Vec<f32>,
    /// Total area.
    area: f32,
}

impl EmitterMesh {
    /// The mesh of `tris` (degenerate triangles dropped); `None` if no area is left.
    pub fn new(tris: Vec<[V3; 3]>) -> Option<Self> {
        let tris: Vec<[V3; 3]> = tris
            .into_iter()
            .filter(|t| (t[1] - t[0]).cross(t[2] - t[0]).length() > 0.0)
            .collect();
        let mut acc = 0.0f64;
        let mut cdf = Vec::with_capacity(tris.len());
        for t in &tris {
            acc += 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).length() as f64;
            cdf.push(acc);
        }
        if !(acc > 0.0 && acc.is_finite()) {
            return None;
        }
        Some(Self {
            tris,
            cdf: cdf.into_iter().map(|c| (c / acc) as f32).collect(),
            area: acc as f32,
        })
    }

    /// A point uniform in area from `(u1, u2) ∈ [0, 1)²` and the unit normal there.
    #[inline]
    fn point(&self, u1: f32, u2: f32) -> (V3, V3) {
        let i = self
            .cdf
            .partition_point(|c| *c <= u1)
            .min(self.tris.len() - 1);
        let lo = if i == 0 { 0.0 } else { self.cdf[i - 1] };
        // u1 rescaled within the chosen triangle's share
        let a = ((u1 - lo) / (self.cdf[i] - lo).max(f32::MIN_POSITIVE)).clamp(0.0, 1.0);
        let t = &self.tris[i];
        let s = a.sqrt();
        let p = t[0] * (1.0 - s) + t[1] * (s * (1.0 - u2)) + t[2] * (s * u2);
        (p, (t[1] - t[0]).cross(t[2] - t[0]).normalize())
    }
}

/// The shape of an area light.
#[derive(Clone, Debug, PartialEq)]
pub enum Emitter {
    /// A parallelogram `corner + s·u + t·v`, `s, t ∈ [0, 1]`, emitting on the side of `u × v`.
    Rect {
        /// A corner.
        corner: V3,
        /// First edge.
        u: V3,
        /// Second edge.
        v: V3,
    },
    /// A sphere emitting outward.
    Sphere {
        /// Centre.
        center: V3,
        /// Radius (> 0).
        radius: f32,
    },
    /// Triangles emitting on both sides.
    Mesh(Arc<EmitterMesh>),
}

/// An area light: a shape, its spectrum and the radiance scale.
#[derive(Clone, Debug)]
pub struct AreaLight {
    /// Geometry.
    pub shape: Emitter,
    /// Spectral power distribution (tabulated, never fitted).
    pub spd: Named,
    /// Radiance scale: a white surface under a hemisphere of this light has `Y = 100 · radiance`.
    pub radiance: f32,
}

/// The environment light.
#[derive(Clone, Debug)]
pub struct Environment {
    /// Spectral power distribution.
    pub spd: Named,
    /// Radiance scale.
    pub radiance: f32,
}

/// A direction toward a light with its estimator weight.
#[derive(Clone, Copy, Debug)]
pub struct LightSample {
    /// Unit direction from the shading point to the light.
    pub dir: V3,
    /// Distance to the sampled point (`∞` for the environment).
    pub dist: f32,
    /// `cos θ / p(ω)` (sr): multiply by `L_e · D/π` for the diffuse estimate.
    pub weight: f32,
}

/// An orthonormal basis `(t, b)` around the unit `n` (Duff et al., "Building an orthonormal
/// basis, revisited", JCGT 6(1), 2017).
#[inline]
pub fn basis(n: V3) -> (V3, V3) {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        V3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        V3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

/// A cosine-distributed direction around the unit `n` from `(u1, u2) ∈ [0, 1)²`
/// (Malley's method: a uniform disk point lifted to the hemisphere).
#[inline]
pub fn cosine_direction(n: V3, u1: f32, u2: f32) -> V3 {
    let r = u1.sqrt();
    let phi = 2.0 * PI * u2;
    let (t, b) = basis(n);
    (t * (r * phi.cos()) + b * (r * phi.sin()) + n * (1.0 - u1).max(0.0).sqrt()).normalize()
}

/// The sample from `p` (unit shading normal `n`) toward the point `q` of an area light of
/// `area` whose cosine toward `dir` is `cos_l(dir)`: weight `cos θ · cos θ_l · A / d²`; `None`
/// if `q` cannot light `p`.
#[inline]
fn toward_area(p: V3, n: V3, q: V3, area: f32, cos_l: impl Fn(V3) -> f32) -> Option<LightSample> {
    let to = q - p;
    let d2 = to.dot(to);
    if d2 <= 0.0 {
        return None;
    }
    let dist = d2.sqrt();
    let dir = to * (1.0 / dist);
    let cos = n.dot(dir);
    let cos_l = cos_l(dir);
    if cos <= 0.0 || cos_l <= 0.0 {
        return None;
    }
    Some(LightSample {
        dir,
        dist,
        weight: cos * cos_l * area / d2,
    })
}

impl Emitter {
    /// Samples a direction from `p` (unit shading normal `n`) toward the light from
    /// `(u1, u2) ∈ [0, 1)²`; `None` if the sample cannot light `p` (behind the light, or
    /// below the surface).
    #[inline]
    pub fn sample(&self, p: V3, n: V3, u1: f32, u2: f32) -> Option<LightSample> {
        match *self {
            Emitter::Mesh(ref m) => {
                let (q, nl) = m.point(u1, u2);
                toward_area(p, n, q, m.area, |dir| nl.dot(dir).abs())
            }
            Emitter::Rect { corner, u, v } => {
                let q = corner + u * u1 + v * u2;
                let nl = u.cross(v);
                let area = nl.length();
                toward_area(p, n, q, area, |dir| -(nl * (1.0 / area)).dot(dir))
            }
            Emitter::Sphere { center, radius } => {
                let to = center - p;
                let d2 = to.dot(to);
                if d2 <= radius * radius {
                    return None;
                }
                let d = d2.sqrt();
                let w = to * (1.0 / d);
                let cos_max = (1.0 - radius * radius / d2).max(0.0).sqrt();
                let cos_a = 1.0 - u1 * (1.0 - cos_max);
                let sin_a = (1.0 - cos_a * cos_a).max(0.0).sqrt();
                let phi = 2.0 * PI * u2;
                let (t, b) = basis(w);
                let dir =
                    (t * (sin_a * phi.cos()) + b * (sin_a * phi.sin()) + w * cos_a).normalize();
                let cos = n.dot(dir);
                if cos <= 0.0 {
                    return None;
                }
                // distance to the near side of the sphere along `dir`
                let bq = to.dot(dir);
                let disc = (bq * bq - (d2 - radius * radius)).max(0.0);
                let dist = bq - disc.sqrt();
                let solid = 2.0 * PI * (1.0 - cos_max);
                Some(LightSample {
                    dir,
                    dist,
                    weight: cos * solid,
                })
            }
        }
    }

    /// The nearest hit with `EPS < t < t_max` on the emitting side: `(t, outward normal)`.
    /// Always `None` for a mesh: its triangles are in the scene's BVH.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<(f32, V3)> {
        match *self {
            Emitter::Mesh(_) => None,
            Emitter::Rect { corner, u, v } => {
                let nl = u.cross(v);
                let den = nl.dot(ray.dir);
                // seen from the front only (the back is black and lets the ray through)
                if den >= 0.0 {
                    return None;
                }
                let t = (corner - ray.origin).dot(nl) / den;
                if t <= EPS || t >= t_max {
                    return None;
                }
                let q = ray.at(t) - corner;
                // coordinates in the (u, v) frame
                let (uu, uv, vv) = (u.dot(u), u.dot(v), v.dot(v));
                let (qu, qv) = (q.dot(u), q.dot(v));
                let det = uu * vv - uv * uv;
                let s = (qu * vv - qv * uv) / det;
                let tt = (qv * uu - qu * uv) / det;
                if !(0.0..=1.0).contains(&s) || !(0.0..=1.0).contains(&tt) {
                    return None;
                }
                Some((t, nl.normalize()))
            }
            Emitter::Sphere { center, radius } => crate::geometry::Shape::Sphere { center, radius }
                .intersect(ray, t_max)
                .map(|h| (h.t, h.normal)),
        }
    }

    /// Area (for messages and power).
    pub fn area(&self) -> f32 {
        match *self {
            Emitter::Rect { u, v, .. } => u.cross(v).length(),
            Emitter::Sphere { radius, .. } => 4.0 * PI * radius * radius,
            Emitter::Mesh(ref m) => m.area,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The mean sample weight of emitter `e` seen from the origin (normal `n`) over a k × k
    /// midpoint grid of `(u1, u2)`.
    fn mean_weight(e: &Emitter, n: V3, k: usize) -> f64 {
        let mut sum = 0.0f64;
        for i in 0..k {
            for j in 0..k {
                let (u1, u2) = ((i as f32 + 0.5) / k as f32, (j as f32 + 0.5) / k as f32);
                sum += e.sample(V3::default(), n, u1, u2).unwrap().weight as f64;
            }
        }
        sum / (k * k) as f64
    }

    /// Irradiance from a sphere light on the axis of a surface facing it is `π L (R/d)²`
    /// (Lambert; e.g. Dutré, *Global Illumination Compendium*, (34)); the cone sampler's
    /// estimate `cos θ / p` averages to `π (R/d)²` — the samples vary in `cos θ` only.
    #[test]
    fn sphere_light_irradiance_is_analytic() {
        let s = Emitter::Sphere {
            center: V3::new(0.0, 3.0, 0.0),
            radius: 1.0,
        };
        let n = V3::new(0.0, 1.0, 0.0);
        let est = mean_weight(&s, n, 64);
        let exact = std::f64::consts::PI / 9.0;
        assert!((est - exact).abs() < 1e-3 * exact, "{est} vs {exact}");
    }

    /// The rectangle sampler integrates the form factor of a parallel square above a point
    /// (Howell's catalogue, C-10 as a sum of four corner configurations: here one unit square
    /// centred above at height h), compared against a fine midpoint sum of `cos θ cos θ' / r²`.
    #[test]
    fn rect_light_matches_a_fine_sum() {
        let h = 1.0f32;
        let r = Emitter::Rect {
            corner: V3::new(-0.5, h, -0.5),
            u: V3::new(1.0, 0.0, 0.0),
            v: V3::new(0.0, 0.0, 1.0),
        };
        let n = V3::new(0.0, 1.0, 0.0);
        let est = mean_weight(&r, n, 200);
        // closed form for a square of side a centred above the point at height h:
        // E/L = 4 · [ (x/√(1+x²)) atan(y/√(1+x²)) + (y/√(1+y²)) atan(x/√(1+y²)) ] / 2,
        // x = y = a/(2h) (the corner-rectangle form factor, Howell C-10, × π, four quadrants)
        let x = 0.5f64 / h as f64;
        let q = (1.0 + x * x).sqrt();
        let exact = 4.0 * (x / q * (x / q).atan());
        assert!((est - exact).abs() < 1e-3 * exact, "{est} vs {exact}");
        // the back of the light gives nothing
        assert!(r.sample(V3::new(0.0, 2.0, 0.0), -n, 0.5, 0.5).is_none());
    }

    /// A square as an emissive mesh of two triangles (sampled by area over both) integrates the
    /// same closed form as the rectangle (Howell C-10, above), from either side.
    #[test]
    fn mesh_light_matches_the_square_form_factor() {
        let (a, b, c, d) = (
            V3::new(-0.5, 1.0, -0.5),
            V3::new(0.5, 1.0, -0.5),
            V3::new(0.5, 1.0, 0.5),
            V3::new(-0.5, 1.0, 0.5),
        );
        let m = Emitter::Mesh(Arc::new(
            EmitterMesh::new(vec![[a, b, c], [c, d, a]]).unwrap(),
        ));
        let n = V3::new(0.0, 1.0, 0.0);
        let est = mean_weight(&m, n, 200);
        let x = 0.5f64;
        let q = (1.0 + x * x).sqrt();
        let exact = 4.0 * (x / q * (x / q).atan());
        assert!((est - exact).abs() < 1e-3 * exact, "{est} vs {exact}");
        // two-sided: seen from above, too
        let above = m.sample(V3::new(0.0, 2.0, 0.0), -n, 0.3, 0.6).unwrap();
        assert!(above.weight > 0.0);
        assert!((m.area() - 1.0).abs() < 1e-6);
    }

    #[test]
    fn cosine_directions_stay_in_the_hemisphere() {
        let n = V3::new(0.3, -0.9, 0.1).normalize();
        for i in 0..100 {
            let d = cosine_direction(n, (i as f32 + 0.5) / 100.0, (i * 37 % 100) as f32 / 100.0);
            assert!(d.dot(n) >= 0.0 && (d.length() - 1.0).abs() < 1e-5);
        }
    }
}
