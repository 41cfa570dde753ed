//! The matrix/curves pixel transform: decode table → 3×3 in fixed point → gamut map → panel
//! inverse-curve table, for panels that obey Cowan's additive model. Its arithmetic is chosen so
//! that a Cortex-M4 runs it in one instruction per step: 16-bit operands for the DSP extension's
//! dual multiply-accumulate (`SMLAD`) and an index made of `USAT`s (the firmware's RGB565 kernel,
//! `firmware/src/board/rgb565.rs`, is this arithmetic in assembly, checked bit for bit against
//! this portable code).
//!
//! Per pixel, with `c` the 8-bit source code values:
//!
//! 1. `d = decode[c]`: the source curve, linear light with `1.0 = 32767` (Q15), 256 × u16;
//! 2. `acc = Σⱼ mᵢⱼ dⱼ` in i32, with `m` the 3×3 `T` of [`linear_matrix`](super::source::linear_matrix)
//!    in Q14 (i16, so `|mᵢⱼ| < 2`; a row's `Σ|mᵢⱼ| < 4` keeps `acc` inside i32 — both checked at
//!    construction); the panel's linear drive is `v = acc >> 14` (`v = 32767` is full drive);
//! 3. the gamut map: [`GamutMap::Clip`] is the saturation in the index below; [`GamutMap::Desaturate`]
//!    sends the rare out-of-gamut pixel through the core's [`map_gamut`] in f32;
//! 4. the panel's inverse curve by one table look-up per channel, without interpolation, at the
//!    index `i = Σₖ clamp(v >> aₖ, 0, 2^nₖ − 1)` over the three [`RAMPS`] `(aₖ, nₖ)` — each term
//!    one `usat` with a shift. The ramps' steps are nested (multiples of `2^aₖ`), so the bins
//!    are the finest climbing ramp's: `2^a₁` units of `v` below `2^(a₁+n₁)`, `2^a₂` below
//!    `2^(a₂+n₂)`, `2^a₃` above — three tiers, because ΔE00 is most sensitive to light errors in
//!    dark colours (CIELAB's slope grows as `Y^(−2/3)`, and below `Y ≈ 0.009` chroma is linear
//!    in X, Y, Z). Where a coarser ramp steps together with a finer one the index skips a value
//!    (never read). Negative drive gives index 0, drive beyond the coarsest ramp's top the last
//!    index: the clip is free.
//!    An entry is the panel level of the light at its bin's centre; entry 0 is black and the last
//!    bin (holding full drive and everything above) is full drive, so black and white are exact.
//!
//! The levels are Q8 (`q · 256 + f`, `f/256` of the way *in light* from level `q` to `q + 1`, by
//! the panel's own curve at its own bit depth), so rounding or dithering to the panel's 5, 6 or
//! 8 bits is an add and a shift. A channel of `b` bits stores them top-aligned in the u16, as
//! `(q · 256 + f) << (8 − b)` (the code in the top `b` bits, e.g. RGB565's red at bits 11–15, its
//! field in the pixel): [`PixelTransform::levels`] shifts back, while the firmware's RGB565 kernel
//! adds the dither threshold shifted to match and masks the field in place (one instruction
//! fewer per pixel). No add overflows: a level below the top has `q ≤ 2^b − 2`, and the top level
//! only full drive's `f = 0`, so `q · 256 + f + t < 2^b · 256` for thresholds `t < 256`.
//!
//! With [`RAMPS`] = (2, 7), (4, 9), (6, 9): bins of 4 units of `v` (1.2·10⁻⁴ of full drive)
//! to 1/64, of 16 (4.9·10⁻⁴) to 1/4, of 64 (2.0·10⁻³) above; [`LEN`] = 1150 entries per channel
//! (992 of them reached), [`PixelTransform::TABLE_BYTES`] = 7 430 B of tables (decode 512 B,
//! matrix 18 B, curves 3 × 2 300 B); fine bins to 1/32 would take 1 278 entries, 8 198 B, over
//! the firmware's 8 KiB. Accuracy and speed in docs/calibration.md and docs/performance.md.

use super::source::linear_matrix;
use super::{level_lights, level_q8, Source, White};
use crate::display::{map_gamut, Display, GamutMap};
use crate::Error;

/// The decode table's linear 1.0 (Q15, the largest i16).
pub const DECODE_ONE: i32 = 32767;
/// The matrix coefficients' fixed point: Q14.
pub const Q: u32 = 14;
/// `v` of full drive.
pub const ONE: i32 = 32767;
/// The index's ramps `(a, n)`: `clamp(v >> a, 0, 2^n − 1)`, finest first. The coarsest must
/// reach past full drive (`2^(a+n) > ONE`).
pub const RAMPS: [(u32, u32); 3] = [(2, 7), (4, 9), (6, 9)];
/// Entries per channel: the largest index plus one.
pub const LEN: usize = (1 << RAMPS[0].1) + (1 << RAMPS[1].1) + (1 << RAMPS[2].1) - 2;

// the coarsest ramp covers full drive; the tiers are ordered
const _: () = assert!(1 << (RAMPS[2].0 + RAMPS[2].1) > ONE as usize);
const _: () = assert!(RAMPS[0].0 + RAMPS[0].1 <= RAMPS[1].0 + RAMPS[1].1);
const _: () = assert!(RAMPS[1].0 + RAMPS[1].1 <= RAMPS[2].0 + RAMPS[2].1);

/// Everything a [`PixelTransform`] computes with: what [`export`](super::export) writes out and
/// [`PixelTransform::from_tables`] takes back (so firmware can keep it in flash).
#[derive(Clone, Debug, PartialEq)]
pub struct Tables {
    /// Source code value → linear light, Q15 (`1.0 = 32767`).
    pub decode: [u16; 256],
    /// `T` in Q14, row-major.
    pub matrix: [[i16; 3]; 3],
    /// Per channel, the levels (Q8) by index, top-aligned: `level << (8 − bits)`.
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

/// A source → panel pixel transform: decode, 3×3, [`LEN`] inverse-curve entries per channel.
#[derive(Clone, Debug, PartialEq)]
pub struct PixelTransform {
    t: Tables,
}

/// The transform as firmware holds it (the name the exports and the demo use).
pub type PanelTransform = PixelTransform;

// the firmware budget (issue 17): tables ≤ 8 KiB of flash
const _: () = assert!(PixelTransform::TABLE_BYTES <= 8 * 1024);

impl PixelTransform {
    /// Bytes of tables (decode, matrix, curves).
    pub const TABLE_BYTES: usize = 256 * 2 + 9 * 2 + 3 * LEN * 2;

    /// Builds the transform for `panel` (Cowan's model: primaries, black, curves).
    ///
    /// Errors: [`Error::Capacity`] for bits outside 1–8 or a matrix outside Q14 (a coefficient
    /// of 2 or more, or a row's absolute sum of 4 or more: a panel gamut tiny against the
    /// source), [`Error::Singular`] for unusable matrices.
    pub fn new(panel: &Display, opts: Options) -> Result<Self, Error> {
        if opts.bits.iter().any(|b| !(1..=8).contains(b)) {
            return Err(Error::Capacity);
        }
        let t = linear_matrix(panel, opts.source, opts.white)?;

        let mut decode = [0u16; 256];
        for (c, d) in decode.iter_mut().enumerate() {
            let l = opts.source.decode(c as f32 / 255.0) as f64;
            *d = (l.clamp(0.0, 1.0) * DECODE_ONE as f64 + 0.5) as u16;
        }

        let one = (1u32 << Q) as f64;
        let mut matrix = [[0i16; 3]; 3];
        for (row, src) in matrix.iter_mut().zip(t.0.iter()) {
            let mut sum = 0i64;
            for (m, v) in row.iter_mut().zip(src.iter()) {
                let q = libm::round(*v as f64 * one);
                if !(q.abs() <= i16::MAX as f64) {
                    return Err(Error::Capacity);
                }
                *m = q as i16;
                sum += (q as i64).abs();
            }
            // |acc| ≤ Σ|m| · 32767 < 2^31
            if sum * DECODE_ONE as i64 >= i32::MAX as i64 {
                return Err(Error::Capacity);
            }
        }

        let mut curve = [[0u16; LEN]; 3];
        let mut lights = [0.0f32; 256];
        for c in 0..3 {
            let n = level_lights(&panel.transfer()[c], opts.bits[c], &mut lights);
            fill_curve(&lights[..n], &mut curve[c]);
            for e in curve[c].iter_mut() {
                *e <<= 8 - opts.bits[c];
            }
        }
        Ok(Self {
            t: Tables {
                decode,
                matrix,
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
    pub const fn from_tables(t: Tables) -> Self {
        Self { t }
    }

    /// The tables.
    pub fn tables(&self) -> &Tables {
        &self.t
    }

    /// The panel's bits per channel.
    pub fn bits(&self) -> [u8; 3] {
        self.t.bits
    }

    /// `acc = m · decode(rgb)` per channel (Q29: `acc >> 14` is the drive `v`).
    // Written out without `array::map` or iterator adapters: firmware builds at `opt-level = "z"`,
    // which does not inline them, and this is the per-pixel path.
    #[inline(always)]
    pub fn acc(&self, rgb: [u8; 3]) -> [i32; 3] {
        let t = &self.t;
        let d0 = t.decode[rgb[0] as usize] as i32;
        let d1 = t.decode[rgb[1] as usize] as i32;
        let d2 = t.decode[rgb[2] as usize] as i32;
        let d = [d0, d1, d2];
        [
            row(&t.matrix[0], d),
            row(&t.matrix[1], d),
            row(&t.matrix[2], d),
        ]
    }

    /// The panel's linear drive for a source pixel, as `v` (`32767` = full; before the gamut map).
    #[inline(always)]
    pub fn drive(&self, rgb: [u8; 3]) -> [i32; 3] {
        let a = self.acc(rgb);
        [a[0] >> Q, a[1] >> Q, a[2] >> Q]
    }

    /// The panel levels (Q8: `level · 256 + fraction`) for a source pixel.
    #[inline(always)]
    pub fn levels(&self, rgb: [u8; 3]) -> [u16; 3] {
        self.levels_for(rgb, self.t.bits)
    }

    /// [`Self::levels`] for a caller that knows the transform's bits per channel at compile
    /// time (the `embedded-graphics` adapter, from its panel colour type): the shifts that undo
    /// the tables' top alignment are then constants. `bits` other than [`Self::bits`] give
    /// wrong levels (never a panic).
    #[inline(always)]
    pub fn levels_for(&self, rgb: [u8; 3], bits: [u8; 3]) -> [u16; 3] {
        let v = self.drive(rgb);
        if self.t.map == GamutMap::Desaturate {
            // full drive's own rounding may land a few units above ONE
            let top = (ONE + 4) as u32;
            if (v[0] as u32 > top) | (v[1] as u32 > top) | (v[2] as u32 > top) {
                let v = self.desaturate(v);
                return [
                    self.lookup(0, v[0], bits[0]),
                    self.lookup(1, v[1], bits[1]),
                    self.lookup(2, v[2], bits[2]),
                ];
            }
        }
        [
            self.lookup(0, v[0], bits[0]),
            self.lookup(1, v[1], bits[1]),
            self.lookup(2, v[2], bits[2]),
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

    /// The table index of drive `v`: `Σₖ clamp(v >> aₖ, 0, 2^nₖ − 1)` over [`RAMPS`] (one `usat`
    /// each on a Cortex-M4; negative drive is index 0, drive past the top the last index).
    #[inline(always)]
    pub fn index(v: i32) -> usize {
        ramp(v, RAMPS[0]) + ramp(v, RAMPS[1]) + ramp(v, RAMPS[2])
    }

    /// The Q8 level of channel `c` (of `bits`) at drive `v`: the top-aligned entry shifted back.
    #[inline(always)]
    fn lookup(&self, c: usize, v: i32, bits: u8) -> u16 {
        self.t.curve[c][Self::index(v)].wrapping_shr(8u32.wrapping_sub(bits as u32))
    }

    /// The out-of-gamut path of [`GamutMap::Desaturate`]: the core's [`map_gamut`] in f32.
    #[cold]
    #[inline(never)]
    fn desaturate(&self, v: [i32; 3]) -> [i32; 3] {
        let one = ONE as f32;
        let l = v.map(|x| x as f32 / one);
        let (m, _) = map_gamut(l, self.t.weights, GamutMap::Desaturate);
        m.map(|x| (x * one + 0.5) as i32)
    }
}

/// `clamp(v >> a, 0, 2^n − 1)`: one ramp of the index (`usat` with a shift).
#[inline(always)]
fn ramp(v: i32, (a, n): (u32, u32)) -> usize {
    (v >> a).clamp(0, (1 << n) - 1) as usize
}

/// The curve table of one channel whose levels emit `lights`: each index's entry is the level of
/// the light at the centre of the drives that map to it (`v` stands for `[v, v + 1)` of
/// `acc / 2^14`); index 0 is black, the last (full drive and above) the top level. Indices the
/// sum of ramps skips repeat the next entry (never read; the table stays monotone).
fn fill_curve(lights: &[f32], out: &mut [u16; LEN]) {
    let top = 1i32 << (RAMPS[2].0 + RAMPS[2].1);
    let full = ((lights.len() - 1) as u16) << 8;
    let level = |lo: i32, hi: i32| {
        let centre = (lo + hi + 1) as f32 * 0.5 / ONE as f32;
        level_q8(lights, centre.min(1.0))
    };
    let (mut start, mut cur) = (0i32, 0usize);
    let mut filled = 0usize; // entries below `filled` are set
    for v in 1..=top {
        let i = if v == top {
            LEN
        } else {
            PixelTransform::index(v)
        };
        if i != cur {
            // the run `start..v` maps to `cur`
            let e = if cur == 0 { 0 } else { level(start, v - 1) };
            for x in &mut out[filled..=cur] {
                *x = e;
            }
            filled = cur + 1;
            (start, cur) = (v, i);
        }
    }
    out[LEN - 1] = full;
}

/// `m · d` (i32, wrapping: the construction keeps it exact).
#[inline(always)]
fn row(m: &[i16; 3], d: [i32; 3]) -> i32 {
    (m[0] as i32)
        .wrapping_mul(d[0])
        .wrapping_add((m[1] as i32).wrapping_mul(d[1]))
        .wrapping_add((m[2] as i32).wrapping_mul(d[2]))
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
    fn the_index_is_monotone_with_three_tiers_of_bins() {
        // the ramps' steps are nested (multiples of 2^a), so in each tier the bins are the finest
        // climbing ramp's: 2^a₁ units of v below 2^(a₁+n₁), 2^a₂ below 2^(a₂+n₂), 2^a₃ above
        let mut last = 0;
        let mut start = 0;
        for v in 1..=(1i32 << 16) {
            let i = PixelTransform::index(v);
            assert!(i >= last && i - last <= 3, "v = {v}: {last} → {i}");
            if i != last {
                let tier = RAMPS
                    .iter()
                    .position(|(a, n)| start < 1 << (a + n))
                    .unwrap();
                let w = 1 << RAMPS[tier].0;
                assert_eq!(v - start, w, "bin at {start}");
                assert_eq!(start % w, 0);
                start = v;
            }
            last = i;
        }
        assert_eq!(last, LEN - 1);
        assert_eq!(PixelTransform::index(0), 0);
        assert_eq!(PixelTransform::index(-5), 0);
        assert_eq!(PixelTransform::index(i32::MIN), 0);
        assert_eq!(PixelTransform::index(ONE), LEN - 1);
        assert_eq!(PixelTransform::index(i32::MAX), LEN - 1);
    }

    #[test]
    fn curves_are_stored_top_aligned_for_the_panel_bits() {
        for bits in [Options::RGB565, Options::RGB666, Options::RGB888] {
            let opts = Options {
                bits,
                ..Options::default()
            };
            let p = PanelTransform::new(&lcd(), opts).unwrap();
            for c in 0..3 {
                let curve = &p.tables().curve[c];
                let low = (1u16 << (8 - bits[c])) - 1;
                assert!(curve.iter().all(|e| e & low == 0), "{bits:?} {c}");
                // full drive: the top code in the top bits
                assert_eq!(curve[LEN - 1], !((1u32 << (16 - bits[c])) - 1) as u16);
                // no dither threshold carries a level past the top code
                for &e in curve.iter() {
                    let q8 = e >> (8 - bits[c]);
                    assert!(
                        q8 as u32 + 255 < 1 << (bits[c] + 8)
                            || q8 as u32 == ((1 << bits[c]) - 1) << 8
                    );
                }
            }
        }
    }

    #[test]
    fn tables_fit_the_firmware_budget() {
        assert_eq!(LEN, 1150);
        assert_eq!(PixelTransform::TABLE_BYTES, 7430);
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
