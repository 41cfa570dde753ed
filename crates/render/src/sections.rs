//! The scene file's sections as TOML writes them (`docs/scenes.md`), before anything is
//! resolved: spectra as written ([`SpectrumSpec`]), `[render]` (with the [`Integrator`]),
//! `[camera]`, lights, materials, shapes, meshes and emitters. Plain data read with `serde`;
//! unknown keys are errors (`deny_unknown_fields`). The lowest layer of the scene file: it
//! depends on nothing else in the crate.

use serde::de::{self, Deserializer, MapAccess, Visitor};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::fmt;

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
    pub integrator: Integrator,
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
/// `[[quad]]`: a planar quadrilateral (two triangles `v0 v1 v2`, `v0 v2 v3`).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct QuadSection {
    /// The four corners in order around the edge.
    pub vertices: [[f32; 3]; 4],
    /// Material name.
    pub material: String,
}

/// `[[mesh]]`: an OBJ or PLY file.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshSection {
    /// The OBJ file, relative to the scene file's folder.
    pub file: String,
    /// Material of faces without a mapped OBJ material.
    pub material: String,
    /// OBJ material name (`usemtl`) → scene material name. OBJ materials whose name is a scene
    /// material map to it without an entry.
    #[serde(default)]
    pub materials: BTreeMap<String, String>,
    /// Uniform scale (applied first).
    #[serde(default = "one")]
    pub scale: f32,
    /// Translation (applied after the scale).
    #[serde(default)]
    pub translate: [f32; 3],
}

/// `[[area_light]]`: a rectangle (`corner`, `u`, `v`), a sphere (`center`, `radius`) or an
/// emissive mesh (`mesh`, with `scale` and `translate`).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AreaLightSection {
    /// Spectral power distribution.
    pub spectrum: SpectrumSpec,
    /// Radiance scale.
    #[serde(default = "one")]
    pub radiance: f32,
    /// Rectangle: a corner.
    pub corner: Option<[f32; 3]>,
    /// Rectangle: first edge.
    pub u: Option<[f32; 3]>,
    /// Rectangle: second edge (it emits on the side of `u × v`).
    pub v: Option<[f32; 3]>,
    /// Sphere: centre.
    pub center: Option<[f32; 3]>,
    /// Sphere: radius.
    pub radius: Option<f32>,
    /// Emissive mesh: an OBJ or PLY file, relative to the scene file's folder.
    pub mesh: Option<String>,
    /// Emissive mesh: uniform scale (applied first).
    pub scale: Option<f32>,
    /// Emissive mesh: translation (applied after the scale).
    pub translate: Option<[f32; 3]>,
}

/// `[environment]`: a constant radiance from every direction.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnvironmentSection {
    /// Spectral power distribution.
    pub spectrum: SpectrumSpec,
    /// Radiance scale.
    #[serde(default = "one")]
    pub radiance: f32,
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
