//! `specpoly fit`: fits spectra by a polynomial representation and prints what the fit costs
//! ([`specpoly_paper::fit_report`]): coefficients, per-span errors and the fit's ΔE00.

use crate::cli::args::Colorimetry;
use crate::error::Result;
use specpoly_formats::stdout::print_json;
use specpoly_paper::fit_report::fit_one;
use specpoly_spectra::repr::Repr;
use specpoly_spectra::spectrum_names;
use std::fmt::Write as _;

/// Arguments of `specpoly fit`.
#[derive(Debug, clap::Args)]
pub struct FitArgs {
    /// Spectra: FILE, FILE#COLUMN, FILE#* or a built-in such as colorchecker#foliage.
    #[arg(required = true, value_name = "SPECTRUM")]
    pub spectra: Vec<String>,
    /// Polynomial representation: poly, paper or poly:SxD.
    #[arg(long, default_value = "poly", value_name = "REPR")]
    pub repr: Repr,
    /// The light and the observer of the fit's colour error.
    #[command(flatten)]
    pub colorimetry: Colorimetry,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
    /// Multiply every spectrum by FACTOR first (0.01 for reflectances in percent).
    #[arg(long, default_value_t = 1.0, value_name = "FACTOR")]
    pub scale: f64,
}

/// Runs `specpoly fit`.
pub fn run(a: &FitArgs) -> Result<()> {
    let repr = a.repr.polynomial_for("fit")?;
    let Colorimetry {
        illuminant,
        observer,
    } = &a.colorimetry;
    let light = spectrum_names::light(illuminant)?;
    let named = specpoly_spectra::plausible::reflectances(&a.spectra, a.scale, true)?;
    let reports = named
        .iter()
        .map(|n| fit_one(n, repr, *observer, &light.tabulated()))
        .collect::<Result<Vec<_>, _>>()?;
    if a.json {
        return Ok(print_json(&reports)?);
    }
    let mut o = String::new();
    for r in &reports {
        let _ = writeln!(
            o,
            "{}  ({}; ΔE00 of the fit under {}, CIE {}: {:.4})",
            r.name,
            r.repr,
            illuminant,
            observer.name(),
            r.delta_e00
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
    Ok(specpoly_formats::stdout::print(&o)?)
}
