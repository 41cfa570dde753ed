//! Geometry in `f32`: vectors, rays, spheres, planes and axis-aligned boxes, and a flat list of
//! shapes searched linearly (the scenes hold tens of shapes; a hierarchy would not pay).

use std::ops::{Add, Mul, Neg, Sub};

/// A 3-vector.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct V3 {
    /// x
    pub x: f32,
    /// y
    pub y: f32,
    /// z
    pub z: f32,
}

impl V3 {
    /// A new vector.
    #[inline]
    pub const fn new(x: f32, y: f32, z: f32) -> Self {
        Self { x, y, z }
    }
    /// From an array.
    pub fn from_array(a: [f32; 3]) -> Self {
        Self::new(a[0], a[1], a[2])
    }
    /// Dot product.
    #[inline]
    pub fn dot(self, o: V3) -> f32 {
        self.x * o.x + self.y * o.y + self.z * o.z
    }
    /// Cross product.
    #[inline]
    pub fn cross(self, o: V3) -> V3 {
        V3::new(
            self.y * o.z - self.z * o.y,
            self.z * o.x - self.x * o.z,
            self.x * o.y - self.y * o.x,
        )
    }
    /// Length.
    #[inline]
    pub fn length(self) -> f32 {
        self.dot(self).sqrt()
    }
    /// Unit vector in the same direction (zero stays zero).
    #[inline]
    pub fn normalize(self) -> V3 {
        let l = self.length();
        if l > 0.0 {
            self * (1.0 / l)
        } else {
            self
        }
    }
    /// Mirror direction of `self` (pointing at the surface) about the unit normal `n`.
    #[inline]
    pub fn reflect(self, n: V3) -> V3 {
        self - n * (2.0 * self.dot(n))
    }
    /// Refracted direction of the unit `self` through a surface with unit normal `n` facing
    /// against `self`, with `eta = n₁/n₂`; `None` on total internal reflection (Snell's law).
    #[inline]
    pub fn refract(self, n: V3, eta: f32) -> Option<V3> {
        let cos_i = -self.dot(n);
        let k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
        if k < 0.0 {
            None
        } else {
            Some((self * eta + n * (eta * cos_i - k.sqrt())).normalize())
        }
    }
    /// Component `i` (0, 1, 2).
    #[inline]
    fn get(self, i: usize) -> f32 {
        match i {
            0 => self.x,
            1 => self.y,
            _ => self.z,
        }
    }
}

impl Add for V3 {
    type Output = V3;
    #[inline]
    fn add(self, o: V3) -> V3 {
        V3::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}
impl Sub for V3 {
    type Output = V3;
    #[inline]
    fn sub(self, o: V3) -> V3 {
        V3::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}
impl Mul<f32> for V3 {
    type Output = V3;
    #[inline]
    fn mul(self, k: f32) -> V3 {
        V3::new(self.x * k, self.y * k, self.z * k)
    }
}
impl Neg for V3 {
    type Output = V3;
    #[inline]
    fn neg(self) -> V3 {
        V3::new(-self.x, -self.y, -self.z)
    }
}

/// A ray `origin + t · dir`, `dir` of unit length.
#[derive(Clone, Copy, Debug)]
pub struct Ray {
    /// Origin.
    pub origin: V3,
    /// Unit direction.
    pub dir: V3,
}

impl Ray {
    /// The point at `t`.
    #[inline]
    pub fn at(&self, t: f32) -> V3 {
        self.origin + self.dir * t
    }
}

/// A primitive.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// A sphere.
    Sphere {
        /// Centre.
        center: V3,
        /// Radius (> 0).
        radius: f32,
    },
    /// An infinite plane through `point` with unit normal `normal`.
    Plane {
        /// A point on the plane.
        point: V3,
        /// Unit normal (the front side).
        normal: V3,
    },
    /// An axis-aligned box.
    Box {
        /// Lower corner.
        min: V3,
        /// Upper corner (each component > the lower one).
        max: V3,
    },
}

/// A ray–surface hit.
#[derive(Clone, Copy, Debug)]
pub struct Hit {
    /// Ray parameter.
    pub t: f32,
    /// Outward unit normal (the plane's front side).
    pub normal: V3,
}

/// Hits closer than this are ignored (self-intersection).
pub const EPS: f32 = 1e-4;

impl Shape {
    /// The nearest hit with `EPS < t < t_max`.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        match *self {
            Shape::Sphere { center, radius } => {
                let (near, far) = sphere_roots(ray, center, radius)?;
                let t = if near <= EPS { far } else { near };
                if t <= EPS || t >= t_max {
                    return None;
                }
                Some(Hit {
                    t,
                    normal: (ray.at(t) - center) * (1.0 / radius),
                })
            }
            Shape::Plane { point, normal } => {
                let den = normal.dot(ray.dir);
                if den.abs() < 1e-9 {
                    return None;
                }
                let t = (point - ray.origin).dot(normal) / den;
                if t <= EPS || t >= t_max {
                    return None;
                }
                Some(Hit { t, normal })
            }
            Shape::Box { min, max } => {
                let (t0, a0, t1, a1) = slabs(ray, min, max)?;
                let (t, axis, entering) = if t0 > EPS {
                    (t0, a0, true)
                } else if t1 > EPS {
                    (t1, a1, false)
                } else {
                    return None;
                };
                if t >= t_max {
                    return None;
                }
                // outward normal on face `axis`: against the ray when entering, with it when leaving
                let d = ray.dir.get(axis);
                let sign = if entering { -d.signum() } else { d.signum() };
                let mut n = V3::default();
                match axis {
                    0 => n.x = sign,
                    1 => n.y = sign,
                    _ => n.z = sign,
                }
                Some(Hit { t, normal: n })
            }
        }
    }

    /// How many times the segment `EPS < t < t_max` crosses the surface (for shadow rays).
    #[inline]
    pub fn crossings(&self, ray: &Ray, t_max: f32) -> u32 {
        let inside = |t: f32| (t > EPS && t < t_max) as u32;
        match *self {
            Shape::Sphere { center, radius } => match sphere_roots(ray, center, radius) {
                Some((near, far)) => inside(near) + inside(far),
                None => 0,
            },
            Shape::Plane { .. } => self.intersect(ray, t_max).is_some() as u32,
            Shape::Box { min, max } => match slabs(ray, min, max) {
                Some((t0, _, t1, _)) => inside(t0) + inside(t1),
                None => 0,
            },
        }
    }
}

/// Where the ray's line meets the sphere, `t_near ≤ t_far` (roots of
/// `|o + t·d − c|² = r²` with `|d| = 1`: `t = −b ± √(b² − c)`, `b = (o − c)·d`,
/// `c = |o − c|² − r²`); `None` if it misses.
#[inline]
fn sphere_roots(ray: &Ray, center: V3, radius: f32) -> Option<(f32, f32)> {
    let oc = ray.origin - center;
    let b = oc.dot(ray.dir);
    let c = oc.dot(oc) - radius * radius;
    let disc = b * b - c;
    if disc < 0.0 {
        return None;
    }
    let s = disc.sqrt();
    Some((-b - s, -b + s))
}

/// Slab test: entry and exit parameters and the axes they lie on, if the line meets the box.
#[inline]
fn slabs(ray: &Ray, min: V3, max: V3) -> Option<(f32, usize, f32, usize)> {
    let mut t0 = f32::NEG_INFINITY;
    let mut t1 = f32::INFINITY;
    let (mut a0, mut a1) = (0, 0);
    for axis in 0..3 {
        let o = ray.origin.get(axis);
        let d = ray.dir.get(axis);
        let (lo, hi) = (min.get(axis), max.get(axis));
        if d.abs() < 1e-12 {
            if o < lo || o > hi {
                return None;
            }
            continue;
        }
        let inv = 1.0 / d;
        let (mut near, mut far) = ((lo - o) * inv, (hi - o) * inv);
        if near > far {
            std::mem::swap(&mut near, &mut far);
        }
        if near > t0 {
            t0 = near;
            a0 = axis;
        }
        if far < t1 {
            t1 = far;
            a1 = axis;
        }
        if t0 > t1 {
            return None;
        }
    }
    Some((t0, a0, t1, a1))
}

/// A pinhole camera.
#[derive(Clone, Copy, Debug)]
pub struct Camera {
    origin: V3,
    forward: V3,
    right: V3,
    up: V3,
    half_h: f32,
}

impl Camera {
    /// A camera at `position` looking at `look_at`, `fov_deg` the vertical field of view.
    /// Looking along +z with +y up, +x is to the right (left-handed, as POV-Ray).
    pub fn new(position: V3, look_at: V3, up: V3, fov_deg: f32) -> Self {
        let forward = (look_at - position).normalize();
        // left-handed, as POV-Ray: x right, y up, z into the screen
        let right = up.cross(forward).normalize();
        let up = forward.cross(right);
        Self {
            origin: position,
            forward,
            right,
            up,
            half_h: (0.5 * fov_deg.to_radians()).tan(),
        }
    }

    /// The ray through the image point `(u, v) ∈ [0, 1]²` (`v = 0` at the top), `aspect` = w/h.
    #[inline]
    pub fn ray(&self, u: f32, v: f32, aspect: f32) -> Ray {
        let x = (2.0 * u - 1.0) * self.half_h * aspect;
        let y = (1.0 - 2.0 * v) * self.half_h;
        Ray {
            origin: self.origin,
            dir: (self.forward + self.right * x + self.up * y).normalize(),
        }
    }
}

/// A ray from `o` along `d` (normalised): the tests' shorthand (here and in `mesh`).
#[cfg(test)]
pub(crate) fn ray(o: [f32; 3], d: [f32; 3]) -> Ray {
    Ray {
        origin: V3::from_array(o),
        dir: V3::from_array(d).normalize(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sphere_hits_front_and_back() {
        let s = Shape::Sphere {
            center: V3::new(0.0, 0.0, 5.0),
            radius: 1.0,
        };
        let h = s.intersect(&ray([0.0; 3], [0.0, 0.0, 1.0]), 1e9).unwrap();
        assert!((h.t - 4.0).abs() < 1e-5);
        assert!((h.normal.z + 1.0).abs() < 1e-5);
        assert_eq!(s.crossings(&ray([0.0; 3], [0.0, 0.0, 1.0]), 1e9), 2);
        assert_eq!(s.crossings(&ray([0.0, 0.0, 5.0], [0.0, 0.0, 1.0]), 1e9), 1);
        assert!(s.intersect(&ray([0.0; 3], [0.0, 1.0, 0.0]), 1e9).is_none());
    }

    #[test]
    fn box_normals_point_out() {
        let b = Shape::Box {
            min: V3::new(-1.0, -1.0, -1.0),
            max: V3::new(1.0, 1.0, 1.0),
        };
        let h = b
            .intersect(&ray([0.0, 0.0, -5.0], [0.0, 0.0, 1.0]), 1e9)
            .unwrap();
        assert!((h.t - 4.0).abs() < 1e-5 && h.normal == V3::new(0.0, 0.0, -1.0));
        let h = b.intersect(&ray([0.0; 3], [1.0, 0.0, 0.0]), 1e9).unwrap();
        assert!((h.t - 1.0).abs() < 1e-5 && h.normal == V3::new(1.0, 0.0, 0.0));
        assert_eq!(b.crossings(&ray([0.0, 0.0, -5.0], [0.0, 0.0, 1.0]), 1e9), 2);
    }

    #[test]
    fn refraction_obeys_snell() {
        let d = V3::new(1.0, -1.0, 0.0).normalize();
        let n = V3::new(0.0, 1.0, 0.0);
        let t = d.refract(n, 1.0 / 1.5).unwrap();
        let sin_i = d.x;
        let sin_t = t.x;
        assert!((sin_i - 1.5 * sin_t).abs() < 1e-5);
        // grazing from inside the denser medium: total internal reflection
        assert!(V3::new(0.9, -0.1, 0.0)
            .normalize()
            .refract(n, 1.5)
            .is_none());
    }
}
