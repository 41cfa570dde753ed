//! A small line-plot renderer with two outputs from one layout: SVG (text as `<text>`) and PNG
//! (its own anti-aliased rasteriser, text in the public-domain 8×8 bitmap font of `font8x8`, so
//! no system font or fontconfig is needed). Enough for spectra: line and point series, dashed
//! vertical markers, axes with ticks, a legend.

use std::fmt::Write as _;

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

#[derive(Clone, Copy, Debug, PartialEq)]
enum Anchor {
    Start,
    Middle,
    End,
}

#[derive(Clone, Debug)]
enum Prim {
    Line {
        pts: Vec<(f64, f64)>,
        width: f64,
        colour: [u8; 3],
        dash: Option<f64>,
    },
    Dot {
        c: (f64, f64),
        r: f64,
        colour: [u8; 3],
    },
    /// A white box with a grey border (legend background).
    Box { lo: (f64, f64), hi: (f64, f64) },
    Text {
        at: (f64, f64),
        size: f64,
        anchor: Anchor,
        vertical: bool,
        s: String,
    },
}

const MARGIN_L: f64 = 120.0;
const MARGIN_R: f64 = 30.0;
const MARGIN_T: f64 = 50.0;
const MARGIN_B: f64 = 70.0;

/// The plot box in pixels (`pl`eft, `pr` right, `pt` top, `pb` bottom) and the data ranges it
/// shows.
#[derive(Clone, Copy, Debug)]
struct PlotBox {
    pl: f64,
    pr: f64,
    pt: f64,
    pb: f64,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
}

impl PlotBox {
    /// Pixel column of data `x`.
    fn px(&self, x: f64) -> f64 {
        self.pl + (x - self.x0) / (self.x1 - self.x0) * (self.pr - self.pl)
    }

    /// Pixel row of data `y`.
    fn py(&self, y: f64) -> f64 {
        self.pb - (y - self.y0) / (self.y1 - self.y0) * (self.pb - self.pt)
    }
}

/// "Nice" tick step for a range (1, 2 or 5 × 10ⁿ, about 5–10 ticks).
fn tick_step(span: f64) -> f64 {
    let raw = span / 6.0;
    let p = 10f64.powf(raw.log10().floor());
    let m = raw / p;
    p * if m < 1.5 {
        1.0
    } else if m < 3.5 {
        2.0
    } else if m < 7.5 {
        5.0
    } else {
        10.0
    }
}

/// Integer scale of the 8×8 bitmap font for a font size (px).
fn text_scale(size: f64) -> usize {
    ((size / 8.0).round() as usize).max(1)
}

/// Width (px) of `s` in the bitmap font; SVG text at the same size is narrower, so layouts
/// sized with this fit both.
fn text_width(s: &str, size: f64) -> f64 {
    (s.chars().count() * 8 * text_scale(size)) as f64
}

fn fmt_tick(v: f64, step: f64) -> String {
    let dec = (-step.log10().floor()).max(0.0) as usize;
    format!("{v:.dec$}")
}

impl Figure {
    fn y_range(&self) -> (f64, f64) {
        if let Some(r) = self.y_range {
            return r;
        }
        let (mut lo, mut hi) = (0.0f64, f64::MIN);
        for s in &self.series {
            for &(_, y) in &s.points {
                if y.is_finite() {
                    lo = lo.min(y);
                    hi = hi.max(y);
                }
            }
        }
        if hi <= lo {
            hi = lo + 1.0;
        }
        let step = tick_step(hi - lo);
        ((lo / step).floor() * step, (hi * 1.02 / step).ceil() * step)
    }

    /// The plot box and the mapping from data to pixels.
    fn plot_box(&self) -> PlotBox {
        let (w, h) = (self.width as f64, self.height as f64);
        let (x0, x1) = self.x_range;
        let (y0, y1) = self.y_range();
        PlotBox {
            pl: MARGIN_L,
            pr: w - MARGIN_R,
            pt: MARGIN_T,
            pb: h - MARGIN_B,
            x0,
            x1,
            y0,
            y1,
        }
    }

    fn prims(&self) -> Vec<Prim> {
        let p = self.plot_box();
        let mut v = Vec::new();
        self.axes(&p, &mut v);
        self.markers_and_series(&p, &mut v);
        self.legend(&p, &mut v);
        v
    }

    /// Frame, ticks, axis labels and title.
    fn axes(&self, p: &PlotBox, v: &mut Vec<Prim>) {
        let (w, h) = (self.width as f64, self.height as f64);
        let black = [0, 0, 0];
        // frame
        v.push(Prim::Line {
            pts: vec![
                (p.pl, p.pt),
                (p.pr, p.pt),
                (p.pr, p.pb),
                (p.pl, p.pb),
                (p.pl, p.pt),
            ],
            width: 1.0,
            colour: black,
            dash: None,
        });
        // ticks
        let xs = tick_step(p.x1 - p.x0);
        let mut t = (p.x0 / xs).ceil() * xs;
        while t <= p.x1 + 1e-9 {
            v.push(Prim::Line {
                pts: vec![(p.px(t), p.pb), (p.px(t), p.pb + 6.0)],
                width: 1.0,
                colour: black,
                dash: None,
            });
            v.push(Prim::Text {
                at: (p.px(t), p.pb + 24.0),
                size: 14.0,
                anchor: Anchor::Middle,
                vertical: false,
                s: fmt_tick(t, xs),
            });
            t += xs;
        }
        let ys = tick_step(p.y1 - p.y0);
        let mut t = (p.y0 / ys).ceil() * ys;
        while t <= p.y1 + 1e-9 {
            v.push(Prim::Line {
                pts: vec![(p.pl - 6.0, p.py(t)), (p.pl, p.py(t))],
                width: 1.0,
                colour: black,
                dash: None,
            });
            v.push(Prim::Text {
                at: (p.pl - 10.0, p.py(t) + 5.0),
                size: 14.0,
                anchor: Anchor::End,
                vertical: false,
                s: fmt_tick(t, ys),
            });
            t += ys;
        }
        // labels
        v.push(Prim::Text {
            at: (0.5 * (p.pl + p.pr), h - 20.0),
            size: 16.0,
            anchor: Anchor::Middle,
            vertical: false,
            s: self.x_label.clone(),
        });
        v.push(Prim::Text {
            at: (20.0, 0.5 * (p.pt + p.pb)),
            size: 16.0,
            anchor: Anchor::Middle,
            vertical: true,
            s: self.y_label.clone(),
        });
        let title_size = if text_width(&self.title, 18.0) <= w - 20.0 {
            18.0
        } else {
            9.0
        };
        v.push(Prim::Text {
            at: (0.5 * w, 30.0),
            size: title_size,
            anchor: Anchor::Middle,
            vertical: false,
            s: self.title.clone(),
        });
    }

    /// Span markers (dashed grey) and the series, clipped to the plot box.
    fn markers_and_series(&self, p: &PlotBox, v: &mut Vec<Prim>) {
        let grey = [150, 150, 150];
        // markers
        for &m in &self.markers {
            v.push(Prim::Line {
                pts: vec![(p.px(m), p.pt), (p.px(m), p.pb)],
                width: 1.0,
                colour: grey,
                dash: Some(6.0),
            });
        }
        // series, clipped to the plot box
        let inside = |(x, y): (f64, f64)| {
            x >= p.pl - 0.5 && x <= p.pr + 0.5 && y >= p.pt - 0.5 && y <= p.pb + 0.5
        };
        for s in &self.series {
            let pts: Vec<(f64, f64)> = s
                .points
                .iter()
                .filter(|(x, y)| x.is_finite() && y.is_finite())
                .map(|&(x, y)| (p.px(x), p.py(y).clamp(p.pt, p.pb)))
                .filter(|q| inside(*q))
                .collect();
            match s.style {
                Style::Line { width, dash } => v.push(Prim::Line {
                    pts,
                    width,
                    colour: s.colour,
                    dash,
                }),
                Style::Points(r) => v.extend(pts.into_iter().map(|c| Prim::Dot {
                    c,
                    r,
                    colour: s.colour,
                })),
            }
        }
    }

    /// The legend, in the corner of the plot box that hides the fewest data points.
    fn legend(&self, p: &PlotBox, v: &mut Vec<Prim>) {
        // legend: in the corner of the plot box that hides the fewest data points
        let labels = self.series.iter().filter(|s| s.label.is_some()).count();
        let widest = self
            .series
            .iter()
            .filter_map(|s| s.label.as_deref())
            .map(|l| text_width(l, 14.0))
            .fold(0.0, f64::max);
        let (bw, bh) = (38.0 + widest + 12.0, 20.0 * labels as f64 + 10.0);
        let corners = [
            (p.pr - 8.0 - bw, p.pt + 8.0),
            (p.pl + 8.0, p.pt + 8.0),
            (p.pr - 8.0 - bw, p.pb - 8.0 - bh),
            (p.pl + 8.0, p.pb - 8.0 - bh),
        ];
        let hidden = |(x, y): (f64, f64)| {
            self.series
                .iter()
                .flat_map(|s| s.points.iter())
                .filter(|&&(a, b)| {
                    let (u, v) = (p.px(a), p.py(b));
                    u >= x && u <= x + bw && v >= y && v <= y + bh
                })
                .count()
        };
        let (bx, by) = corners
            .into_iter()
            .min_by_key(|c| hidden(*c))
            .unwrap_or(corners[0]);
        if labels > 0 {
            v.push(Prim::Box {
                lo: (bx, by),
                hi: (bx + bw, by + bh),
            });
        }
        let mut ly = by + 22.0;
        let lx = bx + 6.0;
        for s in self.series.iter().filter(|s| s.label.is_some()) {
            let label = s.label.clone().unwrap_or_default();
            match s.style {
                Style::Line { width, dash } => v.push(Prim::Line {
                    pts: vec![(lx, ly - 5.0), (lx + 30.0, ly - 5.0)],
                    width,
                    colour: s.colour,
                    dash,
                }),
                Style::Points(r) => v.push(Prim::Dot {
                    c: (lx + 15.0, ly - 5.0),
                    r,
                    colour: s.colour,
                }),
            }
            v.push(Prim::Text {
                at: (lx + 38.0, ly),
                size: 14.0,
                anchor: Anchor::Start,
                vertical: false,
                s: label,
            });
            ly += 20.0;
        }
    }

    /// Draws every primitive on `surface`.
    fn draw(&self, surface: &mut impl Surface) {
        for p in self.prims() {
            match p {
                Prim::Line {
                    pts,
                    width,
                    colour,
                    dash,
                } => surface.draw_line(&pts, width, colour, dash),
                Prim::Dot { c, r, colour } => surface.draw_dot(c, r, colour),
                Prim::Box { lo, hi } => surface.draw_box(lo, hi),
                Prim::Text {
                    at,
                    size,
                    anchor,
                    vertical,
                    s,
                } => surface.draw_text(at, size, anchor, vertical, &s),
            }
        }
    }

    /// The figure as an SVG document.
    pub fn svg(&self) -> String {
        let mut o = Svg(String::new());
        let _ = writeln!(
            o.0,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="DejaVu Sans, Helvetica, Arial, sans-serif">"#,
            w = self.width,
            h = self.height
        );
        let _ = writeln!(o.0, r#"<rect width="100%" height="100%" fill="white"/>"#);
        self.draw(&mut o);
        o.0.push_str("</svg>\n");
        o.0
    }

    /// The figure as RGB pixels (row-major, 3 bytes per pixel).
    pub fn rgb_pixels(&self) -> Vec<u8> {
        let mut c = Canvas::new(self.width as usize, self.height as usize);
        self.draw(&mut c);
        c.to_rgb8()
    }

    /// The figure as a PNG file.
    pub fn png(&self) -> Result<Vec<u8>, png::EncodingError> {
        let pixels = self.rgb_pixels();
        let mut out = Vec::new();
        {
            let mut e = png::Encoder::new(&mut out, self.width, self.height);
            e.set_color(png::ColorType::Rgb);
            e.set_depth(png::BitDepth::Eight);
            let mut w = e.write_header()?;
            w.write_image_data(&pixels)?;
        }
        Ok(out)
    }
}

fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// An RGB float canvas with coverage-based anti-aliasing: each primitive is rasterised into a
/// coverage mask (max over its parts, so a polyline's joints are not painted twice) and then
/// blended once.
struct Canvas {
    w: usize,
    h: usize,
    px: Vec<[f32; 3]>,
    mask: Vec<f32>,
    bbox: Option<(usize, usize, usize, usize)>,
}

impl Canvas {
    fn new(w: usize, h: usize) -> Self {
        Canvas {
            w,
            h,
            px: vec![[1.0; 3]; w * h],
            mask: vec![0.0; w * h],
            bbox: None,
        }
    }

    fn cover(&mut self, x: usize, y: usize, a: f32) {
        let m = &mut self.mask[y * self.w + x];
        if a > *m {
            *m = a;
        }
        self.bbox = Some(match self.bbox {
            None => (x, y, x, y),
            Some((a0, b0, a1, b1)) => (a0.min(x), b0.min(y), a1.max(x), b1.max(y)),
        });
    }

    fn flush(&mut self, colour: [u8; 3]) {
        let Some((x0, y0, x1, y1)) = self.bbox.take() else {
            return;
        };
        let c = colour.map(|v| v as f32 / 255.0);
        for y in y0..=y1 {
            for x in x0..=x1 {
                let i = y * self.w + x;
                let a = self.mask[i];
                if a > 0.0 {
                    for k in 0..3 {
                        self.px[i][k] = self.px[i][k] * (1.0 - a) + c[k] * a;
                    }
                    self.mask[i] = 0.0;
                }
            }
        }
    }

    fn region(&self, lo: (f64, f64), hi: (f64, f64)) -> (usize, usize, usize, usize) {
        let cx = |v: f64| (v.max(0.0) as usize).min(self.w.saturating_sub(1));
        let cy = |v: f64| (v.max(0.0) as usize).min(self.h.saturating_sub(1));
        (cx(lo.0), cy(lo.1), cx(hi.0), cy(hi.1))
    }

    fn segment(&mut self, a: (f64, f64), b: (f64, f64), width: f64) {
        let r = 0.5 * width.max(1.0);
        let (x0, y0, x1, y1) = self.region(
            (a.0.min(b.0) - r - 1.0, a.1.min(b.1) - r - 1.0),
            (a.0.max(b.0) + r + 1.0, a.1.max(b.1) + r + 1.0),
        );
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let len2 = dx * dx + dy * dy;
        for y in y0..=y1 {
            for x in x0..=x1 {
                let (cx, cy) = (x as f64 + 0.5, y as f64 + 0.5);
                let t = if len2 > 0.0 {
                    (((cx - a.0) * dx + (cy - a.1) * dy) / len2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let d = ((cx - a.0 - t * dx).powi(2) + (cy - a.1 - t * dy).powi(2)).sqrt();
                let cov = (r + 0.5 - d).clamp(0.0, 1.0) as f32;
                if cov > 0.0 {
                    self.cover(x, y, cov);
                }
            }
        }
    }

    fn polyline(&mut self, pts: &[(f64, f64)], width: f64, colour: [u8; 3], dash: Option<f64>) {
        match dash {
            None => {
                for p in pts.windows(2) {
                    self.segment(p[0], p[1], width);
                }
            }
            Some(on) => {
                // walk the polyline, drawing `on` px and skipping 0.7·on px
                let off = 0.7 * on;
                let mut drawing = true;
                let mut left = on;
                for p in pts.windows(2) {
                    let (mut a, b) = (p[0], p[1]);
                    loop {
                        let seg = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
                        if seg <= left {
                            if drawing {
                                self.segment(a, b, width);
                            }
                            left -= seg;
                            break;
                        }
                        let f = left / seg;
                        let m = (a.0 + f * (b.0 - a.0), a.1 + f * (b.1 - a.1));
                        if drawing {
                            self.segment(a, m, width);
                        }
                        a = m;
                        drawing = !drawing;
                        left = if drawing { on } else { off };
                    }
                }
            }
        }
        self.flush(colour);
    }

    fn dot(&mut self, c: (f64, f64), r: f64, colour: [u8; 3]) {
        let (x0, y0, x1, y1) = self.region(
            (c.0 - r - 1.0, c.1 - r - 1.0),
            (c.0 + r + 1.0, c.1 + r + 1.0),
        );
        for y in y0..=y1 {
            for x in x0..=x1 {
                let d = ((x as f64 + 0.5 - c.0).powi(2) + (y as f64 + 0.5 - c.1).powi(2)).sqrt();
                let cov = (r + 0.5 - d).clamp(0.0, 1.0) as f32;
                if cov > 0.0 {
                    self.cover(x, y, cov);
                }
            }
        }
        self.flush(colour);
    }

    /// Bitmap text: 8×8 glyphs scaled by an integer factor (size 14–18 → ×2); `at` is the
    /// baseline point of the anchor, as in SVG.
    fn text(&mut self, at: (f64, f64), size: f64, anchor: Anchor, vertical: bool, s: &str) {
        let scale = text_scale(size);
        let glyph_w = 8 * scale;
        let n = s.chars().count();
        let total = (n * glyph_w) as f64;
        let start = match anchor {
            Anchor::Start => 0.0,
            Anchor::Middle => -0.5 * total,
            Anchor::End => -total,
        };
        // glyph box top is 7 rows above the baseline
        let top = -(7.0 * scale as f64);
        for (i, ch) in s.chars().enumerate() {
            let g = glyph(ch);
            for (row, bits) in g.iter().enumerate() {
                for col in 0..8 {
                    if bits & (1 << col) == 0 {
                        continue;
                    }
                    for sy in 0..scale {
                        for sx in 0..scale {
                            // along the text (u) and down (v), relative to the anchor
                            let u = start + (i * glyph_w + col * scale + sx) as f64;
                            let v = top + (row * scale + sy) as f64;
                            let (x, y) = if vertical {
                                (at.0 + v, at.1 - u)
                            } else {
                                (at.0 + u, at.1 + v)
                            };
                            if x >= 0.0
                                && y >= 0.0
                                && (x as usize) < self.w
                                && (y as usize) < self.h
                            {
                                self.cover(x as usize, y as usize, 1.0);
                            }
                        }
                    }
                }
            }
        }
        self.flush([0, 0, 0]);
    }

    fn to_rgb8(&self) -> Vec<u8> {
        self.px
            .iter()
            .flat_map(|p| p.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8))
            .collect()
    }
}

/// The 8×8 glyph of `c` (bit 0 = leftmost pixel); non-ASCII characters get a stand-in.
fn glyph(c: char) -> [u8; 8] {
    let c = match c {
        'λ' => 'l',
        'Δ' => 'D',
        '×' | '·' => '*',
        '–' | '—' => '-',
        c if c.is_ascii() => c,
        _ => '?',
    };
    font8x8::legacy::BASIC_LEGACY[c as usize]
}

/// Where a figure's primitives are drawn: the SVG writer and the PNG canvas.
trait Surface {
    /// A polyline (dashed when `dash` gives the dash length).
    fn draw_line(&mut self, pts: &[(f64, f64)], width: f64, colour: [u8; 3], dash: Option<f64>);
    /// A filled disc.
    fn draw_dot(&mut self, c: (f64, f64), r: f64, colour: [u8; 3]);
    /// A white box with a grey border (the legend's background).
    fn draw_box(&mut self, lo: (f64, f64), hi: (f64, f64));
    /// Text at `at` (the baseline), `size` px, anchored by `anchor`, rotated when `vertical`.
    fn draw_text(&mut self, at: (f64, f64), size: f64, anchor: Anchor, vertical: bool, s: &str);
}

/// An SVG document being written.
struct Svg(String);

fn svg_rgb(c: [u8; 3]) -> String {
    format!("rgb({},{},{})", c[0], c[1], c[2])
}

impl Surface for Svg {
    fn draw_line(&mut self, pts: &[(f64, f64)], width: f64, colour: [u8; 3], dash: Option<f64>) {
        if pts.len() < 2 {
            return;
        }
        let d: Vec<String> = pts.iter().map(|(x, y)| format!("{x:.2},{y:.2}")).collect();
        let dash = dash
            .map(|l| format!(r#" stroke-dasharray="{l:.1},{:.1}""#, l * 0.7))
            .unwrap_or_default();
        let _ = writeln!(
            self.0,
            r#"<polyline fill="none" stroke="{}" stroke-width="{width}" stroke-linejoin="round"{dash} points="{}"/>"#,
            svg_rgb(colour),
            d.join(" ")
        );
    }

    fn draw_dot(&mut self, c: (f64, f64), r: f64, colour: [u8; 3]) {
        let _ = writeln!(
            self.0,
            r#"<circle cx="{:.2}" cy="{:.2}" r="{r}" fill="{}"/>"#,
            c.0,
            c.1,
            svg_rgb(colour)
        );
    }

    fn draw_box(&mut self, lo: (f64, f64), hi: (f64, f64)) {
        let _ = writeln!(
            self.0,
            r#"<rect x="{:.1}" y="{:.1}" width="{:.1}" height="{:.1}" fill="white" stroke="rgb(150,150,150)"/>"#,
            lo.0,
            lo.1,
            hi.0 - lo.0,
            hi.1 - lo.1
        );
    }

    fn draw_text(&mut self, at: (f64, f64), size: f64, anchor: Anchor, vertical: bool, s: &str) {
        let a = match anchor {
            Anchor::Start => "start",
            Anchor::Middle => "middle",
            Anchor::End => "end",
        };
        let rot = if vertical {
            format!(r#" transform="rotate(-90 {:.1} {:.1})""#, at.0, at.1)
        } else {
            String::new()
        };
        let _ = writeln!(
            self.0,
            r#"<text x="{:.1}" y="{:.1}" font-size="{size}" text-anchor="{a}"{rot}>{}</text>"#,
            at.0,
            at.1,
            xml_escape(s)
        );
    }
}

impl Surface for Canvas {
    fn draw_line(&mut self, pts: &[(f64, f64)], width: f64, colour: [u8; 3], dash: Option<f64>) {
        self.polyline(pts, width, colour, dash);
    }

    fn draw_dot(&mut self, c: (f64, f64), r: f64, colour: [u8; 3]) {
        self.dot(c, r, colour);
    }

    fn draw_box(&mut self, lo: (f64, f64), hi: (f64, f64)) {
        let (x0, y0, x1, y1) = self.region(lo, hi);
        for y in y0..=y1 {
            for x in x0..=x1 {
                self.cover(x, y, 1.0);
            }
        }
        self.flush([255, 255, 255]);
        let edge = [
            (lo.0, lo.1),
            (hi.0, lo.1),
            (hi.0, hi.1),
            (lo.0, hi.1),
            (lo.0, lo.1),
        ];
        self.polyline(&edge, 1.0, [150, 150, 150], None);
    }

    fn draw_text(&mut self, at: (f64, f64), size: f64, anchor: Anchor, vertical: bool, s: &str) {
        self.text(at, size, anchor, vertical, s);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fig() -> Figure {
        Figure {
            width: 400,
            height: 300,
            title: "t <1>".into(),
            x_label: "wavelength (nm)".into(),
            y_label: "reflectance".into(),
            x_range: (380.0, 780.0),
            y_range: None,
            series: vec![Series {
                label: Some("a".into()),
                colour: [200, 0, 0],
                style: Style::Line {
                    width: 2.0,
                    dash: Some(5.0),
                },
                points: vec![(380.0, 0.1), (780.0, 0.9)],
            }],
            markers: vec![550.0],
        }
    }

    #[test]
    fn svg_and_png() {
        let f = fig();
        let s = f.svg();
        assert!(s.starts_with("<svg") && s.contains("t &lt;1&gt;") && s.contains("polyline"));
        let px = f.rgb_pixels();
        assert_eq!(px.len(), 400 * 300 * 3);
        assert!(px.chunks(3).any(|p| p[0] > 150 && p[1] < 100)); // the red line is there
        assert!(px.chunks(3).any(|p| p == [0, 0, 0])); // text and frame
        let png = f.png().unwrap();
        assert_eq!(&png[1..4], b"PNG");
    }

    #[test]
    fn ticks_are_nice() {
        assert_eq!(tick_step(400.0), 50.0);
        assert_eq!(tick_step(1.0), 0.2);
    }
}
