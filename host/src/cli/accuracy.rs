//! `specpoly accuracy` (being written; the owner replaces this file).

use crate::error::{CliError, Result};

/// Arguments of `specpoly accuracy`.
#[derive(Debug, clap::Args)]
pub struct AccuracyArgs {}

/// Runs `specpoly accuracy`.
pub fn run(_: &AccuracyArgs) -> Result<()> {
    Err(CliError::usage(
        "`accuracy` is not available in this build yet",
    ))
}
