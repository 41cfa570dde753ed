//! `specpoly light`: colorimetry and colour rendering of a light source's SPD
//! (computations in [`specpoly_spectra::light`] and `specpoly_core::light`).

use crate::error::Result;
use specpoly_formats::stdout::print_json;
use specpoly_spectra::light::{report, LightReport};
use specpoly_spectra::spectrum_names;
use std::fmt::Write as _;
use std::path::PathBuf;

/// Arguments of `specpoly light`.
#[derive(Debug, clap::Args)]
pub struct LightArgs {
    /// The light's spectral power distribution: FILE.csv, FILE.csv#COLUMN, or a built-in
    /// illuminant (A, D50, D65, E, FL2, FL7, FL11).
    #[arg(value_name = "SPD")]
    pub spd: String,
    /// Print JSON: {X, Y, Z, x, y, u_prime, v_prime, cct, duv, ra, r9, rf, rg} (and
    /// extrapolated_from_nm when --extrapolate was needed).
    #[arg(long)]
    pub json: bool,
    /// A light tabulated over less than 380-780 nm: hold its end values to that range (CIE
    /// 015:2018's extrapolation) instead of refusing it; the output says so.
    #[arg(long)]
    pub extrapolate: bool,
    /// ANSI/IES TM-30-20 in full: the 16 hue bins (Rf,hj, Rcs,hj, Rhs,hj, mean a', b', the
    /// colour vector graphic's points), the 99 samples' Rf,CESi and the Annex E design intents;
    /// with --json under the key "tm30".
    #[arg(long)]
    pub tm30: bool,
    /// Write TM-30's colour vector graphic: FILE.svg or FILE.png.
    #[arg(long, value_name = "FILE.svg|FILE.png")]
    pub cvg: Option<PathBuf>,
    /// Write a one-page TM-30 report: FILE.html (self-contained), or FILE.png (a screenshot of
    /// that page by headless Chromium).
    #[arg(long, value_name = "FILE.html|FILE.png")]
    pub report: Option<PathBuf>,
}

/// `v` to `prec` decimals, `-` for none.
pub(crate) fn opt(v: Option<f64>, prec: usize) -> String {
    v.map_or("-".to_string(), |v| format!("{v:.prec$}"))
}

/// The heads of the chromaticity columns the light and mix tables share.
pub(crate) fn chromaticity_head() -> String {
    format!(
        "{:>7} {:>7} {:>7} {:>7} {:>8} {:>8}",
        "x", "y", "u'", "v'", "cct", "duv"
    )
}

/// The cells under [`chromaticity_head`]: x, y, u′, v′ (`xyuv`), CCT and Duv.
pub(crate) fn chromaticity_cells(xyuv: [f64; 4], cct: Option<f64>, duv: Option<f64>) -> String {
    let [x, y, u, v] = xyuv;
    format!(
        "{x:>7.4} {y:>7.4} {u:>7.4} {v:>7.4} {:>8} {:>8}",
        opt(cct, 1),
        opt(duv, 5)
    )
}

/// Formats the text output.
pub fn text(name: &str, r: &LightReport) -> String {
    let mut o = String::new();
    if let Some([lo, hi]) = r.extrapolated_from_nm {
        let _ = writeln!(
            o,
            "# {name}: tabulated over {lo}-{hi} nm, extrapolated to 380-780 nm by holding the \
             end values (CIE 015:2018)"
        );
    }
    let _ = writeln!(
        o,
        "# {name}: XYZ = Km·ΣS·x̄Δλ (CIE 1931; lm for Y when the SPD is in W/nm); CCT, Duv; CIE 13.3 \
         Ra, R9; CIE 224:2017 Rf, TM-30 Rg ('-': more than 0.05 Duv from the Planckian locus)"
    );
    let _ = writeln!(
        o,
        "{:>12} {:>12} {:>12} {} {:>6} {:>7} {:>6} {:>6}",
        "X",
        "Y",
        "Z",
        chromaticity_head(),
        "ra",
        "r9",
        "rf",
        "rg"
    );
    let _ = writeln!(
        o,
        "{:>12.4} {:>12.4} {:>12.4} {} {:>6} {:>7} {:>6} {:>6}",
        r.big_x,
        r.big_y,
        r.big_z,
        chromaticity_cells([r.x, r.y, r.u_prime, r.v_prime], r.cct, r.duv),
        opt(r.ra, 1),
        opt(r.r9, 1),
        opt(r.rf, 1),
        opt(r.rg, 1)
    );
    o
}

/// Runs `specpoly light`.
pub fn run(a: &LightArgs) -> Result<()> {
    let named = spectrum_names::light(&a.spd)?;
    let r = report(&named, a.extrapolate)?;
    if a.tm30 || a.cvg.is_some() || a.report.is_some() {
        let t = super::light_tm30::Tm30Args {
            print: a.tm30,
            json: a.json,
            cvg: a.cvg.as_deref(),
            report: a.report.as_deref(),
            extrapolate: a.extrapolate,
        };
        super::light_tm30::run(&named, &r, &t)?;
        if a.tm30 {
            return Ok(());
        }
    }
    if a.json {
        return Ok(print_json(&r)?);
    }
    Ok(specpoly_formats::stdout::print(&text(&named.name, &r))?)
}
