//! The fit of a spectrum by a polynomial representation and what it costs (printed by
//! `specpoly fit`): the Chebyshev coefficients per span, the RMS and max error at the data samples in each span
//! ([`specpoly_core::Spectrum::fit_errors`]) and the fit's CIEDE2000 against the 1 nm reference
//! under a chosen light (the light itself is never fitted).

use crate::{Error, Result};
use serde::Serialize;
use specpoly_core::{Layout, Observer, Spectrum, Tabulated};
use specpoly_spectra::colour;
use specpoly_spectra::repr::{self, PolyVisitor, Repr};
use specpoly_spectra::spectrum_names::Named;

/// One span of a fit.
#[derive(Clone, Debug, Serialize)]
pub struct SpanFit {
    /// Start (nm).
    pub from_nm: f32,
    /// End (nm).
    pub to_nm: f32,
    /// Chebyshev coefficients `c₀ … c_D` in the span's `t ∈ [-1, 1]`.
    pub coefficients: Vec<f32>,
    /// RMS error at the data samples inside the span.
    pub rms: f32,
    /// Max absolute error at the data samples inside the span.
    pub max: f32,
    /// Number of data samples inside the span.
    pub samples: u32,
}

/// The fit of one spectrum.
#[derive(Clone, Debug, Serialize)]
pub struct FitReport {
    /// The spectrum.
    pub name: String,
    /// The representation.
    pub repr: String,
    /// Per span.
    pub spans: Vec<SpanFit>,
    /// CIEDE2000 of the fitted spectrum against the data, as a reflectance under the light.
    pub delta_e00: f64,
}

struct FitOne<'a> {
    data: Tabulated<'a>,
}

impl PolyVisitor for FitOne<'_> {
    type Output = Result<Vec<SpanFit>, specpoly_core::Error>;
    fn visit<const S: usize, const C: usize, L: Layout<S>>(self) -> Self::Output {
        let breaks = L::BREAKS;
        let p = Spectrum::<S, C, L>::fit(&self.data)?;
        let e = p.fit_errors(&self.data);
        Ok((0..S)
            .map(|s| {
                let (a, b) = breaks.span(s);
                SpanFit {
                    from_nm: a,
                    to_nm: b,
                    coefficients: p.span(s).c.to_vec(),
                    rms: e.rms[s],
                    max: e.max[s],
                    samples: e.count[s],
                }
            })
            .collect())
    }
}

/// Fits one spectrum.
pub fn fit_one(
    n: &Named,
    repr: Repr,
    observer: Observer,
    light: &Tabulated<'_>,
) -> Result<FitReport> {
    let data = n.tabulated();
    let spans = repr::dispatch_poly(repr, "fit", FitOne { data })?.map_err(Error::fit(&n.name))?;
    let tabs = [data];
    let got =
        colour::chains(repr, observer, light, &tabs, &[vec![0]]).map_err(Error::fit(&n.name))?;
    let want = colour::reference(observer, light, &tabs, &[0]);
    Ok(FitReport {
        name: n.name.clone(),
        repr: repr.to_string(),
        spans,
        delta_e00: want.delta_e(&got[0]),
    })
}
