//! The calibrated framebuffer demo, under QEMU with semihosting: a 240×240 RGB565 framebuffer in
//! RAM, filled from an sRGB UI through `specpoly_graphics::Calibrated` (the `embedded-graphics`
//! adapter) with the demo panel's transform baked into flash by `build.rs`; and the same panel in
//! RGB888 through the RGB888 kernel (`boards::mps2::rgb888`, XRGB8888 words and packed bytes). Exits 0
//! when its checks pass. Prints, for `tests/tests/firmware_framebuffer.rs` and docs/performance.md:
//!
//! - `panel …`: the demo panel (primaries, white, gammas), for the host's f64 reference;
//! - `tables BYTES`: the transform's tables in flash;
//! - `px X Y R G B CODE`: sampled pixels of the gradient frame (source sRGB, RGB565 code);
//! - `block R G B C0 … C63`: flat 8×8 blocks (fill_solid), their 64 codes in hex;
//! - `checksum HEX`: FNV-1a of the whole gradient frame;
//! - `px888 X Y R G B XRGB` and `checksum888 HEX`: the same for the RGB888 kernel
//!   (`boards::mps2::rgb888`, the panel in RGB888, no dither; XRGB8888 words, FNV-1a of their LE bytes);
//! - `insns WHAT PER_PIXEL_×100`: instructions per pixel (under `-icount shift=0`);
//! - `check NAME ok|FAIL`, `framebuffer: pass|fail`.
#![no_std]
#![no_main]
#![deny(unsafe_code)]

use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprint, hprintln};
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Dimensions, OriginDimensions, Point, Size};
use embedded_graphics_core::pixelcolor::{IntoStorage, Rgb565, Rgb888};
use embedded_graphics_core::primitives::{PointsIter, Rectangle};
use embedded_graphics_core::Pixel;
use specpoly_firmware::boards::mps2::icount::Counter;
use specpoly_firmware::boards::mps2::rgb565::Rgb565Kernel;
use specpoly_firmware::boards::mps2::rgb888::Rgb888Kernel;
use specpoly_graphics::Calibrated;

include!(concat!(env!("OUT_DIR"), "/framebuffer_panel.rs"));

const W: usize = 240;
const H: usize = 240;
const PIXELS: usize = W * H;

/// An RGB565 framebuffer in RAM (what an SPI panel's driver would then send out).
struct Framebuffer {
    px: [u16; PIXELS],
}

impl OriginDimensions for Framebuffer {
    fn size(&self) -> Size {
        Size::new(W as u32, H as u32)
    }
}

impl DrawTarget for Framebuffer {
    type Color = Rgb565;
    type Error = core::convert::Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<Self::Color>>,
    {
        for Pixel(p, c) in pixels {
            if (0..W as i32).contains(&p.x) && (0..H as i32).contains(&p.y) {
                self.px[p.y as usize * W + p.x as usize] = c.into_storage();
            }
        }
        Ok(())
    }

    fn fill_contiguous<I>(&mut self, area: &Rectangle, colors: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Self::Color>,
    {
        if area.intersection(&self.bounding_box()) != *area {
            return self.draw_iter(area.points().zip(colors).map(|(p, c)| Pixel(p, c)));
        }
        let (x0, y0) = (area.top_left.x as usize, area.top_left.y as usize);
        let w = area.size.width as usize;
        let mut colors = colors.into_iter();
        for y in y0..y0 + area.size.height as usize {
            for (dst, c) in self.px[y * W + x0..y * W + x0 + w]
                .iter_mut()
                .zip(&mut colors)
            {
                *dst = c.into_storage();
            }
        }
        Ok(())
    }
}

/// The UI's picture: an sRGB gradient (red along x, green along y, blue along the diagonal).
fn source(x: usize, y: usize) -> [u8; 3] {
    [
        (x * 255 / (W - 1)) as u8,
        (y * 255 / (H - 1)) as u8,
        ((x + y) * 255 / (W + H - 2)) as u8,
    ]
}

fn fnv1a(px: &[u16]) -> u32 {
    let mut h = 0x811c_9dc5u32;
    for v in px {
        for b in v.to_le_bytes() {
            h = (h ^ b as u32).wrapping_mul(0x0100_0193);
        }
    }
    h
}

/// Solid colours drawn as 8×8 blocks (checked by the host against the f64 reference).
const BLOCKS: [[u8; 3]; 8] = [
    [128, 128, 128],
    [200, 120, 40],
    [30, 60, 200],
    [250, 240, 230],
    [20, 20, 20],
    [90, 200, 90],
    [255, 0, 0],
    [5, 10, 7],
];

/// The per-pixel path without `embedded-graphics`, in portable Rust: transform, Bayer threshold,
/// pack, store.
#[inline(never)]
fn kernel_portable(src: &[[u8; 3]; PIXELS], dst: &mut [u16; PIXELS]) {
    for (y, (s, d)) in src.chunks_exact(W).zip(dst.chunks_exact_mut(W)).enumerate() {
        let b = &specpoly_core::pixel::dither::BAYER8[y & 7];
        let thresholds: [u16; 8] = core::array::from_fn(|i| b[i] as u16 * 4 + 2);
        for (x, (s, d)) in s.iter().zip(d.iter_mut()).enumerate() {
            let t = thresholds[x & 7];
            let c = PANEL.apply(*s, t);
            *d = (c[0] as u16) << 11 | (c[1] as u16) << 5 | c[2] as u16;
        }
    }
}

/// The same in the assembly kernel (`boards::mps2::rgb565`), the whole frame in one call.
#[inline(never)]
fn kernel(k: &Rgb565Kernel, src: &[[u8; 3]; PIXELS], dst: &mut [u16; PIXELS]) {
    k.rows(src, dst, W, 0);
}

/// The RGB888 per-pixel path in portable Rust: transform, rounding (threshold 128), XRGB8888.
#[inline(never)]
fn kernel888_portable(src: &[[u8; 3]; PIXELS], dst: &mut [u32; PIXELS]) {
    for (s, d) in src.iter().zip(dst.iter_mut()) {
        let c = PANEL888.apply(*s, 128);
        *d = (c[0] as u32) << 16 | (c[1] as u32) << 8 | c[2] as u32;
    }
}

/// The RGB888 assembly kernel (`boards::mps2::rgb888`), XRGB8888 words, the whole frame in one call.
#[inline(never)]
fn kernel888(k: &Rgb888Kernel, src: &[[u8; 3]; PIXELS], dst: &mut [u32; PIXELS]) {
    k.xrgb(src, dst);
}

/// The same, packed RGB888 (3 bytes per pixel).
#[inline(never)]
fn kernel888_packed(k: &Rgb888Kernel, src: &[[u8; 3]; PIXELS], dst: &mut [u8; 3 * PIXELS]) {
    k.packed(src, dst);
}

/// Pixels where the XRGB words, the packed bytes and the portable words all agree.
fn same888(xrgb: &[u32], packed: &[u8], portable: &[u32]) -> usize {
    xrgb.iter()
        .zip(packed.chunks_exact(3))
        .zip(portable.iter())
        .filter(|((w, b), p)| {
            *w == *p && (b[0] as u32) << 16 | (b[1] as u32) << 8 | b[2] as u32 == **p
        })
        .count()
}

fn fnv1a32(px: &[u32]) -> u32 {
    let mut h = 0x811c_9dc5u32;
    for v in px {
        for b in v.to_le_bytes() {
            h = (h ^ b as u32).wrapping_mul(0x0100_0193);
        }
    }
    h
}

/// The transform alone (levels, no dither or store), folded into a checksum.
#[inline(never)]
fn levels_only(src: &[[u8; 3]; PIXELS]) -> u32 {
    let mut acc = 0u32;
    for s in src.iter() {
        let l = PANEL.levels(*s);
        acc = acc.wrapping_add(l[0] as u32 ^ (l[1] as u32) << 8 ^ (l[2] as u32) << 16);
    }
    acc
}

#[entry]
fn main() -> ! {
    let mut failed = 0u32;
    let mut check = |name: &str, ok: bool| {
        hprintln!("check {} {}", name, if ok { "ok" } else { "FAIL" });
        if !ok {
            failed += 1;
        }
    };
    let Some(p) = cortex_m::Peripherals::take() else {
        hprintln!("framebuffer: no peripherals");
        debug::exit(debug::EXIT_FAILURE);
        loop {
            cortex_m::asm::wfi();
        }
    };
    let mut counter = Counter::new(p.SYST);
    hprintln!("{}", PANEL_DESC);
    hprintln!(
        "tables {}",
        specpoly_core::pixel::PanelTransform::TABLE_BYTES
    );

    let mut src = [[0u8; 3]; PIXELS];
    for y in 0..H {
        for x in 0..W {
            src[y * W + x] = source(x, y);
        }
    }
    let mut fb = Framebuffer { px: [0; PIXELS] };
    let all = Rectangle::new(Point::zero(), Size::new(W as u32, H as u32));

    // 1. the kernel alone: transform, dither, pack, store; in assembly, then in portable Rust
    let Some(asm) = Rgb565Kernel::new(&PANEL) else {
        hprintln!("framebuffer: the panel's transform is not RGB565 with clip");
        debug::exit(debug::EXIT_FAILURE);
        loop {
            cortex_m::asm::wfi();
        }
    };
    let insns = counter.insns_per_call(1, || kernel(&asm, &src, &mut fb.px));
    hprintln!("insns kernel {}", insns * 100 / PIXELS as u64);
    let kernel_sum = fnv1a(&fb.px);
    let asm_frame = fb.px;
    // a band of rows starting at y = 3 (thresholds by absolute row) equals those rows of the frame
    let mut band = [0u16; 8 * W];
    asm.rows(&src[3 * W..11 * W], &mut band, W, 3);
    check("asm-band-rows", band[..] == asm_frame[3 * W..11 * W]);
    fb.px.fill(0);
    let insns = counter.insns_per_call(1, || kernel_portable(&src, &mut fb.px));
    hprintln!("insns kernel-portable {}", insns * 100 / PIXELS as u64);
    let same = asm_frame
        .iter()
        .zip(fb.px.iter())
        .filter(|(a, b)| a == b)
        .count();
    hprintln!("asm-equals-portable {} of {}", same, PIXELS);
    check("asm-equals-portable", same == PIXELS);
    // and on a frame of random colours (xorshift32): code values all over, in and out of gamut
    let mut noise = [[0u8; 3]; PIXELS];
    let mut s = 0x2545_f491u32;
    for px in noise.iter_mut() {
        s ^= s << 13;
        s ^= s >> 17;
        s ^= s << 5;
        *px = [s as u8, (s >> 8) as u8, (s >> 16) as u8];
    }
    kernel(&asm, &noise, &mut fb.px);
    let asm_noise = fb.px;
    kernel_portable(&noise, &mut fb.px);
    let same = asm_noise
        .iter()
        .zip(fb.px.iter())
        .filter(|(a, b)| a == b)
        .count();
    hprintln!("asm-equals-portable-random {} of {}", same, PIXELS);
    check("asm-equals-portable-random", same == PIXELS);
    // rows an odd number of 8-pixel groups wide (the loop does 16 pixels a turn and starts such
    // a row halfway): 9 rows of 24 and 5 rows of 40 random pixels from y = 5, against the
    // portable transform pixel by pixel
    let mut odd_ok = true;
    for (w, rows) in [(24usize, 9usize), (40, 5)] {
        let n = w * rows;
        let mut out = [0u16; 216];
        asm.rows(&noise[..n], &mut out[..n], w, 5);
        for (i, (s, o)) in noise[..n].iter().zip(&out[..n]).enumerate() {
            let t =
                specpoly_core::pixel::dither::BAYER8[(5 + i / w) & 7][(i % w) & 7] as u16 * 4 + 2;
            let c = PANEL.apply(*s, t);
            odd_ok &= *o == (c[0] as u16) << 11 | (c[1] as u16) << 5 | c[2] as u16;
        }
    }
    check("asm-odd-groups", odd_ok);

    // 1b. the panel in RGB888 (no dither): the assembly kernel's XRGB8888 words and packed
    // bytes against the portable transform, on the gradient and on the random frame
    let Some(k888) = Rgb888Kernel::new(&PANEL888, &PANEL888_CODES) else {
        hprintln!("framebuffer: PANEL888 is not RGB888 with clip, or its codes differ");
        debug::exit(debug::EXIT_FAILURE);
        loop {
            cortex_m::asm::wfi();
        }
    };
    let mut xrgb = [0u32; PIXELS];
    let mut packed = [0u8; 3 * PIXELS];
    let mut portable = [0u32; PIXELS];
    let insns = counter.insns_per_call(1, || kernel888(&k888, &src, &mut xrgb));
    hprintln!("insns kernel888-xrgb {}", insns * 100 / PIXELS as u64);
    let insns = counter.insns_per_call(1, || kernel888_packed(&k888, &src, &mut packed));
    hprintln!("insns kernel888-packed {}", insns * 100 / PIXELS as u64);
    let insns = counter.insns_per_call(1, || kernel888_portable(&src, &mut portable));
    hprintln!("insns kernel888-portable {}", insns * 100 / PIXELS as u64);
    let same = same888(&xrgb, &packed, &portable);
    hprintln!("asm888-equals-portable {} of {}", same, PIXELS);
    check("asm888-equals-portable", same == PIXELS);
    hprintln!("checksum888 {:08x}", fnv1a32(&xrgb));
    for y in (0..H).step_by(17) {
        for x in (0..W).step_by(13) {
            let s = src[y * W + x];
            hprintln!(
                "px888 {} {} {} {} {} {}",
                x,
                y,
                s[0],
                s[1],
                s[2],
                xrgb[y * W + x]
            );
        }
    }
    // a run that is not a multiple of 8 (the tail in portable code) and starts off the frame's
    // 8-pixel grid
    let mut tail = [0u32; 13];
    k888.xrgb(&noise[5..18], &mut tail);
    kernel888(&k888, &noise, &mut xrgb);
    k888.packed(&noise, &mut packed);
    kernel888_portable(&noise, &mut portable);
    let same = same888(&xrgb, &packed, &portable);
    hprintln!("asm888-equals-portable-random {} of {}", same, PIXELS);
    check(
        "asm888-equals-portable-random",
        same == PIXELS && tail[..] == portable[5..18],
    );
    check(
        "white-and-black-888",
        PANEL888.apply([255; 3], 128) == [255; 3] && PANEL888.apply([0; 3], 128) == [0; 3],
    );

    let mut acc = 0;
    let insns = counter.insns_per_call(1, || acc = levels_only(core::hint::black_box(&src)));
    hprintln!(
        "insns levels {} (sum {:x})",
        insns * 100 / PIXELS as u64,
        acc
    );

    // 2. the same frame through the embedded-graphics adapter (fill_contiguous)
    fb.px.fill(0);
    let insns = counter.insns_per_call(1, || {
        let mut d = Calibrated::new(&mut fb, &PANEL).unwrap_or_else(|_| panic!("bits"));
        let colours = src.iter().map(|c| Rgb888::new(c[0], c[1], c[2]));
        let _ = d.fill_contiguous(&all, core::hint::black_box(colours));
    });
    hprintln!("insns adapter-image {}", insns * 100 / PIXELS as u64);
    let checksum = fnv1a(&fb.px);
    hprintln!("checksum {:08x}", checksum);
    check("adapter-equals-kernel", checksum == kernel_sum);
    for y in (0..H).step_by(17) {
        for x in (0..W).step_by(13) {
            let s = src[y * W + x];
            hprintln!(
                "px {} {} {} {} {} {}",
                x,
                y,
                s[0],
                s[1],
                s[2],
                fb.px[y * W + x]
            );
        }
    }

    // 3. the same frame with no colour management (RGB888 → RGB565 by truncation): the baseline
    let insns = counter.insns_per_call(1, || {
        let colours = src
            .iter()
            .map(|c| Rgb565::new(c[0] >> 3, c[1] >> 2, c[2] >> 3));
        let _ = fb.fill_contiguous(&all, core::hint::black_box(colours));
    });
    hprintln!("insns unmanaged-image {}", insns * 100 / PIXELS as u64);

    // 4. solid fills: the colour transformed once, dithered per pixel
    let insns = counter.insns_per_call(1, || {
        let mut d = Calibrated::new(&mut fb, &PANEL).unwrap_or_else(|_| panic!("bits"));
        let _ = d.fill_solid(&all, core::hint::black_box(Rgb888::new(200, 120, 40)));
    });
    hprintln!("insns adapter-solid {}", insns * 100 / PIXELS as u64);
    {
        let mut d = Calibrated::new(&mut fb, &PANEL).unwrap_or_else(|_| panic!("bits"));
        for (i, c) in BLOCKS.iter().enumerate() {
            let area = Rectangle::new(Point::new(8 * i as i32, 0), Size::new(8, 8));
            let _ = d.fill_solid(&area, Rgb888::new(c[0], c[1], c[2]));
        }
    }
    for (i, c) in BLOCKS.iter().enumerate() {
        hprint!("block {} {} {}", c[0], c[1], c[2]);
        for y in 0..8 {
            for x in 0..8 {
                hprint!(" {:x}", fb.px[y * W + 8 * i + x]);
            }
        }
        hprintln!("");
    }
    check(
        "white-and-black",
        PANEL.apply([255; 3], 2) == [31, 63, 31] && PANEL.apply([0; 3], 254) == [0; 3],
    );

    if failed == 0 {
        hprintln!("framebuffer: pass");
        debug::exit(debug::EXIT_SUCCESS);
    } else {
        hprintln!("framebuffer: fail ({} checks)", failed);
        debug::exit(debug::EXIT_FAILURE);
    }
    loop {
        cortex_m::asm::wfi();
    }
}
