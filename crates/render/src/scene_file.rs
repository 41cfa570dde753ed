//! The scene file (TOML, documented in `docs/scenes.md`): its top level ([`SceneFile`], the
//! sections of [`crate::sections`]) and its resolution into a [`Scene`]: values checked, names
//! resolved ([`crate::scene_value`]), triangles and emitters built
//! ([`crate::scene_geometry`]), the work bounded ([`crate::budget`]). Unknown keys are errors
//! (`deny_unknown_fields`); every error names the file and the object.

use crate::error::{Error, Result};
use crate::geometry::{Camera, Shape, V3};
use crate::lights::{AreaLight, Environment};
use crate::scene::{Light, Material, Object, Scene};
use crate::scene_value::{flat, optional, resolve_spectrum_in, v3};
use crate::sections::{
    AmbientSection, AreaLightSection, BoxSection, CameraSection, EnvironmentSection, LightSection,
    MaterialSection, MeshSection, PlaneSection, QuadSection, RenderSection, SpectrumSpec,
    SphereSection,
};
use serde::Deserialize;
use specpoly_core::Observer;
use specpoly_spectra::spectrum_names::Named;
use std::collections::BTreeMap;
use std::path::Path;

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
    pub quad: Vec<QuadSection>,
    /// Triangle meshes from OBJ files.
    #[serde(default)]
    pub mesh: Vec<MeshSection>,
    /// Area lights.
    #[serde(default)]
    pub area_light: Vec<AreaLightSection>,
    /// The environment light.
    pub environment: Option<EnvironmentSection>,
    /// The folder file names resolve against (the scene file's; not in the file).
    #[serde(skip)]
    pub base: Option<std::path::PathBuf>,
}

/// A material with every spectrum resolved to tabulated data (`None` = zero).
impl SceneFile {
    /// Parses TOML text; `source` names the file in errors.
    pub fn parse(text: &str, source: &str) -> Result<Self> {
        toml::from_str(text).map_err(|e| Error::Toml {
            message: specpoly_formats::toml_error::one_line(&e, text, source),
        })
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
        let (area_lights, environment) =
            crate::scene_geometry::lights(&self.area_light, &self.environment, source, base)?;
        let triangles = std::sync::Arc::new(crate::scene_geometry::triangles(
            &self.quad,
            &self.mesh,
            &self.materials,
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
            Error::invalid(
                source,
                format!(
                    "render.observer `{}`: use \"1931\", \"1964\", \"2015-2\" or \"2015-10\"",
                    r.observer
                ),
            )
        })?;
        if r.width == 0 || r.height == 0 || r.width > 16384 || r.height > 16384 {
            return Err(Error::invalid(
                source,
                format!(
                    "render size {}x{} must be 1..16384 on each side",
                    r.width, r.height
                ),
            ));
        }
        if r.samples == 0 || r.samples > 16 {
            return Err(Error::invalid(
                source,
                format!("render.samples {} must be 1..16", r.samples),
            ));
        }
        if r.spp == 0 || r.spp > 1 << 20 {
            return Err(Error::invalid(
                source,
                format!("render.spp {} must be 1..{}", r.spp, 1 << 20),
            ));
        }
        if r.light_samples == 0 || r.light_samples > 16 {
            return Err(Error::invalid(
                source,
                format!("render.light_samples {} must be 1..16", r.light_samples),
            ));
        }
        if !(r.exposure.is_finite() && r.exposure > 0.0) {
            return Err(Error::invalid(source, "render.exposure must be positive"));
        }
        if !(r.cutoff.is_finite() && r.cutoff >= 0.0) {
            return Err(Error::invalid(source, "render.cutoff must be ≥ 0"));
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
            return Err(Error::invalid(
                source,
                "camera: look_at must differ from position and not lie along up",
            ));
        }
        if !(c.fov > 0.0 && c.fov < 180.0) {
            return Err(Error::invalid(
                source,
                format!("camera.fov {} must be between 0 and 180 degrees", c.fov),
            ));
        }
        Ok(Camera::new(pos, at, up, c.fov))
    }

    /// The materials, with their spectra resolved, in name order.
    fn materials(&self, source: &str) -> Result<Vec<Material>> {
        let mut materials = Vec::new();
        for (name, m) in &self.materials {
            let w = |f: &str| format!("{source}: materials.{name}.{f}");
            if !(m.phong.is_finite() && m.phong >= 0.0) {
                return Err(Error::invalid(w("phong"), "must be ≥ 0"));
            }
            if !(m.ior.is_finite() && m.ior > 0.0) {
                return Err(Error::invalid(w("ior"), "must be positive"));
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
                    .map_err(|error| Error::Spectrum {
                        what: w(f),
                        error: Box::new(error),
                    })?;
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
                textures: None,
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
                Error::invalid(
                    source,
                    format!(
                        "{what}: unknown material `{name}` (defined: {})",
                        if known.is_empty() {
                            "none".to_string()
                        } else {
                            known.join(", ")
                        }
                    ),
                )
            })
    }

    /// Spheres, planes and boxes, checked, in that order.
    fn objects(&self, source: &str) -> Result<Vec<Object>> {
        let material = |name: &str, what: &str| self.material_index(source, name, what);
        let mut objects = Vec::new();
        for (i, s) in self.sphere.iter().enumerate() {
            let what = format!("sphere {}", i + 1);
            if !(s.radius.is_finite() && s.radius > 0.0) {
                return Err(Error::invalid(
                    source,
                    format!("{what}: radius {} must be positive", s.radius),
                ));
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
                return Err(Error::invalid(
                    source,
                    format!("{what}: the normal must not be zero"),
                ));
            }
            let checker = match &p.checker_material {
                Some(m) => {
                    if !(p.checker_size.is_finite() && p.checker_size > 0.0) {
                        return Err(Error::invalid(
                            source,
                            format!("{what}: checker_size must be positive"),
                        ));
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
                return Err(Error::invalid(
                    source,
                    format!("{what}: max must exceed min on every axis"),
                ));
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
        area_lights: &[AreaLight],
        environment: &Option<Environment>,
    ) -> Result<(Vec<Light>, Light, Option<Named>)> {
        let base = self.base.as_deref();
        let mut lights = Vec::new();
        for (i, l) in self.light.iter().enumerate() {
            let what = format!("{source}: light {}", i + 1);
            if !(l.intensity.is_finite() && l.intensity >= 0.0) {
                return Err(Error::invalid(&what, "intensity must be ≥ 0"));
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
                    return Err(Error::invalid(source, "ambient.intensity must be ≥ 0"));
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
                return Err(Error::invalid(
                    source,
                    format!("light spectrum `{}` has no power in 380-780 nm", spd.name),
                ));
            }
        }
        Ok((lights, ambient, background))
    }
}
