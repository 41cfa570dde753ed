//! `specpoly fit`: fit spectra by a polynomial representation and show what the fit costs:
//! the Chebyshev coefficients per span, the RMS and max error at the data samples in each span
//! ([`specpoly_core::Spectrum::fit_errors`]) and the fit's CIEDE2000 against the 1 nm reference
//! under a chosen light (the light itself is never fitted).

use crate::cli::xyz::parse_observer;
use crate::colour::{self, PolyVisitor};
use crate::error::{CliError, Result};
use crate::repr::Repr;
use crate::spectra::{self, Named};
use serde::Serialize;
use specpoly_core::{Layout, Observer, Spectrum, Tabulated};
use std::fmt::Write as _;

/// Arguments of `specpoly fit`.
#[derive(Debug, clap::Args)]
pub struct FitArgs {
    /// Spectra: FILE, FILE#COLUMN, FILE#* or a built-in such as colorchecker#foliage.
    #[arg(required = true, value_name = "SPECTRUM")]
    pub spectra: Vec<String>,
    /// Polynomial representation: poly, paper or poly:SxD.
    #[arg(long, default_value = "poly", value_name = "REPR")]
    pub repr: String,
    /// The light for the fit's colour error: A, D50, D65, E, FL2, FL7, FL11, or FILE.
    #[arg(long, short = 'i', default_value = "D65", value_name = "NAME|FILE")]
    pub illuminant: String,
    /// Standard observer for the colour error: 1931 or 1964.
    #[arg(long, default_value = "1964", value_name = "1931|1964")]
    pub observer: String,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

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
    let spans = colour::dispatch_poly(repr, FitOne { data })
        .ok_or_else(|| {
            CliError::usage(format!(
                "`fit` needs a polynomial representation (poly, paper, poly:SxD), not `{repr}`"
            ))
        })?
        .map_err(|e| CliError::data(format!("{}: {e}", n.name)))?;
    let tabs = [data];
    let got = colour::chains(repr, observer, light, &tabs, &[vec![0]])
        .map_err(|e| CliError::data(format!("{}: {e}", n.name)))?;
    let want = colour::reference(observer, light, &tabs, &[0]);
    Ok(FitReport {
        name: n.name.clone(),
        repr: repr.to_string(),
        spans,
        delta_e00: want.delta_e(&got[0]),
    })
}

/// Runs `specpoly fit`.
pub fn run(a: &FitArgs) -> Result<()> {
    let repr: Repr = a.repr.parse()?;
    if !matches!(repr, Repr::Poly { .. } | Repr::Paper) {
        return Err(CliError::usage(format!(
            "`fit` needs a polynomial representation (poly, paper, poly:SxD), not `{repr}`"
        )));
    }
    let observer = parse_observer(&a.observer)?;
    let light = spectra::light(&a.illuminant)?;
    let named = spectra::resolve_all(&a.spectra)?;
    let reports = named
        .iter()
        .map(|n| fit_one(n, repr, observer, &light.tabulated()))
        .collect::<Result<Vec<_>>>()?;
    if a.json {
        let s = serde_json::to_string_pretty(&reports)
            .map_err(|e| CliError::data(format!("JSON: {e}")))?;
        return crate::io::stdout::print(&format!("{s}\n"));
    }
    let mut o = String::new();
    for r in &reports {
        let _ = writeln!(
            o,
            "{}  ({}; ΔE00 of the fit under {}, CIE {}: {:.4})",
            r.name, r.repr, a.illuminant, a.observer, r.delta_e00
        );
        let _ = writeln!(
            o,
            "  {:>11}  {:>9} {:>9} {:>3}  Chebyshev coefficients c0..cD (t in [-1, 1])",
            "span nm", "rms", "max", "n"
        );
        for s in &r.spans {
            let c: Vec<String> = s.coefficients.iter().map(|v| format!("{v:+.6}")).collect();
            let _ = writeln!(
                o,
                "  {:>5}-{:<5}  {:>9.2e} {:>9.2e} {:>3}  {}",
                s.from_nm,
                s.to_nm,
                s.rms,
                s.max,
                s.samples,
                c.join(" ")
            );
        }
    }
    crate::io::stdout::print(&o)
}
