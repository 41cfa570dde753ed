//! The verification report as one self-contained HTML page (`calibrate verify --report FILE.html`):
//! inline SVG figures and CSS, no script, no fonts, images or anything else fetched (a
//! `Content-Security-Policy` of `default-src 'none'` makes the browser refuse any load).
//!
//! - **Gamut**: the CIE 1976 u′v′ diagram (`u′ = 4x/(−2x + 12y + 3)`, `v′ = 9y/(−2x + 12y + 3)`,
//!   CIE 015:2018 §8.1) with the spectral locus of the CIE 1931 2° observer (380–700 nm, closed by
//!   the purple line), the display's primaries and white against sRGB (IEC 61966-2-1) and
//!   Display P3 (SMPTE EG 432-1 primaries, D65 white).
//! - **ΔE00 per patch**: one bar per measured patch in file order, filled with the patch's device
//!   RGB, with DisplayCAL's nominal mean (1.5) and maximum (4) as lines.
//! - **Tone curves**: each channel's single-channel ramp and the grey ramp, measured luminance
//!   above black relative to the channel at full drive, against the target curve (`--tone-target`,
//!   gamma 2.2 by default).
//! - **Pass/fail table** of [`crate::criteria`].
//!
//! The page is well-formed XML as well as HTML (every element closed, no named entities), so tests
//! parse it with an XML parser. Element ids and classes are stable: `svg#gamut`, `svg#delta-e`
//! (`rect.bar` with `data-line`), `svg#tone`, `table#criteria` (`tr` with `data-criterion`).
//! Hand-written (string building, ~300 lines) because the figures are a few polylines and rects;
//! `plotters`' SVG backend draws into a fixed pixel canvas with its own text layout, and we want
//! the bars' colours, ids and `title`s under our control.

use crate::criteria::{Level, Outcome};
use crate::verify::Verification;
use specpoly_core::{Observer, Transfer};
use specpoly_display::calibration::Calibration;
use std::fmt::Write as _;

/// What the page is about, for its heading.
pub struct ReportInfo<'a> {
    /// The calibration file's name.
    pub calibration: &'a str,
    /// The measurement file's name.
    pub measurements: &'a str,
    /// The tone curve the measured ramps are compared with, and its name.
    pub tone_target: (Transfer, String),
    /// The level `verify` requires.
    pub level: Level,
}

/// sRGB's primaries (x, y), red, green, blue (IEC 61966-2-1).
pub const SRGB: [[f64; 2]; 3] = [[0.64, 0.33], [0.30, 0.60], [0.15, 0.06]];
/// Display P3's primaries (x, y) (SMPTE EG 432-1; D65 white).
pub const DISPLAY_P3: [[f64; 2]; 3] = [[0.680, 0.320], [0.265, 0.690], [0.150, 0.060]];

/// CIE 1976 u′v′ of a chromaticity x, y.
pub fn uv_prime(x: f64, y: f64) -> [f64; 2] {
    let d = -2.0 * x + 12.0 * y + 3.0;
    [4.0 * x / d, 9.0 * y / d]
}

/// The page's escape for text and attribute values ([`specpoly_formats::escape::markup`]).
pub use specpoly_formats::escape::markup as escape;

/// The CSS colour of device RGB (0–1) shown as is: `#rrggbb`.
pub fn css_colour(rgb: [f64; 3]) -> String {
    let q = |v: f64| {
        if v.is_finite() {
            (v.clamp(0.0, 1.0) * 255.0).round() as u8
        } else {
            0
        }
    };
    format!("#{:02x}{:02x}{:02x}", q(rgb[0]), q(rgb[1]), q(rgb[2]))
}

/// A number for the page: finite with `digits` decimals, else `n/a`.
fn num(v: f64, digits: usize) -> String {
    if v.is_finite() {
        format!("{v:.digits$}")
    } else {
        "n/a".into()
    }
}

const STYLE: &str = "body{font-family:sans-serif;margin:1.5em;max-width:62em;color:#222;background:#fff}\
h1{font-size:1.4em}h2{font-size:1.15em;margin-top:1.6em}\
table{border-collapse:collapse}td,th{border:1px solid #bbb;padding:.25em .6em;text-align:left}\
td.num{text-align:right;font-variant-numeric:tabular-nums}\
tr.pass td.result{background:#c8f0c8}tr.fail td.result{background:#f6c0c0}tr.na td.result{background:#eee}\
svg{display:block;width:100%;height:auto;border:1px solid #ccc;background:#fff}\
svg.natural{width:auto;max-width:none}div.scroll{overflow-x:auto}\
svg text{font-family:sans-serif;fill:#222}.legend{font-size:.9em}";

/// The whole page.
pub fn page(v: &Verification, cal: &Calibration, info: &ReportInfo) -> String {
    let mut h = String::new();
    let fail = crate::criteria::failures(&v.outcomes, info.level);
    let _ = write!(
        h,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"/>\
<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; style-src 'unsafe-inline'\"/>\
<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\"/>\
<title>Verification of {cal_name}</title><style>{STYLE}</style></head><body>\n\
<h1>Verification of {cal_name}</h1>\n<p>{n} patches of <code>{meas}</code>; ΔE00 mean {mean}, 95th percentile {p95}, maximum {max}. \
Result: <strong id=\"verdict\">{verdict}</strong> at the {level} level.</p>\n",
        cal_name = escape(info.calibration),
        meas = escape(info.measurements),
        n = v.stats.n,
        mean = num(v.stats.mean, 3),
        p95 = num(v.stats.p95, 3),
        max = num(v.stats.max, 3),
        verdict = if fail.is_none() { "pass" } else { "fail" },
        level = match info.level {
            Level::Nominal => "nominal",
            Level::Recommended => "recommended",
        },
    );
    h.push_str("<h2>Criteria</h2>\n");
    h.push_str(&criteria_table(&v.outcomes, info.level));
    h.push_str("<h2>Gamut (CIE 1976 u′v′)</h2>\n");
    h.push_str(&gamut_svg(cal));
    h.push_str("<h2>ΔE00 per patch</h2>\n");
    h.push_str("<div class=\"scroll\">");
    h.push_str(&delta_e_svg(v));
    h.push_str("</div>\n");
    let _ = writeln!(
        h,
        "<h2>Tone curves against {}</h2>",
        escape(&info.tone_target.1)
    );
    h.push_str(&tone_svg(v, &info.tone_target.0));
    h.push_str("</body></html>\n");
    h
}

/// The pass/fail table: one row per criterion.
pub fn criteria_table(outcomes: &[Outcome], level: Level) -> String {
    let mut t = String::from(
        "<table id=\"criteria\"><thead><tr><th>standard</th><th>criterion</th><th>value</th>\
<th>nominal</th><th>recommended</th><th>patches</th><th>result</th></tr></thead><tbody>\n",
    );
    for o in outcomes {
        let c = &o.criterion;
        let (class, result) = match (o.value, o.fails(level)) {
            (None, _) => ("na", "n/a".to_string()),
            (Some(_), true) => ("fail", "FAIL".to_string()),
            (Some(_), false) => (
                "pass",
                match (c.recommended, o.recommended_pass) {
                    (None, _) => "pass".to_string(),
                    (_, Some(true)) => "pass (recommended)".to_string(),
                    _ => "pass (nominal)".to_string(),
                },
            ),
        };
        let _ = writeln!(
            t,
            "<tr data-criterion=\"{id}\" class=\"{class}\"><td>{std}</td><td>{desc}</td>\
<td class=\"num\">{val}</td><td class=\"num\">≤ {nom}</td><td class=\"num\">{rec}</td>\
<td class=\"num\">{n}</td><td class=\"result\">{result}</td></tr>",
            id = c.id,
            std = escape(c.standard),
            desc = escape(c.description),
            val = o.value.map_or("n/a".into(), |v| num(v, 3)),
            nom = c.nominal,
            rec = c.recommended.map_or(String::new(), |r| format!("≤ {r}")),
            n = o.patches,
        );
    }
    t.push_str("</tbody></table>\n");
    t
}

/// The opening tag of a figure `id` with a view box of `width × height`.
fn svg_open(id: &str, width: u32, height: u32) -> String {
    format!(
        "<svg id=\"{id}\" xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {width} {height}\" role=\"img\">"
    )
}

/// Plot area of a figure: `(left, top, width, height)` inside its view box.
struct Frame {
    left: f64,
    top: f64,
    width: f64,
    height: f64,
    x: (f64, f64),
    y: (f64, f64),
}

impl Frame {
    /// A plot area of `width × height` at (60, 15) (room for the axes' labels) showing `x` and
    /// `y`.
    fn new(width: f64, height: f64, x: (f64, f64), y: (f64, f64)) -> Frame {
        Frame {
            left: 60.0,
            top: 15.0,
            width,
            height,
            x,
            y,
        }
    }
    fn px(&self, x: f64) -> f64 {
        self.left + (x - self.x.0) / (self.x.1 - self.x.0) * self.width
    }
    fn py(&self, y: f64) -> f64 {
        self.top + self.height - (y - self.y.0) / (self.y.1 - self.y.0) * self.height
    }
    fn point(&self, p: [f64; 2]) -> String {
        format!("{:.2},{:.2}", self.px(p[0]), self.py(p[1]))
    }
    /// Axes with ticks every `step` and labels.
    fn axes(&self, step: (f64, f64), labels: (&str, &str), digits: usize) -> String {
        let mut s = String::new();
        let _ = write!(
            s,
            "<rect x=\"{:.2}\" y=\"{:.2}\" width=\"{:.2}\" height=\"{:.2}\" fill=\"none\" stroke=\"#888\"/>",
            self.left, self.top, self.width, self.height
        );
        let ticks = |lo: f64, hi: f64, st: f64| {
            let n = ((hi - lo) / st + 1e-9).floor() as usize;
            (0..=n).map(move |i| lo + i as f64 * st)
        };
        for x in ticks(self.x.0, self.x.1, step.0) {
            let _ = write!(
                s,
                "<line x1=\"{px:.2}\" y1=\"{b:.2}\" x2=\"{px:.2}\" y2=\"{b2:.2}\" stroke=\"#888\"/>\
<text x=\"{px:.2}\" y=\"{t:.2}\" font-size=\"12\" text-anchor=\"middle\">{x:.digits$}</text>",
                px = self.px(x),
                b = self.top + self.height,
                b2 = self.top + self.height + 5.0,
                t = self.top + self.height + 18.0,
            );
        }
        for y in ticks(self.y.0, self.y.1, step.1) {
            let _ = write!(
                s,
                "<line x1=\"{l:.2}\" y1=\"{py:.2}\" x2=\"{l2:.2}\" y2=\"{py:.2}\" stroke=\"#888\"/>\
<text x=\"{t:.2}\" y=\"{py4:.2}\" font-size=\"12\" text-anchor=\"end\">{y:.digits$}</text>",
                l = self.left - 5.0,
                l2 = self.left,
                py = self.py(y),
                py4 = self.py(y) + 4.0,
                t = self.left - 8.0,
            );
        }
        let _ = write!(
            s,
            "<text x=\"{:.2}\" y=\"{:.2}\" font-size=\"13\" text-anchor=\"middle\">{}</text>\
<text x=\"12\" y=\"{:.2}\" font-size=\"13\" text-anchor=\"middle\" transform=\"rotate(-90 12 {:.2})\">{}</text>",
            self.left + self.width / 2.0,
            self.top + self.height + 36.0,
            labels.0,
            self.top + self.height / 2.0,
            self.top + self.height / 2.0,
            labels.1
        );
        s
    }
}

/// The u′v′ diagram: spectral locus, the display's gamut, sRGB and Display P3, the white.
pub fn gamut_svg(cal: &Calibration) -> String {
    let f = Frame::new(520.0, 480.0, (0.0, 0.65), (0.0, 0.6));
    let mut s = svg_open("gamut", 880, 550);
    s.push_str(&f.axes((0.1, 0.1), ("u′", "v′"), 1));
    // the spectral locus from the observer table, closed by the purple line
    let t = Observer::Cie1931.table();
    let locus: Vec<[f64; 2]> = (380..=700)
        .map(|nm| {
            let c = t[nm - 380];
            let sum = (c[0] + c[1] + c[2]) as f64;
            uv_prime(c[0] as f64 / sum, c[1] as f64 / sum)
        })
        .collect();
    let pts: Vec<String> = locus.iter().map(|p| f.point(*p)).collect();
    let _ = write!(
        s,
        "<polygon id=\"spectral-locus\" points=\"{}\" fill=\"#f4f4f4\" stroke=\"#222\" stroke-width=\"1.2\"/>",
        pts.join(" ")
    );
    for nm in [460usize, 480, 500, 520, 540, 560, 580, 600, 620] {
        let p = locus[nm - 380];
        let _ = write!(
            s,
            "<text x=\"{:.2}\" y=\"{:.2}\" font-size=\"11\">{nm}</text>",
            f.px(p[0]) + if nm < 510 { -30.0 } else { 6.0 },
            f.py(p[1]) + if nm < 510 { 4.0 } else { 0.0 }
        );
    }
    let tri = |id: &str, xy: [[f64; 2]; 3], style: &str| {
        let p: Vec<String> = xy.iter().map(|c| f.point(uv_prime(c[0], c[1]))).collect();
        format!(
            "<polygon id=\"{id}\" points=\"{}\" fill=\"none\" {style}/>",
            p.join(" ")
        )
    };
    s.push_str(&tri(
        "gamut-srgb",
        SRGB,
        "stroke=\"#1f5fbf\" stroke-width=\"1.5\" stroke-dasharray=\"6 4\"",
    ));
    s.push_str(&tri(
        "gamut-p3",
        DISPLAY_P3,
        "stroke=\"#2a9d4b\" stroke-width=\"1.5\" stroke-dasharray=\"2 3\"",
    ));
    let d = cal.data();
    let prim = d.primaries.array().map(|p| [p.x, p.y]);
    s.push_str(&tri(
        "gamut-display",
        prim,
        "stroke=\"#c0392b\" stroke-width=\"2.2\"",
    ));
    let [wx, wy] = specpoly_core::chromaticity(d.white, d.white);
    let w = uv_prime(wx, wy);
    let _ = write!(
        s,
        "<circle id=\"white-point\" cx=\"{:.2}\" cy=\"{:.2}\" r=\"4\" fill=\"#fff\" stroke=\"#222\"/>",
        f.px(w[0]),
        f.py(w[1])
    );
    let legend = [
        ("#c0392b", "", "this display"),
        ("#1f5fbf", "6 4", "sRGB"),
        ("#2a9d4b", "2 3", "Display P3"),
    ];
    for (i, (c, dash, name)) in legend.iter().enumerate() {
        let y = 40.0 + 22.0 * i as f64;
        let _ = write!(
            s,
            "<line x1=\"600\" y1=\"{y}\" x2=\"640\" y2=\"{y}\" stroke=\"{c}\" stroke-width=\"2\" stroke-dasharray=\"{dash}\"/>\
<text x=\"648\" y=\"{:.1}\" font-size=\"13\">{name}</text>",
            y + 4.0
        );
    }
    let _ = write!(
        s,
        "<circle cx=\"620\" cy=\"106\" r=\"4\" fill=\"#fff\" stroke=\"#222\"/><text x=\"648\" y=\"110\" font-size=\"13\">white (x {wx:.4}, y {wy:.4})</text>"
    );
    for (i, (n, p)) in ["red", "green", "blue"].iter().zip(prim).enumerate() {
        let _ = write!(
            s,
            "<text x=\"600\" y=\"{:.1}\" font-size=\"12\">{n}: x {:.4}, y {:.4}</text>",
            140.0 + 18.0 * i as f64,
            p[0],
            p[1]
        );
    }
    s.push_str("</svg>\n");
    s
}

/// Bars per row of the ΔE00 chart; more patches wrap to further rows.
pub const BARS_PER_ROW: usize = 400;

/// One bar per patch, coloured by the patch, in rows of at most [`BARS_PER_ROW`]. The chart is
/// drawn at its natural size (class `natural`: one unit one CSS pixel, bars at least 2 px wide
/// and 2 px tall
/// on whole pixels), so even a single patch's bar shows in its own colour.
pub fn delta_e_svg(v: &Verification) -> String {
    let n = v.patches.len().max(1);
    let per_row = n.min(BARS_PER_ROW);
    let rows = n.div_ceil(per_row);
    let bar = (800 / per_row).clamp(2, 24) as f64;
    let row_height = if rows == 1 { 300.0 } else { 120.0 };
    let row_step = row_height + 50.0;
    let finite_max = v
        .patches
        .iter()
        .map(|p| p.delta_e00)
        .filter(|d| d.is_finite())
        .fold(0.0f64, f64::max);
    let top_value = (finite_max * 1.05).max(4.5);
    let step = if top_value > 20.0 {
        (top_value / 5.0).ceil()
    } else if top_value > 8.0 {
        2.0
    } else {
        1.0
    };
    let width = 60.0 + bar * per_row as f64 + 20.0;
    let height = 15.0 + row_step * rows as f64;
    let mut s = format!(
        "<svg id=\"delta-e\" class=\"natural\" xmlns=\"http://www.w3.org/2000/svg\" width=\"{width:.0}\" height=\"{height:.0}\" viewBox=\"0 0 {width:.0} {height:.0}\" role=\"img\">"
    );
    for r in 0..rows {
        let first = r * per_row;
        let f = Frame {
            left: 60.0,
            top: 15.0 + r as f64 * row_step,
            width: bar * per_row as f64,
            height: row_height,
            x: (first as f64, (first + per_row) as f64),
            y: (0.0, top_value),
        };
        let _ = write!(
            s,
            "<rect x=\"{:.0}\" y=\"{:.0}\" width=\"{:.0}\" height=\"{:.0}\" fill=\"#dcdcdc\"/>",
            f.left, f.top, f.width, f.height
        );
        for (i, p) in v.patches.iter().enumerate().skip(first).take(per_row) {
            let d = if p.delta_e00.is_finite() {
                p.delta_e00
            } else {
                top_value
            };
            // at least 2 whole pixels tall, so a patch with ΔE00 ≈ 0 still shows its colour
            let bottom = f.top + f.height;
            let h = (bottom - f.py(d.min(top_value))).max(2.0).round();
            let y = bottom - h;
            let _ = write!(
                s,
                "<rect class=\"bar\" data-line=\"{line}\" data-delta-e00=\"{de}\" x=\"{x:.0}\" y=\"{y:.2}\" width=\"{bar:.0}\" height=\"{h:.2}\" fill=\"{c}\"><title>line {line}: RGB {r:.4} {g:.4} {b:.4}, ΔE00 {de}</title></rect>",
                line = p.line,
                de = num(p.delta_e00, 3),
                x = f.px(i as f64),
                c = css_colour(p.device),
                r = p.device[0],
                g = p.device[1],
                b = p.device[2],
            );
        }
        for (val, label, dash) in [
            (1.5, "nominal mean 1.5", "6 4"),
            (4.0, "nominal max 4", "2 3"),
        ] {
            let y = f.py(val);
            let _ = write!(
                s,
                "<line class=\"tolerance\" x1=\"{:.2}\" y1=\"{y:.2}\" x2=\"{:.2}\" y2=\"{y:.2}\" stroke=\"#000\" stroke-dasharray=\"{dash}\"/>\
<text x=\"{:.2}\" y=\"{:.2}\" font-size=\"11\">{label}</text>",
                f.left,
                f.left + f.width,
                f.left + 4.0,
                y - 3.0
            );
        }
        s.push_str(&f.axes((1e9, step), ("patch (file order)", "ΔE00"), 0));
    }
    s.push_str("</svg>\n");
    s
}

/// The measured ramps of one channel (`Some(k)`) or of grey (`None`): `(level, relative
/// luminance above black)`, or nothing when the full-drive patch is missing.
pub fn ramp(v: &Verification, channel: Option<usize>) -> Vec<(f64, f64)> {
    let on = |d: &[f64; 3]| match channel {
        Some(k) => (0..3).all(|j| j == k || d[j] == 0.0),
        None => (d[0] - d[1]).abs() < 1e-6 && (d[1] - d[2]).abs() < 1e-6,
    };
    let level = |d: &[f64; 3]| channel.map_or(d[0], |k| d[k]);
    let mean_y = |pred: &dyn Fn(&[f64; 3]) -> bool| {
        let ys: Vec<f64> = v
            .patches
            .iter()
            .filter(|p| pred(&p.device))
            .map(|p| p.measured[1])
            .collect();
        (!ys.is_empty()).then(|| ys.iter().sum::<f64>() / ys.len() as f64)
    };
    let black = mean_y(&|d: &[f64; 3]| d.iter().all(|&x| x == 0.0)).unwrap_or(0.0);
    let Some(full) = mean_y(&|d: &[f64; 3]| on(d) && level(d) >= 1.0 - 1e-9) else {
        return Vec::new();
    };
    let span = full - black;
    if !(span.is_finite() && span > 0.0) {
        return Vec::new();
    }
    let mut pts: Vec<(f64, f64)> = v
        .patches
        .iter()
        .filter(|p| on(&p.device))
        .map(|p| (level(&p.device), (p.measured[1] - black) / span))
        .filter(|(_, y)| y.is_finite())
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    pts
}

/// Measured tone curves against the target.
pub fn tone_svg(v: &Verification, target: &Transfer) -> String {
    let f = Frame::new(480.0, 400.0, (0.0, 1.0), (0.0, 1.0));
    let mut s = svg_open("tone", 760, 470);
    s.push_str(&f.axes(
        (0.2, 0.2),
        ("device value", "relative luminance above black"),
        1,
    ));
    let curve: Vec<String> = (0..=100)
        .map(|i| {
            let x = i as f64 / 100.0;
            f.point([x, target.decode(x as f32) as f64])
        })
        .collect();
    let _ = write!(
        s,
        "<polyline id=\"tone-target\" points=\"{}\" fill=\"none\" stroke=\"#000\" stroke-width=\"1.5\"/>",
        curve.join(" ")
    );
    let series = [
        (Some(0), "red", "#d62728"),
        (Some(1), "green", "#2ca02c"),
        (Some(2), "blue", "#1f77b4"),
        (None, "grey", "#555555"),
    ];
    for (i, (ch, name, colour)) in series.iter().enumerate() {
        let pts = ramp(v, *ch);
        if !pts.is_empty() {
            let line: Vec<String> = pts
                .iter()
                .map(|(x, y)| f.point([*x, y.clamp(-0.05, 1.1)]))
                .collect();
            let _ = write!(
                s,
                "<polyline class=\"tone-measured\" data-channel=\"{name}\" points=\"{}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"1.2\"/>",
                line.join(" ")
            );
            for (x, y) in &pts {
                let _ = write!(
                    s,
                    "<circle class=\"tone-point\" data-channel=\"{name}\" cx=\"{:.2}\" cy=\"{:.2}\" r=\"2.5\" fill=\"{colour}\"/>",
                    f.px(*x),
                    f.py(y.clamp(-0.05, 1.1))
                );
            }
        }
        let y = 40.0 + 22.0 * i as f64;
        let _ = write!(
            s,
            "<circle cx=\"580\" cy=\"{y}\" r=\"4\" fill=\"{colour}\"/><text x=\"592\" y=\"{:.1}\" font-size=\"13\">{name}{}</text>",
            y + 4.0,
            if pts.is_empty() { " (no ramp)" } else { "" }
        );
    }
    s.push_str(
        "<line x1=\"566\" y1=\"134\" x2=\"594\" y2=\"134\" stroke=\"#000\" stroke-width=\"1.5\"/>\
<text x=\"600\" y=\"138\" font-size=\"13\">target</text></svg>\n",
    );
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uv_of_d65_and_escapes() {
        // CIE 015:2018 Table 9.1: D65 (2°) u′ 0.1978, v′ 0.4683
        let [u, v] = uv_prime(0.31272, 0.32903);
        assert!(
            (u - 0.1978).abs() < 1e-4 && (v - 0.4683).abs() < 1e-4,
            "{u} {v}"
        );
        assert_eq!(escape("a<b & \"c\""), "a&#60;b &#38; &#34;c&#34;");
        assert_eq!(escape("x\u{1b}]0;t\u{7}\ty\n"), "x\\u{1b}]0;t\\u{7}\\ty\n");
        assert_eq!(css_colour([1.0, 0.5, 0.0]), "#ff8000");
        assert_eq!(css_colour([f64::NAN, 2.0, -1.0]), "#00ff00");
    }
}
