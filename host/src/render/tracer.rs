//! The Whitted ray tracer (Whitted, "An improved illumination model for shaded display",
//! CACM 23(6), 1980), generic over the colour representation `T: Shade` and monomorphised, so
//! every mode runs the same code.
//!
//! At a hit with material `(D, S, n, M, F)` the illumination model of the paper (§7) is
//!
//! `I = k_a·D ⊗ L_a + Σ_l v_l·I_l·[(N·L_l) D + (R_l·V)ⁿ S] ⊗ L_l + M·I(reflected) + F·I(refracted)`
//!
//! (Lambertian diffuse, Phong 1975 highlights, mirror and refracted rays), where `⊗ L` means
//! "integrated against light `L`". A path carries its **throughput** `T` — the product of every
//! reflectance and filter met so far, a `Shade` value — and never a light: each light's
//! contribution is `xyz(T · (a·D + b·S), L_l) = a·xyz(T·D, L_l) + b·xyz(T·S, L_l)`, integrated
//! with the light's *exact* precomputed [`Shade::light`] (lights are never fitted, §7.1).
//! XYZ is linear in the spectrum, so at the first hit (`T = 1`) `xyz(D, L_l)` and `xyz(S, L_l)`
//! are precomputed per material and light, and deeper hits form `T·D` and `T·S` once for all
//! lights.
//!
//! Shadow rays see transparent objects as filters: each crossing of a transmitting surface
//! multiplies by its filter `F` (refraction is ignored on the way to the light, as Whitted does);
//! an opaque object blocks. A filter applies at **every** crossing of its surface, so a ray
//! through a solid transparent box is filtered twice (the box is a cell with filter walls).
//! Refraction follows Snell's law with the outside at index 1; total internal reflection sends
//! the transmitted share along the mirror direction.

use super::geometry::{Camera, Ray, Shape, EPS, V3};
use super::scene::{Material, Scene};
use specpoly_core::{Observer, Shade, Tabulated, Xyz};

/// A material with its spectra in representation `T`.
#[derive(Clone, Copy, Debug)]
struct Mat<T> {
    diffuse: Option<T>,
    specular: Option<T>,
    phong: f32,
    mirror: Option<T>,
    transmission: Option<T>,
    ior: f32,
}

/// A point light in representation `T`.
struct LightT<T: Shade> {
    position: V3,
    intensity: f32,
    light: T::Light,
}

/// A scene compiled for representation `T`: every spectrum converted once, lights precomputed,
/// and the first-hit XYZ of every material under every light tabulated.
pub struct Compiled<T: Shade> {
    mats: Vec<Mat<T>>,
    objects: Vec<(Shape, usize, Option<(usize, f32)>)>,
    lights: Vec<LightT<T>>,
    ambient: T::Light,
    ambient_k: f32,
    background: Option<T>,
    background_xyz: Xyz,
    /// `[material][light]`: `(xyz(D, L), xyz(S, L))`.
    first: Vec<Vec<(Xyz, Xyz)>>,
    /// `[material]`: `k_a · xyz(D, L_a)`.
    first_ambient: Vec<Xyz>,
    camera: Camera,
    width: u32,
    height: u32,
    samples: u32,
    max_depth: u32,
}

fn light_of<T: Shade>(observer: Observer, t: Tabulated<'_>, layout: T::Layout) -> T::Light {
    T::light(observer, &t, layout)
}

impl<T: Shade> Compiled<T> {
    /// Converts `scene` to representation `T` with `layout`. Reflectances are converted under the
    /// first point light (for RGB: each reflectance's exact colour under that light, the best an
    /// RGB renderer can know).
    pub fn new(scene: &Scene, layout: T::Layout) -> Result<Self, specpoly_core::Error> {
        let obs = scene.observer;
        let lights: Vec<LightT<T>> = scene
            .lights
            .iter()
            .map(|l| LightT {
                position: l.position,
                intensity: l.intensity,
                light: light_of::<T>(obs, l.spd.tabulated(), layout),
            })
            .collect();
        let ambient = light_of::<T>(obs, scene.ambient.spd.tabulated(), layout);
        let reference = match lights.first() {
            Some(l) => &l.light,
            None => &ambient,
        };
        let conv = |n: &Option<crate::spectra::Named>| -> Result<Option<T>, specpoly_core::Error> {
            n.as_ref()
                .map(|n| T::from_reflectance(&n.tabulated(), reference))
                .transpose()
        };
        let mats = scene
            .materials
            .iter()
            .map(|m: &Material| {
                Ok(Mat {
                    diffuse: conv(&m.diffuse)?,
                    specular: conv(&m.specular)?,
                    phong: m.phong,
                    mirror: conv(&m.mirror)?,
                    transmission: conv(&m.transmission)?,
                    ior: m.ior,
                })
            })
            .collect::<Result<Vec<_>, specpoly_core::Error>>()?;
        let background = conv(&scene.background)?;
        let xyz_or_zero = |v: &Option<T>, l: &T::Light| v.map(|v| v.xyz(l)).unwrap_or_default();
        let first = mats
            .iter()
            .map(|m| {
                lights
                    .iter()
                    .map(|l| {
                        (
                            xyz_or_zero(&m.diffuse, &l.light),
                            xyz_or_zero(&m.specular, &l.light),
                        )
                    })
                    .collect()
            })
            .collect();
        let ambient_k = scene.ambient.intensity;
        let first_ambient = mats
            .iter()
            .map(|m| xyz_or_zero(&m.diffuse, &ambient).scale(ambient_k))
            .collect();
        let background_xyz = xyz_or_zero(&background, &ambient);
        Ok(Self {
            objects: scene
                .objects
                .iter()
                .map(|o| (o.shape, o.material, o.checker))
                .collect(),
            mats,
            lights,
            ambient,
            ambient_k,
            background,
            background_xyz,
            first,
            first_ambient,
            camera: scene.camera,
            width: scene.render.width,
            height: scene.render.height,
            samples: scene.render.samples,
            max_depth: scene.render.max_depth,
        })
    }

    /// Image width.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Image height.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The nearest hit: `(t, outward normal, material index)`.
    #[inline]
    fn nearest(&self, ray: &Ray) -> Option<(f32, V3, usize)> {
        let mut best: Option<(f32, V3, usize)> = None;
        let mut t_max = f32::INFINITY;
        for (i, (shape, _, _)) in self.objects.iter().enumerate() {
            if let Some(h) = shape.intersect(ray, t_max) {
                t_max = h.t;
                best = Some((h.t, h.normal, i));
            }
        }
        best.map(|(t, n, i)| {
            let (shape, m, checker) = &self.objects[i];
            let mut m = *m;
            if let (Some((m2, size)), Shape::Plane { normal, .. }) = (checker, shape) {
                let p = ray.at(t);
                // two axes spanning the plane
                let a = if normal.x.abs() < 0.9 {
                    V3::new(1.0, 0.0, 0.0)
                } else {
                    V3::new(0.0, 1.0, 0.0)
                };
                let u = normal.cross(a).normalize();
                let v = normal.cross(u);
                let cu = (p.dot(u) / size).floor() as i64;
                let cv = (p.dot(v) / size).floor() as i64;
                if (cu + cv).rem_euclid(2) == 1 {
                    m = *m2;
                }
            }
            (t, n, m)
        })
    }

    /// What reaches `p` from a light at distance `dist` along `dir`: `None` if blocked,
    /// `Some(None)` if clear, `Some(Some(F))` through filters with product `F`.
    #[inline]
    fn shadow(&self, p: V3, dir: V3, dist: f32) -> Option<Option<T>> {
        let ray = Ray { origin: p, dir };
        let mut filter: Option<T> = None;
        for (shape, m, _) in &self.objects {
            let k = shape.crossings(&ray, dist);
            if k == 0 {
                continue;
            }
            let f = self.mats[*m].transmission?;
            for _ in 0..k {
                filter = Some(match filter {
                    Some(acc) => acc.mul(&f),
                    None => f,
                });
            }
        }
        Some(filter)
    }

    /// Adds to `out` the light arriving along `ray` with throughput `tp` (`None` = 1).
    fn trace(&self, ray: &Ray, tp: Option<&T>, depth: u32, out: &mut Xyz) {
        let Some((t, normal, mi)) = self.nearest(ray) else {
            *out = *out
                + match (tp, &self.background) {
                    (None, _) => self.background_xyz,
                    (Some(tp), Some(b)) => tp.mul(b).xyz(&self.ambient),
                    (Some(_), None) => Xyz::default(),
                };
            return;
        };
        let m = &self.mats[mi];
        let p = ray.at(t);
        let v = -ray.dir;
        let entering = normal.dot(ray.dir) < 0.0;
        // the shading normal faces the viewer
        let n = if entering { normal } else { -normal };
        let lift = p + n * EPS * 4.0;

        if m.diffuse.is_some() || m.specular.is_some() {
            // T·D and T·S, formed once for all lights (deeper hits only)
            let mut td: Option<(Option<T>, Option<T>)> = None;
            let mut acc = Xyz::default();
            if let Some(tp) = tp {
                let pair = (
                    m.diffuse.map(|d| tp.mul(&d)),
                    m.specular.map(|s| tp.mul(&s)),
                );
                if self.ambient_k > 0.0 {
                    if let Some(d) = &pair.0 {
                        acc = acc + d.xyz(&self.ambient).scale(self.ambient_k);
                    }
                }
                td = Some(pair);
            } else {
                acc = acc + self.first_ambient[mi];
            }
            for (li, l) in self.lights.iter().enumerate() {
                let to = l.position - p;
                let dist = to.length();
                if dist <= 0.0 {
                    continue;
                }
                let ldir = to * (1.0 / dist);
                let cos = n.dot(ldir);
                if cos <= 0.0 {
                    continue;
                }
                let Some(filter) = self.shadow(lift, ldir, dist) else {
                    continue;
                };
                let a = l.intensity * cos;
                let b = if m.specular.is_some() {
                    let r = (-ldir).reflect(n);
                    let rv = r.dot(v);
                    if rv > 0.0 {
                        l.intensity * rv.powf(m.phong)
                    } else {
                        0.0
                    }
                } else {
                    0.0
                };
                match (filter, &td) {
                    (None, None) => {
                        let (xd, xs) = self.first[mi][li];
                        acc = acc + xd.scale(a) + xs.scale(b);
                    }
                    (None, Some((d, s))) => {
                        if let Some(d) = d {
                            acc = acc + d.xyz(&l.light).scale(a);
                        }
                        if let (Some(s), true) = (s, b > 0.0) {
                            acc = acc + s.xyz(&l.light).scale(b);
                        }
                    }
                    (Some(f), _) => {
                        let f = match tp {
                            Some(tp) => tp.mul(&f),
                            None => f,
                        };
                        let mut local: Option<T> = m.diffuse.map(|d| d.scale(a));
                        if let (Some(s), true) = (&m.specular, b > 0.0) {
                            let s = s.scale(b);
                            local = Some(match local {
                                Some(l) => l.add(&s),
                                None => s,
                            });
                        }
                        if let Some(local) = local {
                            acc = acc + f.mul(&local).xyz(&l.light);
                        }
                    }
                }
            }
            *out = *out + acc;
        }

        if depth >= self.max_depth {
            return;
        }
        let next = |w: &T| -> T {
            match tp {
                Some(tp) => tp.mul(w),
                None => *w,
            }
        };
        if let Some(mirror) = &m.mirror {
            let r = Ray {
                origin: lift,
                dir: ray.dir.reflect(n),
            };
            self.trace(&r, Some(&next(mirror)), depth + 1, out);
        }
        if let Some(filter) = &m.transmission {
            let eta = if entering { 1.0 / m.ior } else { m.ior };
            let through = next(filter);
            match ray.dir.refract(n, eta) {
                Some(d) => {
                    let r = Ray {
                        origin: p - n * EPS * 4.0,
                        dir: d,
                    };
                    self.trace(&r, Some(&through), depth + 1, out);
                }
                None => {
                    let r = Ray {
                        origin: lift,
                        dir: ray.dir.reflect(n),
                    };
                    self.trace(&r, Some(&through), depth + 1, out);
                }
            }
        }
    }

    /// XYZ of pixel `(x, y)` (white `Y = 100`): the mean over an `n × n` grid of sub-samples.
    pub fn pixel(&self, x: u32, y: u32) -> Xyz {
        let n = self.samples;
        let aspect = self.width as f32 / self.height as f32;
        let mut sum = Xyz::default();
        for sy in 0..n {
            for sx in 0..n {
                let u = (x as f32 + (sx as f32 + 0.5) / n as f32) / self.width as f32;
                let v = (y as f32 + (sy as f32 + 0.5) / n as f32) / self.height as f32;
                let ray = self.camera.ray(u, v, aspect);
                self.trace(&ray, None, 0, &mut sum);
            }
        }
        sum.scale(1.0 / (n * n) as f32)
    }

    /// One row of pixels into `row` (length `width`).
    pub fn row(&self, y: u32, row: &mut [Xyz]) {
        for (x, px) in row.iter_mut().enumerate() {
            *px = self.pixel(x as u32, y);
        }
    }
}
