//! `specpoly accuracy`: writes the accuracy report ([`specpoly_paper::accuracy::report`]) to
//! `docs/accuracy.md` (atomically).

use crate::error::{CliError, Result};
use std::path::PathBuf;

/// Arguments of `specpoly accuracy`.
#[derive(Debug, clap::Args)]
#[command(
    after_help = "CIEDE2000 of every representation (and of the paper's literal colour \
path) against the 1 nm f64 reference, over the 24 ColorChecker patches and all their chains of \
2 and 3, under D65, A, FL2, FL7, FL11 and D50, for the CIE 1964 and 1931 observers; with a \
tuning/validation split for the default preset. Takes a few seconds."
)]
pub struct AccuracyArgs {
    /// Where to write the Markdown report.
    #[arg(short = 'o', long = "output", default_value = "docs/accuracy.md")]
    pub output: PathBuf,
    /// Also print each representation's ΔE00 summary as JSON on stdout.
    #[arg(long)]
    pub json: bool,
}

/// Runs `specpoly accuracy`.
pub fn run(a: &AccuracyArgs) -> Result<()> {
    // Fail before the computation when the output's folder does not exist.
    if let Some(dir) = a.output.parent() {
        if !dir.as_os_str().is_empty() && !dir.is_dir() {
            return Err(CliError::io(
                &a.output,
                std::io::Error::new(std::io::ErrorKind::NotFound, "no such directory"),
            ));
        }
    }
    let (doc, summary) = specpoly_paper::accuracy::report_and_summary()?;
    specpoly_formats::atomic::write(&a.output, doc.as_bytes())?;
    crate::cli::wrote::wrote(&a.output, "");
    if a.json {
        return Ok(specpoly_formats::stdout::print_json(&summary)?);
    }
    Ok(())
}
