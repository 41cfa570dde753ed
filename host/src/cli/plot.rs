//! `specpoly plot`: the paper's Figures 4 and 5 for any spectra.
//!
//! - Figure 4 (default): each spectrum's data points, its fitted piecewise polynomial (drawn
//!   span by span, so any jump at a breakpoint shows) and the span boundaries.
//! - Figure 5 (`--product`, two spectra): the exact product of the two fitted polynomials
//!   (`Spectrum::mul_exact`, degree `2D` per span, solid) against its reduction back to degree
//!   `D` (`Spectrum::mul`, the paper's eq. 6, dashed), with the product of the data as points.
//!
//! The representation defaults to `paper` (2 cubic spans split at 550 nm), as in the figures.
//! Output: SVG or PNG by the file's extension, written atomically.

use crate::colour::{self, PolyVisitor};
use crate::error::{CliError, Result};
use crate::plot::{Figure, Series, Style};
use crate::repr::Repr;
use crate::spectra::{self, Named};
use specpoly_core::{Breaks, Layout, Spectrum};
use std::path::PathBuf;

/// Arguments of `specpoly plot`.
#[derive(Debug, clap::Args)]
pub struct PlotArgs {
    /// Spectra: FILE, FILE#COLUMN, FILE#* or a built-in such as colorchecker#blue.
    #[arg(required = true, value_name = "SPECTRUM")]
    pub spectra: Vec<String>,
    /// Output file: FILE.svg or FILE.png.
    #[arg(short = 'o', long = "output", value_name = "FILE.svg|FILE.png")]
    pub output: PathBuf,
    /// Plot the exact product of two spectra against its reduced polynomial (Figure 5).
    #[arg(long)]
    pub product: bool,
    /// Polynomial representation: paper (default, as in the paper's figures), poly, poly:SxD.
    #[arg(long, default_value = "paper", value_name = "REPR")]
    pub repr: String,
    /// Image size in pixels, WIDTHxHEIGHT.
    #[arg(long, default_value = "900x560", value_name = "WxH")]
    pub size: String,
}

const PALETTE: [[u8; 3]; 6] = [
    [31, 119, 180],
    [214, 39, 40],
    [44, 160, 44],
    [148, 103, 189],
    [255, 127, 14],
    [23, 190, 207],
];

/// What the plot shows, computed for one polynomial type.
struct Build<'a> {
    named: &'a [Named],
    product: bool,
}

/// Points of each span of a spectrum-like function at ≤ 1 nm steps, one polyline per span.
fn span_curves<const S: usize>(
    breaks: &Breaks<S>,
    eval: impl Fn(usize, f32) -> f32,
) -> Vec<Vec<(f64, f64)>> {
    (0..S)
        .map(|s| {
            let (a, b) = breaks.span(s);
            let n = ((b - a).ceil() as usize).max(8);
            (0..=n)
                .map(|i| {
                    let t = -1.0 + 2.0 * i as f32 / n as f32;
                    let nm = 0.5 * (a + b) + 0.5 * (b - a) * t;
                    (nm as f64, eval(s, t) as f64)
                })
                .collect()
        })
        .collect()
}

impl PolyVisitor for Build<'_> {
    type Output = Result<(Vec<Series>, Vec<f64>)>;
    fn visit<const S: usize, const C: usize, L: Layout<S>>(self) -> Self::Output {
        let breaks = L::BREAKS;
        let fit = |n: &Named| {
            Spectrum::<S, C, L>::fit(&n.tabulated())
                .map_err(|e| CliError::data(format!("{}: {e}", n.name)))
        };
        let markers: Vec<f64> = breaks
            .points()
            .skip(1)
            .take(S.saturating_sub(1))
            .map(f64::from)
            .collect();
        let mut series = Vec::new();
        if self.product {
            let (a, b) = (&self.named[0], &self.named[1]);
            let (pa, pb) = (fit(a)?, fit(b)?);
            // C ≤ 6 in every supported layout, so 11 coefficients hold the exact product.
            let exact = pa.mul_exact::<11>(&pb);
            let reduced = pa.mul(&pb);
            // the data product at the first spectrum's wavelengths (and the second's)
            let (ta, tb) = (a.tabulated(), b.tabulated());
            let mut w: Vec<f32> = a
                .wavelengths
                .iter()
                .chain(&b.wavelengths)
                .copied()
                .filter(|w| (380.0..=780.0).contains(w))
                .collect();
            w.sort_by(f32::total_cmp);
            w.dedup();
            series.push(Series {
                label: Some("data product".into()),
                colour: [90, 90, 90],
                style: Style::Points(3.0),
                points: w
                    .iter()
                    .map(|&nm| (nm as f64, ta.at(nm as f64) * tb.at(nm as f64)))
                    .collect(),
            });
            let deg = C - 1;
            for (i, pts) in span_curves(&breaks, |s, t| exact.span(s).eval(t))
                .into_iter()
                .enumerate()
            {
                series.push(Series {
                    label: (i == 0).then(|| format!("exact product, degree {}", 2 * deg)),
                    colour: PALETTE[0],
                    style: Style::Line {
                        width: 2.0,
                        dash: None,
                    },
                    points: pts,
                });
            }
            for (i, pts) in span_curves(&breaks, |s, t| reduced.span(s).eval(t))
                .into_iter()
                .enumerate()
            {
                series.push(Series {
                    label: (i == 0).then(|| format!("reduced to degree {deg} (eq. 6)")),
                    colour: PALETTE[1],
                    style: Style::Line {
                        width: 2.0,
                        dash: Some(8.0),
                    },
                    points: pts,
                });
            }
        } else {
            for (k, n) in self.named.iter().enumerate() {
                let p = fit(n)?;
                let colour = PALETTE[k % PALETTE.len()];
                series.push(Series {
                    label: Some(format!("{} (data)", n.short())),
                    colour,
                    style: Style::Points(3.0),
                    points: n
                        .wavelengths
                        .iter()
                        .zip(&n.values)
                        .map(|(w, v)| (*w as f64, *v as f64))
                        .collect(),
                });
                for (i, pts) in span_curves(&breaks, |s, t| p.span(s).eval(t))
                    .into_iter()
                    .enumerate()
                {
                    series.push(Series {
                        label: (i == 0).then(|| format!("{} (fit)", n.short())),
                        colour,
                        style: Style::Line {
                            width: 2.0,
                            dash: None,
                        },
                        points: pts,
                    });
                }
            }
        }
        Ok((series, markers))
    }
}

enum Format {
    Svg,
    Png,
}

fn parse_size(s: &str) -> Result<(u32, u32)> {
    let bad = || CliError::usage(format!("--size `{s}`: expected WIDTHxHEIGHT, e.g. 900x560"));
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let (w, h): (u32, u32) = (w.parse().map_err(|_| bad())?, h.parse().map_err(|_| bad())?);
    if !(200..=8000).contains(&w) || !(150..=8000).contains(&h) {
        return Err(CliError::usage(format!(
            "--size `{s}`: between 200x150 and 8000x8000"
        )));
    }
    Ok((w, h))
}

/// Builds the figure `plot` draws.
pub fn figure(a: &PlotArgs) -> Result<Figure> {
    let repr: Repr = a.repr.parse()?;
    let (width, height) = parse_size(&a.size)?;
    let named = spectra::resolve_all(&a.spectra)?;
    if a.product && named.len() != 2 {
        return Err(CliError::usage(format!(
            "--product plots the product of two spectra; {} given",
            named.len()
        )));
    }
    let (series, markers) = colour::dispatch_poly(
        repr,
        Build {
            named: &named,
            product: a.product,
        },
    )
    .ok_or_else(|| {
        CliError::usage(format!(
            "`plot` needs a polynomial representation (paper, poly, poly:SxD), not `{repr}`"
        ))
    })??;
    let title = if a.product {
        format!(
            "{} x {}: exact product vs reduced ({repr})",
            named[0].short(),
            named[1].short()
        )
    } else {
        let names: Vec<&str> = named.iter().map(|n| n.short()).collect();
        format!("{}: data and fitted polynomial ({repr})", names.join(", "))
    };
    Ok(Figure {
        width,
        height,
        title,
        x_label: "wavelength (nm)".into(),
        y_label: if a.product {
            "product".into()
        } else {
            "value".into()
        },
        x_range: (380.0, 780.0),
        y_range: None,
        series,
        markers,
    })
}

/// Runs `specpoly plot`.
pub fn run(a: &PlotArgs) -> Result<()> {
    let ext = a
        .output
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let format = match ext.as_deref() {
        Some("svg") => Format::Svg,
        Some("png") => Format::Png,
        _ => {
            return Err(CliError::usage(format!(
                "{}: the output must end in .svg or .png",
                a.output.display()
            )))
        }
    };
    let fig = figure(a)?;
    let bytes = match format {
        Format::Svg => fig.svg().into_bytes(),
        Format::Png => fig
            .png()
            .map_err(|e| CliError::data(format!("PNG encoding: {e}")))?,
    };
    crate::io::atomic::write(&a.output, &bytes)?;
    eprintln!("wrote {}", a.output.display());
    Ok(())
}
