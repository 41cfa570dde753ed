//! The ANSI/IES TM-30-20 colour vector graphic (CVG), as SVG and PNG from one drawing routine.
//!
//! Drawn in the normalised a′b′ plane of TM-30 (each hue bin's means divided by its reference
//! radius, so the reference is the unit circle): the plane from −1.5 to 1.5 in both
//! directions, `b′` up. On a background of the 16 hue sectors tinted with the bins' colours:
//! the bin edges (dashed, from radius 0.15 to 1.5) and numbers (at radius 1.41), white circles
//! at 0.8, 0.9, 1.1, 1.2 (±10 %, ±20 % chroma), the reference circle (black, radius 1), the
//! test polygon through the 16 test points (red) and an arrow per bin from its reference point to
//! its test point in the bin's colour, then the labels in the corners. The layout and colours
//! follow the TM-30-20 graphic as colour-science 0.4.7 draws it
//! (`colour/plotting/tm3018/components.py`: bin arrow colours, test colour `#F05A4F`).
//!
//! Geometry a reader of the SVG can use: the reference circle is the only black `circle`,
//! centred on the origin of the plane, its `r` the pixels of one unit; arrow `j` is a `polyline`
//! (its shaft, from the reference point) and a `polygon` (its head, apex at the test point)
//! stroked/filled in [`ARROW_COLOURS`]`[j]`. Coordinates are whole pixels.

use crate::{register_font, Error, Result, FAMILY};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// The 16 bins' arrow colours (TM-30-20, as colour-science 0.4.7 lists them).
pub const ARROW_COLOURS: [[u8; 3]; 16] = [
    [0xE6, 0x28, 0x28],
    [0xE7, 0x4B, 0x4B],
    [0xFB, 0x81, 0x2E],
    [0xFF, 0xB5, 0x29],
    [0xCB, 0xCA, 0x46],
    [0x7E, 0xB9, 0x4C],
    [0x41, 0xC0, 0x6D],
    [0x00, 0x9C, 0x7C],
    [0x16, 0xBC, 0xB0],
    [0x00, 0xA4, 0xBF],
    [0x00, 0x85, 0xC3],
    [0x3B, 0x62, 0xAA],
    [0x45, 0x68, 0xAE],
    [0x6A, 0x4E, 0x85],
    [0x9D, 0x69, 0xA1],
    [0xA7, 0x4F, 0x81],
];

/// The 16 bins' bar colours (TM-30-20's bar charts, as colour-science 0.4.7 lists them).
pub const BAR_COLOURS: [[u8; 3]; 16] = [
    [0xA3, 0x5C, 0x60],
    [0xCC, 0x76, 0x5E],
    [0xCC, 0x81, 0x45],
    [0xD8, 0xAC, 0x62],
    [0xAC, 0x99, 0x59],
    [0x91, 0x9E, 0x5D],
    [0x66, 0x8B, 0x5E],
    [0x61, 0xB2, 0x90],
    [0x7B, 0xBA, 0xA6],
    [0x29, 0x7A, 0x7E],
    [0x55, 0x78, 0x8D],
    [0x70, 0x8A, 0xB2],
    [0x98, 0x8C, 0xAA],
    [0x73, 0x58, 0x77],
    [0x8F, 0x66, 0x82],
    [0xBA, 0x7A, 0x8E],
];

/// The test polygon's colour.
pub const TEST_COLOUR: [u8; 3] = [0xF0, 0x5A, 0x4F];

/// Half the side of the plane drawn, in normalised units.
pub const EXTENT: f64 = 1.5;

/// The smallest and largest side accepted, px.
pub const MIN_SIZE: u32 = 200;
/// See [`MIN_SIZE`].
pub const MAX_SIZE: u32 = 4000;

/// One arrow in pixels: the shaft's two ends, the head's three corners (apex first).
pub type Arrow = ([(i32, i32); 2], [(i32, i32); 3]);

/// A colour vector graphic: the 16 bins' normalised reference and test points.
#[derive(Clone, Debug, PartialEq)]
pub struct VectorGraphic {
    /// Side of the square image, px.
    pub size: u32,
    /// Reference points (on the unit circle), `[a′, b′]` per bin.
    pub reference: [[f64; 2]; 16],
    /// Test points, `[a′, b′]` per bin.
    pub test: [[f64; 2]; 16],
    /// Text in the top-left corner, one entry a line (e.g. `Rf 85`, `Rg 101`).
    pub top_left: Vec<String>,
    /// Text in the top-right corner (e.g. `CCT 4103 K`, `Duv 0.0011`).
    pub top_right: Vec<String>,
}

fn rgb(c: [u8; 3]) -> RGBColor {
    RGBColor(c[0], c[1], c[2])
}

/// `c` mixed with white, `k` of `c`.
fn tint(c: [u8; 3], k: f64) -> RGBColor {
    let m = |v: u8| (255.0 - k * (255.0 - v as f64)).round() as u8;
    RGBColor(m(c[0]), m(c[1]), m(c[2]))
}

impl VectorGraphic {
    /// Pixels of one normalised unit.
    pub fn scale(&self) -> f64 {
        0.5 * self.size as f64 / (EXTENT * 1.04)
    }

    /// The pixel of a normalised point (`b′` up), unrounded.
    pub fn pixel(&self, p: [f64; 2]) -> (f64, f64) {
        let c = 0.5 * self.size as f64;
        (c + p[0] * self.scale(), c - p[1] * self.scale())
    }

    fn px(&self, p: [f64; 2]) -> (i32, i32) {
        let (x, y) = self.pixel(p);
        (x.round() as i32, y.round() as i32)
    }

    /// An error unless the size is in range and every point finite.
    fn check(&self) -> Result<()> {
        if !(MIN_SIZE..=MAX_SIZE).contains(&self.size) {
            return Err(Error::Draw(format!(
                "a colour vector graphic is {MIN_SIZE} to {MAX_SIZE} px wide, not {}",
                self.size
            )));
        }
        if self
            .reference
            .iter()
            .chain(&self.test)
            .flatten()
            .any(|v| !v.is_finite())
        {
            return Err(Error::Draw(
                "a hue bin without samples: no colour vector graphic".into(),
            ));
        }
        Ok(())
    }

    /// The arrow of bin `j`: the shaft's two ends and the head's three corners (apex first),
    /// in pixels. The head is 4 % of the side long (at most 0.6 of the arrow), its base
    /// 0.8 of its length wide; the shaft stops inside the head.
    pub fn arrow(&self, j: usize) -> Arrow {
        let (x0, y0) = self.pixel(self.reference[j]);
        let (x1, y1) = self.pixel(self.test[j]);
        let (dx, dy) = (x1 - x0, y1 - y0);
        let len = dx.hypot(dy);
        let head = (0.04 * self.size as f64).min(0.6 * len);
        let (ux, uy) = if len > 0.0 {
            (dx / len, dy / len)
        } else {
            (0.0, 0.0)
        };
        let (bx, by) = (x1 - ux * head, y1 - uy * head);
        let w = 0.4 * head;
        let r = |x: f64, y: f64| (x.round() as i32, y.round() as i32);
        (
            [r(x0, y0), r(x1 - ux * 0.5 * head, y1 - uy * 0.5 * head)],
            [
                r(x1, y1),
                r(bx - uy * w, by + ux * w),
                r(bx + uy * w, by - ux * w),
            ],
        )
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        self.check()?;
        register_font();
        let fail = |e: DrawingAreaErrorKind<DB::ErrorType>| Error::Draw(e.to_string());
        root.fill(&WHITE).map_err(fail)?;
        let s = self.size as f64;
        let unit = self.scale();
        let polar = |r: f64, deg: f64| {
            let a = deg.to_radians();
            [r * a.cos(), r * a.sin()]
        };
        // hue sectors tinted with the bins' colours
        for (j, c) in BAR_COLOURS.iter().enumerate() {
            let mut pts = vec![self.px([0.0, 0.0])];
            for k in 0..=8 {
                pts.push(self.px(polar(EXTENT, 22.5 * (j as f64 + k as f64 / 8.0))));
            }
            root.draw(&Polygon::new(pts, tint(*c, 0.35).filled()))
                .map_err(fail)?;
        }
        let grey = RGBColor(166, 166, 166);
        let thin = (s / 500.0).round().max(1.0) as u32;
        let line = (s / 220.0).round().max(2.0) as u32;
        for j in 0..16 {
            let a = 22.5 * j as f64;
            root.draw(&plotters::element::DashedPathElement::new(
                [self.px(polar(0.15, a)), self.px(polar(EXTENT, a))],
                (s / 100.0).max(3.0) as u32,
                (s / 160.0).max(2.0) as u32,
                grey.stroke_width(thin),
            ))
            .map_err(fail)?;
        }
        let text_px = (s / 40.0).max(9.0);
        let centred = Pos::new(HPos::Center, VPos::Center);
        for j in 0..16 {
            root.draw(&Text::new(
                format!("{}", j + 1),
                self.px(polar(1.41, 22.5 * j as f64 + 11.25)),
                (FAMILY, text_px).into_font().color(&grey).pos(centred),
            ))
            .map_err(fail)?;
        }
        let centre = self.px([0.0, 0.0]);
        for r in [0.8, 0.9, 1.1, 1.2] {
            root.draw(&Circle::new(
                centre,
                (r * unit).round() as u32,
                WHITE.stroke_width(thin),
            ))
            .map_err(fail)?;
        }
        root.draw(&Circle::new(
            centre,
            unit.round() as u32,
            BLACK.stroke_width(2 * thin),
        ))
        .map_err(fail)?;
        // the test polygon, then the arrows over it
        let mut loop_pts: Vec<(i32, i32)> = self.test.iter().map(|p| self.px(*p)).collect();
        loop_pts.push(loop_pts[0]);
        root.draw(&PathElement::new(
            loop_pts,
            rgb(TEST_COLOUR).stroke_width(line),
        ))
        .map_err(fail)?;
        for (j, c) in ARROW_COLOURS.iter().enumerate() {
            let (shaft, head) = self.arrow(j);
            root.draw(&PathElement::new(shaft, rgb(*c).stroke_width(line)))
                .map_err(fail)?;
            root.draw(&Polygon::new(head.to_vec(), rgb(*c).filled()))
                .map_err(fail)?;
        }
        let corner_px = (s / 30.0).max(9.0);
        for (lines, h, x) in [
            (&self.top_left, HPos::Left, 0.02 * s),
            (&self.top_right, HPos::Right, 0.98 * s),
        ] {
            for (i, l) in lines.iter().enumerate() {
                root.draw(&Text::new(
                    l.clone(),
                    (x as i32, (0.02 * s + i as f64 * 1.3 * corner_px) as i32),
                    (FAMILY, corner_px)
                        .into_font()
                        .color(&BLACK)
                        .pos(Pos::new(h, VPos::Top)),
                ))
                .map_err(fail)?;
            }
        }
        root.present().map_err(fail)
    }

    /// The graphic as an SVG document.
    pub fn svg(&self) -> Result<String> {
        let mut s = String::new();
        {
            let root = SVGBackend::with_string(&mut s, (self.size, self.size)).into_drawing_area();
            self.draw(&root)?;
        }
        Ok(s)
    }

    /// The graphic as RGB pixels (row-major, 3 bytes a pixel).
    pub fn rgb_pixels(&self) -> Result<Vec<u8>> {
        self.check()?;
        let mut px = vec![255u8; self.size as usize * self.size as usize * 3];
        {
            let root =
                BitMapBackend::with_buffer(&mut px, (self.size, self.size)).into_drawing_area();
            self.draw(&root)?;
        }
        Ok(px)
    }

    /// The graphic as a PNG file.
    pub fn png(&self) -> Result<Vec<u8>> {
        crate::encode_png(self.size, self.size, &self.rgb_pixels()?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn graphic(size: u32) -> VectorGraphic {
        let polar = |r: f64, j: usize| {
            let a = (22.5 * j as f64 + 11.25).to_radians();
            [r * a.cos(), r * a.sin()]
        };
        VectorGraphic {
            size,
            reference: core::array::from_fn(|j| polar(1.0, j)),
            test: core::array::from_fn(|j| polar(if j % 2 == 0 { 1.2 } else { 0.85 }, j)),
            top_left: vec!["Rf 80".into(), "Rg 101".into()],
            top_right: vec!["CCT 4000 K".into()],
        }
    }

    #[test]
    fn arrow_heads_are_drawn_in_the_bins_colours_where_the_points_say() {
        let g = graphic(500);
        let px = g.rgb_pixels().unwrap();
        for j in 0..16 {
            let (_, head) = g.arrow(j);
            // the head's centroid
            let x = (head.iter().map(|p| p.0).sum::<i32>() as f64 / 3.0).round() as usize;
            let y = (head.iter().map(|p| p.1).sum::<i32>() as f64 / 3.0).round() as usize;
            let i = 3 * (y * 500 + x);
            assert_eq!(px[i..i + 3], ARROW_COLOURS[j], "bin {}", j + 1);
        }
        assert!(g.svg().unwrap().starts_with("<svg"));
        assert_eq!(&g.png().unwrap()[1..4], b"PNG");
    }

    #[test]
    fn sizes_and_empty_bins_are_refused() {
        assert!(graphic(100).svg().is_err());
        let mut g = graphic(400);
        g.test[3] = [f64::NAN; 2];
        assert!(g.png().unwrap_err().to_string().contains("hue bin"));
    }
}
