//! A one-page ANSI/IES TM-30-20 colour rendition report as self-contained HTML, laid out like
//! the IES TM-30 calculator's report page: the figures (CCT, Duv, Rf, Rg, design intents), the
//! light's spectrum against its reference, the colour vector graphic, the 16 hue bins' chroma
//! shift Rcs,hj, hue shift Rhs,hj and fidelity Rf,hj, and the 99 samples' fidelities Rf,CESi.
//!
//! Inline SVG and CSS only, no script and nothing fetched (`Content-Security-Policy:
//! default-src 'none'`). The spectrum ([`crate::Figure`]) and the graphic
//! ([`VectorGraphic`]) are drawn by `plotters`, as `specpoly plot` and `--cvg` draw them; the
//! bar charts are written here (rects with ids and values: `rect#rcs-1` … `rect#rfces-99`,
//! `data-value`). The page has a fixed layout of [`WIDTH`] × [`HEIGHT`] px, every block
//! absolutely placed (`div#page` sized inline, `div#cvg` at [`CVG_BOX`]), so a screenshot of that size shows it whole
//! and where each figure lands is known. Well-formed XML as well as HTML.

use crate::vector_graphic::{VectorGraphic, BAR_COLOURS, TEST_COLOUR};
use crate::{Figure, Result, Series, Style};
use std::fmt::Write as _;

/// Page width, px.
pub const WIDTH: u32 = 1100;
/// Page height, px.
pub const HEIGHT: u32 = 1340;
/// Where the colour vector graphic is: left, top, side (px).
pub const CVG_BOX: (u32, u32, u32) = (560, 70, 520);

/// What the page shows.
#[derive(Clone, Debug)]
pub struct Tm30Page {
    /// The light's name.
    pub name: String,
    /// The figures table: label, value.
    pub summary: Vec<(String, String)>,
    /// Wavelengths of the spectra, nm.
    pub nm: Vec<f64>,
    /// The test light, relative.
    pub test: Vec<f64>,
    /// The reference, relative.
    pub reference: Vec<f64>,
    /// The colour vector graphic (its size is set to [`CVG_BOX`]'s).
    pub graphic: VectorGraphic,
    /// Rf,hj.
    pub rf_h: [f64; 16],
    /// Rcs,hj in percent.
    pub rcs_h_percent: [f64; 16],
    /// Rhs,hj.
    pub rhs_h: [f64; 16],
    /// Rf,CESi.
    pub rf_ces: Vec<f64>,
    /// Each sample's display colour.
    pub ces_colours: Vec<[u8; 3]>,
    /// Notes under the figures (method, sources).
    pub notes: Vec<String>,
}

use specpoly_formats::escape::markup as escape;

fn hex(c: [u8; 3]) -> String {
    format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}

/// A bar chart: one bar a value from 0 (clamped to `range`), y ticks at `ticks`.
struct Bars<'a> {
    id: &'a str,
    title: &'a str,
    width: f64,
    height: f64,
    values: &'a [f64],
    colours: Vec<[u8; 3]>,
    range: (f64, f64),
    ticks: &'a [f64],
    /// Label under bar `i` (1-based) when this returns `Some`.
    label_every: usize,
    /// Decimals of the values written on the bars (`None`: not written).
    value_digits: Option<usize>,
}

impl Bars<'_> {
    fn svg(&self) -> String {
        let (w, h) = (self.width, self.height);
        let (left, right, top, bottom) = (46.0, 8.0, 26.0, 24.0);
        let (lo, hi) = self.range;
        let y = |v: f64| top + (hi - v.clamp(lo, hi)) / (hi - lo) * (h - top - bottom);
        let slot = (w - left - right) / self.values.len() as f64;
        let mut s = String::new();
        let _ = write!(
            s,
            "<svg id=\"{id}\" xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" \
             viewBox=\"0 0 {w} {h}\" role=\"img\"><text x=\"{x}\" y=\"17\" font-size=\"14\" \
             text-anchor=\"middle\">{title}</text>",
            id = self.id,
            x = w / 2.0,
            title = escape(self.title),
        );
        for &t in self.ticks {
            let _ = write!(
                s,
                "<line x1=\"{left}\" x2=\"{x2}\" y1=\"{yt:.1}\" y2=\"{yt:.1}\" stroke=\"{c}\" \
                 stroke-width=\"1\"/><text x=\"{xl}\" y=\"{yl:.1}\" font-size=\"11\" \
                 text-anchor=\"end\">{t}</text>",
                x2 = w - right,
                yt = y(t),
                c = if t == 0.0 { "#444" } else { "#ddd" },
                xl = left - 4.0,
                yl = y(t) + 4.0,
            );
        }
        for (i, v) in self.values.iter().enumerate() {
            let x = left + slot * (i as f64 + 0.12);
            let (a, b) = (y(0.0f64.clamp(lo, hi)), y(*v));
            let (top_y, bar_h) = (a.min(b), (a - b).abs());
            let _ = write!(
                s,
                "<rect id=\"{id}-{n}\" class=\"bar\" data-value=\"{v}\" x=\"{x:.2}\" \
                 y=\"{top_y:.2}\" width=\"{bw:.2}\" height=\"{bar_h:.2}\" fill=\"{c}\">\
                 <title>{n}: {v:.2}</title></rect>",
                id = self.id,
                n = i + 1,
                bw = 0.76 * slot,
                c = hex(self.colours[i % self.colours.len()]),
            );
            if let Some(d) = self.value_digits {
                let ty = if *v >= 0.0 { b - 3.0 } else { b + 11.0 };
                let _ = write!(
                    s,
                    "<text x=\"{x:.1}\" y=\"{ty:.1}\" font-size=\"10\" \
                     text-anchor=\"middle\">{v:.d$}</text>",
                    x = x + 0.38 * slot,
                );
            }
            if (i + 1) % self.label_every == 0 || i == 0 {
                let _ = write!(
                    s,
                    "<text x=\"{x:.1}\" y=\"{yl}\" font-size=\"11\" \
                     text-anchor=\"middle\">{n}</text>",
                    x = x + 0.38 * slot,
                    yl = h - bottom + 15.0,
                    n = i + 1,
                );
            }
        }
        s.push_str("</svg>");
        s
    }
}

const STYLE: &str = "html,body{margin:0;padding:0;background:#fff;color:#222;\
font-family:sans-serif}#page{position:relative;overflow:hidden}\
.b{position:absolute}svg{display:block}svg text{font-family:sans-serif;fill:#222}\
h1{font-size:20px;margin:0}p.name{font-size:15px;margin:4px 0 0 0}\
table{border-collapse:collapse;font-size:14px}td{border:1px solid #bbb;padding:3px 8px}\
td.num{text-align:right;font-variant-numeric:tabular-nums}\
.notes{font-size:11px;line-height:1.35;color:#444}";

fn block(o: &mut String, id: &str, (left, top, w, h): (u32, u32, u32, u32), inner: &str) {
    let _ = writeln!(
        o,
        "<div class=\"b\" id=\"{id}\" style=\"left:{left}px;top:{top}px;width:{w}px;\
         height:{h}px\">{inner}</div>"
    );
}

impl Tm30Page {
    /// The page.
    pub fn html(&self) -> Result<String> {
        let mut g = self.graphic.clone();
        g.size = CVG_BOX.2;
        let cvg = g.svg()?;
        let spd = Figure {
            width: 520,
            height: 300,
            title: "Spectral power distribution (equal luminous flux)".into(),
            x_label: "wavelength (nm)".into(),
            y_label: "relative power".into(),
            x_range: (380.0, 780.0),
            y_range: Some((0.0, 1.05)),
            series: vec![
                Series {
                    label: Some("reference".into()),
                    colour: [0, 0, 0],
                    style: Style::Line {
                        width: 2.0,
                        dash: None,
                    },
                    points: self
                        .nm
                        .iter()
                        .copied()
                        .zip(self.reference.clone())
                        .collect(),
                },
                Series {
                    label: Some("test".into()),
                    colour: TEST_COLOUR,
                    style: Style::Line {
                        width: 2.0,
                        dash: None,
                    },
                    points: self.nm.iter().copied().zip(self.test.clone()).collect(),
                },
            ],
            markers: vec![],
        }
        .svg()?;
        let bins = BAR_COLOURS.to_vec();
        let bar = |id, title, values: &[f64], range, ticks, digits| {
            Bars {
                id,
                title,
                width: 346.0,
                height: 270.0,
                values,
                colours: bins.clone(),
                range,
                ticks,
                label_every: 1,
                value_digits: Some(digits),
            }
            .svg()
        };
        let rcs = bar(
            "rcs",
            "Local chroma shift Rcs,hj (%)",
            &self.rcs_h_percent,
            (-40.0, 40.0),
            &[-40.0, -30.0, -20.0, -10.0, 0.0, 10.0, 20.0, 30.0, 40.0],
            0,
        );
        let rhs = bar(
            "rhs",
            "Local hue shift Rhs,hj",
            &self.rhs_h,
            (-0.5, 0.5),
            &[-0.5, -0.25, 0.0, 0.25, 0.5],
            2,
        );
        let rfh = bar(
            "rfh",
            "Local colour fidelity Rf,hj",
            &self.rf_h,
            (0.0, 100.0),
            &[0.0, 20.0, 40.0, 60.0, 80.0, 100.0],
            0,
        );
        let ces = Bars {
            id: "rfces",
            title: "Colour fidelity of the 99 samples Rf,CESi",
            width: 1060.0,
            height: 260.0,
            values: &self.rf_ces,
            colours: self.ces_colours.clone(),
            range: (0.0, 100.0),
            ticks: &[0.0, 20.0, 40.0, 60.0, 80.0, 100.0],
            label_every: 5,
            value_digits: None,
        }
        .svg();
        let mut table = String::from("<table id=\"figures\">");
        for (k, v) in &self.summary {
            let _ = write!(
                table,
                "<tr><td>{}</td><td class=\"num\">{}</td></tr>",
                escape(k),
                escape(v)
            );
        }
        table.push_str("</table>");
        let mut notes = String::new();
        for n in &self.notes {
            let _ = write!(notes, "<p>{}</p>", escape(n));
        }
        let mut o = String::new();
        let _ = write!(
            o,
            "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"/>\
<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; style-src 'unsafe-inline'\"/>\
<title>TM-30 report: {name}</title><style>{STYLE}</style></head><body>\
<div id=\"page\" style=\"width:{WIDTH}px;height:{HEIGHT}px\">\n",
            name = escape(&self.name)
        );
        block(
            &mut o,
            "head",
            (20, 12, 1060, 52),
            &format!(
                "<h1>ANSI/IES TM-30-20 colour rendition report</h1><p class=\"name\">{}</p>",
                escape(&self.name)
            ),
        );
        block(&mut o, "summary", (20, 76, 520, 270), &table);
        block(&mut o, "spd", (20, 320, 520, 300), &spd);
        let (l, t, side) = CVG_BOX;
        block(&mut o, "cvg", (l, t, side, side), &cvg);
        block(&mut o, "rcs-chart", (20, 640, 346, 270), &rcs);
        block(&mut o, "rhs-chart", (377, 640, 346, 270), &rhs);
        block(&mut o, "rfh-chart", (734, 640, 346, 270), &rfh);
        block(&mut o, "ces-chart", (20, 925, 1060, 260), &ces);
        block(
            &mut o,
            "notes",
            (20, 1195, 1060, 140),
            &format!("<div class=\"notes\">{notes}</div>"),
        );
        o.push_str("</div></body></html>\n");
        Ok(o)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escapes_and_bars() {
        assert_eq!(escape("a<b & 'c'"), "a&#60;b &#38; &#39;c&#39;");
        let b = Bars {
            id: "x",
            title: "t",
            width: 200.0,
            height: 100.0,
            values: &[10.0, -50.0],
            colours: vec![[255, 0, 0]],
            range: (-40.0, 40.0),
            ticks: &[0.0],
            label_every: 1,
            value_digits: Some(0),
        }
        .svg();
        assert!(b.contains("id=\"x-1\"") && b.contains("data-value=\"-50\""));
        assert!(b.contains("fill=\"#ff0000\""));
    }
}
