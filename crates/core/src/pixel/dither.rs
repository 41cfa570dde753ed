//! Ordered dithering of panel levels (Q8) to the panel's bits: a Bayer 8×8 threshold matrix
//! (Bayer 1973). Over any aligned 8×8 block the 64 thresholds `4b + 2`, `b = 0..63`, are each
//! used once, so a flat colour whose level is `q + f/256` shows level `q + 1` on
//! `⌊(f + 2)/4⌋` of the 64 pixels: the block's mean light is the wanted one within 1/128 of a
//! level step. Chosen over blue noise because its table is 64 bytes, it needs no state, and that
//! block mean is exact; its cross-hatch texture is finer than the 5/6-bit steps it replaces.

/// The Bayer 8×8 index matrix `[y][x]`, values `0..64`, built by the recursion
/// `M₂ₙ = [[4Mₙ, 4Mₙ + 2], [4Mₙ + 3, 4Mₙ + 1]]`.
pub const BAYER8: [[u8; 8]; 8] = bayer8();

const fn bayer8() -> [[u8; 8]; 8] {
    let mut m = [[0u8; 8]; 8];
    let mut size = 1;
    while size < 8 {
        // fill the other three quadrants from the top-left `size × size` one, then scale it
        let mut y = 0;
        while y < size {
            let mut x = 0;
            while x < size {
                let v = 4 * m[y][x];
                m[y][x] = v;
                m[y][x + size] = v + 2;
                m[y + size][x] = v + 3;
                m[y + size][x + size] = v + 1;
                x += 1;
            }
            y += 1;
        }
        size *= 2;
    }
    m
}

/// How panel levels become codes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Dither {
    /// Round to the nearest level (threshold 128).
    None,
    /// Bayer 8×8 ordered dither.
    #[default]
    Ordered,
}

impl Dither {
    /// The threshold (`0..256`) added to a Q8 level at pixel `(x, y)` before `>> 8`.
    #[inline(always)]
    pub fn threshold(self, x: u32, y: u32) -> u16 {
        match self {
            Dither::None => 128,
            Dither::Ordered => BAYER8[(y & 7) as usize][(x & 7) as usize] as u16 * 4 + 2,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bayer_is_a_permutation_with_balanced_quadrants() {
        let mut seen = [false; 64];
        for row in BAYER8 {
            for v in row {
                assert!(!seen[v as usize]);
                seen[v as usize] = true;
            }
        }
        // the textbook first row (Bayer 1973; Ulichney, Digital Halftoning, 1987)
        assert_eq!(BAYER8[0], [0, 32, 8, 40, 2, 34, 10, 42]);
        assert_eq!(BAYER8[7], [63, 31, 55, 23, 61, 29, 53, 21]);
    }

    #[test]
    fn block_mean_is_the_level() {
        for f in 0..256u16 {
            let q = 10u16;
            let level = (q << 8) | f;
            let mut sum = 0u32;
            for y in 0..8 {
                for x in 0..8 {
                    sum += ((level + Dither::Ordered.threshold(x, y)) >> 8) as u32;
                }
            }
            let mean = sum as f64 / 64.0;
            let want = q as f64 + f as f64 / 256.0;
            assert!(
                (mean - want).abs() <= 1.0 / 128.0 + 1e-12,
                "{f}: {mean} vs {want}"
            );
        }
    }
}
