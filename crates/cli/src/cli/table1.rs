//! `specpoly table1`: prints the paper's Table 1 on our data ([`specpoly_paper::table1`]).

use crate::error::Result;
use specpoly_formats::stdout::print_json;
use specpoly_paper::table1::compute;
use std::fmt::Write as _;

/// Arguments of `specpoly table1`.
#[derive(Debug, clap::Args)]
#[command(
    after_help = "Error measure (the paper does not state one): the mean squared error \
over a 10 nm grid in each span, ends included (the reflectance: at its own samples in the span). \
Columns: the reflectance's cubic fit; the cubic fit of the CIE 1964 x-bar (core::paper::cmf_fit); \
the exact degree-6 product of the two cubics against its reduction to a cubic (eq. 6). \
The paper's reflectance was a green shingle, which we do not have; the default is \
colorchecker#foliage."
)]
pub struct Table1Args {
    /// The reflectance (the paper used a green shingle, which we do not have).
    #[arg(default_value = "colorchecker#foliage", value_name = "SPECTRUM")]
    pub spectrum: String,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

/// Runs `specpoly table1`.
pub fn run(a: &Table1Args) -> Result<()> {
    let (name, rows) = compute(&a.spectrum)?;
    if a.json {
        return Ok(print_json(
            &serde_json::json!({ "spectrum": name, "rows": rows }),
        )?);
    }
    let mut o = String::new();
    let _ = writeln!(
        o,
        "Table 1 (Raso & Fournier 1991): errors of the paper's 2 cubic spans (split at 550 nm)"
    );
    let _ = writeln!(
            o,"error measure: mean squared error on a 10 nm grid in each span (reflectance: at its samples)");
    let _ = writeln!(
        o,
        "reflectance: ours {name}; paper: a green shingle (we do not have it)"
    );
    let _ = writeln!(
            o,"x: the CIE 1964 x-bar; reduced: cubic reduction (eq. 6) of the reflectance x x-bar product");
    let _ = writeln!(o);
    let _ = writeln!(
        o,
        "{:<12} {:>13} {:>13} {:>13} {:>13} {:>13} {:>13}",
        "span", "reflectance", "(paper)", "x", "(paper)", "reduced", "(paper)"
    );
    for (i, r) in rows.iter().enumerate() {
        let cells = r.cells().map(|v| format!("{v:>13.6e}"));
        let span = format!("{} {}-{}", ["one", "two"][i], r.span_nm[0], r.span_nm[1]);
        let _ = writeln!(o, "{span:<12} {}", cells.join(" "));
    }
    Ok(specpoly_formats::stdout::print(&o)?)
}
