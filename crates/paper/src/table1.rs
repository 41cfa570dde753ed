//! The paper's Table 1 on our data (printed by `specpoly table1`, in `docs/accuracy.md`).
//!
//! Raso & Fournier (1991, §6.2, Table 1) give, per span of their 2-cubic layout (split at
//! 550 nm), the error of (1) fitting a cubic to a reflectance (a green shingle), (2) fitting a
//! cubic to the colour matching function x̄ (CIE 1964) and (3) reducing the degree-6 product of
//! those two cubics back to a cubic (eq. 6). The paper does not say which error measure it
//! uses; its magnitudes (3.5e-5 for a smooth reflectance whose values are ~0.1, 2e-2 for x̄,
//! whose values reach ~1.1) fit a **mean squared error**, and that is what we print: the mean
//! over a 10 nm grid of wavelengths in the span (the paper's data were at 10 nm, §5.2 note 6),
//! ends included, of `(approximation − target)²`, where the target is
//! 1. the tabulated reflectance (its samples that fall in the span; ColorChecker data stop at
//!    730 nm),
//! 2. the tabulated x̄ (1 nm CIE table), against `core::paper::cmf_fit`,
//! 3. the exact degree-6 product `r · x̄_fit` (`Spectrum::mul_exact`), against its reduction
//!    (`Spectrum::mul`, eq. 6 as a Chebyshev truncation).
//!
//! We do not have the green shingle; the default is `colorchecker#foliage`, a natural green.

use crate::{Error, Result};
use serde::Serialize;
use specpoly_core::{paper::cmf_fit, Observer, Paper, PaperSpectrum, Spectrum, PAPER_BREAKS};
use specpoly_spectra::spectrum_names;

/// The paper's Table 1: per span, reflectance, x̄ and reduced errors.
pub const PAPER: [[f64; 3]; 2] = [
    [3.532443e-5, 6.953191e-3, 4.819727e-6],
    [2.381345e-6, 2.124504e-2, 3.651482e-6],
];

/// One row of the table.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    /// Span start and end (nm).
    pub span_nm: [f32; 2],
    /// Mean squared error of the reflectance's cubic fit.
    pub reflectance: f64,
    /// Mean squared error of x̄'s cubic fit.
    pub xbar: f64,
    /// Mean squared error of the reduced product against the exact product.
    pub reduced: f64,
    /// The paper's three numbers for this span.
    pub paper: [f64; 3],
}

impl Row {
    /// Ours and the paper's, side by side: reflectance, paper, x̄, paper, reduced, paper.
    pub fn cells(&self) -> [f64; 6] {
        [
            self.reflectance,
            self.paper[0],
            self.xbar,
            self.paper[1],
            self.reduced,
            self.paper[2],
        ]
    }
}

/// Computes the table for one spectrum.
pub fn compute(spec: &str) -> Result<(String, Vec<Row>)> {
    let mut v = spectrum_names::resolve(spec)?;
    if v.len() != 1 {
        return Err(Error::NotOneSpectrum {
            spec: spec.to_string(),
            count: v.len(),
        });
    }
    let n = v.remove(0);
    let data = n.tabulated();
    let r = PaperSpectrum::fit(&data).map_err(Error::fit(&n.name))?;
    let observer = Observer::Cie1964;
    let [xbar, _, _] = cmf_fit::<2, 4, Paper>(observer);
    let exact: Spectrum<2, 7, Paper> = r.mul_exact::<7>(&xbar);
    let reduced = r.mul(&xbar);
    let mse = |pts: &mut dyn Iterator<Item = (f64, f64)>| {
        let (mut s, mut k) = (0.0, 0usize);
        for (a, b) in pts {
            s += (a - b) * (a - b);
            k += 1;
        }
        if k == 0 {
            f64::NAN
        } else {
            s / k as f64
        }
    };
    let rows = (0..2)
        .map(|s| {
            let (a, b) = PAPER_BREAKS.span(s);
            let t = |nm: f32| (2.0 * nm - (a + b)) / (b - a);
            let grid: Vec<f32> = (0..=40)
                .map(|i| 380.0 + 10.0 * i as f32)
                .filter(|nm| *nm >= a && *nm <= b)
                .collect();
            let refl = mse(&mut data
                .wavelengths()
                .iter()
                .zip(data.values())
                .filter(|(w, _)| **w >= a && **w <= b)
                .map(|(w, v)| (r.span(s).eval(t(*w)) as f64, *v as f64)));
            let xb = mse(&mut grid.iter().map(|nm| {
                (
                    xbar.span(s).eval(t(*nm)) as f64,
                    observer.cmf_at(*nm as f64)[0],
                )
            }));
            let red = mse(&mut grid.iter().map(|nm| {
                (
                    reduced.span(s).eval(t(*nm)) as f64,
                    exact.span(s).eval(t(*nm)) as f64,
                )
            }));
            Row {
                span_nm: [a, b],
                reflectance: refl,
                xbar: xb,
                reduced: red,
                paper: PAPER[s],
            }
        })
        .collect();
    Ok((n.name, rows))
}
