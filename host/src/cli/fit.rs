//! `specpoly fit` (being written; the owner replaces this file).

use crate::error::{CliError, Result};

/// Arguments of `specpoly fit`.
#[derive(Debug, clap::Args)]
pub struct FitArgs {}

/// Runs `specpoly fit`.
pub fn run(_: &FitArgs) -> Result<()> {
    Err(CliError::usage("`fit` is not available in this build yet"))
}
