//! Line plots through `plotters`, one drawing routine for both outputs: SVG (plotters' SVG
//! backend) and PNG (its bitmap backend into an RGB buffer, encoded by `png`). Text in PNGs is
//! DejaVu Sans, embedded in the binary (`crates/plot/assets/fonts/`, with its licence) and rasterised
//! by `ab_glyph`, so no system font or fontconfig is needed and names in any Latin, Greek or
//! Cyrillic script are drawn. Enough for spectra: line series (solid, dashed, dotted) and point
//! series, dashed vertical markers, axes with ticks and a legend beside or below the plot.
//!
//! Readable at every size `plot` allows: type is never smaller than [`MIN_TEXT_PX`]; the
//! legend takes as many columns as it needs beside the plot, or rows below it, and a figure
//! too small to hold it at that size is refused with the size that holds it.
//!
//! Also the ANSI/IES TM-30-20 colour vector graphic ([`vector_graphic`], SVG and PNG from one
//! routine) and the one-page TM-30 report in HTML ([`tm30_page`]).
//!
//! `duplicates` pairs kept: the two legend placements of the layout (beside and below the
//! plot: the same fields, different arithmetic).
#![forbid(unsafe_code)]

pub mod error;
pub mod size;
pub mod tm30_page;
pub mod vector_graphic;

pub use error::{Error, Result};

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::FontStyle;

/// The smallest text drawn (pixels): 9 px DejaVu Sans is still legible.
pub const MIN_TEXT_PX: f64 = 9.0;

/// DejaVu Sans (Bitstream Vera licence, `crates/plot/assets/fonts/LICENSE-DejaVu.txt`).
const FONT: &[u8] = include_bytes!("../assets/fonts/DejaVuSans.ttf");

/// The family name text is drawn in (registered with plotters once).
const FAMILY: &str = "sans-serif";

fn register_font() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        // The font is a fixed, valid file; a failure would show as missing text, not a crash.
        let _ = plotters::style::register_font(FAMILY, FontStyle::Normal, FONT);
    });
}

/// How a series is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Style {
    /// A polyline; `dash` is the dash length in pixels (`None`: solid).
    Line {
        /// Stroke width (px).
        width: f64,
        /// Dash length (px).
        dash: Option<f64>,
    },
    /// Filled circles of this radius (px).
    Points(f64),
}

/// One data series (drawn in data coordinates).
#[derive(Clone, Debug)]
pub struct Series {
    /// Legend entry (`None`: not in the legend).
    pub label: Option<String>,
    /// sRGB colour.
    pub colour: [u8; 3],
    /// Drawing style.
    pub style: Style,
    /// The points `(x, y)`.
    pub points: Vec<(f64, f64)>,
}

/// A figure: title, axes, series and vertical markers.
#[derive(Clone, Debug)]
pub struct Figure {
    /// Pixel width.
    pub width: u32,
    /// Pixel height.
    pub height: u32,
    /// Title.
    pub title: String,
    /// x-axis label.
    pub x_label: String,
    /// y-axis label.
    pub y_label: String,
    /// x range.
    pub x_range: (f64, f64),
    /// y range (`None`: from the data, including 0).
    pub y_range: Option<(f64, f64)>,
    /// The series, drawn in order.
    pub series: Vec<Series>,
    /// Dashed grey vertical lines at these x (e.g. span boundaries).
    pub markers: Vec<f64>,
}

/// "Nice" tick step for a range (1, 2 or 5 × 10ⁿ, about 5–10 ticks).
fn tick_step(span: f64) -> f64 {
    if !(span.is_finite() && span > 0.0) {
        return 1.0;
    }
    let raw = span / 8.0;
    let mag = 10f64.powf(raw.log10().floor());
    let norm = raw / mag;
    let nice = if norm < 1.5 {
        1.0
    } else if norm < 3.5 {
        2.0
    } else if norm < 7.5 {
        5.0
    } else {
        10.0
    };
    nice * mag
}

/// Where the legend goes and how it is laid out.
#[derive(Clone, Copy, Debug, PartialEq)]
enum LegendPlace {
    None,
    Right { columns: usize, rows: usize },
    Below { columns: usize, rows: usize },
}

/// Sizes derived from the figure's size.
#[derive(Clone, Copy, Debug)]
struct Layout {
    /// Body text (ticks, legend), px.
    text: f64,
    /// Axis labels and title, px.
    label: f64,
    /// One legend entry: width and height, px.
    entry: (f64, f64),
    legend: LegendPlace,
}

/// A rough width of `s` in DejaVu Sans at `px` (average advance ≈ 0.6 em): used only to lay
/// out; the text is then measured by plotters where it matters.
fn text_width(s: &str, px: f64) -> f64 {
    s.chars().count() as f64 * 0.6 * px
}

impl Figure {
    fn y_range(&self) -> (f64, f64) {
        if let Some(r) = self.y_range {
            return r;
        }
        let (mut lo, mut hi) = (0.0f64, f64::MIN);
        for s in &self.series {
            for &(x, y) in &s.points {
                if y.is_finite() && x >= self.x_range.0 && x <= self.x_range.1 {
                    lo = lo.min(y);
                    hi = hi.max(y);
                }
            }
        }
        if !(hi > lo) {
            hi = lo + 1.0;
        }
        let step = tick_step(hi - lo);
        let (a, b) = ((lo / step).floor() * step, (hi * 1.02 / step).ceil() * step);
        if a < b && a.is_finite() && b.is_finite() {
            (a, b)
        } else {
            (lo, hi)
        }
    }

    fn labels(&self) -> Vec<&Series> {
        self.series.iter().filter(|s| s.label.is_some()).collect()
    }

    /// Type sizes and the legend's place; an error when the legend cannot be drawn readably.
    fn layout(&self) -> Result<Layout> {
        let (w, h) = (self.width as f64, self.height as f64);
        let text = (h.min(w * 0.7) / 40.0).clamp(MIN_TEXT_PX, 22.0);
        let label = (text * 1.15).max(MIN_TEXT_PX);
        let labels = self.labels();
        let widest = labels
            .iter()
            .filter_map(|s| s.label.as_deref())
            .map(|l| text_width(l, text))
            .fold(0.0, f64::max);
        let entry = (2.6 * text + widest + text, 1.45 * text);
        let n = labels.len();
        if n == 0 {
            return Ok(Layout {
                text,
                label,
                entry,
                legend: LegendPlace::None,
            });
        }
        // beside the plot, in the height the plot takes, using at most 40 % of the width
        let plot_h = h - 2.2 * label - 3.2 * text;
        let rows = ((plot_h / entry.1).floor() as usize).max(1);
        let columns = n.div_ceil(rows);
        if columns as f64 * entry.0 <= 0.4 * w {
            return Ok(Layout {
                text,
                label,
                entry,
                legend: LegendPlace::Right {
                    columns,
                    rows: n.div_ceil(columns),
                },
            });
        }
        // below the plot, using at most 40 % of the height
        let columns = ((w - 2.0 * text) / entry.0).floor().max(1.0) as usize;
        let rows = n.div_ceil(columns);
        if rows as f64 * entry.1 <= 0.4 * h {
            return Ok(Layout {
                text,
                label,
                entry,
                legend: LegendPlace::Below { columns, rows },
            });
        }
        let need_h = (rows as f64 * entry.1 / 0.4).ceil();
        Err(Error::LegendTooBig {
            entries: n,
            width: self.width,
            height: self.height,
            min_text_px: MIN_TEXT_PX,
            need_height: need_h.max(h),
        })
    }

    /// The figure with every text (title, axis labels, legend entries) on one line and its
    /// control characters written as escapes (`\u{1b}`, [`specpoly_formats::escape::one_line`]):
    /// XML 1.0 cannot hold them, not even as character references, so an SVG with one is not
    /// well-formed; in a PNG they would be drawn as missing glyphs.
    fn printable(&self) -> std::borrow::Cow<'_, Figure> {
        use specpoly_formats::escape::one_line;
        let bad = |t: &str| t.chars().any(char::is_control);
        let texts = [&self.title, &self.x_label, &self.y_label];
        if !texts.iter().any(|t| bad(t))
            && !self.series.iter().flat_map(|s| &s.label).any(|t| bad(t))
        {
            return std::borrow::Cow::Borrowed(self);
        }
        let mut f = self.clone();
        for t in [&mut f.title, &mut f.x_label, &mut f.y_label] {
            *t = one_line(t).into_owned();
        }
        for l in f.series.iter_mut().filter_map(|s| s.label.as_mut()) {
            *l = one_line(l).into_owned();
        }
        std::borrow::Cow::Owned(f)
    }

    /// Draws the figure ([`Figure::printable`]) on any plotters drawing area.
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        self.printable().draw_printable(root)
    }

    fn draw_printable<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        let fail = Error::Draw;
        register_font();
        let l = self.layout()?;
        let w = self.width as f64;
        root.fill(&WHITE).map_err(|e| fail(e.to_string()))?;
        let font = |px: f64| (FAMILY, px).into_font();
        // title, shrunk (never below MIN_TEXT_PX) and shortened to fit the width
        let mut title_px = l.label * 1.1;
        while title_px > MIN_TEXT_PX && text_width(&self.title, title_px) > w - 10.0 {
            title_px -= 0.5;
        }
        let mut title = self.title.clone();
        while title.chars().count() > 4 && text_width(&title, title_px) > w - 10.0 {
            title.pop();
            title.pop();
            title.push('…');
        }
        let title_h = (title_px * 1.8).round() as u32;
        let (top, body) = root.split_vertically(title_h);
        top.draw(&Text::new(
            title,
            ((w / 2.0) as i32, (title_px * 0.4) as i32),
            font(title_px)
                .color(&BLACK)
                .pos(plotters::style::text_anchor::Pos::new(
                    plotters::style::text_anchor::HPos::Center,
                    plotters::style::text_anchor::VPos::Top,
                )),
        ))
        .map_err(|e| fail(e.to_string()))?;
        let (plot_area, legend_area) = match l.legend {
            LegendPlace::None => (body, None),
            LegendPlace::Right { columns, .. } => {
                let lw = (columns as f64 * l.entry.0).ceil() as u32;
                let (a, b) = body.split_horizontally(self.width.saturating_sub(lw));
                (a, Some(b))
            }
            LegendPlace::Below { rows, .. } => {
                let lh = (rows as f64 * l.entry.1 + 0.5 * l.text).ceil() as u32;
                let (a, b) = body.split_vertically(self.height.saturating_sub(title_h + lh));
                (a, Some(b))
            }
        };
        let (x0, x1) = self.x_range;
        let (y0, y1) = self.y_range();
        let mut chart = ChartBuilder::on(&plot_area)
            .margin((l.text * 0.8) as u32)
            .x_label_area_size((l.text * 1.4 + l.label * 1.6) as u32)
            .y_label_area_size((l.text * 4.0 + l.label * 1.6) as u32)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| fail(e.to_string()))?;
        let plot_w = (plot_area.dim_in_pixel().0 as f64 - l.text * 6.0).max(10.0);
        let plot_h = (plot_area.dim_in_pixel().1 as f64 - l.text * 4.0).max(10.0);
        chart
            .configure_mesh()
            .disable_x_mesh()
            .bold_line_style(RGBColor(225, 225, 225))
            .light_line_style(TRANSPARENT)
            .x_labels(((plot_w / (l.text * 4.5)) as usize).clamp(2, 10))
            .y_labels(((plot_h / (l.text * 2.5)) as usize).clamp(2, 10))
            .x_desc(self.x_label.as_str())
            .y_desc(self.y_label.as_str())
            .label_style(font(l.text))
            .axis_desc_style(font(l.label))
            .draw()
            .map_err(|e| fail(e.to_string()))?;
        let grey = RGBColor(150, 150, 150);
        for &m in &self.markers {
            chart
                .draw_series(DashedLineSeries::new(
                    [(m, y0), (m, y1)],
                    6,
                    4,
                    grey.stroke_width(1),
                ))
                .map_err(|e| fail(e.to_string()))?;
        }
        let inside = |&(x, y): &(f64, f64)| {
            x.is_finite() && y.is_finite() && x >= x0 && x <= x1 && y >= y0 && y <= y1
        };
        for s in &self.series {
            let c = RGBColor(s.colour[0], s.colour[1], s.colour[2]);
            let pts: Vec<(f64, f64)> = s.points.iter().copied().filter(inside).collect();
            match s.style {
                Style::Line { width, dash: None } => chart
                    .draw_series(LineSeries::new(pts, c.stroke_width(width.round() as u32)))
                    .map(|_| ()),
                Style::Line {
                    width,
                    dash: Some(d),
                } => chart
                    .draw_series(DashedLineSeries::new(
                        pts,
                        d.round().max(1.0) as u32,
                        (d * 0.6).round().max(2.0) as u32,
                        c.stroke_width(width.round() as u32),
                    ))
                    .map(|_| ()),
                Style::Points(r) => chart
                    .draw_series(pts.into_iter().map(|p| Circle::new(p, r, c.filled())))
                    .map(|_| ()),
            }
            .map_err(|e| fail(e.to_string()))?;
        }
        if let Some(area) = legend_area {
            self.draw_legend(&area, &l)
                .map_err(|e| fail(e.to_string()))?;
        }
        root.present().map_err(|e| fail(e.to_string()))
    }

    /// Legend entries: a sample of the series' style, then its label.
    fn draw_legend<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        l: &Layout,
    ) -> std::result::Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        let (columns, rows) = match l.legend {
            LegendPlace::None => return Ok(()),
            LegendPlace::Right { columns, rows } | LegendPlace::Below { columns, rows } => {
                (columns, rows)
            }
        };
        let top = match l.legend {
            LegendPlace::Right { .. } => l.text * 1.2,
            _ => 0.0,
        };
        let left = match l.legend {
            LegendPlace::Below { .. } => l.text,
            _ => 0.0,
        };
        for (i, s) in self.labels().into_iter().enumerate() {
            let (col, row) = if matches!(l.legend, LegendPlace::Right { .. }) {
                (i / rows, i % rows)
            } else {
                (i % columns, i / columns)
            };
            let x = left + col as f64 * l.entry.0;
            let y = top + row as f64 * l.entry.1 + l.entry.1 / 2.0;
            let c = RGBColor(s.colour[0], s.colour[1], s.colour[2]);
            let sw = 2.0 * l.text;
            match s.style {
                Style::Line { width, dash } => {
                    let style = c.stroke_width(width.round() as u32);
                    let d = dash.unwrap_or(sw);
                    let mut a = x;
                    while a < x + sw {
                        let b = (a + d).min(x + sw);
                        area.draw(&PathElement::new(
                            vec![(a as i32, y as i32), (b as i32, y as i32)],
                            style,
                        ))?;
                        a = b + if dash.is_some() { 0.6 * d } else { 0.0 };
                    }
                }
                Style::Points(r) => {
                    area.draw(&Circle::new(
                        ((x + sw / 2.0) as i32, y as i32),
                        r,
                        c.filled(),
                    ))?;
                }
            }
            area.draw(&Text::new(
                s.label.clone().unwrap_or_default(),
                ((x + sw + 0.5 * l.text) as i32, y as i32),
                (FAMILY, l.text).into_font().color(&BLACK).pos(
                    plotters::style::text_anchor::Pos::new(
                        plotters::style::text_anchor::HPos::Left,
                        plotters::style::text_anchor::VPos::Center,
                    ),
                ),
            ))?;
        }
        Ok(())
    }

    /// The figure as an SVG document.
    pub fn svg(&self) -> Result<String> {
        let mut s = String::new();
        {
            let root =
                SVGBackend::with_string(&mut s, (self.width, self.height)).into_drawing_area();
            self.draw(&root)?;
        }
        Ok(s)
    }

    /// The figure as RGB pixels (row-major, 3 bytes per pixel).
    pub fn rgb_pixels(&self) -> Result<Vec<u8>> {
        let mut px = vec![255u8; self.width as usize * self.height as usize * 3];
        {
            let root =
                BitMapBackend::with_buffer(&mut px, (self.width, self.height)).into_drawing_area();
            self.draw(&root)?;
        }
        Ok(px)
    }

    /// The figure as a PNG file.
    pub fn png(&self) -> Result<Vec<u8>> {
        let pixels = self.rgb_pixels()?;
        encode_png(self.width, self.height, &pixels)
    }
}

/// RGB pixels as a PNG file's bytes.
pub fn encode_png(width: u32, height: u32, rgb: &[u8]) -> Result<Vec<u8>> {
    let fail = Error::Png;
    let mut out = Vec::new();
    {
        let mut e = png::Encoder::new(&mut out, width, height);
        e.set_color(png::ColorType::Rgb);
        e.set_depth(png::BitDepth::Eight);
        let mut w = e.write_header().map_err(fail)?;
        w.write_image_data(rgb).map_err(fail)?;
    }
    Ok(out)
}

/// Draws `text` on an RGB buffer (`width` × `height`, row-major) with its top-left corner at
/// `at`, in DejaVu Sans of `px` pixels: labels for composite images (`render --compare`).
pub fn draw_text(
    rgb: &mut [u8],
    (width, height): (u32, u32),
    at: (i32, i32),
    px: f64,
    colour: [u8; 3],
    text: &str,
) -> Result<()> {
    register_font();
    let root = BitMapBackend::with_buffer(rgb, (width, height)).into_drawing_area();
    let style = (FAMILY, px)
        .into_font()
        .color(&RGBColor(colour[0], colour[1], colour[2]));
    root.draw(&Text::new(text.to_string(), at, style))
        .and_then(|_| root.present())
        .map_err(|e| Error::Text(e.to_string()))
}

/// The width of `text` in DejaVu Sans of `px` pixels, as plotters lays it out.
pub fn measure_text(text: &str, px: f64) -> u32 {
    register_font();
    let font = (FAMILY, px).into_font();
    font.box_size(text).map(|(w, _)| w).unwrap_or(0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fig(n: usize, size: (u32, u32), label: &str) -> Figure {
        Figure {
            width: size.0,
            height: size.1,
            title: "t <1>".into(),
            x_label: "wavelength (nm)".into(),
            y_label: "reflectance".into(),
            x_range: (380.0, 780.0),
            y_range: None,
            series: (0..n)
                .map(|i| Series {
                    label: Some(format!("{label} {i}")),
                    colour: [200, (i * 10) as u8, 0],
                    style: Style::Line {
                        width: 2.0,
                        dash: Some(5.0),
                    },
                    points: vec![(380.0, 0.1), (780.0, 0.9)],
                })
                .collect(),
            markers: vec![550.0],
        }
    }

    #[test]
    fn svg_and_png() {
        let f = fig(1, (400, 300), "a");
        let s = f.svg().unwrap();
        assert!(s.starts_with("<svg") && s.contains("t &lt;1&gt;"), "{s}");
        let px = f.rgb_pixels().unwrap();
        assert_eq!(px.len(), 400 * 300 * 3);
        assert!(px.chunks(3).any(|p| p[0] > 150 && p[1] < 100)); // the red line is there
        assert!(px.chunks(3).any(|p| p[0] < 60 && p[1] < 60 && p[2] < 60)); // text and frame
        let png = f.png().unwrap();
        assert_eq!(&png[1..4], b"PNG");
    }

    #[test]
    fn control_characters_in_texts_leave_the_svg_well_formed() {
        let mut f = fig(2, (500, 300), "red\u{1b}]0;owned\u{7}");
        f.title = "t\u{0}\u{8}".into();
        f.x_label = "nm\u{1b}[2J".into();
        let s = f.svg().unwrap();
        assert!(!s.chars().any(|c| c.is_control() && c != '\n'), "{s:?}");
        assert!(s.contains("red\\u{1b}]0;owned\\u{7}"), "{s}");
        assert!(s.contains("nm\\u{1b}[2J"), "{s}");
        assert!(s.contains("t\\u{0}\\u{8}"), "{s}");
    }

    #[test]
    fn non_ascii_labels_are_drawn() {
        // the same figure with `u` and with `ü`, `ß`, `Ω` in a label: the pixels differ
        let a = fig(1, (400, 300), "grun").rgb_pixels().unwrap();
        let b = fig(1, (400, 300), "grün").rgb_pixels().unwrap();
        let c = fig(1, (400, 300), "Ωß").rgb_pixels().unwrap();
        let d = fig(1, (400, 300), "  ").rgb_pixels().unwrap();
        assert_ne!(a, b);
        assert_ne!(c, d, "Ω and ß are drawn, not blank");
    }

    #[test]
    fn legends_fit_or_the_size_that_fits_is_named() {
        // 24 series at the default size: the legend fits beside or below in readable type
        assert!(fig(24, (900, 560), "spectrum").png().is_ok());
        // at the smallest size, 24 do not: the error names a size, which then works
        let e = fig(24, (200, 150), "spectrum")
            .png()
            .unwrap_err()
            .to_string();
        let size = e
            .split("--size ")
            .nth(1)
            .unwrap()
            .split(' ')
            .next()
            .unwrap();
        let (w, h) = size.split_once('x').unwrap();
        let (w, h): (u32, u32) = (w.parse().unwrap(), h.parse().unwrap());
        assert!(fig(24, (w, h), "spectrum").png().is_ok(), "{e}");
        // one series at the smallest size fits
        assert!(fig(1, (200, 150), "a").png().is_ok());
    }

    #[test]
    fn ticks_are_nice() {
        assert_eq!(tick_step(400.0), 50.0);
        assert_eq!(tick_step(1.0), 0.1);
    }
}
