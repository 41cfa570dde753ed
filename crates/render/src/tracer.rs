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

use crate::filter::{Crossings, Filter, FilteredFirst};
use crate::geometry::{Camera, Ray, Shape, EPS, V3};
use crate::lights::Emitter;
use crate::mesh::{Owner, Triangles};
use crate::scene::{Material, Object, Scene};
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

#[inline]
fn count_ray() {
    RAYS.with(|r| r.set(r.get() + 1));
}

/// Phong lobes `(R·V)ⁿ` below this are dropped.
pub(super) const PHONG_MIN: f32 = 1e-6;

/// The energy-normalised Phong lobe `(n + 2)/(2π) · (R·V)ⁿ` (Lewis, "Making shaders more
/// physically plausible", 1994) for light arriving along `l` (unit, toward the light) at a
/// surface with unit normal `n` seen from `v`; 0 below [`PHONG_MIN`].
#[inline]
pub(super) fn phong_lobe(exponent: f32, l: V3, n: V3, v: V3) -> f32 {
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

/// One coefficient of a material (a reflectance or filter) in representation `T`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Coef<T> {
    /// The value.
    pub(super) value: T,
    /// `Some(k)` when the spectrum is flat: products with it are scalings, and
    /// `xyz(T·k) = k·xyz(T)`.
    pub(super) flat: Option<f32>,
    /// Its largest value over 380–780 nm (bounds a path's weight).
    pub(super) max: f32,
}

impl<T: Shade> Coef<T> {
    /// `path · self`.
    #[inline]
    pub(super) fn times(&self, path: &T) -> T {
        match self.flat {
            Some(k) => path.scale(k),
            None => path.mul(&self.value),
        }
    }

    /// `path · self`, with `None` the path of weight one.
    #[inline]
    pub(super) fn after(&self, path: Option<&T>) -> T {
        match path {
            Some(p) => self.times(p),
            None => self.value,
        }
    }

    /// [`Self::after`] by reference: `self`'s value itself for the path of weight one (no
    /// copy), else the product, formed into `formed`.
    #[inline]
    pub(super) fn after_ref<'a>(&'a self, path: Option<&T>, formed: &'a mut Option<T>) -> &'a T {
        match path {
            Some(p) => formed.insert(self.times(p)),
            None => &self.value,
        }
    }

    /// `xyz(path · self)` under `light`; `prod` is `path · self` if already formed, and
    /// `path_xyz` caches `xyz(path)` for flat coefficients.
    #[inline]
    pub(super) fn xyz(
        &self,
        path: &T,
        prod: Option<&T>,
        path_xyz: &mut Option<Xyz>,
        light: &T::Light,
    ) -> Xyz {
        match (self.flat, prod) {
            (Some(k), _) => path_xyz.get_or_insert_with(|| path.xyz(light)).scale(k),
            (None, Some(p)) => p.xyz(light),
            // spectral: `times` is `path.mul(value)`; product and integral in one step
            (None, None) => path.mul_xyz(&self.value, light),
        }
    }
}

/// A material with its spectra in representation `T`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Mat<T> {
    pub(super) diffuse: Option<Coef<T>>,
    pub(super) specular: Option<Coef<T>>,
    pub(super) phong: f32,
    pub(super) mirror: Option<Coef<T>>,
    pub(super) transmission: Option<Coef<T>>,
    pub(super) ior: f32,
}

impl<T: Shade> Mat<T> {
    /// At deeper hits (throughput `tp`), `T·D` and `T·S` (spectral coefficients only), formed
    /// once for all lights. A struct read by reference: destructuring a returned pair copied
    /// both 132-byte halves at every hit (`memcpy`, 8 % of a poly frame of example2).
    #[inline]
    pub(super) fn times(&self, tp: Option<&T>) -> Formed<T> {
        Formed {
            td: match (tp, &self.diffuse) {
                (Some(tp), Some(d)) if d.flat.is_none() => Some(d.times(tp)),
                _ => None,
            },
            ts: match (tp, &self.specular) {
                (Some(tp), Some(s)) if s.flat.is_none() => Some(s.times(tp)),
                _ => None,
            },
        }
    }

    /// Its transmission filter if a shadow ray passes (with `refraction_blocks`, not through a
    /// refracting surface). By reference: a spectral `Coef` is 136 bytes, and copying it per
    /// crossing was 11 % of a poly frame of example2 (`memcpy` calls; docs/performance.md).
    #[inline]
    pub(super) fn filter(&self, refraction_blocks: bool) -> Option<&Coef<T>> {
        match &self.transmission {
            Some(f) if !(refraction_blocks && self.ior != 1.0) => Some(f),
            _ => None,
        }
    }
}

/// `T·D` and `T·S` at a hit ([`Mat::times`]).
pub(super) struct Formed<T> {
    /// `T·D`, if formed.
    pub(super) td: Option<T>,
    /// `T·S`, if formed.
    pub(super) ts: Option<T>,
}

/// The shading frame of a hit, shared by the Whitted and path tracers.
#[derive(Clone, Copy, Debug)]
pub(super) struct Frame {
    /// The hit point.
    pub(super) p: V3,
    /// Toward the viewer.
    pub(super) v: V3,
    /// Whether the ray enters the surface (meets its front side).
    pub(super) entering: bool,
    /// The shading normal, facing the viewer.
    pub(super) n: V3,
    /// `p` lifted off the surface along `n`: where reflected and shadow rays start.
    pub(super) lift: V3,
}

impl Frame {
    /// The frame where `ray` meets a surface of geometric normal `normal` at distance `t`.
    #[inline]
    pub(super) fn at(ray: &Ray, t: f32, normal: V3) -> Self {
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
    pub(super) fn through(&self, dir: V3, ior: f32) -> Ray {
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
pub(super) struct LightT<T: Shade> {
    pub(super) position: V3,
    pub(super) intensity: f32,
    pub(super) light: T::Light,
}

/// An area light in representation `T`.
pub(super) struct AreaT<T: Shade> {
    pub(super) shape: Emitter,
    pub(super) radiance: f32,
    pub(super) light: T::Light,
    /// `radiance · xyz(1, L)`: what the eye sees of it.
    pub(super) emit_xyz: Xyz,
}

/// The environment light in representation `T`.
pub(super) struct EnvT<T: Shade> {
    pub(super) radiance: f32,
    pub(super) light: T::Light,
    /// `radiance · xyz(1, L)`.
    pub(super) emit_xyz: Xyz,
}

/// What a ray hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Surf {
    /// A surface with material `usize`.
    Mat(usize),
    /// Area light `usize`.
    Light(usize),
}

/// The light transport algorithm.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Integrator {
    /// Whitted's recursive ray tracer (the paper's model), deterministic.
    #[default]
    Whitted,
    /// A unidirectional path tracer with next-event estimation and Russian roulette.
    Path,
}

impl std::str::FromStr for Integrator {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "whitted" => Ok(Integrator::Whitted),
            "path" => Ok(Integrator::Path),
            _ => Err(format!("integrator `{s}`: use whitted or path")),
        }
    }
}

impl std::fmt::Display for Integrator {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Integrator::Whitted => "whitted",
            Integrator::Path => "path",
        })
    }
}

/// A scene compiled for representation `T`: every spectrum converted once, lights precomputed,
/// and the first-hit XYZ of every material under every light tabulated.
pub struct Compiled<T: Shade> {
    pub(super) mats: Vec<Mat<T>>,
    objects: Vec<Object>,
    pub(super) triangles: Arc<Triangles>,
    pub(super) lights: Vec<LightT<T>>,
    pub(super) area: Vec<AreaT<T>>,
    pub(super) env: Option<EnvT<T>>,
    ambient: T::Light,
    ambient_k: f32,
    background: Option<T>,
    background_xyz: Xyz,
    /// `[material][light slot]`: `(xyz(D, L), xyz(S, L))`; the slots are the point lights,
    /// then the area lights ([`Self::area_slot`]).
    first: Vec<Vec<(Xyz, Xyz)>>,
    /// The same through 1–2 crossings of each filter ([`FilteredFirst`]).
    pub(super) first_filtered: FilteredFirst,
    /// `[material]`: `k_a · xyz(D, L_a)`.
    first_ambient: Vec<Xyz>,
    pub(super) camera: Camera,
    width: u32,
    height: u32,
    samples: u32,
    pub(super) max_depth: u32,
    cutoff: f32,
    pub(super) integrator: Integrator,
    pub(super) spp: u32,
    pub(super) seed: u64,
    light_samples: u32,
    /// Hero-wavelength sampling: materials bound to wavelengths drawn per path
    /// ([`crate::hero`]); `None` in every other mode.
    pub(super) per_path: Option<crate::hero::PerPath<T>>,
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
            per_path: None,
        })
    }

    /// The light slot of area light `k` in the first-hit tables.
    #[inline]
    pub(super) fn area_slot(&self, k: usize) -> usize {
        self.lights.len() + k
    }

    /// Image width.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Image height.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The nearest hit: `(t, outward normal, what)`: objects, triangles and area lights.
    #[inline]
    pub(super) fn nearest(&self, ray: &Ray) -> Option<(f32, V3, Surf)> {
        count_ray();
        let mut best: Option<(f32, V3, usize)> = None;
        let mut t_max = f32::INFINITY;
        for (i, o) in self.objects.iter().enumerate() {
            if let Some(h) = o.shape.intersect(ray, t_max) {
                t_max = h.t;
                best = Some((h.t, h.normal, i));
            }
        }
        let mut other: Option<(f32, V3, Surf)> = None;
        if let Some((t, n, m)) = self.triangles.intersect(ray, t_max) {
            t_max = t;
            other = Some((
                t,
                n,
                match m {
                    Owner::Material(m) => Surf::Mat(m),
                    Owner::Light(k) => Surf::Light(k),
                },
            ));
        }
        for (k, l) in self.area.iter().enumerate() {
            if let Some((t, n)) = l.shape.intersect(ray, t_max) {
                t_max = t;
                other = Some((t, n, Surf::Light(k)));
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
            (t, n, Surf::Mat(m))
        })
    }

    /// What reaches `p` from a light at distance `dist` along `dir`: `None` if blocked, else
    /// the filters crossed ([`Filter`]; a product of several is kept in `scratch`).
    /// With `refraction_blocks`, transmitting surfaces with an index of refraction other
    /// than 1 block (the path tracer reaches lights through them by refraction instead).
    #[inline]
    pub(super) fn shadow<'a>(
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

    /// Adds to `out` the light arriving along `ray` with throughput `tp` (`None` = 1) whose
    /// largest value is at most `weight`.
    fn trace(&self, ray: &Ray, tp: Option<&T>, weight: f32, depth: u32, out: &mut Xyz) {
        let Some((t, normal, surf)) = self.nearest(ray) else {
            *out = *out
                + match (tp, &self.background) {
                    (None, _) => self.background_xyz,
                    (Some(tp), Some(b)) => tp.mul_xyz(b, &self.ambient),
                    (Some(_), None) => Xyz::default(),
                };
            // the environment, if any, is seen behind the background
            if let Some(e) = &self.env {
                *out = *out + self.emitted(tp, &e.light, e.radiance, e.emit_xyz);
            }
            return;
        };
        let mi = match surf {
            Surf::Mat(mi) => mi,
            Surf::Light(k) => {
                let l = &self.area[k];
                *out = *out + self.emitted(tp, &l.light, l.radiance, l.emit_xyz);
                return;
            }
        };
        let m = &self.mats[mi];
        let hit = Frame::at(ray, t, normal);
        let Frame { p, n, lift, .. } = hit;

        if m.diffuse.is_some() || m.specular.is_some() {
            let mut acc = Xyz::default();
            let formed = m.times(tp);
            let (td, ts) = (&formed.td, &formed.ts);
            match (tp, &m.diffuse) {
                (None, _) => acc = acc + self.first_ambient[mi],
                (Some(tp), Some(d)) if self.ambient_k > 0.0 => {
                    let x = d.xyz(tp, td.as_ref(), &mut None, &self.ambient);
                    acc = acc + x.scale(self.ambient_k);
                }
                _ => {}
            }
            for (li, l) in self.lights.iter().enumerate() {
                let mut scratch = None;
                let Some((filter, a, b)) =
                    self.point_weights(&self.mats, &mut scratch, l, m, &hit, p, false)
                else {
                    continue;
                };
                let at = tp.is_none().then_some((mi, li));
                acc = acc + self.light_term(m, tp, td, ts, &filter, a, b, &l.light, at);
            }
            // area lights: an n × n stratified grid of samples each (deterministic)
            let ns = self.light_samples;
            let inv_n = 1.0 / (ns * ns) as f32;
            for (k, l) in self.area.iter().enumerate() {
                let at = tp.is_none().then_some((mi, self.area_slot(k)));
                let (mut a_sum, mut b_sum) = (0.0f32, 0.0f32);
                for i in 0..ns {
                    for j in 0..ns {
                        let (u1, u2) = ((i as f32 + 0.5) / ns as f32, (j as f32 + 0.5) / ns as f32);
                        let mut scratch = None;
                        let Some((filter, a, b)) = self.area_weights(
                            &self.mats,
                            &mut scratch,
                            l,
                            m,
                            &hit,
                            (u1, u2),
                            inv_n,
                            false,
                        ) else {
                            continue;
                        };
                        if filter.is_clear() {
                            a_sum += a;
                            b_sum += b;
                        } else {
                            acc = acc + self.light_term(m, tp, td, ts, &filter, a, b, &l.light, at);
                        }
                    }
                }
                if a_sum > 0.0 || b_sum > 0.0 {
                    let clear = Filter::Clear;
                    acc = acc + self.light_term(m, tp, td, ts, &clear, a_sum, b_sum, &l.light, at);
                }
            }
            *out = *out + acc;
        }

        if depth >= self.max_depth {
            return;
        }
        if let Some(mirror) = &m.mirror {
            let w = weight * mirror.max;
            if w >= self.cutoff {
                let r = Ray {
                    origin: lift,
                    dir: ray.dir.reflect(n),
                };
                let mut formed = None;
                let next = mirror.after_ref(tp, &mut formed);
                self.trace(&r, Some(next), w, depth + 1, out);
            }
        }
        if let Some(filter) = &m.transmission {
            let w = weight * filter.max;
            if w >= self.cutoff {
                let mut formed = None;
                let through = filter.after_ref(tp, &mut formed);
                self.trace(
                    &hit.through(ray.dir, m.ior),
                    Some(through),
                    w,
                    depth + 1,
                    out,
                );
            }
        }
    }

    /// Point light `l` seen from point `p` (the hit or its lift) of the hit `hit` on material
    /// `m`: the shadow ray's filter and the diffuse and specular weights `(filter, a, b)` for
    /// [`Self::light_term`]; `None` if the light is behind the surface or blocked. Shared by the
    /// Whitted and path tracers.
    #[allow(clippy::too_many_arguments)]
    #[inline]
    pub(super) fn point_weights<'a>(
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
    pub(super) fn area_weights<'a>(
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
    pub(super) fn emitted(&self, tp: Option<&T>, light: &T::Light, k: f32, white: Xyz) -> Xyz {
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
    pub(super) fn light_term(
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
                self.trace(&ray, None, 1.0, 0, &mut sum);
            }
        }
        sum.scale(1.0 / (n * n) as f32)
    }

    /// One row of pixels into `row` (length `width`), with the scene's integrator.
    pub fn row(&self, y: u32, row: &mut [Xyz]) {
        if self.integrator == Integrator::Path {
            return self.path_row(y, row);
        }
        for (x, px) in row.iter_mut().enumerate() {
            *px = self.pixel(x as u32, y);
        }
    }
}
