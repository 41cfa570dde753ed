//! The framebuffer's per-pixel kernel in Cortex-M4 assembly: `specpoly_core::pixel`'s
//! [`PixelTransform`] ([`GamutMap::Clip`]), the Bayer 8×8 threshold and the RGB565 pack, for rows
//! of 8-bit source pixels — the same integers as the portable code, bit for bit (checked by the
//! demo on every pixel of its frame and by `tests/tests/firmware_framebuffer.rs` against the
//! host), in 39.8 instructions per pixel instead of the compiler's 64.4 (docs/performance.md,
//! "Calibrated framebuffer"). The transform stores each channel's levels top-aligned for its
//! bits (`specpoly_core::pixel::transform`) and no add carries past bit 15, so two pixels'
//! levels, packed in one word's halves, are dithered, masked and stored together: per pair one
//! threshold word, three adds, three masks, two `orr`s with shifted operands and one store.
//!
//! Assembly because the two instructions that make it short are the DSP extension's, which
//! stable Rust does not emit on its own here: `SMLAD` (two 16 × 16 products and a 32-bit
//! accumulate: the matrix is 3 × (`SMUL<x>B` + `SMLAD`) on the packed decoded pair `d₀ | d₁ << 16`
//! instead of 9 multiplies with their constants rematerialised) and `PKHBT` (the packing); the
//! index's `USAT`s with shifts the compiler finds too. The 14 registers hold the pointers, the
//! tables' bases and three of the five packed coefficient words; the other two (one `LDM` or
//! `LDRD` a pixel) and the row's four threshold pairs are on the stack, and the first pixel's
//! levels are pushed while the second is computed. The loop does 16 pixels per turn (pair `j` of
//! an 8-pixel group: threshold word `[sp, #12 + 4j]`); a row of an odd number of 8-pixel groups
//! starts halfway into it.
//!
//! Cortex-M4 generic (no mps2 peripheral); here because board support is where the firmware keeps
//! its `unsafe`.

use specpoly_core::pixel::dither::BAYER8;
use specpoly_core::pixel::transform::LEN;
use specpoly_core::pixel::PixelTransform;
use specpoly_core::GamutMap;

/// What the assembly reads, in this order (offsets in the comments are the assembly's).
#[repr(C)]
struct Frame {
    /// 0: the first source pixel (3 bytes each).
    src: *const u8,
    /// 4: the first output pixel.
    dst: *mut u16,
    /// 8: rows (≥ 1).
    rows: u32,
    /// 12: the decode table.
    decode: *const u16,
    /// 16, 20, 24: the R, G, B curve tables.
    curve: [*const u16; 3],
    /// 28, 32, 36: `m_c0 | m_c1 << 16` for c = R, G, B.
    m01: [u32; 3],
    /// 40: `m_R2 | m_G2 << 16`.
    m2rg: u32,
    /// 44: `m_B2`.
    m2b: u32,
    /// 48: source bytes per row (3 × width, width a multiple of 8, ≥ 8).
    row_bytes: u32,
    /// 52: the first row's `y`.
    y: u32,
    /// 56: the thresholds in pairs, `[y & 7][(x & 7) / 2]` ([`PAIRS`]).
    pairs: *const [[u32; 4]; 8],
    /// 60: 1 when a row is an odd number of 8-pixel groups (the loop does 16 pixels a turn).
    odd: u32,
}

/// The Bayer thresholds `4b + 2` by `[y & 7][x & 7]` (`specpoly_core::pixel::Dither`).
static THRESHOLDS: [[u16; 8]; 8] = {
    let mut t = [[0u16; 8]; 8];
    let mut y = 0;
    while y < 8 {
        let mut x = 0;
        while x < 8 {
            t[y][x] = BAYER8[y][x] as u16 * 4 + 2;
            x += 1;
        }
        y += 1;
    }
    t
};

/// The thresholds of pixel pairs, shifted for the RGB565 fields' least bits: `[y & 7][j]` is
/// `t(2j) << 3 | t(2j + 1) << 19` of [`THRESHOLDS`]`[y & 7]` (the red and blue fields' shift;
/// green's `<< 2` is this word `>> 1`).
static PAIRS: [[u32; 4]; 8] = {
    let mut p = [[0u32; 4]; 8];
    let mut y = 0;
    while y < 8 {
        let mut j = 0;
        while j < 4 {
            p[y][j] = (THRESHOLDS[y][2 * j] as u32) << 3 | (THRESHOLDS[y][2 * j + 1] as u32) << 19;
            j += 1;
        }
        y += 1;
    }
    p
};

core::arch::global_asm!(concat!(
    r#"
    .syntax unified
    .thumb
    .section .text.specpoly_rgb565_run,"ax",%progbits
    .global specpoly_rgb565_run
    .type specpoly_rgb565_run,%function
    .thumb_func

@ two pixels, A then B; \j = (x & 7) / 2. Registers: r0 src, r1 dst, r2 decode, r3/r4/r5
@ curves R/G/B, r6/r7 m01 R/G, r8 m2rg (A's levels after the second pixel, so reloaded by the
@ first pixel's LDM); temporaries r9-r12, lr. Stack: [sp, 0] m2rg, 4 m2b, 8 m01b, 12 + 4j the
@ pair's thresholds tA << 3 | tB << 19. A's levels are pushed while B is computed.
.macro PAIR j
"#,
    super::transform_asm::transform_asm!("ldm     sp, {{r8, r11, r12}}", ", lsl #1", "ldrh"),
    r#"    push    {{r10, r11, r12}}           @ A's R, B, G levels
"#,
    super::transform_asm::transform_asm!("ldrd    r11, r12, [sp, #16]", ", lsl #1", "ldrh"),
    r#"    pop     {{r8, r9, lr}}              @ A's R, B, G levels
    pkhbt   r10, r8, r10, lsl #16       @ R of A | R of B << 16 (levels top-aligned: R << 3,
    pkhbt   r11, r9, r11, lsl #16       @ G << 2, B << 3; no add carries past bit 15, so the
    pkhbt   r12, lr, r12, lsl #16       @ two halves add and mask as one word)
    ldr     r9, [sp, #(12 + 4 * \j)]    @ tA << 3 | tB << 19
    add     r10, r10, r9
    add     r11, r11, r9
    add     r12, r12, r9, lsr #1        @ tA << 2 | tB << 18
    and     r10, r10, #0xF800F800       @ R codes << 11, << 27
    and     r11, r11, #0xF800F800       @ B codes << 11, << 27
    and     r12, r12, #0xFC00FC00       @ G codes << 10, << 26
    orr     r10, r10, r12, lsr #5
    orr     r10, r10, r11, lsr #11
    str     r10, [r1], #4               @ A, then B
.endm

specpoly_rgb565_run:
    push    {{r4-r11, lr}}
    sub     sp, sp, #56
    @ stack: 0 m2rg, 4 m2b, 8 m01b, [12, 28) the row's four threshold pairs, 28 end of the row,
    @ 32 rows left, 36 y, 40 row bytes, 44 the threshold-pair table, 48 odd
    ldr     r1, [r0, #40]
    str     r1, [sp, #0]
    ldr     r1, [r0, #44]
    str     r1, [sp, #4]
    ldr     r1, [r0, #36]
    str     r1, [sp, #8]
    ldr     r1, [r0, #8]
    str     r1, [sp, #32]
    ldr     r1, [r0, #52]
    str     r1, [sp, #36]
    ldr     r1, [r0, #48]
    str     r1, [sp, #40]
    ldr     r1, [r0, #56]
    str     r1, [sp, #44]
    ldr     r1, [r0, #60]
    str     r1, [sp, #48]
    ldr     r2, [r0, #12]
    ldr     r3, [r0, #16]
    ldr     r4, [r0, #20]
    ldr     r5, [r0, #24]
    ldr     r6, [r0, #28]
    ldr     r7, [r0, #32]
    ldr     r8, [r0, #40]
    ldr     r1, [r0, #4]
    ldr     r0, [r0, #0]
3:
    ldr     r9, [sp, #36]               @ this row's threshold pairs: table[y & 7]
    ldr     r10, [sp, #44]
    and     r9, r9, #7
    add     r10, r10, r9, lsl #4
    ldm     r10, {{r9, r10, r11, r12}}
    add     lr, sp, #12
    stm     lr, {{r9, r10, r11, r12}}
    ldr     r9, [sp, #40]
    add     r9, r0, r9
    str     r9, [sp, #28]
    ldr     r9, [sp, #48]               @ an odd number of 8-pixel groups: start halfway
    cmp     r9, #0
    bne     2f
1:
    PAIR 0
    PAIR 1
    PAIR 2
    PAIR 3
2:
    PAIR 0
    PAIR 1
    PAIR 2
    PAIR 3
    ldr     r9, [sp, #28]
    cmp     r0, r9
    bne     1b
    ldr     r9, [sp, #36]
    add     r9, r9, #1
    str     r9, [sp, #36]
    ldr     r9, [sp, #32]
    subs    r9, r9, #1
    str     r9, [sp, #32]
    bne     3b
    add     sp, sp, #56
    pop     {{r4-r11, pc}}
    .size specpoly_rgb565_run, . - specpoly_rgb565_run
"#
));

extern "C" {
    fn specpoly_rgb565_run(frame: *const Frame);
}

/// The kernel for one transform: RGB565 (5-6-5 bits) with [`GamutMap::Clip`].
pub struct Rgb565Kernel<'t> {
    t: &'t PixelTransform,
    m01: [u32; 3],
    m2rg: u32,
    m2b: u32,
}

/// `lo | hi << 16` of two i16.
fn pack(lo: i16, hi: i16) -> u32 {
    lo as u16 as u32 | (hi as u16 as u32) << 16
}

impl<'t> Rgb565Kernel<'t> {
    /// The kernel of `t`; `None` unless it makes RGB565 codes with [`GamutMap::Clip`] (the
    /// desaturating map's slow path is not in the assembly).
    pub fn new(t: &'t PixelTransform) -> Option<Self> {
        let tab = t.tables();
        // the assembly's masks and shifts are RGB565's top-aligned fields
        if tab.bits != [5, 6, 5] || tab.map != GamutMap::Clip {
            return None;
        }
        let m = tab.matrix;
        Some(Self {
            t,
            m01: [0, 1, 2].map(|c| pack(m[c][0], m[c][1])),
            m2rg: pack(m[0][2], m[1][2]),
            m2b: pack(m[2][2], 0),
        })
    }

    /// Rows `y0, y0 + 1, …` of a framebuffer `width` pixels wide: `dst[i]` = the RGB565 code of
    /// `src[i]`, dithered at `(i % width, y0 + i / width)`. The assembly runs when `width` is a
    /// multiple of 8; other widths go through the portable transform. Panics if the lengths
    /// differ or are not whole rows.
    pub fn rows(&self, src: &[[u8; 3]], dst: &mut [u16], width: usize, y0: usize) {
        assert_eq!(src.len(), dst.len(), "source and destination");
        assert!(width > 0 && src.len().is_multiple_of(width), "whole rows");
        let rows = src.len() / width;
        if rows == 0 {
            return;
        }
        if !width.is_multiple_of(8) {
            for (i, (s, d)) in src.iter().zip(dst.iter_mut()).enumerate() {
                let t = THRESHOLDS[(y0 + i / width) & 7][(i % width) & 7];
                let c = self.t.apply(*s, t);
                *d = (c[0] as u16) << 11 | (c[1] as u16) << 5 | c[2] as u16;
            }
            return;
        }
        let tab = self.t.tables();
        let curve: &[[u16; LEN]; 3] = &tab.curve;
        let frame = Frame {
            src: src.as_ptr().cast(),
            dst: dst.as_mut_ptr(),
            rows: rows as u32,
            decode: tab.decode.as_ptr(),
            curve: [curve[0].as_ptr(), curve[1].as_ptr(), curve[2].as_ptr()],
            m01: self.m01,
            m2rg: self.m2rg,
            m2b: self.m2b,
            row_bytes: (3 * width) as u32,
            y: y0 as u32,
            pairs: &PAIRS,
            odd: ((width / 8) % 2) as u32,
        };
        // SAFETY: the assembly reads `rows × width` pixels (3 bytes each) from `src` and writes
        // as many u16 to `dst`, both exactly their lengths (checked above; `width` a multiple of
        // 8, so every row ends on its loop: 16 pixels a turn, entered halfway when `odd`; the
        // 32-bit stores of pixel pairs need no alignment on the Cortex-M4); it reads the decode
        // table at code values (0‥255 < 256 entries), each curve table at indices
        // ≤ 127 + 511 + 511 = `LEN − 1` (`usat` bounds every term) and `PAIRS[y & 7]`, all
        // borrowed or static for the call. It restores the callee-saved registers and `sp`
        // (AAPCS) and touches no other memory than its own 56 + 12 bytes of stack (the 12 pushed
        // and popped within a pair, always above `sp`).
        unsafe { specpoly_rgb565_run(&frame) };
    }
}

// the assembly's index bounds are the transform's: (2, 7), (4, 9), (6, 9) with Q = 14
const _: () = assert!(
    specpoly_core::pixel::transform::RAMPS[0].0 == 2
        && specpoly_core::pixel::transform::RAMPS[0].1 == 7
        && specpoly_core::pixel::transform::RAMPS[1].0 == 4
        && specpoly_core::pixel::transform::RAMPS[1].1 == 9
        && specpoly_core::pixel::transform::RAMPS[2].0 == 6
        && specpoly_core::pixel::transform::RAMPS[2].1 == 9
        && specpoly_core::pixel::transform::Q == 14
);
