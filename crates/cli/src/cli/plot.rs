//! `specpoly plot`: the paper's Figures 4 and 5 for any spectra ([`specpoly_paper::figures`]): Figure 4
//! by default, Figure 5 with `--product`.
//!
//! The representation defaults to `paper` (2 cubic spans split at 550 nm), as in the figures.
//! Output: SVG or PNG by the file's extension, written atomically.

use crate::error::{CliError, Result};
use specpoly_paper::figures;
use specpoly_plot::size::Size;
use specpoly_plot::Figure;
use specpoly_spectra::repr::Repr;
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
    pub repr: Repr,
    /// Image size in pixels, WIDTHxHEIGHT (200x150 to 8000x8000).
    #[arg(long, default_value = "900x560", value_name = "WxH")]
    pub size: Size,
    /// Multiply every spectrum by FACTOR first (0.01 for reflectances in percent).
    #[arg(long, default_value_t = 1.0, value_name = "FACTOR")]
    pub scale: f64,
}

enum Format {
    Svg,
    Png,
}

/// Builds the figure `plot` draws.
pub fn figure(a: &PlotArgs) -> Result<Figure> {
    let repr = a.repr.polynomial_for("plot")?;
    a.size.check(figures::MIN_SIZE, figures::MAX_SIZE)?;
    let named = specpoly_spectra::plausible::reflectances(&a.spectra, a.scale, false)?;
    Ok(figures::spectra(&named, repr, a.product, a.size)?)
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
        Format::Svg => fig.svg()?.into_bytes(),
        Format::Png => fig.png()?,
    };
    specpoly_formats::atomic::write(&a.output, &bytes)?;
    crate::cli::wrote::wrote(&a.output, "");
    Ok(())
}
