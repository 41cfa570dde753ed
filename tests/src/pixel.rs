//! An f64 model of a calibrated panel and the reference for the framebuffer pixel transform
//! (`specpoly_core::pixel`): source curve, source and panel matrices from chromaticities,
//! Bradford, the gamut maps, all in f64 and written here, independently of the fixed-point code
//! (the f64 matrix arithmetic and Bradford are the core's [`Mat3`] at f64, tested on their own).

use specpoly_core::pixel::{Source, White};
use specpoly_core::{Display, GamutMap, Mat3, Transfer, Xyz};

/// A 3×3 matrix, row-major.
pub type M3 = [[f64; 3]; 3];

/// `a · b` ([`Mat3`] at f64).
pub fn mul(a: &M3, b: &M3) -> M3 {
    Mat3(*a).mul(&Mat3(*b)).0
}

/// `m · v`.
pub fn apply(m: &M3, v: [f64; 3]) -> [f64; 3] {
    Mat3(*m).apply(v)
}

/// The inverse (NaN entries for a singular matrix).
pub fn inv(m: &M3) -> M3 {
    Mat3(*m).inverse().map_or([[f64::NAN; 3]; 3], |i| i.0)
}

/// Columns: the primaries' XYZ from chromaticities and luminances.
pub fn primaries(xy: [[f64; 2]; 3], lum: [f64; 3]) -> M3 {
    let p = [0, 1, 2].map(|i| {
        let (x, y, l) = (xy[i][0], xy[i][1], lum[i]);
        [x / y * l, l, (1.0 - x - y) / y * l]
    });
    [0, 1, 2].map(|r| [p[0][r], p[1][r], p[2][r]])
}

/// Primaries scaled so that full drive is the white `(x, y)` with `Y = 1`.
pub fn primaries_white(xy: [[f64; 2]; 3], white: [f64; 2]) -> M3 {
    let unit = primaries(xy, [1.0; 3]);
    let w = [
        white[0] / white[1],
        1.0,
        (1.0 - white[0] - white[1]) / white[1],
    ];
    primaries(xy, apply(&inv(&unit), w))
}

/// Bradford adaptation (Lam 1985) from white `from` to white `to`: the core's one Bradford at
/// f64 (checked against Lindbloom's published matrix in `crates/core/tests`).
pub fn bradford(from: [f64; 3], to: [f64; 3]) -> M3 {
    specpoly_core::bradford(Xyz::from_array(from), Xyz::from_array(to)).0
}

#[derive(Clone)]
/// A channel's transfer curve: device value → linear light.
pub enum Curve {
    Srgb,
    Linear,
    Gamma(f64),
    Table(Vec<f64>),
}

impl Curve {
    /// Device value in `[0, 1]` → linear light.
    pub fn decode(&self, v: f64) -> f64 {
        let v = v.clamp(0.0, 1.0);
        match self {
            Curve::Linear => v,
            Curve::Srgb if v <= 0.04045 => v / 12.92,
            Curve::Srgb => ((v + 0.055) / 1.055).powf(2.4),
            Curve::Gamma(g) => v.powf(*g),
            Curve::Table(t) => {
                let x = v * (t.len() - 1) as f64;
                let i = (x.floor() as usize).min(t.len() - 2);
                t[i] + (t[i + 1] - t[i]) * (x - i as f64)
            }
        }
    }
}

/// The f64 model of a panel (Cowan: `XYZ = K + M · curve(d)`).
pub struct Panel {
    /// A name for messages.
    pub name: &'static str,
    /// Columns: the primaries' XYZ at full drive.
    pub m: M3,
    /// XYZ at device 0.
    pub black: [f64; 3],
    /// The channels' curves.
    pub curves: [Curve; 3],
    /// The same panel as the core's model (what the transform is built from).
    pub display: Display,
}

impl Panel {
    /// The emitted XYZ for linear drive `light`.
    pub fn xyz(&self, light: [f64; 3]) -> [f64; 3] {
        let x = apply(&self.m, light);
        [0, 1, 2].map(|i| x[i] + self.black[i])
    }

    /// The white: full drive, black included.
    pub fn white(&self) -> [f64; 3] {
        self.xyz([1.0; 3])
    }

    /// The light a channel emits at Q8 level `lv` (bits `b`): between adjacent levels, in light.
    pub fn level_light(&self, c: usize, bits: u8, lv: u16) -> f64 {
        let max = ((1u32 << bits) - 1) as f64;
        let q = (lv >> 8) as f64;
        let f = (lv & 255) as f64 / 256.0;
        let a = self.curves[c].decode(q / max);
        if f == 0.0 {
            return a;
        }
        a + f * (self.curves[c].decode((q + 1.0) / max) - a)
    }

    /// The reference: the emitted XYZ for 8-bit source codes.
    pub fn reference(&self, source: Source, white: White, map: GamutMap, rgb: [u8; 3]) -> [f64; 3] {
        let (xy, curve) = match source {
            Source::Srgb => ([[0.64, 0.33], [0.30, 0.60], [0.15, 0.06]], Curve::Srgb),
            Source::DisplayP3 => (
                [[0.680, 0.320], [0.265, 0.690], [0.150, 0.060]],
                Curve::Srgb,
            ),
            Source::LinearSrgb => ([[0.64, 0.33], [0.30, 0.60], [0.15, 0.06]], Curve::Linear),
        };
        let s = primaries_white(xy, [0.3127, 0.3290]);
        let pw = apply(&self.m, [1.0; 3]);
        let sw = apply(&s, [1.0; 3]);
        let a = match white {
            White::Adapt => bradford(sw, pw),
            White::Absolute => {
                let k = pw[1] / sw[1];
                [[k, 0.0, 0.0], [0.0, k, 0.0], [0.0, 0.0, k]]
            }
        };
        let t = mul(&inv(&self.m), &mul(&a, &s));
        let lin = apply(&t, rgb.map(|c| curve.decode(c as f64 / 255.0)));
        self.xyz(gamut(lin, self.m[1], map))
    }
}

/// The gamut maps as the core documents them: clip per channel, or mix with the grey of equal
/// luminance (luminance clipped to white) until inside.
pub fn gamut(l: [f64; 3], y_row: [f64; 3], map: GamutMap) -> [f64; 3] {
    let inside = l.iter().all(|v| (-1e-9..=1.0 + 1e-9).contains(v));
    if inside || map == GamutMap::Clip {
        return l.map(|v| v.clamp(0.0, 1.0));
    }
    let s: f64 = y_row.iter().sum();
    let y = ((0..3).map(|i| y_row[i] / s * l[i]).sum::<f64>()).clamp(0.0, 1.0);
    let mut t = 1.0f64;
    for c in l {
        if c > 1.0 {
            t = t.min((1.0 - y) / (c - y));
        } else if c < 0.0 {
            t = t.min(y / (y - c));
        }
    }
    l.map(|c| (y + t.clamp(0.0, 1.0) * (c - y)).clamp(0.0, 1.0))
}

/// A small SPI LCD: narrow gamut, a gamma per channel, bluish white, a black level.
pub fn spi_lcd() -> Panel {
    let xy = [[0.62, 0.34], [0.32, 0.57], [0.15, 0.08]];
    let gammas = [2.4, 2.3, 2.5];
    let m = primaries_white(xy, [0.30, 0.32]).map(|r| r.map(|v| v * 300.0));
    let display = Display::from_primaries(
        xy.map(|p| p.map(|v| v as f32)),
        [0, 1, 2].map(|c| m[1][c] as f32),
        Xyz::new(0.3, 0.32, 0.4),
        gammas.map(|g| Transfer::Gamma(g as f32)),
    )
    .unwrap();
    Panel {
        name: "spi-lcd",
        m,
        black: [0.3, 0.32, 0.4],
        curves: gammas.map(Curve::Gamma),
        display,
    }
}

/// A panel with no black level from its primaries, white chromaticity and luminance, and a
/// pure gamma per channel (the firmware demo's panel, as it prints it).
pub fn gamma_panel(
    name: &'static str,
    xy: [[f64; 2]; 3],
    white: [f64; 2],
    luminance: f64,
    gammas: [f64; 3],
) -> Panel {
    let m = primaries_white(xy, white).map(|r| r.map(|v| v * luminance));
    let display = Display::from_primaries_white(
        xy.map(|p| p.map(|v| v as f32)),
        white.map(|v| v as f32),
        luminance as f32,
        gammas.map(|g| Transfer::Gamma(g as f32)),
    )
    .expect("valid primaries");
    Panel {
        name,
        m,
        black: [0.0; 3],
        curves: gammas.map(Curve::Gamma),
        display,
    }
}

impl Panel {
    /// The reference linear drive (gamut-mapped) for 8-bit source codes.
    pub fn reference_light(
        &self,
        source: Source,
        white: White,
        map: GamutMap,
        rgb: [u8; 3],
    ) -> [f64; 3] {
        let xyz = self.reference(source, white, map, rgb);
        let x = [0, 1, 2].map(|i| xyz[i] - self.black[i]);
        apply(&inv(&self.m), x)
    }
}
