//! `specpoly light`: colorimetry and colour rendering of a light source's SPD
//! (computations in [`specpoly_spectra::light`] and `specpoly_core::light`).

use crate::error::Result;
use specpoly_formats::stdout::print_json;
use specpoly_spectra::light::{report, LightReport};
use specpoly_spectra::spectrum_names::{self, Named};
use std::fmt::Write as _;
use std::path::PathBuf;

/// Arguments of `specpoly light`.
#[derive(Debug, clap::Args)]
pub struct LightArgs {
    /// The lights' spectral power distributions: FILE.csv, FILE.csv#COLUMN, FILE.csv#* (every
    /// column), or a built-in illuminant (A, D50, D65, E, FL2, FL7, FL11). Several lights print
    /// one row each.
    #[arg(value_name = "SPD", required = true, num_args = 1..)]
    pub spd: Vec<String>,
    /// Print JSON: {X, Y, Z, x, y, u_prime, v_prime, cct, duv, ra, r9, rf, rg, ri (R1-R14), r15,
    /// peak_nm, fwhm_nm, dominant_nm, purity, edi_* and der_* (CIE S 026: sc, mc, lc, rh, mel),
    /// ansi_c78377, ja8, ja8_fails} (and extrapolated_from_nm when --extrapolate was needed);
    /// several lights as JSON Lines, one object a light with its "name" first.
    #[arg(long, conflicts_with = "csv")]
    pub json: bool,
    /// Print CSV (RFC 4180): a header, then one row a light with its name first; an empty cell
    /// where a metric is undefined.
    #[arg(long)]
    pub csv: bool,
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
    /// Also the light's XYZ, xy and u′v′ under this observer (1931, 1964, 2015-2, 2015-10,
    /// cie2006:age=A,field=F or FILE.csv): a line after the metrics, with --json under the key
    /// "observer". CCT, Duv, Ra and Rf stay on the observers their standards fix.
    #[arg(long, value_name = "NAME|FILE", value_parser = super::args::observer, conflicts_with = "csv")]
    pub observer: Option<specpoly_core::Observer>,
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
    let name = specpoly_formats::escape::one_line(name);
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
    o += &observer_line(&name, r);
    o += &details(r);
    o
}

/// The spectrum's shape and hue, CIE 13.3 R1-R14 and R15, CIE S 026 and the standards' checks.
fn details(r: &LightReport) -> String {
    let c = &r.checks;
    let mut o = String::new();
    let dom = match c.dominant_nm {
        Some(d) if d < 0.0 => format!("complementary wavelength {:.1} nm", -d),
        Some(d) => format!("dominant wavelength {d:.1} nm"),
        None => "no dominant wavelength".into(),
    };
    let _ = writeln!(
        o,
        "# spectrum: peak {:.0} nm, FWHM {}, {dom}, excitation purity {} (CIE 015, against E)",
        c.peak_nm,
        c.fwhm_nm
            .map_or("- (broad band)".into(), |w| format!("{w:.1} nm")),
        opt(c.purity, 4)
    );
    if let Some(ri) = c.ri {
        let list: Vec<String> = ri
            .iter()
            .enumerate()
            .map(|(i, v)| format!("R{} {v:.1}", i + 1))
            .collect();
        let r15 = c
            .r15
            .map_or(String::new(), |v| format!("; JIS Z 8726: R15 {v:.1}"));
        let _ = writeln!(o, "# CIE 13.3: {}{r15}", list.join(", "));
    }
    let _ = writeln!(
        o,
        "# CIE S 026 (the SPD as W/m2/nm): alpha-opic EDI (lx) and DER: s-cone {:.4} / {:.4}, \
         m-cone {:.4} / {:.4}, l-cone {:.4} / {:.4}, rhodopic {:.4} / {:.4}, melanopic {:.4} / {:.4}",
        c.edi_sc, c.der_sc, c.edi_mc, c.der_mc, c.edi_lc, c.der_lc, c.edi_rh, c.der_rh, c.edi_mel,
        c.der_mel
    );
    let _ = writeln!(o, "{:<62} {:>22}  result", "check", "figure");
    for [clause, figure, result] in specpoly_spectra::light::check_lines(r) {
        let _ = writeln!(o, "{clause:<62} {figure:>22}  {result}");
    }
    o
}

/// The line of `--observer`: the light's colour under that observer (empty without it).
fn observer_line(name: &str, r: &LightReport) -> String {
    r.observer.as_ref().map_or(String::new(), |c| {
        format!(
            "# {name} under observer {}: X {:.4} Y {:.4} Z {:.4}, x {:.6} y {:.6}, u' {:.6} v' {:.6}\n",
            specpoly_formats::escape::one_line(&c.name),
            c.big_x,
            c.big_y,
            c.big_z,
            c.x,
            c.y,
            c.u_prime,
            c.v_prime
        )
    })
}

/// One light's report with its name first (JSON Lines).
#[derive(serde::Serialize)]
struct NamedReport<'a> {
    name: &'a str,
    #[serde(flatten)]
    report: &'a LightReport,
}

/// The table of several lights: one row each, the name first.
pub fn table(rows: &[(Named, LightReport)]) -> String {
    let width = rows
        .iter()
        .map(|(n, _)| n.name.len())
        .max()
        .unwrap_or(4)
        .max(4);
    let mut o = String::new();
    let _ = writeln!(
        o,
        "# XYZ = Km·ΣS·x̄Δλ (CIE 1931); CCT, Duv; CIE 13.3 Ra, R9; CIE 224:2017 Rf, TM-30 Rg \
         ('-': more than 0.05 Duv from the Planckian locus; '*': extrapolated to 380-780 nm); \
         peak, FWHM, dominant wavelength (nm; negative: complementary); CIE S 026 melanopic \
         DER; the ANSI C78.377-2017 quadrangle; JA8's colour clauses"
    );
    let _ = writeln!(
        o,
        "{:width$} {:>12} {} {:>6} {:>7} {:>6} {:>6} {:>5} {:>6} {:>7} {:>7} {:>5} {:>4}",
        "name",
        "Y",
        chromaticity_head(),
        "ra",
        "r9",
        "rf",
        "rg",
        "peak",
        "fwhm",
        "dom",
        "mel_der",
        "ansi",
        "ja8"
    );
    for (n, r) in rows {
        let name = format!(
            "{}{}",
            specpoly_formats::escape::one_line(&n.name),
            if r.extrapolated_from_nm.is_some() {
                "*"
            } else {
                ""
            }
        );
        let _ = writeln!(
            o,
            "{name:width$} {:>12.4} {} {:>6} {:>7} {:>6} {:>6} {:>5.0} {:>6} {:>7} {:>7.4} {:>5} {:>4}",
            r.big_y,
            chromaticity_cells([r.x, r.y, r.u_prime, r.v_prime], r.cct, r.duv),
            opt(r.ra, 1),
            opt(r.r9, 1),
            opt(r.rf, 1),
            opt(r.rg, 1),
            r.checks.peak_nm,
            opt(r.checks.fwhm_nm, 1),
            opt(r.checks.dominant_nm, 1),
            r.checks.der_mel,
            r.checks.ansi_c78377.map_or("-".into(), |k| k.to_string()),
            r.checks.ja8.map_or("-", |p| if p { "pass" } else { "fail" })
        );
    }
    for (n, r) in rows {
        o += &observer_line(&specpoly_formats::escape::one_line(&n.name), r);
    }
    o
}

/// The CSV of the lights: a header, one row a light.
pub fn csv(rows: &[(Named, LightReport)]) -> Result<String> {
    let mut w = csv::Writer::from_writer(Vec::new());
    let cell = |v: Option<f64>| v.map_or(String::new(), |v| v.to_string());
    let head = [
        "name",
        "X",
        "Y",
        "Z",
        "x",
        "y",
        "u_prime",
        "v_prime",
        "cct",
        "duv",
        "ra",
        "r9",
        "rf",
        "rg",
        "extrapolated_from_nm",
        "r1",
        "r2",
        "r3",
        "r4",
        "r5",
        "r6",
        "r7",
        "r8",
        "r10",
        "r11",
        "r12",
        "r13",
        "r14",
        "r15",
        "peak_nm",
        "fwhm_nm",
        "dominant_nm",
        "purity",
        "edi_sc",
        "edi_mc",
        "edi_lc",
        "edi_rh",
        "edi_mel",
        "der_sc",
        "der_mc",
        "der_lc",
        "der_rh",
        "der_mel",
        "ansi_c78377",
        "ja8",
        "ja8_fails",
    ];
    let io = |e: csv::Error| crate::error::CliError::Data(e.to_string());
    w.write_record(head).map_err(io)?;
    for (n, r) in rows {
        let ext = r
            .extrapolated_from_nm
            .map_or(String::new(), |[lo, hi]| format!("{lo}-{hi}"));
        let c = &r.checks;
        let mut ri: Vec<String> = (0..14)
            .filter(|i| *i != 8)
            .map(|i| cell(c.ri.map(|ri| ri[i])))
            .collect();
        let more = [
            cell(c.r15),
            c.peak_nm.to_string(),
            cell(c.fwhm_nm),
            cell(c.dominant_nm),
            cell(c.purity),
            c.edi_sc.to_string(),
            c.edi_mc.to_string(),
            c.edi_lc.to_string(),
            c.edi_rh.to_string(),
            c.edi_mel.to_string(),
            c.der_sc.to_string(),
            c.der_mc.to_string(),
            c.der_lc.to_string(),
            c.der_rh.to_string(),
            c.der_mel.to_string(),
            c.ansi_c78377.map_or(String::new(), |k| k.to_string()),
            c.ja8.map_or(String::new(), |p| p.to_string()),
            c.ja8_fails.join(";"),
        ];
        ri.extend(more);
        let mut record = vec![
            n.name.clone(),
            r.big_x.to_string(),
            r.big_y.to_string(),
            r.big_z.to_string(),
            r.x.to_string(),
            r.y.to_string(),
            r.u_prime.to_string(),
            r.v_prime.to_string(),
            cell(r.cct),
            cell(r.duv),
            cell(r.ra),
            cell(r.r9),
            cell(r.rf),
            cell(r.rg),
            ext,
        ];
        record.extend(ri);
        w.write_record(record).map_err(io)?;
    }
    let bytes = w
        .into_inner()
        .map_err(|e| crate::error::CliError::Data(e.to_string()))?;
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}

/// Runs `specpoly light`.
pub fn run(a: &LightArgs) -> Result<()> {
    let mut rows = Vec::new();
    for spec in &a.spd {
        for named in spectrum_names::lights(spec)? {
            let mut r = report(&named, a.extrapolate)?;
            if let Some(o) = a.observer {
                let s = specpoly_spectra::light::standard_spd(&named, a.extrapolate)?;
                r.observer = Some(specpoly_spectra::light::observer_colour(&s, o));
            }
            rows.push((named, r));
        }
    }
    let single = a.spd.len() == 1 && !a.spd[0].ends_with("#*");
    if a.tm30 || a.cvg.is_some() || a.report.is_some() {
        if !single || rows.len() != 1 {
            return Err(crate::error::CliError::usage(
                "--tm30, --cvg and --report take one light",
            ));
        }
        let t = super::light_tm30::Tm30Args {
            print: a.tm30,
            json: a.json,
            cvg: a.cvg.as_deref(),
            report: a.report.as_deref(),
            extrapolate: a.extrapolate,
        };
        super::light_tm30::run(&rows[0].0, &rows[0].1, &t)?;
        if a.tm30 {
            return Ok(());
        }
    }
    let out = match (a.json, a.csv, single) {
        (true, _, true) => return Ok(print_json(&rows[0].1)?),
        (true, _, false) => {
            let mut o = String::new();
            for (n, r) in &rows {
                let line = serde_json::to_string(&NamedReport {
                    name: &n.name,
                    report: r,
                })
                .map_err(|e| crate::error::CliError::Data(e.to_string()))?;
                o += &line;
                o.push('\n');
            }
            o
        }
        (false, true, _) => csv(&rows)?,
        (false, false, true) => text(&rows[0].0.name, &rows[0].1),
        (false, false, false) => table(&rows),
    };
    Ok(specpoly_formats::stdout::print(&out)?)
}
