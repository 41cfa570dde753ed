//! `specpoly plot` (being written; the owner replaces this file).

use crate::error::{CliError, Result};

/// Arguments of `specpoly plot`.
#[derive(Debug, clap::Args)]
pub struct PlotArgs {}

/// Runs `specpoly plot`.
pub fn run(_: &PlotArgs) -> Result<()> {
    Err(CliError::usage("`plot` is not available in this build yet"))
}
