//! Image textures of glTF materials: PNG images decoded with the `png` crate (bounded before
//! anything is allocated), their lookup (glTF's wrap modes; bilinear, or nearest when the
//! sampler's `magFilter` asks), base-colour textures as palettes of upsampled reflectances,
//! and tangent-space normal maps.
//!
//! **Base colour.** A texel is 8-bit sRGB (glTF: the base-colour texture is sRGB-encoded); it
//! is decoded by IEC 61966-2-1's transfer function, multiplied by the material's linear factor
//! (`baseColorFactor · (1 − metallic)(1 − transmission)`, see [`crate::scene_gltf`]) and
//! upsampled to a smooth reflectance by Jakob and Hanika's sigmoid-polynomial
//! ([`crate::upsample`]). The fit (a Gauss–Newton solve, about 0.1 ms) is **cached per distinct
//! colour of a texture**: each texture keeps a palette of the sigmoid coefficients of the
//! colours it uses and one palette index per texel. Textures repeat colours (flat regions,
//! quantised art), so a palette costs far fewer fits than texels; it is 24 bytes an entry and
//! 4 a texel. When a scene is compiled for a representation, each palette entry is formed once
//! in that representation ([`crate::compiled`]).
//!
//! **Filtering** happens on spectra: a bilinear lookup is `Σ wᵢ rᵢ(λ)` over the four nearest
//! texels' reflectances (texel centres at `(i + ½)/width`), the average reflectance of the
//! footprint, which every representation forms exactly because each is linear in the spectrum
//! (`add`, `scale`). Filtering the sRGB values before upsampling would instead average
//! non-linearly encoded numbers.
//!
//! **Normal maps** (glTF `normalTexture`, linear RGB): a texel `c` is the tangent-space normal
//! `(2c − 1)` with its x and y times the texture's `scale`, normalised; the shading normal is
//! `normalize(x·T + y·B + z·N)` with `N` the interpolated vertex normal, `T` the tangent
//! (glTF's `TANGENT`, else `∂P/∂u` of the triangle), orthogonalised against `N`, and
//! `B = h·(N × T)` with the handedness `h` that makes `B` point to decreasing `v` (up in the
//! image: glTF's texture origin is its top-left corner, and its normal maps have +Y up).

use std::sync::Arc;

/// The most texels a texture may have (8192² texels; 4 bytes each for a base colour).
pub const MAX_TEXELS: u64 = 1 << 26;

/// How coordinates outside `[0, 1]` fold back (glTF `wrapS`, `wrapT`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Wrap {
    /// `REPEAT` (the default).
    Repeat,
    /// `CLAMP_TO_EDGE`.
    Clamp,
    /// `MIRRORED_REPEAT`.
    Mirror,
}

impl Wrap {
    /// Texel `i` of a row of `n` folded into `0..n`.
    fn fold(self, i: i64, n: u32) -> u32 {
        let n = n as i64;
        (match self {
            Wrap::Repeat => i.rem_euclid(n),
            Wrap::Clamp => i.clamp(0, n - 1),
            Wrap::Mirror => {
                let p = i.rem_euclid(2 * n);
                if p < n {
                    p
                } else {
                    2 * n - 1 - p
                }
            }
        }) as u32
    }
}

/// A decoded image: 8-bit RGB texels, row by row from the top.
#[derive(Clone, Debug)]
pub struct Image {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// `width · height` texels, the first row the top of the image.
    pub texels: Vec<[u8; 3]>,
}

/// How a texture is looked up.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Sampling {
    /// Along `u`.
    pub wrap_s: Wrap,
    /// Along `v`.
    pub wrap_t: Wrap,
    /// The nearest texel instead of bilinear filtering (a sampler's `magFilter` `NEAREST`).
    pub nearest: bool,
}

impl Sampling {
    /// The texels (indices into a `width × height` image, row-major from the top) and weights
    /// of the lookup at `(u, v)`: four for bilinear filtering, else the nearest with weight 1
    /// (and three of weight 0). Non-finite coordinates read texel `(0, 0)`.
    pub fn taps(&self, width: u32, height: u32, u: f32, v: f32) -> [(u32, f32); 4] {
        let (u, v) = (
            if u.is_finite() { u } else { 0.0 },
            if v.is_finite() { v } else { 0.0 },
        );
        let at = |x: i64, y: i64| self.wrap_t.fold(y, height) * width + self.wrap_s.fold(x, width);
        let (x, y) = (
            u as f64 * width as f64 - 0.5,
            v as f64 * height as f64 - 0.5,
        );
        if self.nearest {
            let i = at(x.round() as i64, y.round() as i64);
            return [(i, 1.0), (i, 0.0), (i, 0.0), (i, 0.0)];
        }
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = ((x - x0) as f32, (y - y0) as f32);
        let (x0, y0) = (x0 as i64, y0 as i64);
        [
            (at(x0, y0), (1.0 - fx) * (1.0 - fy)),
            (at(x0 + 1, y0), fx * (1.0 - fy)),
            (at(x0, y0 + 1), (1.0 - fx) * fy),
            (at(x0 + 1, y0 + 1), fx * fy),
        ]
    }
}

/// Decodes a PNG image to 8-bit RGB (grey is repeated, alpha dropped, 16-bit samples keep
/// their high byte, palettes are expanded). The header's size is checked against
/// [`MAX_TEXELS`] and `max_bytes` (the decoded RGB size) before the image is allocated, so a
/// header that claims gigabytes over a few bytes of data is refused at once.
pub fn decode_png(bytes: &[u8], max_bytes: u64) -> Result<Image, String> {
    let mut dec = png::Decoder::new_with_limits(
        std::io::Cursor::new(bytes),
        png::Limits {
            bytes: usize::try_from(max_bytes.saturating_mul(2)).unwrap_or(usize::MAX),
        },
    );
    dec.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
    let mut reader = dec
        .read_info()
        .map_err(|e| format!("not a readable PNG image: {e}"))?;
    let (width, height) = (reader.info().width, reader.info().height);
    let texels = width as u64 * height as u64;
    if texels > MAX_TEXELS || texels * 3 > max_bytes {
        return Err(format!(
            "a {width} × {height} image ({} decoded) is beyond the texture limit of {MAX_TEXELS} texels and {} (--max-input-size)",
            specpoly_formats::read::size_text(texels * 3),
            specpoly_formats::read::size_text(max_bytes)
        ));
    }
    if texels == 0 {
        return Err("an image of no texels".into());
    }
    let mut buf = vec![0u8; reader.output_buffer_size()];
    let frame = reader
        .next_frame(&mut buf)
        .map_err(|e| format!("not a readable PNG image: {e}"))?;
    let channels = match frame.color_type {
        png::ColorType::Grayscale => 1,
        png::ColorType::GrayscaleAlpha => 2,
        png::ColorType::Rgb => 3,
        png::ColorType::Rgba => 4,
        png::ColorType::Indexed => return Err("an indexed PNG the decoder did not expand".into()),
    };
    if frame.bit_depth != png::BitDepth::Eight {
        return Err(format!("{:?} samples after decoding", frame.bit_depth));
    }
    let mut texels_out = Vec::with_capacity(texels as usize);
    for row in buf.chunks(frame.line_size).take(height as usize) {
        for px in row.chunks_exact(channels).take(width as usize) {
            texels_out.push(if channels < 3 {
                [px[0]; 3]
            } else {
                [px[0], px[1], px[2]]
            });
        }
    }
    if texels_out.len() as u64 != texels {
        return Err("the image data is shorter than its header says".into());
    }
    Ok(Image {
        width,
        height,
        texels: texels_out,
    })
}

/// IEC 61966-2-1's decoding of an 8-bit sRGB value to linear.
pub fn srgb_to_linear(v: u8) -> f32 {
    let c = v as f64 / 255.0;
    (if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }) as f32
}

/// A base-colour texture as a palette of upsampled reflectances (see the module docs).
#[derive(Debug)]
pub struct BaseColour {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// How it is looked up.
    pub sampling: Sampling,
    /// One palette index per texel.
    pub index: Vec<u32>,
    /// The sigmoid-polynomial coefficients of each palette colour ([`crate::upsample::eval`]).
    pub palette: Vec<[f64; 3]>,
}

impl BaseColour {
    /// The palette of `image` with each colour decoded, times `factor` (linear RGB) and
    /// upsampled; the fits run in parallel.
    pub fn new(image: &Image, sampling: Sampling, factor: [f32; 3]) -> Self {
        use rayon::prelude::*;
        let mut slot = std::collections::HashMap::new();
        let mut colours: Vec<[u8; 3]> = Vec::new();
        let index = image
            .texels
            .iter()
            .map(|c| {
                *slot.entry(*c).or_insert_with(|| {
                    colours.push(*c);
                    (colours.len() - 1) as u32
                })
            })
            .collect();
        let palette = colours
            .par_iter()
            .map(|c| {
                let rgb = [0, 1, 2].map(|k| srgb_to_linear(c[k]) * factor[k]);
                crate::upsample::coefficients(rgb).0
            })
            .collect();
        Self {
            width: image.width,
            height: image.height,
            sampling,
            index,
            palette,
        }
    }

    /// The palette entries and weights of the lookup at `(u, v)`.
    #[inline]
    pub fn taps(&self, u: f32, v: f32) -> [(u32, f32); 4] {
        self.sampling
            .taps(self.width, self.height, u, v)
            .map(|(i, w)| (self.index[i as usize], w))
    }
}

/// A tangent-space normal map.
#[derive(Debug)]
pub struct NormalMap {
    /// The image (linear values), shared with other materials that use it.
    pub image: Arc<Image>,
    /// How it is looked up.
    pub sampling: Sampling,
    /// glTF's `normalTexture.scale`: multiplies the normal's x and y.
    pub scale: f32,
}

impl NormalMap {
    /// The tangent-space normal at `(u, v)` (filtered texels, `2c − 1`, x and y scaled; not
    /// normalised).
    pub fn at(&self, u: f32, v: f32) -> [f32; 3] {
        let mut c = [0.0f32; 3];
        for (i, w) in self
            .sampling
            .taps(self.image.width, self.image.height, u, v)
        {
            let t = self.image.texels[i as usize];
            for k in 0..3 {
                c[k] += w * t[k] as f32;
            }
        }
        let n = c.map(|v| 2.0 * v / 255.0 - 1.0);
        [n[0] * self.scale, n[1] * self.scale, n[2]]
    }
}

/// The textures of one material.
#[derive(Debug, Default)]
pub struct MaterialTextures {
    /// The base colour, driving the diffuse reflectance.
    pub base: Option<BaseColour>,
    /// The normal map.
    pub normal: Option<NormalMap>,
}

/// Shared textures of a scene material.
pub type Textures = Option<Arc<MaterialTextures>>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_modes_fold_as_gltf_says() {
        let r: Vec<u32> = (-3..5).map(|i| Wrap::Repeat.fold(i, 3)).collect();
        assert_eq!(r, [0, 1, 2, 0, 1, 2, 0, 1]);
        let c: Vec<u32> = (-3..5).map(|i| Wrap::Clamp.fold(i, 3)).collect();
        assert_eq!(c, [0, 0, 0, 0, 1, 2, 2, 2]);
        let m: Vec<u32> = (-3..5).map(|i| Wrap::Mirror.fold(i, 3)).collect();
        assert_eq!(m, [2, 1, 0, 0, 1, 2, 2, 1]);
    }

    /// Bilinear weights at a texel centre pick that texel alone; half-way between two texels
    /// they split evenly; the weights sum to one.
    #[test]
    fn bilinear_taps() {
        let s = Sampling {
            wrap_s: Wrap::Clamp,
            wrap_t: Wrap::Clamp,
            nearest: false,
        };
        let t = s.taps(4, 2, 0.375, 0.25);
        assert_eq!(t[0], (1, 1.0));
        let t = s.taps(4, 2, 0.5, 0.25);
        assert_eq!((t[0], t[1]), ((1, 0.5), (2, 0.5)));
        let t = s.taps(4, 2, 0.3, 0.7);
        assert!((t.iter().map(|x| x.1).sum::<f32>() - 1.0).abs() < 1e-6);
        let n = Sampling { nearest: true, ..s };
        assert_eq!(n.taps(4, 2, 0.99, 0.99)[0], (7, 1.0));
    }
}
