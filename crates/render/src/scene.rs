//! The scene file (TOML, documented in `docs/scenes.md`) and its resolution into geometry and
//! tabulated spectra. Unknown keys are errors (`deny_unknown_fields`); every error names the
//! file and the object.

use crate::geometry::{Camera, Shape, V3};
use crate::upsample;
use serde::de::{self, Deserializer, MapAccess, Visitor};
use serde::Deserialize;
use specpoly_core::Observer;
use specpoly_formats::error::{CliError, Result};
use specpoly_spectra::spectrum_names::{self, Named};
use std::collections::BTreeMap;
use std::fmt;
use std::path::Path;

/// A spectrum as a scene file writes it.
#[derive(Clone, Debug, PartialEq)]
pub enum SpectrumSpec {
    /// A constant (flat) spectrum: `0.8`.
    Constant(f32),
    /// A spectrum name: `"colorchecker#red"`, `"FL11"`, `"my.csv#paint"`.
    Name(String),
    /// A table: `{ spectrum = NAME, scale = K, normalize = true }` or `{ rgb = [r, g, b] }`.
    Table(SpectrumTable),
}

/// The table form of a spectrum.
#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpectrumTable {
    /// A spectrum name.
    pub spectrum: Option<String>,
    /// A linear-sRGB colour, upsampled to a smooth reflectance (see [`upsample`]).
    pub rgb: Option<[f32; 3]>,
    /// Divide by the maximum over 380–780 nm first.
    #[serde(default)]
    pub normalize: bool,
    /// Multiply by this.
    pub scale: Option<f32>,
}

impl<'de> Deserialize<'de> for SpectrumSpec {
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = SpectrumSpec;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str(
                    "a spectrum: a number, a name like \"colorchecker#red\", or a table \
                     { spectrum = NAME, scale = K, normalize = BOOL } / { rgb = [R, G, B] }",
                )
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> std::result::Result<SpectrumSpec, E> {
                Ok(SpectrumSpec::Constant(v as f32))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> std::result::Result<SpectrumSpec, E> {
                Ok(SpectrumSpec::Constant(v as f32))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> std::result::Result<SpectrumSpec, E> {
                Ok(SpectrumSpec::Constant(v as f32))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> std::result::Result<SpectrumSpec, E> {
                Ok(SpectrumSpec::Name(v.to_string()))
            }
            fn visit_map<A: MapAccess<'de>>(
                self,
                m: A,
            ) -> std::result::Result<SpectrumSpec, A::Error> {
                let t = SpectrumTable::deserialize(de::value::MapAccessDeserializer::new(m))?;
                Ok(SpectrumSpec::Table(t))
            }
        }
        d.deserialize_any(V)
    }
}

fn zero() -> SpectrumSpec {
    SpectrumSpec::Constant(0.0)
}
fn one() -> f32 {
    1.0
}

/// `[render]`: image and tracer settings.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RenderSection {
    /// Image width (pixels).
    #[serde(default = "default_size")]
    pub width: u32,
    /// Image height (pixels).
    #[serde(default = "default_size")]
    pub height: u32,
    /// Samples per pixel along each axis (a regular `n × n` grid).
    #[serde(default = "default_samples")]
    pub samples: u32,
    /// Largest number of reflections/refractions along a path.
    #[serde(default = "default_depth")]
    pub max_depth: u32,
    /// `"1931"` or `"1964"`.
    #[serde(default = "default_observer")]
    pub observer: String,
    /// Scales every XYZ before display.
    #[serde(default = "one")]
    pub exposure: f32,
    /// Adapt the first light's white to the display white (Bradford) before display.
    #[serde(default = "yes")]
    pub white_balance: bool,
    /// Rays whose path weight (the product of the largest values of the reflectances and
    /// filters along it) falls below this are not traced (adaptive tree depth; 0 disables).
    #[serde(default = "default_cutoff")]
    pub cutoff: f32,
    /// `whitted` (default) or `path`.
    #[serde(default)]
    pub integrator: crate::tracer::Integrator,
    /// Path tracer: paths per pixel.
    #[serde(default = "default_spp")]
    pub spp: u32,
    /// Path tracer: the seed of the per-pixel random sequences.
    #[serde(default)]
    pub seed: u64,
    /// Whitted tracer: each area light is sampled on an `n × n` stratified grid.
    #[serde(default = "default_light_samples")]
    pub light_samples: u32,
}

fn default_spp() -> u32 {
    16
}
fn default_light_samples() -> u32 {
    4
}

fn default_cutoff() -> f32 {
    1e-3
}

fn default_size() -> u32 {
    256
}
fn default_samples() -> u32 {
    1
}
fn default_depth() -> u32 {
    5
}
fn default_observer() -> String {
    "1931".into()
}
fn yes() -> bool {
    true
}

impl Default for RenderSection {
    fn default() -> Self {
        Self {
            width: default_size(),
            height: default_size(),
            samples: default_samples(),
            max_depth: default_depth(),
            observer: default_observer(),
            exposure: 1.0,
            white_balance: true,
            cutoff: default_cutoff(),
            integrator: Default::default(),
            spp: default_spp(),
            seed: 0,
            light_samples: default_light_samples(),
        }
    }
}

/// `[camera]`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraSection {
    /// Eye position.
    pub position: [f32; 3],
    /// Point looked at.
    pub look_at: [f32; 3],
    /// Up direction.
    #[serde(default = "up")]
    pub up: [f32; 3],
    /// Vertical field of view (degrees).
    #[serde(default = "fov")]
    pub fov: f32,
}
fn up() -> [f32; 3] {
    [0.0, 1.0, 0.0]
}
fn fov() -> f32 {
    40.0
}

/// `[ambient]`: the ambient light and the background.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AmbientSection {
    /// The ambient light's spectral power distribution.
    pub spectrum: SpectrumSpec,
    /// Ambient intensity `k_a` (the ambient term is `k_a · diffuse`).
    #[serde(default)]
    pub intensity: f32,
    /// What rays that leave the scene see: a reflectance lit by the ambient light at unit
    /// intensity.
    #[serde(default = "zero")]
    pub background: SpectrumSpec,
}

/// `[[light]]`: a point light.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LightSection {
    /// Position.
    pub position: [f32; 3],
    /// Spectral power distribution (a name: `D65`, `FL11`, a file).
    pub spectrum: SpectrumSpec,
    /// Intensity: a white surface facing the light has `Y = 100 · intensity`.
    #[serde(default = "one")]
    pub intensity: f32,
}

/// `[materials.NAME]`: Whitted's illumination model with Phong highlights.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSection {
    /// Lambertian diffuse reflectance.
    #[serde(default = "zero")]
    pub diffuse: SpectrumSpec,
    /// Phong specular coefficient (a number, or a spectrum for coloured highlights).
    #[serde(default = "zero")]
    pub specular: SpectrumSpec,
    /// Phong exponent.
    #[serde(default = "default_phong")]
    pub phong: f32,
    /// Mirror reflectance.
    #[serde(default = "zero")]
    pub mirror: SpectrumSpec,
    /// Transmission filter, applied at every crossing of the surface.
    #[serde(default = "zero")]
    pub transmission: SpectrumSpec,
    /// Index of refraction (of the inside; the outside is air, 1).
    #[serde(default = "one")]
    pub ior: f32,
}
fn default_phong() -> f32 {
    32.0
}

/// `[[sphere]]`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SphereSection {
    /// Centre.
    pub center: [f32; 3],
    /// Radius (> 0).
    pub radius: f32,
    /// Material name.
    pub material: String,
}

/// `[[plane]]`, optionally a checkerboard of two materials.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlaneSection {
    /// A point on the plane.
    pub point: [f32; 3],
    /// The normal (front side).
    pub normal: [f32; 3],
    /// Material name.
    pub material: String,
    /// Second material of a checkerboard.
    pub checker_material: Option<String>,
    /// Checker square size.
    #[serde(default = "one")]
    pub checker_size: f32,
}

/// `[[box]]`: axis-aligned.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoxSection {
    /// Lower corner.
    pub min: [f32; 3],
    /// Upper corner.
    pub max: [f32; 3],
    /// Material name.
    pub material: String,
}

/// A scene file.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// Image and tracer settings.
    #[serde(default)]
    pub render: RenderSection,
    /// Camera.
    pub camera: CameraSection,
    /// Ambient light and background.
    pub ambient: Option<AmbientSection>,
    /// Point lights.
    #[serde(default)]
    pub light: Vec<LightSection>,
    /// Materials by name.
    #[serde(default)]
    pub materials: BTreeMap<String, MaterialSection>,
    /// Spheres.
    #[serde(default)]
    pub sphere: Vec<SphereSection>,
    /// Planes.
    #[serde(default)]
    pub plane: Vec<PlaneSection>,
    /// Boxes.
    #[serde(default, rename = "box")]
    pub boxes: Vec<BoxSection>,
    /// Quads (two triangles each).
    #[serde(default)]
    pub quad: Vec<crate::scene_geometry::QuadSection>,
    /// Triangle meshes from OBJ files.
    #[serde(default)]
    pub mesh: Vec<crate::scene_geometry::MeshSection>,
    /// Area lights.
    #[serde(default)]
    pub area_light: Vec<crate::scene_geometry::AreaLightSection>,
    /// The environment light.
    pub environment: Option<crate::scene_geometry::EnvironmentSection>,
    /// The folder file names resolve against (the scene file's; not in the file).
    #[serde(skip)]
    pub base: Option<std::path::PathBuf>,
}

/// A material with every spectrum resolved to tabulated data (`None` = zero).
#[derive(Clone, Debug)]
pub struct Material {
    /// Its name in the file.
    pub name: String,
    /// Lambertian diffuse reflectance.
    pub diffuse: Option<Named>,
    /// Phong specular coefficient.
    pub specular: Option<Named>,
    /// Phong exponent.
    pub phong: f32,
    /// Mirror reflectance.
    pub mirror: Option<Named>,
    /// Transmission filter.
    pub transmission: Option<Named>,
    /// Index of refraction.
    pub ior: f32,
}

/// A point light with its spectrum.
#[derive(Clone, Debug)]
pub struct Light {
    /// Position.
    pub position: V3,
    /// Spectral power distribution (tabulated, never fitted).
    pub spd: Named,
    /// Intensity.
    pub intensity: f32,
}

/// A shape and its material(s): `materials.1` is the checkerboard's second material.
#[derive(Clone, Debug)]
pub struct Object {
    /// Geometry.
    pub shape: Shape,
    /// Material index.
    pub material: usize,
    /// Checkerboard: second material and square size.
    pub checker: Option<(usize, f32)>,
}

/// A resolved scene: geometry, materials and lights with tabulated spectra.
#[derive(Clone, Debug)]
pub struct Scene {
    /// Image and tracer settings.
    pub render: RenderSection,
    /// The observer.
    pub observer: Observer,
    /// Camera.
    pub camera: Camera,
    /// Ambient light.
    pub ambient: Light,
    /// The background reflectance (lit by the ambient light at unit intensity).
    pub background: Option<Named>,
    /// Point lights.
    pub lights: Vec<Light>,
    /// Materials.
    pub materials: Vec<Material>,
    /// Objects.
    pub objects: Vec<Object>,
    /// Every triangle (quads and meshes) with its BVH.
    pub triangles: std::sync::Arc<crate::mesh::Triangles>,
    /// Area lights.
    pub area_lights: Vec<crate::lights::AreaLight>,
    /// The environment light.
    pub environment: Option<crate::lights::Environment>,
}

impl Scene {
    /// The light reflectances are judged under (RGB mode's conversion, the white point): the
    /// first point light, else the first area light, else the environment, else the ambient.
    pub fn reference_spd(&self) -> &Named {
        self.lights
            .first()
            .map(|l| &l.spd)
            .or_else(|| self.area_lights.first().map(|l| &l.spd))
            .or_else(|| self.environment.as_ref().map(|e| &e.spd))
            .unwrap_or(&self.ambient.spd)
    }
}

fn is_zero(s: &SpectrumSpec) -> bool {
    matches!(s, SpectrumSpec::Constant(v) if *v == 0.0)
}

fn flat(name: String, v: f32) -> Result<Named> {
    Ok(Named::new(name, vec![380.0, 780.0], vec![v, v])?)
}

/// Resolves one spectrum; `what` names it in errors (`scene.toml: materials.red.diffuse`).
/// File names are taken as given (relative to the current folder).
pub fn resolve_spectrum(spec: &SpectrumSpec, what: &str) -> Result<Named> {
    resolve_spectrum_in(spec, what, None)
}

/// `name` (`FILE`, `FILE#COLUMN`, or a built-in) with a relative `FILE` taken relative to
/// `base`, the scene file's folder. Built-in names (illuminants, tables) stay as they are.
pub fn rebase(name: &str, base: Option<&Path>) -> String {
    let Some(base) = base else {
        return name.to_string();
    };
    let (file, column) = match name.split_once('#') {
        Some((f, c)) => (f, Some(c)),
        None => (name, None),
    };
    let builtin = specpoly_core::Illuminant::from_name(file).is_some()
        || specpoly_spectra::data::TABLES
            .iter()
            .any(|t| t.name.eq_ignore_ascii_case(file));
    let path = Path::new(file);
    if builtin || path.is_absolute() {
        return name.to_string();
    }
    let joined = base.join(path).display().to_string();
    match column {
        Some(c) => format!("{joined}#{c}"),
        None => joined,
    }
}

/// [`resolve_spectrum`] with relative file names taken relative to `base`.
pub fn resolve_spectrum_in(spec: &SpectrumSpec, what: &str, base: Option<&Path>) -> Result<Named> {
    let data = |e: CliError| CliError::data(format!("{what}: {e}"));
    let finite = |v: f32, field: &str| {
        if v.is_finite() {
            Ok(v)
        } else {
            Err(CliError::data(format!("{what}: {field} must be finite")))
        }
    };
    match spec {
        SpectrumSpec::Constant(v) => flat(format!("{v}"), finite(*v, "the value")?),
        SpectrumSpec::Name(n) => {
            let mut v = spectrum_names::resolve(&rebase(n, base)).map_err(|e| data(e.into()))?;
            if v.len() != 1 {
                return Err(CliError::data(format!(
                    "{what}: `{n}` names {} spectra; name one column",
                    v.len()
                )));
            }
            Ok(v.remove(0))
        }
        SpectrumSpec::Table(t) => {
            let mut named = match (&t.spectrum, t.rgb) {
                (Some(_), Some(_)) => {
                    return Err(CliError::data(format!(
                        "{what}: give either `spectrum` or `rgb`, not both"
                    )))
                }
                (None, None) => {
                    return Err(CliError::data(format!(
                        "{what}: a spectrum table needs `spectrum = NAME` or `rgb = [R, G, B]`"
                    )))
                }
                (Some(n), None) => resolve_spectrum_in(&SpectrumSpec::Name(n.clone()), what, base)?,
                (None, Some(rgb)) => {
                    for c in rgb {
                        finite(c, "rgb")?;
                    }
                    Named::new(
                        format!("rgb({}, {}, {})", rgb[0], rgb[1], rgb[2]),
                        upsample::wavelengths(),
                        upsample::rgb_to_reflectance(rgb),
                    )?
                }
            };
            let mut k = finite(t.scale.unwrap_or(1.0), "scale")?;
            if t.normalize {
                let t = named.tabulated();
                let max = (380..=780).map(|nm| t.at(nm as f64)).fold(0.0f64, f64::max);
                if max <= 0.0 {
                    return Err(CliError::data(format!(
                        "{what}: cannot normalize `{}`: its maximum is not positive",
                        named.name
                    )));
                }
                k /= max as f32;
            }
            if k != 1.0 {
                for v in named.values.iter_mut() {
                    *v *= k;
                }
                named.name = format!("{}×{k}", named.name);
            }
            Ok(named)
        }
    }
}

fn optional(spec: &SpectrumSpec, what: &str, base: Option<&Path>) -> Result<Option<Named>> {
    if is_zero(spec) {
        Ok(None)
    } else {
        resolve_spectrum_in(spec, what, base).map(Some)
    }
}

pub(super) fn v3(a: [f32; 3], what: &str) -> Result<V3> {
    if a.iter().all(|v| v.is_finite()) {
        Ok(V3::from_array(a))
    } else {
        Err(CliError::data(format!(
            "{what}: coordinates must be finite"
        )))
    }
}

impl SceneFile {
    /// Parses TOML text; `source` names the file in errors.
    pub fn parse(text: &str, source: &str) -> Result<Self> {
        toml::from_str(text)
            .map_err(|e| CliError::data(specpoly_formats::toml_error::one_line(&e, text, source)))
    }

    /// Resolves names, checks values and builds the scene. `source` names the file in errors.
    /// File names in it are taken relative to `self.base` (the current folder if `None`).
    pub fn resolve(&self, source: &str) -> Result<Scene> {
        let observer = self.check_render(source)?;
        let camera = self.camera(source)?;
        let materials = self.materials(source)?;
        crate::budget::check(&self.render, &materials, source)?;
        let objects = self.objects(source)?;
        let base = self.base.as_deref();
        let (area_lights, environment) = crate::scene_geometry::lights(self, source, base)?;
        let triangles = std::sync::Arc::new(crate::scene_geometry::triangles(
            self,
            source,
            base,
            &|name: &str, what: &str| self.material_index(source, name, what),
            &area_lights,
        )?);
        let (lights, ambient, background) = self.lights(source, &area_lights, &environment)?;
        Ok(Scene {
            render: self.render.clone(),
            observer,
            camera,
            ambient,
            background,
            lights,
            materials,
            objects,
            triangles,
            area_lights,
            environment,
        })
    }

    /// [`SceneFile::resolve`] with file names (spectra, meshes) relative to `base`, the scene
    /// file's folder.
    pub fn resolve_in(&self, source: &str, base: Option<&Path>) -> Result<Scene> {
        let mut f = self.clone();
        f.base = base.map(Path::to_path_buf);
        f.resolve(source)
    }

    /// Checks `[render]` and returns its observer.
    fn check_render(&self, source: &str) -> Result<Observer> {
        let r = &self.render;
        let observer = Observer::from_name(&r.observer).ok_or_else(|| {
            CliError::data(format!(
                "{source}: render.observer `{}`: use \"1931\" or \"1964\"",
                r.observer
            ))
        })?;
        if r.width == 0 || r.height == 0 || r.width > 16384 || r.height > 16384 {
            return Err(CliError::data(format!(
                "{source}: render size {}x{} must be 1..16384 on each side",
                r.width, r.height
            )));
        }
        if r.samples == 0 || r.samples > 16 {
            return Err(CliError::data(format!(
                "{source}: render.samples {} must be 1..16",
                r.samples
            )));
        }
        if r.spp == 0 || r.spp > 1 << 20 {
            return Err(CliError::data(format!(
                "{source}: render.spp {} must be 1..{}",
                r.spp,
                1 << 20
            )));
        }
        if r.light_samples == 0 || r.light_samples > 16 {
            return Err(CliError::data(format!(
                "{source}: render.light_samples {} must be 1..16",
                r.light_samples
            )));
        }
        if !(r.exposure.is_finite() && r.exposure > 0.0) {
            return Err(CliError::data(format!(
                "{source}: render.exposure must be positive"
            )));
        }
        if !(r.cutoff.is_finite() && r.cutoff >= 0.0) {
            return Err(CliError::data(format!(
                "{source}: render.cutoff must be ≥ 0"
            )));
        }
        Ok(observer)
    }

    /// The checked camera.
    fn camera(&self, source: &str) -> Result<Camera> {
        let c = &self.camera;
        let pos = v3(c.position, &format!("{source}: camera.position"))?;
        let at = v3(c.look_at, &format!("{source}: camera.look_at"))?;
        let up = v3(c.up, &format!("{source}: camera.up"))?;
        if (at - pos).length() == 0.0 || (at - pos).cross(up).length() < 1e-6 {
            return Err(CliError::data(format!(
                "{source}: camera: look_at must differ from position and not lie along up"
            )));
        }
        if !(c.fov > 0.0 && c.fov < 180.0) {
            return Err(CliError::data(format!(
                "{source}: camera.fov {} must be between 0 and 180 degrees",
                c.fov
            )));
        }
        Ok(Camera::new(pos, at, up, c.fov))
    }

    /// The materials, with their spectra resolved, in name order.
    fn materials(&self, source: &str) -> Result<Vec<Material>> {
        let mut materials = Vec::new();
        for (name, m) in &self.materials {
            let w = |f: &str| format!("{source}: materials.{name}.{f}");
            if !(m.phong.is_finite() && m.phong >= 0.0) {
                return Err(CliError::data(format!("{} must be ≥ 0", w("phong"))));
            }
            if !(m.ior.is_finite() && m.ior > 0.0) {
                return Err(CliError::data(format!("{} must be positive", w("ior"))));
            }
            // Every material spectrum is a reflectance (or transmittance): refused with a hint
            // when it cannot be one (specpoly_spectra::plausible).
            let reflectance = |spec: &SpectrumSpec, f: &str| -> Result<Option<Named>> {
                let n = optional(spec, &w(f), self.base.as_deref())?;
                if let Some(n) = &n {
                    specpoly_spectra::plausible::reflectance_given(
                        n,
                        specpoly_spectra::plausible::Given::Scene,
                    )
                    .map_err(|e| CliError::data(format!("{}: {e}", w(f))))?;
                }
                Ok(n)
            };
            materials.push(Material {
                name: name.clone(),
                diffuse: reflectance(&m.diffuse, "diffuse")?,
                specular: reflectance(&m.specular, "specular")?,
                phong: m.phong,
                mirror: reflectance(&m.mirror, "mirror")?,
                transmission: reflectance(&m.transmission, "transmission")?,
                ior: m.ior,
            });
        }
        Ok(materials)
    }

    /// The index of material `name`, which `what` (e.g. `sphere 2`) uses.
    fn material_index(&self, source: &str, name: &str, what: &str) -> Result<usize> {
        self.materials
            .keys()
            .position(|k| k == name)
            .ok_or_else(|| {
                let known: Vec<&str> = self.materials.keys().map(String::as_str).collect();
                CliError::data(format!(
                    "{source}: {what}: unknown material `{name}` (defined: {})",
                    if known.is_empty() {
                        "none".to_string()
                    } else {
                        known.join(", ")
                    }
                ))
            })
    }

    /// Spheres, planes and boxes, checked, in that order.
    fn objects(&self, source: &str) -> Result<Vec<Object>> {
        let material = |name: &str, what: &str| self.material_index(source, name, what);
        let mut objects = Vec::new();
        for (i, s) in self.sphere.iter().enumerate() {
            let what = format!("sphere {}", i + 1);
            if !(s.radius.is_finite() && s.radius > 0.0) {
                return Err(CliError::data(format!(
                    "{source}: {what}: radius {} must be positive",
                    s.radius
                )));
            }
            objects.push(Object {
                shape: Shape::Sphere {
                    center: v3(s.center, &format!("{source}: {what}"))?,
                    radius: s.radius,
                },
                material: material(&s.material, &what)?,
                checker: None,
            });
        }
        for (i, p) in self.plane.iter().enumerate() {
            let what = format!("plane {}", i + 1);
            let n = v3(p.normal, &format!("{source}: {what}"))?;
            if n.length() < 1e-6 {
                return Err(CliError::data(format!(
                    "{source}: {what}: the normal must not be zero"
                )));
            }
            let checker = match &p.checker_material {
                Some(m) => {
                    if !(p.checker_size.is_finite() && p.checker_size > 0.0) {
                        return Err(CliError::data(format!(
                            "{source}: {what}: checker_size must be positive"
                        )));
                    }
                    Some((material(m, &what)?, p.checker_size))
                }
                None => None,
            };
            objects.push(Object {
                shape: Shape::Plane {
                    point: v3(p.point, &format!("{source}: {what}"))?,
                    normal: n.normalize(),
                },
                material: material(&p.material, &what)?,
                checker,
            });
        }
        for (i, b) in self.boxes.iter().enumerate() {
            let what = format!("box {}", i + 1);
            let (lo, hi) = (
                v3(b.min, &format!("{source}: {what}"))?,
                v3(b.max, &format!("{source}: {what}"))?,
            );
            if !(hi.x > lo.x && hi.y > lo.y && hi.z > lo.z) {
                return Err(CliError::data(format!(
                    "{source}: {what}: max must exceed min on every axis"
                )));
            }
            objects.push(Object {
                shape: Shape::Box { min: lo, max: hi },
                material: material(&b.material, &what)?,
                checker: None,
            });
        }
        Ok(objects)
    }

    /// The point lights, the ambient light (the first light's spectrum at zero intensity if
    /// the file has none) and the background.
    fn lights(
        &self,
        source: &str,
        area_lights: &[crate::lights::AreaLight],
        environment: &Option<crate::lights::Environment>,
    ) -> Result<(Vec<Light>, Light, Option<Named>)> {
        let base = self.base.as_deref();
        let mut lights = Vec::new();
        for (i, l) in self.light.iter().enumerate() {
            let what = format!("{source}: light {}", i + 1);
            if !(l.intensity.is_finite() && l.intensity >= 0.0) {
                return Err(CliError::data(format!("{what}: intensity must be ≥ 0")));
            }
            lights.push(Light {
                position: v3(l.position, &what)?,
                spd: resolve_spectrum_in(&l.spectrum, &format!("{what}: spectrum"), base)?,
                intensity: l.intensity,
            });
        }
        let (ambient, background) = match &self.ambient {
            Some(a) => {
                if !(a.intensity.is_finite() && a.intensity >= 0.0) {
                    return Err(CliError::data(format!(
                        "{source}: ambient.intensity must be ≥ 0"
                    )));
                }
                (
                    Light {
                        position: V3::default(),
                        spd: resolve_spectrum_in(
                            &a.spectrum,
                            &format!("{source}: ambient.spectrum"),
                            base,
                        )?,
                        intensity: a.intensity,
                    },
                    optional(
                        &a.background,
                        &format!("{source}: ambient.background"),
                        base,
                    )?,
                )
            }
            None => (
                Light {
                    position: V3::default(),
                    spd: match lights
                        .first()
                        .map(|l| &l.spd)
                        .or_else(|| area_lights.first().map(|l| &l.spd))
                        .or_else(|| environment.as_ref().map(|e| &e.spd))
                    {
                        Some(s) => s.clone(),
                        None => flat("E".into(), 1.0)?,
                    },
                    intensity: 0.0,
                },
                None,
            ),
        };
        let spds = lights
            .iter()
            .chain(std::iter::once(&ambient))
            .map(|l| &l.spd)
            .chain(area_lights.iter().map(|l| &l.spd))
            .chain(environment.iter().map(|e| &e.spd));
        for spd in spds {
            let t = spd.tabulated();
            if (380..=780).all(|nm| t.at(nm as f64) <= 0.0) {
                return Err(CliError::data(format!(
                    "{source}: light spectrum `{}` has no power in 380-780 nm",
                    spd.name
                )));
            }
        }
        Ok((lights, ambient, background))
    }
}
