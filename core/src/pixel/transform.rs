//! The matrix/curves pixel transform: decode table → 3×3 in fixed point → gamut map → panel
//! inverse-curve table, for panels that obey Cowan's additive model.
//!
//! Per pixel, with `c` the 8-bit source code values:
//!
//! 1. `d = decode[c]`: the source curve, linear light in Q15 (`1.0 = 32768`), 256 × u16;
//! 2. `v = (Σⱼ mᵢⱼ dⱼ + round) >> shift`: the 3×3 `T` of [`linear_matrix`](super::source::linear_matrix)
//!    in i32, giving the panel's linear drive `l` as `v = round(l · 65472) + 4`. The shift is the
//!    largest that cannot overflow i32 for this `T` (chosen at construction);
//! 3. the gamut map: [`GamutMap::Clip`] is the clamp of `v` to `0..=65535` (one `usat` on a
//!    Cortex-M4); [`GamutMap::Desaturate`] sends the rare out-of-gamut pixel through the core's
//!    [`map_gamut`] in f32;
//! 4. the panel's inverse curve by one table look-up per channel, without interpolation. The
//!    table's bins widen in three tiers, because ΔE00 is most sensitive to light errors in dark
//!    colours (CIELAB's slope grows as `Y^(−2/3)`, and below `Y ≈ 0.009` chroma is linear in
//!    X, Y, Z): `F` *fine* bins of 8 units of `v` from 0, then `M` *middle* bins of 32, then the
//!    rest (`C = LEN − F − M`) *coarse* bins of 128 up to 65536. The index is
//!    `min(v >> 3, (v >> 5) + K₁, (v >> 7) + K₂)`: each tier's own formula is the smallest inside
//!    it (no branch). An entry is the panel level of the light at its bin's centre (the bin
//!    holding `l = 0` is centred on it; the bin holding `l = 1` is full drive), so the emitted
//!    light is off by at most half a bin: 6.1·10⁻⁵ in the fine tier, 2.4·10⁻⁴ in the middle,
//!    9.8·10⁻⁴ in the coarse.
//!
//! The entries are panel levels in Q8 (`q · 256 + f`, `f/256` of the way *in light* from level
//! `q` to `q + 1`, by the panel's own curve at its own bit depth), so rounding or dithering to the
//! panel's 5, 6 or 8 bits is an add and a shift.
//!
//! [`PanelTransform`] (`F = 256` fine bins to 1/32 of full drive, `M = 448` middle ones to 1/4,
//! 384 coarse ones: `LEN = 1088`) holds 6.9 KiB of tables (decode 512 B, matrix 36 B, curves
//! 3 × 2176 B); its accuracy and speed are in docs/calibration.md and docs/performance.md.

use super::source::linear_matrix;
use super::{level_lights, level_q8, Source, White};
use crate::display::{map_gamut, Display, GamutMap};
use crate::Error;

/// The decode table's linear 1.0 (Q15).
pub const DECODE_ONE: i32 = 1 << 15;
/// `v` of linear drive 0 (so that the fine bin holding it is centred on it).
pub const BIAS: i32 = 4;
/// `v − BIAS` of linear drive 1.
pub const ONE: i32 = 65472;
/// The largest `v` (the clamp).
pub const V_MAX: i32 = 65535;
/// Fine bins are `2^FINE_SHIFT` units of `v` wide.
pub const FINE_SHIFT: u32 = 3;
/// Middle bins are `2^MID_SHIFT` units of `v` wide.
pub const MID_SHIFT: u32 = 5;
/// Coarse bins are `2^COARSE_SHIFT` units of `v` wide.
pub const COARSE_SHIFT: u32 = 7;

/// Everything a [`PixelTransform`] computes with: what [`export`](super::export) writes out and
/// [`PixelTransform::from_tables`] takes back (so firmware can keep it in flash).
#[derive(Clone, Debug, PartialEq)]
pub struct Tables<const LEN: usize> {
    /// Source code value → linear light, Q15.
    pub decode: [u16; 256],
    /// `T` scaled to `v` units and by `2^shift`, row-major.
    pub matrix: [[i32; 3]; 3],
    /// The matrix's fixed-point shift.
    pub shift: u32,
    /// `(BIAS << shift) + (1 << (shift − 1))`: the bias and rounding.
    pub round: i32,
    /// Per channel, the levels (Q8): the fine bins, the middle ones, the coarse ones.
    pub curve: [[u16; LEN]; 3],
    /// The panel's bits per channel (5, 6 or 8 for RGB565/666/888).
    pub bits: [u8; 3],
    /// The gamut map.
    pub map: GamutMap,
    /// The panel's luminance weights (for [`GamutMap::Desaturate`]).
    pub weights: [f32; 3],
}

/// How to build a transform: the source, the white, the gamut map and the panel's bit depth.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Options {
    /// The source colour space.
    pub source: Source,
    /// How the source white is reproduced.
    pub white: White,
    /// Out-of-gamut colours.
    pub map: GamutMap,
    /// Bits per panel channel, R G B (1–8): `[5, 6, 5]` for RGB565.
    pub bits: [u8; 3],
}

impl Default for Options {
    /// sRGB, adapted white, clip, RGB888.
    fn default() -> Self {
        Self {
            source: Source::Srgb,
            white: White::Adapt,
            map: GamutMap::Clip,
            bits: [8, 8, 8],
        }
    }
}

impl Options {
    /// The bits of RGB565.
    pub const RGB565: [u8; 3] = [5, 6, 5];
    /// The bits of RGB666.
    pub const RGB666: [u8; 3] = [6, 6, 6];
    /// The bits of RGB888.
    pub const RGB888: [u8; 3] = [8, 8, 8];
}

/// A source → panel pixel transform with `LEN` inverse-curve entries per channel: `F` fine,
/// `M` middle and `LEN − F − M` coarse bins, which must tile `0..65536` (`8F + 32M + 128C =
/// 65536`, tier boundaries on the next tier's bins; checked at compile time).
#[derive(Clone, Debug, PartialEq)]
pub struct PixelTransform<const LEN: usize, const F: usize, const M: usize> {
    t: Tables<LEN>,
}

/// The transform sized for ≤ 8 KiB of tables: fine bins to 1/32 of full drive, middle ones to
/// 1/4, coarse ones above.
pub type PanelTransform = PixelTransform<1088, 256, 448>;

// the firmware budget (issue 17): tables ≤ 8 KiB of flash
const _: () = assert!(PanelTransform::TABLE_BYTES <= 8 * 1024);

impl<const LEN: usize, const F: usize, const M: usize> PixelTransform<LEN, F, M> {
    /// Coarse bins.
    pub const C: usize = LEN - F - M;
    /// Where the middle tier starts (`v`).
    pub const MID_START: usize = F << FINE_SHIFT;
    /// Where the coarse tier starts (`v`).
    pub const COARSE_START: usize = Self::MID_START + (M << MID_SHIFT);
    /// `K₁`: added to `v >> 5` to index the middle tier.
    pub const K_MID: usize = F - (Self::MID_START >> MID_SHIFT);
    /// `K₂`: added to `v >> 7` to index the coarse tier.
    pub const K_COARSE: usize = F + M - (Self::COARSE_START >> COARSE_SHIFT);
    const SIZES_OK: () = assert!(
        F >= 4
            && M >= 4
            && LEN >= F + M + 2
            && (F << FINE_SHIFT) % (1 << MID_SHIFT) == 0
            && ((F << FINE_SHIFT) + (M << MID_SHIFT)) % (1 << COARSE_SHIFT) == 0
            && (F << FINE_SHIFT) + (M << MID_SHIFT) + ((LEN - F - M) << COARSE_SHIFT) == 65536,
        "PixelTransform<LEN, F, M>: 8F + 32M + 128(LEN − F − M) = 65536, F ≡ 0 mod 4, 8F + 32M ≡ 0 mod 128"
    );
    /// Bytes of tables (decode, matrix, curves).
    pub const TABLE_BYTES: usize = 256 * 2 + 9 * 4 + 3 * LEN * 2;

    /// The centre of table entry `i`'s bin, in `v`.
    pub fn centre(i: usize) -> i32 {
        let c = if i < F {
            (i << FINE_SHIFT) + (1 << (FINE_SHIFT - 1))
        } else if i < F + M {
            Self::MID_START + ((i - F) << MID_SHIFT) + (1 << (MID_SHIFT - 1))
        } else {
            Self::COARSE_START + ((i - F - M) << COARSE_SHIFT) + (1 << (COARSE_SHIFT - 1))
        };
        c as i32
    }

    /// Builds the transform for `panel` (Cowan's model: primaries, black, curves).
    ///
    /// Errors: [`Error::Capacity`] for bits outside 1–8 or a matrix too large for i32 fixed
    /// point (a panel gamut tiny against the source), [`Error::Singular`] for unusable matrices.
    pub fn new(panel: &Display, opts: Options) -> Result<Self, Error> {
        let () = Self::SIZES_OK;
        if opts.bits.iter().any(|b| !(1..=8).contains(b)) {
            return Err(Error::Capacity);
        }
        let t = linear_matrix(panel, opts.source, opts.white)?;

        let mut decode = [0u16; 256];
        for (c, d) in decode.iter_mut().enumerate() {
            let l = opts.source.decode(c as f32 / 255.0) as f64;
            *d = (l * DECODE_ONE as f64 + 0.5) as u16;
        }

        // the largest shift with |Σ m d| + round < 2^31 for every input
        let k = ONE as f64 / DECODE_ONE as f64;
        let row =
            t.0.iter()
                .map(|r| r.iter().map(|v| v.abs() as f64).sum::<f64>() * k)
                .fold(0.0f64, f64::max);
        let limit = (i32::MAX - 1) as f64;
        let shift = (6..=20u32)
            .rev()
            .find(|s| {
                let p = (1u64 << s) as f64;
                (row * p + 2.0) * DECODE_ONE as f64 + (BIAS as f64 + 1.0) * p < limit
            })
            .ok_or(Error::Capacity)?;
        let p = (1u64 << shift) as f64;
        let matrix = t.0.map(|r| r.map(|v| libm::round(v as f64 * k * p) as i32));
        let round = (BIAS << shift) + (1 << (shift - 1));

        let mut curve = [[0u16; LEN]; 3];
        let mut lights = [0.0f32; 256];
        let white = Self::index(ONE + BIAS);
        for c in 0..3 {
            let n = level_lights(&panel.transfer()[c], opts.bits[c], &mut lights);
            let lv = &lights[..n];
            for (i, e) in curve[c].iter_mut().enumerate() {
                let l = if i >= white {
                    1.0 // the bin holding full drive (and everything above)
                } else {
                    ((Self::centre(i) - BIAS) as f32 / ONE as f32).clamp(0.0, 1.0)
                };
                *e = level_q8(lv, l);
            }
        }
        Ok(Self {
            t: Tables {
                decode,
                matrix,
                shift,
                round,
                curve,
                bits: opts.bits,
                map: opts.map,
                weights: panel.luminance_weights(),
            },
        })
    }

    /// A transform from tables made by [`Self::new`] (and written out by
    /// [`export`](super::export)): `const`, so the tables can live in flash. The arithmetic
    /// wraps, so any tables are safe (if wrong).
    pub const fn from_tables(t: Tables<LEN>) -> Self {
        let () = Self::SIZES_OK;
        Self { t }
    }

    /// The tables.
    pub fn tables(&self) -> &Tables<LEN> {
        &self.t
    }

    /// The panel's bits per channel.
    pub fn bits(&self) -> [u8; 3] {
        self.t.bits
    }

    /// The panel's linear drive for a source pixel, as `v` (before the gamut map).
    // Written out without `array::map` or iterator adapters: firmware builds at `opt-level = "z"`,
    // which does not inline them, and this is the per-pixel path.
    #[inline(always)]
    pub fn drive(&self, rgb: [u8; 3]) -> [i32; 3] {
        let t = &self.t;
        let d0 = t.decode[rgb[0] as usize] as i32;
        let d1 = t.decode[rgb[1] as usize] as i32;
        let d2 = t.decode[rgb[2] as usize] as i32;
        let d = [d0, d1, d2];
        [
            row(&t.matrix[0], d, t.round, t.shift),
            row(&t.matrix[1], d, t.round, t.shift),
            row(&t.matrix[2], d, t.round, t.shift),
        ]
    }

    /// The panel levels (Q8: `level · 256 + fraction`) for a source pixel.
    #[inline(always)]
    pub fn levels(&self, rgb: [u8; 3]) -> [u16; 3] {
        let mut v = self.drive(rgb);
        if self.t.map == GamutMap::Desaturate {
            let one = ONE as u32;
            let outside = (v[0].wrapping_sub(BIAS) as u32 > one)
                | (v[1].wrapping_sub(BIAS) as u32 > one)
                | (v[2].wrapping_sub(BIAS) as u32 > one);
            if outside {
                v = self.desaturate(v);
            }
        }
        [
            self.lookup(0, v[0]),
            self.lookup(1, v[1]),
            self.lookup(2, v[2]),
        ]
    }

    /// The panel code values for a source pixel, with a dither threshold in `0..256`
    /// (128 rounds; see [`Dither`](super::Dither)).
    #[inline(always)]
    pub fn apply(&self, rgb: [u8; 3], threshold: u16) -> [u8; 3] {
        let l = self.levels(rgb);
        [
            ((l[0] + threshold) >> 8) as u8,
            ((l[1] + threshold) >> 8) as u8,
            ((l[2] + threshold) >> 8) as u8,
        ]
    }

    /// The table index of `v` after the clamp that is [`GamutMap::Clip`]: the smallest of the
    /// three tiers' formulas, which is the tier `v` lies in (no branch; tested for every `v`).
    #[inline(always)]
    pub fn index(v: i32) -> usize {
        let v = v.clamp(0, V_MAX) as usize;
        let fine = v >> FINE_SHIFT;
        let mid = (v >> MID_SHIFT) + Self::K_MID;
        let coarse = (v >> COARSE_SHIFT) + Self::K_COARSE;
        fine.min(mid).min(coarse)
    }

    #[inline(always)]
    fn lookup(&self, c: usize, v: i32) -> u16 {
        self.t.curve[c][Self::index(v)]
    }

    /// The out-of-gamut path of [`GamutMap::Desaturate`]: the core's [`map_gamut`] in f32.
    #[cold]
    #[inline(never)]
    fn desaturate(&self, v: [i32; 3]) -> [i32; 3] {
        let one = ONE as f32;
        let l = v.map(|x| (x - BIAS) as f32 / one);
        let (m, _) = map_gamut(l, self.t.weights, GamutMap::Desaturate);
        m.map(|x| (x * one + 0.5) as i32 + BIAS)
    }
}

/// `(m · d + round) >> shift`, wrapping.
#[inline(always)]
fn row(m: &[i32; 3], d: [i32; 3], round: i32, shift: u32) -> i32 {
    m[0].wrapping_mul(d[0])
        .wrapping_add(m[1].wrapping_mul(d[1]))
        .wrapping_add(m[2].wrapping_mul(d[2]))
        .wrapping_add(round)
        .wrapping_shr(shift)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::display::Transfer;

    /// A small SPI LCD: narrower than sRGB, gamma 2.4, a bluish white.
    fn lcd() -> Display {
        let t = [
            Transfer::Gamma(2.4),
            Transfer::Gamma(2.3),
            Transfer::Gamma(2.5),
        ];
        Display::from_primaries_white(
            [[0.62, 0.34], [0.32, 0.57], [0.15, 0.08]],
            [0.30, 0.32],
            300.0,
            t,
        )
        .unwrap()
    }

    #[test]
    fn black_is_black_and_white_is_full_drive() {
        for source in Source::ALL {
            for bits in [Options::RGB888, Options::RGB565, Options::RGB666] {
                let opts = Options {
                    source,
                    bits,
                    ..Options::default()
                };
                let p = PanelTransform::new(&lcd(), opts).unwrap();
                assert_eq!(p.levels([0, 0, 0]), [0; 3], "{source:?}");
                let max = bits.map(|b| ((1u16 << b) - 1) << 8);
                assert_eq!(p.levels([255; 3]), max, "{source:?} {bits:?}");
                for thr in [2, 128, 254] {
                    assert_eq!(p.apply([0; 3], thr), [0; 3]);
                    assert_eq!(p.apply([255; 3], thr), max.map(|m| (m >> 8) as u8));
                }
            }
        }
    }

    #[test]
    fn identity_panel_reproduces_srgb_codes() {
        // a panel that *is* sRGB: every 8-bit code comes back within rounding
        let p = PanelTransform::new(&Display::srgb(), Options::default()).unwrap();
        for c in 0..=255u8 {
            for rgb in [
                [c, 0, 0],
                [0, c, 0],
                [0, 0, c],
                [c, c, c],
                [c, 255 - c, c / 2],
            ] {
                let got = p.apply(rgb, 128);
                for i in 0..3 {
                    assert!(
                        (got[i] as i32 - rgb[i] as i32).abs() <= 1,
                        "{rgb:?} → {got:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn grey_ramps_are_monotone() {
        let opts = Options {
            source: Source::DisplayP3,
            ..Options::default()
        };
        let p = PanelTransform::new(&lcd(), opts).unwrap();
        let mut last = [0u16; 3];
        for c in 0..=255u8 {
            let l = p.levels([c, c, c]);
            for i in 0..3 {
                assert!(l[i] >= last[i], "{c}: {l:?} after {last:?}");
            }
            last = l;
        }
    }

    #[test]
    fn desaturate_maps_out_of_gamut_colours_and_keeps_in_gamut_ones() {
        let clip = PanelTransform::new(&lcd(), Options::default()).unwrap();
        let desat = PanelTransform::new(
            &lcd(),
            Options {
                map: GamutMap::Desaturate,
                ..Options::default()
            },
        )
        .unwrap();
        // sRGB red is outside this panel: the two maps differ there
        assert_ne!(clip.levels([255, 0, 0]), desat.levels([255, 0, 0]));
        // a mid grey is inside: identical
        assert_eq!(clip.levels([128, 128, 128]), desat.levels([128, 128, 128]));
    }

    #[test]
    fn absolute_white_keeps_d65() {
        // the LCD's white is bluish: an absolute D65 white is not full drive on every channel
        let opts = Options {
            white: White::Absolute,
            ..Options::default()
        };
        let p = PanelTransform::new(&lcd(), opts).unwrap();
        let l = p.levels([255; 3]);
        assert!(l.iter().any(|v| *v < 255 << 8), "{l:?}");
    }

    #[test]
    fn every_v_indexes_its_own_tier() {
        type P = PanelTransform;
        for v in 0..=V_MAX {
            let u = v as usize;
            let want = if u < P::MID_START {
                u >> FINE_SHIFT
            } else if u < P::COARSE_START {
                256 + ((u - P::MID_START) >> MID_SHIFT)
            } else {
                256 + 448 + ((u - P::COARSE_START) >> COARSE_SHIFT)
            };
            assert_eq!(P::index(v), want, "v = {v}");
            // and the entry's bin holds v
            let half = match want {
                i if i < 256 => 4,
                i if i < 256 + 448 => 16,
                _ => 64,
            };
            assert!((P::centre(want) - v).abs() <= half);
        }
        assert_eq!(P::index(-5), 0);
        assert_eq!(P::index(1 << 20), 1087);
    }

    #[test]
    fn bad_bits_are_refused() {
        let opts = Options {
            bits: [0, 6, 5],
            ..Options::default()
        };
        assert_eq!(
            PanelTransform::new(&lcd(), opts).err(),
            Some(Error::Capacity)
        );
    }
}
