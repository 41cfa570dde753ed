//! `specpoly plot`: the paper's Figures 4 and 5 for any spectra ([`specpoly_paper::figures`]): Figure 4
//! by default, Figure 5 with `--product`.
//!
//! The representation defaults to `paper` (2 cubic spans split at 550 nm), as in the figures.
//! Output: SVG or PNG by the file's extension (or `--format`), written atomically; `-o -`
//! writes the figure to stdout (SVG unless `--format png`).

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
    /// Output file: FILE.svg or FILE.png, or - for stdout.
    #[arg(short = 'o', long = "output", value_name = "FILE.svg|FILE.png|-")]
    pub output: PathBuf,
    /// The image format when the file name does not say (stdout: svg by default).
    #[arg(long, value_name = "svg|png")]
    pub format: Option<Format>,
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

/// `plot`'s image formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// Scalable vector graphics (text).
    Svg,
    /// PNG.
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
    let by_name = match ext.as_deref() {
        Some("svg") => Some(Format::Svg),
        Some("png") => Some(Format::Png),
        _ => None,
    };
    let to_stdout = a.output == std::path::Path::new("-");
    let format = match (a.format, by_name) {
        (Some(f), Some(n)) if f != n => {
            return Err(CliError::usage(format!(
                "{}: the name says {}, --format says {}",
                a.output.display(),
                ext.unwrap_or_default(),
                if f == Format::Svg { "svg" } else { "png" }
            )))
        }
        (Some(f), _) | (None, Some(f)) => f,
        (None, None) if to_stdout => Format::Svg,
        (None, None) => {
            return Err(CliError::usage(format!(
                "{}: the output must end in .svg or .png (or give --format)",
                a.output.display()
            )))
        }
    };
    if to_stdout {
        // before drawing, not after
        specpoly_formats::stdout::check_open()?;
    }
    let fig = figure(a)?;
    let bytes = match format {
        Format::Svg => fig.svg()?.into_bytes(),
        Format::Png => fig.png()?,
    };
    specpoly_formats::atomic::write(&a.output, &bytes)?;
    crate::cli::wrote::wrote(&a.output, "");
    Ok(())
}
