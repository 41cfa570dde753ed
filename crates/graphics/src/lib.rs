//! # specpoly-graphics
//!
//! An [`embedded-graphics`](https://docs.rs/embedded-graphics) [`DrawTarget`] that
//! colour-manages every pixel drawn to a panel: the UI draws in 8-bit sRGB (or Display P3, or
//! linear — whatever the transform was built for) as [`Rgb888`], and [`Calibrated`] sends the
//! calibrated panel codes (RGB565, RGB666 or RGB888, Bayer-dithered) to the panel's own
//! `DrawTarget` (a `mipidsi` display, a framebuffer):
//!
//! ```
//! # use embedded_graphics::{mock_display::MockDisplay, pixelcolor::{Rgb565, Rgb888}, prelude::*,
//! #     primitives::{PrimitiveStyle, Rectangle}};
//! # use specpoly_core::pixel::{Options, PanelTransform};
//! # use specpoly_graphics::Calibrated;
//! # let transform = PanelTransform::new(&specpoly_core::Display::srgb(),
//! #     Options { bits: Options::RGB565, ..Options::default() }).unwrap();
//! # let mut panel = MockDisplay::<Rgb565>::new();
//! let mut display = Calibrated::new(&mut panel, &transform)?; // the one line
//! Rectangle::new(Point::new(0, 0), Size::new(16, 8))
//!     .into_styled(PrimitiveStyle::with_fill(Rgb888::new(200, 120, 40)))
//!     .draw(&mut display)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! The transform ([`specpoly_core::pixel`]) is built once from the panel's calibration, on the
//! host (`specpoly calibrate export --format rust`) or on the device. A solid fill transforms its
//! colour once and only dithers per pixel.
//!
//! A separate crate rather than a feature of `specpoly-core`: the core stays free of UI
//! dependencies, and the workspace's plain `cargo test`/`clippy` build, lint and test the adapter
//! without feature flags; it is as `no_std` and allocation-free as the core.
#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

use core::marker::PhantomData;
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Dimensions, Point};
use embedded_graphics_core::pixelcolor::{Rgb565, Rgb666, Rgb888, RgbColor};
use embedded_graphics_core::primitives::Rectangle;
use embedded_graphics_core::Pixel;
use specpoly_core::pixel::{Dither, PixelMap};

/// A panel colour type: built from per-channel codes at its bit depth.
pub trait PanelColor: RgbColor {
    /// Bits per channel, R G B.
    const BITS: [u8; 3];
    /// The colour of codes `0..2^bits` per channel.
    fn from_codes(c: [u8; 3]) -> Self;
}

impl PanelColor for Rgb565 {
    const BITS: [u8; 3] = [5, 6, 5];
    #[inline(always)]
    fn from_codes(c: [u8; 3]) -> Self {
        Rgb565::new(c[0], c[1], c[2])
    }
}

impl PanelColor for Rgb666 {
    const BITS: [u8; 3] = [6, 6, 6];
    #[inline(always)]
    fn from_codes(c: [u8; 3]) -> Self {
        Rgb666::new(c[0], c[1], c[2])
    }
}

impl PanelColor for Rgb888 {
    const BITS: [u8; 3] = [8, 8, 8];
    #[inline(always)]
    fn from_codes(c: [u8; 3]) -> Self {
        Rgb888::new(c[0], c[1], c[2])
    }
}

/// The transform was built for other bits per channel than the panel's colour type has.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BitsMismatch {
    /// The transform's bits.
    pub transform: [u8; 3],
    /// The panel colour's bits.
    pub panel: [u8; 3],
}

impl core::fmt::Display for BitsMismatch {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "the transform makes {:?}-bit codes, the panel takes {:?}",
            self.transform, self.panel
        )
    }
}

impl core::error::Error for BitsMismatch {}

/// A colour-managed [`DrawTarget`] over the panel's `D`, with the pixel map `T`. Borrows the
/// panel, as `embedded-graphics`' own adapters (`translated`, `color_converted`) do.
pub struct Calibrated<'t, D, T> {
    inner: &'t mut D,
    map: &'t T,
    dither: Dither,
}

impl<'t, D, T> Calibrated<'t, D, T>
where
    D: DrawTarget,
    D::Color: PanelColor,
    T: PixelMap,
{
    /// Wraps `inner` (ordered dithering); fails if `map` was built for other bits per channel.
    pub fn new(inner: &'t mut D, map: &'t T) -> Result<Self, BitsMismatch> {
        let (transform, panel) = (map.bits(), D::Color::BITS);
        if transform != panel {
            return Err(BitsMismatch { transform, panel });
        }
        Ok(Self {
            inner,
            map,
            dither: Dither::Ordered,
        })
    }

    /// The same, with the given dithering.
    pub fn with_dither(mut self, dither: Dither) -> Self {
        self.dither = dither;
        self
    }

    /// The panel's draw target.
    pub fn inner(&self) -> &D {
        self.inner
    }

    /// The panel's draw target, mutably.
    pub fn inner_mut(&mut self) -> &mut D {
        self.inner
    }

    /// The panel colour of source colour `c` at `p`.
    #[inline(always)]
    pub fn convert(&self, c: Rgb888, p: Point) -> D::Color {
        convert(self.map, self.dither, c, p)
    }
}

#[inline(always)]
fn codes(levels: [u16; 3], t: u16) -> [u8; 3] {
    [
        ((levels[0] + t) >> 8) as u8,
        ((levels[1] + t) >> 8) as u8,
        ((levels[2] + t) >> 8) as u8,
    ]
}

#[inline(always)]
fn convert<C: PanelColor, T: PixelMap>(map: &T, dither: Dither, c: Rgb888, p: Point) -> C {
    let levels = map.levels_for([c.r(), c.g(), c.b()], C::BITS);
    C::from_codes(codes(levels, dither.threshold(p.x as u32, p.y as u32)))
}

impl<D, T> Dimensions for Calibrated<'_, D, T>
where
    D: DrawTarget,
{
    fn bounding_box(&self) -> Rectangle {
        self.inner.bounding_box()
    }
}

/// The source colours of `area` (row by row, the order of `fill_contiguous`), colour-managed: a
/// column counter and the row's eight thresholds instead of a `Point` per pixel, so the per-pixel
/// work is the transform, one add per channel and the pack.
struct Managed<'t, T, I, C> {
    map: &'t T,
    dither: Dither,
    colors: I,
    /// `area`'s left edge and width.
    x0: i32,
    width: u32,
    /// The column within the row, and the row (absolute).
    x: u32,
    y: i32,
    row: [u16; 8],
    colour: PhantomData<fn() -> C>,
}

impl<'t, T: PixelMap, I, C> Managed<'t, T, I, C> {
    fn new(map: &'t T, dither: Dither, area: &Rectangle, colors: I) -> Self {
        let (x0, y) = (area.top_left.x, area.top_left.y);
        Self {
            map,
            dither,
            colors,
            x0,
            width: area.size.width,
            x: 0,
            y,
            row: row_thresholds(dither, x0, y),
            colour: PhantomData,
        }
    }

    /// The threshold of the next pixel, advancing the column (and the row at its end).
    #[inline(always)]
    fn threshold(&mut self) -> u16 {
        let t = self.row[self.x as usize & 7];
        self.x += 1;
        if self.x == self.width {
            self.x = 0;
            self.y += 1;
            self.row = row_thresholds(self.dither, self.x0, self.y);
        }
        t
    }
}

/// The thresholds of row `y` for columns `x0, x0 + 1, …, x0 + 7` (so column `x` uses `[x & 7]`
/// counted from `x0`).
fn row_thresholds(dither: Dither, x0: i32, y: i32) -> [u16; 8] {
    core::array::from_fn(|i| dither.threshold((x0 + i as i32) as u32, y as u32))
}

impl<T, I, C> Iterator for Managed<'_, T, I, C>
where
    T: PixelMap,
    I: Iterator<Item = Rgb888>,
    C: PanelColor,
{
    type Item = C;

    #[inline]
    fn next(&mut self) -> Option<C> {
        let c = self.colors.next()?;
        let t = self.threshold();
        Some(C::from_codes(codes(
            self.map.levels_for([c.r(), c.g(), c.b()], C::BITS),
            t,
        )))
    }
}

/// A flat colour over `area`, dithered: the eight codes of each row computed once per row.
struct Pattern<C> {
    levels: [u16; 3],
    dither: Dither,
    x0: i32,
    width: u32,
    x: u32,
    y: i32,
    left: u32,
    row: [C; 8],
}

impl<C: PanelColor> Pattern<C> {
    fn new(levels: [u16; 3], dither: Dither, area: &Rectangle) -> Self {
        let (x0, y) = (area.top_left.x, area.top_left.y);
        Self {
            levels,
            dither,
            x0,
            width: area.size.width,
            x: 0,
            y,
            left: area.size.width * area.size.height,
            row: Self::row(levels, dither, x0, y),
        }
    }

    fn row(levels: [u16; 3], dither: Dither, x0: i32, y: i32) -> [C; 8] {
        row_thresholds(dither, x0, y).map(|t| C::from_codes(codes(levels, t)))
    }
}

impl<C: PanelColor> Iterator for Pattern<C> {
    type Item = C;

    #[inline(always)]
    fn next(&mut self) -> Option<C> {
        if self.left == 0 {
            return None;
        }
        self.left -= 1;
        let c = self.row[self.x as usize & 7];
        self.x += 1;
        if self.x == self.width {
            self.x = 0;
            self.y += 1;
            self.row = Self::row(self.levels, self.dither, self.x0, self.y);
        }
        Some(c)
    }
}

impl<D, T> DrawTarget for Calibrated<'_, D, T>
where
    D: DrawTarget,
    D::Color: PanelColor,
    T: PixelMap,
{
    type Color = Rgb888;
    type Error = D::Error;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<Self::Color>>,
    {
        let (map, dither) = (self.map, self.dither);
        self.inner.draw_iter(
            pixels
                .into_iter()
                .map(|Pixel(p, c)| Pixel(p, convert(map, dither, c, p))),
        )
    }

    fn fill_contiguous<I>(&mut self, area: &Rectangle, colors: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Self::Color>,
    {
        if area.is_zero_sized() {
            return Ok(());
        }
        let mapped =
            Managed::<_, _, D::Color>::new(self.map, self.dither, area, colors.into_iter());
        self.inner.fill_contiguous(area, mapped)
    }

    fn fill_solid(&mut self, area: &Rectangle, color: Self::Color) -> Result<(), Self::Error> {
        let levels = self
            .map
            .levels_for([color.r(), color.g(), color.b()], D::Color::BITS);
        match self.dither {
            Dither::None => self
                .inner
                .fill_solid(area, D::Color::from_codes(codes(levels, 128))),
            _ if area.is_zero_sized() => Ok(()),
            dither => self
                .inner
                .fill_contiguous(area, Pattern::<D::Color>::new(levels, dither, area)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics::image::{Image, ImageRaw};
    use embedded_graphics::mock_display::MockDisplay;
    use embedded_graphics::prelude::*;
    use embedded_graphics::primitives::{Circle, PrimitiveStyle, Rectangle};
    use specpoly_core::display::{Display, Transfer};
    use specpoly_core::pixel::{Options, PanelTransform, Source};

    fn panel() -> Display {
        Display::from_primaries_white(
            [[0.62, 0.34], [0.32, 0.57], [0.15, 0.08]],
            [0.30, 0.32],
            300.0,
            [
                Transfer::Gamma(2.4),
                Transfer::Gamma(2.3),
                Transfer::Gamma(2.5),
            ],
        )
        .unwrap()
    }

    fn transform(bits: [u8; 3]) -> PanelTransform {
        let opts = Options {
            bits,
            source: Source::Srgb,
            ..Options::default()
        };
        PanelTransform::new(&panel(), opts).unwrap()
    }

    /// What the panel must hold at `p` for source colour `c`: the transform's codes, dithered.
    fn want<C: PanelColor>(t: &PanelTransform, c: Rgb888, p: Point, dither: Dither) -> C {
        let code = t.apply(
            [c.r(), c.g(), c.b()],
            dither.threshold(p.x as u32, p.y as u32),
        );
        C::from_codes(code)
    }

    fn check<C: PanelColor + core::fmt::Debug>(
        mock: &MockDisplay<C>,
        t: &PanelTransform,
        source: impl Fn(Point) -> Option<Rgb888>,
        dither: Dither,
    ) {
        let mut drawn = 0;
        for y in 0..64 {
            for x in 0..64 {
                let p = Point::new(x, y);
                let got = mock.get_pixel(p);
                match source(p) {
                    Some(c) => {
                        assert_eq!(got, Some(want::<C>(t, c, p, dither)), "{p:?}");
                        drawn += 1;
                    }
                    None => assert_eq!(got, None, "{p:?} drawn"),
                }
            }
        }
        assert!(drawn > 0);
    }

    #[test]
    fn solid_fills_are_managed_and_dithered() {
        let t = transform(Options::RGB565);
        let colour = Rgb888::new(200, 120, 40);
        let area = Rectangle::new(Point::new(3, 5), Size::new(20, 11));
        for dither in [Dither::Ordered, Dither::None] {
            let mut mock = MockDisplay::<Rgb565>::new();
            let mut d = Calibrated::new(&mut mock, &t).unwrap().with_dither(dither);
            area.into_styled(PrimitiveStyle::with_fill(colour))
                .draw(&mut d)
                .unwrap();
            check(&mock, &t, |p| area.contains(p).then_some(colour), dither);
        }
    }

    #[test]
    fn pixels_and_images_are_managed_per_pixel() {
        let t = transform(Options::RGB888);
        // an 8×4 image of distinct colours through fill_contiguous
        let mut data = [0u8; 8 * 4 * 3];
        for (i, px) in data.chunks_mut(3).enumerate() {
            px.copy_from_slice(&[(i * 8) as u8, 255 - (i * 7) as u8, (i * 5) as u8]);
        }
        let raw = ImageRaw::<Rgb888>::new(&data, 8);
        let at = Point::new(10, 20);
        let mut mock = MockDisplay::<Rgb888>::new();
        let mut d = Calibrated::new(&mut mock, &t).unwrap();
        Image::new(&raw, at).draw(&mut d).unwrap();
        let src = |p: Point| {
            let q = p - at;
            ((0..8).contains(&q.x) && (0..4).contains(&q.y)).then(|| {
                let i = (q.y * 8 + q.x) as usize * 3;
                Rgb888::new(data[i], data[i + 1], data[i + 2])
            })
        };
        check(&mock, &t, src, Dither::Ordered);

        // single pixels through draw_iter (a circle's outline)
        let mut mock = MockDisplay::<Rgb888>::new();
        let mut d = Calibrated::new(&mut mock, &t).unwrap();
        let colour = Rgb888::new(30, 200, 90);
        let circle = Circle::new(Point::new(5, 5), 30);
        circle
            .into_styled(PrimitiveStyle::with_stroke(colour, 1))
            .draw(&mut d)
            .unwrap();
        let mut plain = MockDisplay::<Rgb888>::new();
        circle
            .into_styled(PrimitiveStyle::with_stroke(colour, 1))
            .draw(&mut plain)
            .unwrap();
        check(
            &mock,
            &t,
            |p| plain.get_pixel(p).map(|_| colour),
            Dither::Ordered,
        );
    }

    #[test]
    fn wrong_bits_are_refused() {
        let t = transform(Options::RGB888);
        let mut mock = MockDisplay::<Rgb565>::new();
        assert_eq!(
            Calibrated::new(&mut mock, &t).err(),
            Some(BitsMismatch {
                transform: [8, 8, 8],
                panel: [5, 6, 5]
            })
        );
    }

    #[test]
    fn the_panel_sees_its_own_colours_not_the_sources() {
        // sRGB red on a narrower panel: clipped to the panel's red, greens and blues at 0
        let t = transform(Options::RGB888);
        let mut mock = MockDisplay::<Rgb888>::new();
        let mut d = Calibrated::new(&mut mock, &t)
            .unwrap()
            .with_dither(Dither::None);
        Pixel(Point::new(1, 1), Rgb888::new(128, 128, 128))
            .draw(&mut d)
            .unwrap();
        Pixel(Point::new(2, 1), Rgb888::WHITE).draw(&mut d).unwrap();
        assert_eq!(mock.get_pixel(Point::new(2, 1)), Some(Rgb888::WHITE));
        let grey = mock.get_pixel(Point::new(1, 1)).unwrap();
        // a gamma-2.3–2.5 panel needs other codes than sRGB's 128 for sRGB's mid grey
        assert_ne!(grey, Rgb888::new(128, 128, 128));
    }
}
