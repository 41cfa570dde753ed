//! How XYZ pixels become a display's values ([`Output`], [`to_rgb8`]) for the display an image
//! is encoded for ([`specpoly_display::spec::DisplaySpec`]).

use super::{scene_white, Image};
use crate::scene::Scene;
use rayon::prelude::*;
use specpoly_core::display_model::FULL;
use specpoly_core::{bradford, quantize8, Display, DisplayModel, GamutMap, Mat3, Xyz};
use std::sync::Arc;

/// How XYZ pixels become display values.
#[derive(Clone, Debug)]
pub struct Output {
    /// The display.
    pub display: Display,
    /// Gamut mapping.
    pub gamut: GamutMap,
    /// XYZ multiplier before display.
    pub exposure: f32,
    /// Chromatic adaptation applied before display (Bradford, scene white → display white).
    pub adapt: Mat3,
    /// A calibration's full model when it has channel interaction (`calibrate fit`'s
    /// lattice): device values then come from the core's [`DisplayModel::encode_relative`]
    /// (the matrix model's gamut mapping, then the full model's exact inverse), so the full
    /// model emits what the matrix model [`Self::display`] maps the colour to. `None`: the
    /// matrix model alone.
    pub model: Option<Arc<DisplayModel<FULL>>>,
}

impl Output {
    /// The output for `scene` on `display`: its exposure, and its white adapted to the display's
    /// white when the scene asks for white balance.
    pub fn new(scene: &Scene, display: Display, gamut: GamutMap) -> Self {
        let adapt = if scene.render.white_balance {
            let dw = display.white();
            let dw = dw.scale(100.0 / dw.y);
            bradford(scene_white(scene), dw)
        } else {
            Mat3::IDENTITY
        };
        Self {
            display,
            gamut,
            exposure: scene.render.exposure,
            adapt,
            model: None,
        }
    }

    /// The output with a full model (see [`Self::model`]; a model without interaction is the
    /// matrix model and is dropped).
    pub fn with_model(mut self, model: Option<Box<DisplayModel<FULL>>>) -> Self {
        self.model = model.filter(|m| m.interaction().is_some()).map(Arc::from);
        self
    }

    /// One pixel's display device values in `[0, 1]`, before quantisation (8- and 16-bit PNG).
    #[inline]
    pub fn device(&self, xyz: Xyz) -> [f32; 3] {
        let a = Xyz::from_array(self.adapt.apply(xyz.scale(self.exposure).to_array()));
        match &self.model {
            Some(m) => m.encode_relative(a, self.gamut).device,
            None => self.display.encode_relative(a, self.gamut).device,
        }
    }

    /// One pixel's 8-bit device values.
    pub fn encode(&self, xyz: Xyz) -> [u8; 3] {
        self.device(xyz).map(quantize8)
    }
}

/// The image as 8-bit RGB, row-major (in parallel: the transfer curve's powers cost about as
/// much as tracing a simple scene).
pub fn to_rgb8(img: &Image, out: &Output) -> Vec<u8> {
    let mut rgb = vec![0u8; img.xyz.len() * 3];
    rgb.par_chunks_mut(3)
        .zip(img.xyz.par_iter())
        .for_each(|(px, xyz)| px.copy_from_slice(&out.encode(*xyz)));
    rgb
}
