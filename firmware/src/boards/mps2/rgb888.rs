//! The framebuffer's per-pixel kernel for 8-bit panels, in Cortex-M4 assembly: the same
//! transform as [`rgb565`](super::rgb565) (decode, `SMLAD` 3×3, the index's `USAT` ramps and
//! clip, [`GamutMap::Clip`]) with curve tables baked for 8-bit output — the code value itself,
//! one byte per entry ([`Codes`]: the transform's Q8 levels rounded, what
//! [`PixelTransform::apply`] gives at threshold 128, so no dither) — and two stores:
//!
//! - XRGB8888 (`0x00RRGGBB`, one 32-bit store: STM32 LTDC/DMA2D framebuffers, embedded-graphics'
//!   `Rgb888` storage) — [`Rgb888Kernel::xrgb`];
//! - packed RGB888 (3 bytes R, G, B: 18/24-bit SPI panels such as the ILI9488) —
//!   [`Rgb888Kernel::packed`].
//!
//! No dither, so rows do not matter: the loop runs over the whole run of pixels, 8 per turn.
//! The same integers as the portable code, bit for bit (checked by the demo on its frames and by
//! `tests/tests/firmware_framebuffer.rs` against the host); 35.4 instructions per pixel
//! (docs/performance.md, "Calibrated framebuffer").

use specpoly_core::pixel::transform::LEN;
use specpoly_core::pixel::PixelTransform;
use specpoly_core::GamutMap;

/// The 8-bit code tables of an RGB888 transform: `codes[c][i] = (curve[c][i] + 128) >> 8`,
/// 3 × [`LEN`] bytes (3 450 B; with the decode table and matrix 3 980 B of the transform's
/// 7 430 B are read by the kernel). `firmware/build.rs` bakes them into flash beside the
/// transform; [`Rgb888Kernel::new`] checks them against it.
pub type Codes = [[u8; LEN]; 3];

/// What the assembly reads, in this order (offsets in the comments are the assembly's).
#[repr(C)]
struct Run {
    /// 0: the first source pixel (3 bytes each).
    src: *const u8,
    /// 4: the first output pixel.
    dst: *mut u8,
    /// 8: one past the last source byte (3 × a multiple of 8 pixels, ≥ 8 pixels).
    end: *const u8,
    /// 12: the decode table.
    decode: *const u16,
    /// 16, 20, 24: the R, G, B code tables.
    codes: [*const u8; 3],
    /// 28, 32, 36: `m_c0 | m_c1 << 16` for c = R, G, B.
    m01: [u32; 3],
    /// 40: `m_R2 | m_G2 << 16`.
    m2rg: u32,
    /// 44: `m_B2`.
    m2b: u32,
}

core::arch::global_asm!(concat!(
    r#"
    .syntax unified
    .thumb

@ one pixel. Registers: r0 src, r1 dst, r2 decode, r3/r4/r5 code tables R/G/B, r6/r7 m01 R/G,
@ r8 m2rg; temporaries r9-r12, lr. Stack: [sp, 0] end, 4 m2b, 8 m01b. \packed: 3 bytes R G B,
@ else one word 0x00RRGGBB.
.macro PIXEL888 packed
"#,
    super::transform_asm::transform_asm!("ldrd    r11, r12, [sp, #4]", "", "ldrb"),
    r#".if \packed
    strb    r12, [r1, #1]
    strb    r11, [r1, #2]
    strb    r10, [r1], #3
.else
    orr     r12, r12, r10, lsl #8
    orr     r11, r11, r12, lsl #8
    str     r11, [r1], #4
.endif
.endm

.macro RUN888 name, packed
    .section .text.\name,"ax",%progbits
    .global \name
    .type \name,%function
    .thumb_func
\name:
    push    {{r4-r11, lr}}
    sub     sp, sp, #12
    ldr     r1, [r0, #8]
    str     r1, [sp, #0]
    ldr     r1, [r0, #44]
    str     r1, [sp, #4]
    ldr     r1, [r0, #36]
    str     r1, [sp, #8]
    ldr     r2, [r0, #12]
    ldr     r3, [r0, #16]
    ldr     r4, [r0, #20]
    ldr     r5, [r0, #24]
    ldr     r6, [r0, #28]
    ldr     r7, [r0, #32]
    ldr     r8, [r0, #40]
    ldr     r1, [r0, #4]
    ldr     r0, [r0, #0]
1:
    PIXEL888 \packed
    PIXEL888 \packed
    PIXEL888 \packed
    PIXEL888 \packed
    PIXEL888 \packed
    PIXEL888 \packed
    PIXEL888 \packed
    PIXEL888 \packed
    ldr     r9, [sp, #0]
    cmp     r0, r9
    bne     1b
    add     sp, sp, #12
    pop     {{r4-r11, pc}}
    .size \name, . - \name
.endm

    RUN888 specpoly_rgb888_xrgb_run, 0
    RUN888 specpoly_rgb888_packed_run, 1
"#
));

extern "C" {
    fn specpoly_rgb888_xrgb_run(run: *const Run);
    fn specpoly_rgb888_packed_run(run: *const Run);
}

/// The code tables of `t`'s curves (what `firmware/build.rs` bakes for an RGB888 transform).
pub fn codes(t: &PixelTransform) -> Codes {
    let curve = &t.tables().curve;
    let mut out = [[0u8; LEN]; 3];
    for (o, c) in out.iter_mut().zip(curve.iter()) {
        for (o, l) in o.iter_mut().zip(c.iter()) {
            *o = (l.saturating_add(128) >> 8) as u8;
        }
    }
    out
}

/// The kernel for one transform: RGB888 (8-8-8 bits) with [`GamutMap::Clip`], no dither.
pub struct Rgb888Kernel<'t> {
    t: &'t PixelTransform,
    codes: &'t Codes,
    m01: [u32; 3],
    m2rg: u32,
    m2b: u32,
}

/// `lo | hi << 16` of two i16.
fn pack(lo: i16, hi: i16) -> u32 {
    lo as u16 as u32 | (hi as u16 as u32) << 16
}

impl<'t> Rgb888Kernel<'t> {
    /// The kernel of `t` with its code tables `codes`; `None` unless `t` makes RGB888 codes with
    /// [`GamutMap::Clip`] and `codes` are `t`'s rounded levels ([`codes`]; checked here, 3 450
    /// entries once).
    pub fn new(t: &'t PixelTransform, codes: &'t Codes) -> Option<Self> {
        let tab = t.tables();
        if tab.bits != [8, 8, 8] || tab.map != GamutMap::Clip {
            return None;
        }
        let ok = tab.curve.iter().zip(codes.iter()).all(|(l, c)| {
            l.iter()
                .zip(c.iter())
                .all(|(l, c)| (l.saturating_add(128) >> 8) as u8 == *c)
        });
        if !ok {
            return None;
        }
        let m = tab.matrix;
        Some(Self {
            t,
            codes,
            m01: [0, 1, 2].map(|c| pack(m[c][0], m[c][1])),
            m2rg: pack(m[0][2], m[1][2]),
            m2b: pack(m[2][2], 0),
        })
    }

    /// `dst[i]` = the XRGB8888 word (`0x00RRGGBB`) of `src[i]`. The assembly runs over the
    /// largest multiple of 8 pixels, the rest goes through the portable transform. Panics if
    /// the lengths differ.
    pub fn xrgb(&self, src: &[[u8; 3]], dst: &mut [u32]) {
        assert_eq!(src.len(), dst.len(), "source and destination");
        let n = src.len() & !7;
        if n > 0 {
            // SAFETY: as in `run`; `dst` holds `n` u32 (4 bytes each), written as such
            unsafe { self.run(&src[..n], dst.as_mut_ptr().cast(), false) };
        }
        for (s, d) in src[n..].iter().zip(dst[n..].iter_mut()) {
            let c = self.t.apply(*s, 128);
            *d = (c[0] as u32) << 16 | (c[1] as u32) << 8 | c[2] as u32;
        }
    }

    /// `dst[3i..3i + 3]` = the R, G, B codes of `src[i]` (packed RGB888). As [`Self::xrgb`];
    /// panics unless `dst` has 3 bytes per source pixel.
    pub fn packed(&self, src: &[[u8; 3]], dst: &mut [u8]) {
        assert_eq!(3 * src.len(), dst.len(), "3 bytes per pixel");
        let n = src.len() & !7;
        if n > 0 {
            // SAFETY: as in `run`; `dst` holds `3n` bytes
            unsafe { self.run(&src[..n], dst.as_mut_ptr(), true) };
        }
        for (s, d) in src[n..].iter().zip(dst[3 * n..].chunks_exact_mut(3)) {
            d.copy_from_slice(&self.t.apply(*s, 128));
        }
    }

    /// Runs the assembly over `src` (a non-zero multiple of 8 pixels).
    ///
    /// # Safety
    /// `dst` must be valid for writes of `src.len()` pixels: 4 bytes each (aligned to 4) unless
    /// `packed`, else 3.
    unsafe fn run(&self, src: &[[u8; 3]], dst: *mut u8, packed: bool) {
        debug_assert!(!src.is_empty() && src.len().is_multiple_of(8));
        let tab = self.t.tables();
        let range = src.as_ptr_range();
        let run = Run {
            src: range.start.cast(),
            dst,
            end: range.end.cast(),
            decode: tab.decode.as_ptr(),
            codes: [
                self.codes[0].as_ptr(),
                self.codes[1].as_ptr(),
                self.codes[2].as_ptr(),
            ],
            m01: self.m01,
            m2rg: self.m2rg,
            m2b: self.m2b,
        };
        // SAFETY: the assembly reads `src` 8 pixels per turn up to `end` (a multiple of 8
        // pixels away, so it stops there) and writes as many pixels to `dst` (the caller's
        // promise); it reads the decode table at code values (0‥255 < 256 entries) and each
        // code table at indices ≤ 127 + 511 + 511 = `LEN − 1` (`usat` bounds every term), all
        // borrowed for the call. It restores the callee-saved registers and `sp` (AAPCS) and
        // touches no other memory than its own 12 bytes of stack.
        unsafe {
            if packed {
                specpoly_rgb888_packed_run(&run)
            } else {
                specpoly_rgb888_xrgb_run(&run)
            }
        }
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
