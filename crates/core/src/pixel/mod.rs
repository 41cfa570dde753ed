//! Calibrated pixels for a microcontroller's framebuffer: 8-bit source RGB (sRGB, Display P3 or
//! linear sRGB) → the code values of *this* panel, in fixed point, built once from a display
//! calibration ([`Display`](crate::Display), Cowan's model).
//!
//! The maths is the paper's calibrated-display step (§7.3, Cowan 1983) applied to a source
//! colour space instead of a spectrum: with `S` the source's RGB→XYZ matrix, `M` the panel's,
//! `K` its black and `B` the Bradford adaptation from the source white to the panel white
//! (`M · 1`), the panel should emit
//!
//! `XYZ = K + B · S · decode(c)`, i.e. panel linear drive `l = M⁻¹ · B · S · decode(c) = T · decode(c)`
//!
//! (source black → panel black, source white → full drive: black-point compensation in XYZ), then
//! the gamut map ([`GamutMap`](crate::GamutMap)) and the panel's inverse curve. Three stages, each
//! a small table or a 3×3 in fixed point: [`PixelTransform`]. For panels whose model has an
//! interaction term (channels not additive) the whole map is sampled on a grid and interpolated
//! tetrahedrally: [`CubeTransform`]. Both produce *panel levels* in Q8 (level `q` and a fraction
//! `f/256` of the way, in light, to level `q + 1`), so [`dither`] turns them into RGB565/RGB666
//! codes whose 8×8-block mean emits the wanted light.
//!
//! [`export`] writes the tables as C or Rust source for firmware built elsewhere.

pub mod cube;
pub mod dither;
pub mod export;
pub mod source;
pub mod transform;

pub use cube::CubeTransform;
pub use dither::Dither;
pub use source::{Source, White};
pub use transform::{Options, PanelTransform, PixelTransform, Tables};

/// A source → panel pixel map: what the `embedded-graphics` adapter (`specpoly-graphics`) and
/// the firmware draw through. Implemented by [`PixelTransform`] and [`CubeTransform`].
pub trait PixelMap {
    /// The panel levels (Q8: `level · 256 + fraction`) of an 8-bit source pixel.
    fn levels(&self, rgb: [u8; 3]) -> [u16; 3];
    /// The panel's bits per channel.
    fn bits(&self) -> [u8; 3];
    /// [`Self::levels`] when the caller knows [`Self::bits`] at compile time (lets
    /// [`PixelTransform`] shift its top-aligned tables by constants); `bits` must be
    /// [`Self::bits`].
    #[inline(always)]
    fn levels_for(&self, rgb: [u8; 3], bits: [u8; 3]) -> [u16; 3] {
        let _ = bits;
        self.levels(rgb)
    }
}

impl PixelMap for PixelTransform {
    #[inline(always)]
    fn levels(&self, rgb: [u8; 3]) -> [u16; 3] {
        PixelTransform::levels(self, rgb)
    }
    fn bits(&self) -> [u8; 3] {
        PixelTransform::bits(self)
    }
    #[inline(always)]
    fn levels_for(&self, rgb: [u8; 3], bits: [u8; 3]) -> [u16; 3] {
        PixelTransform::levels_for(self, rgb, bits)
    }
}

impl<const G: usize> PixelMap for CubeTransform<G> {
    #[inline(always)]
    fn levels(&self, rgb: [u8; 3]) -> [u16; 3] {
        CubeTransform::levels(self, rgb)
    }
    fn bits(&self) -> [u8; 3] {
        CubeTransform::bits(self)
    }
}

/// The panel level of `light` on a channel whose levels `0..=max` emit `lights[q]` (increasing):
/// `q · 256 + f`, with `q` the last level not above `light` and `f/256` the fraction of the way,
/// in light, to level `q + 1` (rounded; never 256). Shared by both transforms.
pub(crate) fn level_q8(lights: &[f32], light: f32) -> u16 {
    let max = lights.len() - 1;
    if !(light > lights[0]) {
        return 0;
    }
    if light >= lights[max] {
        return (max as u16) << 8;
    }
    // lights[q] ≤ light < lights[q + 1] for some q < max
    let q = lights.partition_point(|l| *l <= light).clamp(1, max) - 1;
    let (a, b) = (lights[q], lights[q + 1]);
    let f = if b > a {
        ((light - a) / (b - a) * 256.0 + 0.5) as u32
    } else {
        0
    };
    if f >= 256 {
        ((q + 1) as u16) << 8
    } else {
        ((q as u16) << 8) | f as u16
    }
}

/// The light each level `0..=2^bits − 1` of a panel channel emits, by its transfer curve.
pub(crate) fn level_lights(curve: &crate::Transfer, bits: u8, out: &mut [f32; 256]) -> usize {
    let max = (1usize << bits) - 1;
    for (q, l) in out.iter_mut().enumerate().take(max + 1) {
        *l = curve.decode(q as f32 / max as f32);
    }
    max + 1
}
