//! A scene compiled for a colour representation `T: Shade` ([`Compiled`]): every spectrum
//! converted once, the lights in `T`, and the first-hit XYZ of every material under every light
//! tabulated; and the queries the integrators ([`crate::tracer`], [`crate::path`]) build on:
//! the nearest hit, shadow rays through filters (`filter`), the light terms of point
//! and area lights, emission, the ambient term and the background. Its fields are private; the
//! integrators read the settings ([`Settings`]), the materials and the lights through a small
//! `pub(crate)` surface.
//!
//! At a hit with material `(D, S, n, M, F)` a light's contribution is
//! `xyz(T · (a·D + b·S), L) = a·xyz(T·D, L) + b·xyz(T·S, L)`, integrated with the light's
//! *exact* precomputed [`Shade::light`] (lights are never fitted, §7.1). XYZ is linear in the
//! spectrum, so at the first hit (`T = 1`) `xyz(D, L)` and `xyz(S, L)` are precomputed per
//! material and light ([`Compiled::light_term`]).

use crate::filter::{Crossings, Filter, FilteredFirst};
use crate::geometry::{Camera, Ray, Shape, EPS, V3};
use crate::lights::Emitter;
use crate::material::{Coef, Mat, MatTables};
use crate::mesh::{Owner, Triangles};
use crate::scene::{Material, Object, Scene};
use crate::sections::Integrator;
use crate::texture::MaterialTextures;
use specpoly_core::{Shade, Xyz};
use std::f32::consts::PI;
use std::sync::Arc;

thread_local! {
    /// Rays traced by this thread (statistics).
    static RAYS: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
}

/// Rays traced so far by the calling thread; differences count a piece of work.
pub fn rays_traced() -> u64 {
    RAYS.with(|r| r.get())
}

/// Counts one ray traced by the calling thread ([`rays_traced`]).
#[inline]
fn count_ray() {
    RAYS.with(|r| r.set(r.get() + 1));
}

/// Phong lobes `(R·V)ⁿ` below this are dropped.
const PHONG_MIN: f32 = 1e-6;

/// The energy-normalised Phong lobe `(n + 2)/(2π) · (R·V)ⁿ` (Lewis, "Making shaders more
/// physically plausible", 1994) for light arriving along `l` (unit, toward the light) at a
/// surface with unit normal `n` seen from `v`; 0 below [`PHONG_MIN`].
#[inline]
fn phong_lobe(exponent: f32, l: V3, n: V3, v: V3) -> f32 {
    let rv = (-l).reflect(n).dot(v);
    if rv <= 0.0 {
        return 0.0;
    }
    let lobe = rv.powf(exponent);
    if lobe > PHONG_MIN {
        (exponent + 2.0) / (2.0 * PI) * lobe
    } else {
        0.0
    }
}

/// The shading frame of a hit, shared by the Whitted and path tracers.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Frame {
    /// The hit point.
    pub(crate) p: V3,
    /// Toward the viewer.
    pub(crate) v: V3,
    /// Whether the ray enters the surface (meets its front side).
    pub(crate) entering: bool,
    /// The shading normal, facing the viewer.
    pub(crate) n: V3,
    /// `p` lifted off the surface along `n`: where reflected and shadow rays start.
    pub(crate) lift: V3,
}

impl Frame {
    /// The frame where `ray` meets a surface of geometric normal `normal` at distance `t`.
    #[inline]
    pub(crate) fn at(ray: &Ray, t: f32, normal: V3) -> Self {
        let p = ray.at(t);
        let entering = normal.dot(ray.dir) < 0.0;
        let n = if entering { normal } else { -normal };
        Frame {
            p,
            v: -ray.dir,
            entering,
            n,
            lift: p + n * EPS * 4.0,
        }
    }

    /// The ray along `dir` refracted into (or out of) a material of index `ior`; on total
    /// internal reflection, the mirror ray.
    #[inline]
    pub(crate) fn through(&self, dir: V3, ior: f32) -> Ray {
        let eta = if self.entering { 1.0 / ior } else { ior };
        match dir.refract(self.n, eta) {
            Some(d) => Ray {
                origin: self.p - self.n * EPS * 4.0,
                dir: d,
            },
            None => Ray {
                origin: self.lift,
                dir: dir.reflect(self.n),
            },
        }
    }
}

/// A point light in representation `T`.
pub(crate) struct LightT<T: Shade> {
    position: V3,
    intensity: f32,
    /// Its spectrum in `T`.
    pub(crate) light: T::Light,
}

/// An area light in representation `T`.
pub(crate) struct AreaT<T: Shade> {
    shape: Emitter,
    /// Its radiance scale.
    pub(crate) radiance: f32,
    /// Its spectrum in `T`.
    pub(crate) light: T::Light,
    /// `radiance · xyz(1, L)`: what the eye sees of it.
    pub(crate) emit_xyz: Xyz,
}

/// The environment light in representation `T`.
pub(crate) struct EnvT<T: Shade> {
    /// Its radiance scale.
    pub(crate) radiance: f32,
    /// Its spectrum in `T`.
    pub(crate) light: T::Light,
    /// `radiance · xyz(1, L)`.
    pub(crate) emit_xyz: Xyz,
}

/// What a ray hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Surf {
    /// A surface with material `usize`.
    Mat(usize),
    /// Area light `usize`.
    Light(usize),
}

/// The image and integrator settings of a compiled scene (from `[render]` and `[camera]`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Settings {
    /// The camera.
    pub(crate) camera: Camera,
    /// Image width.
    pub(crate) width: u32,
    /// Image height.
    pub(crate) height: u32,
    /// Whitted: sub-samples per pixel along each axis.
    pub(crate) samples: u32,
    /// The deepest path (reflections and refractions).
    pub(crate) max_depth: u32,
    /// Whitted: rays whose path weight is below this are not traced.
    pub(crate) cutoff: f32,
    /// The light transport algorithm.
    pub(crate) integrator: Integrator,
    /// Path tracer: paths per pixel.
    pub(crate) spp: u32,
    /// Path tracer: the seed of the per-pixel random sequences.
    pub(crate) seed: u64,
    /// Whitted: each area light is sampled on an `n × n` grid.
    pub(crate) light_samples: u32,
}

/// Per-path spectral sampling in a compiled scene (hero wavelengths, [`crate::hero`]): every
/// material's 1 nm tables and the function that binds the materials to a path's wavelengths
/// and returns its starting throughput.
pub(crate) struct PerPath<T> {
    /// The 1 nm tables, in material order.
    pub(crate) tables: Vec<MatTables>,
    /// Binds `mats` to the wavelengths of `u`; the path's starting throughput.
    pub(crate) bind: fn(&[MatTables], f32, &mut [Mat<T>]) -> T,
}

/// A scene compiled for representation `T`: every spectrum converted once, lights precomputed,
/// and the first-hit XYZ of every material under every light tabulated.
pub struct Compiled<T: Shade> {
    mats: Vec<Mat<T>>,
    objects: Vec<Object>,
    triangles: Arc<Triangles>,
    lights: Vec<LightT<T>>,
    area: Vec<AreaT<T>>,
    env: Option<EnvT<T>>,
    ambient: T::Light,
    ambient_k: f32,
    background: Option<T>,
    background_xyz: Xyz,
    /// `[material][light slot]`: `(xyz(D, L), xyz(S, L))`; the slots are the point lights,
    /// then the area lights ([`Self::area_slot`]).
    first: Vec<Vec<(Xyz, Xyz)>>,
    /// The same through 1–2 crossings of each filter ([`FilteredFirst`]).
    first_filtered: FilteredFirst,
    /// `[material]`: `k_a · xyz(D, L_a)`.
    first_ambient: Vec<Xyz>,
    settings: Settings,
    /// Hero-wavelength sampling: materials bound to wavelengths drawn per path; `None` in
    /// every other mode.
    per_path: Option<PerPath<T>>,
    /// `[material]`: its textures, with the base colour's palette in `T`.
    textures: Vec<Option<TexT<T>>>,
}

/// A material's textures in representation `T` ([`crate::texture`]).
pub(crate) struct TexT<T> {
    src: Arc<MaterialTextures>,
    /// Each base-colour palette entry in `T` and its largest value over 380–780 nm.
    palette: Vec<(T, f32)>,
}

impl<T: Shade> Compiled<T> {
    /// Converts `scene` to representation `T`. Reflectances are converted under the
    /// first point light (for RGB: each reflectance's exact colour under that light, the best an
    /// RGB renderer can know).
    pub fn new(scene: &Scene) -> Result<Self, specpoly_core::Error> {
        let obs = scene.observer;
        let lights: Vec<LightT<T>> = scene
            .lights
            .iter()
            .map(|l| LightT {
                position: l.position,
                intensity: l.intensity,
                light: T::light(obs, &l.spd.tabulated()),
            })
            .collect();
        let ambient = T::light(obs, &scene.ambient.spd.tabulated());
        let white = |l: &T::Light, k: f32| T::constant(1.0, l).xyz(l).scale(k);
        let area: Vec<AreaT<T>> = scene
            .area_lights
            .iter()
            .map(|l| {
                let light = T::light(obs, &l.spd.tabulated());
                AreaT {
                    shape: l.shape.clone(),
                    radiance: l.radiance,
                    emit_xyz: white(&light, l.radiance),
                    light,
                }
            })
            .collect();
        let env = scene.environment.as_ref().map(|e| {
            let light = T::light(obs, &e.spd.tabulated());
            EnvT {
                radiance: e.radiance,
                emit_xyz: white(&light, e.radiance),
                light,
            }
        });
        let reference_light = T::light(obs, &scene.reference_spd().tabulated());
        let reference = &reference_light;
        let conv =
            |n: &Option<specpoly_spectra::spectrum_names::Named>| -> Result<Option<T>, specpoly_core::Error> {
                n.as_ref()
                    .map(|n| T::from_reflectance(&n.tabulated(), reference))
                    .transpose()
            };
        let coef =
            |n: &Option<specpoly_spectra::spectrum_names::Named>| -> Result<Option<Coef<T>>, specpoly_core::Error> {
                let Some(v) = conv(n)? else {
                    return Ok(None);
                };
                let named = n.as_ref().map(|n| n.tabulated());
                let samples: Vec<f64> = named
                    .map(|t| (380..=780).map(|nm| t.at(nm as f64)).collect())
                    .unwrap_or_default();
                let max = samples.iter().copied().fold(0.0f64, f64::max) as f32;
                let flat = match named {
                    Some(t) if t.values().iter().all(|v| *v == t.values()[0]) => {
                        Some(t.values()[0])
                    }
                    _ => None,
                };
                Ok(Some(Coef {
                    value: v,
                    flat,
                    max,
                }))
            };
        let mats = scene
            .materials
            .iter()
            .map(|m: &Material| {
                Ok(Mat {
                    diffuse: coef(&m.diffuse)?,
                    specular: coef(&m.specular)?,
                    phong: m.phong,
                    mirror: coef(&m.mirror)?,
                    transmission: coef(&m.transmission)?,
                    ior: m.ior,
                })
            })
            .collect::<Result<Vec<_>, specpoly_core::Error>>()?;
        let background = conv(&scene.background)?;
        let xyz_or_zero = |v: &Option<T>, l: &T::Light| v.map(|v| v.xyz(l)).unwrap_or_default();
        let coef_xyz = |c: &Option<Coef<T>>, l: &T::Light| xyz_or_zero(&c.map(|c| c.value), l);
        // light slots: the point lights, then the area lights
        let slots: Vec<&T::Light> = lights
            .iter()
            .map(|l| &l.light)
            .chain(area.iter().map(|l| &l.light))
            .collect();
        let first = mats
            .iter()
            .map(|m| {
                slots
                    .iter()
                    .map(|l| (coef_xyz(&m.diffuse, l), coef_xyz(&m.specular, l)))
                    .collect()
            })
            .collect();
        let first_filtered = FilteredFirst::new(&mats, &slots);
        drop(slots);
        let ambient_k = scene.ambient.intensity;
        let first_ambient = mats
            .iter()
            .map(|m| coef_xyz(&m.diffuse, &ambient).scale(ambient_k))
            .collect();
        let background_xyz = xyz_or_zero(&background, &ambient);
        let textures = scene
            .materials
            .iter()
            .map(|m| {
                m.textures
                    .as_ref()
                    .map(|src| texture_palette(src.clone(), reference))
                    .transpose()
            })
            .collect::<Result<Vec<_>, specpoly_core::Error>>()?;
        Ok(Self {
            objects: scene.objects.clone(),
            triangles: scene.triangles.clone(),
            mats,
            lights,
            area,
            env,
            first_filtered,
            ambient,
            ambient_k,
            background,
            background_xyz,
            first,
            first_ambient,
            settings: Settings {
                camera: scene.camera,
                width: scene.render.width,
                height: scene.render.height,
                samples: scene.render.samples,
                max_depth: scene.render.max_depth,
                cutoff: scene.render.cutoff,
                integrator: scene.render.integrator,
                spp: scene.render.spp,
                seed: scene.render.seed,
                light_samples: scene.render.light_samples,
            },
            per_path: None,
            textures,
        })
    }

    /// The material and shading normal at a hit on material `mi` (`m`: the scene's, or bound
    /// to a path's wavelengths) of triangle `tri` at `p` with normal `normal`, where the
    /// material has textures and the triangle texture coordinates: the diffuse reflectance the
    /// base-colour texture's filtered palette (its largest value bounded by the taps'
    /// weighted largest values), the normal the normal map's. `None` otherwise: the material
    /// and normal stand.
    #[inline]
    pub(crate) fn textured(
        &self,
        m: &Mat<T>,
        mi: usize,
        tri: Option<u32>,
        p: V3,
        normal: V3,
    ) -> Option<(Mat<T>, V3)> {
        let tex = self.textures.get(mi)?.as_ref()?;
        let (uv, tangent, bitangent) = self.triangles.surface_at(tri?, p, normal)?;
        let mut out = *m;
        let mut n = normal;
        if let Some(base) = &tex.src.base {
            let mut value: Option<T> = None;
            let mut max = 0.0f32;
            for (i, w) in base.taps(uv[0], uv[1]) {
                if w <= 0.0 {
                    continue;
                }
                let (v, vmax) = &tex.palette[i as usize];
                let v = v.scale(w);
                value = Some(match value {
                    Some(acc) => acc.add(&v),
                    None => v,
                });
                max += w * vmax;
            }
            out.diffuse = value.map(|value| Coef {
                value,
                flat: None,
                max,
            });
        }
        if let (Some(map), true) = (&tex.src.normal, tangent.length() > 0.0) {
            let [x, y, z] = map.at(uv[0], uv[1]);
            let mapped = tangent * x + bitangent * y + normal * z;
            let l = mapped.length();
            if l.is_finite() && l > 1e-6 {
                n = mapped * (1.0 / l);
            }
        }
        Some((out, n))
    }

    /// The light slot of area light `k` in the first-hit tables.
    #[inline]
    pub(crate) fn area_slot(&self, k: usize) -> usize {
        self.lights.len() + k
    }

    /// [`Self::new`] with per-path spectral sampling: the path tracer binds the materials to
    /// each path's wavelengths with `per_path` (hero wavelengths, [`crate::hero`]).
    pub(crate) fn with_per_path(mut self, per_path: PerPath<T>) -> Self {
        self.per_path = Some(per_path);
        self
    }

    /// Image width.
    pub fn width(&self) -> u32 {
        self.settings.width
    }

    /// Image height.
    pub fn height(&self) -> u32 {
        self.settings.height
    }

    /// The light transport algorithm.
    pub fn integrator(&self) -> Integrator {
        self.settings.integrator
    }

    /// The image and integrator settings.
    #[inline]
    pub(crate) fn settings(&self) -> &Settings {
        &self.settings
    }

    /// The materials, in scene order.
    #[inline]
    pub(crate) fn materials(&self) -> &[Mat<T>] {
        &self.mats
    }

    /// The point lights.
    #[inline]
    pub(crate) fn point_lights(&self) -> &[LightT<T>] {
        &self.lights
    }

    /// The area lights (in the order of [`Surf::Light`]).
    #[inline]
    pub(crate) fn area_lights(&self) -> &[AreaT<T>] {
        &self.area
    }

    /// The environment light, if any.
    #[inline]
    pub(crate) fn environment(&self) -> Option<&EnvT<T>> {
        self.env.as_ref()
    }

    /// Per-path spectral sampling (hero wavelengths); `None` in every other mode.
    #[inline]
    pub(crate) fn per_path(&self) -> Option<&PerPath<T>> {
        self.per_path.as_ref()
    }

    /// The first-hit colours through filters (for tests of the table).
    #[cfg(test)]
    pub(crate) fn first_filtered(&self) -> &FilteredFirst {
        &self.first_filtered
    }

    /// What a ray that leaves the scene with throughput `tp` (`None` = 1) sees of the
    /// background (Whitted): the background reflectance lit by the ambient light.
    #[inline]
    pub(crate) fn background(&self, tp: Option<&T>) -> Xyz {
        match (tp, &self.background) {
            (None, _) => self.background_xyz,
            (Some(tp), Some(b)) => tp.mul_xyz(b, &self.ambient),
            (Some(_), None) => Xyz::default(),
        }
    }

    /// The ambient term (Whitted) at a hit on material `mi` (`m`) with throughput `tp`
    /// (`None` = 1) and `td = tp·D` if formed: `k_a · xyz(T·D, L_a)`, tabulated at first hits
    /// when `mi` is given (`None`: a textured material, formed here); `None` where there is
    /// none.
    #[inline]
    pub(crate) fn ambient_term(
        &self,
        mi: Option<usize>,
        m: &Mat<T>,
        tp: Option<&T>,
        td: Option<&T>,
    ) -> Option<Xyz> {
        match (tp, &m.diffuse, mi) {
            (None, _, Some(mi)) => Some(self.first_ambient[mi]),
            (None, Some(d), None) if self.ambient_k > 0.0 => {
                Some(d.value.xyz(&self.ambient).scale(self.ambient_k))
            }
            (None, _, None) => None,
            (Some(tp), Some(d), _) if self.ambient_k > 0.0 => {
                let x = d.xyz(tp, td, &mut None, &self.ambient);
                Some(x.scale(self.ambient_k))
            }
            _ => None,
        }
    }

    /// The nearest hit: `(t, outward normal, what, triangle)`: objects, triangles and area
    /// lights; the triangle's index when it is one and the scene's triangles have texture
    /// coordinates ([`Self::textured`]).
    #[inline]
    pub(crate) fn nearest(&self, ray: &Ray) -> Option<(f32, V3, Surf, Option<u32>)> {
        count_ray();
        let mut best: Option<(f32, V3, usize)> = None;
        let mut t_max = f32::INFINITY;
        for (i, o) in self.objects.iter().enumerate() {
            if let Some(h) = o.shape.intersect(ray, t_max) {
                t_max = h.t;
                best = Some((h.t, h.normal, i));
            }
        }
        let mut other: Option<(f32, V3, Surf, Option<u32>)> = None;
        if let Some((t, n, m, i)) = self.triangles.intersect_indexed(ray, t_max) {
            t_max = t;
            other = Some((
                t,
                n,
                match m {
                    Owner::Material(m) => Surf::Mat(m),
                    Owner::Light(k) => Surf::Light(k),
                },
                self.triangles.has_surface().then_some(i),
            ));
        }
        for (k, l) in self.area.iter().enumerate() {
            if let Some((t, n)) = l.shape.intersect(ray, t_max) {
                t_max = t;
                other = Some((t, n, Surf::Light(k), None));
            }
        }
        if other.is_some() {
            return other;
        }
        best.map(|(t, n, i)| {
            let o = &self.objects[i];
            let mut m = o.material;
            if let (Some((m2, size)), Shape::Plane { normal, .. }) = (o.checker, o.shape) {
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
                    m = m2;
                }
            }
            (t, n, Surf::Mat(m), None)
        })
    }

    /// What reaches `p` from a light at distance `dist` along `dir`: `None` if blocked, else
    /// the filters crossed ([`Filter`]; a product of several is kept in `scratch`).
    /// With `refraction_blocks`, transmitting surfaces with an index of refraction other
    /// than 1 block (the path tracer reaches lights through them by refraction instead).
    #[inline]
    pub(crate) fn shadow<'a>(
        &self,
        mats: &'a [Mat<T>],
        scratch: &'a mut Option<T>,
        p: V3,
        dir: V3,
        dist: f32,
        refraction_blocks: bool,
    ) -> Option<Filter<'a, T>> {
        count_ray();
        let ray = Ray { origin: p, dir };
        let mut crossed = Crossings::new();
        for o in &self.objects {
            let k = o.shape.crossings(&ray, dist);
            if k == 0 {
                continue;
            }
            let f = mats[o.material].filter(refraction_blocks)?;
            for _ in 0..k {
                crossed.cross(f, o.material);
            }
        }
        let mut blocked = false;
        self.triangles.crossings(&ray, dist, |m| match m {
            // emissive meshes are opaque
            Owner::Light(_) => {
                blocked = true;
                false
            }
            Owner::Material(m) => match mats[m].filter(refraction_blocks) {
                Some(f) => {
                    crossed.cross(f, m);
                    true
                }
                None => {
                    blocked = true;
                    false
                }
            },
        });
        if blocked {
            return None;
        }
        Some(crossed.finish(scratch))
    }

    /// Point light `l` seen from point `p` (the hit or its lift) of the hit `hit` on material
    /// `m`: the shadow ray's filter and the diffuse and specular weights `(filter, a, b)` for
    /// [`Self::light_term`]; `None` if the light is behind the surface or blocked. Shared by the
    /// Whitted and path tracers.
    #[allow(clippy::too_many_arguments)]
    #[inline]
    pub(crate) fn point_weights<'a>(
        &self,
        mats: &'a [Mat<T>],
        scratch: &'a mut Option<T>,
        l: &LightT<T>,
        m: &Mat<T>,
        hit: &Frame,
        p: V3,
        refraction_blocks: bool,
    ) -> Option<(Filter<'a, T>, f32, f32)> {
        let Frame { lift, n, v, .. } = *hit;
        let to = l.position - p;
        let dist = to.length();
        if dist <= 0.0 {
            return None;
        }
        let ldir = to * (1.0 / dist);
        let cos = n.dot(ldir);
        if cos <= 0.0 {
            return None;
        }
        let filter = self.shadow(mats, scratch, lift, ldir, dist, refraction_blocks)?;
        let a = l.intensity * cos;
        let b = match &m.specular {
            Some(_) => {
                let rv = (-ldir).reflect(n).dot(v);
                let lobe = if rv > 0.0 { rv.powf(m.phong) } else { 0.0 };
                // below 10⁻⁶ of the light the highlight is dropped (< 10⁻⁴ in Y)
                if lobe > PHONG_MIN {
                    l.intensity * lobe
                } else {
                    0.0
                }
            }
            None => 0.0,
        };
        Some((filter, a, b))
    }

    /// One sample `u` of area light `l` from the hit `hit` on material `m`, weighted by `share`
    /// (1 for one sample): `(filter, a, b)` as for [`Self::point_weights`]; `None` if the
    /// sample misses or is blocked.
    #[allow(clippy::too_many_arguments)]
    #[inline]
    pub(crate) fn area_weights<'a>(
        &self,
        mats: &'a [Mat<T>],
        scratch: &'a mut Option<T>,
        l: &AreaT<T>,
        m: &Mat<T>,
        hit: &Frame,
        u: (f32, f32),
        share: f32,
        refraction_blocks: bool,
    ) -> Option<(Filter<'a, T>, f32, f32)> {
        let Frame { lift, n, v, .. } = *hit;
        let smp = l.shape.sample(lift, n, u.0, u.1)?;
        let filter = self.shadow(
            mats,
            scratch,
            lift,
            smp.dir,
            smp.dist * (1.0 - 1e-4),
            refraction_blocks,
        )?;
        let a = l.radiance * smp.weight * share / PI;
        let b = match &m.specular {
            Some(_) => l.radiance * smp.weight * share * phong_lobe(m.phong, smp.dir, n, v),
            None => 0.0,
        };
        Some((filter, a, b))
    }

    /// What an emitter of radiance `k · L` adds seen through throughput `tp` (`None` = 1;
    /// `white` is `k · xyz(1, L)`).
    #[inline]
    pub(crate) fn emitted(&self, tp: Option<&T>, light: &T::Light, k: f32, white: Xyz) -> Xyz {
        match tp {
            None => white,
            Some(tp) => tp.xyz(light).scale(k),
        }
    }

    /// `xyz(path · (a·D + b·S), L)` for one light, where `path` is the throughput `tp` (`None`
    /// = 1) times the shadow ray's `filter`; `td`, `ts` are `tp·D`, `tp·S` if already formed.
    /// `at = (material, light slot)` at first hits (`tp` one, materials the frame's): then the
    /// precomputed `xyz(D, L)`, `xyz(S, L)` (unfiltered) or `xyz(Fᶜ·D, L)`, `xyz(Fᶜ·S, L)`
    /// (through `c` crossings of one filter) are scaled instead of formed.
    #[allow(clippy::too_many_arguments)]
    #[inline]
    pub(crate) fn light_term(
        &self,
        m: &Mat<T>,
        tp: Option<&T>,
        td: &Option<T>,
        ts: &Option<T>,
        filter: &Filter<'_, T>,
        a: f32,
        b: f32,
        light: &T::Light,
        at: Option<(usize, usize)>,
    ) -> Xyz {
        let mut acc = Xyz::default();
        if m.diffuse.is_none() && (m.specular.is_none() || b <= 0.0) {
            // nothing lit (a specular-only surface outside its highlight): every branch below
            // would add only zeros, after forming a product through the filters for nothing
            return acc;
        }
        let at = if tp.is_none() { at } else { None };
        if let Filter::Clear = filter {
            match (tp, at) {
                (_, Some((mi, slot))) => {
                    let (xd, xs) = self.first[mi][slot];
                    acc = acc + xd.scale(a) + xs.scale(b);
                }
                (None, None) => {
                    if let Some(d) = &m.diffuse {
                        acc = acc + d.value.xyz(light).scale(a);
                    }
                    if let (Some(s), true) = (&m.specular, b > 0.0) {
                        acc = acc + s.value.xyz(light).scale(b);
                    }
                }
                (Some(tp), None) => {
                    let mut tp_xyz = None;
                    if let Some(d) = &m.diffuse {
                        acc = acc + d.xyz(tp, td.as_ref(), &mut tp_xyz, light).scale(a);
                    }
                    if let (Some(s), true) = (&m.specular, b > 0.0) {
                        acc = acc + s.xyz(tp, ts.as_ref(), &mut tp_xyz, light).scale(b);
                    }
                }
            }
            return acc;
        }
        if let (Filter::Same { mat, count, .. }, Some((mi, slot))) = (filter, at) {
            if let Some((xd, xs)) = self.first_filtered.get(mi, *mat, *count, slot) {
                // as formed below: the same values, added in the same order
                if m.diffuse.is_some() {
                    acc = acc + xd.scale(a);
                }
                if m.specular.is_some() && b > 0.0 {
                    acc = acc + xs.scale(b);
                }
                return acc;
            }
        }
        filter.with(|f| {
            let Some(f) = f else {
                return acc;
            };
            match td {
                Some(td) if b == 0.0 => {
                    // diffuse only, T·D already formed: (T·D)·F
                    acc = acc + td.mul_xyz(f, light).scale(a);
                }
                _ => {
                    // the light arrives through filters: path · F · (a·D + b·S)
                    let formed;
                    let path = match tp {
                        Some(tp) => {
                            formed = tp.mul(f);
                            &formed
                        }
                        None => f,
                    };
                    let mut path_xyz = None;
                    if let Some(d) = &m.diffuse {
                        acc = acc + d.xyz(path, None, &mut path_xyz, light).scale(a);
                    }
                    if let (Some(s), true) = (&m.specular, b > 0.0) {
                        acc = acc + s.xyz(path, None, &mut path_xyz, light).scale(b);
                    }
                }
            }
            acc
        })
    }
}

/// A material's textures with the base colour's palette formed in `T` (each entry's 1 nm
/// reflectance from its sigmoid coefficients, converted as every reflectance is).
fn texture_palette<T: Shade>(
    src: Arc<MaterialTextures>,
    reference: &T::Light,
) -> Result<TexT<T>, specpoly_core::Error> {
    use rayon::prelude::*;
    let nm = crate::upsample::wavelengths();
    let palette = match &src.base {
        Some(b) => b
            .palette
            .par_iter()
            .map(|c| {
                let r: Vec<f32> = nm
                    .iter()
                    .map(|&l| crate::upsample::eval(*c, l as f64) as f32)
                    .collect();
                let max = r.iter().copied().fold(0.0f32, f32::max);
                let t = specpoly_core::Tabulated::new(&nm, &r)?;
                Ok((T::from_reflectance(&t, reference)?, max))
            })
            .collect::<Result<Vec<_>, specpoly_core::Error>>()?,
        None => Vec::new(),
    };
    Ok(TexT { src, palette })
}
