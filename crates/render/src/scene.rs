//! The resolved scene: geometry, materials and lights with tabulated spectra, as the scene file
//! ([`crate::scene_file`]) or a built-in scene resolves to. Plain data, checked; what every
//! compiled scene ([`crate::compiled`]) is made from.

use crate::geometry::{Camera, Shape, V3};
use crate::lights::{AreaLight, Environment};
use crate::mesh::Triangles;
use crate::sections::RenderSection;
use specpoly_core::Observer;
use specpoly_spectra::spectrum_names::Named;
use std::sync::Arc;

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
    /// Image textures (glTF materials): a base colour replacing the diffuse reflectance where
    /// a triangle has texture coordinates, a normal map.
    pub textures: crate::texture::Textures,
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
    pub triangles: Arc<Triangles>,
    /// Area lights.
    pub area_lights: Vec<AreaLight>,
    /// The environment light.
    pub environment: Option<Environment>,
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
