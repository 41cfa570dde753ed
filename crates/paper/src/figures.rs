//! The paper's Figures 4 and 5 for any spectra, as a [`Figure`] (drawn by `specpoly plot`):
//!
//! - Figure 4: each spectrum's data points, its fitted piecewise polynomial (drawn span by
//!   span, so any jump at a breakpoint shows) and the span boundaries;
//! - Figure 5 (two spectra): the exact product of the two fitted polynomials
//!   (`Spectrum::mul_exact`, degree `2D` per span, solid) against its reduction back to degree
//!   `D` (`Spectrum::mul`, the paper's eq. 6, dashed), with the product of the data as points.

use crate::{Error, Result};
use specpoly_core::{Breaks, Layout, Spectrum};
use specpoly_plot::size::Size;
use specpoly_plot::{Figure, Series, Style};
use specpoly_spectra::repr::{self, PolyVisitor, Repr};
use specpoly_spectra::spectrum_names::Named;

/// Series colours (Tableau 10); after ten spectra the fitted lines are dashed, after twenty
/// dotted, so 30 spectra are told apart in the legend.
const PALETTE: [[u8; 3]; 10] = [
    [31, 119, 180],
    [214, 39, 40],
    [44, 160, 44],
    [148, 103, 189],
    [255, 127, 14],
    [23, 190, 207],
    [140, 86, 75],
    [227, 119, 194],
    [127, 127, 127],
    [188, 189, 34],
];

/// The fitted line of the `k`-th spectrum: solid, dashed or dotted by the palette's round.
fn fit_style(k: usize) -> Style {
    Style::Line {
        width: 2.0,
        dash: match (k / PALETTE.len()) % 3 {
            0 => None,
            1 => Some(8.0),
            _ => Some(2.0),
        },
    }
}

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
        let fit = |n: &Named| Spectrum::<S, C, L>::fit(&n.tabulated()).map_err(Error::fit(&n.name));
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
                // one legend entry per spectrum (its fitted line); the title says dots are data
                series.push(Series {
                    label: None,
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
                        label: (i == 0).then(|| n.short().to_string()),
                        colour,
                        style: fit_style(k),
                        points: pts,
                    });
                }
            }
        }
        Ok((series, markers))
    }
}

/// The smallest figure `plot` draws.
pub const MIN_SIZE: Size = Size {
    width: 200,
    height: 150,
};
/// The largest figure `plot` draws.
pub const MAX_SIZE: Size = Size {
    width: 8000,
    height: 8000,
};

/// Figure 4 of `named` (or Figure 5 of their product when `product`, which takes exactly two
/// spectra) in the polynomial representation `repr`, `size` pixels.
pub fn spectra(named: &[Named], repr: Repr, product: bool, size: Size) -> Result<Figure> {
    let Size { width, height } = size.check(MIN_SIZE, MAX_SIZE)?;
    if product && named.len() != 2 {
        return Err(Error::ProductNeedsTwo { given: named.len() });
    }
    let (series, markers) = repr::dispatch_poly(repr, "plot", Build { named, product })??;
    let title = if product {
        format!(
            "{} x {}: exact product vs reduced ({repr})",
            named[0].short(),
            named[1].short()
        )
    } else {
        let names: Vec<&str> = named.iter().map(|n| n.short()).collect();
        let names = if names.len() > 3 {
            format!("{} spectra", names.len())
        } else {
            names.join(", ")
        };
        format!("{names}: data (dots) and fitted polynomial (lines, {repr})")
    };
    Ok(Figure {
        width,
        height,
        title,
        x_label: "wavelength (nm)".into(),
        y_label: if product {
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
